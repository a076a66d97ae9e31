/*
 * test_image.c - rendered coverage against the independent truth.
 *
 * Every scene paints one opaque white region with no background, so the
 * linear output of a pixel is its coverage. It is compared with tests/ref:
 *
 *   - CS_AA_SUBSCAN 16 against the exact area of the pixel square inside the
 *     region: worst pixel within 12/255, mean over the image within 0.5/255.
 *     (16 sub-scanlines at y = j + (k+0.5)/16 err by up to 1/32 = 8/255 on a
 *     pixel crossed by one horizontal edge; 12/255 leaves room for two
 *     sloped edges in one pixel.)
 *   - CS_AA_SUBSCAN 16 against the reference's model of 16 sub-scanlines with
 *     exact horizontal coverage: within 0.25/255, because horizontal coverage is
 *     exact (spans have real end points).
 *   - CS_AA_NONE against the pixel-centre truth, pixels whose centre is within
 *     1e-3 px of the boundary excused.
 *
 * Also: resolution independence (4x size box-filtered back down), sub-pixel
 * motion (coverage centroid against the truth's, 1/100 px), cs_render_frame
 * against cs_render_line, skipped lines, determinism.
 */
#include "common.h"

typedef struct image_case {
    const char *name;
    float cw, ch; /* canvas */
    int W, H;     /* device */
    cs_affine xf;
} image_case;

/* Renders the shape in every mode and checks it against the reference. */
static void check_image(const char *name, const tc_shape *s, float cw, float ch, int W, int H,
                        const cs_affine *xf)
{
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    if (tc_scene_one(sc, cw, ch, xf, s) != CS_OK) {
        tl_note("case %s", name);
        free(sc);
        return;
    }
    ref_region *ref = tc_ref(s, xf, (double)W / cw, (double)H / ch);
    size_t n = (size_t)W * H;
    double *got = tl_calloc(n, sizeof *got), *area = tl_calloc(n, sizeof *area);
    double *model = tl_calloc(n, sizeof *model);
    unsigned char *in = tl_calloc(n, 1), *amb = tl_calloc(n, 1);
    char what[200];

    ref_coverage_area(ref, W, H, area);
    if (tc_render(sc, W, H, CS_AA_SUBSCAN, 16, got) == CS_OK) {
        snprintf(what, sizeof what, "%s: 16 sub-scanlines vs exact area", name);
        tc_expect_close(what, got, area, W, H, 12.0 / 255, 0.5 / 255);
        ref_coverage_subscan(ref, W, H, 16, model);
        snprintf(what, sizeof what, "%s: 16 sub-scanlines vs 16-line model", name);
        tc_expect_close(what, got, model, W, H, 0.25 / 255, 0.02 / 255);
    }
    ref_coverage_centre(ref, W, H, 1e-3, in, amb);
    if (tc_render(sc, W, H, CS_AA_NONE, 1, got) == CS_OK) {
        snprintf(what, sizeof what, "%s: aa none vs pixel centres", name);
        tc_expect_centre(what, got, in, amb, W, H);
    }
    free(got);
    free(area);
    free(model);
    free(in);
    free(amb);
    ref_region_free(ref);
    free(sc);
}

static void test_circles(void)
{
    static const double radii[] = {0.3, 0.7, 1.5, 3.3, 7.77, 20.25, 45.6};
    for (int k = 0; k < 7; k++) {
        tc_shape *s = tc_shape_new(0);
        double cx = 50 + 0.37 * k, cy = 49.5 + 0.213 * k;
        tc_add_circle(s, cx, cy, radii[k], k % 2);
        char name[80];
        snprintf(name, sizeof name, "circle r=%g at (%.3f, %.3f)", radii[k], cx, cy);
        check_image(name, s, 100, 100, 100, 100, &tc_identity);
        free(s);
    }
}

