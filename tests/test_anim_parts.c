/*
 * test_anim_parts.c - cubic Bezier and hold easing, TRS transform tracks and
 * cel groups (parent transforms and opacity), against independent truth.
 *
 * Easing is checked against the curve solved in long double by Newton's
 * method from libm-free closed forms of x(v) and x'(v); TRS keys against
 * the matrix product written out with libm's sinl/cosl; rendered frames of
 * turned, grouped and faded cels against the long double reference
 * rasteriser (tests/ref) given the matrix computed here, so neither the
 * core's polynomial sine nor its track code is trusted by the test.
 */
#include <math.h>

#include "common.h"
#include "cs_internal.h"

static cs_scene scene;

/* One cel with a 40 x 10 bar centred on the origin, painted white. */
static void bar_scene(void)
{
    static const double bar[] = {-20, -5, 20, -5, 20, 5, -20, 5};
    tc_shape *s = tc_shape_new(0);
    tc_add_xy(s, 1, 4, bar, NULL);
    tc_scene_one(&scene, 100, 100, NULL, s);
    free(s);
}

/* The eased s at u of (x1 y1 x2 y2), solved in long double. */
static long double ease_ref(const double *e, long double u)
{
    long double v = u;
    for (int i = 0; i < 60; i++) {
        long double w = 1 - v;
        long double x = 3 * w * w * v * e[0] + 3 * w * v * v * e[2] + v * v * v;
        long double dx = 3 * w * w * e[0] + 6 * w * v * (e[2] - e[0]) + 3 * v * v * (1 - e[2]);
        if (dx < 1e-12L) { /* flat start: bisect instead */
            long double lo = 0, hi = 1;
            for (int k = 0; k < 100; k++) {
                long double m = (lo + hi) / 2, mw = 1 - m;
                long double mx = 3 * mw * mw * m * e[0] + 3 * mw * m * m * e[2] + m * m * m;
                if (mx < u)
                    lo = m;
                else
                    hi = m;
            }
            v = (lo + hi) / 2;
            break;
        }
        v -= (x - u) / dx;
        if (v < 0)
            v = 0;
        if (v > 1)
            v = 1;
    }
    long double w = 1 - v;
    return 3 * w * w * v * e[1] + 3 * w * v * v * e[3] + v * v * v;
}

static void add_keys(const float *times, const float *vals, int n, int width)
{
    for (int k = 0; k < n; k++) {
        cs_error err;
        cs_status st = cs_scene_add_key(&scene, times[k], vals + k * width, &err);
        CHECK(st == CS_OK, "key %d: %s", k, tl_status_name(st));
    }
}

