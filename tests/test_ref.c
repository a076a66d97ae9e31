/*
 * test_ref.c - tests of the test suite's own truth (tests/ref).
 *
 * The reference is only worth something if it is right, so it is checked
 * against closed forms that share nothing with it: de Boor against explicit
 * Cox-de Boor basis sums, the DESIGN.md circle against x^2 + y^2 = r^2, cubic
 * Bezier paths against the Bernstein form, per-pixel areas of rectangles
 * against products of overlaps, circle pixel areas against numerical
 * integration of the circle's chord, totals against shoelace and pi r^2, and
 * the three coverage methods against each other.
 */
#include "common.h"

static ref_region *one_contour(int evenodd, int degree, int n, const double *xyw, const double *iv)
{
    tc_shape *s = tc_shape_new(evenodd);
    tc_add(s, degree, n, xyw, iv);
    ref_region *r = tc_ref(s, NULL, 1, 1);
    free(s);
    return r;
}

/* Random valid contour: intervals with zero runs of at most degree-1 (cyclically). */
static int random_contour(int degree, int n, double *xyw, double *iv, double lo, double hi)
{
    for (int k = 0; k < n; k++) {
        xyw[3 * k] = tc_uniform(lo, hi);
        xyw[3 * k + 1] = tc_uniform(lo, hi);
        xyw[3 * k + 2] = exp(tc_uniform(log(0.25), log(4.0)));
    }
    for (;;) {
        int nonzero = 0;
        for (int k = 0; k < n; k++) {
            iv[k] = tc_rand() < 0.3 ? 0.0 : tc_uniform(0.2, 3.0);
            nonzero += iv[k] > 0;
        }
        if (!nonzero)
            continue;
        int ok = 1;
        for (int k = 0; k < n && ok; k++) {
            int run = 0;
            while (run < n && iv[(k + run) % n] == 0)
                run++;
            if (run > degree - 1)
                ok = 0;
        }
        if (ok)
            return nonzero;
    }
}

static void test_deboor_matches_cox_de_boor(void)
{
    tc_seed(11);
    double worst = 0;
    for (int trial = 0; trial < 300; trial++) {
        int p = 1 + trial % 3;
        int n = p + 1 + (int)(tc_rand() * 9);
        double xyw[3 * 16], iv[16];
        random_contour(p, n, xyw, iv, -50, 50);
        ref_region *r = one_contour(0, p, n, xyw, iv);
        const ref_contour *c = &r->contours[0];
        for (int j = 0; j < n; j++) {
            if (!(c->iv[j] > 0))
                continue;
            for (int k = 0; k < 16; k++) {
                long double u = k / 16.0L, a[2], b[2];
                ref_eval_span(c, j, u, a);
                ref_eval_basis(c, j, u, b);
                double d = (double)fmaxl(fabsl(a[0] - b[0]), fabsl(a[1] - b[1]));
                if (d > worst)
                    worst = d;
            }
        }
        ref_region_free(r);
    }
    CHECK(worst < 1e-12, "de Boor vs Cox-de Boor: worst difference %.3g (limit 1e-12)", worst);
}

