/*
 * cs_exact_area.c - the area for exact-area anti-aliasing (stage 4 of
 * cs_exact.c): an effective edge over a proved band adds, FreeType-style,
 * the part of each pixel it passes through that lies to its right to
 * `area`, and its height to `cover`. Arcs are cut at x-extrema and whole
 * columns; polynomial ones integrate in closed form from their Bezier
 * control points (add_poly_arc), rational ones by Gauss-Legendre panels
 * (rational_moment), straight ones as exact trapezoids (add_line).
 */
#include "cs_exact_internal.h"

#if CS_CFG_EXACT /* the whole file: see cs_config.h */

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
static inline int polygon_ends(int k, const cs_exact_end *a, float ya, const cs_exact_end *b,
                               float yb, float *bx, float *by)
{
    if (k <= 0)
        return 0;
    bx[0] = a->x;
    by[0] = 0.0f;
    bx[k + 1] = b->x;
    by[k + 1] = yb - ya;
    return k + 1;
}
static inline int arc_polygon(const cs_segment *s, const cs_exact_end *a, float ya,
                              const cs_exact_end *b, float yb, float *bx, float *by)
{
    int k = cs__exact_control_points(s, a, ya, b, yb, &bx[1], &by[1]);
    return polygon_ends(k, a, ya, b, yb, bx, by);
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

/*
 * Adds a cell's area to entry c and its height to the cover of entry
 * c + 1, as cs__acc_area and cs__acc_cover would, with both entries'
 * touched bits set by one 64-bit OR on x86-64 (little-endian, unaligned
 * access allowed): two read-modify-writes of the bit words were ~10
 * instructions a cell. c + 1 is at most the window's width, so the two
 * words read lie within touched (checked below for the largest width).
 */
#if defined(__x86_64__)
typedef uint64_t touch_pair __attribute__((may_alias, aligned(4)));
typedef char cs__exact_touch_fits_[(CS_CFG_MAX_WIDTH - 1) / 32 + 1 <
                                           (CS_CFG_MAX_WIDTH + 2 + 31) / 32
                                       ? 1
                                       : -1];
static inline void acc_cell(cs_workspace *ws, int32_t c, float area, float cover)
{
    uint32_t u = (uint32_t)c;
    ws->area[u] += area;
    ws->cover[u + 1u] += cover;
    *(touch_pair *)&ws->touched[u >> 5] |= (uint64_t)3u << (u & 31u);
}
#else
static inline void acc_cell(cs_workspace *ws, int32_t c, float area, float cover)
{
    cs__acc_area(ws, c, area);
    cs__acc_cover(ws, c + 1, cover);
}
#endif

/* A cell of an edge: height dy of it in device column c, whose part right
 * of the edge has area dy - m. Edges are cut at the columns of the whole
 * output, viewport or not, so that every cell of the window has the bits
 * the whole render gives it; the cells left of the window only add their
 * heights (multiples of 2^-20, so the sums are exact in any grouping). */
static inline void put_cell(cs__exact_ctx *cx, float sign, int32_t c, float dy, float m)
{
    if (!(dy > 0.0f))
        return;
    cs_workspace *ws = cx->ws;
    c -= cx->x0;
    if (c < 0) { /* left of the screen: all of it is to the right */
        cs__acc_cover(ws, 0, sign * dy);
        cs__exact_touch(cx, 0, 1);
        return;
    }
    if (c >= cx->width) {
        cs__exact_touch(cx, cx->width, cx->width + 1);
        return;
    }
    m = cs__clampf(m, 0.0f, dy);
    acc_cell(ws, c, sign * (dy - m), sign * dy);
    cs__exact_touch(cx, c, c + 2);
}

/* Sub-arc a..b (y0 < y1) lying in column c: the part of the column right
 * of it is inside (sign +1) or outside (-1) from here on. */
static void add_cell(cs__exact_ctx *cx, const cs_segment *s, float sign, int32_t c,
                     const cs_exact_end *a, float y0, const cs_exact_end *b, float y1)
{
    float dy = y1 - y0;
    if (!(dy > 0.0f) || c < cx->x0 || c - cx->x0 >= cx->width) { /* no moment needed */
        put_cell(cx, sign, c, dy, 0.0f);
        return;
    }
    float fc = (float)c, m;
    if (cs__exact_polynomial(s))
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
    cs__exact_eval_end(s, u, y, out);
    out->x = k;
    *y_out = y;
}

/* An x-monotone curved sub-arc, top (y0) to bottom (y1): cut at integer x
 * (straight ones go to add_line). Only cuts inside [0, width] matter;
 * beyond them whole columns do not. */
static void add_monotone(cs__exact_ctx *cx, const cs_segment *s, float sign,
                         const cs_exact_end *top,
                         float y0, const cs_exact_end *bot, float y1)
{
    float width = cx->wall_x;
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
static void add_line(cs__exact_ctx *cx, float sign, float x0, float y0, float x1, float y1)
{
    float width = cx->wall_x, xa = x0, ya = y0;
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

/*
 * A select by the sign of h, written as one: neg_mask(h) is h < 0 as a
 * lane mask, pick(m, a, b) is m ? a : b. With AVX they are vcmpltss and
 * vblendvps in asm, which the compiler keeps as selects; as C, the
 * profile-guided v3 build turned even the selects of bools into a branch
 * on the data. Elsewhere the plain C (the same values: a select is exact).
 */
#if defined(__GNUC__) && defined(__AVX__)
static inline float neg_mask(float h)
{
    float m;
    __asm__("vcmpltss %2, %1, %0" : "=x"(m) : "x"(h), "x"(0.0f));
    return m;
}
static inline float pick(float m, float a, float b)
{
    float r;
    __asm__("vblendvps %1, %2, %3, %0" : "=x"(r) : "x"(m), "x"(a), "x"(b));
    return r;
}
#else
static inline float neg_mask(float h)
{
    return h < 0.0f ? 1.0f : 0.0f;
}
static inline float pick(float m, float a, float b)
{
    return m != 0.0f ? a : b;
}
#endif

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
        /* t's side of the root narrows the bracket: by the data, so as
         * selects rather than a branch (13 k mispredicts a Many-blobs
         * exact frame as one) */
        float neg = neg_mask(h);
        lo = pick(neg, inc ? t : lo, inc ? lo : t);
        hi = pick(neg, inc ? hi : t, inc ? t : hi);
        float dd = 2.0f * (a[2] + 3.0f * a3t);
        float d = a[1] + t * (2.0f * a[2] + 3.0f * a3t);
        float rd = 1.0f / d, st = -h * rd, next = t + st;
        *rd_out = rd;
        if ((cs__exact_mag(dd) + 2.0f * cs__exact_mag(a[3] * st)) * (st * st) <= 2.0f * CUT_TOL)
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
static CS__HOT_INLINE void add_poly_arc_dir(cs__exact_ctx *cx, float sign, int p, const float *bx,
                                            const float *by, bool inc)
{
    float x0 = bx[0], x1 = bx[p], y0 = by[0], y1 = by[p], width = cx->wall_x;
    float k = inc ? cs__maxf((float)(cs__floori(x0) + 1), 0.0f)
                  : cs__minf((float)(-cs__floori(-x0) - 1), width);
    /* One column: that of the lesser x, x0 rising (inc is x1 > x0, see
     * add_poly_arc) and else x1. As cs__minf(x0, x1), asm the compiler
     * cannot see through, it was a min and a second floor. */
    if (inc ? !(k < x1 && k <= width) : !(k > x1 && k >= 0.0f)) { /* one column */
        int32_t c = cs__floori(inc ? x0 : x1);
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
    /* The cell's column as a float: a whole number, so its int is the
     * column and it is the column's float (floori and the conversion back
     * per cell before). Rising, the first is x0's column and then each
     * cut's; falling, the cut's. */
    float fa = (float)cs__floori(x0);
    for (; inc ? (k < x1 && k <= width) : (k > x1 && k >= 0.0f); k += inc ? 1.0f : -1.0f) {
        /* Newton's step from the last cut (1/x' there, a column away),
         * or the chord of what is left of the arc */
        float guess = t + (inc ? rd : -rd);
        if (!(guess > t && guess < 1.0f))
            guess = t + (1.0f - t) * ((k - xa) / (x1 - xa));
        float tk = cut_t(a, k - x0, t, 1.0f, guess, inc, &rd);
        float yk = cs__clampf(on_grid(y0 + tk * (b[1] + tk * (b[2] + tk * b[3]))), ya, y1);
        float Mk = tk * tk * (m2 + tk * (m3 + tk * (m4 + tk * (m5 + tk * m6))));
        float fc = inc ? fa : k;
        put_cell(cx, sign, (int32_t)fc, yk - ya, (Mk - Ma) + (x0 - fc) * (yk - ya));
        t = tk;
        xa = k;
        fa = k;
        ya = yk;
        Ma = Mk;
    }
    int32_t c = cs__floori(cs__minf(xa, x1));
    float M1 = m2 + (m3 + (m4 + (m5 + m6)));
    put_cell(cx, sign, c, y1 - ya, (M1 - Ma) + (x0 - (float)c) * (y1 - ya));
}

/* add_poly_arc_dir once for each direction of x, so that neither copy
 * tests the direction in its loop. */
static void add_poly_arc(cs__exact_ctx *cx, float sign, int p, const float *bx, const float *by)
{
    /* The fields put_cell reads and writes, in a local: acc_cell's store
     * of the touched bits (may_alias) could be to *cx as far as the
     * compiler knows, so it reloaded them all, and stored lo and hi, cell
     * by cell. The rest of lc is never read. */
    cs__exact_ctx lc;
    lc.ws = cx->ws;
    lc.x0 = cx->x0;
    lc.width = cx->width;
    lc.wall_x = cx->wall_x;
    lc.lo = cx->lo;
    lc.hi = cx->hi;
    if (bx[p] > bx[0])
        add_poly_arc_dir(&lc, sign, p, bx, by, true);
    else
        add_poly_arc_dir(&lc, sign, p, bx, by, false);
    cx->lo = lc.lo;
    cx->hi = lc.hi;
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
static inline bool add_poly_part(cs__exact_ctx *cx, const cs_segment *s, float sign,
                                 const cs_exact_end *a,
                          float ya, const cs_exact_end *b, float yb)
{
    if (!(cs__exact_mag(b->x - a->x) <= POLY_ARC_COLUMNS))
        return false;
    float bx[4], by[4]; /* a polynomial segment of degree 2 or 3: its polygon always forms */
    int p = polygon_ends(cs__exact_poly_points(s->degree, a, ya, b, yb, &bx[1], &by[1]), a, ya, b,
                         yb, bx, by);
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
static CS__EXACT_NOINLINE void add_poly_parts(cs__exact_ctx *cx, const cs_segment *s,
                                              float sign, const cs_exact_end *top, float y0,
                                              const cs_exact_end *bot, float y1)
{
    float span = cs__absf(bot->x - top->x);
    int32_t n = 1;
    if (span > POLY_ARC_COLUMNS)
        n = (int32_t)(cs__minf(span, cx->wall_x + 2.0f) * (2.0f / POLY_ARC_COLUMNS)) + 1;
    cs_exact_end a = *top, b;
    float ya = y0;
    for (int32_t i = 1; i <= n; i++) {
        float yb = y1;
        if (i < n) {
            float u = top->u + (bot->u - top->u) * ((float)i / (float)n);
            yb = cs__clampf(cs__segment_y(s, u), ya, y1);
            cs__exact_eval_end(s, u, yb, &b);
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
static inline void add_poly_monotone(cs__exact_ctx *cx, const cs_segment *s, float sign,
                                     const cs_exact_end *top, float y0, const cs_exact_end *bot,
                                     float y1)
{
    if (!add_poly_part(cx, s, sign, top, y0, bot, y1))
        add_poly_parts(cx, s, sign, top, y0, bot, y1);
}

/* An x-monotone sub-arc between two x-extrema of the arc. */
static void add_x_monotone(cs__exact_ctx *cx, const cs_segment *s, float sign,
                           const cs_exact_end *top,
                           float y0, const cs_exact_end *bot, float y1)
{
    if (cs__exact_polynomial(s))
        add_poly_monotone(cx, s, sign, top, y0, bot, y1);
    else
        add_monotone(cx, s, sign, top, y0, bot, y1);
}

/*
 * An effective edge that is neither straight nor a monotone polynomial
 * arc: one column (no solve), a monotone rational arc, or one cut at its
 * x-extrema into x-monotone sub-arcs. Kept out of cs__exact_add_edge,
 * which every arc passes through: written into it, its registers and
 * stack made the common path's entry and exit dearer (CS__EXACT_NOINLINE).
 */
static CS__EXACT_NOINLINE void add_curved_edge(cs__exact_ctx *cx, const cs_segment *s,
                                               const cs_exact_piece *e, float sign, float ya,
                                               float yb)
{
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
        cs__exact_eval_end(s, u, y, &b);
        add_x_monotone(cx, s, sign, &a, y0, &b, y);
        a = b;
        y0 = y;
    }
    add_x_monotone(cx, s, sign, &a, y0, &e->bot, yb);
}

/* Effective edge e over the band [ya, yb]: sign +1 where the region begins.
 * Called by the loop over a row's clusters for a lone arc and by the band
 * sweep (cs_exact.c). */
void cs__exact_add_edge(cs__exact_ctx *cx, const cs_exact_piece *e, float sign, float ya, float yb)
{
    cs_workspace *ws = cx->ws;
    if (e->hidden) { /* only what it adds right of its opaque pixels matters */
        int32_t c = (int32_t)e->xmin - cx->x0;
        cs__acc_cover(ws, c, sign * (yb - ya));
        cs__exact_touch(cx, c, c + 1);
        return;
    }
    if (e->xmax <= cx->left) { /* its cells' heights sum to the band's exactly */
        cs__acc_cover(ws, 0, sign * (yb - ya));
        cs__exact_touch(cx, 0, 1);
        return;
    }
    if (e->xmin >= cx->right) {
        cs__exact_touch(cx, cx->width, cx->width + 1);
        return;
    }
    const cs_segment *s = e->segment;
    if (s->degree == 1) {
        add_line(cx, sign, e->top.x, 0.0f, e->bot.x, yb - ya); /* heights in the band */
        return;
    }
    if (e->monotone && cs__exact_polynomial(s)) { /* most arcs */
        add_poly_monotone(cx, s, sign, &e->top, ya, &e->bot, yb);
        return;
    }
    add_curved_edge(cx, s, e, sign, ya, yb);
}


#endif /* CS_CFG_EXACT */
