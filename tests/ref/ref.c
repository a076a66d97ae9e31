/*
 * ref.c - the independent reference of the test suite: long double NURBS
 * evaluation straight from the knot vector, dense adaptive flattening, and
 * exact polygon coverage per pixel. See ref.h for the methods and their error
 * bounds. Speed is secondary to being obviously right; the only concession is
 * bucketing edges by pixel row.
 */
#include "ref.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void *ref_alloc(size_t n, size_t size)
{
    void *p = calloc(n ? n : 1, size);
    if (!p) {
        fprintf(stderr, "ref: out of memory\n");
        exit(2);
    }
    return p;
}

static void *ref_grow(void *p, size_t n, size_t size)
{
    void *q = realloc(p, (n ? n : 1) * size);
    if (!q) {
        fprintf(stderr, "ref: out of memory\n");
        exit(2);
    }
    return q;
}

/* ------------------------------------------------------------ contours */

/* Private per-contour prefix sums of the knot intervals, parallel to contours[]. */
typedef struct ref_contour_x {
    long double *prefix; /* prefix[m] = t(m) for 0 <= m <= N */
} ref_contour_x;

ref_region *ref_region_new(int evenodd)
{
    ref_region *r = ref_alloc(1, sizeof *r);
    r->evenodd = evenodd;
    return r;
}

static void ref_poly_free(ref_poly *p)
{
    free(p->start);
    free(p->x);
    free(p->y);
    memset(p, 0, sizeof *p);
}

void ref_region_free(ref_region *r)
{
    if (!r)
        return;
    for (int i = 0; i < r->contour_count; i++) {
        ref_contour *c = &r->contours[i];
        free(c->x);
        free(c->y);
        free(c->w);
        free(c->iv);
    }
    ref_poly_free(&r->poly);
    free(r);
}

int ref_region_add(ref_region *r, int degree, int count, const float *xyw, const float *intervals)
{
    if (r->contour_count >= REF_MAX_CONTOURS || count <= 0)
        return -1;
    ref_contour *c = &r->contours[r->contour_count];
    c->degree = degree;
    c->count = count;
    c->x = ref_alloc((size_t)count, sizeof *c->x);
    c->y = ref_alloc((size_t)count, sizeof *c->y);
    c->w = ref_alloc((size_t)count, sizeof *c->w);
    /* iv holds N intervals followed by N+1 prefix sums (the knots t(0..N)). */
    c->iv = ref_alloc((size_t)(2 * count + 1), sizeof *c->iv);
    for (int k = 0; k < count; k++) {
        c->x[k] = (long double)xyw[3 * k];
        c->y[k] = (long double)xyw[3 * k + 1];
        c->w[k] = (long double)xyw[3 * k + 2];
        c->iv[k] = intervals ? (long double)intervals[k] : 1.0L;
    }
    long double *prefix = c->iv + count;
    prefix[0] = 0;
    for (int k = 0; k < count; k++)
        prefix[k + 1] = prefix[k] + c->iv[k];
    r->flattened = 0;
    return r->contour_count++;
}

void ref_region_transform(ref_region *r, const long double m[6], long double sx, long double sy)
{
    for (int i = 0; i < r->contour_count; i++) {
        ref_contour *c = &r->contours[i];
        for (int k = 0; k < c->count; k++) {
            long double x = c->x[k], y = c->y[k];
            c->x[k] = (m[0] * x + m[2] * y + m[4]) * sx;
            c->y[k] = (m[1] * x + m[3] * y + m[5]) * sy;
        }
    }
    if (r->flattened)
        ref_poly_free(&r->poly);
    r->flattened = 0;
}

long double ref_knot(const ref_contour *c, long k)
{
    long n = c->count;
    long q = k / n, m = k % n;
    if (m < 0) {
        m += n;
        q -= 1;
    }
    const long double *prefix = c->iv + n;
    return (long double)q * prefix[n] + prefix[m];
}

static long ref_mod(long k, long n)
{
    long m = k % n;
    return m < 0 ? m + n : m;
}

