/*
 * test_exact.c - exact-area anti-aliasing (--aa exact) against an
 * independent high-precision reference (exact_ref.c), plus the seam and
 * motion promises of issue 3.
 *
 * Every scene is painted white on nothing (no background, front light 1,
 * back light 0), so the core's linear output is the coverage itself. The
 * reference first proves its own accuracy against closed forms (circle
 * radius, circle area, Sutherland-Hodgman pixel areas); then each scene
 * asserts |exact - reference| <= 1/255 on every pixel (DESIGN.md's bound) and prints the
 * largest error, with --aa 16 alongside for scale.
 *
 * Output ends with `test_exact: N passed, M failed`; the exit status is
 * non-zero if anything failed.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celscan_private.h"
#include "exact_ref.h"

#define PI 3.14159265358979323846

#ifndef TEST_NAME
#define TEST_NAME "test_exact"
#endif
#define TOL_EXACT (1.0 / 255.0)
#define SUBSCAN_REF 1024
#define MAXP 640
#define MAXC 8

#include "testlib.h"

/* ------------------------------------------------------------ scenes */

typedef struct tcontour {
    int degree, count;
    double xyw[3 * MAXP];
    double iv[MAXP];
} tcontour;

typedef struct tregion {
    int evenodd, ncont;
    tcontour cont[MAXC];
} tregion;

typedef struct tscene {
    const char *name;
    double cw, ch;     /* canvas */
    int width, height; /* output */
    double aff[6];     /* cel transform a b c d e f */
    int nreg;
    tregion reg[2];
} tscene;

static tscene *new_scene(const char *name, double cw, double ch, int w, int h)
{
    static tscene t;
    memset(&t, 0, sizeof t);
    t.name = name;
    t.cw = cw;
    t.ch = ch;
    t.width = w;
    t.height = h;
    t.aff[0] = t.aff[3] = 1.0;
    t.nreg = 1;
    return &t;
}

/* Inputs go through float on the way to the core; the reference gets the
 * same float values, so both see one geometry. */
static double fl(double v) { return (double)(float)v; }

static tcontour *begin(tregion *r, int degree)
{
    tcontour *c = &r->cont[r->ncont++];
    c->degree = degree;
    c->count = 0;
    return c;
}

static void pt(tcontour *c, double x, double y, double w, double interval)
{
    c->xyw[3 * c->count] = fl(x);
    c->xyw[3 * c->count + 1] = fl(y);
    c->xyw[3 * c->count + 2] = fl(w);
    c->iv[c->count] = fl(interval);
    c->count++;
}

/*
 * The unit circle as a degree-2 NURBS (edge midpoints w=1, corners w=sqrt(1/2),
 * intervals 1,0,...), mapped by [m00 m01; m10 m11] and moved to (cx, cy):
 * circles and rotated ellipses, exactly. `reverse` runs it the other way.
 */
static void conic(tregion *r, double cx, double cy, double m00, double m01, double m10, double m11,
                  int reverse)
{
    tcontour *c = begin(r, 2);
    for (int k = 0; k < 8; k++) {
        double a = (reverse ? -1.0 : 1.0) * (double)k * PI / 4.0;
        double ux = cos(a), uy = sin(a), w = 1.0;
        if (k & 1) {
            ux *= sqrt(2.0);
            uy *= sqrt(2.0);
            w = sqrt(0.5);
        }
        pt(c, cx + m00 * ux + m01 * uy, cy + m10 * ux + m11 * uy, w, (k & 1) ? 0.0 : 1.0);
    }
}

static void circle(tregion *r, double cx, double cy, double rad, int reverse)
{
    conic(r, cx, cy, rad, 0, 0, rad, reverse);
}

static void ellipse(tregion *r, double cx, double cy, double rx, double ry, double deg)
{
    double a = deg * PI / 180.0, co = cos(a), si = sin(a);
    conic(r, cx, cy, rx * co, -ry * si, rx * si, ry * co, 0);
}

static unsigned rng_state = 12345u;
static double rnd(double lo, double hi)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return lo + (hi - lo) * (double)(rng_state >> 8) / 16777216.0;
}

/* A closed NURBS blob: n points around (cx, cy), radius jittered, weights
 * and knot intervals random (one interval zero when zero_at >= 0). */
static void blob(tregion *r, int degree, int n, double cx, double cy, double rad, double wlo,
                 double whi, int zero_at)
{
    tcontour *c = begin(r, degree);
    for (int k = 0; k < n; k++) {
        double a = 2.0 * PI * (double)k / (double)n + rnd(-0.2, 0.2);
        double rr = rad * rnd(0.7, 1.25);
        double w = rnd(wlo, whi), iv = rnd(0.5, 2.0); /* in this order on every compiler */
        pt(c, cx + rr * cos(a), cy + rr * sin(a), w, k == zero_at ? 0.0 : iv);
    }
}

/* Star {n/step}: points on a circle visited step by step, degree 1..3. */
static void star(tregion *r, int degree, int n, int step, double cx, double cy, double rad,
                 double rot, double w_odd)
{
    tcontour *c = begin(r, degree);
    for (int k = 0; k < n; k++) {
        double a = rot + 2.0 * PI * (double)((k * step) % n) / (double)n;
        pt(c, cx + rad * cos(a), cy + rad * sin(a), (k & 1) ? w_odd : 1.0, 1.0);
    }
}

