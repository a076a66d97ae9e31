/*
 * cs_exact_place.c - arc placement for exact-area anti-aliasing (stage 0 of
 * cs_exact.c): where each active piece enters and leaves a pixel row, u at
 * a given height by Newton from the chord (closed form for a straight
 * piece, plane coordinates for a polynomial one), with x, x', y' and W'/W
 * at both ends, and from those the arc's x range. The band proof
 * (cs_exact.c) moves ends to its cuts with the same solve, and the area
 * (cs_exact_area.c) evaluates ends at x-extrema.
 */
#include "cs_exact_internal.h"

#if CS_CFG_EXACT /* the whole file: see cs_config.h */


/*
 * The end at u: x, and x', y' and W'/W for the control points. `y` is the
 * point's y, known to the caller (a band's level, or computed at a cut);
 * with it the rational derivative y' needs no evaluation of Y.
 */
void cs__exact_eval_end(const cs_segment *s, float u, float y, cs_exact_end *e)
{
    int p = s->degree;
    float dX, X = cs__horner_d(s->x, p, u, &dX);
    float dY;
    (void)cs__horner_d(s->y, p, u, &dY);
    e->u = u;
    if (cs__exact_polynomial(s)) {
        float W = s->w[0], inv = 1.0f / W;
        e->x = (float)s->ox + X / W;
        e->dx = dX * inv;
        e->dy = dY * inv;
        e->w = W;
        e->dwr = 0.0f;
    } else {
        /* x and y from the segment's origin, as X and Y are */
        float dW, W = cs__horner_d(s->w, p, u, &dW), inv = 1.0f / W, x = X / W;
        e->x = (float)s->ox + x;
        e->dx = (dX - x * dW) * inv;
        e->dy = (dY - (y - (float)s->oy) * dW) * inv;
        e->w = W;
        e->dwr = dW * inv;
    }
}

/*
 * Value, first and second derivative at u of the cubic c (c[3] and c[2]
 * are 0 for lower degrees: cs_nurbs.c clears them).
 */
static inline float jet(const float *c, float u, float *d1, float *d2)
{
    float t3 = c[3] * u, k3 = 3.0f * t3;
    *d2 = 2.0f * (k3 + c[2]);
    *d1 = (k3 + 2.0f * c[2]) * u + c[1];
    return ((t3 + c[2]) * u + c[1]) * u + c[0];
}

/*
 * g = Y - yv W is a cubic, so Newton's step s from u leaves exactly
 * (g''/2 + g3 s) s^2 of it: (g''/2 + g3 s) s^2 / W in y. The end is
 * accepted once that is below LEVEL_TOL px: its point is then exactly on
 * the curve, at a height off by less than that, which moves the row's
 * area by about as much. (Dropping the g3 term let an inflection pass a
 * 0.09/255 error in a random rational scene.)
 */
#define LEVEL_TOL (1.0f / 262144.0f)
#define LEVEL_MAX_ITER 8

/*
 * The end of s at height yv, with u searched in [lo, hi] (on which y is
 * monotone, growing with u if `rising`) by Newton's method from `u`.
 * Every step keeps the bracket; a step that would leave it hands the narrowed
 * bracket to the bounded solve of cs_poly.c.
 */
inline void cs__exact_place_end(const cs_segment *s, bool poly, float yv, float lo, float hi,
                                float u, bool rising, cs_exact_end *e)
{
    float g[4];
    yv -= (float)s->oy; /* from the segment's origin, as Y is */
    for (int i = 0; i < 4; i++)
        g[i] = s->y[i] - yv * s->w[i];
    float f, d, dd;
    if (lo == hi) { /* a piece's end: its u is known exactly */
        u = lo;
        f = jet(g, u, &d, &dd);
    } else if (s->degree == 1) { /* Y - yv W is linear: its root directly */
        u = cs__clampf(-g[0] / g[1], lo, hi);
        f = jet(g, u, &d, &dd);
    } else {
        float wt = poly ? s->w[0] : cs__horner(s->w, s->degree, u);
        float tol = (2.0f * LEVEL_TOL) * wt;
        bool done = false;
        if (u > lo && u < hi) {
            for (int it = 0; it < LEVEL_MAX_ITER; it++) {
                f = jet(g, u, &d, &dd);
                if (f == 0.0f) {
                    done = true;
                    break;
                }
                if ((f < 0.0f) == rising)
                    lo = u;
                else
                    hi = u;
                float rd = 1.0f / d, st = -f * rd, next = u + st;
                /* g being a cubic, the step leaves exactly
                 * (g''/2 + g3 s) s^2 of it */
                if ((cs__exact_mag(dd) + 2.0f * cs__exact_mag(g[3] * st)) * (st * st) <= tol) {
                    /* g' at the accepted point: exact Taylor for a cubic */
                    d += st * (dd + 3.0f * g[3] * st);
                    u = cs__clampf(next, lo, hi);
                    done = true;
                    break;
                }
                /* Chebyshev's correction (the root of the quadratic model)
                 * makes the steps converge cubically where the model holds. */
                float c = 0.5f * dd * st * rd;
                if (c > -0.5f && c < 0.5f)
                    next -= c * st;
                if (!(next > lo && next < hi))
                    break;
                u = next;
            }
        }
        if (!done) {
            u = cs__solve_level(s->y, s->w, s->degree, yv, lo, hi);
            f = jet(g, u, &d, &dd);
        }
    }
    float dX, ddX, X = jet(s->x, u, &dX, &ddX);
    e->u = u;
    if (poly) {
        float inv = 1.0f / s->w[0];
        e->x = (float)s->ox + X * inv;
        e->dx = dX * inv;
        e->dy = d * inv;
        e->w = s->w[0];
        e->dwr = 0.0f;
    } else {
        float dW, ddW, W = jet(s->w, u, &dW, &ddW), inv = 1.0f / W, x = X * inv;
        e->x = (float)s->ox + x;
        e->dx = (dX - x * dW) * inv;
        e->dy = d * inv;
        e->w = W;
        e->dwr = dW * inv;
    }
}