static void test_circle_exact(void)
{
    tc_shape *s = tc_shape_new(0);
    tc_add_circle(s, 3.25, -7.5, 12.0, 1);
    tc_add_circle(s, 3.25, -7.5, 12.0, 0);
    ref_region *r = tc_ref(s, NULL, 1, 1);
    double worst = 0;
    for (int ci = 0; ci < 2; ci++) {
        const ref_contour *c = &r->contours[ci];
        for (int j = 0; j < 8; j++) {
            if (!(c->iv[j] > 0))
                continue;
            for (int k = 0; k <= 64; k++) {
                long double pt[2];
                ref_eval_span(c, j, k / 64.0L, pt);
                long double dx = pt[0] - 3.25L, dy = pt[1] + 7.5L;
                double d = fabs((double)sqrtl(dx * dx + dy * dy) - 12.0);
                if (d > worst)
                    worst = d;
            }
        }
    }
    /* The weight sqrt(1/2) is rounded to float; that alone moves the arc by ~1e-7 r. */
    CHECK(worst < 1e-5, "DESIGN.md circle off the circle by %.3g (limit 1e-5 of r = 12)", worst);
    const ref_poly *p = ref_region_poly(r);
    int n0 = p->start[1] - p->start[0];
    long double a0 = 0;
    for (int i = p->start[0]; i < p->start[1]; i++) {
        int k = i + 1 < p->start[1] ? i + 1 : p->start[0];
        a0 += p->x[i] * p->y[k] - p->x[k] * p->y[i];
    }
    a0 /= 2;
    /* Chords lie inside the arc by at most REF_FLAT_TOL: the area may fall short by up to
     * perimeter * REF_FLAT_TOL. */
    long double lim = 2 * 3.14159265358979323846L * 12 * REF_FLAT_TOL;
    CHECK(fabsl(a0) <= 3.14159265358979323846L * 144 + 1e-9L &&
              fabsl(a0) >= 3.14159265358979323846L * 144 - lim,
          "flattened circle area %.12Lf, expected pi*144 = %.12f less at most %.3Lg (%d vertices)",
          fabsl(a0), 3.14159265358979323846 * 144, lim, n0);
    CHECK(fabsl(ref_poly_signed_area(p)) < 1e-6L,
          "circle and its reverse should cancel: signed area %.3Lg", ref_poly_signed_area(p));
    ref_region_free(r);
    free(s);
}

static void test_bezier_path(void)
{
    /* Closed cubic Bezier path, K = 2: on-curve points 0 and 3, intervals [1,0,0,1,0,0]. */
    static const double P[6][2] = {{0, 0}, {10, -5}, {20, 5}, {30, 0}, {20, 20}, {5, 15}};
    static const double iv[6] = {1, 0, 0, 1, 0, 0};
    double xyw[18];
    for (int k = 0; k < 6; k++) {
        xyw[3 * k] = P[k][0];
        xyw[3 * k + 1] = P[k][1];
        xyw[3 * k + 2] = 1;
    }
    ref_region *r = one_contour(0, 3, 6, xyw, iv);
    const ref_contour *c = &r->contours[0];
    /* Span j is driven by points j-3 .. j: span 0 runs P3 -> P4 -> P5 -> P0, span 3 P0 -> P3. */
    static const int spans[2] = {0, 3};
    double worst = 0;
    for (int s = 0; s < 2; s++) {
        int j = spans[s];
        const double *b[4];
        for (int i = 0; i < 4; i++)
            b[i] = P[(j - 3 + i + 6) % 6];
        for (int k = 0; k <= 32; k++) {
            double u = k / 32.0, v = 1 - u;
            double bx = v * v * v * b[0][0] + 3 * v * v * u * b[1][0] + 3 * v * u * u * b[2][0] +
                        u * u * u * b[3][0];
            double by = v * v * v * b[0][1] + 3 * v * v * u * b[1][1] + 3 * v * u * u * b[2][1] +
                        u * u * u * b[3][1];
            long double pt[2];
            ref_eval_span(c, j, u, pt);
            double d = fmax(fabs((double)pt[0] - bx), fabs((double)pt[1] - by));
            if (d > worst)
                worst = d;
        }
    }
    CHECK(worst < 1e-12, "Bezier path vs Bernstein form: worst %.3g", worst);
    ref_region_free(r);
}

/* Exact coverage of an axis-aligned rectangle: product of overlaps. */
static double rect_cov(double x0, double y0, double x1, double y1, int i, int j)
{
    double ox = fmin(x1, i + 1.0) - fmax(x0, (double)i);
    double oy = fmin(y1, j + 1.0) - fmax(y0, (double)j);
    return ox > 0 && oy > 0 ? ox * oy : 0;
}

