/*
 * sv_bands.c - a gradient as solid bands with exact geometry, the fallback
 * for gradients the core's paint functions cannot draw (sv_plan.c).
 *
 * The IR keeps a gradient-filled region whole, with its gradient; this file
 * adds the fallback the back ends use meanwhile. The gradient parameter t
 * is cut into bands where the colour changes by at most 4/255 per band
 * (boundaries at equal steps of the colour's total variation, so bands
 * crowd where the colour changes fast), each painted with its mean colour.
 *
 *  - Linear: t is an affine function of the canvas point, so a band is the
 *    region clipped to a strip between two parallel lines - two exact
 *    half-plane clips (sv_clip.c). Bands are disjoint and abut exactly,
 *    and since they share a cel the core's coverage sum leaves no seam.
 *  - Radial: the sets t <= t_k are nested discs (while the focal point is
 *    inside the end circle). With S_k the region clipped to disc k (a
 *    32-gon in gradient space mapped to canvas units, still convex), ring k
 *    is S_k+1 together with the reversed contours of S_k under the region's
 *    own fill rule: inside disc k both clipped copies carry the region's
 *    winding number, so the reversed one cancels it exactly, and outside
 *    disc k the inner copy winds zero. The polygon moves a band boundary by
 *    0.5% of its radius: a colour step, never an edge of the artwork.
 *
 * Outside [0,1] the spread method decides the colour, so pad gives two
 * constant end bands and reflect/repeat keep banding.
 */
#include <math.h>

#include "sv_gradient.h"
#include "sv_internal.h"

#define MAX_BANDS 32
#define STEP 4.0 /* largest colour change per band, in 1/255 of sRGB: error <= 2/255 */
#define DISC_SIDES 32

/* Gradient parameter of a canvas point, before the spread method. */
static double t_at(const sv_gradient *g, sv_affine inv, sv_pt q)
{
    sv_pt p = sv_affine_apply(inv, q);
    if (g->type == SV_GRAD_LINEAR) {
        double dx = g->x2 - g->x1, dy = g->y2 - g->y1, l2 = dx * dx + dy * dy;
        return ((p.x - g->x1) * dx + (p.y - g->y1) * dy) / l2;
    }
    double cdx = g->cx - g->fx, cdy = g->cy - g->fy, dr = g->r - g->fr;
    double px = p.x - g->fx, py = p.y - g->fy;
    double a = cdx * cdx + cdy * cdy - dr * dr, b = px * cdx + py * cdy + g->fr * dr;
    double c = px * px + py * py - g->fr * g->fr;
    if (fabs(a) < 1e-12 * (g->r * g->r))
        return b != 0 ? c / (2 * b) : 0;
    double disc = b * b - a * c;
    if (disc < 0)
        return 0;
    double s = sqrt(disc);
    return fmax((b + s) / a, (b - s) / a);
}

static void add_band(sv_region *parent, sv_path *geo, const double rgb[3], double alpha,
                     double opacity)
{
    sv_region b;
    memset(&b, 0, sizeof b);
    sv_path_to_contours(geo, &b.contours, &b.ncontours);
    if (b.ncontours == 0 || !(alpha * opacity > 0)) { /* bands are disjoint: skip clear ones */
        for (int i = 0; i < b.ncontours; i++)
            sv_contour_free(&b.contours[i]);
        free(b.contours);
        return;
    }
    b.fill_rule = parent->fill_rule;
    memcpy(b.paint.pigment, rgb, 3 * sizeof(double));
    b.paint.medium[0] = b.paint.medium[1] = b.paint.medium[2] = 1;
    b.paint.beta = fmin(1, alpha * opacity);
    b.paint.gradient = parent->paint.gradient;
    b.clip = parent->clip;
    memcpy(b.bbox, parent->bbox, sizeof b.bbox);
    parent->bands = sv_xrealloc(parent->bands, (size_t)(parent->nbands + 1) * sizeof b);
    parent->bands[parent->nbands++] = b;
}

/* Clips p to the disc of parameter t (empty if its radius is not positive). */
static void clip_disc(const sv_gradient *g, double t, sv_path *p)
{
    double cx = g->fx + t * (g->cx - g->fx), cy = g->fy + t * (g->cy - g->fy);
    double rad = g->fr + t * (g->r - g->fr);
    if (!(rad > 0)) {
        sv_path_free(p);
        return;
    }
    sv_pt poly[DISC_SIDES];
    for (int i = 0; i < DISC_SIDES; i++) {
        double a = 2 * M_PI * i / DISC_SIDES;
        poly[i] = sv_affine_apply(g->transform, sv_pt_make(cx + rad * cos(a), cy + rad * sin(a)));
    }
    sv_path_clip_polygon(p, poly, DISC_SIDES);
}

static void build(const sv_gradient *g, const sv_path *area, double opacity, sv_region *r,
                  sv_affine inv, double t0, double t1, const double *cum, double var, int n);

