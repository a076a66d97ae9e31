/*
 * test_beta.c - the beta colour model, cel lighting and cel stacks.
 *
 * Every expectation here is computed independently of the renderer, in
 * double precision, from the equations of DESIGN.md:
 *   E = b p F + (1-b) m B,  T = (1-b) m,  coverage c: (c E, 1 - c (1 - T)),
 *   regions of a cel summed, cels overlaid front to back, pixel = E + T L,
 *   L = background * F_s with a card, else B_s.
 * Coverage is known exactly where the test asks: rectangles whose edges sit
 * on multiples of 1/16 are exact under 16 sub-scanlines, and circles are
 * only sampled on pixels wholly inside or outside. Gradients are evaluated
 * from their definitions (the radial one by bisection, not by the
 * renderer's quadratic). CSG is checked against a reference coverage of the
 * boolean combination of exact circles and polygons: exact horizontal
 * intervals on 512 rows per pixel, in long double.
 *
 * On tests/testlib.h; the last line is `test_beta: N passed, M failed`.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "celscan.h"
#include "shapes.h"
#include "testlib.h"

static cs_scene g_scene;
static cs_workspace g_ws;

/* ------------------------------------------------------------ building */

static const cs_affine identity = {1, 0, 0, 1, 0, 0};

static cs_paint paint(double pr, double pg, double pb, double mr, double mg, double mb,
                      double beta)
{
    cs_paint p = {{(float)pr, (float)pg, (float)pb}, {(float)mr, (float)mg, (float)mb},
                  (float)beta};
    return p;
}

static void add_region(cs_scene *s, cs_paint p)
{
    cs_error e;
    if (cs_scene_add_region(s, CS_FILL_NONZERO, &p, &e) != CS_OK)
        exit(2);
}

static void add_cel(cs_scene *s, const cs_affine *m, const float *front, const float *back)
{
    cs_error e;
    if (cs_scene_add_cel(s, m ? m : &identity, front, back, &e) != CS_OK)
        exit(2);
}

static cs_render_opts opts_n(int w, int h, int sub)
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
static cs_status render(const cs_scene *s, const cs_render_opts *o, const cs_cache *cache,
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

static double srgb(double v)
{
    v = v < 0 ? 0 : v > 1 ? 1 : v;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
}

static double srgb_inv(double e)
{
    return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4);
}

/* ------------------------------------------------ the model, in double */

typedef struct map {
    double E[3], T[3];
} map;

static map clear_map(void)
{
    map m = {{0, 0, 0}, {1, 1, 1}};
    return m;
}

