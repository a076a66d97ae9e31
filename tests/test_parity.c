/*
 * test_parity.c - crossings keep their parity on adversarial scanlines.
 *
 * A scanline that meets a contour at a vertex, a tangent, a cusp, a
 * self-intersection or along a horizontal edge must still see an even number
 * of crossings, or the span pairing slips and coverage streaks to the right
 * edge of the image. Every shape here is placed so that such events fall
 * exactly on pixel centres (y = j + 0.5, the one-sample-per-pixel scanline)
 * and on sub-scanlines (y = j + (k + 0.5)/N), in exactly representable
 * coordinates. Three checks per shape:
 *
 *   - CS_AA_NONE equals the pixel-centre truth of tests/ref on every pixel
 *     whose centre is more than 1e-3 px from the boundary (centres on the
 *     boundary may go either way);
 *   - CS_AA_SUBSCAN N equals the reference's model of N sub-scanlines with
 *     exact horizontal coverage (ref_coverage_subscan) within 2/255: a single
 *     parity slip on one sub-scanline costs 1/N >= 4/255 on every pixel to the
 *     right;
 *   - shapes well inside the image leave a 2 px border untouched on every row
 *     in every mode (no streaks).
 */
#include "common.h"

#define W 48
#define H 48

static const int subs[] = {1, 2, 3, 4, 5, 8, 16, 32, 64};

static void check_shape(const char *name, const tc_shape *s, int inside_image)
{
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    if (tc_scene_one(sc, W, H, NULL, s) != CS_OK) {
        tl_note("shape %s", name);
        free(sc);
        return;
    }
    ref_region *ref = tc_ref(s, NULL, 1, 1);
    double *got = tl_calloc(W * H, sizeof *got), *want = tl_calloc(W * H, sizeof *want);
    unsigned char *in = tl_calloc(W * H, 1), *amb = tl_calloc(W * H, 1);
    char what[160];

    ref_coverage_centre(ref, W, H, 1e-3, in, amb);
    if (tc_render(sc, W, H, CS_AA_NONE, 1, got) == CS_OK) {
        snprintf(what, sizeof what, "%s, aa none", name);
        tc_expect_centre(what, got, in, amb, W, H);
        if (inside_image)
            tc_expect_border_clear(what, got, W, H, 2);
    }
    for (size_t k = 0; k < sizeof subs / sizeof subs[0]; k++) {
        int n = subs[k];
        if (tc_render(sc, W, H, CS_AA_SUBSCAN, n, got) != CS_OK)
            continue;
        snprintf(what, sizeof what, "%s, %d sub-scanlines vs model", name, n);
        ref_coverage_subscan(ref, W, H, n, want);
        tc_expect_close(what, got, want, W, H, 2.0 / 255, 0.05 / 255);
        if (inside_image) {
            snprintf(what, sizeof what, "%s, %d sub-scanlines", name, n);
            tc_expect_border_clear(what, got, W, H, 2);
        }
    }
    free(got);
    free(want);
    free(in);
    free(amb);
    ref_region_free(ref);
    free(sc);
}

static void poly(const char *name, int evenodd, int n, const double *xy)
{
    tc_shape *s = tc_shape_new(evenodd);
    tc_add_xy(s, 1, n, xy, NULL);
    check_shape(name, s, 1);
    free(s);
}

static void test_polygon_vertices(void)
{
    double diamond[] = {24.5, 6.5, 40.5, 22.5, 24.5, 38.5, 8.5, 22.5};
    poly("diamond, vertices at pixel centres", 0, 4, diamond);
    double diamond_q[] = {24.25, 6.25, 40.75, 22.75, 24.25, 38.25, 8.75, 22.75};
    poly("diamond, vertices on the 1/4 grid", 0, 4, diamond_q);
    /* Monotone pass-through vertices on centre lines, on both sides. */
    double hexa[] = {20.25, 5.5, 30.75, 10.5, 38.5, 20.5, 33.25, 30.5, 21.5, 40.5, 10.5, 30.5, 7.25, 15.5};
    poly("heptagon, pass-through vertices at y = j + 0.5", 0, 7, hexa);
    /* A notch: local maxima and minima pointing into the shape, at centre lines. */
    double notch[] = {6.5, 8.5, 16.5, 8.5, 20.5, 24.5, 24.5, 8.5, 30.5, 30.5, 34.5, 8.5, 41.5, 8.5,
                      41.5, 40.5, 30.5, 28.5, 24.5, 40.5, 18.5, 30.5, 6.5, 40.5};
    poly("W notch, extrema on centre lines", 0, 12, notch);
    poly("W notch evenodd", 1, 12, notch);
}