static void polygon(tregion *r, const double *xy, int n)
{
    tcontour *c = begin(r, 1);
    for (int k = 0; k < n; k++)
        pt(c, xy[2 * k], xy[2 * k + 1], 1.0, 1.0);
}

/* Closed path of cubic Beziers: xy holds 3 points per segment (on-curve first). */
static void bezier_path(tregion *r, const double *xy, int segments, double w_ctrl)
{
    tcontour *c = begin(r, 3);
    for (int k = 0; k < 3 * segments; k++)
        pt(c, xy[2 * k], xy[2 * k + 1], (k % 3) ? w_ctrl : 1.0, (k % 3) ? 0.0 : 1.0);
}

/* ---------------------------------------------------------- renderers */

static cs_scene *g_scene;
static cs_workspace *g_ws;

static cs_status build_core(const tscene *t)
{
    cs_error err;
    cs_status st = cs_scene_init(g_scene, (float)t->cw, (float)t->ch);
    cs_affine m = {(float)t->aff[0], (float)t->aff[1], (float)t->aff[2],
                   (float)t->aff[3], (float)t->aff[4], (float)t->aff[5]};
    if (st == CS_OK)
        st = cs_scene_add_cel(g_scene, &m, NULL, NULL, &err);
    cs_paint white = {{1, 1, 1}, {1, 1, 1}, 1.0f};
    for (int i = 0; i < t->nreg && st == CS_OK; i++) {
        const tregion *r = &t->reg[i];
        st = cs_scene_add_region(g_scene, r->evenodd ? CS_FILL_EVENODD : CS_FILL_NONZERO, &white,
                                 &err);
        for (int k = 0; k < r->ncont && st == CS_OK; k++) {
            const tcontour *c = &r->cont[k];
            cs_point pts[MAXP];
            float iv[MAXP];
            for (int j = 0; j < c->count; j++) {
                pts[j] = (cs_point){(float)c->xyw[3 * j], (float)c->xyw[3 * j + 1],
                                    (float)c->xyw[3 * j + 2]};
                iv[j] = (float)c->iv[j];
            }
            st = cs_scene_add_contour(g_scene, c->degree, c->count, pts, iv, &err);
        }
    }
    return st;
}

/* Renders the window [x0, x0+w) x [y0, y0+h) of t's output into out
 * (w*h, channel 0 = coverage). */
static cs_status render_window(const tscene *t, cs_aa_mode aa, int sub, int x0, int y0, int w,
                               int h, double *out)
{
    cs_status st = build_core(t);
    if (st != CS_OK)
        return st;
    cs_render_opts o = cs_render_defaults(t->width, t->height);
    o.aa = aa;
    o.subscanlines = sub;
    cs_renderer r;
    cs_error err;
    st = cs_frame_begin(&r, g_ws, g_scene, &o, &err);
    if (st != CS_OK)
        return st;
    float *line = malloc(sizeof(float) * 3 * (size_t)t->width);
    for (int y = 0; y < h && st == CS_OK; y++) {
        st = cs_render_line(&r, y0 + y, line);
        for (int x = 0; x < w; x++)
            out[(size_t)y * (size_t)w + (size_t)x] = line[3 * (x0 + x)];
    }
    free(line);
    return st == CS_OK ? r.sticky.status : st;
}

/* Renders t into out (width*height, channel 0 = coverage). */
static cs_status render_core(const tscene *t, cs_aa_mode aa, int sub, double *out)
{
    return render_window(t, aa, sub, 0, 0, t->width, t->height, out);
}

static xref_view view_of(const tscene *t)
{
    xref_view v = {t->aff[0], t->aff[1], t->aff[2], t->aff[3], t->aff[4], t->aff[5],
                  (double)((float)t->width / (float)t->cw),
                  (double)((float)t->height / (float)t->ch)};
    for (int k = 0; k < 6; k++)
        (&v.a)[k] = fl((&v.a)[k]);
    return v;
}

static int ref_region_cov(const tscene *t, int ri, int subscan, double *out)
{
    xref_contour rc[MAXC];
    const tregion *r = &t->reg[ri];
    for (int k = 0; k < r->ncont; k++)
        rc[k] = (xref_contour){r->cont[k].degree, r->cont[k].count, r->cont[k].xyw, r->cont[k].iv};
    xref_region rr = {r->evenodd, r->ncont, rc};
    xref_view v = view_of(t);
    return xref_coverage(&rr, &v, t->width, t->height, subscan, out);
}

/* ---------------------------------------------------- reference checks */

/* The reference's de Boor evaluation and circle construction: every
 * flattened point of a circle lies on it. */
static void test_ref_circle_points(void)
{
    tscene *t = new_scene("ref-circle", 64, 64, 64, 64);
    circle(&t->reg[0], 30.25, 29.75, 20.5, 0);
    xref_contour rc = {2, t->reg[0].cont[0].count, t->reg[0].cont[0].xyw, t->reg[0].cont[0].iv};
    xref_view v = view_of(t);
    long cap = 1 << 20;
    long double *pts = malloc(sizeof(long double) * 2 * (size_t)cap);
    long n = xref_flatten(&rc, &v, pts, cap);
    double worst = 0.0;
    double cx = fl(30.25), cy = fl(29.75), rad = fl(20.5);
    for (long i = 0; i < n; i++) {
        long double dx = pts[2 * i] - cx, dy = pts[2 * i + 1] - cy;
        double d = fabs((double)sqrtl(dx * dx + dy * dy) - rad);
        if (d > worst)
            worst = d;
    }
    /* corner points are float-rounded sqrt(2) and sqrt(1/2): the circle is exact to ~1e-6 */
    CHECK(n > 1000 && worst < 2e-5, "reference circle: %ld points, off the circle by %g", n, worst);
    free(pts);
}