static map paint_map(const double *p, const double *m, double beta, const double *F,
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
static void cel_add(map *cel, const map *region, double c)
{
    for (int k = 0; k < 3; k++) {
        cel->E[k] += c * region->E[k];
        cel->T[k] -= c * (1 - region->T[k]);
    }
}

static map over(const map *front, const map *back)
{
    map r;
    for (int k = 0; k < 3; k++) {
        r.E[k] = front->E[k] + front->T[k] * back->E[k];
        r.T[k] = front->T[k] * back->T[k];
    }
    return r;
}

/* Overlap of [a, b] with [i, i+1]. */
static double overlap(double a, double b, int i)
{
    double lo = a > i ? a : i, hi = b < i + 1 ? b : i + 1;
    return hi > lo ? hi - lo : 0;
}

static double rect_cov(const double *r, int x, int y)
{
    return overlap(r[0], r[2], x) * overlap(r[1], r[3], y);
}

/* 1 inside, 0 outside, -1 when the circle cuts the pixel. */
static int circle_cov(double cx, double cy, double rad, int x, int y)
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
static double code_diff(const float *got, const double *want)
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

static double lin_diff(const float *got, const double *want)
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

static float img_a[256 * 256 * 3], img_b[256 * 256 * 3], img_c[256 * 256 * 3];

/* ------------------------------------------- 1. closed form, overlapping */

static void test_closed_form(void)
{
    const double Fs[3] = {0.9, 1.0, 0.7}, Bs[3] = {0.25, 0.1, 0.4};
    const double F0[3] = {1.2, 0.8, 1.0}, B0[3] = {0.5, 0.6, 0.2};
    const double B2[3] = {0.3, 0.3, 0.35}, black[3] = {0, 0, 0};
    const double bg[3] = {0.3, 0.5, 0.2};
    /* Cel 0: two regions sharing the edge x = 30.5. Cel 1: a circle.
     * Cel 2: a big rectangle with its own back light. */
    const double ra[4] = {8.25, 8.75, 30.5, 40.25}, rb[4] = {30.5, 8.75, 50.625, 40.25};
    const double rc[4] = {4.5, 20.5, 60.25, 60.75};
    const double pa[3] = {0.9, 0.2, 0.1}, ma[3] = {0.3, 0.8, 0.6}, ba = 0.55;
    const double pb[3] = {0.1, 0.7, 0.3}, mb[3] = {0.9, 0.9, 0.2}, bb = 0.25;
    const double pcirc[3] = {0.2, 0.3, 0.9}, mcirc[3] = {0.7, 0.4, 0.9}, bcirc = 0.4;
    const double pr[3] = {0.6, 0.6, 0.1}, mr[3] = {0.5, 0.9, 0.9}, br = 0.7;
    const double ccx = 36, ccy = 36, crad = 18;

    for (int with_bg = 0; with_bg < 2; with_bg++) {
        cs_scene *s = &g_scene;
        cs_scene_init(s, 64, 64);
        float f[3], b[3];
        for (int k = 0; k < 3; k++) {
            f[k] = (float)F0[k];
            b[k] = (float)B0[k];
        }
        add_cel(s, NULL, f, b);
        add_region(s, paint(pa[0], pa[1], pa[2], ma[0], ma[1], ma[2], ba));
        TL_MUST(ts_add_rect(s, ra[0], ra[1], ra[2], ra[3]));
        add_region(s, paint(pb[0], pb[1], pb[2], mb[0], mb[1], mb[2], bb));
        TL_MUST(ts_add_rect(s, rb[0], rb[1], rb[2], rb[3]));
        add_cel(s, NULL, NULL, NULL); /* front = stack front, back = black */
        add_region(s, paint(pcirc[0], pcirc[1], pcirc[2], mcirc[0], mcirc[1], mcirc[2], bcirc));
        TL_MUST(ts_add_circle(s, ccx, ccy, crad));
        float b2[3] = {(float)B2[0], (float)B2[1], (float)B2[2]};
        add_cel(s, NULL, NULL, b2);
        add_region(s, paint(pr[0], pr[1], pr[2], mr[0], mr[1], mr[2], br));
        TL_MUST(ts_add_rect(s, rc[0], rc[1], rc[2], rc[3]));
        /* Stack lights set after the cels: cel 1 and 2 must still follow. */
        float fs[3] = {(float)Fs[0], (float)Fs[1], (float)Fs[2]};
        float bs[3] = {(float)Bs[0], (float)Bs[1], (float)Bs[2]};
        cs_scene_set_lights(s, fs, bs);
        double L[3];
        if (with_bg) {
            float bgf[3] = {(float)bg[0], (float)bg[1], (float)bg[2]};
            cs_scene_set_background(s, bgf);
            for (int k = 0; k < 3; k++)
                L[k] = bg[k] * Fs[k];
        } else {
            for (int k = 0; k < 3; k++)
                L[k] = Bs[k];
        }
        cs_render_opts o = opts_n(64, 64, 16);
        CHECK(render(s, &o, NULL, img_a) == CS_OK, "render");
        map ma_ = paint_map(pa, ma, ba, F0, B0), mb_ = paint_map(pb, mb, bb, F0, B0);
        map mc_ = paint_map(pcirc, mcirc, bcirc, Fs, black), mr_ = paint_map(pr, mr, br, Fs, B2);
        double worst = 0, worst_lin = 0;
        int checked = 0, edges = 0;
        for (int y = 0; y < 64; y++)
            for (int x = 0; x < 64; x++) {
                int cc = circle_cov(ccx, ccy, crad, x, y);
                if (cc < 0)
                    continue;
                map cel0 = clear_map(), cel1 = clear_map(), cel2 = clear_map();
                double ca = rect_cov(ra, x, y), cb = rect_cov(rb, x, y), cr = rect_cov(rc, x, y);
                cel_add(&cel0, &ma_, ca);
                cel_add(&cel0, &mb_, cb);
                cel_add(&cel1, &mc_, cc);
                cel_add(&cel2, &mr_, cr);
                map st = over(&cel0, &cel1);
                st = over(&st, &cel2);
                double want[3];
                for (int k = 0; k < 3; k++)
                    want[k] = st.E[k] + st.T[k] * L[k];
                const float *got = &img_a[3 * (64 * y + x)];
                double d = code_diff(got, want), dl = lin_diff(got, want);
                if (d > worst)
                    worst = d;
                if (dl > worst_lin)
                    worst_lin = dl;
                checked++;
                if ((ca > 0 && ca < 1) || (cb > 0 && cb < 1) || (cr > 0 && cr < 1))
                    edges++;
            }
        CHECK(worst <= 1.5, "closed form (bg=%d): worst sRGB code diff %.3f > 1.5", with_bg, worst);
        CHECK(worst_lin <= 1e-4, "closed form (bg=%d): worst linear diff %.2e", with_bg, worst_lin);
        CHECK(checked > 3000 && edges > 150, "closed form: too few pixels checked (%d, %d edges)",
              checked, edges);
        printf("  closed form bg=%d: %d pixels (%d on edges), worst %.3f/255 sRGB, %.1e linear\n",
               with_bg, checked, edges, worst, worst_lin);
    }
}

/* --------------------------------- 2. m = 1, F = 1, B = 0 is alpha over */

static void test_alpha_over(void)
{
    cs_scene *s = &g_scene;
    cs_scene_init(s, 48, 48);
    const double bg[3] = {0.1, 0.2, 0.6};
    float bgf[3] = {0.1f, 0.2f, 0.6f};
    cs_scene_set_background(s, bgf);
    const double col[3][3] = {{0.9, 0.1, 0.1}, {0.1, 0.8, 0.2}, {0.9, 0.9, 0.2}};
    const double alpha[3] = {0.5, 0.75, 0.3};
    const double rects[3][4] = {{4.5, 6.25, 30.75, 30.5}, {16.125, 12.5, 44.5, 40.0625},
                                {0, 20.25, 48, 44.75}};
    for (int i = 0; i < 3; i++) {
        add_cel(s, NULL, NULL, NULL);
        add_region(s, paint(col[i][0], col[i][1], col[i][2], 1, 1, 1, alpha[i]));
        TL_MUST(ts_add_rect(s, rects[i][0], rects[i][1], rects[i][2], rects[i][3]));
    }
    cs_render_opts o = opts_n(48, 48, 16);
    CHECK(render(s, &o, NULL, img_a) == CS_OK, "render");
    double worst = 0, worst_lin = 0;
    for (int y = 0; y < 48; y++)
        for (int x = 0; x < 48; x++) {
            /* Porter-Duff over, premultiplied, back to front. */
            double acc[3] = {bg[0], bg[1], bg[2]};
            for (int i = 2; i >= 0; i--) {
                double a = alpha[i] * rect_cov(rects[i], x, y);
                for (int k = 0; k < 3; k++)
                    acc[k] = a * col[i][k] + (1 - a) * acc[k];
            }
            const float *got = &img_a[3 * (48 * y + x)];
            double d = code_diff(got, acc), dl = lin_diff(got, acc);
            worst = d > worst ? d : worst;
            worst_lin = dl > worst_lin ? dl : worst_lin;
        }
    CHECK(worst <= 1.5 && worst_lin <= 1e-5, "alpha over: worst %.3f/255, %.2e linear", worst,
          worst_lin);
    printf("  premultiplied alpha over: worst %.3f/255 sRGB, %.1e linear\n", worst, worst_lin);
}

/* ------------------------------------------ 3. mattes, gels, foggy cels */

/* One front cel over an opaque red card-cel over the background; returns
 * the rendered centre pixel of the front cel's square. */
static void matte_case(const char *name, cs_paint front, const float *back_light,
                       const double *want_map_E, const double *want_map_T)
{
    cs_scene *s = &g_scene;
    cs_scene_init(s, 32, 32);
    float bgf[3] = {0.2f, 0.4f, 0.6f};
    cs_scene_set_background(s, bgf);
    float fs[3] = {0.9f, 0.95f, 1.0f};
    float bs[3] = {0, 0, 0};
    cs_scene_set_lights(s, fs, bs);
    add_cel(s, NULL, NULL, back_light);
    add_region(s, front);
    TL_MUST(ts_add_rect(s, 4, 4, 20, 28));
    add_cel(s, NULL, NULL, NULL);
    add_region(s, paint(0.8, 0.1, 0.05, 0, 0, 0, 1)); /* opaque red, right half */
    TL_MUST(ts_add_rect(s, 16, 0, 32, 32));
    cs_render_opts o = opts_n(32, 32, 4);
    CHECK(render(s, &o, NULL, img_a) == CS_OK, "%s: render", name);
    const double L[3] = {0.2 * 0.9, 0.4 * 0.95, 0.6};
    const double red[3] = {0.8 * 0.9, 0.1 * 0.95, 0.05};
    double worst = 0;
    /* Pixel (8, 16): front cel over the background. Pixel (18, 16): over red. */
    for (int side = 0; side < 2; side++) {
        int x = side ? 18 : 8;
        const double *behind = side ? red : L;
        double want[3];
        for (int k = 0; k < 3; k++)
            want[k] = want_map_E[k] + want_map_T[k] * behind[k];
        double d = lin_diff(&img_a[3 * (32 * 16 + x)], want);
        worst = d > worst ? d : worst;
    }
    CHECK(worst <= 1e-6, "%s: worst linear diff %.2e", name, worst);
}

static void test_mattes(void)
{
    const double zero[3] = {0, 0, 0};
    const double F[3] = {0.9, 0.95, 1.0};
    /* Hard hold-out: (0, 0) whatever lies behind, the card included. */
    matte_case("hard matte", paint(0, 0, 0, 1, 1, 1, 1), NULL, zero, zero);
    /* Soft hold-out: black pigment, clear medium, beta 0.6: (0, 0.4). */
    const double t04[3] = {0.4, 0.4, 0.4};
    matte_case("soft matte", paint(0, 0, 0, 1, 1, 1, 0.6), NULL, zero, t04);
    /* Grey-medium matte: beta 0, medium 0.3: holds out 70% of everything. */
    const double t03[3] = {0.3, 0.3, 0.3};
    matte_case("grey matte", paint(0.5, 0.5, 0.5, 0.3, 0.3, 0.3, 0), NULL, zero, t03);
    /* Coloured gel lit from behind by its own back light: E = m B, T = m. */
    float gel_back[3] = {0.5f, 0.25f, 1.0f};
    const double gm[3] = {0.9, 0.3, 0.2};
    const double gE[3] = {0.9 * 0.5, 0.3 * 0.25, 0.2 * 1.0};
    matte_case("gel", paint(0, 0, 0, gm[0], gm[1], gm[2], 0), gel_back, gE, gm);
    /* Foggy: partly scattering (white pigment under the front light), partly clear. */
    const double fogE[3] = {0.35 * 0.9 * F[0], 0.35 * 0.9 * F[1], 0.35 * 0.95 * F[2]};
    const double fogT[3] = {0.65, 0.65, 0.65};
    matte_case("foggy", paint(0.9, 0.9, 0.95, 1, 1, 1, 0.35), NULL, fogE, fogT);
    /* Nearly opaque: T = 0.004 must still let the light behind through. */
    const double nE[3] = {0.996 * 0.5 * F[0], 0.996 * 0.5 * F[1], 0.996 * 0.5 * F[2]};
    const double nT[3] = {0.004, 0.004, 0.004};
    matte_case("nearly opaque", paint(0.5, 0.5, 0.5, 1, 1, 1, 0.996), NULL, nE, nT);
    /* Gel with a tinted, partly scattering medium and a back light. */
    float back2[3] = {0.2f, 0.2f, 0.2f};
    const double p2[3] = {0.3, 0.6, 0.9}, m2[3] = {0.5, 0.7, 0.1}, b2[3] = {0.2, 0.2, 0.2};
    map m = paint_map(p2, m2, 0.3, F, b2);
    matte_case("tinted fog", paint(p2[0], p2[1], p2[2], m2[0], m2[1], m2[2], 0.3), back2, m.E,
               m.T);
}

/* --------------------------------------------------- 4. functional paints */

static cs_paint_func make_func(int kind, int spread, const double *geom, int ngeom, int nstops,
                               const double *off, const double (*val)[3])
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

static double spread_d(double t, int mode)
{
    if (mode == CS_SPREAD_REPEAT)
        return t - floor(t);
    if (mode == CS_SPREAD_REFLECT) {
        double m = fmod(fabs(t), 2.0);
        return m > 1 ? 2 - m : m;
    }
    return t < 0 ? 0 : t > 1 ? 1 : t;
}

static void stops_d(int n, const double *off, const double (*val)[3], double t, double *out)
{
    for (int k = 0; k < 3; k++) {
        if (t <= off[0]) {
            out[k] = val[0][k];
            continue;
        }
        if (t >= off[n - 1]) {
            out[k] = val[n - 1][k];
            continue;
        }
        for (int i = 0; i + 1 < n; i++)
            if (t >= off[i] && t < off[i + 1]) {
                double w = (t - off[i]) / (off[i + 1] - off[i]);
                out[k] = val[i][k] + (val[i + 1][k] - val[i][k]) * w;
                break;
            }
    }
}

/* SVG focal radial t by bisection: the point lies on the circle with
 * centre f + t (c - f) and radius t r. */
static double radial_t(double qx, double qy, double cx, double cy, double r, double fx,
                       double fy)
{
    double lo = 0, hi = 1;
    /* grow hi until the point is inside circle(hi) */
    for (int i = 0; i < 60; i++) {
        double ox = fx + hi * (cx - fx), oy = fy + hi * (cy - fy);
        if (hypot(qx - ox, qy - oy) <= hi * r)
            break;
        hi *= 2;
    }
    for (int i = 0; i < 200; i++) {
        double mid = 0.5 * (lo + hi);
        double ox = fx + mid * (cx - fx), oy = fy + mid * (cy - fy);
        if (hypot(qx - ox, qy - oy) <= mid * r)
            hi = mid;
        else
            lo = mid;
    }
    return 0.5 * (lo + hi);
}

static void test_gradients(void)
{
    /* A cel rotated by 30 degrees, scaled and moved; canvas 100 x 50 shown
     * at 200 x 100, so geometry goes through both transforms. */
    const double ang = 30.0 * 3.14159265358979323846 / 180.0, sc = 0.8;
    const double M[6] = {sc * cos(ang), sc * sin(ang), -sc * sin(ang), sc * cos(ang), 52, -6};
    cs_affine A = {(float)M[0], (float)M[1], (float)M[2], (float)M[3], (float)M[4], (float)M[5]};
    /* Inverse in double, from the float matrix the scene holds. */
    double a = A.a, b = A.b, c = A.c, d = A.d, e = A.e, f = A.f, det = a * d - b * c;
    const double off3[3] = {0, 0.4, 1};
    const double val3[3][3] = {{0.9, 0.1, 0.05}, {0.2, 0.8, 0.3}, {0.05, 0.2, 0.95}};
    const double off2[2] = {0.2, 0.9};
    const double beta2[2][3] = {{1, 1, 1}, {0.25, 0.25, 0.25}};
    const double lin[4] = {-10, 0, 30, 10};
    const double rad[5] = {10, 5, 40, 22, 12};
    const double mapg[6] = {-20, -30, 50, 0, 0, 40};
    const double mapv[6][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 1, 1}};
    const double Fs[3] = {0.95, 0.9, 1.0};

    for (int kind = 0; kind < 4; kind++)
        for (int spread = 0; spread < 3; spread++) {
            cs_scene *s = &g_scene;
            cs_scene_init(s, 100, 50);
            float fs[3] = {0.95f, 0.9f, 1.0f}, zero[3] = {0, 0, 0};
            cs_scene_set_lights(s, fs, zero);
            add_cel(s, &A, NULL, NULL);
            /* medium [0.5, 0.6, 0.7] so that a beta function shows */
            add_region(s, paint(0.5, 0.5, 0.5, 0.5, 0.6, 0.7, 1));
            TL_MUST(ts_add_rect(s, -200, -200, 300, 300)); /* covers everything */
            cs_paint_func fn;
            cs_error err;
            int field = CS_FIELD_PIGMENT;
            if (kind == 0)
                fn = make_func(CS_FUNC_LINEAR, spread, lin, 4, 3, off3, val3);
            else if (kind == 1)
                fn = make_func(CS_FUNC_RADIAL, spread, rad, 5, 3, off3, val3);
            else if (kind == 2) {
                fn = make_func(CS_FUNC_MAP, spread, mapg, 6, 6, NULL, mapv);
                fn.map_cols = 3;
            } else {
                fn = make_func(CS_FUNC_LINEAR, spread, lin, 4, 2, off2, beta2);
                field = CS_FIELD_BETA;
            }
            cs_status st = cs_scene_set_region_func(s, (cs_paint_field)field, &fn, &err);
            CHECK(st == CS_OK, "set func kind %d: %s", kind, cs_status_str(st));
            cs_render_opts o = opts_n(200, 100, 4);
            CHECK(render(s, &o, NULL, img_a) == CS_OK, "render");
            double worst = 0, worst_code = 0;
            for (int y = 0; y < 100; y += 3)
                for (int x = 0; x < 200; x += 3) {
                    /* pixel centre -> canvas -> cel space */
                    double px = (x + 0.5) / 2.0, py = (y + 0.5) / 2.0;
                    double qx = (d * (px - e) - c * (py - f)) / det;
                    double qy = (-b * (px - e) + a * (py - f)) / det;
                    double pig[3] = {0.5, 0.5, 0.5}, beta = 1;
                    double traw[2] = {0.5, 0.5};
                    if (kind == 0 || kind == 3) {
                        double gx = lin[2] - lin[0], gy = lin[3] - lin[1];
                        traw[0] = ((qx - lin[0]) * gx + (qy - lin[1]) * gy) / (gx * gx + gy * gy);
                        double t = spread_d(traw[0], spread);
                        if (kind == 0)
                            stops_d(3, off3, val3, t, pig);
                        else {
                            double bv[3];
                            stops_d(2, off2, beta2, t, bv);
                            beta = bv[0];
                        }
                    } else if (kind == 1) {
                        traw[0] = radial_t(qx, qy, rad[0], rad[1], rad[2], rad[3], rad[4]);
                        stops_d(3, off3, val3, spread_d(traw[0], spread), pig);
                    } else {
                        /* q = o + s u + t v, u = (50, 0), v = (0, 40) */
                        traw[0] = (qx - mapg[0]) / 50.0;
                        traw[1] = (qy - mapg[1]) / 40.0;
                        double sv = spread_d(traw[0], spread), tv = spread_d(traw[1], spread);
                        double fsv = sv * 2, ftv = tv;
                        int i = (int)floor(fsv);
                        if (i > 1)
                            i = 1;
                        double ws = fsv - i;
                        for (int k = 0; k < 3; k++) {
                            double top = mapv[i][k] + (mapv[i + 1][k] - mapv[i][k]) * ws;
                            double bot = mapv[3 + i][k] + (mapv[4 + i][k] - mapv[3 + i][k]) * ws;
                            pig[k] = top + (bot - top) * ftv;
                        }
                    }
                    /* Repeat jumps at whole t: skip pixels within float
                     * rounding of a jump, where either side is right. */
                    if (spread == CS_SPREAD_REPEAT &&
                        (fabs(traw[0] - floor(traw[0] + 0.5)) < 1e-3 ||
                         fabs(traw[1] - floor(traw[1] + 0.5)) < 1e-3))
                        continue;
                    double want[3];
                    for (int k = 0; k < 3; k++)
                        want[k] = beta * pig[k] * Fs[k]; /* B = 0, L = B_s = 0 */
                    const float *got = &img_a[3 * (200 * y + x)];
                    double dl = lin_diff(got, want), dc = code_diff(got, want);
                    worst = dl > worst ? dl : worst;
                    worst_code = dc > worst_code ? dc : worst_code;
                }
            printf("    kind %d spread %d: worst %.3f/255 lin %.2e\n", kind, spread, worst_code, worst);
            CHECK(worst_code <= 1.5 && worst <= 1e-4, "gradient kind %d spread %d: worst %.3f/255 (lin %.2e)", kind,
                  spread, worst_code, worst);
        }
    printf("  gradients: linear, radial (focal), 3x2 map, beta ramp x pad/reflect/repeat\n");
}