/* A rational cubic blob: non-unit weights and non-uniform intervals with a zero. */
static void add_blob(tc_shape *s, double cx, double cy, double scale)
{
    static const double pts[7][3] = {{1, 0, 1},     {0.7, 0.8, 2.5}, {-0.2, 1.1, 0.6}, {-1, 0.4, 1},
                                     {-0.9, -0.6, 3}, {0.1, -1, 0.4},  {0.8, -0.7, 1.7}};
    static const double iv[7] = {1, 0.5, 2, 0, 1.5, 0.75, 1};
    double xyw[21];
    for (int k = 0; k < 7; k++) {
        xyw[3 * k] = cx + scale * pts[k][0];
        xyw[3 * k + 1] = cy + scale * pts[k][1];
        xyw[3 * k + 2] = pts[k][2];
    }
    tc_add(s, 3, 7, xyw, iv);
}

static void test_blobs(void)
{
    tc_shape *s = tc_shape_new(0);
    add_blob(s, 40.3, 38.7, 30);
    check_image("rational cubic blob", s, 80, 80, 80, 80, &tc_identity);
    free(s);
    /* Degree 2 with weights and a Bezier-style path (conic arcs). */
    double conic[] = {10, 40, 1, 20, 5, 3, 60, 12, 1, 72, 50, 0.3, 40, 75, 1, 12, 70, 2};
    double civ[] = {1, 0, 1, 0, 1, 0};
    s = tc_shape_new(0);
    tc_add(s, 2, 6, conic, civ);
    check_image("conic arcs with weights 3, 0.3, 2", s, 80, 80, 80, 80, &tc_identity);
    free(s);
}

static void test_rings(void)
{
    tc_shape *s = tc_shape_new(0);
    tc_add_circle(s, 40.2, 39.9, 30, 1);
    tc_add_circle(s, 42.7, 37.1, 14.5, 0);
    check_image("ring, nonzero, hole reversed", s, 80, 80, 80, 80, &tc_identity);
    free(s);
    s = tc_shape_new(1);
    tc_add_circle(s, 40.2, 39.9, 30, 1);
    tc_add_circle(s, 42.7, 37.1, 14.5, 1);
    check_image("ring, evenodd, hole same way", s, 80, 80, 80, 80, &tc_identity);
    free(s);
    /* Same orientation under nonzero: winding 2 inside, so no hole. */
    s = tc_shape_new(0);
    tc_add_circle(s, 40.2, 39.9, 30, 1);
    tc_add_circle(s, 42.7, 37.1, 14.5, 1);
    check_image("nested circles, nonzero, same way (filled)", s, 80, 80, 80, 80, &tc_identity);
    free(s);
    /* A blob with a circular hole crossing its outline. */
    s = tc_shape_new(1);
    add_blob(s, 40, 40, 28);
    tc_add_circle(s, 60, 45, 12, 1);
    check_image("blob minus overlapping circle, evenodd", s, 80, 80, 80, 80, &tc_identity);
    free(s);
}

static void test_stars(void)
{
    double star[10];
    for (int k = 0; k < 5; k++) {
        double a = -1.5707963267948966 + 0.1 + k * 2.5132741228718345;
        star[2 * k] = 40.3 + 33 * cos(a);
        star[2 * k + 1] = 41.1 + 33 * sin(a);
    }
    for (int p = 1; p <= 3; p++)
        for (int rule = 0; rule < 2; rule++) {
            tc_shape *s = tc_shape_new(rule);
            double xyw[15];
            for (int k = 0; k < 5; k++) {
                xyw[3 * k] = star[2 * k];
                xyw[3 * k + 1] = star[2 * k + 1];
                xyw[3 * k + 2] = p == 3 ? (k % 2 ? 2.0 : 0.7) : 1.0;
            }
            tc_add(s, p, 5, xyw, NULL);
            char name[80];
            snprintf(name, sizeof name, "star degree %d %s", p, rule ? "evenodd" : "nonzero");
            check_image(name, s, 80, 80, 80, 80, &tc_identity);
            free(s);
        }
}

