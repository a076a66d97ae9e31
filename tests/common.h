/*
 * common.h - shapes, scenes and image comparisons shared by the test programs.
 *
 * A test describes a shape once (tc_shape: contours as the floats the core
 * receives) and gets from it both a core scene (tc_scene_one) and the
 * independent reference region in device space (tc_ref). tc_render renders a
 * scene through the public API into a coverage image: the scene has no
 * background, stack lights front 1 back 0 and one white opaque paint
 * (pigment 1, beta 1), so the linear output of every pixel is its coverage.
 *
 * Comparisons make one CHECK per image and metric, with a message naming the
 * worst pixel, expected and got, and notes for the first few offenders.
 *
 * Included once per test program (everything is static), after testlib.h.
 */
#ifndef CELSCAN_TEST_COMMON_H
#define CELSCAN_TEST_COMMON_H

#include <math.h>
#include <stdint.h>

#include "celscan_private.h"
#include "ref/ref.h"
#include "testlib.h"

#define TC_MAX_CONTOURS 256
#define TC_MAX_POINTS 16384

typedef struct tc_shape {
    int evenodd;
    int ncont, npts;
    int degree[TC_MAX_CONTOURS], count[TC_MAX_CONTOURS], first[TC_MAX_CONTOURS];
    int has_iv[TC_MAX_CONTOURS];
    float xyw[3 * TC_MAX_POINTS];
    float iv[TC_MAX_POINTS];
} tc_shape;

static TL_UNUSED tc_shape *tc_shape_new(int evenodd)
{
    tc_shape *s = tl_calloc(1, sizeof *s);
    s->evenodd = evenodd;
    return s;
}

/* Appends a contour from count (x, y, w) triples; iv may be NULL (all ones). */
static TL_UNUSED void tc_add(tc_shape *s, int degree, int count, const double *xyw,
                             const double *iv)
{
    if (s->ncont >= TC_MAX_CONTOURS || s->npts + count > TC_MAX_POINTS) {
        printf("tc_add: test shape too large\n");
        exit(2);
    }
    int c = s->ncont++;
    s->degree[c] = degree;
    s->count[c] = count;
    s->first[c] = s->npts;
    s->has_iv[c] = iv != NULL;
    for (int k = 0; k < count; k++) {
        int q = s->npts + k;
        s->xyw[3 * q] = (float)xyw[3 * k];
        s->xyw[3 * q + 1] = (float)xyw[3 * k + 1];
        s->xyw[3 * q + 2] = (float)xyw[3 * k + 2];
        s->iv[q] = iv ? (float)iv[k] : 1.0f;
    }
    s->npts += count;
}

/* Appends a contour from count (x, y) pairs with unit weights. */
static TL_UNUSED void tc_add_xy(tc_shape *s, int degree, int count, const double *xy,
                                const double *iv)
{
    double *xyw = tl_calloc((size_t)count * 3, sizeof *xyw);
    for (int k = 0; k < count; k++) {
        xyw[3 * k] = xy[2 * k];
        xyw[3 * k + 1] = xy[2 * k + 1];
        xyw[3 * k + 2] = 1.0;
    }
    tc_add(s, degree, count, xyw, iv);
    free(xyw);
}

/*
 * An ellipse with semi-axes rx, ry rotated by `angle` radians about (cx, cy),
 * as the exact degree-2 circle of DESIGN.md mapped affinely. ccw = 0 reverses
 * the point order (a hole under nonzero).
 */