/* --------------------------------------------- 5. early termination exact */

static void build_busy_scene(cs_scene *s)
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

static void test_early_out_exact(void)
{
    build_busy_scene(&g_scene);
    for (int aa = 0; aa < 5; aa++) {
        cs_render_opts o = opts_n(96, 64, aa == 3 ? 3 : aa == 4 ? 7 : 5);
        o.aa = aa == 0 ? CS_AA_NONE : aa == 2 ? CS_AA_EXACT : CS_AA_SUBSCAN;
        CHECK(render(&g_scene, &o, NULL, img_a) == CS_OK, "render");
        o.no_early_out = true;
        CHECK(render(&g_scene, &o, NULL, img_b) == CS_OK, "render");
        CHECK(memcmp(img_a, img_b, sizeof(float) * 3 * 96 * 64) == 0,
              "early out changed pixels (aa mode %d)", aa);
    }
}

/* --------------------------------------------------------- 6. the cache */

static double max_diff(const float *a, const float *b, size_t n)
{
    double worst = 0;
    for (size_t i = 0; i < n; i++) {
        double d = fabs((double)a[i] - b[i]);
        worst = d > worst ? d : worst;
    }
    return worst;
}

static unsigned char cache_buf[4 << 20];

static void test_cache(void)
{
    build_busy_scene(&g_scene);
    cs_render_opts o = opts_n(96, 64, 5);
    cs_cache cache;
    cs_error e;
    const size_t n = (size_t)3 * 96 * 64;
    /* Too small: reported with the size it needs, and refused by the frame. */
    cs_status st = cs_cache_build(&cache, cache_buf + 1, 100, &g_ws, &g_scene, &o, 3, 13, &e);
    CHECK(st == CS_ERR_CAP_CACHE && cache.status != CS_OK && cache.bytes_needed > 100,
          "small cache: %s, needed %zu", cs_status_str(st), cache.bytes_needed);
    cs_renderer r;
    CHECK(cs_frame_begin_cached(&r, &g_ws, &g_scene, &o, &cache, &e) == CS_ERR_STATE,
          "unusable cache refused");
    size_t needed = cache.bytes_needed;
    /* Exactly the reported size fits (odd address: alignment is handled). */
    st = cs_cache_build(&cache, cache_buf + 1, needed, &g_ws, &g_scene, &o, 3, 13, &e);
    CHECK(st == CS_OK && cache.bytes_used == needed, "cache of the needed size: %s, %zu vs %zu",
          cs_status_str(st), cache.bytes_used, needed);
    st = cs_cache_build(&cache, cache_buf + 1, needed - 1, &g_ws, &g_scene, &o, 3, 13, &e);
    CHECK(st == CS_ERR_CAP_CACHE && cache.bytes_needed == needed, "one byte short: %s",
          cs_status_str(st));
    st = cs_cache_build(&cache, cache_buf + 1, needed, &g_ws, &g_scene, &o, 3, 13, &e);
    printf("  cache of cels 3..15 at 96x64: %u runs, %zu bytes\n", cache.run_count,
           cache.bytes_used);
    /* Cels 0-2 live in front, the cached background behind. */
    CHECK(render(&g_scene, &o, NULL, img_a) == CS_OK, "direct");
    CHECK(render(&g_scene, &o, &cache, img_b) == CS_OK, "cached");
    double d = max_diff(img_a, img_b, n);
    CHECK(d <= 1.0 / 255.0 && d < 1e-5, "cache vs direct: %.2e", d);
    /* Animate the front: move cel 0; the cache stays valid. */
    for (int t = 0; t < 3; t++) {
        g_scene.cels[0].transform.e = 5.0f * (float)t;
        g_scene.cels[1].transform.f = -3.0f * (float)t;
        render(&g_scene, &o, NULL, img_a);
        render(&g_scene, &o, &cache, img_b);
        d = max_diff(img_a, img_b, n);
        CHECK(d < 1e-5, "animated front, frame %d: cache vs direct %.2e", t, d);
    }
    /* A cached range in the middle: live cels in front and behind. */
    st = cs_cache_build(&cache, cache_buf, sizeof cache_buf, &g_ws, &g_scene, &o, 1, 5, &e);
    CHECK(st == CS_OK, "middle cache: %s", cs_status_str(st));
    render(&g_scene, &o, NULL, img_a);
    render(&g_scene, &o, &cache, img_b);
    d = max_diff(img_a, img_b, n);
    CHECK(d < 1e-5, "middle cache vs direct: %.2e", d);
    /* Without the background card, with a light box behind. */
    g_scene.has_background = false;
    float fs[3] = {1, 1, 1}, bs[3] = {0.6f, 0.5f, 0.9f};
    cs_scene_set_lights(&g_scene, fs, bs);
    g_scene.cel_count -= 1; /* drop the opaque back wall so the light shows */
    st = cs_cache_build(&cache, cache_buf, sizeof cache_buf, &g_ws, &g_scene, &o, 2, 10, &e);
    CHECK(st == CS_OK, "light box cache: %s", cs_status_str(st));
    render(&g_scene, &o, NULL, img_a);
    render(&g_scene, &o, &cache, img_b);
    d = max_diff(img_a, img_b, n);
    CHECK(d < 1e-5, "light box cache vs direct: %.2e", d);
    /* Pre-combined and reused at other options is refused. */
    cs_render_opts o2 = opts_n(96, 64, 4);
    CHECK(cs_frame_begin_cached(&r, &g_ws, &g_scene, &o2, &cache, &e) == CS_ERR_STATE,
          "cache at other AA refused");
    o2 = opts_n(80, 64, 5);
    CHECK(cs_frame_begin_cached(&r, &g_ws, &g_scene, &o2, &cache, &e) == CS_ERR_STATE,
          "cache at other size refused");
    /* Bad ranges. */
    CHECK(cs_cache_build(&cache, cache_buf, sizeof cache_buf, &g_ws, &g_scene, &o, 5, 0, &e) ==
              CS_ERR_ARG,
          "empty range");
    CHECK(cs_cache_build(&cache, cache_buf, sizeof cache_buf, &g_ws, &g_scene, &o, 10, 100,
                         &e) == CS_ERR_ARG,
          "range past the end");
    /* Size query: no buffer at all. */
    st = cs_cache_build(&cache, NULL, 0, &g_ws, &g_scene, &o, 0, 3, &e);
    CHECK(st == CS_ERR_CAP_CACHE && cache.bytes_needed > 0, "size query");
}

