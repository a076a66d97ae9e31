/*
 * cs_runs.h - a line as runs of pixels that share one state.
 *
 * The stack of a line (its emitted light E and transmittance T per
 * channel) and the cel being folded into it (claimed coverage `used`, the
 * cel's summed E and 1 - T) are piecewise constant along x: they change
 * only where some region has an edge. So the line is kept as runs of
 * pixels [s, run_end[s]) that share all of these values, stored once, at
 * the run's first pixel s, in the workspace's per-pixel arrays (entries at
 * other pixels are stale and never read). The cel's E and 1 - T of a run
 * mean something only where its claimed coverage `used` is not 0: a cel
 * starts every run at zero by setting `used` alone (with CS_CFG_CEL_LIST,
 * the runs where it is not 0 are listed in ws->cel_runs, in no particular
 * order, for the cel's compositing). A bit per pixel in run_starts
 * marks the starts, so the run holding any x is found by a backward bit
 * scan, and a run is split in O(1) by copying its values to the new start.
 *
 * Work is then per run, not per pixel: a region's coverage is folded into
 * the runs it meets, a cel composites run by run, and the finished line is
 * converted to pixels once per run. Runs are whole pixels, so there are at
 * most `width` of them and the memory stays O(width). The arithmetic on
 * each run is the per-pixel arithmetic of the pixels it stands for, in the
 * same order, so the result is the same bits as computing every pixel.
 *
 * A frame whose every paint transmits grey (cs_renderer.grey: T the same
 * on every channel, as for any white or grey medium) keeps T and the cel's
 * A in channel 0 alone: the same products on one number instead of three
 * equal ones, so the same bits, with a third of the transmittance work.
 * The functions here take `grey` as an argument, a constant wherever they
 * are inlined into one of the two specialised copies of the line code.
 *
 * A run whose stack transmits nothing (T = 0 on every channel) is opaque:
 * nothing behind it can show, so later cels skip it and it is never split
 * again. With the early-out off (cs_render_opts.no_early_out) nothing is
 * treated as opaque, which changes no bit, only the work (in exact mode, a
 * last bit at most: see hide() in cs_exact.c).
 */
#ifndef CS_RUNS_H
#define CS_RUNS_H

#include "cs_internal.h"

/* Highest set bit of v != 0, by de Bruijn multiplication: an integer table
 * lookup that needs no compiler builtin (on RV32 without Zbb a builtin
 * would call into libgcc, which the freestanding core may not). x86-64
 * has the instruction in every build (bsr, or lzcnt in x86-64-v3), so the
 * host takes the builtin: ~1 M fewer instructions in a Many-blobs frame. */
static inline uint32_t cs__high_bit(uint32_t v)
{
#if defined(__GNUC__) && defined(__x86_64__)
    return 31u - (uint32_t)__builtin_clz(v);
#else
    static const uint8_t table[32] = {0,  9,  1,  10, 13, 21, 2,  29, 11, 14, 16,
                                      18, 22, 25, 3,  30, 8,  12, 20, 28, 15, 17,
                                      24, 7,  19, 27, 23, 6,  26, 5,  4,  31};
    v |= v >> 1;
    v |= v >> 2;
    v |= v >> 4;
    v |= v >> 8;
    v |= v >> 16;
    return table[(v * 0x07C4ACDDu) >> 27];
#endif
}

/* Lowest set bit of v != 0 (the builtin as for cs__high_bit). */
static inline uint32_t cs__low_bit(uint32_t v)
{
#if defined(__GNUC__) && defined(__x86_64__)
    return (uint32_t)__builtin_ctz(v);
#else
    static const uint8_t table[32] = {0,  1,  28, 2,  29, 14, 24, 3,  30, 22, 20,
                                      15, 25, 17, 4,  8,  31, 27, 13, 23, 21, 19,
                                      16, 7,  26, 12, 18, 6,  11, 5,  10, 9};
    return table[((v & (0u - v)) * 0x077CB531u) >> 27];
#endif
}

