/*
 * cs_nurbs.c - closed periodic NURBS to rational polynomial segments.
 *
 * A contour of degree p with N control points and N knot intervals is an
 * infinite periodic knot vector with t(k+1) - t(k) = intervals[k mod N].
 * Each non-empty knot span [t(j), t(j+1)) is one segment, a polynomial
 * in u = (t - t(j)) / (t(j+1) - t(j)) driven by control points j-p .. j.
 * Following Choi, Yoo and Lee ("Matrix representation for NURB curves and
 * surfaces", CAD 1990), the basis functions restricted to the span are
 * expanded into power-basis polynomials in u; together they form the
 * (p+1) x (p+1) segment matrix that maps homogeneous control points
 * (w x, w y, w) to the coefficients of X(u), Y(u), W(u). The matrix is
 * built here by running the Cox-de Boor recursion on polynomials, which
 * handles non-uniform and repeated knots alike (0/0 terms are zero, as in
 * the recursion's convention).
 *
 * Segments come one at a time (cs__contour_next), so that the frame keeps
 * only those its rows need and never holds a whole contour it will mostly
 * drop (cs_frame.c).
 *
 * A zero interval yields no segment, and the validation in cs_scene.c
 * guarantees at most p-1 of them in a row, so neighbouring spans still meet
 * with at least C0 continuity and the contour stays closed.
 *
 * The matrix depends only on the knots around the span, and in practice
 * they repeat from span to span (a Bezier path, a uniform B-spline, a
 * circle's [1,0,1,0...]), so the last matrix is kept and reused while the
 * knots are the same floats: the same matrix, computed once per contour
 * instead of once per segment.
 */
#include "cs_internal.h"

/* p(u) *= (a + b u), in place, for a polynomial of degree < 3. */
static void mul_linear(float *poly, float a, float b)
{
    for (int i = 3; i > 0; i--)
        poly[i] = poly[i] * a + poly[i - 1] * b;
    poly[0] *= a;
}

/*
 * basis[k] receives the power coefficients of N(j-p+k, p) on span j, for
 * k = 0..p. knot(m) = t(j+m) - t(j) for m in -p..p+1, stored at knots[m+p].
 */
static void span_basis(int degree, const float *knots, float h, float basis[4][4])
{
#define KNOT(m) knots[(m) + degree]
    for (int k = 0; k < 4; k++)
        for (int i = 0; i < 4; i++)
            basis[k][i] = 0.0f;
    basis[degree][0] = 1.0f; /* N(j, 0) = 1 on the span */
    for (int level = 1; level <= degree; level++) {
        /* At this level N(i, level) for i = j-level .. j are non-zero. */
        for (int k = degree - level; k <= degree; k++) {
            int m = k - degree; /* i - j */
            float term1[4] = {0, 0, 0, 0}, term2[4] = {0, 0, 0, 0};
            float d1 = KNOT(m + level) - KNOT(m);
            if (d1 > 0.0f) {
                /* (t - t_i) / d1 with t = t_j + u h */
                for (int i = 0; i < 4; i++)
                    term1[i] = basis[k][i];
                mul_linear(term1, -KNOT(m) / d1, h / d1);
            }
            float d2 = KNOT(m + level + 1) - KNOT(m + 1);
            if (k < degree && d2 > 0.0f) {
                for (int i = 0; i < 4; i++)
                    term2[i] = basis[k + 1][i];
                mul_linear(term2, KNOT(m + level + 1) / d2, -h / d2);
            }
            for (int i = 0; i < 4; i++)
                basis[k][i] = term1[i] + term2[i];
        }
    }
#undef KNOT
}

/* The whole pixel at device coordinate v (|v| <= CS_CFG_COORD_LIMIT),
 * within int16_t: beyond it the origin only helps less. */
static int16_t origin(float v)
{
    int32_t i = cs__floori(v);
    return (int16_t)(i < -32768 ? -32768 : i > 32767 ? 32767 : i);
}

cs_status cs__contour_begin(cs__contour_iter *it, const cs_point *points, const float *intervals,
                            int count, int degree, const cs_affine *to_device, uint16_t region,
                            int32_t *bad_point)
{
    *bad_point = -1;
    float ymin = CS_CFG_COORD_LIMIT, ymax = -CS_CFG_COORD_LIMIT;
    for (int i = 0; i < count; i++) {
        float x = points[i].x, y = points[i].y;
        float dx = to_device->a * x + to_device->c * y + to_device->e;
        float dy = to_device->b * x + to_device->d * y + to_device->f;
        if (!(cs__absf(dx) <= CS_CFG_COORD_LIMIT && cs__absf(dy) <= CS_CFG_COORD_LIMIT)) {
            *bad_point = i;
            return CS_ERR_RANGE;
        }
        ymin = cs__minf(ymin, dy);
        ymax = cs__maxf(ymax, dy);
    }
    it->ymin = ymin;
    it->ymax = ymax;
    it->points = points;
    it->intervals = intervals;
    it->to_device = to_device;
    it->count = count;
    it->degree = degree;
    it->region = region;
    it->j = 0;
    it->have_basis = false;
    return CS_OK;
}