/* ---------------------------------------------------- 6b. the grey path */

/* Whether a frame at o takes the grey path (cs_renderer.grey: a private
 * field, read here to know which path the pixels came from). */
static bool frame_grey(const cs_scene *s, const cs_render_opts *o, const cs_cache *cache)
{
    cs_renderer r;
    cs_error e;
    return cs_frame_begin_cached(&r, &g_ws, s, o, cache, &e) == CS_OK && r.grey;
}

/* Renders at o with the grey path allowed and refused: the same bits. */
static bool same_bits_both_paths(const cs_scene *s, cs_render_opts o, const cs_cache *cache)
{
    size_t bytes = sizeof(float) * 3 * (size_t)o.width * (size_t)o.height;
    o.no_grey = false;
    bool ok = render(s, &o, cache, img_a) == CS_OK;
    o.no_grey = true;
    ok = ok && render(s, &o, cache, img_b) == CS_OK;
    return ok && memcmp(img_a, img_b, bytes) == 0;
}

/*
 * A frame whose every transmittance is grey keeps T in one channel
 * (cs_renderer.grey). Its pixels must be the bits of the three-channel
 * path, which the rest of this file checks against closed forms; here the
 * two paths are compared, and which frames may take the grey one.
 */
static void test_grey_path(void)
{
    build_busy_scene(&g_scene);
    cs_render_opts o = opts_n(96, 64, 5);
    CHECK(!frame_grey(&g_scene, &o, NULL), "coloured media: three channels");
    /* The same scene with every medium grey (constant and gradient). */
    for (uint32_t i = 0; i < g_scene.region_count; i++) {
        float *m = g_scene.regions[i].paint.medium;
        m[1] = m[2] = m[0];
    }
    for (uint32_t f = 0; f < g_scene.func_count; f++)
        for (uint32_t k = 0; k < g_scene.funcs[f].stop_count; k++) {
            float *v = g_scene.funcs[f].stops[k].value;
            v[1] = v[2] = v[0];
        }
    CHECK(frame_grey(&g_scene, &o, NULL), "grey media: one channel");
    o.no_grey = true;
    CHECK(!frame_grey(&g_scene, &o, NULL), "no_grey refuses the grey path");
    for (int aa = 0; aa < 4; aa++) {
        cs_render_opts m = opts_n(96, 64, aa == 3 ? 16 : 5);
        m.aa = aa == 0 ? CS_AA_NONE : aa == 2 ? CS_AA_EXACT : CS_AA_SUBSCAN;
        for (int early = 0; early < 2; early++) {
            m.no_early_out = early != 0;
            CHECK(same_bits_both_paths(&g_scene, m, NULL),
                  "grey path differs from three channels (aa mode %d, early-out %s)", aa,
                  early ? "off" : "on");
        }
        m.blend = CS_BLEND_SRGB;
        CHECK(same_bits_both_paths(&g_scene, m, NULL),
              "grey path differs from three channels (aa mode %d, sRGB blending)", aa);
    }
    /* A grey cache behind grey live cels stays grey; its runs hold T whole. */
    cs_cache cache;
    cs_error e;
    o.no_grey = false;
    cs_status st = cs_cache_build(&cache, cache_buf, sizeof cache_buf, &g_ws, &g_scene, &o, 3,
                                  13, &e);
    CHECK(st == CS_OK && cache.grey, "grey cache: %s, grey %d", cs_status_str(st), cache.grey);
    CHECK(frame_grey(&g_scene, &o, &cache), "grey cache, grey frame");
    CHECK(same_bits_both_paths(&g_scene, o, &cache), "grey cached frame differs");
    /* A coloured medium in the cached range only: the cache is coloured, so
     * the frame keeps three channels though its live cels are grey. */
    float *m = g_scene.regions[g_scene.cels[14].first_region].paint.medium;
    m[1] = 0.5f * m[0];
    st = cs_cache_build(&cache, cache_buf, sizeof cache_buf, &g_ws, &g_scene, &o, 3, 13, &e);
    CHECK(st == CS_OK && !cache.grey, "coloured cache: %s, grey %d", cs_status_str(st),
          cache.grey);
    CHECK(!frame_grey(&g_scene, &o, &cache), "coloured cache: three channels");
    render(&g_scene, &o, NULL, img_a);
    render(&g_scene, &o, &cache, img_b);
    double d = max_diff(img_a, img_b, (size_t)3 * 96 * 64);
    CHECK(d < 1e-5, "coloured cache behind grey cels vs direct: %.2e", d);

    /* An opaque paint transmits nothing on any channel, whatever its medium;
     * but a functional beta lets its coloured medium through. */
    cs_scene_init(&g_scene, 64, 32);
    const float card[3] = {0.8f, 0.7f, 0.6f}; /* light behind the stack, so T shows */
    cs_scene_set_background(&g_scene, card);
    add_cel(&g_scene, NULL, NULL, NULL);
    add_region(&g_scene, paint(0.2, 0.6, 0.9, 0.9, 0.5, 0.2, 1));
    TL_MUST(ts_add_rect(&g_scene, 4, 4, 30, 28));
    add_cel(&g_scene, NULL, NULL, NULL);
    add_region(&g_scene, paint(0.9, 0.9, 0.1, 1, 1, 1, 0));
    TL_MUST(ts_add_circle(&g_scene, 20, 16, 12));
    o = opts_n(64, 32, 5);
    CHECK(frame_grey(&g_scene, &o, NULL), "opaque paint with a coloured medium: grey");
    add_cel(&g_scene, NULL, NULL, NULL);
    add_region(&g_scene, paint(0.3, 0.3, 0.3, 0.9, 0.5, 0.2, 1));
    const double g[4] = {0, 0, 64, 0};
    const double off[2] = {0, 1};
    const double ramp[2][3] = {{0, 0, 0}, {1, 1, 1}};
    cs_paint_func fn = make_func(CS_FUNC_LINEAR, CS_SPREAD_PAD, g, 4, 2, off, ramp);
    CHECK(cs_scene_set_region_func(&g_scene, CS_FIELD_BETA, &fn, &e) == CS_OK, "beta ramp");
    TL_MUST(ts_add_rect(&g_scene, 0, 8, 64, 24));
    CHECK(!frame_grey(&g_scene, &o, NULL), "functional beta over a coloured medium: three channels");
    CHECK(same_bits_both_paths(&g_scene, o, NULL), "functional beta: the paths differ");
    /* A grey medium gradient is grey; one coloured stop is not. */
    g_scene.regions[2].paint.medium[1] = g_scene.regions[2].paint.medium[2] = 0.9f;
    CHECK(frame_grey(&g_scene, &o, NULL), "functional beta over a grey medium: grey");
    CHECK(same_bits_both_paths(&g_scene, o, NULL), "grey functional beta: the paths differ");
    const double greys[2][3] = {{0.2, 0.2, 0.2}, {0.8, 0.8, 0.8}};
    fn = make_func(CS_FUNC_LINEAR, CS_SPREAD_REFLECT, g, 4, 2, off, greys);
    CHECK(cs_scene_set_region_func(&g_scene, CS_FIELD_MEDIUM, &fn, &e) == CS_OK, "medium ramp");
    CHECK(frame_grey(&g_scene, &o, NULL), "grey medium gradient: grey");
    CHECK(same_bits_both_paths(&g_scene, o, NULL), "grey medium gradient: the paths differ");
    g_scene.funcs[g_scene.regions[2].func[CS_FIELD_MEDIUM] - 1u].stops[1].value[2] = 0.7f;
    CHECK(!frame_grey(&g_scene, &o, NULL), "coloured medium stop: three channels");
    printf("  grey path: same bits as three channels in every mode, cached and not\n");
}

