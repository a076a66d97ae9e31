/*
 * beta_common.h - what the beta-model tests share (test_beta, test_cache,
 * test_csg): a scene store and workspace, building and rendering helpers,
 * the beta model worked out in double from DESIGN.md's equations, exact
 * coverage of rectangles and circles on the pixels the tests sample, and a
 * busy scene of sixteen overlapping cels.
 *
 * Everything is static: each program includes this once.
 */
#ifndef CELSCAN_BETA_COMMON_H
#define CELSCAN_BETA_COMMON_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "celscan_private.h"
#include "shapes.h"
#include "testlib.h"

static TL_UNUSED cs_scene g_scene;
static TL_UNUSED cs_workspace g_ws;

/* ------------------------------------------------------------ building */

static const cs_affine identity = {1, 0, 0, 1, 0, 0};

static TL_UNUSED cs_paint paint(double pr, double pg, double pb, double mr, double mg, double mb,
                                double beta)
{
    cs_paint p = {{(float)pr, (float)pg, (float)pb}, {(float)mr, (float)mg, (float)mb},
                  (float)beta};
    return p;
}

static TL_UNUSED void add_region(cs_scene *s, cs_paint p)
{
    cs_error e;
    if (cs_scene_add_region(s, CS_FILL_NONZERO, &p, &e) != CS_OK)
        exit(2);
}

static TL_UNUSED void add_cel(cs_scene *s, const cs_affine *m, const float *front,
                              const float *back)
{
    cs_error e;
    if (cs_scene_add_cel(s, m ? m : &identity, front, back, &e) != CS_OK)
        exit(2);
}

static TL_UNUSED cs_render_opts opts_n(int w, int h, int sub)
{
    cs_render_opts o;
    memset(&o, 0, sizeof o);
    o.width = w;
    o.height = h;
    o.aa = CS_AA_SUBSCAN;
    o.subscanlines = sub;
    return o;
}

/* Renders a frame into img (3 w h floats), optionally from a cache. */
static TL_UNUSED cs_status render(const cs_scene *s, const cs_render_opts *o, const cs_cache *cache,
                                  float *img)
{
    cs_renderer r;
    cs_error e;
    cs_status st = cs_frame_begin_cached(&r, &g_ws, s, o, cache, &e);
    if (st != CS_OK)
        return st;
    for (int y = 0; y < o->height; y++) {
        st = cs_render_line(&r, y, img + (size_t)3 * o->width * y);
        if (st != CS_OK)
            return st;
    }
    return r.sticky.status;
}

static TL_UNUSED double srgb(double v)
{
    v = v < 0 ? 0 : v > 1 ? 1 : v;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
}

static TL_UNUSED double srgb_inv(double e)
{
    return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4);
}

/* ------------------------------------------------ the model, in double */

typedef struct map {
    double E[3], T[3];
} map;

static TL_UNUSED map clear_map(void)
{
    map m = {{0, 0, 0}, {1, 1, 1}};
    return m;
}

static TL_UNUSED map paint_map(const double *p, const double *m, double beta, const double *F,
                               const double *B)
{
    map r;
    for (int k = 0; k < 3; k++) {
        r.E[k] = beta * p[k] * F[k] + (1 - beta) * m[k] * B[k];
        r.T[k] = (1 - beta) * m[k];
    }
    return r;
}

/* A cel's map: the sum of its regions' coverage-weighted maps. */
static TL_UNUSED void cel_add(map *cel, const map *region, double c)
{
    for (int k = 0; k < 3; k++) {
        cel->E[k] += c * region->E[k];
        cel->T[k] -= c * (1 - region->T[k]);
    }
}

static TL_UNUSED map over(const map *front, const map *back)
{
    map r;
    for (int k = 0; k < 3; k++) {
        r.E[k] = front->E[k] + front->T[k] * back->E[k];
        r.T[k] = front->T[k] * back->T[k];
    }
    return r;
}

/* Overlap of [a, b] with [i, i+1]. */
static TL_UNUSED double overlap(double a, double b, int i)
{
    double lo = a > i ? a : i, hi = b < i + 1 ? b : i + 1;
    return hi > lo ? hi - lo : 0;
}

static TL_UNUSED double rect_cov(const double *r, int x, int y)
{
    return overlap(r[0], r[2], x) * overlap(r[1], r[3], y);
}

/* 1 inside, 0 outside, -1 when the circle cuts the pixel. */
static TL_UNUSED int circle_cov(double cx, double cy, double rad, int x, int y)
{
    double nx = cx < x ? x : cx > x + 1 ? x + 1 : cx;
    double ny = cy < y ? y : cy > y + 1 ? y + 1 : cy;
    double near2 = (nx - cx) * (nx - cx) + (ny - cy) * (ny - cy);
    double fx = fabs(cx - x) > fabs(cx - x - 1) ? x : x + 1;
    double fy = fabs(cy - y) > fabs(cy - y - 1) ? y : y + 1;
    double far2 = (fx - cx) * (fx - cx) + (fy - cy) * (fy - cy);
    if (far2 < (rad - 0.01) * (rad - 0.01))
        return 1;
    if (near2 > (rad + 0.01) * (rad + 0.01))
        return 0;
    return -1;
}

/* Compares a rendered linear pixel with the expected one: 8-bit sRGB codes
 * within 1.5 (the bar); returns the worst code difference. */
