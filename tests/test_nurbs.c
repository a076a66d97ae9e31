/*
 * test_nurbs.c - NURBS contours become the right rational segments.
 *
 * cs_frame_begin converts every contour into power-basis rational segments in
 * device space (r.ws->segments). Per DESIGN.md, for a contour of N points the
 * segments are produced for j = 0..N-1 with intervals[j] != 0, in that order;
 * segment j covers knot span [t(j), t(j+1)), u in [0,1) mapping linearly onto
 * it, and is driven by control points j-p..j (mod N). Each is checked at many
 * u against the long double de Boor evaluation of tests/ref, straight from the
 * knots. The tolerance is relative to the coordinate magnitude (the core is
 * single precision): 1e-5 * max(1, |coordinate|).
 */
#include "common.h"

typedef struct contour_case {
    const char *name;
    int degree, n;
    double xyw[3 * 64];
    double iv[64];
    int has_iv;
} contour_case;

/* Core segment s at u, evaluated in long double from its float coefficients. */
static void seg_eval(const cs_segment *sg, long double u, long double out[2])
{
    long double X = 0, Y = 0, Wt = 0;
    for (int i = 3; i >= 0; i--) {
        X = X * u + sg->x[i];
        Y = Y * u + sg->y[i];
        Wt = Wt * u + sg->w[i];
    }
    out[0] = sg->ox + X / Wt;
    out[1] = sg->oy + Y / Wt;
}

/*
 * Builds a one-contour scene (canvas cw x ch, cel transform xf), renders the
 * frame set-up at W x H and compares every segment with the reference.
 */
static void check_shape(const char *name, const tc_shape *s, const cs_affine *xf, float cw,
                        float ch, int W, int H)
{
    int degree = s->degree[0], n = s->count[0];
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    if (tc_scene_one(sc, cw, ch, xf, s) != CS_OK) {
        tl_note("case %s", name);
        goto out;
    }
    ref_region *ref = tc_ref(s, xf, (double)W / cw, (double)H / ch);
    const ref_contour *c = &ref->contours[0];
    int spans[64], ns = 0;
    for (int j = 0; j < n; j++)
        if (c->iv[j] > 0)
            spans[ns++] = j;

    cs_renderer r;
    cs_render_opts o = {.width = W, .height = H, .aa = CS_AA_SUBSCAN, .subscanlines = 4};
    cs_error err;
    cs_status st = cs_frame_begin(&r, tc_workspace(), sc, &o, &err);
    if (CHECK(st == CS_OK, "%s: cs_frame_begin gave %s", name, tl_status_name(st)) &&
        CHECK((int)r.segment_count == ns, "%s: expected %d segments (one per non-zero interval), got %u",
              name, ns, (unsigned)r.segment_count)) {
        long double mag = 1;
        for (int k = 0; k < n; k++)
            mag = fmaxl(mag, fmaxl(fabsl(c->x[k]), fabsl(c->y[k])));
        double tol = 1e-5 * (double)mag;
        double worst = -1;
        int ws_ = -1;
        long double wu = 0, wp[2] = {0, 0}, wq[2] = {0, 0};
        int bad_meta = 0;
        for (int sgi = 0; sgi < ns; sgi++) {
            const cs_segment *sg = &r.ws->segments[sgi];
            if (sg->degree != degree || sg->region != 0)
                bad_meta++;
            for (int k = 0; k <= 64; k++) {
                long double u = k / 64.0L, p[2], q[2];
                seg_eval(sg, u, p);
                ref_eval_span(c, spans[sgi], u, q);
                double d = (double)fmaxl(fabsl(p[0] - q[0]), fabsl(p[1] - q[1]));
                if (!(d == d))
                    d = INFINITY;
                if (d > worst) {
                    worst = d;
                    ws_ = sgi;
                    wu = u;
                    wp[0] = p[0], wp[1] = p[1], wq[0] = q[0], wq[1] = q[1];
                }
            }
        }
        CHECK(bad_meta == 0, "%s: %d segments with degree != %d or region != 0", name, bad_meta,
              degree);
        CHECK(worst <= tol,
              "%s: segment %d (knot span %d) at u=%.4Lf: expected (%.6Lf, %.6Lf), got (%.6Lf, "
              "%.6Lf), off by %.3g px (limit %.3g)",
              name, ws_, ws_ >= 0 ? spans[ws_] : -1, wu, wq[0], wq[1], wp[0], wp[1], worst, tol);
    }
    ref_region_free(ref);
out:
    free(sc);
}