/* The end of a straight segment at height yv: u in closed form (or
 * `exact`, a piece's own end, if not negative), clamped to [ua, ub]
 * (either order). */
static void line_end(const cs_segment *s, float yv, float exact, float ua, float ub,
                     cs_exact_end *e)
{
    yv -= (float)s->oy; /* from the segment's origin, as Y is */
    float gy = s->y[1] - yv * s->w[1];
    float u = exact >= 0.0f ? exact
                            : cs__clampf((yv * s->w[0] - s->y[0]) / gy, cs__minf(ua, ub),
                                         cs__maxf(ua, ub));
    float W = s->w[1] * u + s->w[0], inv = 1.0f / W;
    float x = (s->x[1] * u + s->x[0]) * inv;
    e->u = u;
    e->x = (float)s->ox + x;
    e->dx = (s->x[1] - x * s->w[1]) * inv;
    e->dy = gy * inv;
    e->w = W;
    e->dwr = s->w[1] * inv;
}


/*
 * u in [lo, hi] where the polynomial Y (degree <= 3, monotone there,
 * growing if `rising`) equals `level`, by Newton's method from u, with
 * Y' there. The same iteration and acceptance as cs__exact_place_end, for
 * the common case of constant weight, with nothing else to carry.
 */
static float poly_level(const float *Y, int p, float level, float lo, float hi, float u,
                        bool rising, float tol, float *d1)
{
    float g0 = Y[0] - level, y1 = Y[1], y2 = Y[2], y3 = Y[3];
    float y2x2 = 2.0f * y2, y3x3 = 3.0f * y3;
    if (u > lo && u < hi) {
        for (int it = 0; it < LEVEL_MAX_ITER; it++) {
            float f = ((y3 * u + y2) * u + y1) * u + g0;
            float d = (y3x3 * u + y2x2) * u + y1;
            float dd = 2.0f * (y3x3 * u + y2);
            if (f == 0.0f) {
                *d1 = d;
                return u;
            }
            if ((f < 0.0f) == rising)
                lo = u;
            else
                hi = u;
            float rd = 1.0f / d, st = -f * rd, next = u + st;
            if ((cs__exact_mag(dd) + 2.0f * cs__exact_mag(y3 * st)) * (st * st) <= tol) {
                /* g' there: exact Taylor for a cubic */
                *d1 = d + st * (dd + y3x3 * st);
                return cs__clampf(next, lo, hi);
            }
            float c = 0.5f * dd * st * rd;
            if (c > -0.5f && c < 0.5f)
                next -= c * st;
            if (!(next > lo && next < hi))
                break;
            u = next;
        }
    }
    float w[4] = {1.0f, 0.0f, 0.0f, 0.0f};
    u = cs__solve_level(Y, w, p, level, lo, hi);
    *d1 = (y3x3 * u + y2x2) * u + y1;
    return u;
}

/*
 * The end of polynomial piece pc (constant weight w0, degree 2 or 3) at
 * height yv: its own end's u if yv is one, else Newton from the piece's
 * chord over the whole piece. It depends on the piece and yv alone, never
 * on the row asking, so the bottom of one row is the top of the next
 * (see the level memo in cs__exact_place_arc).
 */
