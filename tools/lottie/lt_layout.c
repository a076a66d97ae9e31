/*
 * lt_layout.c - one control-point layout for a shape's every frame.
 *
 * A points track keeps a contour's degree and point count, but a stroke's
 * outline (its offset curves are subdivided to a tolerance that depends on
 * the width and the curvature) or a trimmed path (whose cut moves across
 * vertices) changes its layout from frame to frame. Such frames are brought
 * to a common layout without changing their shapes: every contour takes the
 * highest degree and segment count it has in any frame, its segments are
 * raised to that degree (exact, in homogeneous coordinates) and the longest
 * are halved (exact de Casteljau) until the count is reached; a contour
 * missing in a frame is a point, which covers nothing. Contours are Bezier
 * form, one segment per `degree` points with knot intervals 1, 0, ..., 0,
 * as sv_path_to_contours and lt_fixed_contours make them.
 */
#include <stdlib.h>
#include <string.h>

#include "../svg/sv_internal.h"
#include "lt_internal.h"

typedef struct hseg {
    int d;
    double p[4][3]; /* homogeneous X Y W */
} hseg;

static void seg_of(const sv_contour *c, int j, hseg *s)
{
    s->d = c->degree;
    for (int m = 0; m <= c->degree; m++) {
        const double *q = &c->pts[3 * ((j * c->degree + m) % c->count)];
        s->p[m][0] = q[0] * q[2];
        s->p[m][1] = q[1] * q[2];
        s->p[m][2] = q[2];
    }
}

static void elevate(hseg *s, int degree)
{
    while (s->d < degree) {
        double q[4][3];
        int d = s->d;
        for (int i = 0; i <= d + 1; i++)
            for (int k = 0; k < 3; k++) {
                double a = (double)i / (d + 1);
                q[i][k] = (i > 0 ? a * s->p[i - 1][k] : 0) + (i <= d ? (1 - a) * s->p[i][k] : 0);
            }
        memcpy(s->p, q, sizeof q);
        s->d++;
    }
}

static void halve(const hseg *s, hseg *a, hseg *b)
{
    double t[4][4][3];
    int d = s->d;
    memcpy(t[0], s->p, sizeof t[0]);
    for (int r = 1; r <= d; r++)
        for (int i = 0; i + r <= d; i++)
            for (int k = 0; k < 3; k++)
                t[r][i][k] = 0.5 * (t[r - 1][i][k] + t[r - 1][i + 1][k]);
    a->d = b->d = d;
    for (int i = 0; i <= d; i++)
        for (int k = 0; k < 3; k++) {
            a->p[i][k] = t[i][0][k];
            b->p[i][k] = t[d - i][i][k];
        }
}

static double chord(const hseg *s)
{
    double dx = s->p[s->d][0] / s->p[s->d][2] - s->p[0][0] / s->p[0][2];
    double dy = s->p[s->d][1] / s->p[s->d][2] - s->p[0][1] / s->p[0][2];
    return dx * dx + dy * dy;
}

/* Contour c rewritten as `nseg` segments of `degree` into out. */
static void relayout(const sv_contour *c, int degree, int nseg, sv_contour *out, const double *pt)
{
    out->degree = degree;
    out->count = nseg * degree;
    out->pts = sv_xrealloc(NULL, (size_t)out->count * 3 * sizeof(double));
    out->intervals = sv_xrealloc(NULL, (size_t)out->count * sizeof(double));
    for (int i = 0; i < out->count; i++)
        out->intervals[i] = i % degree == 0 ? 1.0 : 0.0;
    if (!c) {
        for (int i = 0; i < out->count; i++) {
            out->pts[3 * i] = pt[0];
            out->pts[3 * i + 1] = pt[1];
            out->pts[3 * i + 2] = 1;
        }
        return;
    }
    int n = c->count / c->degree;
    hseg *segs = sv_xrealloc(NULL, (size_t)nseg * sizeof *segs);
    for (int j = 0; j < n; j++) {
        seg_of(c, j, &segs[j]);
        elevate(&segs[j], degree);
    }
    while (n < nseg) {
        int best = 0;
        for (int j = 1; j < n; j++)
            if (chord(&segs[j]) > chord(&segs[best]))
                best = j;
        memmove(&segs[best + 2], &segs[best + 1], (size_t)(n - best - 1) * sizeof *segs);
        hseg a, b;
        halve(&segs[best], &a, &b);
        segs[best] = a;
        segs[best + 1] = b;
        n++;
    }
    for (int j = 0; j < nseg; j++)
        for (int m = 0; m < degree; m++) {
            double *q = &out->pts[3 * (j * degree + m)];
            q[2] = segs[j].p[m][2];
            q[0] = segs[j].p[m][0] / q[2];
            q[1] = segs[j].p[m][1] / q[2];
        }
    free(segs);
}

void lt_unify_layout(sv_contour **frames, int *counts, int nframes)
{
    int nc = 0;
    for (int n = 0; n < nframes; n++)
        nc = counts[n] > nc ? counts[n] : nc;
    int *deg = calloc((size_t)(nc ? nc : 1), sizeof *deg);
    int *segs = calloc((size_t)(nc ? nc : 1), sizeof *segs);
    if (!deg || !segs) {
        free(deg), free(segs);
        return;
    }
    for (int n = 0; n < nframes; n++)
        for (int i = 0; i < counts[n]; i++) {
            const sv_contour *c = &frames[n][i];
            deg[i] = c->degree > deg[i] ? c->degree : deg[i];
            int s = c->count / c->degree;
            segs[i] = s > segs[i] ? s : segs[i];
        }
    for (int n = 0; n < nframes; n++) {
        sv_contour *out = sv_xrealloc(NULL, (size_t)(nc ? nc : 1) * sizeof *out);
        double pt[2] = {0, 0};
        if (counts[n] > 0)
            pt[0] = frames[n][0].pts[0], pt[1] = frames[n][0].pts[1];
        for (int i = 0; i < nc; i++)
            relayout(i < counts[n] ? &frames[n][i] : NULL, deg[i], segs[i], &out[i], pt);
        lt_free_contours(frames[n], counts[n]);
        frames[n] = out;
        counts[n] = nc;
    }
    free(deg);
    free(segs);
}