static TL_UNUSED void tc_add_ellipse(tc_shape *s, double cx, double cy, double rx, double ry,
                                     double angle, int ccw)
{
    static const double unit[8][3] = {
        {1, 0, 1}, {1, 1, 0}, {0, 1, 1}, {-1, 1, 0}, {-1, 0, 1}, {-1, -1, 0}, {0, -1, 1}, {1, -1, 0},
    };
    static const double iv[8] = {1, 0, 1, 0, 1, 0, 1, 0};
    double xyw[24];
    double ca = cos(angle), sa = sin(angle);
    for (int k = 0; k < 8; k++) {
        int m = ccw ? k : (8 - k) % 8;
        double ux = unit[m][0] * rx, uy = unit[m][1] * ry;
        xyw[3 * k] = cx + ca * ux - sa * uy;
        xyw[3 * k + 1] = cy + sa * ux + ca * uy;
        xyw[3 * k + 2] = unit[m][2] ? 1.0 : sqrt(0.5);
    }
    /* Reversed, point k is unit[-k]; span k is then driven by unit[2-k], unit[1-k],
     * unit[-k], which is again (on, off, on) for even k: the intervals stay the same. */
    tc_add(s, 2, 8, xyw, iv);
}

static TL_UNUSED void tc_add_circle(tc_shape *s, double cx, double cy, double r, int ccw)
{
    tc_add_ellipse(s, cx, cy, r, r, 0.0, ccw);
}

static const cs_affine tc_identity = {1, 0, 0, 1, 0, 0};

static TL_UNUSED cs_paint tc_white_paint(void)
{
    cs_paint p = {{1, 1, 1}, {1, 1, 1}, 1.0f};
    return p;
}

/* Adds the shape's contours to the last region of sc; status of the first failure. */
static TL_UNUSED cs_status tc_add_contours(cs_scene *sc, const tc_shape *s)
{
    for (int c = 0; c < s->ncont; c++) {
        cs_point pts[TC_MAX_POINTS > 4096 ? 4096 : TC_MAX_POINTS];
        cs_point *pp = s->count[c] <= 4096 ? pts : tl_calloc((size_t)s->count[c], sizeof *pp);
        for (int k = 0; k < s->count[c]; k++) {
            int q = s->first[c] + k;
            pp[k].x = s->xyw[3 * q];
            pp[k].y = s->xyw[3 * q + 1];
            pp[k].w = s->xyw[3 * q + 2];
        }
        cs_error err;
        cs_status st = cs_scene_add_contour(sc, s->degree[c], s->count[c], pp,
                                            s->has_iv[c] ? &s->iv[s->first[c]] : NULL, &err);
        if (pp != pts)
            free(pp);
        if (st != CS_OK)
            return st;
    }
    return CS_OK;
}

/*
 * A scene of canvas cw x ch with one cel (transform xf, or identity) holding
 * one region of the shape painted opaque white; no background, lights front 1
 * back 0. Records a failed CHECK and returns the status if any call fails.
 */
static TL_UNUSED cs_status tc_scene_one(cs_scene *sc, float cw, float ch, const cs_affine *xf,
                                        const tc_shape *s)
{
    cs_error err;
    cs_status st = cs_scene_init(sc, cw, ch);
    if (!CHECK(st == CS_OK, "cs_scene_init(%g, %g) gave %s", (double)cw, (double)ch,
               tl_status_name(st)))
        return st;
    st = cs_scene_add_cel(sc, xf ? xf : &tc_identity, NULL, NULL, &err);
    if (!CHECK(st == CS_OK, "cs_scene_add_cel gave %s", tl_status_name(st)))
        return st;
    cs_paint paint = tc_white_paint();
    st = cs_scene_add_region(sc, s->evenodd ? CS_FILL_EVENODD : CS_FILL_NONZERO, &paint, &err);
    if (!CHECK(st == CS_OK, "cs_scene_add_region gave %s", tl_status_name(st)))
        return st;
    st = tc_add_contours(sc, s);
    CHECK(st == CS_OK, "cs_scene_add_contour gave %s", tl_status_name(st));
    return st;
}