/* The reference's sub-scanline integration: a rotated quadrilateral, per
 * pixel, against Sutherland-Hodgman clipping; a small circle per pixel
 * against its flattened polygon clipped exactly; circle area against pi r^2. */
static void test_ref_accuracy(void)
{
    tscene *t = new_scene("ref-quad", 24, 24, 24, 24);
    const double quad[8] = {3.3, 5.1, 19.7, 2.45, 21.2, 17.9, 6.05, 20.3};
    polygon(&t->reg[0], quad, 4);
    double *cov = malloc(sizeof(double) * 24 * 24);
    CHECK(ref_region_cov(t, 0, SUBSCAN_REF, cov) == 0, "reference failed");
    long double q[8];
    for (int k = 0; k < 8; k++)
        q[k] = fl(quad[k]);
    double worst = 0.0;
    for (int j = 0; j < 24; j++)
        for (int i = 0; i < 24; i++) {
            double d = fabs(fabs((double)xref_polygon_pixel_area(q, 4, i, j)) - cov[j * 24 + i]);
            if (d > worst)
                worst = d;
        }
    CHECK(worst < 5e-6, "reference vs clipping, quadrilateral: %g", worst);
    printf("reference self-check: quadrilateral per pixel within %.2g\n", worst);

    t = new_scene("ref-smallcircle", 16, 16, 16, 16);
    circle(&t->reg[0], 7.8125, 8.3, 6.3, 0);
    CHECK(ref_region_cov(t, 0, SUBSCAN_REF, cov) == 0, "reference failed");
    xref_contour rc = {2, t->reg[0].cont[0].count, t->reg[0].cont[0].xyw, t->reg[0].cont[0].iv};
    xref_view v = view_of(t);
    long cap = 1 << 20;
    long double *pts = malloc(sizeof(long double) * 2 * (size_t)cap);
    long n = xref_flatten(&rc, &v, pts, cap);
    worst = 0.0;
    for (int j = 0; j < 16; j++)
        for (int i = 0; i < 16; i++) {
            double d = fabs(fabs((double)xref_polygon_pixel_area(pts, (int)n, i, j)) - cov[j * 16 + i]);
            if (d > worst)
                worst = d;
        }
    CHECK(worst < 2e-5, "reference vs clipping, circle: %g", worst);
    printf("reference self-check: circle per pixel within %.2g (flattened to %ld points)\n", worst,
           n);
    free(pts);

    double sum = 0.0, rad = fl(6.3);
    for (int k = 0; k < 256; k++)
        sum += cov[k];
    CHECK(fabs(sum - PI * rad * rad) < 1e-5, "reference circle area %.9f vs %.9f", sum,
          PI * rad * rad);
    free(cov);
}

/* ------------------------------------------------------- scene checks */

static double g_worst_exact;
static double g_err_sum;  /* |exact - reference| summed over partly covered pixels */
static long g_err_count;

/*
 * Compares the exact and --aa 16 renders of t with the reference over
 * `ref_t`'s pixels: t itself, or (see scene_far_tall) the window of t's output
 * at (x0, y0) that ref_t holds, moved to its own origin.
 */
static double compare_window(const tscene *t, const tscene *ref_t, int x0, int y0)
{
    int w = ref_t->width, h = ref_t->height;
    size_t np = (size_t)w * (size_t)h;
    double *ref = malloc(sizeof(double) * np), *ex = malloc(sizeof(double) * np),
           *s16 = malloc(sizeof(double) * np);
    CHECK(ref_region_cov(ref_t, 0, SUBSCAN_REF, ref) == 0, "%s: reference failed", t->name);
    cs_status st = render_window(t, CS_AA_EXACT, 0, x0, y0, w, h, ex);
    CHECK(st == CS_OK, "%s: exact render: %s", t->name, cs_status_str(st));
    st = render_window(t, CS_AA_SUBSCAN, 16, x0, y0, w, h, s16);
    CHECK(st == CS_OK, "%s: aa 16 render: %s", t->name, cs_status_str(st));
    double worst = 0.0, worst16 = 0.0, area_ref = 0.0, area_ex = 0.0, sum = 0.0;
    long partial = 0, inner_off = 0;
    int wi = 0, wj = 0;
    for (size_t k = 0; k < np; k++) {
        double d = fabs(ex[k] - ref[k]);
        if (d > worst) {
            worst = d;
            wi = (int)(k % (size_t)w);
            wj = (int)(k / (size_t)w);
        }
        if (ref[k] > 0.0 && ref[k] < 1.0) {
            sum += d;
            partial++;
        }
        /* A pixel wholly inside must be covered exactly 1, not to within
         * rounding: only then is it opaque, and the early-out skips what
         * lies behind it (an edge's cells must add up to its height). */
        if (ref[k] == 1.0 && ex[k] != 1.0)
            inner_off++;
        d = fabs(s16[k] - ref[k]);
        if (d > worst16)
            worst16 = d;
        area_ref += ref[k];
        area_ex += ex[k];
    }
    if (worst > g_worst_exact)
        g_worst_exact = worst;
    g_err_sum += sum;
    g_err_count += partial;
    CHECK(inner_off == 0, "%s: %ld pixels wholly inside are not covered exactly 1", t->name,
          inner_off);
    CHECK(worst <= TOL_EXACT, "%s: exact off by %.3f/255 at (%d, %d): %.6f vs %.6f", t->name,
          worst * 255.0, x0 + wi, y0 + wj, ex[wj * w + wi], ref[wj * w + wi]);
    printf("%-22s exact max err %.4f/255 at (%3d,%3d)   aa16 max err %6.2f/255   area %.4f vs %.4f\n",
           t->name, worst * 255.0, x0 + wi, y0 + wj, worst16 * 255.0, area_ex, area_ref);
    free(ref);
    free(ex);
    free(s16);
    return worst;
}

