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
 * 1. Bands. The row is cut at every y_top / y_bot of the region's active
 *    y-monotone pieces. Between two cuts (a band) the set of pieces is
 *    fixed, and each piece is one arc from u_top to u_bot.
 *
 * 2. Order. If no two arcs cross inside a band, their left-to-right order
 *    is the same at every height of it, and the fill rule can be applied
 *    once per band instead of once per sample. That the order holds is
 *    proved, not sampled: each arc is converted to Bernstein form over its
 *    band, and since weights are positive the arc lies in the convex hull
 *    of its control points, so within a strip [dmin, dmax] around its
 *    chord. Walking the arcs in chord order, an arc whose strip may reach
 *    left of the strips before it (the test is linear in y, so checking
 *    both band ends is enough) may cross them; the band is then cut where
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
 *    it adds (y1-y0) - Int (x - c) dy. That integral is Int (x(u) - c) y'(u)
 *    du, by Gauss-Legendre: 3 nodes are exact for polynomial segments
 *    (integrand of degree <= 5); rational ones use 5 nodes per panel, with
 *    panels cut until W varies little enough on each that the error is
 *    about 1e-6 of the value (see arc_moment). Straight pieces use the
 *    exact trapezoid and find their integer-x cuts by interpolation. The
 *    common case, an arc whose control polygon stays in one column, needs
 *    no solve beyond the two that place it in its band.
 *
 *    As in the sub-scanline code the region is outside far to the left;
 *    an edge left of the screen adds its height to every pixel, and one
 *    right of it adds nothing.
 *
 * The result lands in the same area/cover accumulators the sub-scanline
 * code uses, so render_region's fold, the within-cel coverage budget and
 * the compositing are shared by every AA mode. Line state is the region's
 * active pieces plus the O(width) accumulators; memory is fixed.
 */
#include "cs_internal.h"

#if CS_CFG_EXACT /* the whole file: see cs_config.h */

/* Area (px^2) by which a crossing hidden in an accepted band could be wrong. */
#define BAND_TOL (1.0f / 32768.0f)
/* Pending band cuts of one band; deeper cuts are not attempted. */
#define MAX_DEPTH 40
/* Stands for "no bound": a hull that could not be formed. */
#define HUGE_X 1.0e30f

typedef struct exact_ctx {
    cs_workspace *ws;
    const cs_region *region;
    uint32_t n;          /* ws->exact[0..n): the region's active pieces */
    int32_t width;
    int32_t lo, hi;      /* accumulator entries written: [lo, hi) */
    uint32_t bands_left; /* CS_CFG_EXACT_MAX_BANDS countdown */
    bool overflow;
} exact_ctx;

static float seg_x(const cs_segment *s, float u)
{
    return cs__poly_eval(s->x, s->degree, u) / cs__poly_eval(s->w, s->degree, u);
}

static float seg_y(const cs_segment *s, float u)
{
    return cs__poly_eval(s->y, s->degree, u) / cs__poly_eval(s->w, s->degree, u);
}

static float top_u(const cs_piece *pc) { return pc->dir > 0 ? pc->u0 : pc->u1; }
static float bot_u(const cs_piece *pc) { return pc->dir > 0 ? pc->u1 : pc->u0; }

/* u where piece pc is at height yv, searched between a and b. The ends
 * are taken as they are: their y values are the ones shared exactly with
 * the neighbouring pieces. */
static float level_u(const cs_segment *s, const cs_piece *pc, float yv, float a, float b)
{
    if (yv == pc->y_top)
        return top_u(pc);
    if (yv == pc->y_bot)
        return bot_u(pc);
    return cs__solve_level(s->y, s->w, s->degree, yv, cs__minf(a, b), cs__maxf(a, b));
}

static void set_top(cs_workspace *ws, cs_exact_piece *e, float yv)
{
    const cs_piece *pc = &ws->pieces[e->piece];
    const cs_segment *s = &ws->segments[pc->segment];
    e->u_top = level_u(s, pc, yv, pc->u0, pc->u1);
    e->x_top = seg_x(s, e->u_top);
}