/* The reference region in device space: transform xf, then canvas-to-device scale. */
static TL_UNUSED ref_region *tc_ref(const tc_shape *s, const cs_affine *xf, double sx, double sy)
{
    ref_region *r = ref_region_new(s->evenodd);
    for (int c = 0; c < s->ncont; c++)
        ref_region_add(r, s->degree[c], s->count[c], &s->xyw[3 * s->first[c]],
                       s->has_iv[c] ? &s->iv[s->first[c]] : NULL);
    const cs_affine *m = xf ? xf : &tc_identity;
    long double mm[6] = {m->a, m->b, m->c, m->d, m->e, m->f};
    ref_region_transform(r, mm, sx, sy);
    return r;
}

static cs_workspace *tc_ws_;

static TL_UNUSED cs_workspace *tc_workspace(void)
{
    if (!tc_ws_)
        tc_ws_ = tl_calloc(1, sizeof *tc_ws_);
    return tc_ws_;
}

/*
 * Renders sc at W x H into out (W*H linear values of the red channel) line by
 * line; also checks that green and blue equal red (every test paint is grey).
 * Returns the first failing status (and CHECKs it), or CS_OK.
 */
static TL_UNUSED cs_status tc_render_rgb(const cs_scene *sc, int W, int H, cs_aa_mode aa, int nsub,
                                         float *rgb /* 3*W*H */)
{
    cs_renderer r;
    cs_render_opts o = {.width = W, .height = H, .aa = aa, .subscanlines = nsub};
    cs_error err;
    cs_status st = cs_frame_begin(&r, tc_workspace(), sc, &o, &err);
    if (!CHECK(st == CS_OK, "cs_frame_begin(%dx%d, aa %d/%d) gave %s (cel %d region %d contour %d item %d)",
               W, H, (int)aa, nsub, tl_status_name(st), (int)err.cel, (int)err.region,
               (int)err.contour, (int)err.item))
        return st;
    for (int y = 0; y < H; y++) {
        st = cs_render_line(&r, y, rgb + (size_t)3 * W * y);
        if (st != CS_OK)
            break;
    }
    CHECK(st == CS_OK, "cs_render_line of %dx%d (aa %d/%d) gave %s", W, H, (int)aa, nsub,
          tl_status_name(st));
    return st;
}

static TL_UNUSED cs_status tc_render(const cs_scene *sc, int W, int H, cs_aa_mode aa, int nsub,
                                     double *out)
{
    float *rgb = tl_calloc((size_t)3 * W * H, sizeof *rgb);
    cs_status st = tc_render_rgb(sc, W, H, aa, nsub, rgb);
    if (st == CS_OK) {
        int bad = 0, bi = 0, bj = 0;
        for (int j = 0; j < H; j++)
            for (int i = 0; i < W; i++) {
                const float *p = rgb + 3 * ((size_t)W * j + i);
                if ((p[1] != p[0] || p[2] != p[0]) && bad++ == 0) {
                    bi = i;
                    bj = j;
                }
                out[(size_t)W * j + i] = p[0];
            }
        CHECK(bad == 0, "grey paint gave %d non-grey pixels, first (%d,%d)", bad, bi, bj);
    }
    free(rgb);
    return st;
}

/*
 * got vs want: worst |got - want| <= worst_tol and mean over all pixels <=
 * mean_tol (tolerances in coverage units; callers write them as k/255.0).
 */