static void check_segments(const char *name, int degree, int n, const double *xyw,
                           const double *iv, const cs_affine *xf, float cw, float ch, int W, int H)
{
    tc_shape *s = tc_shape_new(0);
    tc_add(s, degree, n, xyw, iv);
    check_shape(name, s, xf, cw, ch, W, H);
    free(s);
}

static void test_degree1(void)
{
    double sq[] = {10, 10, 1, 90, 12, 1, 85, 80, 1, 15, 70, 1};
    check_segments("square, unit intervals", 1, 4, sq, NULL, NULL, 100, 100, 100, 100);
    double iv[] = {0.5, 3, 1, 0.125};
    check_segments("square, non-uniform intervals", 1, 4, sq, iv, NULL, 100, 100, 100, 100);
    double wq[] = {10, 10, 3, 90, 12, 0.5, 85, 80, 1, 15, 70, 2};
    check_segments("square, weights (non-linear speed)", 1, 4, wq, iv, NULL, 100, 100, 100, 100);
    double tri[] = {50, 5, 1, 95, 95, 1, 5, 95, 1};
    check_segments("triangle", 1, 3, tri, NULL, NULL, 100, 100, 100, 100);
    /* Degree 1, span j runs from point j-1 to point j: segment 0 starts at the last point. */
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    tc_shape *s = tc_shape_new(0);
    tc_add(s, 1, 3, tri, NULL);
    if (tc_scene_one(sc, 100, 100, NULL, s) == CS_OK) {
        cs_renderer r;
        cs_render_opts o = {.width = 100, .height = 100, .aa = CS_AA_NONE, .subscanlines = 1};
        cs_error err;
        if (cs_frame_begin(&r, tc_workspace(), sc, &o, &err) == CS_OK && r.segment_count == 3) {
            long double p[2];
            seg_eval(&r.ws->segments[0], 0, p);
            CHECK(fabsl(p[0] - 5) < 1e-4L && fabsl(p[1] - 95) < 1e-4L,
                  "degree-1 segment 0 should start at point N-1 (5,95), got (%.4Lf, %.4Lf)", p[0],
                  p[1]);
            seg_eval(&r.ws->segments[0], 1, p);
            CHECK(fabsl(p[0] - 50) < 1e-4L && fabsl(p[1] - 5) < 1e-4L,
                  "degree-1 segment 0 should end at point 0 (50,5), got (%.4Lf, %.4Lf)", p[0], p[1]);
        }
    }
    free(s);
    free(sc);
}

static void test_circle_on_circle(void)
{
    static const double radii[] = {0.4, 3, 17.25, 60};
    for (int ri = 0; ri < 4; ri++) {
        double R = radii[ri], cx = 64.3, cy = 63.8;
        for (int ccw = 0; ccw < 2; ccw++) {
            cs_scene *sc = tl_calloc(1, sizeof *sc);
            tc_shape *s = tc_shape_new(0);
            tc_add_circle(s, cx, cy, R, ccw);
            char name[64];
            snprintf(name, sizeof name, "circle r=%g %s", R, ccw ? "ccw" : "reversed");
            check_shape(name, s, NULL, 128, 128, 128, 128);
            if (tc_scene_one(sc, 128, 128, NULL, s) == CS_OK) {
                cs_renderer r;
                cs_render_opts o = {.width = 128, .height = 128, .aa = CS_AA_SUBSCAN, .subscanlines = 4};
                cs_error err;
                cs_status st = cs_frame_begin(&r, tc_workspace(), sc, &o, &err);
                if (CHECK(st == CS_OK, "%s: frame_begin %s", name, tl_status_name(st)) &&
                    CHECK(r.segment_count == 4, "%s: expected 4 segments, got %u", name,
                          (unsigned)r.segment_count)) {
                    double worst = 0;
                    for (unsigned sg = 0; sg < 4; sg++)
                        for (int k = 0; k <= 256; k++) {
                            long double p[2];
                            seg_eval(&r.ws->segments[sg], k / 256.0L, p);
                            double d = fabs((double)hypotl(p[0] - (float)cx, p[1] - (float)cy) -
                                            (float)R);
                            if (d > worst)
                                worst = d;
                        }
                    CHECK(worst < 1e-4 * R, "%s: segments leave the circle by %.3g (limit %.3g)",
                          name, worst, 1e-4 * R);
                }
            }
            free(s);
            free(sc);
        }
    }
}