/* ------------------------------------------------------------- 7. CSG */

/* The reference: shapes with exact membership, combined by the same RPN. */
typedef struct shape {
    int kind; /* 0 circle, 1 polygon */
    double cx, cy, r;
    const double *xy;
    int n;
    int operand;
} shape;

/* x positions where row y crosses the shape's boundary. */
static int shape_breaks(const shape *s, long double y, long double *out)
{
    if (s->kind == 0) {
        long double dy = y - s->cy, q = (long double)s->r * s->r - dy * dy;
        if (q <= 0)
            return 0;
        long double h = sqrtl(q);
        out[0] = s->cx - h;
        out[1] = s->cx + h;
        return 2;
    }
    int k = 0;
    for (int i = 0; i < s->n; i++) {
        long double x0 = s->xy[2 * i], y0 = s->xy[2 * i + 1];
        long double x1 = s->xy[2 * ((i + 1) % s->n)], y1 = s->xy[2 * ((i + 1) % s->n) + 1];
        if ((y0 <= y && y < y1) || (y1 <= y && y < y0))
            out[k++] = x0 + (y - y0) * (x1 - x0) / (y1 - y0);
    }
    return k;
}

static int shape_inside(const shape *s, long double x, long double y)
{
    if (s->kind == 0)
        return (x - s->cx) * (x - s->cx) + (y - s->cy) * (y - s->cy) < (long double)s->r * s->r;
    int in = 0;
    for (int i = 0; i < s->n; i++) {
        long double x0 = s->xy[2 * i], y0 = s->xy[2 * i + 1];
        long double x1 = s->xy[2 * ((i + 1) % s->n)], y1 = s->xy[2 * ((i + 1) % s->n) + 1];
        if ((y0 <= y && y < y1) || (y1 <= y && y < y0))
            if (x < x0 + (y - y0) * (x1 - x0) / (y1 - y0))
                in ^= 1;
    }
    return in;
}

/* Evaluates the RPN over operand memberships (operand = evenodd of its shapes). */
static int rpn_eval(const int *rpn, int len, const int *in_operand)
{
    int st[32], sp = 0;
    for (int i = 0; i < len; i++) {
        if (rpn[i] >= 0) {
            st[sp++] = in_operand[rpn[i]];
            continue;
        }
        int b = st[--sp], a = st[--sp];
        st[sp++] = rpn[i] == CS_CSG_UNION       ? (a || b)
                   : rpn[i] == CS_CSG_INTERSECT ? (a && b)
                   : rpn[i] == CS_CSG_DIFFERENCE ? (a && !b)
                                                 : (a != b);
    }
    return st[0];
}

static void reference_coverage(const shape *sh, int ns, const int *rpn, int len, int w, int h,
                               double *cov)
{
    const int rows = 512;
    for (int i = 0; i < w * h; i++)
        cov[i] = 0;
    long double brk[64];
    for (int y = 0; y < h; y++)
        for (int k = 0; k < rows; k++) {
            long double ys = y + (k + 0.5L) / rows;
            int nb = 0;
            for (int s = 0; s < ns; s++)
                nb += shape_breaks(&sh[s], ys, brk + nb);
            brk[nb++] = 0;
            brk[nb++] = w;
            for (int i = 1; i < nb; i++) /* insertion sort */
                for (int j = i; j > 0 && brk[j - 1] > brk[j]; j--) {
                    long double t = brk[j];
                    brk[j] = brk[j - 1];
                    brk[j - 1] = t;
                }
            for (int i = 0; i + 1 < nb; i++) {
                long double a = brk[i] < 0 ? 0 : brk[i], b = brk[i + 1] > w ? w : brk[i + 1];
                if (!(b > a))
                    continue;
                long double mid = 0.5L * (a + b);
                int in_op[8] = {0};
                for (int s = 0; s < ns; s++)
                    in_op[sh[s].operand] ^= shape_inside(&sh[s], mid, ys);
                if (!rpn_eval(rpn, len, in_op))
                    continue;
                for (int px = (int)a; px < w && px < b; px++)
                    cov[y * w + px] += (double)(overlap((double)a, (double)b, px) / rows);
            }
        }
}