void ref_eval_span(const ref_contour *c, int j, long double u, long double out[2])
{
    int p = c->degree;
    if (p < 1 || p > 3) {
        out[0] = out[1] = NAN;
        return;
    }
    long double t = ref_knot(c, j) + u * c->iv[j];
    if (u >= 1.0L)
        t = ref_knot(c, j + 1);
    /* Homogeneous control points j-p .. j: d[i] is point j-p+i. */
    long double dx[4], dy[4], dw[4];
    for (int i = 0; i <= p; i++) {
        long k = ref_mod((long)j - p + i, c->count);
        dw[i] = c->w[k];
        dx[i] = c->x[k] * c->w[k];
        dy[i] = c->y[k] * c->w[k];
    }
    for (int s = 1; s <= p; s++) {
        for (int i = p; i >= s; i--) {
            long idx = (long)j - p + i;
            long double t0 = ref_knot(c, idx), t1 = ref_knot(c, idx + p + 1 - s);
            long double a = (t - t0) / (t1 - t0);
            dx[i] = (1 - a) * dx[i - 1] + a * dx[i];
            dy[i] = (1 - a) * dy[i - 1] + a * dy[i];
            dw[i] = (1 - a) * dw[i - 1] + a * dw[i];
        }
    }
    out[0] = dx[p] / dw[p];
    out[1] = dy[p] / dw[p];
    /* A span whose driving points share a coordinate is exactly constant in it (a horizontal or
     * vertical line, perhaps folding back on itself). Say so exactly: rounding wobble of 1e-18
     * would make a horizontal span cross a scanline laid exactly on it, at random parity. */
    int same_x = 1, same_y = 1;
    for (int i = 1; i <= p; i++) {
        long k0 = ref_mod((long)j - p, c->count), k = ref_mod((long)j - p + i, c->count);
        same_x &= c->x[k] == c->x[k0];
        same_y &= c->y[k] == c->y[k0];
    }
    if (same_x)
        out[0] = c->x[ref_mod((long)j - p, c->count)];
    if (same_y)
        out[1] = c->y[ref_mod((long)j - p, c->count)];
}

/* N(k, q)(t) by the Cox-de Boor recursion, 0/0 taken as 0. */
static long double ref_basis(const ref_contour *c, long k, int q, long double t)
{
    if (q == 0)
        return (ref_knot(c, k) <= t && t < ref_knot(c, k + 1)) ? 1.0L : 0.0L;
    long double tk = ref_knot(c, k), tkq = ref_knot(c, k + q);
    long double tk1 = ref_knot(c, k + 1), tkq1 = ref_knot(c, k + q + 1);
    long double v = 0;
    if (tkq > tk)
        v += (t - tk) / (tkq - tk) * ref_basis(c, k, q - 1, t);
    if (tkq1 > tk1)
        v += (tkq1 - t) / (tkq1 - tk1) * ref_basis(c, k + 1, q - 1, t);
    return v;
}

void ref_eval_basis(const ref_contour *c, int j, long double u, long double out[2])
{
    int p = c->degree;
    long double t = ref_knot(c, j) + u * c->iv[j];
    long double sx = 0, sy = 0, sw = 0;
    /* Every basis function whose support can hold t: a wide window, not just j-p..j. */
    for (long k = (long)j - p - 2; k <= (long)j + 2; k++) {
        long double b = ref_basis(c, k, p, t);
        if (b == 0)
            continue;
        long m = ref_mod(k, c->count);
        sx += b * c->w[m] * c->x[m];
        sy += b * c->w[m] * c->y[m];
        sw += b * c->w[m];
    }
    out[0] = sx / sw;
    out[1] = sy / sw;
}

/* ------------------------------------------------------------ flattening */

typedef struct ref_pbuf {
    long double *x, *y;
    int n, cap;
} ref_pbuf;

