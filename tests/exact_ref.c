/*
 * exact_ref.c - the independent coverage reference of the exact-AA tests.
 *
 * Deliberately built another way than the core: the core converts each
 * knot span to power-basis rational polynomials in float and integrates
 * area analytically per band; this file evaluates the NURBS with de Boor's
 * algorithm in long double, flattens it by adaptive bisection until every
 * chord is within FLAT_TOL of the curve, and integrates coverage by brute
 * force: sample lines at least `subscan` per pixel row and never
 * straddling a polygon vertex, each intersected exactly with the polygon,
 * spans taken under the fill rule and their exact horizontal extent summed
 * per pixel. Its error is the flattening tolerance plus the midpoint
 * rule's error at the kinks where a crossing passes an integer x, both
 * checked against closed forms by the tests.
 */
#include "exact_ref.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define FLAT_TOL 1.0e-7L /* device px: chord to curve */
#define MAX_DEGREE 3

typedef struct edge {
    long double x0, y0, x1, y1; /* y0 < y1 */
    int dir;                    /* +1 if the contour runs down (y grows) */
} edge;

/* Knot t(m) of a periodic contour, m any integer, t(0) = 0. */
static long double knot(const xref_contour *c, long m)
{
    long n = c->count;
    long double t = 0.0L;
    if (m >= 0)
        for (long k = 0; k < m; k++)
            t += c->intervals ? (long double)c->intervals[k % n] : 1.0L;
    else
        for (long k = -1; k >= m; k--)
            t -= c->intervals ? (long double)c->intervals[((k % n) + n) % n] : 1.0L;
    return t;
}

/* Knots t(span-p .. span+p+1) into kn[0 .. 2p+1]. */
static void span_knots(const xref_contour *c, int span, long double *kn)
{
    for (int m = -c->degree; m <= c->degree + 1; m++)
        kn[m + c->degree] = knot(c, span + m);
}

static void span_point(const xref_contour *c, const xref_view *v, int span, const long double *kn,
                       long double t, long double *x, long double *y)
{
    int p = c->degree;
    long double d[MAX_DEGREE + 1][3];
    for (int i = 0; i <= p; i++) {
        long idx = ((long)span - p + i) % c->count;
        if (idx < 0)
            idx += c->count;
        long double w = (long double)c->xyw[3 * idx + 2];
        d[i][0] = w * (long double)c->xyw[3 * idx];
        d[i][1] = w * (long double)c->xyw[3 * idx + 1];
        d[i][2] = w;
    }
    /* de Boor: d_i = (1-a) d_(i-1) + a d_i, a = (t - t(k-p+i)) / (t(k+1+i-r) - t(k-p+i)). */
    for (int r = 1; r <= p; r++)
        for (int i = p; i >= r; i--) {
            long double lo = kn[i], hi = kn[i + 1 - r + p];
            long double a = (t - lo) / (hi - lo);
            for (int k = 0; k < 3; k++)
                d[i][k] = (1.0L - a) * d[i - 1][k] + a * d[i][k];
        }
    long double cx = d[p][0] / d[p][2], cy = d[p][1] / d[p][2];
    *x = (long double)v->sx * ((long double)v->a * cx + (long double)v->c * cy + (long double)v->e);
    *y = (long double)v->sy * ((long double)v->b * cx + (long double)v->d * cy + (long double)v->f);
}

void xref_contour_point(const xref_contour *c, const xref_view *v, int span, long double t,
                       long double *x, long double *y)
{
    long double kn[2 * MAX_DEGREE + 2];
    span_knots(c, span, kn);
    span_point(c, v, span, kn, t, x, y);
}

typedef struct poly_buf {
    long double *pts;
    long n, cap;
} poly_buf;

static int push(poly_buf *b, long double x, long double y)
{
    if (b->n >= b->cap)
        return -1;
    b->pts[2 * b->n] = x;
    b->pts[2 * b->n + 1] = y;
    b->n++;
    return 0;
}

static long double dist_to_chord(long double ax, long double ay, long double bx, long double by,
                                 long double px, long double py)
{
    long double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
    long double ex = px - ax, ey = py - ay;
    if (len2 == 0.0L)
        return ex * ex + ey * ey > 0.0L ? (ex < 0 ? -ex : ex) + (ey < 0 ? -ey : ey) : 0.0L;
    long double cr = dx * ey - dy * ex;
    if (cr < 0)
        cr = -cr;
    /* |cross| / |chord|, compared squared to avoid a sqrt */
    return cr * cr / len2;
}

