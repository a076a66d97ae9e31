/*
 * cs_exact_place.c - arc placement for exact-area anti-aliasing (stage 0 of
 * cs_exact.c): where each active piece enters and leaves a pixel row, u at
 * a given height by Newton from the chord (closed form for a straight
 * piece, plane coordinates for a polynomial one), with x, x', y' and W'/W
 * at both ends, and from those the arc's x range; a polynomial piece's
 * ends at its next row boundaries are solved side by side (fill_levels)
 * and kept for the rows below; a piece whose pixels are all opaque becomes
 * a stand-in instead (hide). The band proof
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
 * The levels of a polynomial piece are solved side by side, one per lane
 * of a vector (the GCC and clang vector extension): eight lanes where the
 * build has AVX (x86-64-v3), else four (SSE on baseline x86-64, where the
 * compiler splits eight-lane compares into scalar ones; plain floats on
 * the boards' compilers, which build without exact mode). A lane does the
 * float operations one solve alone would, in the same order, and stops
 * where it would, so every end has the bits of its scalar solve whatever
 * the width; only the branches became masks.
 */
#if defined(__AVX__)
#define LANES 8
#define LANE_INDEX {0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f}
/* Shuffle indices (__builtin_shufflevector: GCC 12 and clang alike, where
 * GCC's __builtin_shuffle stopped the clang builds, TSan and the fuzzers):
 * lanes interleaved in pairs, then pairs of pairs, within each half. */
#define PAIR_LO 0, 8, 1, 9, 4, 12, 5, 13
#define PAIR_HI 2, 10, 3, 11, 6, 14, 7, 15
#define QUAD_LO 0, 1, 8, 9, 4, 5, 12, 13
#define QUAD_HI 2, 3, 10, 11, 6, 7, 14, 15
#define LO_HALVES 0, 1, 2, 3, 8, 9, 10, 11
#define HI_HALVES 4, 5, 6, 7, 12, 13, 14, 15
#else
#define LANES 4
#define LANE_INDEX {0.0f, 1.0f, 2.0f, 3.0f}
#define PAIR_LO 0, 4, 1, 5
#define PAIR_HI 2, 6, 3, 7
#define QUAD_LO 0, 1, 4, 5
#define QUAD_HI 2, 3, 6, 7
#endif
typedef float lanes_f __attribute__((vector_size(4 * LANES)));
typedef int32_t lanes_i __attribute__((vector_size(4 * LANES)));
typedef float lanes_fu __attribute__((vector_size(4 * LANES), aligned(4))); /* stored anywhere */
typedef char cs__exact_lanes_fit_[CS_EXACT_LEVELS % LANES == 0 ? 1 : -1];

/* Lane by lane, m ? a : b (m all ones or zero per lane). A macro: a
 * function taking vectors is an ABI question on baseline x86-64. With AVX
 * one vblendvps, which takes a lane's sign bit (set exactly where m is):
 * as the masks ANDed, GCC made it three operations (xor, and, xor). */
#if defined(__AVX__) && LANES == 8
#define PICK(m, a, b) \
    ((lanes_f)__builtin_ia32_blendvps256((lanes_f)(b), (lanes_f)(a), (lanes_f)(m)))
#else
#define PICK(m, a, b) ((lanes_f)(((m) & (lanes_i)(a)) | (~(m) & (lanes_i)(b))))
#endif

/* Whether any lane of a mask is set: one vptest with AVX, one movmskps
 * with SSE (GCC and clang both know these builtins; the 64-bit lanes ORed
 * one by one took nine instructions a test on the v3 build), else its
 * bits as 64-bit lanes, ORed. */
#if defined(__AVX__)
typedef long long lanes_ll __attribute__((vector_size(32))); /* the builtin's type */
#define ANY_LANE(m, out) ((out) = !__builtin_ia32_ptestz256((lanes_ll)(m), (lanes_ll)(m)))
#elif defined(__SSE__) && LANES == 4
#define ANY_LANE(m, out) ((out) = __builtin_ia32_movmskps((lanes_f)(m)) != 0)
#else
typedef int64_t lanes_q __attribute__((vector_size(4 * LANES)));
#define ANY_LANE(m, out)                                                                  \
    do {                                                                                  \
        lanes_q q_ = (lanes_q)(m);                                                        \
        int64_t any_ = 0;                                                                 \
        for (int l_ = 0; l_ < LANES / 2; l_++)                                            \
            any_ |= q_[l_];                                                               \
        (out) = any_ != 0;                                                                \
    } while (0)