static void test_horizontal_edges(void)
{
    double rect[] = {8.5, 10.5, 40.5, 10.5, 40.5, 30.5, 8.5, 30.5};
    poly("rectangle on centre lines", 0, 4, rect);
    double rect_int[] = {8, 10, 40, 10, 40, 30, 8, 30};
    poly("rectangle on pixel edges", 0, 4, rect_int);
    /* A staircase: horizontal edges at centres and at 1/64 steps, vertical edges at x.5 and x.25. */
    double stairs[] = {6.5,  6.5,  12.5, 6.5,  12.5, 10.5, 18.25, 10.5,    18.25, 14.5,
                       24.5, 14.5, 24.5, 19.0, 30.5, 19.0, 30.5, 23.015625, 36.5,  23.015625,
                       36.5, 40.5, 6.5,  40.5};
    poly("staircase", 0, 12, stairs);
    /* Collinear vertices along a horizontal edge, and a repeated vertex. */
    double collinear[] = {10.5, 12.5, 20.5, 12.5, 20.5, 12.5, 30.5, 12.5, 38.5, 12.5,
                          38.5, 36.5, 24.5, 36.5, 10.5, 36.5};
    poly("collinear and repeated vertices", 0, 8, collinear);
    /* A horizontal edge that is a local maximum of a concave outline (a T shape). */
    double tee[] = {8.5, 8.5, 40.5, 8.5, 40.5, 16.5, 28.5, 16.5, 28.5, 40.5, 20.5, 40.5, 20.5, 16.5, 8.5, 16.5};
    poly("T shape, inner horizontal edges", 0, 8, tee);
    /* A comb of horizontal teeth edges at dyadic heights (sub-scanline centres for many N). */
    double comb[2 * 20];
    int n = 0;
    for (int t = 0; t < 4; t++) {
        double x0 = 8 + t * 8;
        comb[n++] = x0;
        comb[n++] = 40;
        comb[n++] = x0;
        comb[n++] = 8 + t * 0.125 + 1.0 / 128;
        comb[n++] = x0 + 4;
        comb[n++] = 8 + t * 0.125 + 1.0 / 128;
        comb[n++] = x0 + 4;
        comb[n++] = 36 - t * (1.0 / 64);
    }
    comb[n++] = 40;
    comb[n++] = 40;
    poly("comb with horizontal edges on sub-scanlines", 0, n / 2, comb);
}

static void test_self_intersections(void)
{
    double bowtie[] = {8.5, 8.5, 40.5, 40.5, 40.5, 8.5, 8.5, 40.5};
    poly("bow tie crossing at a pixel centre, nonzero", 0, 4, bowtie);
    poly("bow tie crossing at a pixel centre, evenodd", 1, 4, bowtie);
    /* Pentagram with its top on a centre line. */
    double star[10];
    for (int k = 0; k < 5; k++) {
        double a = -1.5707963267948966 + k * 2.5132741228718345;
        star[2 * k] = 24.5 + 17 * cos(a);
        star[2 * k + 1] = 25.5 + 17 * sin(a);
    }
    poly("pentagram nonzero", 0, 5, star);
    poly("pentagram evenodd", 1, 5, star);
    /* Two overlapping rectangles in one region: edges cross at pixel centres. */
    for (int rule = 0; rule < 2; rule++) {
        tc_shape *s = tc_shape_new(rule);
        double a[] = {8.5, 14.5, 40.5, 14.5, 40.5, 30.5, 8.5, 30.5};
        double b[] = {16.5, 6.5, 30.5, 6.5, 30.5, 40.5, 16.5, 40.5};
        tc_add_xy(s, 1, 4, a, NULL);
        tc_add_xy(s, 1, 4, b, NULL);
        check_shape(rule ? "crossed rectangles evenodd" : "crossed rectangles nonzero", s, 1);
        free(s);
    }
    /* Curved figure-eight: uniform B-spline of a bow tie, symmetric about (24.5, 24.5), which it
     * passes through twice (at the midpoints of spans 2 and 0 by the point symmetry). */
    for (int p = 2; p <= 3; p++)
        for (int rule = 0; rule < 2; rule++) {
            double fig8[] = {12.5, 12.5, 12.5, 36.5, 36.5, 12.5, 36.5, 36.5};
            tc_shape *s = tc_shape_new(rule);
            tc_add_xy(s, p, 4, fig8, NULL);
            char name[80];
            snprintf(name, sizeof name, "degree %d figure eight crossing at a centre, %s", p,
                     rule ? "evenodd" : "nonzero");
            check_shape(name, s, 1);
            free(s);
        }
}

