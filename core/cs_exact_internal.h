/*
 * cs_exact_internal.h - what the exact-area files share (cs_exact.c, the
 * band proof and the driver; cs_exact_place.c, arc placement;
 * cs_exact_area.c, the area): the per-row context, the few small helpers
 * every stage uses, inline as they were in one file, and the functions
 * that cross from one stage to the next. See cs_exact.c for the method.
 */
#ifndef CS_EXACT_INTERNAL_H
#define CS_EXACT_INTERNAL_H

#include "cs_runs.h"

#if CS_CFG_EXACT

/*
 * For a path kept out of a hot function, so that the hot one saves fewer
 * registers on every call. Not `cold`: that compiles it for size, and
 * struct copies then call memcpy (RISC-V), which the core must not.
 */
#if defined(__GNUC__)
#define CS__EXACT_NOINLINE __attribute__((noinline))
#else
#define CS__EXACT_NOINLINE
#endif

/* Stands for "no bound": a hull that could not be formed. */
#define HUGE_X 1.0e30f

typedef struct cs__exact_ctx {
    cs_workspace *ws;
    const cs_region *region;
    float row_top, row_bot;
    int32_t x0, width;   /* the window: device columns [x0, x0 + width) */
    float left, right;   /* x0 and x0 + width, as floats */
    float wall_x;        /* the whole output's width, where cuts stop (see put_cell) */
    int32_t lo, hi;      /* accumulator entries written: [lo, hi) */
    uint32_t bands_left; /* CS_CFG_EXACT_MAX_BANDS countdown */
    bool overflow;
} cs__exact_ctx;

static inline float cs__exact_top_u(const cs_piece *pc) { return pc->dir > 0 ? pc->u0 : pc->u1; }
static inline float cs__exact_bot_u(const cs_piece *pc) { return pc->dir > 0 ? pc->u1 : pc->u0; }

static inline bool cs__exact_polynomial(const cs_segment *s) { return !s->rational; }

/*
 * |v| for the Newton steps' acceptance tests: one AND (GCC's builtin,
 * inline on every target the core builds for; no libm), where cs__absf
 * (v < 0 ? -v : v) compiles to a compare, a negation and a blend. The two
 * differ only on -0 and the sign of a NaN, which a sum compared with a
 * tolerance cannot tell apart.
 */
static inline float cs__exact_mag(float v)
{
#if defined(__GNUC__)
    return __builtin_fabsf(v);
#else
    return cs__absf(v);
#endif
}

/* The part of the row the piece spans. */
static inline float cs__exact_row_top(const cs__exact_ctx *cx, const cs_piece *pc)
{
    return cs__maxf(pc->y_top, cx->row_top);
}
static inline float cs__exact_row_end(const cs__exact_ctx *cx, const cs_piece *pc)
{
    return cs__minf(pc->y_bot, cx->row_bot);
}

/* Widens the row's accumulator range to [a, b). Stored either way, so
 * that the compiler can select without a branch: whether a cell widens
 * the range goes by the data (~30 k mispredicted branches of a Many-blobs
 * exact frame when it was `if (a < cx->lo) cx->lo = a`). */
static inline void cs__exact_touch(cs__exact_ctx *cx, int32_t a, int32_t b)
{
    cx->lo = a < cx->lo ? a : cx->lo;
    cx->hi = b > cx->hi ? b : cx->hi;
}

/* u between ua (at height ya) and ub (at yb) where y is yv, on the chord. */
static inline float cs__exact_chord_u(float ua, float ya, float ub, float yb, float yv)
{
    return ua + (yv - ya) / (yb - ya) * (ub - ua);
}

/*
 * Inner control points of the arc from end a to end b (parameter step
 * h = b.u - a.u, either sign), y running from ya to yb: in homogeneous
 * form b1 = P(a) + h/p P'(a) and b(p-1) = P(b) - h/p P'(b), which in the
 * plane is the end plus t P' / (1 + t W'/W) with t = +-h/p. Returns the
 * number written (p - 1), or -1 if a weight is not positive (it cannot
 * be for positive segment weights, but rounding is not trusted).
 *
 * py is given as height below ya, not as y: near the bottom of a 1080-line
 * screen a float y holds 2^-14 px, and an edge's cell in column c weighs
 * its height by up to the arc's length in columns (add_poly_arc), which
 * made long, shallow arcs 0.5/255 off pixel by pixel. Heights within the
 * row keep 2^-24 of it.
 *
 * cs__exact_control_points of a polynomial segment of degree p (2 or 3):
 * q = 1, so nothing to test. */