static void test_rectangle_area(void)
{
    const int W = 12, H = 9;
    const double x0 = 2.25, y0 = 1.75, x1 = 9.5, y1 = 6.125;
    double xy[8] = {x0, y0, x1, y0, x1, y1, x0, y1};
    double want[12 * 9], got[12 * 9];
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++)
            want[j * W + i] = rect_cov(x0, y0, x1, y1, i, j);
    for (int rule = 0; rule < 2; rule++)
        for (int rev = 0; rev < 2; rev++) {
            double q[8];
            for (int k = 0; k < 4; k++) {
                int m = rev ? 3 - k : k;
                q[2 * k] = xy[2 * m];
                q[2 * k + 1] = xy[2 * m + 1];
            }
            tc_shape *s = tc_shape_new(rule);
            tc_add_xy(s, 1, 4, q, NULL);
            ref_region *r = tc_ref(s, NULL, 1, 1);
            ref_coverage_area(r, W, H, got);
            tc_expect_close(rule ? "rectangle evenodd area" : "rectangle nonzero area", got, want,
                            W, H, 1e-12, 1e-13);
            ref_coverage_subscan(r, W, H, 8, got);
            /* Edges at multiples of 1/8 fall between sub-scanline centres: exact too. */
            tc_expect_close("rectangle sub-scanlines", got, want, W, H, 1e-12, 1e-13);
            ref_region_free(r);
            free(s);
        }
}

/* Area of the disc (cx, cy, R) inside pixel (i, j) by composite Simpson over x. */
static double disc_pixel_area(double cx, double cy, double R, int i, int j)
{
    double a = fmax((double)i, cx - R), b = fmin(i + 1.0, cx + R);
    if (b <= a)
        return 0;
    const int n = 4000;
    long double h = (long double)(b - a) / n, sum = 0;
    for (int k = 0; k <= n; k++) {
        long double x = a + k * h, dx = x - cx;
        long double s2 = (long double)R * R - dx * dx;
        long double s = s2 > 0 ? sqrtl(s2) : 0;
        long double lo = fmaxl(cy - s, (long double)j), hi = fminl(cy + s, j + 1.0L);
        long double f = hi > lo ? hi - lo : 0;
        sum += f * (k == 0 || k == n ? 1 : (k % 2 ? 4 : 2));
    }
    return (double)(sum * h / 3);
}

static void test_circle_area(void)
{
    const int W = 24, H = 24;
    const double cx = 11.3, cy = 12.15, R = 7.6;
    tc_shape *s = tc_shape_new(0);
    tc_add_circle(s, cx, cy, R, 1);
    ref_region *r = tc_ref(s, NULL, 1, 1);
    double *got = tl_calloc((size_t)W * H, sizeof *got), *want = tl_calloc((size_t)W * H, sizeof *want);
    /* The truth circle must be the float-rounded one the reference sees. */
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++)
            want[j * W + i] = disc_pixel_area((float)cx, (float)cy, (float)R, i, j);
    ref_coverage_area(r, W, H, got);
    /* Simpson at the sqrt end points limits the check to ~1e-6; the weight's float rounding
     * bends the arc by ~1e-6 px. */
    tc_expect_close("circle area vs Simpson", got, want, W, H, 2e-5, 2e-6);
    double total = tc_sum(got, (size_t)W * H);
    CHECK_NEAR(total, 3.14159265358979 * (double)(float)R * (double)(float)R, 1e-4,
               "sum of circle coverage");
    ref_coverage_subscan(r, W, H, 1024, want);
    tc_expect_close("circle area vs 1024 sub-scanlines", want, got, W, H, 2.0 / 1024, 1e-4);
    free(got);
    free(want);
    ref_region_free(r);
    free(s);
}

