/*
 * celfw_frame.c - reassembly of whole frames from one byte sequence (see
 * celfw_frame.h).
 *
 * The header hunt follows the core decoder's rules (core/cs_stream.c), so a
 * stream framed here and then decoded gives the same reports as one decoded
 * straight: the last 16 bytes sit in a ring, a header is recognised where
 * the ring holds a known magic whose CRC matches, a length is trusted only
 * then, and a transaction or envelope header met inside a frame cuts that
 * frame short (a sender that restarted) instead of being eaten as its body.
 * The one exception is the inner transaction of an envelope, whose header
 * sits where the envelope says it does.
 */
#include "celfw_frame.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { F_HUNT, F_BODY, F_SKIP };

/* A buffer up to this size is kept between frames (patches); a larger one is freed. */
#define KEEP_BUFFER ((size_t)1 << 20)

static uint32_t rd_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

void celfw_framer_init(celfw_framer *f, const char *name)
{
    memset(f, 0, sizeof *f);
    snprintf(f->name, sizeof f->name, "%s", name);
}

void celfw_framer_free(celfw_framer *f)
{
    free(f->buf);
    f->buf = NULL;
    f->cap = f->len = 0;
}

/* Which frame the ring holds a header of (copied out in order), or NONE. */
static celfw_frame_kind ring_header(const celfw_framer *f, uint8_t *hdr)
{
    if (f->ring_count < CS_WIRE_HEADER_SIZE || f->ring[f->ring_pos] != 'C')
        return CELFW_FRAME_NONE;
    for (int i = 0; i < CS_WIRE_HEADER_SIZE; i++)
        hdr[i] = f->ring[(f->ring_pos + i) % CS_WIRE_HEADER_SIZE];
    celfw_frame_kind k = CELFW_FRAME_NONE;
    if (!memcmp(hdr, CS_WIRE_TXN_MAGIC, 4))
        k = CELFW_FRAME_TXN;
    else if (!memcmp(hdr, CS_WIRE_SIGNED_MAGIC, 4))
        k = CELFW_FRAME_SIGNED;
    else if (!memcmp(hdr, CS_WIRE_STREAM_MAGIC, 4))
        k = CELFW_FRAME_STREAM;
    if (k == CELFW_FRAME_NONE || cs_crc32(0, hdr, 12) != rd_u32(hdr + 12))
        return CELFW_FRAME_NONE;
    return k;
}

static void error(celfw_frame *fr, cs_status st, uint64_t offset, uint64_t at, const char *what)
{
    fr->kind = CELFW_FRAME_ERROR;
    fr->status = st;
    fr->offset = offset;
    fr->at = at;
    fr->what = what;
    fr->data = NULL;
    fr->len = 0;
}

/* Appends to the frame buffer, growing it as bytes come (never past `want`). */
static bool append(celfw_framer *f, const uint8_t *p, size_t n)
{
    if (f->len + n > f->cap) {
        size_t cap = f->cap ? f->cap : 4096;
        while (cap < f->len + n)
            cap *= 2;
        if (cap > f->want)
            cap = f->want;
        uint8_t *b = realloc(f->buf, cap);
        if (!b)
            return false;
        f->buf = b;
        f->cap = cap;
    }
    memcpy(f->buf + f->len, p, n);
    f->len += n;
    return true;
}

/* A header is in the ring at hdr_at: start its frame. Returns true if *fr is an event. */
static bool start(celfw_framer *f, celfw_frame_kind k, const uint8_t *hdr, uint64_t hdr_at, celfw_frame *fr)
{
    f->ring_count = 0;
    f->in_garbage = false;
    f->len = 0;
    f->frame_offset = hdr_at;
    f->kind = (uint8_t)k;
    if (k == CELFW_FRAME_STREAM) {
        f->want = CS_WIRE_HEADER_SIZE;
        if (!append(f, hdr, CS_WIRE_HEADER_SIZE)) {
            error(fr, CS_ERR_STREAM_TOO_BIG, hdr_at, hdr_at, "out of memory for a stream header");
            return true;
        }
        f->state = F_HUNT;
        fr->kind = k;
        fr->data = f->buf;
        fr->len = f->len;
        fr->offset = hdr_at;
        fr->at = 0;
        return true;
    }
    uint64_t body = rd_u32(hdr + 8);
    uint64_t total = CS_WIRE_HEADER_SIZE + body + CS_WIRE_TRAILER_SIZE;
    if (total > CELFW_FRAME_MAX) {
        /* its CRC matched, so its length can be skipped; a header met on the way starts anew */
        f->state = F_SKIP;
        f->skip_left = body + CS_WIRE_TRAILER_SIZE;
        error(fr, CS_ERR_STREAM_TOO_BIG, hdr_at, hdr_at + 8,
              "transaction longer than this board accepts: skipped");
        return true;
    }
    f->want = (size_t)total;
    if (!append(f, hdr, CS_WIRE_HEADER_SIZE)) {
        f->state = F_SKIP;
        f->skip_left = body + CS_WIRE_TRAILER_SIZE;
        error(fr, CS_ERR_STREAM_TOO_BIG, hdr_at, hdr_at, "out of memory for the transaction: skipped");
        return true;
    }
    f->state = F_BODY;
    return false;
}