/* Appends the points of span j on (ta, tb], bisecting until flat. */
static int flatten_span(const xref_contour *c, const xref_view *v, int span, const long double *kn,
                        long double ta,
                        long double xa, long double ya, long double tb, long double xb,
                        long double yb, int depth, poly_buf *out)
{
    long double tq[3], xq[3], yq[3];
    int flat = depth >= 6;
    for (int k = 0; k < 3; k++) {
        tq[k] = ta + (tb - ta) * (long double)(k + 1) / 4.0L;
        span_point(c, v, span, kn, tq[k], &xq[k], &yq[k]);
        if (flat && dist_to_chord(xa, ya, xb, yb, xq[k], yq[k]) > FLAT_TOL * FLAT_TOL)
            flat = 0;
    }
    if (flat || depth >= 40)
        return push(out, xb, yb);
    if (flatten_span(c, v, span, kn, ta, xa, ya, tq[1], xq[1], yq[1], depth + 1, out))
        return -1;
    return flatten_span(c, v, span, kn, tq[1], xq[1], yq[1], tb, xb, yb, depth + 1, out);
}

long xref_flatten(const xref_contour *c, const xref_view *v, long double *pts, long cap)
{
    poly_buf b = {pts, 0, cap};
    for (int j = 0; j < c->count; j++) {
        long double ta = knot(c, j), tb = knot(c, j + 1);
        if (!(tb > ta))
            continue;
        long double xa, ya, xb, yb, kn[2 * MAX_DEGREE + 2];
        span_knots(c, j, kn);
        span_point(c, v, j, kn, ta, &xa, &ya);
        span_point(c, v, j, kn, tb, &xb, &yb);
        if (flatten_span(c, v, j, kn, ta, xa, ya, tb, xb, yb, 0, &b))
            return -1;
    }
    return b.n;
}

static int cmp_edge(const void *a, const void *b)
{
    const edge *p = a, *q = b;
    return p->y0 < q->y0 ? -1 : (p->y0 > q->y0 ? 1 : 0);
}

static int cmp_ld(const void *a, const void *b)
{
    long double p = *(const long double *)a, q = *(const long double *)b;
    return p < q ? -1 : (p > q ? 1 : 0);
}

typedef struct xing {
    long double x;
    int dir;
} xing;

static int cmp_xing(const void *a, const void *b)
{
    const xing *p = a, *q = b;
    return p->x < q->x ? -1 : (p->x > q->x ? 1 : 0);
}

/* Adds the exact horizontal extent of [a, b) (clamped to the row) times w. */
static void add_span(long double *acc, int width, long double a, long double b, long double w)
{
    if (a < 0)
        a = 0;
    if (b > width)
        b = width;
    if (!(b > a))
        return;
    long ia = (long)a, ib = (long)b;
    if (ia == ib) {
        acc[ia] += w * (b - a);
        return;
    }
    acc[ia] += w * ((long double)(ia + 1) - a);
    for (long i = ia + 1; i < ib; i++)
        acc[i] += w;
    if (ib < width)
        acc[ib] += w * (b - (long double)ib);
}