static double compare_scene(const tscene *t) { return compare_window(t, t, 0, 0); }

static void scene_circles(void)
{
    tscene *t = new_scene("circles", 128, 96, 128, 96);
    circle(&t->reg[0], 20.3, 20.7, 3.3, 0);
    circle(&t->reg[0], 45.55, 60.2, 10.7, 1);
    circle(&t->reg[0], 95.1, 50.9, 28.4, 0);
    circle(&t->reg[0], 10.5, 85.5, 0.35, 0);
    circle(&t->reg[0], 30.17, 84.9, 0.8, 0);
    compare_scene(t);
}

static void scene_blobs(void)
{
    tscene *t = new_scene("rational blobs", 128, 128, 128, 128);
    rng_state = 777u;
    blob(&t->reg[0], 3, 9, 35.2, 36.7, 26.0, 0.35, 3.0, 4);
    blob(&t->reg[0], 2, 7, 92.6, 34.1, 25.0, 0.3, 2.5, -1);
    blob(&t->reg[0], 3, 12, 40.4, 95.3, 24.0, 0.5, 2.0, 7);
    blob(&t->reg[0], 1, 11, 95.9, 94.2, 24.0, 0.5, 2.0, -1);
    compare_scene(t);
}

static void scene_stars(void)
{
    tscene *t = new_scene("star lines evenodd", 128, 128, 128, 128);
    t->reg[0].evenodd = 1;
    star(&t->reg[0], 1, 5, 2, 40.3, 40.6, 34.0, 0.1, 1.0);
    star(&t->reg[0], 1, 7, 3, 90.15, 88.35, 35.0, 0.3, 1.0);
    star(&t->reg[0], 1, 5, 2, 90.5, 30.2, 12.0, 0.0, 1.0); /* tip pointing straight up */
    compare_scene(t);

    t = new_scene("star curves evenodd", 128, 128, 128, 128);
    t->reg[0].evenodd = 1;
    star(&t->reg[0], 3, 7, 3, 62.3, 64.8, 60.0, 0.2, 1.0);
    star(&t->reg[0], 2, 5, 2, 30.7, 30.2, 28.0, 0.5, 2.5); /* rational */
    compare_scene(t);

    t = new_scene("star curves nonzero", 128, 128, 128, 128);
    star(&t->reg[0], 3, 9, 4, 64.1, 63.4, 62.0, 0.05, 0.6);
    compare_scene(t);
}

static void scene_rings(void)
{
    tscene *t = new_scene("rings nonzero", 128, 96, 128, 96);
    circle(&t->reg[0], 40.4, 44.6, 36.0, 0);
    circle(&t->reg[0], 45.3, 41.2, 22.0, 1);
    circle(&t->reg[0], 100.0, 50.0, 20.0, 0);
    ellipse(&t->reg[0], 100.0, 50.0, 14.0, 6.0, 30.0);
    t->reg[0].cont[3].xyw[0] += 0.0; /* same orientation: nonzero fills it, winding 2 */
    compare_scene(t);

    t = new_scene("rings evenodd", 128, 96, 128, 96);
    t->reg[0].evenodd = 1;
    circle(&t->reg[0], 40.4, 44.6, 36.0, 0);
    circle(&t->reg[0], 45.3, 41.2, 22.0, 0);
    circle(&t->reg[0], 44.1, 40.0, 9.0, 1);
    rng_state = 99u;
    circle(&t->reg[0], 100.0, 50.0, 24.0, 0);
    blob(&t->reg[0], 3, 8, 100.0, 50.0, 12.0, 0.5, 2.0, -1);
    compare_scene(t);
}

static void scene_thin(void)
{
    tscene *t = new_scene("thin ellipses", 128, 128, 128, 128);
    ellipse(&t->reg[0], 40.3, 30.7, 36.0, 0.3, 25.0);
    ellipse(&t->reg[0], 70.1, 80.2, 45.0, 0.08, -60.0);
    ellipse(&t->reg[0], 64.0, 110.5, 50.0, 0.6, 1.5);
    ellipse(&t->reg[0], 110.2, 64.0, 0.45, 50.0, 0.0);
    compare_scene(t);

    t = new_scene("crescent sliver", 96, 96, 96, 96);
    circle(&t->reg[0], 48.0, 48.0, 40.0, 0);
    circle(&t->reg[0], 48.07, 48.02, 39.9, 1);
    compare_scene(t);
}