/* Coverage as celscan renders it: white paint, black surround. */
static void celscan_coverage(const shape *sh, int ns, const int *rpn, int len, int w, int h,
                             int aa, double *cov)
{
    cs_scene *s = &g_scene;
    cs_scene_init(s, (float)w, (float)h);
    add_cel(s, NULL, NULL, NULL);
    cs_paint p = paint(1, 1, 1, 0, 0, 0, 1);
    cs_error e;
    cs_scene_add_region(s, CS_FILL_EVENODD, &p, &e);
    if (len > 0) {
        cs_status st = cs_scene_set_region_csg(s, rpn, len, &e);
        CHECK(st == CS_OK, "set csg: %s", cs_status_str(st));
    }
    for (int i = 0; i < ns; i++) {
        if (sh[i].kind == 0)
            TL_MUST(ts_add_circle(s, sh[i].cx, sh[i].cy, sh[i].r));
        else
            TL_MUST(ts_add_polygon(s, sh[i].xy, sh[i].n));
        cs_scene_set_contour_operand(s, sh[i].operand, &e);
    }
    cs_render_opts o = opts_n(w, h, 64);
    o.aa = aa ? CS_AA_EXACT : CS_AA_SUBSCAN;
    CHECK(render(s, &o, NULL, img_c) == CS_OK, "render csg");
    for (int i = 0; i < w * h; i++)
        cov[i] = img_c[3 * i];
}

static double cov_ref[64 * 64], cov_got[64 * 64], cov_a[64 * 64], cov_b[64 * 64],
    cov_ab[64 * 64];

static void test_csg(void)
{
    static const double tri[6] = {6, 58, 60, 50.5, 30.3, 6.2};
    static const double square[8] = {20.5, 20.5, 44.25, 20.5, 44.25, 44.75, 20.5, 44.75};
    /* Operands: 0 = circle A, 1 = circle B, 2 = triangle, 3 = ring (two
     * circles in one operand: evenodd makes it a ring), 4 = square. */
    const shape sh[] = {
        {0, 24, 28, 15.5, NULL, 0, 0}, {0, 38.3, 31.7, 13.2, NULL, 0, 1},
        {1, 0, 0, 0, tri, 3, 2},       {0, 32, 32, 27, NULL, 0, 3},
        {0, 32, 32, 22.5, NULL, 0, 3}, {1, 0, 0, 0, square, 4, 4},
    };
    const int ns = 6;
    struct {
        const char *name;
        int rpn[8];
        int len;
    } progs[] = {
        {"A union B", {0, 1, CS_CSG_UNION}, 3},
        {"A intersect B", {0, 1, CS_CSG_INTERSECT}, 3},
        {"A - B", {0, 1, CS_CSG_DIFFERENCE}, 3},
        {"A xor B", {0, 1, CS_CSG_XOR}, 3},
        {"(A - B) u tri", {0, 1, CS_CSG_DIFFERENCE, 2, CS_CSG_UNION}, 5},
        {"tri n (A u B)", {2, 0, 1, CS_CSG_UNION, CS_CSG_INTERSECT}, 5},
        {"ring - square", {3, 4, CS_CSG_DIFFERENCE}, 3},
        {"ring xor tri", {3, 2, CS_CSG_XOR}, 3},
    };
    const int W = 64, H = 64;
    for (unsigned p = 0; p < sizeof progs / sizeof progs[0]; p++) {
        reference_coverage(sh, ns, progs[p].rpn, progs[p].len, W, H, cov_ref);
        for (int aa = 0; aa < 2; aa++) {
            celscan_coverage(sh, ns, progs[p].rpn, progs[p].len, W, H, aa, cov_got);
            double worst = 0, sum = 0, area_ref = 0, area_got = 0;
            for (int i = 0; i < W * H; i++) {
                double d = fabs(cov_got[i] - cov_ref[i]);
                worst = d > worst ? d : worst;
                sum += d;
                area_ref += cov_ref[i];
                area_got += cov_got[i];
            }
            /* 64 sub-scanlines: per pixel the midpoint rule errs by at most
             * half a sub-scanline's height across the pixel (1/128). */
            CHECK(worst <= 1.0 / 128 + 1e-4 && sum / (W * H) < 1e-3,
                  "csg %s (aa %d): worst %.4f mean %.2e", progs[p].name, aa, worst,
                  sum / (W * H));
            CHECK(fabs(area_got - area_ref) < 0.05, "csg %s area %.3f vs %.3f", progs[p].name,
                  area_got, area_ref);
            if (aa == 0)
                printf("  csg %-14s area %8.3f ref %8.3f  worst %.4f  mean %.1e\n",
                       progs[p].name, area_got, area_ref, worst, sum / (W * H));
        }
    }
    /* Identities on the renderer's own coverage (same samples, so tight):
     * |A u B| + |A n B| = |A| + |B|, |A - B| = |A| - |A n B|,
     * |A xor B| = |A u B| - |A n B|. */
    int ra[] = {0}, rb[] = {1}, run[] = {0, 1, CS_CSG_UNION}, rin[] = {0, 1, CS_CSG_INTERSECT};
    int rdf[] = {0, 1, CS_CSG_DIFFERENCE}, rx[] = {0, 1, CS_CSG_XOR};
    celscan_coverage(sh, ns, ra, 1, W, H, 0, cov_a);
    celscan_coverage(sh, ns, rb, 1, W, H, 0, cov_b);
    celscan_coverage(sh, ns, rin, 3, W, H, 0, cov_ab);
    double w1 = 0, w2 = 0, w3 = 0;
    celscan_coverage(sh, ns, run, 3, W, H, 0, cov_got);
    for (int i = 0; i < W * H; i++)
        w1 = fmax(w1, fabs(cov_got[i] + cov_ab[i] - cov_a[i] - cov_b[i]));
    celscan_coverage(sh, ns, rdf, 3, W, H, 0, cov_got);
    for (int i = 0; i < W * H; i++)
        w2 = fmax(w2, fabs(cov_got[i] - (cov_a[i] - cov_ab[i])));
    celscan_coverage(sh, ns, rx, 3, W, H, 0, cov_ref);
    celscan_coverage(sh, ns, run, 3, W, H, 0, cov_got);
    for (int i = 0; i < W * H; i++)
        w3 = fmax(w3, fabs(cov_ref[i] - (cov_got[i] - cov_ab[i])));
    CHECK(w1 < 1e-4 && w2 < 1e-4 && w3 < 1e-4, "csg identities: %.2e %.2e %.2e", w1, w2, w3);
    /* A region without CSG ignores operands: contours wind together. */
    cs_scene *s = &g_scene;
    cs_scene_init(s, 64, 64);
    add_cel(s, NULL, NULL, NULL);
    add_region(s, paint(1, 1, 1, 0, 0, 0, 1));
    cs_error e;
    TL_MUST(ts_add_circle(s, 24, 28, 15.5));
    cs_scene_set_contour_operand(s, 3, &e);
    cs_render_opts o = opts_n(64, 64, 64);
    render(s, &o, NULL, img_c);
    int rq[] = {0};
    shape one = sh[0];
    reference_coverage(&one, 1, rq, 1, W, H, cov_ref);
    double worst = 0;
    for (int i = 0; i < W * H; i++)
        worst = fmax(worst, fabs(img_c[3 * i] - cov_ref[i]));
    CHECK(worst <= 1.0 / 128 + 1e-4, "no-csg region with an operand set: %.4f", worst);
}

static void test_csg_validation(void)
{
    cs_scene *s = &g_scene;
    cs_scene_init(s, 10, 10);
    cs_error e;
    int bad_under[] = {0, CS_CSG_UNION};
    int bad_left[] = {0, 1};
    int bad_op[] = {0, 1, -9};
    int bad_operand[] = {CS_CFG_MAX_OPERANDS};
    int good[] = {0, 1, CS_CSG_XOR};
    CHECK(cs_scene_set_region_csg(s, good, 3, &e) == CS_ERR_STATE, "csg before any region");
    add_cel(s, NULL, NULL, NULL);
    add_region(s, paint(1, 1, 1, 0, 0, 0, 1));
    CHECK(cs_scene_set_region_csg(s, bad_under, 2, &e) == CS_ERR_CSG && e.item == 1,
          "operator without two inputs (item %d)", e.item);
    CHECK(cs_scene_set_region_csg(s, bad_left, 2, &e) == CS_ERR_CSG, "two results left");
    CHECK(cs_scene_set_region_csg(s, bad_op, 3, &e) == CS_ERR_CSG && e.item == 2, "bad operator");
    CHECK(cs_scene_set_region_csg(s, bad_operand, 1, &e) == CS_ERR_CSG, "operand out of range");
    CHECK(cs_scene_set_region_csg(s, good, 0, &e) == CS_ERR_CSG, "empty program");
    CHECK(cs_scene_set_region_csg(s, good, CS_CFG_MAX_CSG + 1, &e) == CS_ERR_CSG, "too long");
    CHECK(s->regions[0].csg_len == 0, "rejected programs leave the region unchanged");
    CHECK(cs_scene_set_region_csg(s, good, 3, &e) == CS_OK, "good program");
    CHECK(cs_scene_set_contour_operand(s, 1, &e) == CS_ERR_STATE, "operand before a contour");
    TL_MUST(ts_add_rect(s, 1, 1, 5, 5));
    CHECK(cs_scene_set_contour_operand(s, -1, &e) == CS_ERR_CSG, "negative operand");
    CHECK(cs_scene_set_contour_operand(s, CS_CFG_MAX_OPERANDS, &e) == CS_ERR_CSG,
          "operand too large");
    CHECK(cs_scene_set_contour_operand(s, 1, &e) == CS_OK && s->contours[0].operand == 1,
          "operand set");
}