bool sv_gradient_bands(const sv_gradient *g, const sv_path *area, double opacity, sv_region *r,
                       long *work)
{
    sv_affine inv;
    if (g->nstops < 2 || !sv_affine_invert(g->transform, &inv))
        return true;
    if (g->type == SV_GRAD_LINEAR &&
        !((g->x2 - g->x1) * (g->x2 - g->x1) + (g->y2 - g->y1) * (g->y2 - g->y1) > 0))
        return true;
    if (g->type == SV_GRAD_RADIAL) {
        /* nested discs need the focal circle inside the end circle */
        double d = hypot(g->fx - g->cx, g->fy - g->cy);
        if (!(g->r > 0) || d + g->fr >= g->r)
            return true;
    }
    /* the most segment clips it can take: every band clips the area (a disc: each side,
     * for two discs), and the halving below builds at most twice */
    long segs = 0;
    for (int i = 0; i < area->n; i++)
        segs += area->sub[i].n;
    long cost = segs * MAX_BANDS * 2 * (g->type == SV_GRAD_RADIAL ? 2 * DISC_SIDES : 2);
    if (cost > *work)
        return false;
    *work -= cost;
    /* the range of t over the region's box */
    double box[4];
    sv_path_bbox(area, box);
    double t0 = INFINITY, t1 = -INFINITY;
    for (int j = 0; j <= 32; j++)
        for (int i = 0; i <= 32; i++) {
            double t = t_at(g, inv, sv_pt_make(box[0] + (box[2] - box[0]) * i / 32,
                                               box[1] + (box[3] - box[1]) * j / 32));
            t0 = fmin(t0, t);
            t1 = fmax(t1, t);
        }
    if (g->type == SV_GRAD_RADIAL)
        t0 = fmax(t0, 0);
    if (!(t1 > t0))
        return true;
    /* colour variation along t, to place the band boundaries */
    enum { S = 1024 };
    double cum[S + 1], prev[4], var = 0;
    for (int i = 0; i <= S; i++) {
        double c[3], a;
        sv_gradient_color_at(g, t0 + (t1 - t0) * i / S, c, &a);
        double cur[4] = {c[0] * 255, c[1] * 255, c[2] * 255, a * 255 * opacity};
        if (i > 0) {
            double d = 0;
            for (int k = 0; k < 4; k++)
                d = fmax(d, fabs(cur[k] - prev[k]));
            var += d;
        }
        cum[i] = var;
        memcpy(prev, cur, sizeof prev);
    }
    int n = (int)ceil(var / STEP);
    if (n > MAX_BANDS)
        n = MAX_BANDS;
    size_t base = 0;
    for (int i = 0; i < area->n; i++)
        base += (size_t)area->sub[i].n * 3;
    size_t budget = base * 6 > 1500 ? base * 6 : 1500;
    for (; n >= 2; n /= 2) { /* fewer, wider bands while the points exceed the budget */
        build(g, area, opacity, r, inv, t0, t1, cum, var, n);
        size_t pts = 0;
        for (int b = 0; b < r->nbands; b++)
            for (int k = 0; k < r->bands[b].ncontours; k++)
                pts += (size_t)r->bands[b].contours[k].count;
        if (pts <= budget)
            return true;
        for (int b = 0; b < r->nbands; b++) {
            for (int k = 0; k < r->bands[b].ncontours; k++)
                sv_contour_free(&r->bands[b].contours[k]);
            free(r->bands[b].contours);
        }
        free(r->bands);
        r->bands = NULL;
        r->nbands = 0;
    }
    return true;
}

/* The n bands of t in [t0, t1] placed by the cumulative colour variation. */
static void build(const sv_gradient *g, const sv_path *area, double opacity, sv_region *r,
                  sv_affine inv, double t0, double t1, const double *cum, double var, int n)
{
    enum { S = 1024 };
    double bound[MAX_BANDS + 1];
    bound[0] = t0;
    bound[n] = t1;
    for (int k = 1, i = 0; k < n; k++) {
        while (i < S && cum[i + 1] < var * k / n)
            i++;
        bound[k] = t0 + (t1 - t0) * (i + 0.5) / S;
    }
    for (int k = 0; k < n; k++) {
        /* the band's mean colour (opacity-weighted) over its t interval */
        double sum[3] = {0, 0, 0}, asum = 0;
        for (int i = 0; i < 16; i++) {
            double c[3], a;
            sv_gradient_color_at(g, bound[k] + (bound[k + 1] - bound[k]) * (i + 0.5) / 16, c, &a);
            for (int m = 0; m < 3; m++)
                sum[m] += a * c[m];
            asum += a;
        }
        double rgb[3] = {0, 0, 0};
        if (asum > 0)
            for (int m = 0; m < 3; m++)
                rgb[m] = sum[m] / asum;
        sv_path geo;
        sv_path_init(&geo);
        sv_path_append(&geo, area);
        if (g->type == SV_GRAD_LINEAR) {
            /* t(q) = ta x + tb y + tc on the canvas */
            double dx = g->x2 - g->x1, dy = g->y2 - g->y1, l2 = dx * dx + dy * dy;
            double ta = (inv.a * dx + inv.b * dy) / l2, tb = (inv.c * dx + inv.d * dy) / l2;
            double tc = ((inv.e - g->x1) * dx + (inv.f - g->y1) * dy) / l2;
            if (k > 0)
                sv_path_clip_halfplane(&geo, ta, tb, tc - bound[k]);
            if (k + 1 < n)
                sv_path_clip_halfplane(&geo, -ta, -tb, bound[k + 1] - tc);
            add_band(r, &geo, rgb, asum / 16, opacity);
        } else {
            /* ring k: S_k+1 and S_k reversed */
            if (k + 1 < n)
                clip_disc(g, bound[k + 1], &geo);
            if (k > 0) {
                sv_path inner;
                sv_path_init(&inner);
                sv_path_append(&inner, area);
                clip_disc(g, bound[k], &inner);
                sv_path_reverse(&inner);
                sv_path_append(&geo, &inner);
                sv_path_free(&inner);
            }
            add_band(r, &geo, rgb, asum / 16, opacity);
        }
        sv_path_free(&geo);
    }
}