static void scene_transforms(void)
{
    tscene *t = new_scene("rotated scaled", 100, 80, 150, 110);
    double a = 33.0 * PI / 180.0, sx = 1.3, sy = 0.55, sh = 0.2;
    t->aff[0] = sx * cos(a);
    t->aff[1] = sx * sin(a);
    t->aff[2] = -sy * sin(a) + sh;
    t->aff[3] = sy * cos(a);
    t->aff[4] = 48.3;
    t->aff[5] = 5.7;
    rng_state = 4242u;
    blob(&t->reg[0], 3, 10, 10.0, 20.0, 16.0, 0.4, 2.5, 2);
    circle(&t->reg[0], 40.0, 10.0, 14.0, 0);
    star(&t->reg[0], 2, 7, 2, 30.0, 60.0, 18.0, 0.1, 1.7);
    compare_scene(t);

    t = new_scene("scaled up 7x", 20, 20, 140, 140);
    circle(&t->reg[0], 10.1, 9.93, 8.1, 0);
    circle(&t->reg[0], 10.3, 10.2, 3.3, 1);
    compare_scene(t);
}

static void scene_clipped(void)
{
    tscene *t = new_scene("clipped at borders", 96, 96, 96, 96);
    circle(&t->reg[0], 10.3, 48.6, 70.0, 0);
    rng_state = 31337u;
    blob(&t->reg[0], 3, 9, 95.0, 20.0, 18.0, 0.5, 2.0, -1);
    ellipse(&t->reg[0], 60.0, 97.0, 30.0, 8.0, 10.0);
    compare_scene(t);
}

/* Weight 0.22 next to 3.6 puts a zero of W 3% of an arc's length outside
 * it: one Gauss-Legendre panel of 5 nodes was 1.7/255 off here. */
static void scene_near_cusp(void)
{
    tscene *t = new_scene("near-cusp rational", 96, 96, 96, 96);
    tcontour *c = begin(&t->reg[0], 2);
    pt(c, 46.9534496, 47.5493815, 3.59944224, 0.0);
    pt(c, 47.898708, 48.6370978, 1.0, 0.569904983);
    pt(c, 49.2094408, 46.9546294, 1.0, 0.0);
    pt(c, 47.661104, 47.2307289, 0.218210697, 1.59659612);
    c = begin(&t->reg[0], 3); /* the same kind of thing, bigger, as a cubic */
    pt(c, 20.0, 60.0, 4.0, 1.0);
    pt(c, 70.0, 75.0, 1.0, 0.0);
    pt(c, 45.0, 90.0, 0.1, 1.0);
    pt(c, 10.0, 85.0, 1.0, 1.0);
    compare_scene(t);
}

/* Far from the origin, where a float's step is 1.2e-4 px: a full 1080p frame. */
static void scene_far(void)
{
    tscene *t = new_scene("1080p far corner", 1920, 1080, 1920, 1080);
    circle(&t->reg[0], 1890.3, 1050.6, 45.0, 0);
    star(&t->reg[0], 2, 7, 3, 1780.25, 1010.5, 60.0, 0.2, 1.8);
    ellipse(&t->reg[0], 1700.0, 1060.0, 80.0, 0.7, 12.0);
    compare_scene(t);
}

static void scene_coincident(void)
{
    tscene *t = new_scene("coincident evenodd", 96, 96, 96, 96);
    t->reg[0].evenodd = 1;
    circle(&t->reg[0], 30.3, 30.8, 20.0, 0);
    circle(&t->reg[0], 30.3, 30.8, 20.0, 0); /* cancels the first */
    circle(&t->reg[0], 66.6, 66.1, 22.0, 0);
    circle(&t->reg[0], 66.6, 66.1, 22.0, 1); /* same, reversed: cancels too */
    const double sq[8] = {10.5, 60.25, 40.75, 60.25, 40.75, 90.5, 10.5, 90.5};
    polygon(&t->reg[0], sq, 4);
    compare_scene(t);

    t = new_scene("coincident nonzero", 96, 96, 96, 96);
    rng_state = 5u;
    blob(&t->reg[0], 3, 9, 48.3, 48.2, 30.0, 0.5, 2.0, -1);
    t->reg[0].cont[1] = t->reg[0].cont[0]; /* winding 2: still covered once */
    t->reg[0].ncont = 2;
    compare_scene(t);
}

/* Horizontal edges have no y-monotone piece, yet join two far apart: a
 * row cut into independent clusters of pieces must not lose them. Small
 * contours sit between the sides of each horizontal edge, on its row. */
/*
 * Long, shallow polynomial arcs: a row's arc then spans dozens of columns
 * and its Bezier control polygon is long, which is where a power-basis
 * moment loses digits to cancellation (it once put pixels 0.5-0.8/255
 * off on the demo's ribbons; 0.054/255 here). Held to a tighter bound than the rest.
 */
