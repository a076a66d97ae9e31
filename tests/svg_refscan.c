/*
 * svg_refscan.c - the reference polygon scanner (see svg_refscan.h).
 *
 * Deliberately simple and slow: every sub-scanline intersects every edge
 * whose y range holds it (edges sorted by top, an active list), sorts the
 * crossings, walks them with a winding count and adds each inside span's
 * exact length to the pixels it covers. Nothing is shared with the core.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "svg_refscan.h"

void ref_init(ref_raster *r, int w, int h)
{
    memset(r, 0, sizeof *r);
    r->w = w;
    r->h = h;
}

void ref_free(ref_raster *r)
{
    free(r->e);
    memset(r, 0, sizeof *r);
}

void ref_add_poly(ref_raster *r, const long double *xy, int n)
{
    for (int i = 0; i < n; i++) {
        long double x0 = xy[2 * i], y0 = xy[2 * i + 1];
        long double x1 = xy[2 * ((i + 1) % n)], y1 = xy[2 * ((i + 1) % n) + 1];
        if (y0 == y1)
            continue;
        if (r->n == r->cap) {
            r->cap = r->cap ? 2 * r->cap : 1024;
            r->e = realloc(r->e, (size_t)r->cap * sizeof *r->e);
        }
        ref_edge *e = &r->e[r->n++];
        if (y0 < y1) {
            *e = (ref_edge){x0, y0, x1, y1, 1};
        } else {
            *e = (ref_edge){x1, y1, x0, y0, -1};
        }
    }
}

static int cmp_top(const void *a, const void *b)
{
    long double ya = ((const ref_edge *)a)->y0, yb = ((const ref_edge *)b)->y0;
    return ya < yb ? -1 : ya > yb;
}

/* Adds [xa, xb) with weight w to row accumulators (pixel = unit interval). */
static void add_span(long double *row, int w, long double xa, long double xb, long double wt)
{
    if (xa < 0)
        xa = 0;
    if (xb > w)
        xb = w;
    if (!(xb > xa))
        return;
    /* floor of values >= 0, exactly: truncate through double, then step
     * back where rounding to double went up to the next integer. (Inline x87
     * floorl, which switches the control word twice per call, ran this
     * loop 3x slower or faster depending on where the linker placed it.) */
    int ia = (int)(double)xa, ib = (int)(double)xb;
    if (ia > xa)
        ia--;
    if (ib > xb)
        ib--;
    if (ib >= w)
        ib = w - 1;
    if (ia == ib) {
        row[ia] += wt * (xb - xa);
        return;
    }
    row[ia] += wt * ((long double)(ia + 1) - xa);
    for (int i = ia + 1; i < ib; i++)
        row[i] += wt;
    row[ib] += wt * (xb - (long double)ib);
}

void ref_render(const ref_raster *r, int subs, double *cov)
{
    ref_edge *e = malloc((size_t)(r->n ? r->n : 1) * sizeof *e);
    memcpy(e, r->e, (size_t)r->n * sizeof *e);
    qsort(e, (size_t)r->n, sizeof *e, cmp_top);
    /* active edges with their crossing x, kept in x order between sub-scanlines
     * (the order barely changes, so insertion sort costs almost nothing) */
    int *act = malloc((size_t)(r->n ? r->n : 1) * sizeof *act);
    long double *ax = malloc((size_t)(r->n ? r->n : 1) * sizeof *ax);
    long double *row = malloc((size_t)r->w * sizeof *row);
    int nact = 0, next = 0;
    long double wt = 1.0L / subs;
    for (int y = 0; y < r->h; y++) {
        for (int i = 0; i < r->w; i++)
            row[i] = 0;
        for (int k = 0; k < subs; k++) {
            long double ys = y + (k + 0.5L) * wt;
            while (next < r->n && e[next].y0 <= ys)
                act[nact++] = next++;
            int keep = 0;
            for (int i = 0; i < nact; i++) {
                const ref_edge *g = &e[act[i]];
                if (g->y1 <= ys)
                    continue; /* finished for good: sub-scanlines only go down */
                long double t = (ys - g->y0) / (g->y1 - g->y0);
                ax[keep] = g->x0 + t * (g->x1 - g->x0);
                act[keep++] = act[i];
            }
            nact = keep;
            for (int i = 1; i < nact; i++) {
                long double x = ax[i];
                int a = act[i], j = i;
                while (j > 0 && ax[j - 1] > x) {
                    ax[j] = ax[j - 1];
                    act[j] = act[j - 1];
                    j--;
                }
                ax[j] = x;
                act[j] = a;
            }
            int wind = 0;
            for (int i = 0; i + 1 < nact; i++) {
                wind += e[act[i]].dir;
                if (wind != 0)
                    add_span(row, r->w, ax[i], ax[i + 1], wt);
            }
        }
        for (int i = 0; i < r->w; i++)
            cov[(size_t)y * r->w + i] = (double)row[i];
    }
    free(e);
    free(act);
    free(ax);
    free(row);
}