static inline int cs__exact_poly_points(int p, const cs_exact_end *a, float ya,
                                        const cs_exact_end *b, float yb, float *px, float *py)
{
    float t = (b->u - a->u) / (p == 3 ? 3.0f : 2.0f), h = yb - ya; /* = / (float)p */
    px[0] = a->x + t * a->dx;
    py[0] = t * a->dy;
    if (p == 3) {
        px[1] = b->x - t * b->dx;
        py[1] = h - t * b->dy;
    }
    return p - 1;
}
static inline int cs__exact_control_points(const cs_segment *s, const cs_exact_end *a, float ya,
                          const cs_exact_end *b, float yb, float *px, float *py)
{
    int p = s->degree;
    if (p < 2)
        return 0;
    if (a->dwr == 0.0f && b->dwr == 0.0f) /* polynomial: q = 1 */
        return cs__exact_poly_points(p, a, ya, b, yb, px, py);
    float t = (b->u - a->u) / (float)p, h = yb - ya;
    float q = 1.0f + t * a->dwr;
    if (!(q > 0.0f))
        return -1;
    float f = t / q;
    px[0] = a->x + f * a->dx;
    py[0] = f * a->dy;
    if (p == 3) {
        q = 1.0f - t * b->dwr;
        if (!(q > 0.0f))
            return -1;
        f = t / q;
        px[1] = b->x - f * b->dx;
        py[1] = h - f * b->dy;
    }
    return p - 1;
}

/*
 * Bounds of the arc of e over the band [ya, yb]: its x range, whether it
 * is x-monotone (variation diminishing: a control polygon monotone in x
 * makes the curve so) and, if `strip`, its strip around the chord and its
 * order key (only bands of more than one arc need those).
 */
static inline void cs__exact_hull(const cs_segment *s, cs_exact_piece *e, float ya, float yb,
                                  bool strip)
{
    float x0 = e->top.x, x1 = e->bot.x;
    e->key = x0 + x1;
    e->dmin = e->dmax = 0.0f;
    e->xmin = cs__minf(x0, x1);
    e->xmax = cs__maxf(x0, x1);
    e->monotone = true;
    float px[3], py[2];
    int k = cs__exact_control_points(s, &e->top, ya, &e->bot, yb, px, py);
    if (k < 0) {
        e->dmin = e->xmin = -HUGE_X;
        e->dmax = e->xmax = HUGE_X;
        e->monotone = false;
        return;
    }
    if (k == 0)
        return; /* a straight line, whatever its weights */
    px[k] = x1;
    bool up = false, down = false;
    float prev = x0;
    for (int j = 0; j <= k; j++) {
        e->xmin = cs__minf(e->xmin, px[j]);
        e->xmax = cs__maxf(e->xmax, px[j]);
        up = up || px[j] > prev;
        down = down || px[j] < prev;
        prev = px[j];
    }
    e->monotone = !(up && down);
    if (!strip)
        return;
    float slope = (x1 - x0) / (yb - ya);
    /* The end control points are the arc's ends, x_top and x_bot: their d
     * is 0 by definition, which keeps rounding out of touching vertices. */
    for (int j = 0; j < k; j++) {
        float d = px[j] - (x0 + py[j] * slope);
        e->dmin = cs__minf(e->dmin, d);
        e->dmax = cs__maxf(e->dmax, d);
    }
}

/* cs_exact_place.c: the end at u (x, x', y', W'/W); the end at height yv
 * searched in [lo, hi] from u; the arcs of a region's active pieces
 * act[0..n) across the row, into ws->exact[0..n) (stand-ins where the
 * pixels they could touch are opaque). */
void cs__exact_eval_end(const cs_segment *s, float u, float y, cs_exact_end *e);
void cs__exact_place_end(const cs_segment *s, bool poly, float yv, float lo, float hi, float u,
                         bool rising, cs_exact_end *e);
void cs__exact_place_row(const cs_renderer *r, const cs__exact_ctx *cx, const cs_index *act,
                         uint32_t n);

/* cs_exact_area.c: adds effective edge e over the band [ya, yb], sign +1
 * where the region begins, to the area/cover accumulators. */
void cs__exact_add_edge(cs__exact_ctx *cx, const cs_exact_piece *e, float sign, float ya,
                        float yb);

#endif /* CS_CFG_EXACT */
#endif /* CS_EXACT_INTERNAL_H */
