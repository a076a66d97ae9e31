/*
 * cs_exact.c - exact-area anti-aliasing: the area of each pixel square that
 * lies inside a region, found from the curves themselves. This file is the
 * row's driver (cs__exact_region): clusters, bands, the proof of their
 * order and the effective edges (steps 1-3 below). The arcs are placed by
 * cs_exact_place.c (step 0) and their area added by cs_exact_area.c (step
 * 4); what the three share is in cs_exact_internal.h.
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
 *    solve per row boundary (a polynomial piece's next eight solved side
 *    by side, lane by lane as each would be alone), and the same bits
 *    whichever lines came before, or none. A straight piece is placed in
 *    closed form, a polynomial one in plane coordinates; the iteration
 *    stops once the residual of its last step, known exactly for a cubic, is below
 *    2^-18 px in y (cs__exact_place_end). Those give the arc's inner Bezier control
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
 * code uses, so the fold (cs_composite.c, fold_region), the within-cel coverage
 * budget and the compositing are shared by every AA mode. Line state is the region's
 * active pieces plus the O(width) accumulators; memory is fixed.
 */
#include "cs_exact_internal.h"

#if CS_CFG_EXACT /* the whole file: see cs_config.h */

/* Area (px^2) by which a crossing hidden in an accepted band could be wrong. */
#define BAND_TOL (1.0f / 32768.0f)
/* Pending band cuts of one band; deeper cuts are not attempted. */
#define MAX_DEPTH 40

/* Neighbouring pieces closer than this (px) share one band sweep. */
#define CLUSTER_GAP (1.0f / 16.0f)

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

/* Orders (a, b) as insertion sort does, keys with them: swapped if ka > kb.
 * Selects, not a branch: which way goes by the data. */