static void ref_pbuf_push(ref_pbuf *b, long double x, long double y)
{
    if (b->n == b->cap) {
        b->cap = b->cap ? 2 * b->cap : 1024;
        b->x = ref_grow(b->x, (size_t)b->cap, sizeof *b->x);
        b->y = ref_grow(b->y, (size_t)b->cap, sizeof *b->y);
    }
    b->x[b->n] = x;
    b->y[b->n] = y;
    b->n++;
}

/* Distance from p to the segment a-b. */
static long double ref_seg_dist(long double px, long double py, long double ax, long double ay,
                                long double bx, long double by)
{
    long double dx = bx - ax, dy = by - ay;
    long double len2 = dx * dx + dy * dy;
    long double s = 0;
    if (len2 > 0) {
        s = ((px - ax) * dx + (py - ay) * dy) / len2;
        if (s < 0)
            s = 0;
        if (s > 1)
            s = 1;
    }
    long double ex = ax + s * dx - px, ey = ay + s * dy - py;
    return sqrtl(ex * ex + ey * ey);
}

/* Emits the chord start points of span j on [u0, u1) (u1's point belongs to the next chord). */
static void ref_flatten_span(const ref_contour *c, int j, long double u0, const long double p0[2],
                             long double u1, const long double p1[2], int depth, ref_pbuf *b)
{
    long double um = 0.5L * (u0 + u1), pm[2], q1[2], q3[2];
    ref_eval_span(c, j, um, pm);
    int split = depth < REF_MIN_DEPTH;
    if (!split && depth < 40) {
        ref_eval_span(c, j, 0.5L * (u0 + um), q1);
        ref_eval_span(c, j, 0.5L * (um + u1), q3);
        split = ref_seg_dist(pm[0], pm[1], p0[0], p0[1], p1[0], p1[1]) > REF_FLAT_TOL ||
                ref_seg_dist(q1[0], q1[1], p0[0], p0[1], p1[0], p1[1]) > REF_FLAT_TOL ||
                ref_seg_dist(q3[0], q3[1], p0[0], p0[1], p1[0], p1[1]) > REF_FLAT_TOL;
    }
    if (split) {
        ref_flatten_span(c, j, u0, p0, um, pm, depth + 1, b);
        ref_flatten_span(c, j, um, pm, u1, p1, depth + 1, b);
    } else {
        ref_pbuf_push(b, p0[0], p0[1]);
    }
}

const ref_poly *ref_region_poly(ref_region *r)
{
    if (r->flattened)
        return &r->poly;
    ref_poly *p = &r->poly;
    ref_poly_free(p);
    ref_pbuf b = {0};
    p->contour_count = r->contour_count;
    p->start = ref_alloc((size_t)r->contour_count + 1, sizeof *p->start);
    for (int ci = 0; ci < r->contour_count; ci++) {
        const ref_contour *c = &r->contours[ci];
        p->start[ci] = b.n;
        for (int j = 0; j < c->count; j++) {
            if (!(c->iv[j] > 0))
                continue;
            long double p0[2], p1[2];
            ref_eval_span(c, j, 0, p0);
            ref_eval_span(c, j, 1, p1);
            ref_flatten_span(c, j, 0, p0, 1, p1, 0, &b);
        }
    }
    p->start[r->contour_count] = b.n;
    p->x = b.x;
    p->y = b.y;
    p->total = b.n;
    r->flattened = 1;
    return p;
}

long double ref_poly_signed_area(const ref_poly *p)
{
    long double a = 0;
    for (int ci = 0; ci < p->contour_count; ci++) {
        int s = p->start[ci], e = p->start[ci + 1];
        for (int i = s; i < e; i++) {
            int k = i + 1 < e ? i + 1 : s;
            a += p->x[i] * p->y[k] - p->x[k] * p->y[i];
        }
    }
    return a / 2;
}

/* ---------------------------------------------------------------- edges */

/* A non-horizontal polygon edge with y0 < y1; dir is +1 if the polygon runs down it. */
typedef struct ref_edge {
    long double x0, y0, x1, y1;
    int dir;
} ref_edge;