static void scene_shallow(void)
{
    tscene *t = new_scene("shallow cubics", 1920, 48, 1920, 48);
    const double ribbon[12] = {-30.0, 12.3, 400.0, 4.1, 1300.0, 31.7, 1950.0, 9.6,
                               1500.0, 44.2, 500.0, 25.5};
    bezier_path(&t->reg[0], ribbon, 2, 1.0);
    double worst = compare_scene(t);
    CHECK(worst <= 0.025 / 255.0, "shallow cubics: exact off by %.3f/255 (limit 0.025/255)",
          worst * 255.0);
}

static void scene_horizontal(void)
{
    for (int evenodd = 0; evenodd < 2; evenodd++) {
        tscene *t = new_scene(evenodd ? "horizontal evenodd" : "horizontal nonzero", 128, 96,
                              128, 96);
        t->reg[0].evenodd = evenodd;
        const double rect[8] = {10.3, 20.4, 100.7, 20.4, 100.7, 60.6, 10.3, 60.6};
        polygon(&t->reg[0], rect, 4);
        /* a staircase: three horizontal edges in one row, and a notch */
        const double stairs[16] = {20.2, 70.3, 40.6, 70.3, 40.6, 70.7, 70.1, 70.7,
                                   70.1, 80.5, 50.5, 80.5, 50.5, 75.2, 20.2, 75.2};
        polygon(&t->reg[0], stairs, 8);
        circle(&t->reg[0], 30.3, 20.5, 0.3, 0);   /* inside one row, across the top edge */
        circle(&t->reg[0], 55.2, 20.9, 0.4, 1);   /* reversed, across two rows */
        circle(&t->reg[0], 80.6, 60.3, 1.2, 0);   /* across the bottom edge */
        circle(&t->reg[0], 45.1, 70.5, 0.15, 0);  /* between the stairs' risers */
        circle(&t->reg[0], 60.4, 80.45, 0.25, 1); /* on the notch's floor */
        compare_scene(t);
    }
}

/* Scribbles: random closed curves of every degree, weights from 0.2 to 5,
 * crossing themselves and each other many times, random fill rule. */
static void scene_random(int count)
{
    char name[32];
    rng_state = 2024u;
    for (int s = 0; s < count; s++) {
        snprintf(name, sizeof name, "scribble %d", s);
        tscene *t = new_scene(name, 96, 96, 96, 96);
        t->reg[0].evenodd = rnd(0, 1) < 0.5;
        int nc = 1 + (int)rnd(0, 3);
        for (int c = 0; c < nc; c++) {
            int degree = 1 + (int)rnd(0, 3);
            int n = degree + 2 + (int)rnd(0, 10);
            tcontour *k = begin(&t->reg[0], degree);
            for (int i = 0; i < n; i++) {
                double x = rnd(-10, 106), y = rnd(-10, 106);
                double w = rnd(0, 1) < 0.5 ? 1.0 : rnd(0.2, 5.0);
                double iv = rnd(0, 1) < 0.15 ? 0.0 : rnd(0.3, 2.0);
                pt(k, x, y, w, iv);
            }
            /* at most degree-1 zero intervals in a row; none for lines */
            for (int i = 0; i < n; i++)
                if (k->iv[i] == 0.0 && (degree == 1 || k->iv[(i + n - 1) % n] == 0.0))
                    k->iv[i] = 1.0;
        }
        compare_scene(t);
    }
}

/*
 * Far from the screen's origin: rational blobs (weights 0.3 to 3.5) near
 * the bottom right corner of the largest screen, CS_CFG_MAX_WIDTH x 16384
 * lines, where a float coordinate's last bit is 1/1024 px. Strong weights
 * used to multiply that (the segments' coefficients were held in screen
 * coordinates: 1.17/255 on the Rational bench scene at this size, over the
 * bound); a segment now keeps its coefficients from its own origin. Only
 * the window holding the blobs is rendered and compared. The reference
 * gets the same float points moved to the window's origin by a whole
 * number of pixels, which is exact in double, so both see one geometry.
 */
static void scene_far_tall(void)
{
    const int size = 160, W = CS_CFG_MAX_WIDTH, H = 16384;
    const int x0 = W - size - 7, y0 = H - size - 3;
    tscene *t = new_scene("far corner blobs", W, H, W, H);
    rng_state = 4242u;
    blob(&t->reg[0], 3, 9, x0 + 40.3, y0 + 41.7, 30.0, 0.3, 3.5, 4);
    blob(&t->reg[0], 2, 7, x0 + 118.6, y0 + 39.1, 30.0, 0.3, 3.5, -1);
    blob(&t->reg[0], 3, 12, x0 + 44.4, y0 + 117.3, 30.0, 0.3, 3.5, 7);
    circle(&t->reg[0], x0 + 117.7, y0 + 118.2, 29.3, 0);
    /* A control point 20000 px above, of weight 0.002: the curve passes
     * ~40 px from the others, and a segment it starts keeps its origin on
     * the curve, not at the far point. */
    tcontour *pulled = begin(&t->reg[0], 2);
    pt(pulled, x0 + 80.3, y0 + 70.2, 1.0, 1.0);
    pt(pulled, x0 + 95.1, y0 - 20000.0, 0.002, 1.0);
    pt(pulled, x0 + 110.6, y0 + 72.9, 1.0, 1.0);
    pt(pulled, x0 + 96.2, y0 + 90.4, 1.0, 1.0);
    tscene *win = malloc(sizeof *win);
    *win = *t;
    win->cw = win->width = size;
    win->ch = win->height = size;
    for (int c = 0; c < win->reg[0].ncont; c++)
        for (int k = 0; k < win->reg[0].cont[c].count; k++) {
            win->reg[0].cont[c].xyw[3 * k] -= x0;
            win->reg[0].cont[c].xyw[3 * k + 1] -= y0;
        }
    compare_window(t, win, x0, y0);
    free(win);
}