static void test_cubic_ease(void)
{
    static const double eases[][4] = {
        {0.42, 0, 0.58, 1}, {0.25, 0.1, 0.25, 1}, {0, 0, 1, 1}, {0.33, 0, 0.67, 1},
        {0.17, 0.67, 0.83, 0.67}, {0.5, -0.5, 0.5, 1.5}, {0, 1, 0, 1}, {1, 0, 1, 0},
    };
    bar_scene();
    cs_error err;
    double worst = 0;
    for (size_t q = 0; q < sizeof eases / sizeof eases[0]; q++) {
        CHECK_STATUS(cs_scene_add_track(&scene, CS_TRACK_TRANSFORM, 0, CS_EASE_CUBIC, &err), CS_OK,
                     "cubic transform track");
        float keys[2][10] = {{(float)eases[q][0], (float)eases[q][1], (float)eases[q][2],
                              (float)eases[q][3], 1, 0, 0, 1, 0, 0},
                             {0, 0, 1, 1, 1, 0, 0, 1, 10, 0}};
        add_keys((const float[]){0, 2}, &keys[0][0], 2, 10);
        const cs_track *tr = cs__track_find(&scene, CS_TRACK_TRANSFORM, 0);
        for (int i = 0; i <= 200; i++) {
            float t = 2.0f * (float)i / 200.0f, s;
            uint32_t i0, i1;
            cs__track_locate(&scene, tr, t, &i0, &i1, &s);
            long double want = i == 200 ? 1 : ease_ref(eases[q], (long double)t / 2);
            double got = i == 200 ? (i1 == 1 ? 1.0 : -9) : s;
            double d = fabs(got - (double)want);
            if (d > worst)
                worst = d;
            if (d > 2e-6)
                tl_note("ease %zu at u %g: %.9f, want %.9Lf", q, t / 2.0, got, want);
        }
    }
    CHECK(worst < 2e-6, "cubic easing within 2e-6 of the long double solution, worst %.3g", worst);

    /* Control points on the diagonal: exactly linear. */
    CHECK_STATUS(cs_scene_add_track(&scene, CS_TRACK_TRANSFORM, 0, CS_EASE_CUBIC, &err), CS_OK,
                 "diagonal");
    float lin[2][10] = {{0.3f, 0.3f, 0.8f, 0.8f, 1, 0, 0, 1, 0, 0}, {0, 0, 1, 1, 1, 0, 0, 1, 1, 0}};
    add_keys((const float[]){1, 4}, &lin[0][0], 2, 10);
    const cs_track *tr = cs__track_find(&scene, CS_TRACK_TRANSFORM, 0);
    int exact = 1;
    for (int i = 0; i <= 30; i++) {
        float t = 1.0f + 0.1f * (float)i, s;
        uint32_t i0, i1;
        cs__track_locate(&scene, tr, t, &i0, &i1, &s);
        exact &= i0 == i1 || s == (t - 1.0f) / 3.0f;
    }
    CHECK(exact, "a diagonal cubic gives the linear s bit for bit");
}