static void test_slivers(void)
{
    static const struct {
        double ry, angle;
    } sl[] = {{0.35, 0.3}, {0.35, 0.9}, {0.1, 1.2}, {0.2, 2.0}, {0.05, 0.6}};
    for (int k = 0; k < 5; k++) {
        tc_shape *s = tc_shape_new(0);
        tc_add_ellipse(s, 40.3, 39.6, 30, sl[k].ry, sl[k].angle, 1);
        char name[80];
        snprintf(name, sizeof name, "sliver 30 x %g rotated %g rad", sl[k].ry, sl[k].angle);
        check_image(name, s, 80, 80, 80, 80, &tc_identity);
        free(s);
    }
    /* Thin degree-1 wedge meeting at a sharp point. */
    double wedge[] = {5.2, 10.3, 75.1, 40.6, 5.7, 12.1};
    tc_shape *s = tc_shape_new(0);
    tc_add_xy(s, 1, 3, wedge, NULL);
    check_image("thin wedge", s, 80, 80, 80, 80, &tc_identity);
    free(s);
}

static void test_transforms(void)
{
    const double a = 0.5235987755982988;
    cs_affine rot = {(float)(1.7 * cos(a)), (float)(1.7 * sin(a)), (float)(-1.7 * sin(a)),
                     (float)(1.7 * cos(a)), 70.3f, -8.6f};
    tc_shape *s = tc_shape_new(0);
    add_blob(s, 30, 40, 20);
    check_image("blob in a rotated, scaled cel", s, 120, 120, 120, 120, &rot);
    /* Canvas 200x150 shown at 160x120 (scale 0.8), and at 300x225 (1.5). */
    check_image("blob, canvas 200x150 at 160x120", s, 200, 150, 160, 120, &rot);
    check_image("blob, canvas 200x150 at 300x225", s, 200, 150, 300, 225, &rot);
    free(s);
    cs_affine shear = {1, 0.3f, -0.5f, 0.9f, 40, 3};
    s = tc_shape_new(1);
    tc_add_circle(s, 30, 40, 25, 1);
    tc_add_circle(s, 35, 40, 10, 1);
    check_image("ring in a sheared cel", s, 120, 100, 120, 100, &shear);
    free(s);
    cs_affine mirror = {-1, 0, 0, 1, 100, 0};
    s = tc_shape_new(0);
    add_blob(s, 40, 40, 30);
    check_image("blob in a mirrored cel", s, 100, 80, 100, 80, &mirror);
    free(s);
}

static void test_many_contours(void)
{
    /* 40 overlapping circles in one nonzero region: the union. */
    tc_seed(5);
    tc_shape *s = tc_shape_new(0);
    for (int k = 0; k < 40; k++)
        tc_add_circle(s, tc_uniform(15, 85), tc_uniform(15, 85), tc_uniform(1, 12), k % 2);
    check_image("40 overlapping circles, nonzero union", s, 100, 100, 100, 100, &tc_identity);
    s->evenodd = 1;
    check_image("40 overlapping circles, evenodd", s, 100, 100, 100, 100, &tc_identity);
    free(s);
}

/* 4x the size, box-filtered back, gives the same picture. */
static void test_resolution_independence(void)
{
    tc_shape *s = tc_shape_new(1);
    add_blob(s, 30.3, 33.1, 22);
    tc_add_circle(s, 36.2, 30.7, 8.4, 1);
    tc_add_ellipse(s, 32, 34, 28, 0.6, 0.4, 1);
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    const int W = 64, H = 64, F = 4;
    if (tc_scene_one(sc, W, H, NULL, s) == CS_OK) {
        double *small = tl_calloc((size_t)W * H, sizeof *small);
        double *big = tl_calloc((size_t)W * H * F * F, sizeof *big);
        double *down = tl_calloc((size_t)W * H, sizeof *down);
        if (tc_render(sc, W, H, CS_AA_SUBSCAN, 16, small) == CS_OK &&
            tc_render(sc, W * F, H * F, CS_AA_SUBSCAN, 16, big) == CS_OK) {
            for (int j = 0; j < H; j++)
                for (int i = 0; i < W; i++) {
                    double sum = 0;
                    for (int b = 0; b < F; b++)
                        for (int a = 0; a < F; a++)
                            sum += big[(size_t)(j * F + b) * W * F + i * F + a];
                    down[j * W + i] = sum / (F * F);
                }
            tc_expect_close("64x64 vs 256x256 box-filtered to 64x64 (16 sub-scanlines)", small,
                            down, W, H, 12.0 / 255, 1.0 / 255);
            /* Against the truth both are close; the 4x one closer. */
            ref_region *ref = tc_ref(s, NULL, 1, 1);
            double *area = tl_calloc((size_t)W * H, sizeof *area);
            ref_coverage_area(ref, W, H, area);
            tc_expect_close("256x256 box-filtered to 64x64 vs exact area", down, area, W, H,
                            4.0 / 255, 0.25 / 255);
            free(area);
            ref_region_free(ref);
        }
        free(small);
        free(big);
        free(down);
    }
    free(sc);
    free(s);
}