/* ---------------------------------------------------------- seams */

/* Two regions of one cel share an S-shaped cubic edge: their coverage
 * must add up to 1 along it, so the union looks like one square. */
static void test_seam(double w_ctrl, const char *name)
{
    tscene *t = new_scene(name, 96, 96, 96, 96);
    t->nreg = 2;
    /* S-curve from (48, 8) down to (48, 88). Straight sides as cubics too. */
    const double right[] = {48, 8,  8, 36,  88, 60,  48, 88,  61.33, 88,  74.67, 88,
                            88, 88, 88, 61.33, 88, 34.67,  88, 8,  74.67, 8,  61.33, 8};
    const double left[] = {48, 88, 88, 60,  8, 36,   48, 8,  34.67, 8,  21.33, 8,
                           8, 8,   8, 34.67,  8, 61.33,  8, 88,  21.33, 88,  34.67, 88};
    bezier_path(&t->reg[0], right, 4, 1.0);
    bezier_path(&t->reg[1], left, 4, 1.0);
    /* rational S: weights on the S's inner control points only */
    t->reg[0].cont[0].xyw[3 * 1 + 2] = t->reg[0].cont[0].xyw[3 * 2 + 2] = fl(w_ctrl);
    t->reg[1].cont[0].xyw[3 * 1 + 2] = t->reg[1].cont[0].xyw[3 * 2 + 2] = fl(w_ctrl);
    for (int aa = 0; aa < 2; aa++) {
        double *out = malloc(sizeof(double) * 96 * 96);
        cs_status st = render_core(t, aa ? CS_AA_SUBSCAN : CS_AA_EXACT, 16, out);
        CHECK(st == CS_OK, "%s: render: %s", name, cs_status_str(st));
        double worst = 0.0;
        int wi = 0, wj = 0;
        for (int j = 8; j < 88; j++)
            for (int i = 8; i < 88; i++) {
                double d = fabs(1.0 - out[j * 96 + i]);
                if (d > worst) {
                    worst = d;
                    wi = i;
                    wj = j;
                }
            }
        /* the square's own border is pixel aligned: outside it, nothing */
        double outside = 0.0;
        for (int j = 0; j < 96; j++)
            for (int i = 0; i < 96; i++)
                if (i < 8 || i >= 88 || j < 8 || j >= 88)
                    outside = fmax(outside, out[j * 96 + i]);
        CHECK(worst <= 1.0 / 255.0, "%s (%s): seam %.3f/255 at (%d, %d)", name,
              aa ? "aa 16" : "exact", worst * 255.0, wi, wj);
        CHECK(outside <= 1e-6, "%s: coverage outside the square: %g", name, outside);
        printf("%-22s %s: largest departure from 1 inside the square %.5f/255\n", name,
               aa ? "aa 16" : "exact", worst * 255.0);
        free(out);
    }
}

/* ---------------------------------------------------------- motion */

/* A circle moved in 1/32 px steps: its rendered centroid follows exactly. */
static void test_motion(void)
{
    const int n = 64;
    double *out = malloc(sizeof(double) * (size_t)(n * n));
    const cs_aa_mode modes[3] = {CS_AA_EXACT, CS_AA_SUBSCAN, CS_AA_SUBSCAN};
    const int subs[3] = {0, 5, 16};
    for (int m = 0; m < 3; m++) {
        double worst = 0.0;
        for (int dir = 0; dir < 2; dir++)
            for (int k = 0; k <= 32; k++) {
                tscene *t = new_scene("motion", n, n, n, n);
                double cx = fl(31.3 + (double)k / 32.0);
                double cy = fl(30.9 + (dir ? (double)k / 64.0 : 0.0));
                /* the circle is built at the origin and moved by the cel transform */
                circle(&t->reg[0], 0.0, 0.0, 11.7, 0);
                t->aff[4] = cx;
                t->aff[5] = cy;
                cs_status st = render_core(t, modes[m], subs[m], out);
                CHECK(st == CS_OK, "motion render: %s", cs_status_str(st));
                double s = 0.0, sx = 0.0, sy = 0.0;
                for (int j = 0; j < n; j++)
                    for (int i = 0; i < n; i++) {
                        double c = out[j * n + i];
                        s += c;
                        sx += c * (i + 0.5);
                        sy += c * (j + 0.5);
                    }
                double e = fmax(fabs(sx / s - cx), fabs(sy / s - cy));
                if (e > worst)
                    worst = e;
            }
        if (m == 0)
            CHECK(worst <= 0.01, "exact: centroid off by %.4f px", worst);
        printf("motion, 1/32 px steps: %-6s centroid within %.5f px of the true centre\n",
               m == 0 ? "exact" : (m == 1 ? "aa 5" : "aa 16"), worst);
    }
    free(out);
}

/* ---------------------------------------------------------- workspace */