/* Steps one byte; true if *fr now holds an event. */
static bool step(celfw_framer *f, uint8_t b, celfw_frame *fr)
{
    uint64_t at = f->offset++;
    f->ring[f->ring_pos] = b;
    f->ring_pos = (uint8_t)((f->ring_pos + 1) % CS_WIRE_HEADER_SIZE);
    if (f->ring_count < CS_WIRE_HEADER_SIZE)
        f->ring_count++;
    uint8_t hdr[CS_WIRE_HEADER_SIZE];
    celfw_frame_kind k = ring_header(f, hdr);
    uint64_t hdr_at = at + 1 - CS_WIRE_HEADER_SIZE;
    bool inner = f->state == F_BODY && f->kind == CELFW_FRAME_SIGNED &&
                 hdr_at == f->frame_offset + CS_WIRE_HEADER_SIZE + CS_WIRE_SIG_BLOCK_SIZE;
    if ((k == CELFW_FRAME_TXN || k == CELFW_FRAME_SIGNED) && !inner) {
        uint64_t cut = f->frame_offset;
        bool was_body = f->state == F_BODY;
        bool ev = start(f, k, hdr, hdr_at, fr);
        if (was_body && !ev) {
            error(fr, CS_ERR_STREAM_TRUNCATED, cut, hdr_at,
                  "transaction cut short by the next transaction header");
            return true;
        }
        return ev;
    }
    if (k == CELFW_FRAME_STREAM && f->state == F_HUNT)
        return start(f, k, hdr, hdr_at, fr);
    switch (f->state) {
    case F_HUNT:
        /* the oldest byte of a full ring can no longer start a header */
        if (f->ring_count == CS_WIRE_HEADER_SIZE && !f->in_garbage) {
            f->in_garbage = true;
            error(fr, CS_ERR_STREAM_SYNC, hdr_at, hdr_at,
                  "bytes outside any transaction: skipping to the next header");
            return true;
        }
        return false;
    case F_BODY:
        if (!append(f, &b, 1)) {
            f->state = F_SKIP;
            f->skip_left = f->want - f->len - 1;
            error(fr, CS_ERR_STREAM_TOO_BIG, f->frame_offset, at, "out of memory for the transaction: skipped");
            return true;
        }
        if (f->len < f->want)
            return false;
        f->state = F_HUNT;
        f->ring_count = 0;
        fr->kind = (celfw_frame_kind)f->kind;
        fr->data = f->buf;
        fr->len = f->len;
        fr->offset = f->frame_offset;
        fr->at = 0;
        return true;
    default: /* F_SKIP */
        if (--f->skip_left == 0) {
            f->state = F_HUNT;
            f->ring_count = 0;
        }
        return false;
    }
}

size_t celfw_framer_push(celfw_framer *f, const uint8_t *p, size_t n, celfw_frame *fr)
{
    fr->kind = CELFW_FRAME_NONE;
    if (f->state != F_BODY) {
        f->len = 0; /* the frame handed out last is no longer needed */
        if (f->cap > KEEP_BUFFER)
            celfw_framer_free(f); /* a big scene went through: give its memory back */
    }
    for (size_t i = 0; i < n; i++)
        if (step(f, p[i], fr))
            return i + 1;
    return n;
}

bool celfw_framer_end(celfw_framer *f, celfw_frame *fr)
{
    bool ev = false;
    if (f->state == F_BODY) {
        error(fr, CS_ERR_STREAM_TRUNCATED, f->frame_offset, f->offset, "input ended inside a transaction");
        ev = true;
    } else if (f->state == F_HUNT && f->ring_count > 0 && !f->in_garbage) {
        uint64_t from = f->offset - f->ring_count;
        error(fr, CS_ERR_STREAM_SYNC, from, from, "input ended with bytes that are no transaction");
        ev = true;
    }
    char name[sizeof f->name];
    memcpy(name, f->name, sizeof name);
    celfw_framer_free(f);
    celfw_framer_init(f, name);
    return ev;
}