static void centroid(const double *v, int W, int H, double *cx, double *cy)
{
    double sx = 0, sy = 0, sw = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            double c = v[(size_t)j * W + i];
            sx += c * (i + 0.5);
            sy += c * (j + 0.5);
            sw += c;
        }
    *cx = sx / sw;
    *cy = sy / sw;
}

/* Sub-pixel motion: the coverage centroid follows the truth's to 1/100 px. */
static void test_motion_centroid(void)
{
    const int W = 48, H = 48;
    tc_shape *s = tc_shape_new(0);
    tc_add_circle(s, 20.1, 22.3, 6.3, 1);
    add_blob(s, 26.0, 24.0, 5.0);
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    double *got = tl_calloc((size_t)W * H, sizeof *got), *area = tl_calloc((size_t)W * H, sizeof *area);
    double worst = 0;
    int worst_k = -1;
    double wg[2] = {0, 0}, wt[2] = {0, 0};
    for (int k = 0; k <= 16; k++) {
        cs_affine xf = {1, 0, 0, 1, (float)(k / 16.0 * 1.0), (float)(k / 16.0 * 0.75)};
        if (tc_scene_one(sc, W, H, &xf, s) != CS_OK)
            break;
        if (tc_render(sc, W, H, CS_AA_SUBSCAN, 16, got) != CS_OK)
            break;
        ref_region *ref = tc_ref(s, &xf, 1, 1);
        ref_coverage_area(ref, W, H, area);
        ref_region_free(ref);
        double gx, gy, tx, ty;
        centroid(got, W, H, &gx, &gy);
        centroid(area, W, H, &tx, &ty);
        double d = fmax(fabs(gx - tx), fabs(gy - ty));
        if (d > worst) {
            worst = d;
            worst_k = k;
            wg[0] = gx, wg[1] = gy, wt[0] = tx, wt[1] = ty;
        }
    }
    CHECK(worst <= 0.01,
          "moving shape, step %d/16: centroid expected (%.5f, %.5f), got (%.5f, %.5f): off by "
          "%.4f px (limit 0.01)",
          worst_k, wt[0], wt[1], wg[0], wg[1], worst);
    free(got);
    free(area);
    free(sc);
    free(s);
}

typedef struct sink_ctx {
    float *image;
    int width, height, calls, next_y, bad_order;
    int stop_at;
} sink_ctx;

static cs_status sink(void *user, int y, const float *rgb, int width)
{
    sink_ctx *c = user;
    if (y != c->next_y || width != c->width)
        c->bad_order++;
    c->next_y = y + 1;
    c->calls++;
    if (y >= 0 && y < c->height && width == c->width)
        memcpy(c->image + (size_t)3 * width * y, rgb, sizeof(float) * 3 * (size_t)width);
    if (c->stop_at >= 0 && y == c->stop_at)
        return CS_ERR_IO; /* the display refuses: the frame must stop here */
    return CS_OK;
}