static void test_func_validation(void)
{
    cs_scene *s = &g_scene;
    cs_scene_init(s, 10, 10);
    cs_error e;
    const double g[6] = {0, 0, 10, 0, 0, 0};
    const double off[3] = {0, 0.5, 1};
    const double v[3][3] = {{0, 0, 0}, {0.5, 0.5, 0.5}, {1, 1, 1}};
    cs_paint_func f = make_func(CS_FUNC_LINEAR, 0, g, 4, 3, off, v);
    CHECK(cs_scene_set_region_func(s, CS_FIELD_PIGMENT, &f, &e) == CS_ERR_STATE, "no region");
    add_cel(s, NULL, NULL, NULL);
    add_region(s, paint(1, 1, 1, 0, 0, 0, 1));
    CHECK(cs_scene_set_region_func(s, CS_FIELD_PIGMENT, &f, &e) == CS_OK, "good linear");
    CHECK(cs_scene_set_region_func(s, CS_FIELD_PIGMENT, &f, &e) == CS_OK && s->func_count == 1,
          "setting again replaces (count %u)", s->func_count);
    CHECK(cs_scene_set_region_func(s, (cs_paint_field)3, &f, &e) == CS_ERR_ARG, "bad field");
    cs_paint_func b = f;
    b.stops[1].offset = 1.5f;
    CHECK(cs_scene_set_region_func(s, CS_FIELD_MEDIUM, &b, &e) == CS_ERR_FUNC && e.item == 1,
          "offset > 1");
    b = f;
    b.stops[2].offset = 0.25f;
    CHECK(cs_scene_set_region_func(s, CS_FIELD_MEDIUM, &b, &e) == CS_ERR_FUNC && e.item == 2,
          "offsets out of order");
    b = f;
    b.stops[0].value[1] = 1.25f;
    CHECK(cs_scene_set_region_func(s, CS_FIELD_MEDIUM, &b, &e) == CS_ERR_PAINT, "value > 1");
    b = f;
    b.stops[0].value[1] = NAN;
    CHECK(cs_scene_set_region_func(s, CS_FIELD_MEDIUM, &b, &e) == CS_ERR_NONFINITE, "NaN value");
    b = f;
    b.geom[2] = 0;
    CHECK(cs_scene_set_region_func(s, CS_FIELD_MEDIUM, &b, &e) == CS_ERR_FUNC, "p0 = p1");
    b = f;
    b.geom[1] = INFINITY;
    CHECK(cs_scene_set_region_func(s, CS_FIELD_MEDIUM, &b, &e) == CS_ERR_NONFINITE, "inf geom");
    b = f;
    b.stop_count = 0;
    CHECK(cs_scene_set_region_func(s, CS_FIELD_MEDIUM, &b, &e) == CS_ERR_FUNC, "no stops");
    b.stop_count = CS_CFG_MAX_STOPS + 1;
    CHECK(cs_scene_set_region_func(s, CS_FIELD_MEDIUM, &b, &e) == CS_ERR_FUNC, "too many stops");
    const double rg[5] = {5, 5, 3, 5, 8.5};
    b = make_func(CS_FUNC_RADIAL, 0, rg, 5, 3, off, v);
    CHECK(cs_scene_set_region_func(s, CS_FIELD_MEDIUM, &b, &e) == CS_ERR_FUNC,
          "focal outside the circle");
    b.geom[4] = 6;
    CHECK(cs_scene_set_region_func(s, CS_FIELD_MEDIUM, &b, &e) == CS_OK, "focal inside");
    b.geom[2] = 0;
    CHECK(cs_scene_set_region_func(s, CS_FIELD_MEDIUM, &b, &e) == CS_ERR_FUNC, "r = 0");
    const double mg[6] = {0, 0, 1, 1, 2, 2};
    b = make_func(CS_FUNC_MAP, 0, mg, 6, 3, NULL, v);
    b.map_cols = 3;
    CHECK(cs_scene_set_region_func(s, CS_FIELD_BETA, &b, &e) == CS_ERR_FUNC, "parallel map axes");
    b.geom[4] = -2;
    b.map_cols = 2;
    CHECK(cs_scene_set_region_func(s, CS_FIELD_BETA, &b, &e) == CS_ERR_FUNC,
          "3 values do not make rows of 2");
    b.map_cols = 3;
    CHECK(cs_scene_set_region_func(s, CS_FIELD_BETA, &b, &e) == CS_OK, "good map");
    b.kind = 9;
    CHECK(cs_scene_set_region_func(s, CS_FIELD_BETA, &b, &e) == CS_ERR_FUNC, "bad kind");
    /* Capacity: every region takes new functions until the store is full. */
    cs_status st = CS_OK;
    for (int i = 0; i < CS_CFG_MAX_FUNCS + 2 && st == CS_OK; i++) {
        add_region(s, paint(1, 1, 1, 0, 0, 0, 1));
        st = cs_scene_set_region_func(s, CS_FIELD_PIGMENT, &f, &e);
    }
    CHECK(st == CS_ERR_CAP_FUNCS && s->func_count == CS_CFG_MAX_FUNCS, "function capacity: %s",
          cs_status_str(st));
}

/* ----------------------------------------------------- 8. dithering */