static void test_hold_and_ranges(void)
{
    bar_scene();
    cs_error err;
    /* A cubic track with a hold segment, then a linear one. */
    CHECK_STATUS(cs_scene_add_track(&scene, CS_TRACK_TRANSFORM, 0, CS_EASE_CUBIC, &err), CS_OK,
                 "track");
    float keys[3][10] = {{-1, 0, 0, 0, 1, 0, 0, 1, 0, 0},
                         {0, 0, 1, 1, 1, 0, 0, 1, 10, 0},
                         {0, 0, 1, 1, 1, 0, 0, 1, 20, 0}};
    add_keys((const float[]){0, 1, 2}, &keys[0][0], 3, 10);
    const cs_track *tr = cs__track_find(&scene, CS_TRACK_TRANSFORM, 0);
    uint32_t i0, i1;
    float s;
    cs__track_locate(&scene, tr, 0.999f, &i0, &i1, &s);
    CHECK(i0 == 0 && s == 0.0f, "hold segment keeps the first key (i0 %u, s %g)", i0, (double)s);
    cs__track_locate(&scene, tr, 1.5f, &i0, &i1, &s);
    CHECK(i0 == 1 && s == 0.5f, "the next segment is linear (i0 %u, s %g)", i0, (double)s);

    /* A whole-track hold. */
    CHECK_STATUS(cs_scene_add_track(&scene, CS_TRACK_TRANSFORM, 0, CS_EASE_HOLD, &err), CS_OK,
                 "hold track");
    float hk[2][6] = {{1, 0, 0, 1, 0, 0}, {1, 0, 0, 1, 5, 0}};
    add_keys((const float[]){0, 1}, &hk[0][0], 2, 6);
    tr = cs__track_find(&scene, CS_TRACK_TRANSFORM, 0);
    cs__track_locate(&scene, tr, 0.9f, &i0, &i1, &s);
    CHECK(i0 == 0 && s == 0.0f, "hold ease keeps the earlier key");

    /* Easing values out of range, NaN, a malformed hold. */
    static const float bad[][4] = {{1.5f, 0, 0.5f, 1}, {0.5f, 0, -0.1f, 1}, {0.5f, 3.5f, 0.5f, 1},
                                   {-1, 0, 0, 1},      {NAN, 0, 1, 1}};
    static const cs_status why[] = {CS_ERR_RANGE, CS_ERR_RANGE, CS_ERR_RANGE, CS_ERR_RANGE,
                                    CS_ERR_NONFINITE};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        CHECK_STATUS(cs_scene_add_track(&scene, CS_TRACK_TRANSFORM, 0, CS_EASE_CUBIC, &err), CS_OK,
                     "track");
        float v[10] = {bad[k][0], bad[k][1], bad[k][2], bad[k][3], 1, 0, 0, 1, 0, 0};
        cs_status st = cs_scene_add_key(&scene, 0, v, &err);
        CHECK(st == why[k] && err.item == 0, "bad easing %zu refused with %s (got %s, item %d)", k,
              tl_status_name(why[k]), tl_status_name(st), (int)err.item);
    }
    /* Overshoot is clamped on a paint track but kept on a transform. */
    CHECK_STATUS(cs_scene_add_track(&scene, CS_TRACK_PAINT, 0, CS_EASE_CUBIC, &err), CS_OK,
                 "paint track");
    float pk[2][11] = {{0.5f, 3, 0.5f, 3, 1, 1, 1, 1, 1, 1, 0}, {0, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1}};
    add_keys((const float[]){0, 1}, &pk[0][0], 2, 11);
    tr = cs__track_find(&scene, CS_TRACK_PAINT, 0);
    cs__track_locate(&scene, tr, 0.5f, &i0, &i1, &s);
    CHECK(s == 1.0f, "paint overshoot clamped to 1 (s %g)", (double)s);
    CHECK_STATUS(cs_scene_add_track(&scene, CS_TRACK_TRANSFORM, 0, CS_EASE_CUBIC, &err), CS_OK,
                 "transform track");
    float tk[2][10] = {{0.5f, 3, 0.5f, 3, 1, 0, 0, 1, 0, 0}, {0, 0, 1, 1, 1, 0, 0, 1, 1, 0}};
    add_keys((const float[]){0, 1}, &tk[0][0], 2, 10);
    tr = cs__track_find(&scene, CS_TRACK_TRANSFORM, 0);
    cs__track_locate(&scene, tr, 0.5f, &i0, &i1, &s);
    CHECK(s > 1.5f, "transform overshoot kept (s %g)", (double)s);
}

/* The TRS matrix written out in long double with libm. */
static void trs_ref(const double *v, long double m[6])
{
    long double d = 3.14159265358979323846264338327950288L / 180;
    long double c = cosl(v[6] * d), s = sinl(v[6] * d);
    long double k = tanl(v[7] * d), ca = cosl(v[8] * d), sa = sinl(v[8] * d);
    /* K = R(axis) [1 k; 0 1] R(-axis) */
    long double K[4] = {1 - k * sa * ca, -k * sa * sa, k * ca * ca, 1 + k * sa * ca};
    long double RK[4] = {c * K[0] - s * K[1], s * K[0] + c * K[1], c * K[2] - s * K[3],
                         s * K[2] + c * K[3]};
    m[0] = RK[0] * v[4];
    m[1] = RK[1] * v[4];
    m[2] = RK[2] * v[5];
    m[3] = RK[3] * v[5];
    m[4] = v[0] - m[0] * v[2] - m[2] * v[3];
    m[5] = v[1] - m[1] * v[2] - m[3] * v[3];
}

