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
 * renderer's quadratic). The cache (test_cache.c) and CSG (test_csg.c) have
 * programs of their own, on the same helpers (beta_common.h).
 *
 * On tests/testlib.h; the last line is `test_beta: N passed, M failed`.
 */
#include "beta_common.h"

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

/* ------------------------------------------------------ 6. the grey path */

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

/* ------------------------------------------- 7. paint function refusals */

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
    test_grey_path();
    test_func_validation();
    test_dither();
    test_srgb_blend();
    return tl_summary("test_beta");
}