/* `narrow`: the bottom moves up from its current place, so search above it. */
static void set_bot(cs_workspace *ws, cs_exact_piece *e, float yv, bool narrow)
{
    const cs_piece *pc = &ws->pieces[e->piece];
    const cs_segment *s = &ws->segments[pc->segment];
    e->u_bot = level_u(s, pc, yv, e->u_top, narrow ? e->u_bot : bot_u(pc));
    e->x_bot = seg_x(s, e->u_bot);
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
 * Bounds of the arc of e over the band [ya, yb]: its strip around the
 * chord, its x range and whether it is x-monotone (variation diminishing:
 * a control polygon monotone in x makes the curve so).
 */
static void hull(cs_workspace *ws, cs_exact_piece *e, float ya, float yb)
{
    const cs_segment *s = &ws->segments[ws->pieces[e->piece].segment];
    int p = s->degree;
    float x0 = e->x_top, x1 = e->x_bot;
    e->key = x0 + x1;
    e->dmin = e->dmax = 0.0f;
    e->xmin = cs__minf(x0, x1);
    e->xmax = cs__maxf(x0, x1);
    e->monotone = true;
    if (p == 1)
        return; /* a straight line, whatever its weights */
    float a = cs__minf(e->u_top, e->u_bot), h = cs__absf(e->u_bot - e->u_top);
    float bx[4], by[4], bw[4];
    bernstein(s->x, p, a, h, bx);
    bernstein(s->y, p, a, h, by);
    bernstein(s->w, p, a, h, bw);
    bool from_top = e->u_top <= e->u_bot;
    float slope = (x1 - x0) / (yb - ya);
    float prev = x0;
    int sense = 0;
    /* The end control points are the arc's ends, x_top and x_bot: their d
     * is 0 by definition, which keeps rounding out of touching vertices. */
    for (int j = 1; j <= p; j++) {
        float px;
        if (j < p) {
            int jj = from_top ? j : p - j;
            if (!(bw[jj] > 0.0f)) { /* cannot happen for positive weights */
                e->dmin = e->xmin = -HUGE_X;
                e->dmax = e->xmax = HUGE_X;
                e->monotone = false;
                return;
            }
            px = bx[jj] / bw[jj];
            float d = px - (x0 + (by[jj] / bw[jj] - ya) * slope);
            e->dmin = cs__minf(e->dmin, d);
            e->dmax = cs__maxf(e->dmax, d);
            e->xmin = cs__minf(e->xmin, px);
            e->xmax = cs__maxf(e->xmax, px);
        } else {
            px = x1;
        }
        int step = px > prev ? 1 : (px < prev ? -1 : 0);
        if (step != 0) {
            if (sense != 0 && step != sense)
                e->monotone = false;
            sense = step;
        }
        prev = px;
    }
}

/* Shell sort of the band's pieces by key; they arrive nearly sorted. */
static void sort_by_key(const cs_exact_piece *ex, uint32_t *ord, uint32_t m)
{
    static const uint32_t gaps[] = {57, 23, 10, 4, 1};
    for (unsigned g = 0; g < sizeof gaps / sizeof gaps[0]; g++) {
        uint32_t gap = gaps[g];
        for (uint32_t i = gap; i < m; i++) {
            uint32_t t = ord[i];
            float kt = ex[t].key;
            uint32_t j = i;
            while (j >= gap && ex[ord[j - gap]].key > kt) {
                ord[j] = ord[j - gap];
                j -= gap;
            }
            ord[j] = t;
        }
    }
}

/*
 * Whether the order by key provably holds over [ya, yb], up to BAND_TOL.
 * If not, *cut is where to split the band.
 */
static bool band_ordered(const cs_workspace *ws, uint32_t m, float ya, float yb, float *cut)
{
    const cs_exact_piece *ex = ws->exact;
    const uint32_t *ord = ws->exact_order;
    float reach_top = -HUGE_X, reach_bot = -HUGE_X, overlap = 0.0f;
    uint32_t first = 0;
    for (uint32_t k = 0; k < m; k++) {
        const cs_exact_piece *e = &ex[ord[k]];
        float g = cs__maxf(reach_top - (e->x_top + e->dmin), reach_bot - (e->x_bot + e->dmin));
        if (g > 0.0f) {
            if (overlap == 0.0f)
                first = k;
            overlap += g;
        }
        reach_top = cs__maxf(reach_top, e->x_top + e->dmax);
        reach_bot = cs__maxf(reach_bot, e->x_bot + e->dmax);
    }
    float h = yb - ya;
    if (!(overlap * h > BAND_TOL))
        return true;
    float t = 0.5f;
    if (first > 0) {
        const cs_exact_piece *p = &ex[ord[first - 1]], *q = &ex[ord[first]];
        float dt = q->x_top - p->x_top, db = q->x_bot - p->x_bot;
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

/* Gauss-Legendre sum of (x(u) - c) y'(u) over [a, b], with `nodes` nodes. */
static float gauss(const cs_segment *s, const float *dy, const float *dw, int nodes, float a,
                   float b, float c)
{
    int p = s->degree;
    const float *nt = nodes == 5 ? gl5_t : gl3_t, *nw = nodes == 5 ? gl5_w : gl3_w;
    float mid = 0.5f * (a + b), half = 0.5f * (b - a), sum = 0.0f;
    for (int k = 0; k < nodes; k++) {
        float u = mid + half * nt[k];
        float W = cs__poly_eval(s->w, p, u);
        float Y = cs__poly_eval(s->y, p, u);
        float xr = cs__poly_eval(s->x, p, u) / W - c;
        float yd = (cs__poly_eval(dy, p - 1, u) * W - Y * cs__poly_eval(dw, p - 1, u)) / (W * W);
        sum += nw[k] * (xr * yd);
    }
    return half * sum;
}

/*
 * Int (x - c) dy along the arc from u0 to u1 (its sign follows y).
 *
 * The integrand is X (Y'W - YW') / W^3. With W constant it is a polynomial
 * of degree <= 5 and 3 nodes are exact. Otherwise its poles are the zeros
 * of W, which strong weights can put just outside the arc (weight 0.2
 * next to 3.6 puts one 3% of the arc's length away, and 5 nodes then miss
 * by 6%). So the arc is cut into panels on which W's Bernstein
 * coefficients stay within a ratio of WEIGHT_SPREAD: W then has no zero
 * inside the Bernstein ellipse of rho ~ 3.9 around the panel, and 5 nodes
 * are good to about rho^-10 ~ 1e-6 of the panel's value. Arcs of conics
 * and mild weights pass as a single panel.
 */
#define WEIGHT_SPREAD 1.25f
#define MAX_PANEL_DEPTH 12
static float arc_moment(const cs_segment *s, float u0, float u1, float c)
{
    int p = s->degree;
    float dy[3] = {0.0f, 0.0f, 0.0f}, dw[3] = {0.0f, 0.0f, 0.0f};
    for (int i = 1; i <= p; i++) {
        dy[i - 1] = (float)i * s->y[i];
        dw[i - 1] = (float)i * s->w[i];
    }
    if (s->w[1] == 0.0f && s->w[2] == 0.0f && s->w[3] == 0.0f)
        return gauss(s, dy, dw, 3, u0, u1, c);
    /* Panels depth first, left to right, so the sum's order is fixed. */
    float lo[MAX_PANEL_DEPTH + 1], hi[MAX_PANEL_DEPTH + 1];
    int depth[MAX_PANEL_DEPTH + 1], top = 0;
    lo[0] = u0;
    hi[0] = u1;
    depth[0] = 0;
    float sum = 0.0f;
    while (top >= 0) {
        float a = lo[top], b = hi[top];
        int d = depth[top--];
        if (d < MAX_PANEL_DEPTH) {
            float bw[4];
            bernstein(s->w, p, cs__minf(a, b), cs__absf(b - a), bw);
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
        }
        sum += gauss(s, dy, dw, 5, a, b, c);
    }
    return sum;
}

/* Sub-arc u0..u1 (y0 < y1) lying in column c: the part of the column right
 * of it is inside (sign +1) or outside (-1) from here on. */
static void add_cell(exact_ctx *cx, const cs_segment *s, float sign, int32_t c, float u0, float x0,
                     float y0, float u1, float x1, float y1)
{
    float dy = y1 - y0;
    if (!(dy > 0.0f))
        return;
    cs_workspace *ws = cx->ws;
    if (c < 0) { /* left of the screen: all of it is to the right */
        cs__acc_cover(ws, 0, sign * dy);
        touch(cx, 0, 1);
        return;
    }
    if (c >= cx->width) {
        touch(cx, cx->width, cx->width + 1);
        return;
    }
    float fc = (float)c;
    float m = s->degree == 1 ? (0.5f * (x0 + x1) - fc) * dy : arc_moment(s, u0, u1, fc);
    m = cs__clampf(m, 0.0f, dy);
    cs__acc_area(ws, c, sign * (dy - m));
    cs__acc_cover(ws, c + 1, sign * dy);
    touch(cx, c, c + 2);
}

/* An x-monotone sub-arc, top (y0) to bottom (y1): cut at integer x. Only
 * cuts inside [0, width] matter; beyond them whole columns do not. */
static void add_monotone(exact_ctx *cx, const cs_segment *s, float sign, float u0, float x0,
                         float y0, float u1, float x1, float y1)
{
    float width = (float)cx->width;
    float ulo = cs__minf(u0, u1), uhi = cs__maxf(u0, u1);
    /* A straight piece needs no solve: y is linear in x along it. */
    bool line = s->degree == 1;
    float ys = y0, dydx = line && x1 != x0 ? (y1 - y0) / (x1 - x0) : 0.0f, xs = x0;
    if (x1 > x0) {
        float k = (float)(cs__floori(x0) + 1);
        for (k = cs__maxf(k, 0.0f); k < x1 && k <= width; k += 1.0f) {
            float uk = line ? 0.0f : cs__solve_level(s->x, s->w, s->degree, k, ulo, uhi);
            float yk = cs__clampf(line ? ys + (k - xs) * dydx : seg_y(s, uk), y0, y1);
            add_cell(cx, s, sign, cs__floori(x0), u0, x0, y0, uk, k, yk);
            u0 = uk;
            x0 = k;
            y0 = yk;
        }
    } else if (x1 < x0) {
        float k = (float)(-cs__floori(-x0) - 1);
        for (k = cs__minf(k, width); k > x1 && k >= 0.0f; k -= 1.0f) {
            float uk = line ? 0.0f : cs__solve_level(s->x, s->w, s->degree, k, ulo, uhi);
            float yk = cs__clampf(line ? ys + (k - xs) * dydx : seg_y(s, uk), y0, y1);
            add_cell(cx, s, sign, cs__floori(k), u0, x0, y0, uk, k, yk);
            u0 = uk;
            x0 = k;
            y0 = yk;
        }
    }
    add_cell(cx, s, sign, cs__floori(cs__minf(x0, x1)), u0, x0, y0, u1, x1, y1);
}

/* Effective edge e over the band [ya, yb]: sign +1 where the region begins. */
static void add_edge(exact_ctx *cx, const cs_exact_piece *e, float sign, float ya, float yb)
{
    cs_workspace *ws = cx->ws;
    const cs_segment *s = &ws->segments[ws->pieces[e->piece].segment];
    if (e->xmax <= 0.0f) {
        cs__acc_cover(ws, 0, sign * (yb - ya));
        touch(cx, 0, 1);
        return;
    }
    if (e->xmin >= (float)cx->width) {
        touch(cx, cx->width, cx->width + 1);
        return;
    }
    if (e->xmax - e->xmin < 1.0f) { /* the usual case: one column, no solve */
        int32_t c = cs__floori(e->xmin);
        if (e->xmax <= (float)c + 1.0f) {
            add_cell(cx, s, sign, c, e->u_top, e->x_top, ya, e->u_bot, e->x_bot, yb);
            return;
        }
    }
    /* Points from the band's top to its bottom, x-monotone in between. */
    float pu[6], px[6], py[6];
    int np = 0;
    pu[np] = e->u_top;
    px[np] = e->x_top;
    py[np++] = ya;
    if (!e->monotone) {
        float t[4];
        int nt = cs__turns(s->x, s->w, s->degree, cs__minf(e->u_top, e->u_bot),
                           cs__maxf(e->u_top, e->u_bot), t);
        bool up = e->u_top <= e->u_bot;
        for (int k = 0; k < nt; k++) {
            float u = up ? t[k] : t[nt - 1 - k];
            pu[np] = u;
            px[np] = seg_x(s, u);
            py[np] = cs__clampf(seg_y(s, u), py[np - 1], yb);
            np++;
        }
    }
    pu[np] = e->u_bot;
    px[np] = e->x_bot;
    py[np++] = yb;
    for (int k = 0; k + 1 < np; k++)
        add_monotone(cx, s, sign, pu[k], px[k], py[k], pu[k + 1], px[k + 1], py[k + 1]);
}

/* Applies the fill rule along the band's arcs, in x order. */
static void emit_band(exact_ctx *cx, uint32_t m, float ya, float yb)
{
    cs_workspace *ws = cx->ws;
    int32_t winding[CS_CFG_MAX_OPERANDS];
    for (int k = 0; k < CS_CFG_MAX_OPERANDS; k++) /* a loop: `= {0}` may call memset */
        winding[k] = 0;
    bool inside = false;
    for (uint32_t k = 0; k < m; k++) {
        const cs_exact_piece *e = &ws->exact[ws->exact_order[k]];
        const cs_piece *pc = &ws->pieces[e->piece];
        winding[pc->operand] += pc->dir;
        bool now = cs__region_inside(cx->region, winding);
        if (now != inside) {
            add_edge(cx, e, now ? 1.0f : -1.0f, ya, yb);
            inside = now;
        }
    }
}

/* The band [ya, yb] between two consecutive piece ends, cut further until
 * its order is proved. On return every piece in it has its top at yb. */
static void run_band(exact_ctx *cx, float ya, float yb)
{
    cs_workspace *ws = cx->ws;
    cs_exact_piece *ex = ws->exact;
    uint32_t *ord = ws->exact_order;
    uint32_t m = 0;
    for (uint32_t i = 0; i < cx->n; i++) {
        const cs_piece *pc = &ws->pieces[ex[i].piece];
        if (pc->y_top <= ya && pc->y_bot >= yb)
            ord[m++] = i;
    }
    if (m == 0)
        return;
    for (uint32_t k = 0; k < m; k++)
        set_bot(ws, &ex[ord[k]], yb, false);
    float pending[MAX_DEPTH];
    int depth = 0;
    for (;;) {
        for (uint32_t k = 0; k < m; k++)
            hull(ws, &ex[ord[k]], ya, yb);
        sort_by_key(ex, ord, m);
        float cut = 0.0f;
        if (m > 1 && !band_ordered(ws, m, ya, yb, &cut) && cut > ya && cut < yb &&
            depth < MAX_DEPTH) {
            if (cx->bands_left > 0) {
                cx->bands_left--;
                pending[depth++] = yb;
                yb = cut;
                for (uint32_t k = 0; k < m; k++)
                    set_bot(ws, &ex[ord[k]], yb, true);
                continue;
            }
            cx->overflow = true; /* accepted unproved: a crossing may be misplaced */
        }
        emit_band(cx, m, ya, yb);
        for (uint32_t k = 0; k < m; k++) {
            ex[ord[k]].u_top = ex[ord[k]].u_bot;
            ex[ord[k]].x_top = ex[ord[k]].x_bot;
        }
        if (depth == 0)
            break;
        ya = yb;
        yb = pending[--depth];
        for (uint32_t k = 0; k < m; k++)
            set_bot(ws, &ex[ord[k]], yb, false);
    }
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
    cx.n = n;
    cx.width = r->opts.width;
    cx.lo = INT32_MAX;
    cx.hi = INT32_MIN;
    cx.bands_left = CS_CFG_EXACT_MAX_BANDS;
    cx.overflow = false;
    float ya = (float)y, row_bot = (float)(y + 1);
    for (uint32_t i = 0; i < n; i++) {
        ws->exact[i].piece = act[i];
        if (ws->pieces[act[i]].y_top <= ya)
            set_top(ws, &ws->exact[i], ya);
    }
    while (ya < row_bot) {
        float yb = row_bot;
        for (uint32_t i = 0; i < n; i++) {
            const cs_piece *pc = &ws->pieces[act[i]];
            if (pc->y_top > ya && pc->y_top < yb)
                yb = pc->y_top;
            if (pc->y_bot > ya && pc->y_bot < yb)
                yb = pc->y_bot;
        }
        run_band(&cx, ya, yb);
        ya = yb;
        for (uint32_t i = 0; i < n; i++)
            if (ws->pieces[act[i]].y_top == ya)
                set_top(ws, &ws->exact[i], ya);
    }
    if (cx.lo < *lo)
        *lo = cx.lo;
    if (cx.hi > *hi)
        *hi = cx.hi;
    return cx.overflow ? CS_ERR_CAP_CROSSINGS : CS_OK;
}

#endif /* CS_CFG_EXACT */