static inline void order_pair(uint32_t *a, uint32_t *b, float *ka, float *kb)
{
    bool swap = *ka > *kb;
    uint32_t ia = *a, ib = *b;
    float fa = *ka, fb = *kb;
    *a = swap ? ib : ia;
    *b = swap ? ia : ib;
    *ka = swap ? fb : fa;
    *kb = swap ? fa : fb;
}

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
    if (m == 3u) {
        /* The most common cluster row (a chain beside a lone arc): the
         * insertion sort below as three compare-exchanges, each of the
         * same test on the same pair, so the same order, ties and all. */
        uint32_t a = ord[0], b = ord[1], c = ord[2];
        float ka = by_xmin ? ex[a].xmin : ex[a].key, kb = by_xmin ? ex[b].xmin : ex[b].key,
              kc = by_xmin ? ex[c].xmin : ex[c].key;
        order_pair(&a, &b, &ka, &kb);
        order_pair(&b, &c, &kb, &kc);
        order_pair(&a, &b, &ka, &kb);
        ord[0] = a;
        ord[1] = b;
        ord[2] = c;
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

/* Applies the fill rule along the band's arcs ord[0..m), in x order, from
 * the winding `w` (updated) met left of them. */
static bool emit_band(cs__exact_ctx *cx, const uint32_t *ord, uint32_t m, float ya, float yb,
                      int32_t *w, bool inside)
{
    cs_workspace *ws = cx->ws;
    for (uint32_t k = 0; k < m; k++) {
        const cs_exact_piece *e = &ws->exact[ord[k]];
        const cs_piece *pc = &ws->pieces[e->piece];
        w[pc->operand] += pc->dir;
        bool now = cs__region_inside(cx->region, w);
        if (now != inside) {
            cs__exact_add_edge(cx, e, now ? 1.0f : -1.0f, ya, yb);
            inside = now;
        }
    }
    return inside;
}

/* Moves e's bottom to height yb, searching from its top towards the known
 * point (uref at yref) below yb. */
static void set_bot(cs__exact_ctx *cx, cs_exact_piece *e, float ya, float yb, float uref,
                    float yref)
{
    cs_workspace *ws = cx->ws;
    const cs_piece *pc = &ws->pieces[e->piece];
    const cs_segment *s = e->segment;
    if (e->hidden)
        return; /* it stays where it was put */
    e->row_arc = false;
    if (yb == yref) {
        cs__exact_place_end(s, cs__exact_polynomial(s), yb, uref, uref, uref, pc->dir > 0, &e->bot);
        return;
    }
    cs__exact_place_end(s, cs__exact_polynomial(s), yb, cs__minf(e->top.u, uref),
                        cs__maxf(e->top.u, uref),
              cs__exact_chord_u(e->top.u, ya, uref, yref, yb), pc->dir > 0, &e->bot);
}

/*
 * The band [ya, yb] of the cluster cl[0..nc) between two consecutive ends
 * of its pieces, cut further until its order is proved; `w` is the winding
 * left of the cluster. On return every piece in it has its top at yb.
 * Returns how many pieces the band had; w_out gets the winding right of
 * them, if any.
 */
static uint32_t run_band(cs__exact_ctx *cx, uint32_t *cl, uint32_t nc, float ya, float yb,
                         const int32_t *w, bool inside, int32_t *w_out)
{
    cs_workspace *ws = cx->ws;
    cs_exact_piece *ex = ws->exact;
    /* The band's pieces to the front of cl. */
    uint32_t m = 0;
    for (uint32_t i = 0; i < nc; i++) {
        const cs_piece *pc = &ws->pieces[ex[cl[i]].piece];
        if (cs__exact_row_top(cx, pc) <= ya && cs__exact_row_end(cx, pc) >= yb) {
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
        if (!(e->row_arc && yb == cs__exact_row_end(cx, pc)))
            set_bot(cx, e, ya, yb, e->u_row, cs__exact_row_end(cx, pc));
    }
    float pending[MAX_DEPTH];
    int depth = 0;
    bool first = true;
    for (;;) {
        for (uint32_t k = 0; k < m; k++) {
            cs_exact_piece *e = &ex[cl[k]];
            if (!e->hidden) /* a stand-in keeps its place (hide) */
                cs__exact_hull(e->segment, e, ya, yb, true);
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
            set_bot(cx, e, ya, yb, e->u_row, cs__exact_row_end(cx, pc));
        }
    }
    return m;
}


/* The next height below ya (at most the row's bottom) where a piece of
 * cl[0..nc) starts or ends: the bottom of the band that starts at ya. */
static float next_cut(const cs__exact_ctx *cx, const uint32_t *cl, uint32_t nc, float ya)
{
    const cs_workspace *ws = cx->ws;
    float yb = cx->row_bot;
    for (uint32_t i = 0; i < nc; i++) {
        const cs_piece *pc = &ws->pieces[ws->exact[cl[i]].piece];
        float t = cs__exact_row_top(cx, pc), b = cs__exact_row_end(cx, pc);
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
static bool run_cluster(cs__exact_ctx *cx, uint32_t *cl, uint32_t nc, int32_t *w, bool inside)
{
    /* The first band with arcs writes w_out; the others' winding is the
     * same and goes to wb. Without one, w stays as it was. */
    int32_t w_out[CS_CFG_MAX_OPERANDS], wb[CS_CFG_MAX_OPERANDS];
    for (int k = 0; k < CS_CFG_MAX_OPERANDS; k++)
        w_out[k] = w[k];
    bool got = false;
    float ya = cx->row_top;
    while (ya < cx->row_bot) {
        float yb = next_cut(cx, cl, nc, ya);
        if (run_band(cx, cl, nc, ya, yb, w, inside, got ? wb : w_out) > 0)
            got = true;
        ya = yb;
    }
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
static uint32_t end_tags(const cs__exact_ctx *cx, const cs_piece *pc, bool *inner)
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
static bool winding_constant(const cs__exact_ctx *cx, const uint32_t *cl, uint32_t nc)
{
    const cs_workspace *ws = cx->ws;
    int32_t d0[CS_CFG_MAX_OPERANDS];
    for (int k = 0; k < CS_CFG_MAX_OPERANDS; k++) /* set by the first band; for -O3's sake */
        d0[k] = 0;
    float ya = cx->row_top;
    bool first = true;
    while (ya < cx->row_bot) {
        float yb = next_cut(cx, cl, nc, ya);
        int32_t d[CS_CFG_MAX_OPERANDS];
        for (int k = 0; k < CS_CFG_MAX_OPERANDS; k++)
            d[k] = 0;
        for (uint32_t i = 0; i < nc; i++) {
            const cs_piece *pc = &ws->pieces[ws->exact[cl[i]].piece];
            if (cs__exact_row_top(cx, pc) <= ya && cs__exact_row_end(cx, pc) >= yb)
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

/* A cluster of one arc, e (of piece pc), whose winding change makes the
 * region inside right of it (now) or not: one band, nothing to order.
 * Returns now. */
static inline bool lone_cross(cs__exact_ctx *cx, const cs_exact_piece *e, const cs_piece *pc,
                              bool now, bool inside)
{
    if (now != inside)
        cs__exact_add_edge(cx, e, now ? 1.0f : -1.0f, cs__exact_row_top(cx, pc),
                           cs__exact_row_end(cx, pc));
    return now;
}

/* lone_cross where the change applies the fill rule to `w` (updated). */
static inline bool lone_edge(cs__exact_ctx *cx, const cs_exact_piece *e, int32_t *w, bool inside)
{
    const cs_piece *pc = &cx->ws->pieces[e->piece];
    w[pc->operand] += pc->dir;
    return lone_cross(cx, e, pc, cs__region_inside(cx->region, w), inside);
}

/*
 * Whether the pieces p and q make a chain across the row: one (*top) from
 * above the row down to a height h inside it, where the other (*bot)
 * begins and goes on below the row, in the same operand and direction.
 * run_cluster would take them as two bands of one arc each, [row_top, h]
 * and [h, row_bot], both from the winding left of them: the same as two
 * lone arcs whose winding changes once, which is how clusters takes them.
 * 1,565 of Many-blobs' 1,813 clusters of several pieces are pairs, mostly
 * these: the joint of two segments of a contour's side within a row.
 */
static inline bool chain_pair(const cs__exact_ctx *cx, const cs_piece *p, const cs_piece *q,
                              const cs_piece **top)
{
    const cs_piece *t = p->y_top <= cx->row_top ? p : q, *b = t == p ? q : p;
    float h = cs__exact_row_end(cx, t);
    *top = t;
    return p->operand == q->operand && p->dir == q->dir && t->y_top <= cx->row_top &&
           b->y_bot >= cx->row_bot && h > cx->row_top && cs__exact_row_top(cx, b) == h &&
           h < cx->row_bot;
}

/*
 * The usual row of a region (50,937 of Many-blobs' 54,862 arcs are lone):
 * two arcs, apart by more than CLUSTER_GAP, the left one across the whole
 * row. The cluster loop would make each a cluster of its own, since the
 * left one has no inner end to change the winding within the row; this
 * says so with two comparisons, without the sort, the reach and the end
 * tags. Returns the left arc's index in ex (0 or 1), its piece in *left,
 * or 2 for a row that is not this one.
 */
static inline uint32_t two_apart(const cs__exact_ctx *cx, const cs_exact_piece *ex,
                                 const cs_piece **left)
{
    uint32_t a = ex[1].xmin < ex[0].xmin ? 1u : 0u; /* sort_pieces' order of two */
    const cs_piece *pc = &cx->ws->pieces[ex[a].piece];
    if (ex[1u - a].xmin <= ex[a].xmax + CLUSTER_GAP || pc->y_top > cx->row_top ||
        pc->y_bot < cx->row_bot)
        return 2u;
    *left = pc;
    return a;
}

/* The row's accumulator range, grown from [*lo, *hi), back into them, and
 * its status. */
static inline cs_status exact_done(const cs__exact_ctx *cx, int32_t *lo, int32_t *hi)
{
    *lo = cx->lo;
    *hi = cx->hi;
    return cx->overflow ? CS_ERR_CAP_CROSSINGS : CS_OK;
}

/* The chain (chain_pair) of arcs p and q, whose upper piece is top: the
 * upper arc's band first, as run_cluster; one change of the winding `w`
 * (updated) for both. Returns whether the region is inside right of it. */
static CS__HOT_INLINE bool chain_edges(cs__exact_ctx *cx, const cs_exact_piece *ex, uint32_t p, uint32_t q,
                               const cs_piece *top, int32_t *w, bool inside)
{
    const cs_workspace *ws = cx->ws;
    uint32_t a = &ws->pieces[ex[p].piece] == top ? p : q;
    uint32_t b = a == p ? q : p;
    const cs_piece *bot = &ws->pieces[ex[b].piece];
    w[top->operand] += top->dir;
    bool now = cs__region_inside(cx->region, w);
    (void)lone_cross(cx, &ex[a], top, now, inside);
    return lone_cross(cx, &ex[b], bot, now, inside);
}

/*
 * The most common row of three pieces (1,302 of Many-blobs' 1,978 rows
 * that clusters takes), in xmin order ord[0..3): a lone arc across the row
 * and, apart from it, a chain of two. Decided by the tests the cluster loop
 * below would make, in its order, with the same outcome: a lone arc with no
 * inner end closes its cluster; a chain closes its own; the last piece
 * closes whatever is open. Spared: the end tags (two hashes per inner end)
 * and the loop's bookkeeping. Returns false, having done nothing, for any
 * other row.
 */
static CS__HOT_INLINE bool lone_and_chain(cs__exact_ctx *cx, const cs_exact_piece *ex, const uint32_t *ord,
                                  int32_t *w)
{
    const cs_workspace *ws = cx->ws;
    uint32_t o0 = ord[0], o1 = ord[1], o2 = ord[2];
    const cs_piece *p0 = &ws->pieces[ex[o0].piece], *p1 = &ws->pieces[ex[o1].piece],
                   *p2 = &ws->pieces[ex[o2].piece], *top;
    if (!(ex[o1].xmin <= ex[o0].xmax + CLUSTER_GAP)) {
        /* ord[0] alone if it has no inner end (end_tags); then ord[1] takes
         * ord[2] in if they overlap, and the two close at the row's end */
        if (p0->y_top > cx->row_top || p0->y_bot < cx->row_bot ||
            !(ex[o2].xmin <= ex[o1].xmax + CLUSTER_GAP) || !chain_pair(cx, p1, p2, &top))
            return false;
        bool inside = lone_edge(cx, &ex[o0], w, false);
        (void)chain_edges(cx, ex, o1, o2, top, w, inside);
        return true;
    }
    /* ord[0] takes ord[1] in; a chain then closes if ord[2] is apart, and
     * ord[2] is alone, the last piece */
    if (ex[o2].xmin <= cs__maxf(ex[o0].xmax, ex[o1].xmax) + CLUSTER_GAP ||
        !chain_pair(cx, p0, p1, &top))
        return false;
    bool inside = chain_edges(cx, ex, o0, o1, top, w, false);
    (void)lone_edge(cx, &ex[o2], w, inside);
    return true;
}

/*
 * The row's pieces cluster by cluster, for rows that two_apart does not
 * take. Clusters: runs of pieces in xmin order whose x ranges overlap, so
 * that no curve passes between two of them. A horizontal segment has no
 * piece, yet joins the ends of two that may lie far apart; a cluster whose
 * winding changes inside the row (found by its end tags, and confirmed
 * band by band) therefore takes in the next one until the changes cancel.
 * The whole row always qualifies. Out of line: its 32-byte windings (w
 * here, run_cluster's and winding_constant's when inlined) made GCC
 * realign the stack of cs__exact_region, which every region-row enters.
 */
static CS__EXACT_NOINLINE void clusters(cs__exact_ctx *cx, cs_exact_piece *ex, uint32_t *ord,
                                        uint32_t n)
{
    const cs_workspace *ws = cx->ws;
    int32_t w[CS_CFG_MAX_OPERANDS];
    for (int k = 0; k < CS_CFG_MAX_OPERANDS; k++) /* a loop: `= {0}` may call memset */
        w[k] = 0;
    bool inside = false;
    for (uint32_t i = 0; i < n; i++)
        ord[i] = i;
    sort_pieces(ex, ord, n, true);
    if (n == 3u && lone_and_chain(cx, ex, ord, w))
        return;
    for (uint32_t i = 0; i < n;) {
        float reach = ex[ord[i]].xmax;
        uint32_t j = i, tags = 0;
        bool inner = false, chain = false;
        const cs_piece *top = NULL;
        for (;;) {
            reach = cs__maxf(reach, ex[ord[j]].xmax);
            tags += end_tags(cx, &ws->pieces[ex[ord[j]].piece], &inner);
            j++;
            chain = j == i + 2 && chain_pair(cx, &ws->pieces[ex[ord[i]].piece],
                                             &ws->pieces[ex[ord[i + 1]].piece], &top);
            if (j == n)
                break;
            if (ex[ord[j]].xmin <= reach + CLUSTER_GAP)
                continue;
            /* a chain's tags cancel, and its winding is constant */
            if (!inner || chain || (tags == 0 && winding_constant(cx, &ord[i], j - i)))
                break;
        }
        if (j == i + 1) { /* alone: one band, nothing to order */
            inside = lone_edge(cx, &ex[ord[i]], w, inside);
        } else if (chain) {
            inside = chain_edges(cx, ex, ord[i], ord[i + 1], top, w, inside);
        } else {
            inside = run_cluster(cx, &ord[i], j - i, w, inside);
        }
        i = j;
    }
}

cs_status cs__exact_region(cs_renderer *r, const cs_region *region, const cs_index *act,
                           uint32_t n, int y, int32_t *lo, int32_t *hi)
{
    if (n > CS_CFG_MAX_CROSSINGS)
        return CS_ERR_CAP_CROSSINGS;
    cs_workspace *ws = r->ws;
    cs__exact_ctx cx;
    cx.ws = ws;
    cx.region = region;
    cx.row_top = (float)y;
    cx.row_bot = (float)(y + 1);
    cx.x0 = r->vx;
    cx.width = r->vw;
    cx.left = (float)cx.x0;
    cx.right = (float)(cx.x0 + cx.width);
    cx.wall_x = (float)r->opts.width;
    cx.lo = *lo; /* cs__exact_touch only widens it */
    cx.hi = *hi;
    cx.bands_left = CS_CFG_EXACT_MAX_BANDS;
    cx.overflow = false;
    cs_exact_piece *ex = ws->exact;
    cs__exact_place_row(r, &cx, act, n); /* each piece's arc across the row into ex */
    const cs_piece *pl = NULL;
    uint32_t a = n == 2u && region->csg_len == 0 ? two_apart(&cx, ex, &pl) : 2u;
    if (a < 2u) {
        /* one operand (pieces move counter 0 without CSG): its winding is
         * a scalar, the fill rule the test. An array here, 32 bytes, made
         * GCC realign this frame, for every region-row. The left arc
         * spans the row, so its band is the row. */
        const cs_exact_piece *er = &ex[1u - a];
        int32_t w0 = pl->dir;
        bool inside = cs__fill(region->fill_rule, w0);
        if (inside)
            cs__exact_add_edge(&cx, &ex[a], 1.0f, cx.row_top, cx.row_bot);
        const cs_piece *pr = &ws->pieces[er->piece];
        w0 += pr->dir;
        (void)lone_cross(&cx, er, pr, cs__fill(region->fill_rule, w0), inside);
    } else {
        clusters(&cx, ex, ws->exact_order, n);
    }
    return exact_done(&cx, lo, hi);
}

#endif /* CS_CFG_EXACT */
