/*
 * cels_write.h - writing cel streams on the host (docs/STREAM.md).
 *
 * Two levels. cels_write_scene / cels_encode_scene turn a whole scene store
 * (with its tracks) into a stream: what `celc compile` writes after the JSON
 * loader has built the scene, so a .cels file decodes to the very store the
 * JSON gave. Below that, a growable byte buffer with record and transaction
 * framing (lengths and CRCs filled in at the end) lets tools and tests write
 * patches, or deliberately odd streams, record by record.
 *
 * Host code: it allocates with malloc and writes with stdio. Not in the core.
 */
#ifndef CELS_WRITE_H
#define CELS_WRITE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "celscan.h"
#include "cs_wire.h"

typedef struct cels_buf {
    uint8_t *data;
    size_t len, cap;
    bool oom;          /* an allocation failed: the content is incomplete */
    size_t txn_start;  /* offset of the open transaction's header */
    size_t rec_start;  /* offset of the open record's header */
} cels_buf;

void cels_buf_init(cels_buf *b);
void cels_buf_free(cels_buf *b);

void cels_put_bytes(cels_buf *b, const void *p, size_t n);
void cels_put_u8(cels_buf *b, uint8_t v);
void cels_put_u16(cels_buf *b, uint16_t v);
void cels_put_u32(cels_buf *b, uint32_t v);
void cels_put_f32(cels_buf *b, float v);
void cels_put_f32s(cels_buf *b, const float *v, size_t n);

/* The 16-byte stream header (magic, version, CRC). */
void cels_stream_header(cels_buf *b);
/* Opens a transaction; cels_txn_end fills in its length, header CRC and trailer CRC. */
void cels_txn_begin(cels_buf *b);
void cels_txn_end(cels_buf *b);
/* Opens a signed envelope (tools/cels_sign.h fills it); closed by cels_txn_end too. */
void cels_envelope_begin(cels_buf *b);
/* Opens a record of `type`; cels_rec_end fills in its payload length. */
void cels_rec_begin(cels_buf *b, uint16_t type);
void cels_rec_end(cels_buf *b);
/* An empty COMMIT record. */
void cels_rec_commit(cels_buf *b);

/*
 * Appends one transaction that defines `scene` whole: SCENE, LIGHTS,
 * BACKGROUND, then each cel with its regions (each with its paint
 * functions and CSG program) and contours (each with its CSG operand), then its tracks
 * in the order their keys were added, then COMMIT. Returns 0, or -1 if the
 * buffer ran out of memory.
 */
int cels_encode_scene(cels_buf *b, const cs_scene *scene);

/* Writes the stream header and the scene's transaction to `out`; 0 or -1. */
int cels_write_scene(const cs_scene *scene, FILE *out);

#endif /* CELS_WRITE_H */