/* The frame's start marks every piece's level memo empty and nothing
 * else: whatever an earlier frame or the allocator left in the workspace
 * (a memo's other fields, its ends) must not reach a pixel. Polynomial
 * and rational blobs, rows 0..7 included (where an empty memo's key lies
 * nearest the rows asked), rendered into a zeroed workspace and into one
 * filled with each byte pattern: the same bits. */
static void test_stale_workspace(void)
{
    const int n = 48;
    const unsigned char fill[3] = {0x40, 0x7F, 0xFF}; /* 3.0f / huge counts, 3.4e38f, NaN */
    double *want = malloc(sizeof(double) * (size_t)(n * n));
    double *got = malloc(sizeof(double) * (size_t)(n * n));
    tscene *t = new_scene("stale workspace", n, n, n, n);
    rng_state = 31u;
    blob(&t->reg[0], 3, 9, 15.3, 14.6, 13.0, 1.0, 1.0, -1); /* polynomial */
    blob(&t->reg[0], 2, 7, 34.2, 13.9, 12.0, 1.0, 1.0, -1);
    blob(&t->reg[0], 3, 8, 24.7, 33.1, 12.0, 0.5, 2.0, -1); /* rational */
    memset(g_ws, 0, sizeof *g_ws);
    cs_status st = render_core(t, CS_AA_EXACT, 0, want);
    CHECK(st == CS_OK, "stale workspace, zeroed: %s", cs_status_str(st));
    for (int f = 0; f < 3; f++) {
        memset(g_ws, fill[f], sizeof *g_ws);
        st = render_core(t, CS_AA_EXACT, 0, got);
        int diff = 0;
        for (int i = 0; i < n * n; i++)
            diff += memcmp(&want[i], &got[i], sizeof want[i]) != 0;
        CHECK(st == CS_OK && diff == 0, "stale workspace 0x%02X: %s, %d of %d pixels differ",
              fill[f], cs_status_str(st), diff, n * n);
    }
    free(want);
    free(got);
}

/* ---------------------------------------------------------- limits */

/* More pieces of one region on a row than CS_CFG_MAX_CROSSINGS: reported,
 * never written past. */
static void test_capacity(void)
{
    /* Combs side by side in one region: each tooth puts two pieces on rows
     * 10..11, and there are more teeth than the workspace holds. */
    int teeth = (MAXP - 2) / 2;
    int combs = CS_CFG_MAX_CROSSINGS / (2 * teeth) + 1;
    if (combs > MAXC)
        combs = MAXC;
    int width = combs * (teeth + 8);
    tscene *t = new_scene("comb", width, 40, width, 40);
    static double xy[2 * (MAXP)];
    for (int c = 0; c < combs; c++) {
        double x0 = 2.0 + c * (teeth + 8);
        int k = 0;
        for (int i = 0; i < teeth; i++) {
            xy[2 * k] = x0 + i;
            xy[2 * k + 1] = 10.2;
            k++;
            xy[2 * k] = x0 + i + 0.5;
            xy[2 * k + 1] = 10.8;
            k++;
        }
        xy[2 * k] = x0 + teeth;
        xy[2 * k + 1] = 30.0;
        k++;
        xy[2 * k] = x0;
        xy[2 * k + 1] = 30.0;
        k++;
        polygon(&t->reg[0], xy, k);
    }
    double *out = malloc(sizeof(double) * (size_t)width * 40);
    cs_status st = render_core(t, CS_AA_EXACT, 0, out);
    CHECK(combs * 2 * teeth > CS_CFG_MAX_CROSSINGS, "the combs overflow the workspace (%d pieces)",
          combs * 2 * teeth);
    CHECK(st == CS_ERR_CAP_CROSSINGS, "%d combs of %d teeth: %s", combs, teeth,
          cs_status_str(st));
    /* rows without the teeth are still right */
    CHECK(fabs(out[20 * width + 100] - 1.0) < 1e-6 && out[35 * width + 100] == 0.0,
          "comb: rows away from the overflow");
    free(out);
}

int main(void)
{
    g_scene = malloc(sizeof *g_scene);
    g_ws = malloc(sizeof *g_ws);
    if (!g_scene || !g_ws) {
        printf("test_exact: out of memory\n");
        return 2;
    }
    test_ref_circle_points();
    test_ref_accuracy();
    scene_circles();
    scene_blobs();
    scene_stars();
    scene_rings();
    scene_thin();
    scene_transforms();
    scene_clipped();
    scene_coincident();
    scene_far();
    scene_far_tall();
    scene_near_cusp();
    scene_horizontal();
    scene_shallow();
    scene_random(getenv("EXACT_RANDOM") ? atoi(getenv("EXACT_RANDOM")) : 12);
    printf("largest exact-mode error over all scenes: %.4f/255 (limit %.1f/255)\n",
           g_worst_exact * 255.0, TOL_EXACT * 255.0);
    printf("mean exact-mode error over partly covered pixels: %.6f/255 (%ld pixels)\n",
           g_err_count ? g_err_sum / (double)g_err_count * 255.0 : 0.0, g_err_count);
    test_seam(1.0, "seam S cubic");
    test_seam(2.5, "seam S rational");
    test_motion();
    test_stale_workspace();
    test_capacity();
    free(g_scene);
    free(g_ws);
    return tl_summary(TEST_NAME);
}