#if defined(__GNUC__) && defined(__x86_64__)
/* Two words of a bitmap read as one (x86-64 loads it unaligned). */
typedef uint64_t cs__bits64 __attribute__((may_alias, aligned(4)));
#define CS__BITS64 1
#else
#define CS__BITS64 0
#endif

/* The start of the run holding pixel x. Pixel 0 always starts a run. The
 * scan back goes over long runs (a blob's interior, the clear line), ~8
 * words a call on Many-blobs: x86-64 reads two words a step. */
static inline uint32_t cs__run_start(const cs_workspace *ws, uint32_t x)
{
    uint32_t w = x >> 5;
    uint32_t bits = ws->run_starts[w] & (0xFFFFFFFFu >> (31u - (x & 31u)));
#if CS__BITS64
    while (bits == 0u && w >= 2u) {
        w -= 2u;
        uint64_t b = *(const cs__bits64 *)&ws->run_starts[w];
        if (b != 0u)
            return (w << 5) + 63u - (uint32_t)__builtin_clzll(b);
    }
#endif
    while (bits == 0u)
        bits = ws->run_starts[--w];
    return (w << 5) + cs__high_bit(bits);
}

/* Copies a map (E, T), T channel 0 alone if grey, written out: a loop here
 * is left rolled by the compiler, and a split is on every edge pixel. */
static CS__SPECIALISE void cs__copy_map(float *dE, float *dT, const float *sE, const float *sT,
                                        bool grey)
{
    float e0 = sE[0], e1 = sE[1], e2 = sE[2], t0 = sT[0];
    dE[0] = e0;
    dE[1] = e1;
    dE[2] = e2;
    dT[0] = t0;
    if (!grey) {
        float t1 = sT[1], t2 = sT[2];
        dT[1] = t1;
        dT[2] = t2;
    }
}

/* The stack's T of the run at s on all three channels: a grey frame keeps
 * it in channel 0 alone (the others are stale). */
static CS__SPECIALISE void cs__run_T(const cs_workspace *ws, bool grey, uint32_t s, float T[3])
{
    const float *st = &ws->stack_T[3 * s];
    T[0] = st[0];
    T[1] = grey ? st[0] : st[1];
    T[2] = grey ? st[0] : st[2];
}

/* Splits the run starting at s at pixel x (s < x < run_end[s]). In a grey
 * frame only channel 0 of T and of the cel's A is kept (cs_renderer.grey).
 * `bare`: the cel has reached no run of the line (used is 0 on all, as
 * while a cel's only region on the line folds straight into the stack),
 * so the new run's `used` is 0 without a read and a test. */
static CS__SPECIALISE void cs__run_split_as(cs_workspace *ws, bool grey, bool bare, uint32_t s,
                                            uint32_t x)
{
    ws->run_end[x] = ws->run_end[s];
    ws->run_end[s] = (uint16_t)x;
    ws->run_starts[x >> 5] |= 1u << (x & 31u);
    cs__copy_map(&ws->stack_E[3 * x], &ws->stack_T[3 * x], &ws->stack_E[3 * s],
                 &ws->stack_T[3 * s], grey);
    if (bare) {
        ws->used[x] = 0.0f;
        return;
    }
    float used = ws->used[s];
    ws->used[x] = used;
    if (used != 0.0f) { /* a run the cel has not reached holds no cel values */
        cs__copy_map(&ws->cel_E[3 * x], &ws->cel_A[3 * x], &ws->cel_E[3 * s], &ws->cel_A[3 * s],
                     grey);
#if CS_CFG_CEL_LIST
        ws->cel_runs[ws->cel_run_count++] = (uint16_t)x;
#endif
    }
}