static TL_UNUSED void tc_expect_close(const char *what, const double *got, const double *want,
                                      int W, int H, double worst_tol, double mean_tol)
{
    double worst = -1, sum = 0;
    int wi = 0, wj = 0, over = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            size_t k = (size_t)W * j + i;
            double d = fabs(got[k] - want[k]);
            if (!(d == d))
                d = INFINITY;
            sum += d;
            if (d > worst) {
                worst = d;
                wi = i;
                wj = j;
            }
            if (d > worst_tol)
                over++;
        }
    double mean = sum / ((double)W * H);
    size_t wk = (size_t)W * wj + wi;
    if (getenv("TL_VERBOSE"))
        tl_note("%s: worst %.3f/255 at (%d,%d), mean %.4f/255", what, worst * 255, wi, wj,
                mean * 255);
    if (!CHECK(worst <= worst_tol,
               "%s: worst pixel (%d,%d) expected coverage %.5f, got %.5f: off by %.2f/255 "
               "(limit %.2f/255); %d pixels over the limit",
               what, wi, wj, want[wk], got[wk], worst * 255, worst_tol * 255, over)) {
        int shown = 0;
        for (int j = 0; j < H && shown < 8; j++)
            for (int i = 0; i < W && shown < 8; i++) {
                size_t k = (size_t)W * j + i;
                if (fabs(got[k] - want[k]) > worst_tol) {
                    tl_note("pixel (%d,%d): expected %.5f got %.5f", i, j, want[k], got[k]);
                    shown++;
                }
            }
    }
    CHECK(mean <= mean_tol, "%s: mean abs error %.3f/255 over %dx%d pixels (limit %.3f/255)", what,
          mean * 255, W, H, mean_tol * 255);
}

/*
 * One-sample-per-pixel output vs pixel-centre truth: every pixel not flagged
 * ambiguous must be exactly 0 or 1 as the truth says.
 */
static TL_UNUSED void tc_expect_centre(const char *what, const double *got,
                                       const unsigned char *inside, const unsigned char *amb,
                                       int W, int H)
{
    int bad = 0, namb = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            size_t k = (size_t)W * j + i;
            if (amb && amb[k]) {
                namb++;
                continue;
            }
            double want = inside[k] ? 1.0 : 0.0;
            if (fabs(got[k] - want) > 1e-6) {
                if (bad < 8)
                    tl_note("%s: pixel (%d,%d): centre is %s, expected %.0f got %.6f", what, i,
                            j, inside[k] ? "inside" : "outside", want, got[k]);
                bad++;
            }
        }
    CHECK(bad == 0, "%s: %d pixels differ from the pixel-centre truth (%d near-boundary pixels "
                    "excused)",
          what, bad, namb);
}

/* No coverage within `margin` pixels of the image border (catches streaks to the edge). */
static TL_UNUSED void tc_expect_border_clear(const char *what, const double *got, int W, int H,
                                             int margin)
{
    int bad = 0, rows = 0, last_row = -1;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            if (i >= margin && i < W - margin && j >= margin && j < H - margin)
                continue;
            double v = got[(size_t)W * j + i];
            if (v != 0.0) {
                if (bad < 6)
                    tl_note("%s: border pixel (%d,%d) has coverage %.6f", what, i, j, v);
                bad++;
                if (j != last_row) {
                    rows++;
                    last_row = j;
                }
            }
        }
    CHECK(bad == 0, "%s: %d pixels in %d rows have coverage within %d px of the border (a streak "
                    "or a leak)",
          what, bad, rows, margin);
}

static TL_UNUSED double tc_sum(const double *v, size_t n)
{
    double s = 0;
    for (size_t i = 0; i < n; i++)
        s += v[i];
    return s;
}

/* Deterministic PRNG (xorshift64*), so a failure reproduces. */
static uint64_t tc_rng_state = 0x9E3779B97F4A7C15ull;

static TL_UNUSED void tc_seed(uint64_t s)
{
    tc_rng_state = s ? s : 1;
}

static TL_UNUSED double tc_rand(void) /* [0, 1) */
{
    tc_rng_state ^= tc_rng_state >> 12;
    tc_rng_state ^= tc_rng_state << 25;
    tc_rng_state ^= tc_rng_state >> 27;
    return (double)((tc_rng_state * 2685821657736338717ull) >> 11) / 9007199254740992.0;
}

static TL_UNUSED double tc_uniform(double lo, double hi)
{
    return lo + (hi - lo) * tc_rand();
}

#endif /* CELSCAN_TEST_COMMON_H */