typedef struct ref_edges {
    ref_edge *e;
    int n;
    int *row_start; /* H+1 offsets into row_idx */
    int *row_idx;   /* edges overlapping the open row (j, j+1) */
} ref_edges;

static void ref_edges_build(ref_region *r, int H, ref_edges *E)
{
    const ref_poly *p = ref_region_poly(r);
    E->e = ref_alloc((size_t)p->total, sizeof *E->e);
    E->n = 0;
    for (int ci = 0; ci < p->contour_count; ci++) {
        int s = p->start[ci], e = p->start[ci + 1];
        for (int i = s; i < e; i++) {
            int k = i + 1 < e ? i + 1 : s;
            long double ax = p->x[i], ay = p->y[i], bx = p->x[k], by = p->y[k];
            if (ay == by)
                continue;
            ref_edge *ed = &E->e[E->n++];
            if (ay < by) {
                *ed = (ref_edge){ax, ay, bx, by, +1};
            } else {
                *ed = (ref_edge){bx, by, ax, ay, -1};
            }
        }
    }
    E->row_start = ref_alloc((size_t)H + 1, sizeof *E->row_start);
    int *cnt = ref_alloc((size_t)H + 1, sizeof *cnt);
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1) {
            int total = 0;
            for (int j = 0; j < H; j++) {
                E->row_start[j] = total;
                total += cnt[j];
                cnt[j] = 0;
            }
            E->row_start[H] = total;
            E->row_idx = ref_alloc((size_t)total, sizeof *E->row_idx);
        }
        for (int i = 0; i < E->n; i++) {
            const ref_edge *ed = &E->e[i];
            if (ed->y1 <= 0 || ed->y0 >= H)
                continue;
            long double lo = floorl(ed->y0), hi = ceill(ed->y1) - 1;
            int jlo = lo < 0 ? 0 : (int)lo;
            int jhi = hi > H - 1 ? H - 1 : (int)hi;
            for (int j = jlo; j <= jhi; j++) {
                if (pass == 0)
                    cnt[j]++;
                else
                    E->row_idx[E->row_start[j] + cnt[j]++] = i;
            }
        }
    }
    free(cnt);
}

static void ref_edges_free(ref_edges *E)
{
    free(E->e);
    free(E->row_start);
    free(E->row_idx);
}

static long double ref_edge_x(const ref_edge *e, long double y)
{
    return e->x0 + (e->x1 - e->x0) * ((y - e->y0) / (e->y1 - e->y0));
}

static int ref_inside(int evenodd, int winding)
{
    return evenodd ? (winding & 1) : (winding != 0);
}

/* --------------------------------------------------------- cell accumulation */

/* One pixel row being accumulated: cell[c] plus the prefix sum of cover[0..c]. */
typedef struct ref_row {
    int W;
    long double *cell, *cover;
} ref_row;

/* G(x) = integral from c to x of clamp(c+1-x', 0, 1) dx', as a function of s = x - c. */
static long double ref_G(long double s)
{
    if (s <= 0)
        return s;
    if (s >= 1)
        return 0.5L;
    return s - 0.5L * s * s;
}

/*
 * Adds sign * (area right of the straight edge from (xa, ya) to (xb, yb),
 * within the strip of height h) to every pixel column: column c receives
 * h * mean over the edge of clamp(c+1-x, 0, 1).
 */
static void ref_row_add(ref_row *row, int sign, long double xa, long double xb, long double h)
{
    long double x0 = xa < xb ? xa : xb, x1 = xa < xb ? xb : xa;
    int W = row->W;
    if (x0 >= W)
        return;
    if (x1 <= 0) {
        row->cover[0] += sign * h;
        return;
    }
    long double f0 = floorl(x0), f1 = floorl(x1);
    int c0 = f0 < 0 ? 0 : (int)f0;
    int c1 = f1 > W - 1 ? W - 1 : (int)f1;
    long double dx = x1 - x0;
    for (int c = c0; c <= c1; c++) {
        long double mean;
        if (dx < 1e-12L) {
            long double g = c + 1 - 0.5L * (x0 + x1);
            mean = g < 0 ? 0 : (g > 1 ? 1 : g);
        } else {
            mean = (ref_G(x1 - c) - ref_G(x0 - c)) / dx;
        }
        row->cell[c] += sign * h * mean;
    }
    if (f1 + 1 <= W - 1)
        row->cover[(int)f1 + 1] += sign * h;
}

