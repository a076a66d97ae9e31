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

/*
 * Whether a point is inside `region`, given the winding number of each of
 * its operands (winding[0] only, unless the region combines operands). Every
 * coverage method asks this one question, so fill rules and CSG mean the
 * same thing in every anti-aliasing mode.
 */
static inline bool cs__region_inside(const cs_region *region, const int32_t *winding)
{
    return region->fill_rule == CS_FILL_EVENODD ? (winding[0] & 1) != 0 : winding[0] != 0;
}

/*
 * Exact-area coverage of `region` on pixel row y (cs_exact.c), from its
 * active pieces act[0..n): adds to ws->area / ws->cover what the
 * sub-scanline code adds for its spans, so render_region folds both alike.
 * [*lo, *hi) grows to every accumulator entry written. Returns
 * CS_ERR_CAP_CROSSINGS, adding nothing, if n exceeds CS_CFG_MAX_CROSSINGS,
 * or, with the row still added, if it needed more than
 * CS_CFG_EXACT_MAX_BANDS bands to separate crossing curves.
 */
cs_status cs__exact_region(cs_renderer *r, const cs_region *region, const uint32_t *act,
                           uint32_t n, int y, int32_t *lo, int32_t *hi);

/* 16-bit sRGB code of linear (i/1024)^2 (cs_srgb_table.c). */
extern const uint16_t cs__srgb_by_sqrt[1025];

#endif /* CS_INTERNAL_H */
