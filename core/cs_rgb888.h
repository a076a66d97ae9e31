/*
 * cs_rgb888.h - writing runs of 8-bit sRGB pixels, for the two places that
 * do it: the run conversion of a finished line (cs_pixfmt.c) and the pass
 * that finishes a line and converts it at once (cs_line.c, the display
 * path of the x86-64-v3 build). Inline, because both call these once per
 * run of a line, ~91 k times a Many-blobs frame, where a call and its
 * argument shuffling cost as much as a short run's stores.
 *
 * With AVX2 (CS__RGB888_VEC) a run's three channel codes also come from
 * one pass of vector instructions (cs__srgb8_lanes): the cells of the
 * three floats by their bits, the two tables read by gathers, one compare. It
 * computes cs__srgb8 of each lane, for values in [0, 1], which is what a
 * finished pixel is.
 */
#ifndef CS_RGB888_H
#define CS_RGB888_H

#include "cs_internal.h"

/* Four bytes at p, least significant first: byte stores the compiler may
 * merge into one word store where the target allows unaligned words. */
static inline void cs__put32(uint8_t *p, uint32_t w)
{
    p[0] = (uint8_t)w;
    p[1] = (uint8_t)(w >> 8);
    p[2] = (uint8_t)(w >> 16);
    p[3] = (uint8_t)(w >> 24);
}

#if defined(__SSE2__)
/*
 * Sixteen pixels of 8-bit codes are 48 bytes, three 16-byte stores of the
 * three phases of the 12-byte pattern w0 w1 w2 (x86 is little-endian, and
 * SSE2 stores need no alignment). A run of n >= 16 pixels is such blocks
 * from its start, and a last block that ends at its end: it overlaps the
 * one before by a whole number of pixels, so it writes the same bytes
 * there, and no tail loop is needed. Written out because GCC, left to
 * vectorise the word loop below, built the pattern byte by byte (~100
 * instructions a run, more than the stores of a 100-pixel run).
 */
typedef uint32_t px16_rgb888 __attribute__((vector_size(16), aligned(1), may_alias));

static inline void cs__rgb888_wide(uint8_t *p, uint32_t n, uint32_t w0, uint32_t w1, uint32_t w2)
{
    px16_rgb888 a = {w0, w1, w2, w0}, b = {w1, w2, w0, w1}, c = {w2, w0, w1, w2};
    uint8_t *last = p + 3u * (n - 16u);
    for (; p < last; p += 48) {
        *(px16_rgb888 *)p = a;
        *(px16_rgb888 *)(p + 16) = b;
        *(px16_rgb888 *)(p + 32) = c;
    }
    *(px16_rgb888 *)last = a;
    *(px16_rgb888 *)(last + 16) = b;
    *(px16_rgb888 *)(last + 32) = c;
}
#endif

#if defined(__SSSE3__)
/*
 * With SSSE3 (the x86-64-v3 build) a run's pixel, c0 | c1 << 8 | c2 << 16,
 * becomes the three 16-byte phases by one byte shuffle each, and a line's
 * runs, converted left to right, are written 16 pixels a step from each
 * run's start while the run lasts, past its end by up to 15 pixels, which
 * the runs after it then overwrite. Every run, a 1-pixel edge or a
 * 300-pixel interior, takes one loop with no test of its length: the
 * length tests of cs__rgb888_fill were mispredicted ~60 k times a Many-blobs
 * exact frame (cachegrind --branch-sim), where edge pixels and interiors
 * alternate. The caller leaves it the runs within 15 pixels of the line's
 * end, where there is no room to write ahead.
 */
typedef uint8_t px16_u8 __attribute__((vector_size(16)));

/* n >= 0 pixels at p, 16 a step from p while the run lasts (at least one
 * step), as the three phases a b c of the 12-byte pattern. */
static inline void cs__rgb888_steps(uint8_t *p, uint32_t n, px16_u8 a, px16_u8 b, px16_u8 c)
{
    const uint8_t *end = p + 3u * n;
    do {
        *(px16_rgb888 *)p = (px16_rgb888)a;
        *(px16_rgb888 *)(p + 16) = (px16_rgb888)b;
        *(px16_rgb888 *)(p + 32) = (px16_rgb888)c;
        p += 48;
    } while (p < end);
}