static TL_UNUSED double code_diff(const float *got, const double *want)
{
    double worst = 0;
    uint8_t out[3];
    cs_pixfmt_convert(CS_PIX_RGB888_SRGB, got, 1, out);
    for (int k = 0; k < 3; k++) {
        double w = want[k] < 0 ? 0 : want[k] > 1 ? 1 : want[k];
        double d = fabs(out[k] - 255.0 * srgb(w));
        if (d > worst)
            worst = d;
    }
    return worst;
}

static TL_UNUSED double lin_diff(const float *got, const double *want)
{
    double worst = 0;
    for (int k = 0; k < 3; k++) {
        double w = want[k] < 0 ? 0 : want[k] > 1 ? 1 : want[k];
        double d = fabs(got[k] - w);
        if (d > worst)
            worst = d;
    }
    return worst;
}

static TL_UNUSED float img_a[256 * 256 * 3], img_b[256 * 256 * 3], img_c[256 * 256 * 3];

/* ------------------------------------------------------- a busy scene */

static TL_UNUSED cs_paint_func make_func(int kind, int spread, const double *geom, int ngeom,
                                         int nstops, const double *off, const double (*val)[3])
{
    cs_paint_func f;
    memset(&f, 0, sizeof f);
    f.kind = (uint8_t)kind;
    f.spread = (uint8_t)spread;
    f.stop_count = (uint8_t)nstops;
    f.map_cols = 1;
    for (int i = 0; i < ngeom; i++)
        f.geom[i] = (float)geom[i];
    for (int i = 0; i < nstops; i++) {
        f.stops[i].offset = off ? (float)off[i] : 0.0f;
        for (int k = 0; k < 3; k++)
            f.stops[i].value[k] = (float)val[i][k];
    }
    return f;
}

/* --------------------------------------------- 5. early termination exact */

static TL_UNUSED void build_busy_scene(cs_scene *s)
{
    cs_scene_init(s, 96, 64);
    float bgf[3] = {0.3f, 0.3f, 0.35f};
    cs_scene_set_background(s, bgf);
    /* Front: a translucent disc and a gradient gel. */
    add_cel(s, NULL, NULL, NULL);
    add_region(s, paint(0.9, 0.8, 0.1, 0.6, 0.6, 0.9, 0.4));
    TL_MUST(ts_add_circle(s, 30, 30, 14));
    add_cel(s, NULL, NULL, NULL);
    add_region(s, paint(0.2, 0.2, 0.2, 1, 1, 1, 0));
    TL_MUST(ts_add_rect(s, 40, 4, 90, 60));
    const double g[4] = {40, 0, 90, 0};
    const double off[2] = {0, 1};
    const double v[2][3] = {{1, 0.3, 0.3}, {0.3, 0.3, 1}};
    cs_paint_func fn = make_func(CS_FUNC_LINEAR, CS_SPREAD_PAD, g, 4, 2, off, v);
    cs_error e;
    cs_scene_set_region_func(s, CS_FIELD_MEDIUM, &fn, &e);
    /* An opaque card over the middle (partly covering), and a fully opaque
     * full-width band that hides everything behind it on its lines. */
    add_cel(s, NULL, NULL, NULL);
    add_region(s, paint(0.1, 0.6, 0.2, 0, 0, 0, 1));
    TL_MUST(ts_add_rect(s, 10.3, 10.6, 70.2, 40.4));
    add_region(s, paint(0.7, 0.2, 0.2, 0, 0, 0, 1));
    TL_MUST(ts_add_rect(s, 0, 44, 96, 52));
    /* Two opaque regions of one cel meeting at a slanted edge: their
     * coverages on the seam pixels sum to 1 only up to rounding. */
    add_cel(s, NULL, NULL, NULL);
    add_region(s, paint(0.9, 0.3, 0.3, 0, 0, 0, 1));
    const double left[8] = {72.1, 2.3, 80.37, 2.3, 84.71, 62.2, 72.1, 62.2};
    TL_MUST(ts_add_polygon(s, left, 4));
    add_region(s, paint(0.3, 0.3, 0.9, 0, 0, 0, 1));
    const double right[8] = {80.37, 2.3, 95.3, 2.3, 95.3, 62.2, 84.71, 62.2};
    TL_MUST(ts_add_polygon(s, right, 4));
    /* Just behind the card, poking out of it by under a pixel on each side:
     * hidden only where the card is, so its bounds must be honest. */
    add_cel(s, NULL, NULL, NULL);
    add_region(s, paint(0.9, 0.9, 0.1, 0.2, 0.2, 0.2, 0.8));
    TL_MUST(ts_add_rect(s, 9.9, 12.2, 70.6, 38.3));
    /* Behind: many cels the early-out should skip in places. */
    for (int i = 0; i < 12; i++) {
        add_cel(s, NULL, NULL, NULL);
        add_region(s, paint(0.1 * (i % 10), 0.5, 0.9 - 0.05 * i, 0.8, 0.7, 0.6, 0.5 + 0.04 * i));
        TL_MUST(ts_add_circle(s, 8 + 7 * i, 20 + (i % 3) * 12, 9 + (i % 4)));
    }
    add_cel(s, NULL, NULL, NULL);
    add_region(s, paint(0.4, 0.4, 0.4, 0, 0, 0, 1)); /* opaque back wall */
    TL_MUST(ts_add_rect(s, 0, 0, 96, 64));
}


static TL_UNUSED double max_diff(const float *a, const float *b, size_t n)
{
    double worst = 0;
    for (size_t i = 0; i < n; i++) {
        double d = fabs((double)a[i] - b[i]);
        worst = d > worst ? d : worst;
    }
    return worst;
}

static TL_UNUSED unsigned char cache_buf[4 << 20];

#endif /* CELSCAN_BETA_COMMON_H */