/* Whether the stack of the run at s is opaque (and the early-out is on):
 * its bit in opaque_bits, which cs__run_join sets for the whole run when
 * T reaches 0 on every channel (an opaque run is never split again), and
 * only with the early-out on (r->record), so the bit alone tells: the
 * test of r->record per visited run was ~0.4 M instructions of a
 * Many-blobs exact frame. */
static inline bool cs__run_opaque(const cs_renderer *r, uint32_t s)
{
    return ((r->ws->opaque_bits[s >> 5] >> (s & 31u)) & 1u) != 0u;
}

/* The same at a run start s. On x86-64 from the run's `used`: cs__run_join
 * sets it to CS__USED_OPAQUE where it marks the run opaque (no cel folds
 * into an opaque run, so it is never read as coverage), and coverage is
 * never negative, so the sign bit alone tells: one load and a test of the
 * sign, against opaque_bits' load, shift and bit test, on each run a fold
 * visits (fold_run_as; -0.31 M instructions a Many-blobs exact frame). On
 * a Cortex-M4 the bit test is as short and the extra store costs (+0.1 M
 * in the board demo's frame), so the boards test the bit. */
#if defined(__x86_64__)
#define CS__OPAQUE_IN_USED 1
#else
#define CS__OPAQUE_IN_USED 0
#endif
#define CS__USED_OPAQUE (-1.0f)

static inline bool cs__run_start_opaque(const cs_renderer *r, uint32_t s)
{
#if CS__OPAQUE_IN_USED
    union {
        float f;
        int32_t i;
    } u = {r->ws->used[s]};
    return u.i < 0;
#else
    return cs__run_opaque(r, s);
#endif
}

/* Bits a..b-1 of a word, 0 <= a < b <= 32. */
static inline uint32_t cs__bit_range(uint32_t a, uint32_t b)
{
    return (0xFFFFFFFFu << a) & (0xFFFFFFFFu >> (32u - b));
}

/* Whether every pixel of [a, b) is opaque (a < b): a test of the bits
 * cs__run_join set, a word (32 pixels) at a time. */
static inline bool cs__span_opaque(const cs_renderer *r, uint32_t a, uint32_t b)
{
    if (r->opaque_px == 0u) /* always so with the early-out off */
        return false;
    const uint32_t *bits = r->ws->opaque_bits;
    /* The clear bits, shifted so that those outside [a, b) fall off the
     * word: no mask to build (-0.2 M instructions a Many-blobs exact
     * frame, most from the exact area's hull tests). */
    uint32_t wa = a >> 5, wb = (b - 1u) >> 5;
    if (wa == wb) /* b - a bits from bit a & 31 */
        return ((~bits[wa] >> (a & 31u)) << (32u - (b - a))) == 0u;
    if ((~bits[wa] >> (a & 31u)) != 0u)
        return false;
    for (uint32_t w = wa + 1u; w < wb; w++)
        if (bits[w] != 0xFFFFFFFFu)
            return false;
    return (~bits[wb] << (31u - ((b - 1u) & 31u))) == 0u;
}

/* Marks pixels [a, b) opaque (a < b). */
static inline void cs__mark_opaque(cs_workspace *ws, uint32_t a, uint32_t b)
{
    uint32_t wa = a >> 5, wb = (b - 1u) >> 5;
    if (wa == wb) { /* b - a bits from bit a & 31 */
        ws->opaque_bits[wa] |= (0xFFFFFFFFu >> (32u - (b - a))) << (a & 31u);
        return;
    }
    ws->opaque_bits[wa] |= cs__bit_range(a & 31u, 32u);
    for (uint32_t w = wa + 1u; w < wb; w++)
        ws->opaque_bits[w] = 0xFFFFFFFFu;
    ws->opaque_bits[wb] |= cs__bit_range(0u, ((b - 1u) & 31u) + 1u);
}

/* The start of the run holding pixel a, walking right from run start s <= a. */
static inline uint32_t cs__run_seek(const cs_workspace *ws, uint32_t s, uint32_t a)
{
    while (ws->run_end[s] <= a)
        s = ws->run_end[s];
    return s;
}

