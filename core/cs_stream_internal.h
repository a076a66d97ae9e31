/*
 * cs_stream_internal.h - what the stream decoder's two files share: its
 * states, the little-endian readers of the wire, and cs__stream_apply, by
 * which the decoder (cs_stream.c) hands a record whose fields are all in
 * to the code that applies it to the back store (cs_stream_apply.c).
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

/* Applies the record in s->buf (type s->rec_type; its points, keys or
 * function already read into the back store at s->base) to the back store.
 * Returns the scene call's status, with where it was found in *where. */
cs_status cs__stream_apply(cs_stream *s, cs_error *where);

#endif /* CS_STREAM_INTERNAL_H */