static inline void cs__rgb888_ahead(uint8_t *p, uint32_t n, uint32_t px)
{
    px16_u8 v = (px16_u8)(px16_rgb888){px, 0u, 0u, 0u};
    cs__rgb888_steps(
        p, n, __builtin_shufflevector(v, v, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0),
        __builtin_shufflevector(v, v, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1),
        __builtin_shufflevector(v, v, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2));
}
#endif

/* n pixels of the 8-bit codes c0 c1 c2 at p: most runs are a pixel or two
 * of an edge, written byte by byte; long ones four pixels (three words) a
 * step, or on x86 sixteen (cs__rgb888_wide). */
static inline void cs__rgb888_fill(uint8_t *p, uint32_t n, uint32_t c0, uint32_t c1, uint32_t c2)
{
    if (n >= 8u) {
        uint32_t w0 = c0 | c1 << 8 | c2 << 16 | c0 << 24;
        uint32_t w1 = c1 | c2 << 8 | c0 << 16 | c1 << 24;
        uint32_t w2 = c2 | c0 << 8 | c1 << 16 | c2 << 24;
#if defined(__SSE2__)
        if (n >= 16u) {
            cs__rgb888_wide(p, n, w0, w1, w2);
            return;
        }
#endif
        for (; n >= 4u; n -= 4u, p += 12) {
            cs__put32(p, w0);
            cs__put32(p + 4, w1);
            cs__put32(p + 8, w2);
        }
    }
    for (; n > 0u; n--, p += 3) {
        p[0] = (uint8_t)c0;
        p[1] = (uint8_t)c1;
        p[2] = (uint8_t)c2;
    }
}

/* The run [s, e) of a line `width` pixels wide in the 8-bit codes c0 c1
 * c2, where the line's runs are written left to right: ahead of the run
 * where the line leaves room (with SSSE3), else exactly. */
static inline void cs__rgb888_run(uint8_t *out, uint32_t s, uint32_t e, uint32_t width,
                                  uint32_t c0, uint32_t c1, uint32_t c2)
{
#if defined(__SSSE3__)
    if (e + 15u <= width) {
        cs__rgb888_ahead(out + 3u * s, e - s, c0 | c1 << 8 | c2 << 16);
        return;
    }
#else
    (void)width;
#endif
    cs__rgb888_fill(out + 3u * s, e - s, c0, c1, c2);
}

#if defined(__AVX2__) && defined(__GNUC__) && CS_CFG_SRGB8_BITS && defined(__x86_64__)
#define CS__RGB888_VEC 1

typedef float cs__v4f __attribute__((vector_size(16)));
typedef int32_t cs__v4i __attribute__((vector_size(16)));
typedef uint32_t cs__v4u __attribute__((vector_size(16)));
/* Four floats at any float's address, in memory of any type. */
typedef float cs__v4f_u __attribute__((vector_size(16), aligned(4), may_alias));

/* Four dwords from base + scale * idx, by one gather. Inline asm because
 * GCC and clang name the builtin differently and <immintrin.h> brings
 * <stdlib.h> into the freestanding core. The tables are const, so the asm
 * needs no memory operand beyond its address. */
#define CS__GATHER4(r, base, idx, scale)                                              \
    do {                                                                              \
        cs__v4i m_;                                                                   \
        __asm__("vpcmpeqd %1, %1, %1\n\tvpgatherdd %1, (%2, %3, " #scale "), %0"      \
                : "=&x"(r), "=&x"(m_)                                                 \
                : "r"(base), "x"(idx));                                               \
    } while (0)

/* The 8-bit codes of lanes 0..2 of v, each in [0, 1] (not NaN), in byte 0
 * of lanes 0..2 (the bytes above are the table's next cells): cs__srgb8 of
 * each. A value below the first cell is taken to its start, where it lies
 * below the cell's step (so code 0); 1.0 has a cell of its own, past the
 * others. The cell's offset goes into the tables' addresses, and the base
 * table is padded, so a dword gather at the last cells stays within it. */