#if defined(__GNUC__) && defined(__AVX__)
/* Three floats and the one after them as a vector (loads and stores of any
 * alignment; AVX's vblendps keeps the fourth). Not may_alias: a float
 * vector aliases floats alone, so its stores do not make GCC read the
 * workspace pointer and the cel's run count again after each one
 * (-0.3 M instructions a Many-blobs exact frame). */
typedef float cs__v4 __attribute__((vector_size(16), aligned(4)));
#define CS__VEC3 1
#else
#define CS__VEC3 0
#endif

/* d[0..2] += T * E[0..2]: the products and sums of the channels, each the
 * same bits as alone. The AVX build takes one vector for the three (6
 * instructions instead of 9, on each of ~133 k joins a Many-blobs exact
 * frame) and writes the fourth float back as it read it: it is the next
 * pixel's E[0], whose run may start there. E[3] is read (a float of the
 * same object or struct: cel_E and stack_E are followed by more floats,
 * a cache run's E by its T) and its lane discarded. */
static inline void cs__add_scaled3(float *d, float T, const float *E)
{
#if CS__VEC3
    cs__v4 v = *(const cs__v4 *)d;
    cs__v4 sum = v + T * *(const cs__v4 *)E;
    *(cs__v4 *)d = __builtin_shufflevector(sum, v, 0, 1, 2, 7);
#else
    for (int ch = 0; ch < 3; ch++)
        d[ch] += T * E[ch];
#endif
}

/* Puts a map (E, t) behind the stack of the run [s, e): E_s += T_s E,
 * T_s *= t; the run is counted opaque once T_s is 0 on every channel, if
 * the early-out is on (r->record): with it off, no bit of opaque_bits is
 * ever set and opaque_px stays 0, so the tests of both need no other.
 * Every way into the stack (a cel, a lone region, the cache) ends here.
 * In a grey frame T_s and t are their channel 0: the products are those of
 * the three channels, which hold the same number. */
static CS__SPECIALISE void cs__run_join(cs_renderer *r, bool grey, uint32_t s, uint32_t e,
                                        const float E[3], const float t[3])
{
    float *se = &r->ws->stack_E[3 * s], *st = &r->ws->stack_T[3 * s];
    bool opaque;
    if (grey) {
        float T = st[0];
        cs__add_scaled3(se, T, E);
        st[0] = T * t[0];
        opaque = st[0] == 0.0f;
    } else {
        for (int ch = 0; ch < 3; ch++) {
            se[ch] += st[ch] * E[ch];
            st[ch] *= t[ch];
        }
        opaque = (st[0] == 0.0f) & (st[1] == 0.0f) & (st[2] == 0.0f);
    }
    if (opaque && r->record) {
        r->opaque_px += e - s;
        cs__mark_opaque(r->ws, s, e);
#if CS__OPAQUE_IN_USED
        r->ws->used[s] = CS__USED_OPAQUE; /* cs__run_start_opaque */
#endif
    }
}

/* Splits the run at *s, which meets [a, b), so that it lies within [a, b);
 * *s becomes its start and the return value its end. `bare` as for
 * cs__run_split_as. */
static CS__SPECIALISE uint32_t cs__run_clip_as(cs_workspace *ws, bool grey, bool bare,
                                               uint32_t *s, uint32_t a, uint32_t b)
{
    uint32_t e = ws->run_end[*s];
    if (*s < a) {
        cs__run_split_as(ws, grey, bare, *s, a);
        *s = a;
    }
    if (e > b) {
        cs__run_split_as(ws, grey, bare, *s, b);
        e = b;
    }
    return e;
}

static CS__SPECIALISE uint32_t cs__run_clip(cs_workspace *ws, bool grey, uint32_t *s, uint32_t a,
                                            uint32_t b)
{
    return cs__run_clip_as(ws, grey, false, s, a, b);
}

#endif /* CS_RUNS_H */