#endif

/*
 * Levels y0 + c0 .. y0 + n - 1 of polynomial piece pc, at most LANES of
 * them, into m->end[c0..]: one vector's worth of fill_levels.
 */
static CS__HOT_INLINE void solve_lanes(const cs_piece *pc, const cs_segment *s, float y0,
                                       uint32_t c0, uint32_t n, cs_exact_level *m)
{
    const float *X = s->x, *Y = s->y;
    float w0 = s->w[0], inv = 1.0f / w0;
    float ut = cs__exact_top_u(pc), ub = cs__exact_bot_u(pc);
    float tol = (2.0f * LEVEL_TOL) * w0;
    float y1 = Y[1], y2 = Y[2], y3 = Y[3], y2x2 = 2.0f * y2, y3x3 = 3.0f * y3;
    /* Scalars to every lane as x - 0, which keeps a -0 (x + 0 would not).
     * Lanes past n repeat the first: the same steps. */
    const lanes_f zero = {0.0f}, lane = LANE_INDEX;
    lanes_f k = (float)c0 + lane, first = (float)c0 - zero;
    lanes_f yv = y0 + PICK(k < (float)n, k, first);
    lanes_f lo = cs__minf(ut, ub) - zero, hi = cs__maxf(ut, ub) - zero;
    lanes_f level = (yv - (float)s->oy) * w0;
    lanes_f g0 = Y[0] - level;
    lanes_f u = ut + (yv - pc->y_top) / (pc->y_bot - pc->y_top) * (ub - ut); /* the chord */
    lanes_f res = u, d1 = u; /* every lane below n sets both: a root, accepted or solved */
    lanes_i live = (u > lo) & (u < hi), fall = ~live;
    /* y falling with u flips the side of the root: a mask, as one select
     * of the piece rather than a copy of the loop for each direction */
    const lanes_i flip = pc->dir > 0 ? (lanes_i){0} : ~(lanes_i){0};
    for (int it = 0; it < LEVEL_MAX_ITER; it++) {
        bool going;
        ANY_LANE(live, going);
        if (!going)
            break;
        lanes_f f = ((y3 * u + y2) * u + y1) * u + g0;
        lanes_f d = (y3x3 * u + y2x2) * u + y1;
        lanes_f dd = 2.0f * (y3x3 * u + y2);
        lanes_i root = live & (f == 0.0f);
        res = PICK(root, u, res);
        d1 = PICK(root, d, d1);
        live &= ~root;
        lanes_i below = (f < 0.0f) ^ flip; /* f < 0, or not, where y falls */
        lo = PICK(live & below, u, lo);
        hi = PICK(live & ~below, u, hi);
        lanes_f rd = 1.0f / d, st = -f * rd, next = u + st;
        /* g being a cubic, the step leaves exactly (g''/2 + g3 s) s^2 of it */
        lanes_f ad = (lanes_f)((lanes_i)dd & 0x7FFFFFFF);
        lanes_f a3 = (lanes_f)((lanes_i)(y3 * st) & 0x7FFFFFFF);
        lanes_i ok = live & ((ad + 2.0f * a3) * (st * st) <= tol);
        d1 = PICK(ok, d + st * (dd + y3x3 * st), d1); /* g' there: exact Taylor */
        lanes_f up = PICK(next > lo, next, lo);
        res = PICK(ok, PICK(up < hi, up, hi), res);
        live &= ~ok;
        /* Chebyshev's correction (the root of the quadratic model) makes
         * the steps converge cubically where the model holds. */
        lanes_f c = 0.5f * dd * st * rd;
        next = PICK((c > -0.5f) & (c < 0.5f), next - c * st, next);
        lanes_i out = live & ~((next > lo) & (next < hi));
        fall |= out;
        live &= ~out;
        u = PICK(live, next, u);
    }
    fall |= live; /* out of steps */
    uint32_t nl = n - c0 < LANES ? n - c0 : LANES; /* lanes of levels */
    bool fell;
    ANY_LANE(fall, fell);
    for (uint32_t l = 0; fell && l < nl; l++) {
        if (fall[l] == 0)
            continue;
        /* a step left the bracket: the bounded solve of cs_poly.c */
        float w[4] = {1.0f, 0.0f, 0.0f, 0.0f};
        float ul = cs__solve_level(Y, w, s->degree, level[l], lo[l], hi[l]);
        res[l] = ul;
        d1[l] = (y3x3 * ul + y2x2) * ul + y1;
    }
    lanes_f xv = (float)s->ox + (((X[3] * res + X[2]) * res + X[1]) * res + X[0]) * inv;
    lanes_f dxv = ((3.0f * X[3] * res + 2.0f * X[2]) * res + X[1]) * inv;
    lanes_f dyv = d1 * inv;
    /* Into the memo's records (u, x, x', y'), which memo_get copies whole:
     * the four vectors transposed by shuffles and stored whole, the lanes
     * past n onto records the memo does not hold. */
    lanes_f t0 = __builtin_shufflevector(res, xv, PAIR_LO);
    lanes_f t1 = __builtin_shufflevector(res, xv, PAIR_HI);
    lanes_f t2 = __builtin_shufflevector(dxv, dyv, PAIR_LO);
    lanes_f t3 = __builtin_shufflevector(dxv, dyv, PAIR_HI);
    lanes_f r0 = __builtin_shufflevector(t0, t2, QUAD_LO);
    lanes_f r1 = __builtin_shufflevector(t0, t2, QUAD_HI);
    lanes_f r2 = __builtin_shufflevector(t1, t3, QUAD_LO);
    lanes_f r3 = __builtin_shufflevector(t1, t3, QUAD_HI);
#if LANES == 8 /* r0 holds records 0 and 4, r1 1 and 5, r2 2 and 6, r3 3 and 7 */
    *(lanes_fu *)m->end[c0] = __builtin_shufflevector(r0, r1, LO_HALVES);
    *(lanes_fu *)m->end[c0 + 2] = __builtin_shufflevector(r2, r3, LO_HALVES);
    *(lanes_fu *)m->end[c0 + 4] = __builtin_shufflevector(r0, r1, HI_HALVES);
    *(lanes_fu *)m->end[c0 + 6] = __builtin_shufflevector(r2, r3, HI_HALVES);
#else
    *(lanes_fu *)m->end[c0] = r0;
    *(lanes_fu *)m->end[c0 + 1] = r1;
    *(lanes_fu *)m->end[c0 + 2] = r2;
    *(lanes_fu *)m->end[c0 + 3] = r3;
#endif
}