static void poly_end(const cs_piece *pc, const cs_segment *s, float yv, cs_exact_end *e)
{
    const float *X = s->x, *Y = s->y;
    float w0 = s->w[0], inv = 1.0f / w0;
    float ut = cs__exact_top_u(pc), ub = cs__exact_bot_u(pc), u, d1;
    if (yv == pc->y_top || yv == pc->y_bot) { /* the piece's own end: its u is exact */
        u = yv == pc->y_top ? ut : ub;
        d1 = (3.0f * Y[3] * u + 2.0f * Y[2]) * u + Y[1];
    } else {
        u = poly_level(Y, s->degree, (yv - (float)s->oy) * w0, cs__minf(ut, ub), cs__maxf(ut, ub),
                       cs__exact_chord_u(ut, pc->y_top, ub, pc->y_bot, yv), pc->dir > 0,
                       (2.0f * LEVEL_TOL) * w0, &d1);
    }
    e->u = u;
    e->x = (float)s->ox + (((X[3] * u + X[2]) * u + X[1]) * u + X[0]) * inv;
    e->dx = ((3.0f * X[3] * u + 2.0f * X[2]) * u + X[1]) * inv;
    e->dy = d1 * inv;
    e->w = w0;
    e->dwr = 0.0f;
}

/* The end of any curved piece at height yv: poly_end, or for a rational
 * piece cs__exact_place_end from the chord over the whole piece. */
static void level_end(const cs_piece *pc, const cs_segment *s, float yv, cs_exact_end *e)
{
    if (cs__exact_polynomial(s)) {
        poly_end(pc, s, yv, e);
        return;
    }
    float ut = cs__exact_top_u(pc), ub = cs__exact_bot_u(pc);
    if (yv == pc->y_top || yv == pc->y_bot) {
        float u = yv == pc->y_top ? ut : ub;
        cs__exact_place_end(s, false, yv, u, u, u, pc->dir > 0, e);
    } else {
        cs__exact_place_end(s, false, yv, cs__minf(ut, ub), cs__maxf(ut, ub),
                  cs__exact_chord_u(ut, pc->y_top, ub, pc->y_bot, yv), pc->dir > 0, e);
    }
}

/*
 * x bounds of a polynomial arc from its control polygon (hull without the
 * strip): cheaper than cs__exact_hull(), which also serves rational arcs.
 */
static void poly_bounds(int p, cs_exact_piece *e)
{
    float xt = e->top.x, xb = e->bot.x;
    float t = (e->bot.u - e->top.u) / (float)p;
    float c1 = xt + t * e->top.dx, c2 = p == 3 ? xb - t * e->bot.dx : c1;
    e->key = xt + xb;
    e->dmin = e->dmax = 0.0f;
    e->xmin = cs__minf(cs__minf(xt, xb), cs__minf(c1, c2));
    e->xmax = cs__maxf(cs__maxf(xt, xb), cs__maxf(c1, c2));
    bool up = c1 > xt || c2 > c1 || xb > c2, down = c1 < xt || c2 < c1 || xb < c2;
    e->monotone = !(up && down);
}

/*
 * The arc of piece `piece` across the row: its ends and its x bounds. An
 * end inside the piece is a pure function of the piece and the height
 * (level_end), so the row's bottom end is kept in the level
 * memo and serves as the next row's top: one solve per row boundary, and
 * the same bits whichever lines were rendered before.
 */
void cs__exact_place_arc(const cs__exact_ctx *cx, cs_exact_piece *e, cs_index piece)
{
    cs_workspace *ws = cx->ws;
    const cs_piece *pc = &ws->pieces[piece];
    const cs_segment *s = &ws->segments[pc->segment];
    float ya = cs__exact_row_top(cx, pc), yb = cs__exact_row_end(cx, pc);
    float ut = cs__exact_top_u(pc), ub = cs__exact_bot_u(pc);
    e->piece = piece;
    e->row_arc = true;
    if (s->degree == 1) {
        line_end(s, ya, ya == pc->y_top ? ut : -1.0f, ut, ub, &e->top);
        line_end(s, yb, yb == pc->y_bot ? ub : -1.0f, ut, ub, &e->bot);
        e->u_row = e->bot.u;
        e->key = e->top.x + e->bot.x;
        e->dmin = e->dmax = 0.0f;
        e->xmin = cs__minf(e->top.x, e->bot.x);
        e->xmax = cs__maxf(e->top.x, e->bot.x);
        e->monotone = true;
        return;
    }
    cs_exact_level *memo = &ws->level_memo[piece];
    if (memo->y == ya)
        e->top = memo->end;
    else
        level_end(pc, s, ya, &e->top);
    level_end(pc, s, yb, &e->bot);
    if (yb < pc->y_bot) {
        memo->y = yb;
        memo->end = e->bot;
    }
    e->u_row = e->bot.u;
    if (cs__exact_polynomial(s))
        poly_bounds(s->degree, e);
    else
        cs__exact_hull(s, e, ya, yb, false);
}

#endif /* CS_CFG_EXACT */