static void test_degree2_3(void)
{
    double pts6[] = {20, 20, 1, 60, 10, 2, 100, 30, 0.5, 110, 90, 1, 60, 110, 3, 15, 80, 0.75};
    double iv_a[] = {1, 1, 1, 1, 1, 1};
    double iv_b[] = {0.5, 2, 1, 3, 0.25, 1.5};
    double iv_c[] = {1, 0, 2, 0, 0.5, 1};    /* single zeros: allowed for p >= 2 */
    double iv_d[] = {1, 0, 0, 2, 0.5, 0};    /* a double zero (p = 3 only) and a wrap */
    double iv_e[] = {0, 2, 1, 0.25, 1.5, 0}; /* zeros at both ends: a run of 2 across the wrap */
    for (int p = 2; p <= 3; p++) {
        char name[80];
        snprintf(name, sizeof name, "degree %d uniform, weights", p);
        check_segments(name, p, 6, pts6, iv_a, NULL, 128, 128, 128, 128);
        snprintf(name, sizeof name, "degree %d non-uniform", p);
        check_segments(name, p, 6, pts6, iv_b, NULL, 128, 128, 128, 128);
        snprintf(name, sizeof name, "degree %d single zero intervals", p);
        check_segments(name, p, 6, pts6, iv_c, NULL, 128, 128, 128, 128);
    }
    check_segments("degree 3 double zero interval", 3, 6, pts6, iv_d, NULL, 128, 128, 128, 128);
    check_segments("degree 3 double zero across the wrap", 3, 6, pts6, iv_e, NULL, 128, 128, 128,
                   128);
    double pts4[] = {20, 20, 1, 100, 20, 1, 100, 100, 1, 20, 100, 1};
    check_segments("degree 3 with only p+1 points", 3, 4, pts4, NULL, NULL, 128, 128, 128, 128);
    check_segments("degree 2 with only p+1 points", 2, 3, pts4, NULL, NULL, 128, 128, 128, 128);
    /* Closed cubic Bezier path, K = 3: intervals [1,0,0] x 3, on-curve points 0, 3, 6. */
    double bez[] = {10, 60, 1,  30, 10, 1,  70, 10, 2,  90, 60, 1,  110, 90, 1,
                    80, 120, 0.5, 60, 100, 1, 40, 120, 1, 20, 100, 1};
    double bez_iv[] = {1, 0, 0, 1, 0, 0, 1, 0, 0};
    check_segments("closed rational cubic Bezier path", 3, 9, bez, bez_iv, NULL, 128, 128, 128,
                   128);
    double bez2[] = {10, 60, 1, 60, 5, 0.3, 110, 60, 1, 60, 115, 4};
    double bez2_iv[] = {1, 0, 1, 0};
    check_segments("quadratic Bezier path (conic arcs)", 2, 4, bez2, bez2_iv, NULL, 128, 128, 128,
                   128);
}

static void test_transforms(void)
{
    double pts[] = {20, 20, 1, 60, 10, 2, 100, 30, 0.5, 110, 90, 1, 60, 110, 3, 15, 80, 0.75};
    double iv[] = {0.5, 2, 1, 0, 0.25, 1.5};
    const double a = 0.5235987755982988; /* 30 degrees */
    cs_affine rot = {(float)(1.3 * cos(a)), (float)(1.3 * sin(a)), (float)(-1.3 * sin(a)),
                     (float)(1.3 * cos(a)), 40.25f, -12.5f};
    check_segments("rotated and scaled cel", 3, 6, pts, iv, &rot, 200, 150, 200, 150);
    cs_affine shear = {1, 0.25f, -0.4f, 0.8f, 30, 5};
    check_segments("sheared cel", 2, 6, pts, iv, &shear, 200, 150, 200, 150);
    check_segments("canvas 200x150 shown at 400x300", 2, 6, pts, iv, NULL, 200, 150, 400, 300);
    check_segments("canvas 200x150 shown at 50x37.5->38", 3, 6, pts, iv, &rot, 200, 150, 50, 38);
    cs_affine flip = {-1, 0, 0, -1, 128, 128};
    check_segments("flipped cel (det > 0, reversed y)", 3, 6, pts, iv, &flip, 128, 128, 128, 128);
    cs_affine mirror = {-1, 0, 0, 1, 128, 0};
    check_segments("mirrored cel (det < 0)", 2, 6, pts, iv, &mirror, 128, 128, 128, 128);
}