static void test_render_frame_and_lines(void)
{
    const int W = 70, H = 50;
    tc_shape *s = tc_shape_new(1);
    add_blob(s, 35, 25, 20);
    tc_add_circle(s, 30, 25, 9, 1);
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    if (tc_scene_one(sc, W, H, NULL, s) != CS_OK)
        goto out;
    float *by_line = tl_calloc((size_t)3 * W * H, sizeof(float));
    float *by_frame = tl_calloc((size_t)3 * W * H, sizeof(float));
    float *again = tl_calloc((size_t)3 * W * H, sizeof(float));
    float *line = tl_calloc((size_t)3 * W, sizeof(float));
    tc_render_rgb(sc, W, H, CS_AA_SUBSCAN, 5, by_line);

    cs_renderer r;
    cs_render_opts o = {.width = W, .height = H, .aa = CS_AA_SUBSCAN, .subscanlines = 5};
    cs_error err;
    sink_ctx ctx = {by_frame, W, H, 0, 0, 0, -1};
    CHECK_STATUS(cs_frame_begin(&r, tc_workspace(), sc, &o, &err), CS_OK, "frame_begin");
    CHECK_STATUS(cs_render_frame(&r, line, sink, &ctx), CS_OK, "cs_render_frame");
    CHECK(ctx.calls == H && ctx.bad_order == 0,
          "sink called %d times (expected %d), %d out of order or wrong width", ctx.calls, H,
          ctx.bad_order);
    CHECK(memcmp(by_line, by_frame, sizeof(float) * 3 * W * H) == 0,
          "cs_render_frame output differs from cs_render_line output");

    /* A sink error stops the frame and is returned. */
    sink_ctx stop = {again, W, H, 0, 0, 0, 7};
    cs_frame_begin(&r, tc_workspace(), sc, &o, &err);
    CHECK_STATUS(cs_render_frame(&r, line, sink, &stop), CS_ERR_IO, "sink error returned");
    CHECK_EQ_INT(stop.calls, 8, "sink calls before the stop");

    /* Skipped lines: every third line, each equal to the full render's line. */
    cs_frame_begin(&r, tc_workspace(), sc, &o, &err);
    int bad = 0;
    for (int y = 1; y < H; y += 3) {
        if (cs_render_line(&r, y, line) != CS_OK ||
            memcmp(line, by_line + (size_t)3 * W * y, sizeof(float) * 3 * W) != 0) {
            if (bad++ < 4)
                tl_note("line %d differs when rendering every third line", y);
        }
    }
    CHECK(bad == 0, "%d skipped-line renders differ from the full render", bad);

    /* Determinism: the same frame again, bit for bit. */
    tc_render_rgb(sc, W, H, CS_AA_SUBSCAN, 5, again);
    CHECK(memcmp(by_line, again, sizeof(float) * 3 * W * H) == 0,
          "rendering the same frame twice gave different bits");

    /* A frame abandoned half way (wider, other mode) leaves nothing behind in the workspace. */
    cs_render_opts wide = {.width = W + 30, .height = H, .aa = CS_AA_SUBSCAN, .subscanlines = 16};
    float *wline = tl_calloc((size_t)3 * (W + 30), sizeof(float));
    cs_frame_begin(&r, tc_workspace(), sc, &wide, &err);
    for (int y = 0; y < H / 2; y++)
        cs_render_line(&r, y, wline);
    free(wline);
    tc_render_rgb(sc, W, H, CS_AA_SUBSCAN, 5, again);
    CHECK(memcmp(by_line, again, sizeof(float) * 3 * W * H) == 0,
          "a frame rendered after an abandoned one differs from a fresh render");

    /* cs_render_line writes exactly 3 * width floats. */
    float *guarded = tl_calloc((size_t)3 * W + 64, sizeof(float));
    for (int i = 0; i < 3 * W + 64; i++)
        guarded[i] = -7.0f;
    cs_frame_begin(&r, tc_workspace(), sc, &o, &err);
    for (int y = 0; y < H; y++)
        cs_render_line(&r, y, guarded);
    int past = 0;
    for (int i = 3 * W; i < 3 * W + 64; i++)
        past += guarded[i] != -7.0f;
    CHECK(past == 0, "cs_render_line wrote %d floats past 3 * width", past);
    free(guarded);
    free(by_line);
    free(by_frame);
    free(again);
    free(line);
out:
    free(sc);
    free(s);
}

int main(int argc, char **argv)
{
    (void)argc;
    TL_RUN(test_circles);
    TL_RUN(test_blobs);
    TL_RUN(test_rings);
    TL_RUN(test_stars);
    TL_RUN(test_slivers);
    TL_RUN(test_transforms);
    TL_RUN(test_many_contours);
    TL_RUN(test_resolution_independence);
    TL_RUN(test_motion_centroid);
    TL_RUN(test_render_frame_and_lines);
    free(tc_ws_);
    return tl_summary(argv[0]);
}