static void test_tangents(void)
{
    /* Circles whose top, bottom, left and right are pixel centres. */
    tc_shape *s = tc_shape_new(0);
    tc_add_circle(s, 24.5, 24.5, 12, 1);
    check_shape("circle r=12 tangent at centres", s, 1);
    free(s);
    s = tc_shape_new(0);
    tc_add_circle(s, 24, 24, 17.5, 0);
    check_shape("circle r=17.5 (reversed) tangent at centres", s, 1);
    free(s);
    /* Tangent exactly on sub-scanlines: top at y = 8 + 1/128 (N = 64, k = 0). */
    s = tc_shape_new(0);
    tc_add_circle(s, 24, 24, 16 - 1.0 / 128, 1);
    check_shape("circle tangent on a sub-scanline", s, 1);
    free(s);
    s = tc_shape_new(0);
    tc_add_ellipse(s, 24.5, 24.5, 15, 9, 0, 1);
    check_shape("ellipse 15x9 tangent at centres", s, 1);
    free(s);
    /* Two circles touching at one point (24.5, 24.5), in one region and as a ring. */
    s = tc_shape_new(0);
    tc_add_circle(s, 16.5, 24.5, 8, 1);
    tc_add_circle(s, 32.5, 24.5, 8, 1);
    check_shape("two circles touching at a centre", s, 1);
    free(s);
    s = tc_shape_new(0);
    tc_add_circle(s, 24.5, 24.5, 16, 1);
    tc_add_circle(s, 24.5, 20.5, 12, 0);
    check_shape("ring whose hole touches the outline at the top", s, 1);
    free(s);
    /* Horizontal inflection: y = 24.5 + 8 (2t-1)^3 has y' = 0 at (24.5, 24.5) but no extremum. */
    s = tc_shape_new(0);
    double bz[] = {12.5, 16.5, 20.5, 32.5, 28.5, 16.5, 36.5, 32.5, 36.5, 35.166666666666664,
                   36.5, 37.833333333333336, 36.5, 40.5, 28.5, 40.5, 20.5, 40.5, 12.5, 40.5,
                   12.5, 32.5, 12.5, 24.5};
    double bz_iv[] = {1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0};
    /* On-curve points 0, 3, 6, 9; span 3 (points 0..3) is the S-curve, span 9 a horizontal line
     * on the centre line y = 40.5. */
    tc_add_xy(s, 3, 12, bz, bz_iv);
    check_shape("cubic with a horizontal inflection at a centre", s, 1);
    free(s);
}

static void test_cusps(void)
{
    /* Cubic (0,0),(1,1),(0,1),(1,0) has a cusp at t = 1/2, point (1/2, 3/4); scaled by 16 and
     * moved so that the cusp is at (24.5, 20.5), pointing down. Closed by an arc above. */
    double down[] = {16.5, 8.5, 32.5, 24.5, 16.5, 24.5, 32.5, 8.5, 28.5, 2.5, 20.5, 2.5};
    double iv[] = {1, 0, 0, 1, 0, 0};
    tc_shape *s = tc_shape_new(0);
    tc_add_xy(s, 3, 6, down, iv);
    check_shape("cusp pointing down at a centre", s, 1);
    free(s);
    /* The same turned sideways: cusp at (20.5, 24.5) pointing right, y monotone through it. */
    double side[] = {8.5, 16.5, 24.5, 32.5, 24.5, 16.5, 8.5, 32.5, 2.5, 28.5, 2.5, 20.5};
    s = tc_shape_new(0);
    tc_add_xy(s, 3, 6, side, iv);
    check_shape("cusp pointing right on a centre line", s, 1);
    free(s);
    /* A B-spline corner from a triple control point (degree 3), at a centre. */
    double corner[] = {10.5, 38.5, 24.5, 10.5, 24.5, 10.5, 24.5, 10.5, 38.5, 38.5, 24.5, 30.5};
    s = tc_shape_new(0);
    tc_add_xy(s, 3, 6, corner, NULL);
    check_shape("degree 3 corner from a triple point", s, 1);
    free(s);
    /* Degree 2 corner from a double point. */
    s = tc_shape_new(0);
    tc_add_xy(s, 2, 5, corner + 2, NULL);
    check_shape("degree 2 corner from a double point", s, 1);
    free(s);
}