static void ref_row_flush(ref_row *row, double *out)
{
    long double run = 0;
    for (int c = 0; c < row->W; c++) {
        run += row->cover[c];
        long double v = run + row->cell[c];
        if (v < 0)
            v = 0;
        if (v > 1)
            v = 1;
        out[c] = (double)v;
        row->cell[c] = 0;
        row->cover[c] = 0;
    }
    row->cover[row->W] = 0;
}

/* ------------------------------------------------------------ exact area */

typedef struct ref_active {
    long double xa, xb, xm;
    int dir;
} ref_active;

static int ref_cmp_active(const void *pa, const void *pb)
{
    const ref_active *a = pa, *b = pb;
    if (a->xm < b->xm)
        return -1;
    if (a->xm > b->xm)
        return 1;
    long double sa = a->xa + a->xb, sb = b->xa + b->xb;
    return (sa > sb) - (sa < sb);
}

static int ref_cmp_ld(const void *pa, const void *pb)
{
    long double a = *(const long double *)pa, b = *(const long double *)pb;
    return (a > b) - (a < b);
}

typedef struct ref_strip_ctx {
    const ref_edges *E;
    const int *list;
    int list_n;
    int evenodd;
    ref_row *row;
    ref_active *act;
    long double *ys;
    size_t ys_cap;
} ref_strip_ctx;

static void ref_strip(ref_strip_ctx *ctx, long double ya, long double yb, int may_split)
{
    long double h = yb - ya;
    if (!(h > 0))
        return;
    long double ym = 0.5L * (ya + yb);
    int n = 0;
    for (int i = 0; i < ctx->list_n; i++) {
        const ref_edge *e = &ctx->E->e[ctx->list[i]];
        if (e->y0 <= ya && e->y1 >= yb) {
            ref_active *a = &ctx->act[n++];
            a->xa = ref_edge_x(e, ya);
            a->xb = ref_edge_x(e, yb);
            a->xm = ref_edge_x(e, ym);
            a->dir = e->dir;
        }
    }
    if (n == 0)
        return;
    qsort(ctx->act, (size_t)n, sizeof *ctx->act, ref_cmp_active);
    int sorted = 1;
    for (int i = 0; i + 1 < n && sorted; i++) {
        long double tol = 1e-13L * (1 + fabsl(ctx->act[i].xm));
        if (ctx->act[i].xa > ctx->act[i + 1].xa + tol || ctx->act[i].xb > ctx->act[i + 1].xb + tol)
            sorted = 0;
    }
    if (!sorted && may_split) {
        /* Edges cross inside the strip: cut it at every crossing and start again. */
        ref_active *copy = ref_alloc((size_t)n, sizeof *copy);
        memcpy(copy, ctx->act, (size_t)n * sizeof *copy);
        size_t ny = 0, cap = 64;
        long double *ys = ref_alloc(cap, sizeof *ys);
        for (int i = 0; i < n; i++) {
            for (int k = i + 1; k < n; k++) {
                long double da = copy[i].xa - copy[k].xa, db = copy[i].xb - copy[k].xb;
                if ((da < 0 && db > 0) || (da > 0 && db < 0)) {
                    long double y = ya + h * (da / (da - db));
                    if (y > ya && y < yb) {
                        if (ny == cap) {
                            cap *= 2;
                            ys = ref_grow(ys, cap, sizeof *ys);
                        }
                        ys[ny++] = y;
                    }
                }
            }
        }
        free(copy);
        qsort(ys, ny, sizeof *ys, ref_cmp_ld);
        long double prev = ya;
        for (size_t i = 0; i <= ny; i++) {
            long double next = i < ny ? ys[i] : yb;
            if (next > prev) {
                ref_strip(ctx, prev, next, 0);
                prev = next;
            }
        }
        free(ys);
        return;
    }
    int w = 0;
    for (int i = 0; i < n; i++) {
        int was = ref_inside(ctx->evenodd, w);
        w += ctx->act[i].dir;
        int now = ref_inside(ctx->evenodd, w);
        if (!was && now)
            ref_row_add(ctx->row, +1, ctx->act[i].xa, ctx->act[i].xb, h);
        else if (was && !now)
            ref_row_add(ctx->row, -1, ctx->act[i].xa, ctx->act[i].xb, h);
    }
}