static void test_trs_affine(void)
{
    tc_seed(25);
    double worst = 0;
    for (int i = 0; i < 20000; i++) {
        double v[10] = {tc_uniform(-500, 500), tc_uniform(-500, 500), tc_uniform(-100, 100),
                        tc_uniform(-100, 100), tc_uniform(-3, 3),     tc_uniform(-3, 3),
                        i < 10000 ? tc_uniform(-720, 720) : tc_uniform(-1e5, 1e5),
                        i % 3 ? 0 : tc_uniform(-80, 80), tc_uniform(-180, 180), 1};
        float f[10], m[6];
        for (int k = 0; k < 10; k++)
            f[k] = (float)v[k];
        for (int k = 0; k < 10; k++)
            v[k] = f[k];
        long double r[6];
        trs_ref(v, r);
        cs__trs_affine(f, m);
        /* Relative to the map's size: the linear part's and the offset's. */
        long double lin = 1 + fabsl(r[0]) + fabsl(r[1]) + fabsl(r[2]) + fabsl(r[3]);
        long double off = 1 + fabsl(v[0]) + lin * (fabsl(v[2]) + fabsl(v[3]));
        for (int k = 0; k < 6; k++) {
            double d = (double)(fabsl(m[k] - r[k]) / (k < 4 ? lin : off));
            if (d > worst)
                worst = d;
        }
    }
    CHECK(worst < 2e-6, "TRS maps within 2e-6 (relative) of long double libm, worst %.3g", worst);
    float q[10] = {0, 0, 0, 0, 1, 1, 90, 0, 0, 1}, m[6];
    cs__trs_affine(q, m);
    CHECK(m[0] == 0 && m[1] == 1 && m[2] == -1 && m[3] == 0, "90 degrees is exact: %g %g %g %g",
          (double)m[0], (double)m[1], (double)m[2], (double)m[3]);
    q[6] = -270;
    cs__trs_affine(q, m);
    CHECK(m[0] == 0 && m[1] == 1 && m[2] == -1 && m[3] == 0, "-270 degrees is 90");
    /* Key checks: opacity, skew, NaN. */
    bar_scene();
    cs_error err;
    static const float bad[][10] = {{0, 0, 0, 0, 1, 1, 0, 0, 0, 1.5f},
                                    {0, 0, 0, 0, 1, 1, 0, 86, 0, 1},
                                    {0, 0, 0, 0, 1e5f, 1, 0, 0, 0, 1},
                                    {0, 0, 0, 0, 1, 1, NAN, 0, 0, 1}};
    static const cs_status why[] = {CS_ERR_PAINT, CS_ERR_RANGE, CS_ERR_RANGE, CS_ERR_NONFINITE};
    for (int k = 0; k < 4; k++) {
        CHECK_STATUS(cs_scene_add_track(&scene, CS_TRACK_TRS, 0, CS_EASE_LINEAR, &err), CS_OK,
                     "TRS track");
        cs_status st = cs_scene_add_key(&scene, 0, bad[k], &err);
        CHECK(st == why[k], "bad TRS key %d: %s, want %s", k, tl_status_name(st),
              tl_status_name(why[k]));
    }
}

/* Renders the scene at time t into cov (100 x 100 coverage). */
static void render_at(float t, double *cov)
{
    float *rgb = tl_calloc(3 * 100 * 100, sizeof *rgb);
    cs_renderer r;
    cs_render_opts o = cs_render_defaults(100, 100);
    o.time = t;
    cs_error err;
    cs_status st = cs_frame_begin(&r, tc_workspace(), &scene, &o, &err);
    CHECK(st == CS_OK, "frame at %g: %s", (double)t, tl_status_name(st));
    for (int y = 0; y < 100 && st == CS_OK; y++)
        st = cs_render_line(&r, y, rgb + 300 * y);
    for (int i = 0; i < 100 * 100; i++)
        cov[i] = rgb[3 * i];
    free(rgb);
}

/* The bar's reference coverage under map m (long double). */
static void bar_ref(const long double m[6], double *cov)
{
    static const float bar[] = {-20, -5, 1, 20, -5, 1, 20, 5, 1, -20, 5, 1};
    ref_region *r = ref_region_new(0);
    ref_region_add(r, 1, 4, bar, NULL);
    ref_region_transform(r, m, 1, 1);
    ref_coverage_area(r, 100, 100, cov);
    ref_region_free(r);
}