static void test_dither(void)
{
    enum { W = 256 };
    static float line[3 * W];
    static uint8_t out[8][3 * W], plain[3 * W];
    /* A slow ramp: the mean of each 8x8 tile must track the input. */
    for (int x = 0; x < W; x++)
        for (int k = 0; k < 3; k++)
            line[3 * x + k] = (float)srgb_inv(0.2 + 0.1 * x / W);
    const cs_pixfmt fmts[] = {CS_PIX_RGB565_SRGB, CS_PIX_RGB444_SRGB, CS_PIX_RGB332_SRGB,
                              CS_PIX_RGB888_SRGB};
    for (unsigned f = 0; f < 4; f++) {
        for (int y = 0; y < 8; y++)
            cs_pixfmt_convert_dither(fmts[f], line, W, y, out[y]);
        cs_pixfmt_convert(fmts[f], line, W, plain);
        double worst = 0, worst_plain = 0;
        int levels_plain = 0, last = -1;
        for (int tile = 0; tile < W / 8; tile++) {
            double sum = 0, sum_plain = 0, want = 0;
            for (int y = 0; y < 8; y++)
                for (int x = tile * 8; x < tile * 8 + 8; x++) {
                    /* green channel, in output steps */
                    double g, gp, max;
                    if (fmts[f] == CS_PIX_RGB565_SRGB) {
                        g = ((out[y][2 * x] | out[y][2 * x + 1] << 8) >> 5) & 63;
                        gp = ((plain[2 * x] | plain[2 * x + 1] << 8) >> 5) & 63;
                        max = 63;
                    } else if (fmts[f] == CS_PIX_RGB444_SRGB) {
                        g = (out[y][2 * x] >> 4) & 15;
                        gp = (plain[2 * x] >> 4) & 15;
                        max = 15;
                    } else if (fmts[f] == CS_PIX_RGB332_SRGB) {
                        g = (out[y][x] >> 2) & 7;
                        gp = (plain[x] >> 2) & 7;
                        max = 7;
                    } else {
                        g = out[y][3 * x + 1];
                        gp = plain[3 * x + 1];
                        max = 255;
                    }
                    sum += g / max;
                    sum_plain += gp / max;
                    want += srgb(line[3 * x + 1]);
                    if (y == 0 && (int)gp != last) {
                        levels_plain++;
                        last = (int)gp;
                    }
                }
            worst = fmax(worst, fabs(sum - want) / 64);
            worst_plain = fmax(worst_plain, fabs(sum_plain - want) / 64);
        }
        /* Tile means within ~1/64 of a step (plus the encoder's rounding). */
        double step = fmts[f] == CS_PIX_RGB565_SRGB   ? 1.0 / 63
                      : fmts[f] == CS_PIX_RGB444_SRGB ? 1.0 / 15
                      : fmts[f] == CS_PIX_RGB332_SRGB ? 1.0 / 7
                                                      : 1.0 / 255;
        CHECK(worst <= step * 0.1, "dither fmt %d: tile mean off by %.4f (step %.4f)", fmts[f],
              worst, step);
        if (fmts[f] != CS_PIX_RGB888_SRGB)
            CHECK(worst < worst_plain, "dither fmt %d does not beat banding (%.4f vs %.4f)",
                  fmts[f], worst, worst_plain);
        printf("  dither fmt %d: tile-mean error %.2f%% of a step (plain rounding %.2f%%)\n",
               fmts[f], 100 * worst / step, 100 * worst_plain / step);
    }
    /* Values exactly on an output level are left alone: every level of the
     * 4- and 8-bit formats is a whole 16-bit code (4369 k, 257 k). */
    int disturbed = 0;
    for (int bits = 4; bits <= 8; bits += 4) {
        unsigned max = (1u << bits) - 1u, stepc = 65535u / max;
        cs_pixfmt fmt = bits == 4 ? CS_PIX_RGB444_SRGB : CS_PIX_RGB888_SRGB;
        for (unsigned lvl = 0; lvl <= max; lvl++) {
            float v = cs_srgb_decode((float)(lvl * stepc) / 65535.0f);
            if (cs_srgb_encode16(v) != lvl * stepc)
                continue; /* covered by the round-trip test */
            float px[3 * 8];
            for (int i = 0; i < 24; i++)
                px[i] = v;
            uint8_t a[24], b[24];
            for (int y = 0; y < 8; y++) {
                cs_pixfmt_convert_dither(fmt, px, 8, y, a);
                cs_pixfmt_convert(fmt, px, 8, b);
                disturbed += memcmp(a, b, cs_pixfmt_bytes_per_pixel(fmt) * 8) != 0;
            }
        }
    }
    CHECK(disturbed == 0, "dithering disturbed %d exact levels", disturbed);
    uint8_t a1[3 * W], a2[3 * W];
    cs_pixfmt_convert_dither(CS_PIX_RGB565_SRGB, line, W, 5, a1);
    cs_pixfmt_convert_dither(CS_PIX_RGB565_SRGB, line, W, 5, a2);
    CHECK(memcmp(a1, a2, 2 * W) == 0, "dither deterministic");
    /* Plain RGB565 as before: nearest of 31 steps of the sRGB code. */
    int bad = 0;
    for (int i = 0; i < 1000; i++) {
        float v = (float)i / 999.0f;
        float px[3] = {v, v, v};
        uint8_t o[2];
        cs_pixfmt_convert(CS_PIX_RGB565_SRGB, px, 1, o);
        unsigned r5 = (unsigned)(o[1] >> 3);
        double want = srgb(v) * 31;
        if (fabs(r5 - want) > 0.5 + 1e-3)
            bad++;
    }
    CHECK(bad == 0, "plain RGB565 rounding changed (%d)", bad);
    /* Packing of the new formats. */
    float px[3] = {1, 0, 1};
    uint8_t o[2];
    cs_pixfmt_convert(CS_PIX_RGB444_SRGB, px, 1, o);
    CHECK(o[0] == 0x0F && o[1] == 0x0F, "RGB444 packing %02x %02x", o[0], o[1]);
    cs_pixfmt_convert(CS_PIX_RGB332_SRGB, px, 1, o);
    CHECK(o[0] == 0xE3, "RGB332 packing %02x", o[0]);
    CHECK(cs_pixfmt_bytes_per_pixel(CS_PIX_RGB444_SRGB) == 2 &&
              cs_pixfmt_bytes_per_pixel(CS_PIX_RGB332_SRGB) == 1,
          "bytes per pixel");
}

/* --------------------------------------------------- 9. sRGB blending */

static void test_srgb_blend(void)
{
    /* decode inverts encode on every 16-bit code. */
    int bad = 0;
    double worst = 0;
    for (int c = 0; c <= 65535; c++) {
        float lin = cs_srgb_decode((float)c / 65535.0f);
        if (abs((int)cs_srgb_encode16(lin) - c) > 0)
            bad++;
        worst = fmax(worst, fabs(lin - srgb_inv(c / 65535.0)));
    }
    CHECK(bad == 0, "encode(decode(c)) != c for %d codes", bad);
    CHECK(worst < 2e-5, "decode vs pow: %.2e", worst);
    /* Half-transparent red over blue, blended as SVG does: in sRGB codes. */
    cs_scene *s = &g_scene;
    cs_scene_init(s, 16, 16);
    float blue[3] = {0, 0, 1};
    cs_scene_set_background(s, blue);
    add_cel(s, NULL, NULL, NULL);
    add_region(s, paint(1, 0, 0, 1, 1, 1, 0.5));
    TL_MUST(ts_add_rect(s, 0, 0, 8.5, 16));
    /* a gradient too: stops interpolate in sRGB */
    add_region(s, paint(1, 1, 1, 1, 1, 1, 1));
    TL_MUST(ts_add_rect(s, 8.5, 0, 16, 16));
    const double g[4] = {8.5, 0, 16, 0}, off[2] = {0, 1};
    const double v[2][3] = {{srgb_inv(0.2), srgb_inv(0.2), srgb_inv(0.2)},
                            {srgb_inv(0.8), srgb_inv(0.8), srgb_inv(0.8)}};
    cs_paint_func fn = make_func(CS_FUNC_LINEAR, 0, g, 4, 2, off, v);
    cs_error e;
    cs_scene_set_region_func(s, CS_FIELD_PIGMENT, &fn, &e);
    cs_render_opts o = opts_n(16, 16, 4);
    o.blend = CS_BLEND_SRGB;
    CHECK(render(s, &o, NULL, img_a) == CS_OK, "render srgb");
    uint8_t px[3 * 16];
    cs_pixfmt_convert(CS_PIX_RGB888_SRGB, img_a + 3 * 16 * 5, 16, px);
    CHECK(abs(px[3 * 3] - 128) <= 1 && px[3 * 3 + 1] == 0 && abs(px[3 * 3 + 2] - 128) <= 1,
          "srgb blend: %d %d %d, want 128 0 128", px[9], px[10], px[11]);
    /* the edge pixel x = 8: half red-over-blue, half gradient start */
    for (int x = 10; x < 16; x++) {
        double t = (x + 0.5 - 8.5) / 7.5;
        double want = 255 * (0.2 + 0.6 * t);
        CHECK(fabs(px[3 * x] - want) <= 1.0, "srgb gradient at %d: %d want %.1f", x, px[3 * x],
              want);
    }
    o.blend = CS_BLEND_LINEAR;
    render(s, &o, NULL, img_b);
    cs_pixfmt_convert(CS_PIX_RGB888_SRGB, img_b + 3 * 16 * 5, 16, px);
    CHECK(abs(px[3 * 3] - 188) <= 1, "linear blend: %d, want 188", px[9]);
}

/* ------------------------------------------------- 10. defaults, misc */

static void test_defaults(void)
{
    cs_scene *s = &g_scene;
    cs_scene_init(s, 8, 8);
    add_cel(s, NULL, NULL, NULL);
    add_region(s, paint(0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5));
    TL_MUST(ts_add_rect(s, 0, 0, 8, 8));
    float f[3] = {0.4f, 0.8f, 1.6f}, b[3] = {0.3f, 0.2f, 0.1f};
    cs_scene_set_lights(s, f, b);
    cs_render_opts o = opts_n(8, 8, 1);
    render(s, &o, NULL, img_a);
    /* cel front = stack front (set later), cel back = black, L = B_s */
    double want[3];
    for (int k = 0; k < 3; k++)
        want[k] = 0.5 * 0.5 * f[k] + 0.25 * b[k];
    CHECK(lin_diff(img_a, want) < 1e-6, "defaults: cel front follows the stack, back black");
    float bg[3] = {0.5f, 0.25f, 0.5f};
    cs_scene_set_background(s, bg);
    render(s, &o, NULL, img_a);
    for (int k = 0; k < 3; k++)
        want[k] = 0.5 * 0.5 * f[k] + 0.25 * bg[k] * f[k];
    CHECK(lin_diff(img_a, want) < 1e-6, "background card lit by the stack front");
    CHECK(strcmp(cs_status_str(CS_ERR_CAP_CACHE), "unknown status") != 0 &&
              strcmp(cs_status_str(CS_ERR_CSG), "unknown status") != 0,
          "status strings");
}

int main(void)
{
    test_defaults();
    test_closed_form();
    test_alpha_over();
    test_mattes();
    test_gradients();
    test_early_out_exact();
    test_cache();
    test_grey_path();
    test_csg();
    test_csg_validation();
    test_func_validation();
    test_dither();
    test_srgb_blend();
    return tl_summary("test_beta");
}