int xref_coverage(const xref_region *reg, const xref_view *v, int width, int height, int subscan,
                 double *out)
{
    long cap = 1L << 22, nedges = 0, ecap = 0;
    long double *pts = malloc(sizeof(long double) * 2 * (size_t)cap);
    edge *edges = NULL;
    xing *xs = NULL;
    long *active = NULL;
    long double *vys = NULL;
    long double *acc = calloc((size_t)width, sizeof(long double));
    int status = -1;
    if (!pts || !acc)
        goto done;
    for (int k = 0; k < reg->contour_count; k++) {
        long n = xref_flatten(&reg->contours[k], v, pts, cap);
        if (n < 0)
            goto done;
        edge *grown = realloc(edges, sizeof(edge) * (size_t)(ecap + n));
        if (!grown)
            goto done;
        edges = grown;
        ecap += n;
        for (long i = 0; i < n; i++) {
            long j = (i + 1) % n;
            long double x0 = pts[2 * i], y0 = pts[2 * i + 1], x1 = pts[2 * j], y1 = pts[2 * j + 1];
            if (y0 == y1)
                continue;
            edge *e = &edges[nedges++];
            if (y0 < y1) {
                *e = (edge){x0, y0, x1, y1, 1};
            } else {
                *e = (edge){x1, y1, x0, y0, -1};
            }
        }
    }
    qsort(edges, (size_t)nedges, sizeof(edge), cmp_edge);
    xs = malloc(sizeof(xing) * (size_t)(nedges + 1));
    active = malloc(sizeof(long) * (size_t)(nedges + 1));
    vys = malloc(sizeof(long double) * (size_t)(2 * nedges + 1));
    if (!xs || !active || !vys)
        goto done;
    for (long i = 0; i < nedges; i++) {
        vys[2 * i] = edges[i].y0;
        vys[2 * i + 1] = edges[i].y1;
    }
    qsort(vys, (size_t)(2 * nedges), sizeof(long double), cmp_ld);
    long next = 0, nact = 0, nv = 0;
    for (int j = 0; j < height; j++) {
        for (int i = 0; i < width; i++)
            acc[i] = 0.0L;
        /* Between consecutive vertex heights every edge is one straight
         * piece, so each pixel's horizontal coverage is linear in y but for
         * kinks where a crossing passes an integer x or another crossing:
         * the midpoint rule on sub-intervals of at most 1/subscan is exact
         * but for those kinks, and the vertices (where a flattened curve's
         * tangent turns horizontal, a square-root singularity) are never
         * straddled. */
        long double a = (long double)j, row_end = (long double)(j + 1);
        while (nv < 2 * nedges && vys[nv] <= a)
            nv++;
        while (a < row_end) {
            long double b = row_end;
            if (nv < 2 * nedges && vys[nv] < row_end)
                b = vys[nv];
            long steps = (long)ceill((b - a) * (long double)subscan);
            if (steps < 1)
                steps = 1;
            long double w = (b - a) / (long double)steps;
            for (long s = 0; s < steps; s++) {
                long double ys = a + ((long double)s + 0.5L) * w;
                while (next < nedges && edges[next].y0 <= ys)
                    active[nact++] = next++;
                long kept = 0, nx = 0;
                for (long k = 0; k < nact; k++) {
                    const edge *e = &edges[active[k]];
                    if (e->y1 <= ys)
                        continue;
                    active[kept++] = active[k];
                    long double x = e->x0 + (ys - e->y0) * (e->x1 - e->x0) / (e->y1 - e->y0);
                    xs[nx++] = (xing){x, e->dir};
                }
                nact = kept;
                qsort(xs, (size_t)nx, sizeof(xing), cmp_xing);
                int wind = 0;
                for (long k = 0; k + 1 < nx; k++) {
                    wind += xs[k].dir;
                    int inside = reg->evenodd ? (wind & 1) : wind != 0;
                    if (inside)
                        add_span(acc, width, xs[k].x, xs[k + 1].x, w);
                }
            }
            a = b;
            while (nv < 2 * nedges && vys[nv] <= a)
                nv++;
        }
        for (int i = 0; i < width; i++)
            out[(size_t)j * (size_t)width + (size_t)i] = (double)acc[i];
    }
    status = 0;
done:
    free(pts);
    free(edges);
    free(xs);
    free(active);
    free(vys);
    free(acc);
    return status;
}

/* Clips polygon in[0..n) to the half plane s*(coord k) <= s*lim... here
 * expressed as keep(p) = sign * (p[axis] - lim) >= 0. */
static int clip(const long double *in, int n, long double *out, int axis, long double lim,
                long double sign)
{
    int m = 0;
    for (int i = 0; i < n; i++) {
        const long double *p = &in[2 * i], *q = &in[2 * ((i + 1) % n)];
        long double fp = sign * (p[axis] - lim), fq = sign * (q[axis] - lim);
        if (fp >= 0) {
            out[2 * m] = p[0];
            out[2 * m + 1] = p[1];
            m++;
        }
        if ((fp >= 0) != (fq >= 0)) {
            long double t = fp / (fp - fq);
            out[2 * m] = p[0] + t * (q[0] - p[0]);
            out[2 * m + 1] = p[1] + t * (q[1] - p[1]);
            m++;
        }
    }
    return m;
}

long double xref_polygon_pixel_area(const long double *poly, int n, int i, int j)
{
    /* Each clip adds at most one point per edge; four clips of n points. */
    long double *a = malloc(sizeof(long double) * 2 * (size_t)(n + 8) * 2);
    long double *b = malloc(sizeof(long double) * 2 * (size_t)(n + 8) * 2);
    if (!a || !b) {
        free(a);
        free(b);
        return -1.0L;
    }
    memcpy(a, poly, sizeof(long double) * 2 * (size_t)n);
    int m = clip(a, n, b, 0, (long double)i, 1.0L);
    m = clip(b, m, a, 0, (long double)(i + 1), -1.0L);
    m = clip(a, m, b, 1, (long double)j, 1.0L);
    m = clip(b, m, a, 1, (long double)(j + 1), -1.0L);
    long double area = 0.0L;
    for (int k = 0; k < m; k++) {
        const long double *p = &a[2 * k], *q = &a[2 * ((k + 1) % m)];
        area += p[0] * q[1] - q[0] * p[1];
    }
    free(a);
    free(b);
    return 0.5L * area;
}