bool cs__contour_more(const cs__contour_iter *it)
{
    for (int j = it->j; j < it->count; j++)
        if (it->intervals[j] > 0.0f)
            return true;
    return false;
}

#if defined(__AVX__) && defined(__GNUC__)
/* A segment's four coefficients of x, y or w (float[4], 4-byte aligned). */
typedef float cs__seg4 __attribute__((vector_size(16), aligned(4), may_alias));
#endif

bool cs__contour_next(cs__contour_iter *it, cs_segment *s)
{
    const int count = it->count, degree = it->degree;
#if defined(__GNUC__)
    /* Degrees are 1..3 (cs__check_contour). Told so, GCC unrolls the loops
     * over k <= degree for what they are; otherwise it vectorises them for
     * four or more terms and sends every real contour down the remainder
     * path, which the x86-64-v3 build's profile then lays out as cold. */
    if (degree < 1 || degree > 3)
        __builtin_unreachable();
#endif
    const float *intervals = it->intervals;
    const cs_affine *to_device = it->to_device;
    int j = it->j;
    while (j < count && intervals[j] <= 0.0f)
        j++;
    if (j >= count) {
        it->j = count;
        return false;
    }
    it->j = j + 1;
    float h = intervals[j];
    /* Indices stay within [0, 2 count): count >= degree + 1 (cs_scene.c). */
    float knots[8];
    knots[degree] = 0.0f;
    for (int m = 0; m < degree + 1; m++) { /* t(j+m+1) */
        int at = j + m < count ? j + m : j + m - count;
        knots[degree + m + 1] = knots[degree + m] + intervals[at];
    }
    for (int m = 0; m > -degree; m--) { /* t(j+m-1) */
        int at = j + m - 1 >= 0 ? j + m - 1 : j + m - 1 + count;
        knots[degree + m - 1] = knots[degree + m] - intervals[at];
    }
    bool same = it->have_basis;
    for (int m = 0; m <= 2 * degree + 1 && same; m++)
        same = knots[m] == it->last[m];
    if (!same) {
        span_basis(degree, knots, h, it->basis);
        for (int m = 0; m <= 2 * degree + 1; m++)
            it->last[m] = knots[m];
        it->have_basis = true;
    }
    const float(*basis)[4] = (const float(*)[4])it->basis;

    for (int i = 0; i < 4; i++)
        s->x[i] = s->y[i] = s->w[i] = 0.0f;
    /* The segment's control points in device space, and its start,
     * sum_k basis[k][0] w_k P_k / sum_k basis[k][0] w_k. */
    float px[4] = {0}, py[4] = {0}, pw[4] = {0}, sx = 0.0f, sy = 0.0f, sw = 0.0f;
    for (int k = 0; k <= degree; k++) {
        int at = j - degree + k >= 0 ? j - degree + k : j - degree + k + count;
        const cs_point *p = &it->points[at];
        px[k] = to_device->a * p->x + to_device->c * p->y + to_device->e;
        py[k] = to_device->b * p->x + to_device->d * p->y + to_device->f;
        pw[k] = p->w;
        sx += basis[k][0] * pw[k] * px[k];
        sy += basis[k][0] * pw[k] * py[k];
        sw += basis[k][0] * pw[k];
    }
    /* The origin: the pixel of the segment's start, which lies on the
     * curve (a control point may lie far off it). Any origin is exact,
     * so a start that cannot be formed falls back to the first point. */
    float ax = px[0], ay = py[0];
    if (sw > 0.0f && cs__absf(sx / sw) <= CS_CFG_COORD_LIMIT &&
        cs__absf(sy / sw) <= CS_CFG_COORD_LIMIT) {
        ax = sx / sw;
        ay = sy / sw;
    }
    s->ox = origin(ax);
    s->oy = origin(ay);
    float ox = (float)s->ox, oy = (float)s->oy;
#if defined(__AVX__) && defined(__GNUC__)
    /* The four coefficients of each as one vector: per lane the loop below,
     * the same products and sums in the same order. Lanes past the degree
     * add basis 0 (or -0) times a finite value to +0, which stays +0. */
    cs__seg4 cx = {0.0f, 0.0f, 0.0f, 0.0f}, cy = cx, cw = cx;
    for (int k = 0; k <= degree; k++) {
        float hx = pw[k] * (px[k] - ox), hy = pw[k] * (py[k] - oy);
        cs__seg4 b = *(const cs__seg4 *)basis[k];
        cx += b * hx;
        cy += b * hy;
        cw += b * pw[k];
    }
    *(cs__seg4 *)s->x = cx;
    *(cs__seg4 *)s->y = cy;
    *(cs__seg4 *)s->w = cw;
#else
    for (int k = 0; k <= degree; k++) {
        float hx = pw[k] * (px[k] - ox), hy = pw[k] * (py[k] - oy);
        for (int i = 0; i <= degree; i++) {
            s->x[i] += basis[k][i] * hx;
            s->y[i] += basis[k][i] * hy;
            s->w[i] += basis[k][i] * pw[k];
        }
    }
#endif
    s->degree = (uint8_t)degree;
    s->rational = !(s->w[1] == 0.0f && s->w[2] == 0.0f && s->w[3] == 0.0f);
    s->region = it->region;
    return true;
}