/* A half turn between two keys keeps the bar's size; the matrix track does not. */
static void test_half_turn(void)
{
    double *got = tl_calloc(100 * 100, sizeof *got), *want = tl_calloc(100 * 100, sizeof *want);
    bar_scene();
    cs_error err;
    CHECK_STATUS(cs_scene_add_track(&scene, CS_TRACK_TRS, 0, CS_EASE_LINEAR, &err), CS_OK, "trs");
    float keys[2][10] = {{50, 50, 0, 0, 1, 1, 0, 0, 0, 1}, {50, 50, 0, 0, 1, 1, 180, 0, 0, 1}};
    add_keys((const float[]){0, 1}, &keys[0][0], 2, 10);
    static const float times[] = {0, 0.25f, 0.5f, 0.7f, 1};
    for (int i = 0; i < 5; i++) {
        render_at(times[i], got);
        double v[10] = {50, 50, 0, 0, 1, 1, 180.0 * times[i], 0, 0, 1};
        long double m[6];
        trs_ref(v, m);
        bar_ref(m, want);
        char what[64];
        snprintf(what, sizeof what, "half turn at t %g", (double)times[i]);
        tc_expect_close(what, got, want, 100, 100, 3 / 255.0, 0.2 / 255.0);
        CHECK(fabs(tc_sum(got, 100 * 100) - 400) < 0.5, "%s: area %.3f, want 400", what,
              tc_sum(got, 100 * 100));
    }
    /* The same turn as two matrix keys collapses to nothing half way. */
    CHECK_STATUS(cs_scene_remove_track(&scene, CS_TRACK_TRS, 0, &err), CS_OK, "remove");
    CHECK_STATUS(cs_scene_add_track(&scene, CS_TRACK_TRANSFORM, 0, CS_EASE_LINEAR, &err), CS_OK,
                 "matrix");
    float mk[2][6] = {{1, 0, 0, 1, 50, 50}, {-1, 0, 0, -1, 50, 50}};
    add_keys((const float[]){0, 1}, &mk[0][0], 2, 6);
    render_at(0.5f, got);
    CHECK(tc_sum(got, 100 * 100) < 1, "the matrix track's half turn has no area (%.3f)",
          tc_sum(got, 100 * 100));
    free(got);
    free(want);
}