void ref_coverage_area(ref_region *r, int W, int H, double *out)
{
    ref_edges E;
    ref_edges_build(r, H, &E);
    ref_row row = {W, ref_alloc((size_t)W, sizeof(long double)),
                   ref_alloc((size_t)W + 1, sizeof(long double))};
    ref_strip_ctx ctx = {0};
    ctx.E = &E;
    ctx.evenodd = r->evenodd;
    ctx.row = &row;
    ctx.act = ref_alloc((size_t)E.n + 1, sizeof *ctx.act);
    long double *ev = ref_alloc(2 * (size_t)E.n + 2, sizeof *ev);
    for (int j = 0; j < H; j++) {
        ctx.list = E.row_idx + E.row_start[j];
        ctx.list_n = E.row_start[j + 1] - E.row_start[j];
        int ne = 0;
        ev[ne++] = j;
        ev[ne++] = j + 1;
        for (int i = 0; i < ctx.list_n; i++) {
            const ref_edge *e = &E.e[ctx.list[i]];
            if (e->y0 > j && e->y0 < j + 1)
                ev[ne++] = e->y0;
            if (e->y1 > j && e->y1 < j + 1)
                ev[ne++] = e->y1;
        }
        qsort(ev, (size_t)ne, sizeof *ev, ref_cmp_ld);
        for (int k = 0; k + 1 < ne; k++)
            if (ev[k + 1] > ev[k])
                ref_strip(&ctx, ev[k], ev[k + 1], 1);
        ref_row_flush(&row, out + (size_t)j * W);
    }
    free(ev);
    free(ctx.act);
    free(row.cell);
    free(row.cover);
    ref_edges_free(&E);
}

/* ------------------------------------------------------- sub-scanlines */

typedef struct ref_cross {
    long double x;
    int dir;
} ref_cross;

static int ref_cmp_cross(const void *pa, const void *pb)
{
    const ref_cross *a = pa, *b = pb;
    return (a->x > b->x) - (a->x < b->x);
}

/* Crossings of row j's edges with the line at y (half-open: y0 <= y < y1), sorted. */
static int ref_crossings(const ref_edges *E, int j, long double y, ref_cross *cr)
{
    int n = 0;
    for (int i = E->row_start[j]; i < E->row_start[j + 1]; i++) {
        const ref_edge *e = &E->e[E->row_idx[i]];
        if (e->y0 <= y && y < e->y1) {
            cr[n].x = ref_edge_x(e, y);
            cr[n].dir = e->dir;
            n++;
        }
    }
    qsort(cr, (size_t)n, sizeof *cr, ref_cmp_cross);
    return n;
}

