/*
 * celfw_frame.h - whole frames out of one input's bytes: the reassembly in
 * front of celfw's trust check and decoder.
 *
 * Every frame of the cel stream starts with the same 16-byte header (magic,
 * version, flags, length, header CRC; docs/STREAM.md), so the framing is
 * generic: a stream header (CELS) is 16 bytes, a transaction (CSTX) and a
 * signed envelope (CSSG) are 16 + L + 4. A framer collects the frames of one
 * byte sequence (a TCP connection, a file, stdin, a tty, one fleet message)
 * and hands each out only when it is whole. So several TCP clients can send
 * at once without mixing bytes into one transaction, a signature can be
 * checked before the decoder sees a byte of what it covers, and a sender
 * that stops half-way holds nothing but its own buffer.
 *
 * Bytes outside frames, frames cut by the next header or by the end of the
 * sequence, and frames longer than a board accepts are reported with the
 * byte offsets the decoder would give (they count from the start of the
 * sequence), and the framer resynchronises on the next header, as the core
 * decoder does. Memory: the frame being collected, grown as its bytes come,
 * at most CELFW_FRAME_MAX bytes, and given back after a frame of more than
 * a megabyte.
 */
#ifndef CELFW_FRAME_H
#define CELFW_FRAME_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "celscan.h"
#include "cs_wire.h"

/* The largest frame: an envelope around the largest transaction the decoder accepts. */
#define CELFW_FRAME_MAX                                                                            \
    ((size_t)CS_WIRE_HEADER_SIZE + CS_WIRE_SIGNED_MIN_BODY + CS_CFG_STREAM_MAX_TXN + CS_WIRE_TRAILER_SIZE)

typedef enum celfw_frame_kind {
    CELFW_FRAME_NONE = 0, /* every byte given was used; nothing to hand out */
    CELFW_FRAME_STREAM,   /* a stream header */
    CELFW_FRAME_TXN,      /* a transaction, header to trailer (its CRC not yet checked) */
    CELFW_FRAME_SIGNED,   /* a signed envelope, header to trailer */
    CELFW_FRAME_ERROR     /* bytes dropped: status, what, offsets */
} celfw_frame_kind;

typedef struct celfw_frame {
    celfw_frame_kind kind;
    const uint8_t *data; /* the whole frame; valid until the framer is used again */
    size_t len;
    uint64_t offset;     /* of the frame's first byte (errors: of the dropped bytes) */
    uint64_t at;         /* errors: where the fault was found */
    cs_status status;    /* errors: CS_ERR_STREAM_SYNC, _TRUNCATED or _TOO_BIG */
    const char *what;    /* errors: what happened */
} celfw_frame;

typedef struct celfw_framer {
    char name[96];       /* the source, for log lines: "tcp client 127.0.0.1:5000" */
    uint64_t offset;     /* bytes of this sequence so far */
    uint64_t applied;    /* transactions of this sequence that committed: counted by
                            the sink, watched by the input as the sender's progress */
    uint64_t frame_offset, skip_left;
    uint8_t *buf;
    size_t len, cap, want;
    uint8_t ring[CS_WIRE_HEADER_SIZE];
    uint8_t ring_pos, ring_count;
    uint8_t state, kind;
    bool in_garbage;
} celfw_framer;

void celfw_framer_init(celfw_framer *f, const char *name);
/* Frees the frame buffer; the framer may be initialised again. */
void celfw_framer_free(celfw_framer *f);
/*
 * Consumes bytes until a frame or an error is ready in *fr (or the bytes run
 * out: CELFW_FRAME_NONE). Returns how many were consumed; call again with
 * the rest, even if that is nothing, until it gives CELFW_FRAME_NONE.
 */
size_t celfw_framer_push(celfw_framer *f, const uint8_t *p, size_t n, celfw_frame *fr);
/*
 * The sequence ended: reports a frame cut short or trailing bytes in *fr
 * (true), else returns false; either way the framer starts afresh at offset 0.
 */
bool celfw_framer_end(celfw_framer *f, celfw_frame *fr);

#endif /* CELFW_FRAME_H */