/* The level memo's key: m->y keeps its first level plus MEMO_KEY, so
 * that the frame's reset to -1 ("none yet", cs_frame.c, which writes
 * nothing else) puts every row yv >= 0 at index yv + MEMO_KEY + 1, past
 * the levels: one unsigned compare then tests both bounds and "none"
 * (memo_has). Row boundaries are whole numbers far below 2^24, so the
 * difference is exact, and a negative one wraps past the levels. */
#define MEMO_KEY ((float)CS_EXACT_LEVELS)
static inline float memo_key(float y0)
{
    return y0 + MEMO_KEY;
}

/*
 * The ends of polynomial piece pc (constant weight w0, degree 2 or 3) at
 * the levels y0, y0 + 1, ... above its bottom, at most CS_EXACT_LEVELS of
 * them, into m. Each is u where Y = (yv - oy) w0 by Newton's method from
 * the piece's chord over the whole piece, accepted as cs__exact_place_end
 * accepts, with Y' there: a function of the piece and the level alone,
 * never of the row asking, so the bottom of one row is the top of the
 * next, and bands of lines on other threads or in another order get the
 * same bits. Out of line, so that its vector registers are not saved by
 * the callers that find their level in the memo (most).
 */
static CS__EXACT_NOINLINE void fill_levels(const cs_piece *pc, const cs_segment *s, float y0,
                                           cs_exact_level *m)
{
    /* n levels: those above the piece's bottom (y0 + n < y_bot), the
     * first always. Below CS_EXACT_LEVELS, y_bot - y0 is exact (y0 a whole
     * row, y_bot within 8 of it), so n is its ceiling. The lanes past n
     * hold the first level again; no row asks for them (memo_has). */
    float left = pc->y_bot - y0;
    uint32_t n = CS_EXACT_LEVELS;
    if (left < (float)CS_EXACT_LEVELS) {
        int32_t c = -cs__floori(-left);
        n = c > 1 ? (uint32_t)c : 1u;
    }
#if LANES == CS_EXACT_LEVELS /* one vector (a loop of one step measured 0.5 % dearer) */
    solve_lanes(pc, s, y0, 0, n, m);
#else
    for (uint32_t c0 = 0; c0 < n; c0 += LANES)
        solve_lanes(pc, s, y0, c0, n, m);
#endif
    m->y = memo_key(y0);
}