static inline px16_u8 cs__srgb8_lanes(cs__v4f v)
{
    const cs__v4f lo = (cs__v4f)(cs__v4i){CS__SRGB8_BITS_FIRST << 16, CS__SRGB8_BITS_FIRST << 16,
                                          CS__SRGB8_BITS_FIRST << 16, CS__SRGB8_BITS_FIRST << 16};
    cs__v4i i = (cs__v4i)((cs__v4u)__builtin_ia32_maxps(v, lo) >> 16);
    cs__v4i base, step;
    CS__GATHER4(base, (uintptr_t)cs__srgb8_bits_base - CS__SRGB8_BITS_FIRST, i, 1);
    CS__GATHER4(step, (uintptr_t)cs__srgb8_bits_step - 4u * CS__SRGB8_BITS_FIRST, i, 4);
    /* base + 1 where v >= step (a code is at most 255: no carry) */
    return (px16_u8)(base - (v >= (cs__v4f)step));
}

/* Thirty-two pixels of 8-bit codes are 96 bytes, three 32-byte stores of
 * the phases (0 1), (2 0) and (1 2) of the 12-byte pattern. */
typedef uint32_t px32_rgb888 __attribute__((vector_size(32), aligned(1), may_alias));
typedef uint8_t px32_u8 __attribute__((vector_size(32)));

/* The first 32 pixels of a run at p, from codes in bytes 0, 4 and 8
 * (cs__srgb8_lanes), whatever the run's length: the fused pass writes the
 * rest of the runs longer than 32 pixels apart (cs__rgb888_rest). */
static inline void cs__rgb888_first_lanes(uint8_t *p, px16_u8 c)
{
    /* c in both halves (the byte shuffles work half by half). By asm: GCC
     * builds it from a shufflevector by clearing the upper half of c's
     * register first, then vpermq, one instruction more a run. */
    px32_u8 w;
    __asm__("vinserti128 $1, %x1, %t1, %0" : "=x"(w) : "x"(c));
    *(px32_rgb888 *)p = (px32_rgb888)__builtin_shufflevector(
        w, w, 0, 4, 8, 0, 4, 8, 0, 4, 8, 0, 4, 8, 0, 4, 8, 0, 20, 24, 16, 20, 24, 16, 20, 24, 16,
        20, 24, 16, 20, 24, 16, 20);
    *(px32_rgb888 *)(p + 32) = (px32_rgb888)__builtin_shufflevector(
        w, w, 8, 0, 4, 8, 0, 4, 8, 0, 4, 8, 0, 4, 8, 0, 4, 8, 16, 20, 24, 16, 20, 24, 16, 20, 24,
        16, 20, 24, 16, 20, 24, 16);
    *(px32_rgb888 *)(p + 64) = (px32_rgb888)__builtin_shufflevector(
        w, w, 4, 8, 0, 4, 8, 0, 4, 8, 0, 4, 8, 0, 4, 8, 0, 4, 24, 16, 20, 24, 16, 20, 24, 16, 20,
        24, 16, 20, 24, 16, 20, 24);
}

/* Pixels 32..n-1 (n > 32) of a run at p whose first 32 are written, as
 * they are: 64 a step, in two blocks of 32 each placed at the block's
 * position or, past the run, at its last 32 pixels (a block within the run
 * at a whole pixel writes the bytes that are there), then the last 32. A
 * step whatever the length covers runs of up to 128 pixels, 14.8 k of the
 * 18.7 k runs longer than 32 of a Many-blobs exact frame, so the loop's
 * exit is mostly not taken: a loop of one 16-pixel block a step was
 * mispredicted about once a run (callgrind --branch-sim), the runs'
 * lengths varying from 17 pixels to hundreds. */
static inline void cs__rgb888_rest(uint8_t *p, uint32_t n)
{
    px32_rgb888 a = *(const px32_rgb888 *)p, b = *(const px32_rgb888 *)(p + 32),
                c = *(const px32_rgb888 *)(p + 64);
    uint8_t *last = p + 3u * (n - 32u);
    uint8_t *q = p + 96;
    do {
        for (uint32_t k = 0; k < 2u; k++, q += 96) {
            uint8_t *d = q < last ? q : last;
            *(px32_rgb888 *)d = a;
            *(px32_rgb888 *)(d + 32) = b;
            *(px32_rgb888 *)(d + 64) = c;
        }
    } while (q < last);
    *(px32_rgb888 *)last = a;
    *(px32_rgb888 *)(last + 32) = b;
    *(px32_rgb888 *)(last + 64) = c;
}

/* A uint16_t that may lie in memory of another type (a float array that
 * is free between lines). */
typedef uint16_t cs__u16_alias __attribute__((may_alias));
#else
#define CS__RGB888_VEC 0
#endif

#endif /* CS_RGB888_H */
