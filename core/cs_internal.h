/*
 * cs_internal.h - helpers shared by the core's files, not part of the API.
 *
 * The core may not call libm, so the handful of float operations it needs
 * live here as inline functions whose results are the same on every IEEE-754
 * target (no contraction, no library calls). Private names use the cs__
 * prefix, public ones cs_.
 */
#ifndef CS_INTERNAL_H
#define CS_INTERNAL_H

#include "celscan.h"

static inline float cs__absf(float v) { return v < 0.0f ? -v : v; }
static inline float cs__minf(float a, float b) { return a < b ? a : b; }
static inline float cs__maxf(float a, float b) { return a > b ? a : b; }
static inline float cs__clampf(float v, float lo, float hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

/* True for every float that is neither NaN nor infinite. */
static inline bool cs__finite(float v)
{
    return v == v && v - v == 0.0f;
}

/* floor() for |v| < 2^31; the core only asks it of device coordinates. */
static inline int32_t cs__floori(float v)
{
    int32_t i = (int32_t)v;
    return ((float)i > v) ? i - 1 : i;
}

/* Correctly rounded square root: one instruction with -fno-math-errno on
 * SSE, VFP and RISC-V F, so the result is identical on every target. */
static inline float cs__sqrtf(float v) { return __builtin_sqrtf(v); }

static inline void cs__error(cs_error *err, cs_status st, int32_t cel, int32_t region,
                             int32_t contour, int32_t item)
{
    if (err) {
        err->status = st;
        err->cel = cel;
        err->region = region;
        err->contour = contour;
        err->item = item;
    }
}

/* Validation shared by the builder (cs_scene.c), editing (cs_edit.c) and
 * animation keys (cs_anim.c), so every path into the store checks alike. */
cs_status cs__check_canvas(float canvas_w, float canvas_h);
cs_status cs__check_lights(const float *front, const float *back); /* either may be NULL */
cs_status cs__check_colour(const float *rgb);                    /* finite, in 0..1 */
cs_status cs__check_affine(const cs_affine *m, int32_t *item);
cs_status cs__check_paint(const cs_paint *p);
cs_status cs__check_point(const cs_point *p);
cs_status cs__check_contour(int degree, int count, const cs_point *pts, const float *intervals,
                            int32_t *item);
void cs__copy_paint(cs_paint *dst, const cs_paint *src);

/* Removes the tracks whose target of `kind`'s family lies in [first, first+count)
 * and renumbers the later targets down by `count` (cs_anim.c). */
void cs__tracks_remove_range(cs_scene *scene, int family, uint32_t first, uint32_t count);
/* Track families: what a target index counts. */
enum { CS__FAM_CEL = 0, CS__FAM_REGION = 1, CS__FAM_CONTOUR = 2, CS__FAM_STACK = 3 };
int cs__track_family(int kind);
/* Re-sorts the tracks by (kind, target) after targets were renumbered. */
void cs__tracks_sort(cs_scene *scene);

/* The track of (kind, target), or NULL (binary search; the tracks are sorted). */
const cs_track *cs__track_find(const cs_scene *scene, int kind, uint32_t target);
/*
 * Where time t falls among a track's keys: the value is
 * (1-s) * key[i0] + s * key[i1], with i0 == i1 (and s = 0) outside the keys.
 */
void cs__track_locate(const cs_scene *scene, const cs_track *tr, float t, uint32_t *i0,
                      uint32_t *i1, float *s);
/* (1-s) a + s b: exactly a at s = 0 and b at s = 1, between them (to rounding) otherwise. */
static inline float cs__lerp(float a, float b, float s) { return (1.0f - s) * a + s * b; }

/* Polynomials of degree <= 4 in power basis, c[0] + c[1] u + ... */
float cs__poly_eval(const float *c, int degree, float u);

/*
 * Real roots of the polynomial c (degree <= 4) strictly inside (lo, hi), in
 * increasing order, written to roots[]; returns how many (at most degree).
 * Roots are isolated between the roots of the derivative and refined by a
 * bounded bracketed solve, so the cost is fixed and no recursion follows
 * the input.
 */
int cs__poly_roots(const float *c, int degree, float lo, float hi, float *roots);

/*
 * Solves f(u) = 0 for u in [lo, hi] where f(lo) and f(hi) have opposite
 * signs (or one is zero), f given as num(u) - level*den(u) with num, den
 * polynomials of degree `degree`. Bounded Illinois iteration; returns the
 * end point with the smaller |f| if the signs do not bracket.
 */
float cs__solve_level(const float *num, const float *den, int degree, float level, float lo,
                      float hi);

/*
 * Converts one closed periodic NURBS contour to rational polynomial segments
 * in device space (cs_nurbs.c). Control points go through `to_device` first;
 * a transformed NURBS is still a NURBS with the same weights. Fails with
 * CS_ERR_RANGE (and *bad_point set) if a transformed point leaves the
 * coordinate limit, or CS_ERR_CAP_SEGMENTS when `capacity` is too small.
 */
cs_status cs__contour_segments(const cs_point *points, const float *intervals, int count,
                               int degree, const cs_affine *to_device, uint16_t region,
                               cs_segment *out, uint32_t capacity, uint32_t *written,
                               int32_t *bad_point);

/* 16-bit sRGB code of linear (i/1024)^2 (cs_srgb_table.c). */
extern const uint16_t cs__srgb_by_sqrt[1025];

#endif /* CS_INTERNAL_H */
