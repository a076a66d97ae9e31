/*
 * cs_exact.c - exact-area anti-aliasing: the area of each pixel square that
 * lies inside a region, found from the curves themselves.
 *
 * Willis & Oddy compute horizontal coverage exactly and supersample
 * vertically; they describe, but never built, a geometric solution that
 * uses the exact horizontal information in both directions. This is it.
 * Nothing is flattened: every quantity below comes from the rational
 * polynomial segments (X(u), Y(u), W(u)) of cs_frame.c.
 *
 * Per pixel row [y, y+1) and per region:
 *
 * 0. Arcs and clusters. Each active piece's arc across the row is placed
 *    once: u where it enters the row and where it leaves (Newton from the
 *    chord of the piece), with x, x', y' and W'/W at both ends. An end is
 *    a pure function of the piece and the height, so the bottom end of a
 *    row is kept (the level memo) and is the top end of the next: one
 *    solve per row boundary, and the same bits whichever lines came
 *    before, or none. A straight piece is placed in closed form, a
 *    polynomial one in plane coordinates; the iteration stops once the
 *    residual of its last step, known exactly for a cubic, is below
 *    2^-18 px in y (place_end). Those give the arc's inner Bezier control
 *    points directly (P(a) + h/p P'(a) in homogeneous form), hence its x
 *    range. Pieces in order of xmin fall into clusters whose x ranges
 *    overlap; no curve passes between two clusters, so the winding across
 *    each is the same at every height of the row, and each cluster is
 *    banded and ordered on its own. A lone piece, the usual case, is one
 *    band with nothing to order. One exception: a horizontal segment has
 *    no piece, yet joins the ends of two that may be far apart. A cluster
 *    whose winding changes inside the row (its inner ends' height tags do
 *    not cancel, or, if they do, its bands disagree) takes in the next
 *    cluster until the changes cancel; the whole row always qualifies.
 *
 * 1. Bands. A cluster's part of the row is cut at every y_top / y_bot of
 *    its pieces. Between two cuts (a band) the set of pieces is fixed, and
 *    each piece is one arc from u_top to u_bot.
 *
 * 2. Order. If no two arcs cross inside a band, their left-to-right order
 *    is the same at every height of it, and the fill rule can be applied
 *    once per band instead of once per sample. That the order holds is
 *    proved, not sampled: each arc's Bezier control points over its band
 *    come from its ends, and since weights are positive the arc lies in
 *    their convex hull, so within a strip [dmin, dmax] around its chord,
 *    and within the hull's x range. Walking the arcs in chord order, an
 *    arc whose strip may reach left of the strips before it (the test is
 *    linear in y, so checking both band ends is enough) and whose x range
 *    begins left of where theirs end may cross them; the band is then cut where
 *    the two chords cross (exact for straight edges), or in the middle,
 *    and both halves are checked again. A band is accepted when the sum of
 *    possible overlaps times its height is below BAND_TOL (2^-15 px^2):
 *    that sum bounds the area that a crossing hidden inside it could put
 *    on the wrong side. Self-intersections, overlapping contours and
 *    shared vertices all go through this one test; a transversal crossing
 *    of two curves costs a few cuts. The cuts wait on a fixed stack; the
 *    bands of one row are counted against CS_CFG_EXACT_MAX_BANDS, beyond
 *    which bands are accepted unproved and CS_ERR_CAP_CROSSINGS reported.
 *
 * 3. Effective edges. Walking a band's arcs left to right with per-operand
 *    windings, cs__region_inside() (the predicate every AA mode uses) says
 *    where the region begins (+1) and ends (-1). Only these arcs matter,
 *    and because their weights are +-1 the region's coverage is their
 *    linear sum: nonzero, even-odd, holes and CSG all reduce to it.
 *
 * 4. Area. An effective edge adds, FreeType-style, to `area` the part of
 *    each pixel it passes through that lies to its right, and to `cover`
 *    the height it spans, for every pixel further right. The arc is cut at
 *    its x-extrema (roots of X'W - XW') and at integer x (X - kW = 0, a
 *    bracketed solve on an x-monotone arc); over each sub-arc in column c
 *    it adds (y1-y0) - Int (x - c) dy. For polynomial segments that is a
 *    closed form in the arc's Bezier control points, again from its ends'
 *    derivatives: in the arc's own parameter t, M(t) = Int (x - x0) y' dt
 *    is a polynomial, so a column's share is a difference of M and the
 *    cuts are roots of a cubic in t, with no evaluation of the segment
 *    (add_poly_arc; exact, like the 3-node Gauss rule it replaced). Rational
 *    ones use Int (x(u) - c) y'(u) du by Gauss-Legendre, 5 nodes per panel,
 *    panels cut until W varies little enough on each that the error is
 *    about 1e-6 of the value (3 nodes for a conic whose W is nearly
 *    constant on the panel; see rational_moment). Straight pieces use the
 *    exact trapezoid and find their integer-x cuts by interpolation. The
 *    common case, an arc whose control polygon stays in one column, needs
 *    no solve beyond the two that place it in its band.
 *
 *    As in the sub-scanline code the region is outside far to the left;
 *    an edge left of the screen adds its height to every pixel, and one
 *    right of it adds nothing.
 *
 * The result lands in the same area/cover accumulators the sub-scanline
 * code uses, so the fold (cs_line.c, fold_region), the within-cel coverage
 * budget and the compositing are shared by every AA mode. Line state is the region's
 * active pieces plus the O(width) accumulators; memory is fixed.
 */
#include "cs_runs.h"

#if CS_CFG_EXACT /* the whole file: see cs_config.h */

/* Area (px^2) by which a crossing hidden in an accepted band could be wrong. */
#define BAND_TOL (1.0f / 32768.0f)
/* Pending band cuts of one band; deeper cuts are not attempted. */
#define MAX_DEPTH 40
/* Stands for "no bound": a hull that could not be formed. */
#define HUGE_X 1.0e30f

/* Neighbouring pieces closer than this (px) share one band sweep. */
#define CLUSTER_GAP (1.0f / 16.0f)

typedef struct exact_ctx {
    cs_workspace *ws;
    const cs_region *region;
    float row_top, row_bot;
    int32_t x0, width;   /* the window: device columns [x0, x0 + width) */
    int32_t wall;        /* the whole output's width, where cuts stop (see put_cell) */
    int32_t lo, hi;      /* accumulator entries written: [lo, hi) */
    uint32_t bands_left; /* CS_CFG_EXACT_MAX_BANDS countdown */
    bool overflow;
} exact_ctx;

static float top_u(const cs_piece *pc) { return pc->dir > 0 ? pc->u0 : pc->u1; }
static float bot_u(const cs_piece *pc) { return pc->dir > 0 ? pc->u1 : pc->u0; }

static bool polynomial(const cs_segment *s) { return !s->rational; }

/* The part of the row the piece spans. */
static float row_top(const exact_ctx *cx, const cs_piece *pc)
{
    return cs__maxf(pc->y_top, cx->row_top);
}
static float row_end(const exact_ctx *cx, const cs_piece *pc)
{
    return cs__minf(pc->y_bot, cx->row_bot);
}

/*
 * The end at u: x, and x', y' and W'/W for the control points. `y` is the
 * point's y, known to the caller (a band's level, or computed at a cut);
 * with it the rational derivative y' needs no evaluation of Y.
 */