/* The end of polynomial piece pc at its own top or bottom (yv is y_top or
 * y_bot): its u is exact. */
static CS__EXACT_NOINLINE void poly_own_end(const cs_piece *pc, const cs_segment *s, float yv,
                                            cs_exact_end *e)
{
    const float *X = s->x, *Y = s->y;
    float w0 = s->w[0], inv = 1.0f / w0;
    float u = yv == pc->y_top ? cs__exact_top_u(pc) : cs__exact_bot_u(pc);
    float d1 = (3.0f * Y[3] * u + 2.0f * Y[2]) * u + Y[1];
    e->u = u;
    e->x = (float)s->ox + (((X[3] * u + X[2]) * u + X[1]) * u + X[0]) * inv;
    e->dx = ((3.0f * X[3] * u + 2.0f * X[2]) * u + X[1]) * inv;
    e->dy = d1 * inv;
    e->dwr = 0.0f; /* w unset: only rational arcs read it */
}

/* The end of a rational piece at height yv: cs__exact_place_end, exactly
 * at its own ends, else from the chord over the whole piece. */
static CS__EXACT_NOINLINE void rational_end(const cs_piece *pc, const cs_segment *s, float yv,
                                            cs_exact_end *e)
{
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
 * Whether polynomial memo m holds level yv (a row boundary), and which
 * (see memo_key). Only its first n levels were solved (fill_levels), yet
 * no test of n is needed: a row boundary asked for lies above the piece's
 * bottom (poly_row_ends: at a piece's own end it asks nothing), so
 * yv - y0 < y_bot - y0, whose ceiling is n (or n is CS_EXACT_LEVELS).
 */
static inline bool memo_has(const cs_exact_level *m, float yv, uint32_t *i)
{
    *i = (uint32_t)(int32_t)(memo_key(yv) - m->y);
    return *i < CS_EXACT_LEVELS;
}

/* Level i of m, as an end: u, x, x' and y'. A polynomial end takes W'/W =
 * 0 and leaves w unset, which only rational arcs read (rational_moment);
 * a rational one takes both from the memo (rational_level_end). */
static inline void memo_get(const cs_exact_level *m, uint32_t i, cs_exact_end *e)
{
    e->u = m->end[i][0];
    e->x = m->end[i][1];
    e->dx = m->end[i][2];
    e->dy = m->end[i][3];
}

/* The end of polynomial piece pc at row boundary yv: from the level memo m
 * if it holds yv, else solved with the levels below it into m (the piece's
 * later rows take those). */
static CS__HOT_INLINE void poly_memo_end(const cs_piece *pc, const cs_segment *s, float yv,
                                         cs_exact_level *m, cs_exact_end *e)
{
    uint32_t i;
    if (!memo_has(m, yv, &i)) {
        fill_levels(pc, s, yv, m);
        i = 0;
    }
    memo_get(m, i, e);
    e->dwr = 0.0f;
}

/*
 * The ends of polynomial piece pc at ya and yb, the top and bottom of its
 * arc across a row, each a row boundary (poly_memo_end) or one of its own
 * ends. Each is looked up on its own: taking level i + 1 after a top at
 * level i gave wrong ends where the next row boundary was not the next
 * level (test_svg's bevelled strokes and glyphs).
 */
static CS__HOT_INLINE void poly_row_ends(const cs_piece *pc, const cs_segment *s, float ya,
                                         float yb, cs_exact_level *m, cs_exact_end *top,
                                         cs_exact_end *bot)
{
    if (ya == pc->y_top) /* an active piece (y_top < y + 1, y_bot > y) ends below ya */
        poly_own_end(pc, s, ya, top);
    else
        poly_memo_end(pc, s, ya, m, top);
    if (yb == pc->y_bot) /* and starts above yb */
        poly_own_end(pc, s, yb, bot);
    else
        poly_memo_end(pc, s, yb, m, bot);
}

/* The same for a rational piece, whose memo keeps one level: the bottom
 * of the row before. */
static CS__HOT_INLINE void rational_level_end(const cs_piece *pc, const cs_segment *s, float yv,
                                             cs_exact_level *m, cs_exact_end *e)
{
    bool own = yv == pc->y_top || yv == pc->y_bot;
    if (!own && m->y == memo_key(yv)) { /* never -1, the reset: no row is above 0 */
        memo_get(m, 0, e);
        e->w = m->w;
        e->dwr = m->dwr;
        return;
    }
    rational_end(pc, s, yv, e);
    if (own)
        return;
    m->end[0][0] = e->u;
    m->end[0][1] = e->x;
    m->end[0][2] = e->dx;
    m->end[0][3] = e->dy;
    m->w = e->w;
    m->dwr = e->dwr;
    m->y = memo_key(yv);
}

typedef float bounds_f __attribute__((vector_size(16)));
typedef long long bounds_q __attribute__((vector_size(16))); /* ptest's type */

/*
 * x bounds of a polynomial arc from its control polygon (hull without the
 * strip): cheaper than cs__exact_hull(), which also serves rational arcs.
 * The strip and the order key are left to the band sweep, which forms
 * them for every arc it orders (a lone arc needs neither).
 */
static CS__HOT_INLINE void poly_bounds(int p, cs_exact_piece *e)
{
    float xt = e->top.x, xb = e->bot.x;
    float t = (e->bot.u - e->top.u) / (p == 3 ? 3.0f : 2.0f); /* the same quotient, no conversion */
    float c1 = xt + t * e->top.dx, c2 = p == 3 ? xb - t * e->bot.dx : c1;
    e->xmin = cs__minf(cs__minf(xt, xb), cs__minf(c1, c2));
    e->xmax = cs__maxf(cs__maxf(xt, xb), cs__maxf(c1, c2));
    /* the polygon's three steps compared lane by lane: the same compares
     * as scalars, in a vector (the scalar ||s took ~20 instructions) */
    bounds_f to = {c1, c2, xb, xb}, from = {xt, c1, c2, xb};
    bounds_q up = (bounds_q)(to > from), down = (bounds_q)(to < from);
    /* | rather than ||: whether an arc turns goes by the data (23 k
     * mispredicted branches a Many-blobs exact frame as ||). With SSE4.1
     * each "no lane" is one ptest (the 64-bit lanes ORed were three
     * instructions and a setcc each). */
#if defined(__SSE4_1__)
    e->monotone = __builtin_ia32_ptestz128(up, up) | __builtin_ia32_ptestz128(down, down);
#else
    e->monotone = ((up[0] | up[1]) == 0) | ((down[0] | down[1]) == 0);
#endif
}

/*
 * The arc of piece `piece` across the row: its ends and its x bounds. An
 * end inside the piece is a pure function of the piece and the height
 * (poly_row_ends), so the ends of a polynomial piece at its next
 * CS_EXACT_LEVELS row boundaries are solved together and kept in the
 * level memo, where the rows below find their tops and bottoms: one solve
 * per row boundary, several side by side, and the same bits whichever
 * lines were rendered before.
 */
static CS__HOT_INLINE void place_arc(const cs__exact_ctx *cx, cs_exact_piece *e, cs_index piece)
{
    cs_workspace *ws = cx->ws;
    const cs_piece *pc = &ws->pieces[piece];
    const cs_segment *s = e->segment;
    float ya = cs__exact_row_top(cx, pc), yb = cs__exact_row_end(cx, pc);
    e->piece = piece;
    e->row_arc = true;
    if (s->degree == 1) {
        /* u's at the piece's ends here only: taken before the test, the
         * direction they follow became a branch on the data shared by every
         * arc (12 k mispredicts a Many-blobs exact frame) */
        float ut = cs__exact_top_u(pc), ub = cs__exact_bot_u(pc);
        line_end(s, ya, ya == pc->y_top ? ut : -1.0f, ut, ub, &e->top);
        line_end(s, yb, yb == pc->y_bot ? ub : -1.0f, ut, ub, &e->bot);
        e->u_row = e->bot.u;
        e->xmin = cs__minf(e->top.x, e->bot.x);
        e->xmax = cs__maxf(e->top.x, e->bot.x);
        e->monotone = true;
        return;
    }
    cs_exact_level *memo = &ws->level_memo[piece];
    if (cs__exact_polynomial(s)) {
        poly_row_ends(pc, s, ya, yb, memo, &e->top, &e->bot);
        e->u_row = e->bot.u;
        poly_bounds(s->degree, e);
        return;
    }
    rational_level_end(pc, s, ya, memo, &e->top);
    rational_level_end(pc, s, yb, memo, &e->bot);
    e->u_row = e->bot.u;
    cs__exact_hull(s, e, ya, yb, false);
}

/*
 * A piece whose every possible pixel (its segment's hull) is already
 * opaque. Those pixels will show nothing of the region, so the arc need
 * not be placed: it becomes a vertical stand-in at the hull's left edge
 * pa, and as an effective edge it adds only its height, to the cover of
 * every pixel from pa on (cs__exact_add_edge). Pixels right of the opaque stretch
 * get the same total; the stand-in changes the x order only within the
 * stretch, and the fill rule's effective edges there sum to the same
 * change of "inside" across it whatever their order. A cluster holds
 * stand-ins and real arcs only where their hulls are apart, so their
 * order is right. The only difference right of the stretch is the order
 * in which the cover deltas are summed: a last-bit one at most.
 *
 * Only what a stand-in is read for is written: its x (xmin, for the area
 * and the clusters), its ends' x, strip and key (the band sweep's order
 * and proof, which neither moves nor re-hulls a hidden arc: set_bot and
 * run_band test `hidden` first). Its ends' u and derivatives, u_row and
 * `monotone` keep what the slot held: nothing reads them (the area takes
 * a hidden arc's height alone, cs__exact_add_edge).
 */
static void hide(cs_exact_piece *e, cs_index piece, int32_t pa)
{
    float x = (float)pa;
    e->piece = piece;
    e->row_arc = true;
    e->top.x = e->bot.x = x;
    e->dmin = e->dmax = 0.0f;
    e->xmin = e->xmax = x;
    e->key = 2.0f * x;
}

/*
 * Piece `piece`'s arc across the row into e, or a stand-in (hide) where
 * every pixel it could touch is already opaque.
 */
static CS__HOT_INLINE void place_piece(const cs_renderer *r, const cs__exact_ctx *cx,
                                       cs_exact_piece *e, cs_index piece)
{
    const cs_workspace *ws = cx->ws;
    const cs_piece *pc = &ws->pieces[piece];
    const cs_segment *s = &ws->segments[pc->segment];
    int32_t pa = s->px_lo, pb = s->px_hi;
    e->segment = s;
    /* the hull's first pixel, one bit, rules most pieces out */
    e->hidden = pa < pb && cs__run_opaque(r, (uint32_t)pa) &&
                cs__span_opaque(r, (uint32_t)pa, (uint32_t)pb);
    if (e->hidden) {
        hide(e, piece, pa + r->vx); /* in device columns, as placed arcs */
        return;
    }
    place_arc(cx, e, piece);
    /* Its pixels on this row (its hull, widened as the segment's is) may
     * all be opaque though the segment's are not: then it is a stand-in
     * too, spared its area (14% of Many-blobs' arcs). The pixel of its top
     * end, one bit, rules most arcs out. */
    float x0 = cx->left; /* r->vx: arcs are in device columns, the line's bits in its own */
    float xt = e->top.x - x0;
    if (r->opaque_px != 0u && xt >= 0.0f && xt < (float)cx->width &&
        cs__run_opaque(r, (uint32_t)xt)) {
        /* clamped as floats first: a hull that could not be formed is +-HUGE_X */
        float xl = cs__maxf(e->xmin - 0.5f - x0, 0.0f);
        float xr = cs__minf(e->xmax + 0.5f - x0, (float)cx->width);
        int32_t qa = cs__floori(xl), qb = cs__floori(xr) + 1;
        qb = qb > cx->width ? cx->width : qb;
        if (qa < qb && cs__span_opaque(r, (uint32_t)qa, (uint32_t)qb)) {
            e->hidden = true;
            hide(e, piece, qa + r->vx);
        }
    }
}

/* Every active piece's arc across the row, act[i] into ws->exact[i]: one
 * call per region-row, with the placement written into its loop (a call
 * per piece, and the registers it saved, measured dearer). Two pieces, a
 * region's left and right edge, are most rows (93 % of Many-blobs'): those
 * are placed by two copies outside the loop (0.5 M instructions fewer a
 * Many-blobs exact frame, with poly_bounds kept inline in both). */
void cs__exact_place_row(const cs_renderer *r, const cs__exact_ctx *cx, const cs_index *act,
                         uint32_t n)
{
    cs_exact_piece *ex = cx->ws->exact;
    if (n == 2u) {
        place_piece(r, cx, &ex[0], act[0]);
        place_piece(r, cx, &ex[1], act[1]);
        return;
    }
    for (uint32_t i = 0; i < n; i++)
        place_piece(r, cx, &ex[i], act[i]);
}

#endif /* CS_CFG_EXACT */