void ref_coverage_subscan(ref_region *r, int W, int H, int nsub, double *out)
{
    ref_edges E;
    ref_edges_build(r, H, &E);
    ref_row row = {W, ref_alloc((size_t)W, sizeof(long double)),
                   ref_alloc((size_t)W + 1, sizeof(long double))};
    ref_cross *cr = ref_alloc((size_t)E.n + 1, sizeof *cr);
    long double h = 1.0L / nsub;
    for (int j = 0; j < H; j++) {
        for (int k = 0; k < nsub; k++) {
            long double y = j + (k + 0.5L) * h;
            int n = ref_crossings(&E, j, y, cr);
            int w = 0;
            long double xl = 0;
            for (int i = 0; i < n; i++) {
                int was = ref_inside(r->evenodd, w);
                w += cr[i].dir;
                int now = ref_inside(r->evenodd, w);
                if (!was && now)
                    xl = cr[i].x;
                else if (was && !now) {
                    ref_row_add(&row, +1, xl, xl, h);
                    ref_row_add(&row, -1, cr[i].x, cr[i].x, h);
                }
            }
        }
        ref_row_flush(&row, out + (size_t)j * W);
    }
    free(cr);
    free(row.cell);
    free(row.cover);
    ref_edges_free(&E);
}

/* --------------------------------------------------------- pixel centres */

void ref_coverage_centre(ref_region *r, int W, int H, double eps, unsigned char *inside,
                         unsigned char *ambiguous)
{
    ref_edges E;
    ref_edges_build(r, H, &E);
    ref_cross *cr = ref_alloc((size_t)E.n + 1, sizeof *cr);
    for (int j = 0; j < H; j++) {
        long double y = j + 0.5L;
        int n = ref_crossings(&E, j, y, cr);
        int w = 0, k = 0;
        for (int i = 0; i < W; i++) {
            long double x = i + 0.5L;
            while (k < n && cr[k].x < x)
                w += cr[k++].dir;
            inside[(size_t)j * W + i] = (unsigned char)ref_inside(r->evenodd, w);
        }
    }
    free(cr);
    ref_edges_free(&E);
    if (!ambiguous)
        return;
    memset(ambiguous, 0, (size_t)W * H);
    const ref_poly *p = ref_region_poly(r);
    long double e = (long double)eps;
    for (int ci = 0; ci < p->contour_count; ci++) {
        int s = p->start[ci], end = p->start[ci + 1];
        for (int a = s; a < end; a++) {
            int b = a + 1 < end ? a + 1 : s;
            long double ax = p->x[a], ay = p->y[a], bx = p->x[b], by = p->y[b];
            long double xmin = fminl(ax, bx) - e, xmax = fmaxl(ax, bx) + e;
            long double ymin = fminl(ay, by) - e, ymax = fmaxl(ay, by) + e;
            /* Pixel centres (i+0.5, j+0.5) inside the box. */
            long double jl = ceill(ymin - 0.5L), jh = floorl(ymax - 0.5L);
            long double il = ceill(xmin - 0.5L), ih = floorl(xmax - 0.5L);
            if (jh < 0 || jl > H - 1 || ih < 0 || il > W - 1)
                continue;
            int j0 = jl < 0 ? 0 : (int)jl, j1 = jh > H - 1 ? H - 1 : (int)jh;
            int i0 = il < 0 ? 0 : (int)il, i1 = ih > W - 1 ? W - 1 : (int)ih;
            for (int j = j0; j <= j1; j++)
                for (int i = i0; i <= i1; i++)
                    if (ref_seg_dist(i + 0.5L, j + 0.5L, ax, ay, bx, by) < e)
                        ambiguous[(size_t)j * W + i] = 1;
        }
    }
}

int ref_winding(ref_region *r, long double x, long double y)
{
    const ref_poly *p = ref_region_poly(r);
    int w = 0;
    for (int ci = 0; ci < p->contour_count; ci++) {
        int s = p->start[ci], e = p->start[ci + 1];
        for (int a = s; a < e; a++) {
            int b = a + 1 < e ? a + 1 : s;
            long double ay = p->y[a], by = p->y[b];
            if (ay == by)
                continue;
            int dir = ay < by ? 1 : -1;
            long double y0 = dir > 0 ? ay : by, y1 = dir > 0 ? by : ay;
            if (y0 <= y && y < y1) {
                long double xc = p->x[a] + (p->x[b] - p->x[a]) * ((y - ay) / (by - ay));
                if (xc < x)
                    w += dir;
            }
        }
    }
    return w;
}