static void eval_end(const cs_segment *s, float u, float y, cs_exact_end *e)
{
    int p = s->degree;
    float dX, X = cs__horner_d(s->x, p, u, &dX);
    float dY;
    (void)cs__horner_d(s->y, p, u, &dY);
    e->u = u;
    if (polynomial(s)) {
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
static inline void place_end(const cs_segment *s, bool poly, float yv, float lo, float hi, float u,
                      bool rising, cs_exact_end *e)
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
                if ((cs__absf(dd) + 2.0f * cs__absf(g[3] * st)) * (st * st) <= tol) {
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

/* u between ua (at height ya) and ub (at yb) where y is yv, on the chord. */
static float chord_u(float ua, float ya, float ub, float yb, float yv)
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
 */
static inline int control_points(const cs_segment *s, const cs_exact_end *a, float ya,
                          const cs_exact_end *b, float yb, float *px, float *py)
{
    int p = s->degree;
    if (p < 2)
        return 0;
    float t = (b->u - a->u) / (float)p, h = yb - ya;
    if (a->dwr == 0.0f && b->dwr == 0.0f) { /* polynomial: q = 1 */
        px[0] = a->x + t * a->dx;
        py[0] = t * a->dy;
        if (p == 3) {
            px[1] = b->x - t * b->dx;
            py[1] = h - t * b->dy;
        }
        return p - 1;
    }
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
static inline void hull(const cs_segment *s, cs_exact_piece *e, float ya, float yb, bool strip)
{
    float x0 = e->top.x, x1 = e->bot.x;
    e->key = x0 + x1;
    e->dmin = e->dmax = 0.0f;
    e->xmin = cs__minf(x0, x1);
    e->xmax = cs__maxf(x0, x1);
    e->monotone = true;
    float px[3], py[2];
    int k = control_points(s, &e->top, ya, &e->bot, yb, px, py);
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

/*
 * u in [lo, hi] where the polynomial Y (degree <= 3, monotone there,
 * growing if `rising`) equals `level`, by Newton's method from u, with
 * Y' there. The same iteration and acceptance as place_end, for
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
            if ((cs__absf(dd) + 2.0f * cs__absf(y3 * st)) * (st * st) <= tol) {
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
 * (see the level memo in place_arc).
 */
static void poly_end(const cs_piece *pc, const cs_segment *s, float yv, cs_exact_end *e)
{
    const float *X = s->x, *Y = s->y;
    float w0 = s->w[0], inv = 1.0f / w0;
    float ut = top_u(pc), ub = bot_u(pc), u, d1;
    if (yv == pc->y_top || yv == pc->y_bot) { /* the piece's own end: its u is exact */
        u = yv == pc->y_top ? ut : ub;
        d1 = (3.0f * Y[3] * u + 2.0f * Y[2]) * u + Y[1];
    } else {
        u = poly_level(Y, s->degree, (yv - (float)s->oy) * w0, cs__minf(ut, ub), cs__maxf(ut, ub),
                       chord_u(ut, pc->y_top, ub, pc->y_bot, yv), pc->dir > 0,
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
 * piece place_end from the chord over the whole piece. */
static void level_end(const cs_piece *pc, const cs_segment *s, float yv, cs_exact_end *e)
{
    if (polynomial(s)) {
        poly_end(pc, s, yv, e);
        return;
    }
    float ut = top_u(pc), ub = bot_u(pc);
    if (yv == pc->y_top || yv == pc->y_bot) {
        float u = yv == pc->y_top ? ut : ub;
        place_end(s, false, yv, u, u, u, pc->dir > 0, e);
    } else {
        place_end(s, false, yv, cs__minf(ut, ub), cs__maxf(ut, ub),
                  chord_u(ut, pc->y_top, ub, pc->y_bot, yv), pc->dir > 0, e);
    }
}

/*
 * x bounds of a polynomial arc from its control polygon (hull without the
 * strip): cheaper than hull(), which also serves rational arcs.
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
static void place_arc(const exact_ctx *cx, cs_exact_piece *e, cs_index piece)
{
    cs_workspace *ws = cx->ws;
    const cs_piece *pc = &ws->pieces[piece];
    const cs_segment *s = &ws->segments[pc->segment];
    float ya = row_top(cx, pc), yb = row_end(cx, pc);
    float ut = top_u(pc), ub = bot_u(pc);
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
    if (polynomial(s))
        poly_bounds(s->degree, e);
    else
        hull(s, e, ya, yb, false);
}

/*
 * Sorts ord[0..m) by xmin (by_xmin) or by key. They arrive nearly sorted,
 * or in short runs: insertion sort, after a Shell pass when there are many
 * (gaps 3^k-ish, no gap at or beyond m).
 */
#define SORT_BODY(KEY)                                                                    \
    do {                                                                                  \
        static const uint32_t gaps[] = {57, 23, 10, 4};                                  \
        for (unsigned g = 0; g < sizeof gaps / sizeof gaps[0]; g++) {                    \
            uint32_t gap = gaps[g];                                                       \
            for (uint32_t i = gap; i < m; i++) {                                          \
                uint32_t t = ord[i];                                                      \
                float kt = ex[t].KEY;                                                     \
                uint32_t j = i;                                                           \
                while (j >= gap && ex[ord[j - gap]].KEY > kt) {                           \
                    ord[j] = ord[j - gap];                                                \
                    j -= gap;                                                             \
                }                                                                         \
                ord[j] = t;                                                               \
            }                                                                             \
        }                                                                                 \
        for (uint32_t i = 1; i < m; i++) {                                                \
            uint32_t t = ord[i];                                                          \
            float kt = ex[t].KEY;                                                         \
            uint32_t j = i;                                                               \
            for (float kp = ex[ord[j - 1]].KEY; kp > kt; kp = ex[ord[j - 1]].KEY) {       \
                ord[j] = ord[j - 1];                                                      \
                if (--j == 0)                                                             \
                    break;                                                                \
            }                                                                             \
            ord[j] = t;                                                                   \
        }                                                                                 \
    } while (0)

static void sort_pieces(const cs_exact_piece *ex, uint32_t *ord, uint32_t m, bool by_xmin)
{
    if (m == 2u) { /* the usual row of a region: two arcs */
        uint32_t a = ord[0], b = ord[1];
        if (by_xmin ? ex[b].xmin < ex[a].xmin : ex[b].key < ex[a].key) {
            ord[0] = b;
            ord[1] = a;
        }
        return;
    }
    if (by_xmin)
        SORT_BODY(xmin);
    else
        SORT_BODY(key);
}
#undef SORT_BODY

/*
 * Whether the order by key provably holds over [ya, yb], up to BAND_TOL.
 * If not, *cut is where to split the band.
 */
static bool band_ordered(const cs_exact_piece *ex, const uint32_t *ord, uint32_t m, float ya,
                         float yb, float *cut)
{
    float reach_top = -HUGE_X, reach_bot = -HUGE_X, reach_x = -HUGE_X, overlap = 0.0f;
    uint32_t first = 0;
    for (uint32_t k = 0; k < m; k++) {
        const cs_exact_piece *e = &ex[ord[k]];
        float g = cs__maxf(reach_top - (e->top.x + e->dmin), reach_bot - (e->bot.x + e->dmin));
        /* Either bound caps the width of what could lie on the wrong
         * side; the x ranges settle what the strips cannot near a
         * vertical tangent, where a strip stays wide however thin the
         * band (the top of a circle beside a steep edge took a dozen cuts). */
        g = cs__minf(g, reach_x - e->xmin);
        reach_x = cs__maxf(reach_x, e->xmax);
        if (g > 0.0f) {
            if (overlap == 0.0f)
                first = k;
            overlap += g;
        }
        reach_top = cs__maxf(reach_top, e->top.x + e->dmax);
        reach_bot = cs__maxf(reach_bot, e->bot.x + e->dmax);
    }
    float h = yb - ya;
    if (!(overlap * h > BAND_TOL))
        return true;
    float t = 0.5f;
    if (first > 0) {
        const cs_exact_piece *p = &ex[ord[first - 1]], *q = &ex[ord[first]];
        float dt = q->top.x - p->top.x, db = q->bot.x - p->bot.x;
        if ((dt < 0.0f && db > 0.0f) || (dt > 0.0f && db < 0.0f))
            t = cs__clampf(dt / (dt - db), 1.0f / 64.0f, 63.0f / 64.0f);
    }
    *cut = ya + t * h;
    return false;
}

static void touch(exact_ctx *cx, int32_t a, int32_t b)
{
    if (a < cx->lo)
        cx->lo = a;
    if (b > cx->hi)
        cx->hi = b;
}

static const float gl3_t[3] = {-0.77459666924148338f, 0.0f, 0.77459666924148338f};
static const float gl3_w[3] = {0.55555555555555556f, 0.88888888888888889f, 0.55555555555555556f};
static const float gl5_t[5] = {-0.90617984593866399f, -0.53846931010568309f, 0.0f,
                               0.53846931010568309f, 0.90617984593866399f};
static const float gl5_w[5] = {0.23692688505618909f, 0.47862867049936647f, 0.56888888888888889f,
                               0.47862867049936647f, 0.23692688505618909f};

/* Gauss-Legendre sum (3 or 5 nodes) of (x(u) - c) y'(u) over [a, b]. */
static float gauss(const cs_segment *s, int nodes, float a, float b, float c)
{
    int p = s->degree;
    const float *nt = nodes == 5 ? gl5_t : gl3_t, *nw = nodes == 5 ? gl5_w : gl3_w;
    float mid = 0.5f * (a + b), half = 0.5f * (b - a), sum = 0.0f;
    for (int k = 0; k < nodes; k++) {
        float u = mid + half * nt[k];
        float dW, W = cs__horner_d(s->w, p, u, &dW);
        float dY, Y = cs__horner_d(s->y, p, u, &dY);
        float xr = cs__horner(s->x, p, u) / W - (c - (float)s->ox);
        float yd = (dY * W - Y * dW) / (W * W);
        sum += nw[k] * (xr * yd);
    }
    return half * sum;
}

/* Bernstein coefficients over u in [a, a+h] of the degree-p power-basis c. */
static void bernstein(const float *c, int p, float a, float h, float *b)
{
    float q[4] = {c[0], c[1], c[2], c[3]};
    for (int k = 0; k < p; k++) /* Taylor shift to a, by repeated Horner */
        for (int i = p - 1; i >= k; i--)
            q[i] += a * q[i + 1];
    float hk = h;
    for (int k = 1; k <= p; k++) {
        q[k] *= hk;
        hk *= h;
    }
    /* b_j = sum_k C(j,k)/C(p,k) q_k */
    b[0] = q[0];
    if (p == 2) {
        b[1] = q[0] + 0.5f * q[1];
        b[2] = q[0] + q[1] + q[2];
    } else if (p == 3) {
        b[1] = q[0] + q[1] / 3.0f;
        b[2] = q[0] + (2.0f * q[1] + q[2]) / 3.0f;
        b[3] = q[0] + q[1] + q[2] + q[3];
    } else {
        b[1] = q[0] + q[1];
    }
}

/*
 * Int (x - c) dy along a rational arc from u0 to u1 (its sign follows y).
 *
 * The integrand is X (Y'W - YW') / W^3. Its poles are the zeros of W,
 * which strong weights can put just outside the arc (weight 0.2 next to
 * 3.6 puts one 3% of the arc's length away, and 5 nodes then miss by 6%).
 * So the arc is cut into panels on which W's Bernstein coefficients stay
 * within a ratio of WEIGHT_SPREAD: W then has no zero inside the Bernstein
 * ellipse of rho ~ 3.9 around the panel, and 5 nodes are good to about
 * rho^-10 ~ 1e-6 of the panel's value. Arcs of conics and mild weights
 * pass as a single panel.
 */
#define WEIGHT_SPREAD 1.25f
/*
 * Where W varies less still, fewer nodes do. With Bernstein coefficients
 * within w(1 +- e), W = w (1 + sum e_j B_j(t)) cannot vanish where
 * (|t| + |1 - t|)^p e < 1, i.e. inside the ellipse of rho ~ 2 e^(-1/p).
 * For a conic (p = 2; the integrand's numerator then has degree 4, which
 * 3 nodes integrate exactly) a spread of 1.05 gives rho ~ 13 and 3 nodes
 * are good to rho^-6 ~ 2e-7: the usual case, a conic's arc within a pixel.
 */
#define CONIC_SPREAD_3 1.05f
#define MAX_PANEL_DEPTH 12
static float rational_moment(const cs_segment *s, const cs_exact_end *e0, const cs_exact_end *e1,
                             float c)
{
    float u0 = e0->u, u1 = e1->u;
    int p = s->degree;
    /* Panels depth first, left to right, so the sum's order is fixed. */
    float lo[MAX_PANEL_DEPTH + 1], hi[MAX_PANEL_DEPTH + 1];
    int depth[MAX_PANEL_DEPTH + 1], top = 0;
    lo[0] = u0;
    hi[0] = u1;
    depth[0] = 0;
    float sum = 0.0f;
    while (top >= 0) {
        float a = lo[top], b = hi[top];
        int d = depth[top--], nodes = 5;
        if (d < MAX_PANEL_DEPTH) {
            float bw[4];
            if (d == 0) { /* the whole arc: W's coefficients from its ends */
                float t = (u1 - u0) * (p == 3 ? 1.0f / 3.0f : 0.5f);
                bw[0] = e0->w;
                bw[1] = e0->w * (1.0f + t * e0->dwr);
                bw[2] = p == 3 ? e1->w * (1.0f - t * e1->dwr) : e1->w;
                bw[3] = e1->w;
            } else {
                bernstein(s->w, p, cs__minf(a, b), cs__absf(b - a), bw);
            }
            float wmin = bw[0], wmax = bw[0];
            for (int j = 1; j <= p; j++) {
                wmin = cs__minf(wmin, bw[j]);
                wmax = cs__maxf(wmax, bw[j]);
            }
            float m = 0.5f * (a + b);
            if (!(wmax <= WEIGHT_SPREAD * wmin) && m != a && m != b) {
                lo[++top] = m; /* right half waits, left half next */
                hi[top] = b;
                depth[top] = d + 1;
                lo[++top] = a;
                hi[top] = m;
                depth[top] = d + 1;
                continue;
            }
            if (p == 2 && wmax <= CONIC_SPREAD_3 * wmin)
                nodes = 3;
        }
        sum += gauss(s, nodes, a, b, c);
    }
    return sum;
}

/*
 * The control polygon (bx, by)[0..p] of the arc from end a (at ya) to end
 * b (at yb), y as height below ya (see control_points). Returns its
 * degree p, or less than 2 if it has none (a straight segment, or a
 * weight that is not positive).
 */
static inline int arc_polygon(const cs_segment *s, const cs_exact_end *a, float ya,
                              const cs_exact_end *b, float yb, float *bx, float *by)
{
    int k = control_points(s, a, ya, b, yb, &bx[1], &by[1]);
    if (k <= 0)
        return 0;
    bx[0] = a->x;
    by[0] = 0.0f;
    bx[k + 1] = b->x;
    by[k + 1] = yb - ya;
    return k + 1;
}

/*
 * Int (x - c) dy along a polynomial arc of degree p (2 or 3) in closed
 * form from its Bezier control points (bx, by)[0..p]:
 * sum_ij K_ij (x_i - c) (y_(j+1) - y_j), K_ij = Int B_i^p (p B_j^(p-1))
 * = C(p,i) C(p-1,j) / (2 C(2p-1,i+j)). Exact, like the 3-node Gauss rule
 * it replaced, but with no evaluation of the segment.
 */
static inline float bezier_moment(int p, const float *bx, const float *by, float c)
{
    float x0 = bx[0] - c, x1 = bx[1] - c, x3 = bx[p] - c;
    if (p == 2) {
        float d0 = by[1] - by[0], d1 = by[2] - by[1];
        return (0.5f * x0 + (1.0f / 3.0f) * x1 + (1.0f / 6.0f) * x3) * d0 +
               ((1.0f / 6.0f) * x0 + (1.0f / 3.0f) * x1 + 0.5f * x3) * d1;
    }
    float x2 = bx[2] - c;
    float d0 = by[1] - by[0], d1 = by[2] - by[1], d2 = by[3] - by[2];
    return (0.5f * x0 + 0.3f * x1 + 0.15f * x2 + 0.05f * x3) * d0 +
           (0.2f * x0 + 0.3f * x1 + 0.3f * x2 + 0.2f * x3) * d1 +
           (0.05f * x0 + 0.15f * x1 + 0.3f * x2 + 0.5f * x3) * d2;
}

/* Int (x - c) dy along a polynomial arc from a (at y0) to b (at y1). */
static float poly_moment(const cs_segment *s, const cs_exact_end *a, float y0,
                         const cs_exact_end *b, float y1, float c)
{
    float bx[4], by[4];
    int p = arc_polygon(s, a, y0, b, y1, bx, by);
    if (p < 2) /* no control polygon: the chord's trapezoid */
        return 0.5f * ((a->x - c) + (b->x - c)) * (y1 - y0);
    return bezier_moment(p, bx, by, c);
}

/*
 * A height within the row (0..1) rounded to a multiple of 2^-20 px: adding
 * 8 leaves no bit below that, and subtracting it again is exact. An edge
 * adds its cells' heights to `cover`, and a pixel inside a region must
 * come out covered exactly 1, or it never counts as opaque and everything
 * behind it is composited too. Heights on one grid make every partial sum
 * exact, so an edge's cells add up to its band's height to the bit, as
 * they did when heights were absolute y (multiples of its ulp).
 */
static inline float on_grid(float h)
{
    return (h + 8.0f) - 8.0f;
}

/* A cell of an edge: height dy of it in device column c, whose part right
 * of the edge has area dy - m. Edges are cut at the columns of the whole
 * output, viewport or not, so that every cell of the window has the bits
 * the whole render gives it; the cells left of the window only add their
 * heights (multiples of 2^-20, so the sums are exact in any grouping). */
static inline void put_cell(exact_ctx *cx, float sign, int32_t c, float dy, float m)
{
    if (!(dy > 0.0f))
        return;
    cs_workspace *ws = cx->ws;
    c -= cx->x0;
    if (c < 0) { /* left of the screen: all of it is to the right */
        cs__acc_cover(ws, 0, sign * dy);
        touch(cx, 0, 1);
        return;
    }
    if (c >= cx->width) {
        touch(cx, cx->width, cx->width + 1);
        return;
    }
    m = cs__clampf(m, 0.0f, dy);
    cs__acc_area(ws, c, sign * (dy - m));
    cs__acc_cover(ws, c + 1, sign * dy);
    touch(cx, c, c + 2);
}

/* Sub-arc a..b (y0 < y1) lying in column c: the part of the column right
 * of it is inside (sign +1) or outside (-1) from here on. */
static void add_cell(exact_ctx *cx, const cs_segment *s, float sign, int32_t c,
                     const cs_exact_end *a, float y0, const cs_exact_end *b, float y1)
{
    float dy = y1 - y0;
    if (!(dy > 0.0f) || c < cx->x0 || c - cx->x0 >= cx->width) { /* no moment needed */
        put_cell(cx, sign, c, dy, 0.0f);
        return;
    }
    float fc = (float)c, m;
    if (polynomial(s))
        m = poly_moment(s, a, y0, b, y1, fc);
    else
        m = rational_moment(s, a, b, fc);
    put_cell(cx, sign, c, dy, m);
}

/* The point of an x-monotone sub-arc from a (at ya) to b (at yb) where x
 * is k, with y clamped to the sub-arc's range. */
static void cut_at_x(const cs_segment *s, const cs_exact_end *a, float ya, const cs_exact_end *b,
                     float yb, float k, cs_exact_end *out, float *y_out)
{
    float ua = a->u, ub = b->u, slope;
    /* Newton's first step from a (the cut before, a column away), or the chord. */
    float guess = a->dx != 0.0f ? ua + (k - a->x) / a->dx : ua;
    if (!(guess > cs__minf(ua, ub) && guess < cs__maxf(ua, ub)))
        guess = ua + (k - a->x) / (b->x - a->x) * (ub - ua);
    bool rising = (b->x > a->x) == (ub > ua);
    float u = cs__solve_level_from(s->x, s->w, s->degree, k - (float)s->ox, cs__minf(ua, ub), cs__maxf(ua, ub),
                                   guess, rising, &slope);
    float y = cs__clampf(cs__segment_y(s, u), ya, yb);
    eval_end(s, u, y, out);
    out->x = k;
    *y_out = y;
}

/* An x-monotone curved sub-arc, top (y0) to bottom (y1): cut at integer x
 * (straight ones go to add_line). Only cuts inside [0, width] matter;
 * beyond them whole columns do not. */
static void add_monotone(exact_ctx *cx, const cs_segment *s, float sign, const cs_exact_end *top,
                         float y0, const cs_exact_end *bot, float y1)
{
    float width = (float)cx->wall;
    cs_exact_end a = *top, k_end;
    float x0 = a.x, x1 = bot->x;
    bool inc = x1 > x0;
    float k = inc ? cs__maxf((float)(cs__floori(x0) + 1), 0.0f)
                  : cs__minf((float)(-cs__floori(-x0) - 1), width);
    for (; inc ? (k < x1 && k <= width) : (k > x1 && k >= 0.0f); k += inc ? 1.0f : -1.0f) {
        float yk;
        cut_at_x(s, &a, y0, bot, y1, k, &k_end, &yk);
        add_cell(cx, s, sign, cs__floori(inc ? a.x : k), &a, y0, &k_end, yk);
        a = k_end;
        y0 = yk;
    }
    add_cell(cx, s, sign, cs__floori(cs__minf(a.x, x1)), &a, y0, bot, y1);
}


/* A straight edge from (x0, y0) to (x1, y1), y0 < y1: cut at integer x,
 * where y is linear in x; each cell's moment is its trapezoid. */
static void add_line(exact_ctx *cx, float sign, float x0, float y0, float x1, float y1)
{
    float width = (float)cx->wall, xa = x0, ya = y0;
    if (x1 > x0) {
        float dydx = (y1 - y0) / (x1 - x0);
        float k = cs__maxf((float)(cs__floori(x0) + 1), 0.0f);
        for (; k < x1 && k <= width; k += 1.0f) {
            float yk = cs__clampf(on_grid(y0 + (k - x0) * dydx), ya, y1);
            int32_t c = cs__floori(xa);
            put_cell(cx, sign, c, yk - ya, (0.5f * (xa + k) - (float)c) * (yk - ya));
            xa = k;
            ya = yk;
        }
    } else if (x1 < x0) {
        float dydx = (y1 - y0) / (x1 - x0);
        float k = cs__minf((float)(-cs__floori(-x0) - 1), width);
        for (; k > x1 && k >= 0.0f; k -= 1.0f) {
            float yk = cs__clampf(on_grid(y0 + (k - x0) * dydx), ya, y1);
            put_cell(cx, sign, (int32_t)k, yk - ya, (0.5f * (xa + k) - k) * (yk - ya));
            xa = k;
            ya = yk;
        }
    }
    int32_t c = cs__floori(cs__minf(xa, x1));
    put_cell(cx, sign, c, y1 - ya, (0.5f * (xa + x1) - (float)c) * (y1 - ya));
}

/* The cut of an arc at x = x0 + r: h(t) = t (a1 + t (a2 + t a3)) - r,
 * monotone on [lo, hi] (growing if `inc`), by Newton's method from t.
 * A step s leaves (h''/2 + a3 s) s^2 of x; accepted once that is below
 * CUT_TOL px. A cut off by dx hands the bit of arc between it and the
 * true one, which lies within dx of the column edge, to the wrong
 * column: its height is at most that of the cell, and its moment about
 * either column differs from the true one by at most dx times it, so a
 * pixel moves by at most dx. A step that would leave the bracket
 * bisects it. *rd_out gets 1/h' at the last iterate (0 if none was
 * taken): the caller's guess for the next column's cut is one column's
 * Newton step from this one, which spares the chord's division. */
#define CUT_TOL (1.0f / 16384.0f)
#define CUT_MAX_ITER 24
static float cut_t(const float *a, float r, float lo, float hi, float t, bool inc, float *rd_out)
{
    *rd_out = 0.0f;
    for (int it = 0; it < CUT_MAX_ITER; it++) {
        float a3t = a[3] * t;
        float h = t * (a[1] + t * (a[2] + a3t)) - r;
        if (h == 0.0f)
            return t;
        if ((h < 0.0f) == inc)
            lo = t;
        else
            hi = t;
        float dd = 2.0f * (a[2] + 3.0f * a3t);
        float d = a[1] + t * (2.0f * a[2] + 3.0f * a3t);
        float rd = 1.0f / d, st = -h * rd, next = t + st;
        *rd_out = rd;
        if ((cs__absf(dd) + 2.0f * cs__absf(a[3] * st)) * (st * st) <= 2.0f * CUT_TOL)
            return cs__clampf(next, lo, hi);
        float c = 0.5f * dd * st * rd;
        if (c > -0.5f && c < 0.5f)
            next -= c * st;
        if (!(next > lo && next < hi))
            next = 0.5f * (lo + hi);
        t = next;
    }
    return t;
}

/*
 * An x-monotone polynomial arc given by its Bezier control points
 * (bx, by)[0..p], by[0] < by[p]. With t the arc's own parameter,
 * x - x0 = sum a_i t^i and y - y0 = sum b_i t^i, so that
 * M(t) = Int_0^t (x - x0) y' dt is a polynomial of degree 2p. The cell of
 * column c between two cuts then has moment M(t1) - M(t0) + (x0 - c)
 * (y1 - y0): one solve for t per cut and no other evaluation. An arc in
 * one column takes the moment from its control points directly.
 */
static void add_poly_arc(exact_ctx *cx, float sign, int p, const float *bx, const float *by)
{
    float x0 = bx[0], x1 = bx[p], y0 = by[0], y1 = by[p], width = (float)cx->wall;
    bool inc = x1 > x0;
    float k = inc ? cs__maxf((float)(cs__floori(x0) + 1), 0.0f)
                  : cs__minf((float)(-cs__floori(-x0) - 1), width);
    if (inc ? !(k < x1 && k <= width) : !(k > x1 && k >= 0.0f)) { /* one column */
        int32_t c = cs__floori(cs__minf(x0, x1));
        put_cell(cx, sign, c, y1 - y0, bezier_moment(p, bx, by, (float)c));
        return;
    }
    float a[4], b[4];
    a[0] = b[0] = 0.0f;
    if (p == 3) {
        a[1] = 3.0f * (bx[1] - x0);
        a[2] = 3.0f * ((bx[2] - bx[1]) - (bx[1] - x0));
        a[3] = (x1 - x0) - 3.0f * (bx[2] - bx[1]);
        b[1] = 3.0f * (by[1] - y0);
        b[2] = 3.0f * ((by[2] - by[1]) - (by[1] - y0));
        b[3] = (y1 - y0) - 3.0f * (by[2] - by[1]);
    } else {
        a[1] = 2.0f * (bx[1] - x0);
        a[2] = (x1 - bx[1]) - (bx[1] - x0);
        a[3] = 0.0f;
        b[1] = 2.0f * (by[1] - y0);
        b[2] = (y1 - by[1]) - (by[1] - y0);
        b[3] = 0.0f;
    }
    /* M = m2 t^2 + ... + m6 t^6 */
    float m2 = 0.5f * a[1] * b[1];
    float m3 = (2.0f * a[1] * b[2] + a[2] * b[1]) * (1.0f / 3.0f);
    float m4 = (3.0f * a[1] * b[3] + 2.0f * a[2] * b[2] + a[3] * b[1]) * 0.25f;
    float m5 = (3.0f * a[2] * b[3] + 2.0f * a[3] * b[2]) * 0.2f;
    float m6 = 0.5f * a[3] * b[3];
    float t = 0.0f, xa = x0, ya = y0, Ma = 0.0f, rd = 0.0f;
    for (; inc ? (k < x1 && k <= width) : (k > x1 && k >= 0.0f); k += inc ? 1.0f : -1.0f) {
        /* Newton's step from the last cut (1/x' there, a column away),
         * or the chord of what is left of the arc */
        float guess = t + (inc ? rd : -rd);
        if (!(guess > t && guess < 1.0f))
            guess = t + (1.0f - t) * ((k - xa) / (x1 - xa));
        float tk = cut_t(a, k - x0, t, 1.0f, guess, inc, &rd);
        float yk = cs__clampf(on_grid(y0 + tk * (b[1] + tk * (b[2] + tk * b[3]))), ya, y1);
        float Mk = tk * tk * (m2 + tk * (m3 + tk * (m4 + tk * (m5 + tk * m6))));
        int32_t c = cs__floori(inc ? xa : k);
        put_cell(cx, sign, c, yk - ya, (Mk - Ma) + (x0 - (float)c) * (yk - ya));
        t = tk;
        xa = k;
        ya = yk;
        Ma = Mk;
    }
    int32_t c = cs__floori(cs__minf(xa, x1));
    float M1 = m2 + (m3 + (m4 + (m5 + m6)));
    put_cell(cx, sign, c, y1 - ya, (M1 - Ma) + (x0 - (float)c) * (y1 - ya));
}

/*
 * add_poly_arc serves arcs across at most this many columns. Its
 * power-basis coefficients grow with the arc's length L in columns, so
 * the cuts and the cells' moments carry about L 2^-24 px of rounding:
 * 4e-6 px at 64 columns, well below CUT_TOL. (The limit was 8, for errors
 * of 0.5-0.8/255 on the demo's ribbons at 32 that were put down to the
 * moment polynomial; they came from heights taken as absolute y, see
 * control_points, and with heights within the row 64 and 256 columns
 * measure the same as 8.) A longer arc is cut into parts of about half as
 * many columns, at equal steps of u, each part placed by its ends like
 * any arc (add_poly_monotone).
 */
#define POLY_ARC_COLUMNS 64.0f

/* An x-monotone polynomial part from a (at ya) to b (at yb), if it is
 * short enough for add_poly_arc and its control points can be formed. */
static inline bool add_poly_part(exact_ctx *cx, const cs_segment *s, float sign, const cs_exact_end *a,
                          float ya, const cs_exact_end *b, float yb)
{
    if (!(cs__absf(b->x - a->x) <= POLY_ARC_COLUMNS))
        return false;
    float bx[4], by[4];
    int p = arc_polygon(s, a, ya, b, yb, bx, by);
    if (p < 2)
        return false;
    add_poly_arc(cx, sign, p, bx, by);
    return true;
}

/*
 * An x-monotone polynomial sub-arc too long for add_poly_part, top (y0) to
 * bottom (y1): in parts of equal u; a part still too long (x far from
 * linear in u) is cut column by column (add_monotone). The parts are
 * counted over the screen's width at most, so an arc reaching far off
 * screen costs no more than one across it: its long parts off screen go
 * to add_monotone, which passes over whole columns there.
 */
static void add_poly_parts(exact_ctx *cx, const cs_segment *s, float sign,
                           const cs_exact_end *top, float y0, const cs_exact_end *bot, float y1)
{
    float span = cs__absf(bot->x - top->x);
    int32_t n = 1;
    if (span > POLY_ARC_COLUMNS)
        n = (int32_t)(cs__minf(span, (float)cx->wall + 2.0f) * (2.0f / POLY_ARC_COLUMNS)) + 1;
    cs_exact_end a = *top, b;
    float ya = y0;
    for (int32_t i = 1; i <= n; i++) {
        float yb = y1;
        if (i < n) {
            float u = top->u + (bot->u - top->u) * ((float)i / (float)n);
            yb = cs__clampf(cs__segment_y(s, u), ya, y1);
            eval_end(s, u, yb, &b);
        } else {
            b = *bot;
        }
        if (!add_poly_part(cx, s, sign, &a, ya, &b, yb))
            add_monotone(cx, s, sign, &a, ya, &b, yb);
        a = b;
        ya = yb;
    }
}

/* An x-monotone polynomial sub-arc, whole if short enough, else in parts. */
static inline void add_poly_monotone(exact_ctx *cx, const cs_segment *s, float sign,
                                     const cs_exact_end *top, float y0, const cs_exact_end *bot,
                                     float y1)
{
    if (!add_poly_part(cx, s, sign, top, y0, bot, y1))
        add_poly_parts(cx, s, sign, top, y0, bot, y1);
}

/* An x-monotone sub-arc between two x-extrema of the arc. */
static void add_x_monotone(exact_ctx *cx, const cs_segment *s, float sign, const cs_exact_end *top,
                           float y0, const cs_exact_end *bot, float y1)
{
    if (polynomial(s))
        add_poly_monotone(cx, s, sign, top, y0, bot, y1);
    else
        add_monotone(cx, s, sign, top, y0, bot, y1);
}

/* Effective edge e over the band [ya, yb]: sign +1 where the region begins.
 * Written into the loop over a row's clusters for the common lone arc
 * (-0.7 % of a Many-blobs frame: its call was ~10 % of its cost); the
 * band sweep calls the copy below. */
static CS__HOT_INLINE void add_edge_inline(exact_ctx *cx, const cs_exact_piece *e, float sign,
                                           float ya, float yb)
{
    cs_workspace *ws = cx->ws;
    const cs_segment *s = &ws->segments[ws->pieces[e->piece].segment];
    if (e->hidden) { /* only what it adds right of its opaque pixels matters */
        int32_t c = (int32_t)e->xmin - cx->x0;
        cs__acc_cover(ws, c, sign * (yb - ya));
        touch(cx, c, c + 1);
        return;
    }
    if (e->xmax <= (float)cx->x0) { /* its cells' heights sum to the band's exactly */
        cs__acc_cover(ws, 0, sign * (yb - ya));
        touch(cx, 0, 1);
        return;
    }
    if (e->xmin >= (float)(cx->x0 + cx->width)) {
        touch(cx, cx->width, cx->width + 1);
        return;
    }
    if (s->degree == 1) {
        add_line(cx, sign, e->top.x, 0.0f, e->bot.x, yb - ya); /* heights in the band */
        return;
    }
    bool poly = polynomial(s);
    if (e->monotone && poly) {
        add_poly_monotone(cx, s, sign, &e->top, ya, &e->bot, yb);
        return;
    }
    if (e->xmax - e->xmin < 1.0f) { /* the usual case: one column, no solve */
        int32_t c = cs__floori(e->xmin);
        if (e->xmax <= (float)c + 1.0f) {
            add_cell(cx, s, sign, c, &e->top, ya, &e->bot, yb);
            return;
        }
    }
    if (e->monotone) {
        add_monotone(cx, s, sign, &e->top, ya, &e->bot, yb);
        return;
    }
    /* Cut at the x-extrema: points from the band's top to its bottom,
     * x-monotone in between. */
    float t[4];
    int nt = cs__turns(s->x, s->w, s->degree, cs__minf(e->top.u, e->bot.u),
                       cs__maxf(e->top.u, e->bot.u), t);
    bool up = e->top.u <= e->bot.u;
    cs_exact_end a = e->top, b;
    float y0 = ya;
    for (int k = 0; k < nt; k++) {
        float u = up ? t[k] : t[nt - 1 - k];
        float y = cs__clampf(cs__segment_y(s, u), y0, yb);
        eval_end(s, u, y, &b);
        add_x_monotone(cx, s, sign, &a, y0, &b, y);
        a = b;
        y0 = y;
    }
    add_x_monotone(cx, s, sign, &a, y0, &e->bot, yb);
}

static void add_edge(exact_ctx *cx, const cs_exact_piece *e, float sign, float ya, float yb)
{
    add_edge_inline(cx, e, sign, ya, yb);
}

/* Applies the fill rule along the band's arcs ord[0..m), in x order, from
 * the winding `w` (updated) met left of them. */
static bool emit_band(exact_ctx *cx, const uint32_t *ord, uint32_t m, float ya, float yb,
                      int32_t *w, bool inside)
{
    cs_workspace *ws = cx->ws;
    for (uint32_t k = 0; k < m; k++) {
        const cs_exact_piece *e = &ws->exact[ord[k]];
        const cs_piece *pc = &ws->pieces[e->piece];
        w[pc->operand] += pc->dir;
        bool now = cs__region_inside(cx->region, w);
        if (now != inside) {
            add_edge(cx, e, now ? 1.0f : -1.0f, ya, yb);
            inside = now;
        }
    }
    return inside;
}

/* Moves e's bottom to height yb, searching from its top towards the known
 * point (uref at yref) below yb. */
static void set_bot(exact_ctx *cx, cs_exact_piece *e, float ya, float yb, float uref, float yref)
{
    cs_workspace *ws = cx->ws;
    const cs_piece *pc = &ws->pieces[e->piece];
    const cs_segment *s = &ws->segments[pc->segment];
    if (e->hidden)
        return; /* it stays where it was put */
    e->row_arc = false;
    if (yb == yref) {
        place_end(s, polynomial(s), yb, uref, uref, uref, pc->dir > 0, &e->bot);
        return;
    }
    place_end(s, polynomial(s), yb, cs__minf(e->top.u, uref), cs__maxf(e->top.u, uref),
              chord_u(e->top.u, ya, uref, yref, yb), pc->dir > 0, &e->bot);
}

/*
 * The band [ya, yb] of the cluster cl[0..nc) between two consecutive ends
 * of its pieces, cut further until its order is proved; `w` is the winding
 * left of the cluster. On return every piece in it has its top at yb.
 * Returns how many pieces the band had; w_out gets the winding right of
 * them, if any.
 */
static uint32_t run_band(exact_ctx *cx, uint32_t *cl, uint32_t nc, float ya, float yb,
                         const int32_t *w, bool inside, int32_t *w_out)
{
    cs_workspace *ws = cx->ws;
    cs_exact_piece *ex = ws->exact;
    /* The band's pieces to the front of cl. */
    uint32_t m = 0;
    for (uint32_t i = 0; i < nc; i++) {
        const cs_piece *pc = &ws->pieces[ex[cl[i]].piece];
        if (row_top(cx, pc) <= ya && row_end(cx, pc) >= yb) {
            uint32_t t = cl[m];
            cl[m++] = cl[i];
            cl[i] = t;
        }
    }
    if (m == 0)
        return 0;
    for (uint32_t k = 0; k < m; k++) {
        cs_exact_piece *e = &ex[cl[k]];
        const cs_piece *pc = &ws->pieces[e->piece];
        if (!(e->row_arc && yb == row_end(cx, pc)))
            set_bot(cx, e, ya, yb, e->u_row, row_end(cx, pc));
    }
    float pending[MAX_DEPTH];
    int depth = 0;
    bool first = true;
    for (;;) {
        for (uint32_t k = 0; k < m; k++) {
            cs_exact_piece *e = &ex[cl[k]];
            if (!e->hidden) /* a stand-in keeps its place (hide) */
                hull(&ws->segments[ws->pieces[e->piece].segment], e, ya, yb, true);
        }
        sort_pieces(ex, cl, m, false);
        float cut = 0.0f;
        if (m > 1 && !band_ordered(ex, cl, m, ya, yb, &cut) && cut > ya && cut < yb &&
            depth < MAX_DEPTH) {
            if (cx->bands_left > 0) {
                cx->bands_left--;
                pending[depth++] = yb;
                for (uint32_t k = 0; k < m; k++) {
                    cs_exact_piece *e = &ex[cl[k]];
                    set_bot(cx, e, ya, cut, e->bot.u, yb);
                }
                yb = cut;
                continue;
            }
            cx->overflow = true; /* accepted unproved: a crossing may be misplaced */
        }
        int32_t wb[CS_CFG_MAX_OPERANDS];
        for (int k = 0; k < CS_CFG_MAX_OPERANDS; k++)
            wb[k] = w[k];
        emit_band(cx, cl, m, ya, yb, wb, inside);
        if (first) {
            for (int k = 0; k < CS_CFG_MAX_OPERANDS; k++)
                w_out[k] = wb[k];
            first = false;
        }
        for (uint32_t k = 0; k < m; k++) {
            ex[cl[k]].top = ex[cl[k]].bot;
            ex[cl[k]].row_arc = false;
        }
        if (depth == 0)
            break;
        ya = yb;
        yb = pending[--depth];
        for (uint32_t k = 0; k < m; k++) {
            cs_exact_piece *e = &ex[cl[k]];
            const cs_piece *pc = &ws->pieces[e->piece];
            set_bot(cx, e, ya, yb, e->u_row, row_end(cx, pc));
        }
    }
    return m;
}


/* The next height below ya (at most the row's bottom) where a piece of
 * cl[0..nc) starts or ends: the bottom of the band that starts at ya. */
static float next_cut(const exact_ctx *cx, const uint32_t *cl, uint32_t nc, float ya)
{
    const cs_workspace *ws = cx->ws;
    float yb = cx->row_bot;
    for (uint32_t i = 0; i < nc; i++) {
        const cs_piece *pc = &ws->pieces[ws->exact[cl[i]].piece];
        float t = row_top(cx, pc), b = row_end(cx, pc);
        if (t > ya && t < yb)
            yb = t;
        if (b > ya && b < yb)
            yb = b;
    }
    return yb;
}
/*
 * The pieces cl[0..nc) of one cluster, band by band down the row. No
 * curve passes between two clusters (see the loop over them in
 * cs__exact_region), so the winding to the right of this one is the same
 * at every height: any band's arcs give it.
 */
static bool run_cluster(exact_ctx *cx, uint32_t *cl, uint32_t nc, int32_t *w, bool inside)
{
    int32_t w_out[CS_CFG_MAX_OPERANDS];
    bool got = false;
    float ya = cx->row_top;
    while (ya < cx->row_bot) {
        float yb = next_cut(cx, cl, nc, ya);
        int32_t wb[CS_CFG_MAX_OPERANDS];
        if (run_band(cx, cl, nc, ya, yb, w, inside, wb) > 0 && !got) {
            for (int k = 0; k < CS_CFG_MAX_OPERANDS; k++)
                w_out[k] = wb[k];
            got = true;
        }
        ya = yb;
    }
    if (got)
        for (int k = 0; k < CS_CFG_MAX_OPERANDS; k++)
            w[k] = w_out[k];
    return cs__region_inside(cx->region, w);
}

/* A bijective mix of 32 bits (the MurmurHash3 finaliser). */
static uint32_t mix32(uint32_t v)
{
    v ^= v >> 16;
    v *= 0x85ebca6bu;
    v ^= v >> 13;
    v *= 0xc2b2ae35u;
    v ^= v >> 16;
    return v;
}

static uint32_t height_tag(float h, uint32_t operand)
{
    union {
        float f;
        uint32_t u;
    } b;
    b.f = h;
    return mix32(b.u ^ (operand * 0x9e3779b9u));
}

/*
 * Where piece pc starts or ends inside the row, the winding across its
 * cluster changes unless another piece of the cluster starts or ends at
 * the same height. Returns the sum of dir * tag(height) over its inner
 * ends (wrapping), so that a cluster whose changes all cancel sums to 0.
 */
static uint32_t end_tags(const exact_ctx *cx, const cs_piece *pc, bool *inner)
{
    uint32_t t = 0;
    if (pc->y_top > cx->row_top) {
        uint32_t v = height_tag(pc->y_top, pc->operand);
        t = pc->dir > 0 ? t + v : t - v;
        *inner = true;
    }
    if (pc->y_bot < cx->row_bot) {
        uint32_t v = height_tag(pc->y_bot, pc->operand);
        t = pc->dir > 0 ? t - v : t + v;
        *inner = true;
    }
    return t;
}

/* Whether the winding across the pieces cl[0..nc) is the same at every
 * height of the row (every band of theirs, empty ones included). */
static bool winding_constant(const exact_ctx *cx, const uint32_t *cl, uint32_t nc)
{
    const cs_workspace *ws = cx->ws;
    int32_t d0[CS_CFG_MAX_OPERANDS];
    float ya = cx->row_top;
    bool first = true;
    while (ya < cx->row_bot) {
        float yb = next_cut(cx, cl, nc, ya);
        int32_t d[CS_CFG_MAX_OPERANDS];
        for (int k = 0; k < CS_CFG_MAX_OPERANDS; k++)
            d[k] = 0;
        for (uint32_t i = 0; i < nc; i++) {
            const cs_piece *pc = &ws->pieces[ws->exact[cl[i]].piece];
            if (row_top(cx, pc) <= ya && row_end(cx, pc) >= yb)
                d[pc->operand] += pc->dir;
        }
        for (int k = 0; k < CS_CFG_MAX_OPERANDS; k++) {
            if (first)
                d0[k] = d[k];
            else if (d[k] != d0[k])
                return false;
        }
        first = false;
        ya = yb;
    }
    return true;
}

/*
 * A piece whose every possible pixel (its segment's hull) is already
 * opaque. Those pixels will show nothing of the region, so the arc need
 * not be placed: it becomes a vertical stand-in at the hull's left edge
 * pa, and as an effective edge it adds only its height, to the cover of
 * every pixel from pa on (add_edge). Pixels right of the opaque stretch
 * get the same total; the stand-in changes the x order only within the
 * stretch, and the fill rule's effective edges there sum to the same
 * change of "inside" across it whatever their order. A cluster holds
 * stand-ins and real arcs only where their hulls are apart, so their
 * order is right. The only difference right of the stretch is the order
 * in which the cover deltas are summed: a last-bit one at most.
 */
static void hide(cs_exact_piece *e, cs_index piece, const cs_piece *pc, int32_t pa)
{
    float ut = top_u(pc), ub = bot_u(pc);
    cs_exact_end at;
    e->piece = piece;
    e->row_arc = true;
    at.u = ut;
    at.x = (float)pa;
    at.dx = at.dy = at.dwr = 0.0f;
    at.w = 1.0f;
    e->top = at;
    at.u = ub;
    e->bot = at;
    e->u_row = ub;
    e->dmin = e->dmax = 0.0f;
    e->xmin = e->xmax = (float)pa;
    e->key = 2.0f * (float)pa;
    e->monotone = true;
}

cs_status cs__exact_region(cs_renderer *r, const cs_region *region, const cs_index *act,
                           uint32_t n, int y, int32_t *lo, int32_t *hi)
{
    if (n > CS_CFG_MAX_CROSSINGS)
        return CS_ERR_CAP_CROSSINGS;
    cs_workspace *ws = r->ws;
    exact_ctx cx;
    cx.ws = ws;
    cx.region = region;
    cx.row_top = (float)y;
    cx.row_bot = (float)(y + 1);
    cx.x0 = r->vx;
    cx.width = r->vw;
    cx.wall = r->opts.width;
    cx.lo = INT32_MAX;
    cx.hi = INT32_MIN;
    cx.bands_left = CS_CFG_EXACT_MAX_BANDS;
    cx.overflow = false;
    cs_exact_piece *ex = ws->exact;
    uint32_t *ord = ws->exact_order;
    /* Each piece's arc across the row, and its bounds. */
    for (uint32_t i = 0; i < n; i++) {
        cs_exact_piece *e = &ex[i];
        const cs_piece *pc = &ws->pieces[act[i]];
        const cs_segment *s = &ws->segments[pc->segment];
        int32_t pa = s->px_lo, pb = s->px_hi;
        e->hidden = pa < pb && cs__span_opaque(r, (uint32_t)pa, (uint32_t)pb);
        if (e->hidden) {
            hide(e, act[i], pc, pa + r->vx); /* in device columns, as placed arcs */
        } else {
            place_arc(&cx, e, act[i]);
            /* Its pixels on this row (its hull, widened as the segment's
             * is) may all be opaque though the segment's are not: then it
             * is a stand-in too, spared its area (14% of Many-blobs' arcs).
             * The pixel of its top end, one bit, rules most arcs out. */
            float x0 = (float)r->vx; /* arcs are in device columns, the line's bits in its own */
            float xt = e->top.x - x0;
            if (r->opaque_px != 0u && xt >= 0.0f && xt < (float)cx.width &&
                cs__run_opaque(r, (uint32_t)xt)) {
                /* clamped as floats first: a hull that could not be formed is +-HUGE_X */
                float xl = cs__maxf(e->xmin - 0.5f - x0, 0.0f);
                float xr = cs__minf(e->xmax + 0.5f - x0, (float)cx.width);
                int32_t qa = cs__floori(xl), qb = cs__floori(xr) + 1;
                qb = qb > cx.width ? cx.width : qb;
                if (qa < qb && cs__span_opaque(r, (uint32_t)qa, (uint32_t)qb)) {
                    e->hidden = true;
                    hide(e, act[i], pc, qa + r->vx);
                }
            }
        }
        ord[i] = i;
    }
    /*
     * Clusters: runs of pieces in xmin order whose x ranges overlap, so
     * that no curve passes between two of them. A horizontal segment has
     * no piece, yet joins the ends of two that may lie far apart; a
     * cluster whose winding changes inside the row (found by its end tags,
     * and confirmed band by band) therefore takes in the next one until
     * the changes cancel. The whole row always qualifies.
     */
    sort_pieces(ex, ord, n, true);
    int32_t w[CS_CFG_MAX_OPERANDS];
    for (int k = 0; k < CS_CFG_MAX_OPERANDS; k++) /* a loop: `= {0}` may call memset */
        w[k] = 0;
    bool inside = false;
    for (uint32_t i = 0; i < n;) {
        float reach = ex[ord[i]].xmax;
        uint32_t j = i, tags = 0;
        bool inner = false;
        for (;;) {
            reach = cs__maxf(reach, ex[ord[j]].xmax);
            tags += end_tags(&cx, &ws->pieces[ex[ord[j]].piece], &inner);
            j++;
            if (j == n)
                break;
            if (ex[ord[j]].xmin <= reach + CLUSTER_GAP)
                continue;
            if (!inner || (tags == 0 && winding_constant(&cx, &ord[i], j - i)))
                break;
        }
        if (j == i + 1) { /* alone: one band, nothing to order */
            const cs_exact_piece *e = &ex[ord[i]];
            const cs_piece *pc = &ws->pieces[e->piece];
            w[pc->operand] += pc->dir;
            bool now = cs__region_inside(region, w);
            if (now != inside) {
                add_edge_inline(&cx, e, now ? 1.0f : -1.0f, row_top(&cx, pc), row_end(&cx, pc));
                inside = now;
            }
        } else {
            inside = run_cluster(&cx, &ord[i], j - i, w, inside);
        }
        i = j;
    }
    if (cx.lo < *lo)
        *lo = cx.lo;
    if (cx.hi > *hi)
        *hi = cx.hi;
    return cx.overflow ? CS_ERR_CAP_CROSSINGS : CS_OK;
}

#endif /* CS_CFG_EXACT */