/* Random valid contours: every degree, zero runs up to p-1 (also across the wrap), weights. */
static void test_random_contours(void)
{
    tc_seed(2024);
    int cases = 0;
    for (int trial = 0; trial < 300; trial++) {
        int p = 1 + trial % 3;
        int n = p + 1 + (int)(tc_rand() * 12);
        double xyw[3 * 16], iv[16];
        for (int k = 0; k < n; k++) {
            xyw[3 * k] = tc_uniform(-20, 280);
            xyw[3 * k + 1] = tc_uniform(-20, 280);
            xyw[3 * k + 2] = exp(tc_uniform(log(0.2), log(5.0)));
        }
        for (;;) {
            int nonzero = 0, ok = 1;
            for (int k = 0; k < n; k++) {
                iv[k] = tc_rand() < 0.35 ? 0.0 : tc_uniform(0.1, 4.0);
                nonzero += iv[k] > 0;
            }
            for (int k = 0; k < n && ok; k++) {
                int run = 0;
                while (run < n && iv[(k + run) % n] == 0)
                    run++;
                ok = run <= p - 1;
            }
            if (nonzero && ok)
                break;
        }
        char name[64];
        snprintf(name, sizeof name, "random contour %d (degree %d, %d points)", trial, p, n);
        check_segments(name, p, n, xyw, iv, NULL, 256, 256, 256, 256);
        cases++;
    }
    CHECK(cases == 300, "ran %d random cases", cases);
}

/* Several contours and regions: segments of region k carry region == k, counts add up. */
static void test_regions_and_counts(void)
{
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    cs_error err;
    cs_paint paint = tc_white_paint();
    cs_scene_init(sc, 100, 100);
    cs_scene_add_cel(sc, &tc_identity, NULL, NULL, &err);
    cs_scene_add_region(sc, CS_FILL_NONZERO, &paint, &err);
    cs_point tri[3] = {{10, 10, 1}, {40, 10, 1}, {20, 40, 1}};
    cs_point quad[4] = {{50, 50, 1}, {90, 50, 1}, {90, 90, 1}, {50, 90, 1}};
    float ivq[4] = {1, 0, 1, 2};
    cs_scene_add_contour(sc, 1, 3, tri, NULL, &err);
    cs_scene_add_contour(sc, 2, 4, quad, ivq, &err); /* 3 segments */
    cs_scene_add_cel(sc, &tc_identity, NULL, NULL, &err);
    cs_scene_add_region(sc, CS_FILL_EVENODD, &paint, &err);
    cs_scene_add_region(sc, CS_FILL_NONZERO, &paint, &err);
    cs_status st = cs_scene_add_contour(sc, 3, 4, quad, NULL, &err); /* 4 segments, region 2 */
    CHECK_STATUS(st, CS_OK, "building a 2-cel, 3-region scene");
    CHECK_EQ_INT(sc->region_count, 3, "scene region_count");
    CHECK_EQ_INT(sc->contour_count, 3, "scene contour_count");
    CHECK_EQ_INT(sc->point_count, 11, "scene point_count");
    cs_renderer r;
    cs_render_opts o = {.width = 100, .height = 100, .aa = CS_AA_NONE, .subscanlines = 1};
    st = cs_frame_begin(&r, tc_workspace(), sc, &o, &err);
    CHECK_STATUS(st, CS_OK, "cs_frame_begin");
    CHECK_EQ_INT(r.segment_count, 3 + 3 + 4, "segment count over all contours");
    int per_region[3] = {0, 0, 0}, bad = 0;
    for (uint32_t i = 0; i < r.segment_count && i < 10; i++) {
        unsigned reg = r.ws->segments[i].region;
        if (reg < 3)
            per_region[reg]++;
        else
            bad++;
    }
    CHECK(bad == 0 && per_region[0] == 6 && per_region[1] == 0 && per_region[2] == 4,
          "segments per region: expected 6/0/4, got %d/%d/%d (%d out of range)", per_region[0],
          per_region[1], per_region[2], bad);
    free(sc);
}

int main(int argc, char **argv)
{
    (void)argc;
    TL_RUN(test_degree1);
    TL_RUN(test_circle_on_circle);
    TL_RUN(test_degree2_3);
    TL_RUN(test_transforms);
    TL_RUN(test_random_contours);
    TL_RUN(test_regions_and_counts);
    free(tc_ws_);
    return tl_summary(argv[0]);
}