/* A cel in a group of a group: the product of three animated maps, and opacity. */
static void test_groups(void)
{
    double *got = tl_calloc(100 * 100, sizeof *got), *want = tl_calloc(100 * 100, sizeof *want);
    bar_scene();
    cs_error err;
    static const cs_affine id = {1, 0, 0, 1, 0, 0};
    CHECK_STATUS(cs_scene_add_cel(&scene, &id, NULL, NULL, &err), CS_OK, "group cel 1");
    CHECK_STATUS(cs_scene_add_cel(&scene, &id, NULL, NULL, &err), CS_OK, "group cel 2");
    CHECK_STATUS(cs_scene_set_cel_parent(&scene, 0, 1, &err), CS_OK, "0 in 1");
    CHECK_STATUS(cs_scene_set_cel_parent(&scene, 1, 2, &err), CS_OK, "1 in 2");
    double a[2][10] = {{0, 0, 0, 0, 1, 1, 0, 0, 0, 1}, {0, 0, 0, 0, 1, 1, 60, 0, 0, 0.5}};
    double b[2][10] = {{10, 0, 0, 0, 1, 1, 0, 0, 0, 1}, {0, 10, 0, 0, 0.5, 1.5, 0, 20, 30, 1}};
    double c[2][10] = {{50, 50, 0, 0, 1, 1, 0, 0, 0, 1}, {40, 60, 5, 5, 1, 1, -30, 0, 0, 0.8}};
    const double (*tracks[3])[10] = {a, b, c};
    for (uint32_t cel = 0; cel < 3; cel++) {
        CHECK_STATUS(cs_scene_add_track(&scene, CS_TRACK_TRS, cel, CS_EASE_LINEAR, &err), CS_OK,
                     "trs");
        float f[2][10];
        for (int k = 0; k < 20; k++)
            f[k / 10][k % 10] = (float)tracks[cel][k / 10][k % 10];
        add_keys((const float[]){0, 1}, &f[0][0], 2, 10);
    }
    for (int i = 0; i <= 4; i++) {
        double t = i / 4.0, opacity = 1;
        long double m[6] = {1, 0, 0, 1, 0, 0};
        for (int cel = 0; cel < 3; cel++) {
            double v[10];
            for (int k = 0; k < 10; k++)
                v[k] = (1 - t) * tracks[cel][0][k] + t * tracks[cel][1][k];
            long double p[6], r[6];
            trs_ref(v, p);
            r[0] = p[0] * m[0] + p[2] * m[1];
            r[1] = p[1] * m[0] + p[3] * m[1];
            r[2] = p[0] * m[2] + p[2] * m[3];
            r[3] = p[1] * m[2] + p[3] * m[3];
            r[4] = p[0] * m[4] + p[2] * m[5] + p[4];
            r[5] = p[1] * m[4] + p[3] * m[5] + p[5];
            for (int k = 0; k < 6; k++)
                m[k] = r[k];
            opacity *= v[9];
        }
        bar_ref(m, want);
        for (int k = 0; k < 100 * 100; k++)
            want[k] *= opacity; /* white on black at beta * opacity */
        render_at((float)t, got);
        char what[64];
        snprintf(what, sizeof what, "nested groups at t %g", t);
        tc_expect_close(what, got, want, 100, 100, 3 / 255.0, 0.2 / 255.0);
    }
    /* Cycles and chains too deep are refused; removal frees children. */
    CHECK_STATUS(cs_scene_set_cel_parent(&scene, 2, 0, &err), CS_ERR_GROUP, "cycle 0-1-2-0");
    CHECK_STATUS(cs_scene_set_cel_parent(&scene, 2, 2, &err), CS_ERR_GROUP, "own parent");
    CHECK_STATUS(cs_scene_set_cel_parent(&scene, 2, 3, &err), CS_ERR_INDEX, "no such parent");
    for (int k = 3; k < 3 + CS_CFG_MAX_GROUP_DEPTH; k++)
        cs_scene_add_cel(&scene, &id, NULL, NULL, &err);
    cs_status st = CS_OK;
    uint32_t k = 2;
    while (st == CS_OK && k + 1 < scene.cel_count) {
        st = cs_scene_set_cel_parent(&scene, k, k + 1, &err);
        k++;
    }
    CHECK(st == CS_ERR_GROUP && k == CS_CFG_MAX_GROUP_DEPTH,
          "a chain of %d cels is refused at the link that makes it (%s at %u)",
          CS_CFG_MAX_GROUP_DEPTH + 1, tl_status_name(st), k);
    CHECK_STATUS(cs_scene_remove_cel(&scene, 1, &err), CS_OK, "remove the middle group");
    CHECK(scene.cels[0].parent == CS_NO_PARENT && scene.cels[1].parent == 2,
          "child of the removed cel has no parent (%u), later links renumbered (%u)",
          scene.cels[0].parent, scene.cels[1].parent);
    CHECK_STATUS(cs_scene_move_cel(&scene, 1, 0, &err), CS_OK, "move");
    CHECK(scene.cels[0].parent == 2 && scene.cels[1].parent == CS_NO_PARENT,
          "links follow a move (%u, %u)", scene.cels[0].parent, scene.cels[1].parent);
    free(got);
    free(want);
}

int main(int argc, char **argv)
{
    (void)argc;
    TL_RUN(test_cubic_ease);
    TL_RUN(test_hold_and_ranges);
    TL_RUN(test_trs_affine);
    TL_RUN(test_half_turn);
    TL_RUN(test_groups);
    return tl_summary(argv[0]);
}