static void test_star_rules(void)
{
    /* A pentagram: the centre pentagon has winding 2, so evenodd leaves it empty. */
    const int W = 40, H = 40;
    double xy[10];
    for (int k = 0; k < 5; k++) {
        double a = -1.5707963267948966 + k * 2.5132741228718345; /* 144 degrees */
        xy[2 * k] = 20.2 + 16 * cos(a);
        xy[2 * k + 1] = 20.7 + 16 * sin(a);
    }
    double *area = tl_calloc((size_t)W * H, sizeof *area);
    double *sub = tl_calloc((size_t)W * H, sizeof *sub);
    unsigned char *in = tl_calloc((size_t)W * H, 1), *amb = tl_calloc((size_t)W * H, 1);
    double totals[2];
    for (int rule = 0; rule < 2; rule++) {
        tc_shape *s = tc_shape_new(rule);
        tc_add_xy(s, 1, 5, xy, NULL);
        ref_region *r = tc_ref(s, NULL, 1, 1);
        int w = ref_winding(r, 20.2L, 20.7L);
        CHECK(w == 2 || w == -2, "pentagram centre winding: expected +-2, got %d", w);
        ref_coverage_area(r, W, H, area);
        ref_coverage_subscan(r, W, H, 2048, sub);
        tc_expect_close(rule ? "pentagram evenodd: area vs 2048 subs"
                             : "pentagram nonzero: area vs 2048 subs",
                        sub, area, W, H, 3.0 / 2048, 1e-4);
        ref_coverage_centre(r, W, H, 1e-6, in, amb);
        int bad = 0;
        for (int k = 0; k < W * H; k++)
            if ((area[k] == 0 && in[k]) || (area[k] == 1 && !in[k]))
                bad++;
        CHECK(bad == 0, "pentagram rule %d: %d pixel centres disagree with full/empty area", rule,
              bad);
        totals[rule] = tc_sum(area, (size_t)W * H);
        ref_region_free(r);
        free(s);
    }
    /* Pentagram with circumradius R: the inner pentagon has circumradius R*sin(18)/sin(126)... the
     * check here is only the relation: nonzero - evenodd = inner pentagon area. */
    double ri = 16 * sin(0.3141592653589793) / sin(2.199114857512855);
    double pent = 2.5 * ri * ri * sin(1.2566370614359172);
    CHECK_NEAR(totals[0] - totals[1], pent, 1e-3, "nonzero minus evenodd pentagram area");
    free(area);
    free(sub);
    free(in);
    free(amb);
}

static void test_centre_flags(void)
{
    const int W = 10, H = 8;
    double xy[8] = {2.5, 1.25, 7.5, 1.25, 7.5, 6.0, 2.5, 6.0};
    tc_shape *s = tc_shape_new(0);
    tc_add_xy(s, 1, 4, xy, NULL);
    ref_region *r = tc_ref(s, NULL, 1, 1);
    unsigned char in[80], amb[80];
    ref_coverage_centre(r, W, H, 1e-3, in, amb);
    int bad = 0, bad_amb = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            double x = i + 0.5, y = j + 0.5;
            int on_edge = (x == 2.5 || x == 7.5) && y > 1.25 && y < 6.0;
            int want = x > 2.5 && x < 7.5 && y > 1.25 && y < 6.0;
            if (!on_edge && in[j * W + i] != want)
                bad++;
            if (amb[j * W + i] != on_edge)
                bad_amb++;
        }
    CHECK(bad == 0, "rectangle centre inside flags: %d wrong", bad);
    CHECK(bad_amb == 0, "rectangle centre ambiguity flags: %d wrong", bad_amb);
    ref_region_free(r);
    free(s);
}

int main(int argc, char **argv)
{
    (void)argc;
    TL_RUN(test_deboor_matches_cox_de_boor);
    TL_RUN(test_circle_exact);
    TL_RUN(test_bezier_path);
    TL_RUN(test_rectangle_area);
    TL_RUN(test_circle_area);
    TL_RUN(test_star_rules);
    TL_RUN(test_centre_flags);
    return tl_summary(argv[0]);
}