static void test_partly_outside(void)
{
    /* Spans that start left of the image, end right of it, shapes above and below. */
    tc_shape *s = tc_shape_new(0);
    tc_add_circle(s, -10, 24.5, 30, 1);
    check_shape("circle mostly left of the image", s, 0);
    free(s);
    s = tc_shape_new(0);
    tc_add_circle(s, 60, 24.5, 30, 1);
    check_shape("circle mostly right of the image", s, 0);
    free(s);
    s = tc_shape_new(1);
    tc_add_circle(s, 24.5, 24.5, 40, 1);
    tc_add_circle(s, 24.5, 24.5, 10, 1);
    check_shape("ring larger than the image (evenodd)", s, 0);
    free(s);
    double wide[] = {-100, 10.5, 148, 10.5, 148, 20.25, -100, 20.25};
    s = tc_shape_new(0);
    tc_add_xy(s, 1, 4, wide, NULL);
    check_shape("band wider than the image", s, 0);
    free(s);
    /* Entirely outside: nothing may show. */
    double left[] = {-30, 5, -2, 5, -2, 40, -30, 40};
    double above[] = {5, -30, 40, -30, 40, -0.5, 5, -0.5};
    double right[] = {48.01, 5, 90, 5, 90, 40, 48.01, 40};
    double below[] = {5, 48, 40, 48, 40, 90, 5, 90};
    const double *outs[] = {left, above, right, below};
    const char *names[] = {"polygon left of the image", "polygon above the image",
                           "polygon right of the image", "polygon below the image"};
    for (int k = 0; k < 4; k++) {
        s = tc_shape_new(0);
        tc_add_xy(s, 1, 4, outs[k], NULL);
        check_shape(names[k], s, 1);
        free(s);
    }
}

/* Random shapes snapped to the half- and quarter-pixel grids: vertices on centres galore. */
static void test_random_snapped(void)
{
    tc_seed(77);
    for (int trial = 0; trial < 120; trial++) {
        int p = 1 + trial % 3;
        int n = p + 1 + (int)(tc_rand() * (p == 1 ? 12 : 8));
        double grid = p == 1 ? 0.5 : 0.25;
        double xyw[3 * 24];
        for (int k = 0; k < n; k++) {
            xyw[3 * k] = floor(tc_uniform(4, 44) / grid) * grid;
            xyw[3 * k + 1] = floor(tc_uniform(4, 44) / grid) * grid;
            xyw[3 * k + 2] = p == 1 ? 1 : (tc_rand() < 0.5 ? 1 : (tc_rand() < 0.5 ? 0.5 : 2));
        }
        /* Horizontal runs: copy y from the previous point now and then. */
        for (int k = 1; k < n; k++)
            if (tc_rand() < 0.3)
                xyw[3 * k + 1] = xyw[3 * (k - 1) + 1];
        tc_shape *s = tc_shape_new(trial % 2);
        tc_add(s, p, n, xyw, NULL);
        char name[80];
        snprintf(name, sizeof name, "random snapped shape %d (degree %d, %d points, %s)", trial, p,
                 n, trial % 2 ? "evenodd" : "nonzero");
        check_shape(name, s, 1);
        free(s);
    }
}

int main(int argc, char **argv)
{
    (void)argc;
    TL_RUN(test_polygon_vertices);
    TL_RUN(test_horizontal_edges);
    TL_RUN(test_self_intersections);
    TL_RUN(test_tangents);
    TL_RUN(test_cusps);
    TL_RUN(test_partly_outside);
    TL_RUN(test_random_snapped);
    free(tc_ws_);
    return tl_summary(argv[0]);
}
