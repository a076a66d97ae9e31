/*
 * cs_stream_internal.h - what the stream decoder's two files share: its
 * states, the little-endian readers of the wire, and the table of record
 * types (cs_stream_apply.c) by whose rows the decoder (cs_stream.c) reads
 * each record and hands it, once its fields are all in, to the function
 * that applies it to the back store.
 */
#ifndef CS_STREAM_INTERNAL_H
#define CS_STREAM_INTERNAL_H

#include "cs_internal.h"
#include "cs_wire.h"

enum { ST_HUNT, ST_BODY, ST_TRAILER, ST_SKIP };
enum { P_HDR, P_FIXED, P_FLOATS, P_SKIP, P_DEAD };
enum { M_NONE, M_FULL, M_PATCH };
enum { H_NONE, H_STREAM, H_TXN, H_SIGNED };

static inline uint32_t cs__rd_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static inline float cs__rd_f32(const uint8_t *p)
{
    union {
        uint32_t u;
        float f;
    } v;
    v.u = cs__rd_u32(p);
    return v.f;
}

static inline float cs__word_f32(uint32_t w)
{
    union {
        uint32_t u;
        float f;
    } v;
    v.u = w;
    return v.f;
}

/* n floats from p into out (cs_stream_apply.c). */
void cs__rd_f32s(const uint8_t *p, float *out, int n);

/* What follows a record's fixed part, and how the decoder reads it
 * (cs_stream.c: begin_floats, put_word). */
enum {
    L_FIXED,      /* nothing: the fixed part is the whole record */
    L_FLAGS_AT0,  /* nothing; the fixed part's word 0 is cel flags (CEL) */
    L_FLAGS_AT4,  /* nothing; its word 1 is cel flags (CEL_LIGHTS) */
    L_POINTS_NEW, /* x y w per point [, intervals], into the store's free end (CONTOUR) */
    L_POINTS_AT,  /* the same, in place over the contour's points (CONTOUR_POINTS) */
    L_KEYS,       /* time, value * width per key; each key added when complete (TRACK) */
    L_STOPS,      /* offset, value[3] per stop, into the function's slot (REGION_FUNC) */
    L_TOKENS      /* an i32 per CSG token, kept in buf after the length (REGION_CSG) */
};

/* A record type the decoder knows: one row of cs__rec_kinds. */
typedef struct cs__rec_kind {
    uint16_t type;  /* CS_REC_* */
    uint8_t fixed;  /* bytes of its fixed part */
    uint8_t layout; /* L_*: what follows the fixed part */
    /* Applies the record (its fixed part in s->buf; its points, keys or
     * function already read into the back store at s->base) to the back
     * store; returns the scene call's status, with where it was found in
     * *where. NULL: nothing is left to apply. */
    cs_status (*apply)(cs_stream *s, cs_error *where);
} cs__rec_kind;

extern const cs__rec_kind cs__rec_kinds[];

/* The row of `type` in cs__rec_kinds, or -1 for a type this version skips. */
int cs__rec_kind_find(uint32_t type);

#endif /* CS_STREAM_INTERNAL_H */
