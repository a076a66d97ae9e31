/*
 * test_composite.c - the beta colour model against its closed form.
 *
 * DESIGN.md, per channel in linear light: a paint (pigment p, medium m, beta)
 * on a cel lit by front F and back B maps light L from behind to E + T L with
 *   E = beta p F + (1 - beta) m B,   T = (1 - beta) m;
 * coverage c gives (c E, 1 - c (1 - T)); cels stack front to back as
 * (E1 + T1 E2, T1 T2); the stack sees L_behind = background * F_s with a
 * background card, else the stack back light B_s. A cel's front light
 * defaults to F_s, its back light to black. Regions of one cel that share an
 * edge leave no seam (their coverage-weighted maps add up).
 *
 * Scenes are rectangles with vertical edges at x.0 or x.5 and horizontal
 * edges on pixel boundaries, so coverage is exactly 0, 1/2 or 1 and every
 * pixel has a closed form; tolerance 1e-5.
 */
#include "common.h"

#define W 32
#define H 8

typedef struct map {
    double E[3], T[3];
} map;

static map paint_map(const cs_paint *p, const float F[3], const float B[3])
{
    map m;
    for (int c = 0; c < 3; c++) {
        m.E[c] = (double)p->beta * p->pigment[c] * F[c] + (1.0 - p->beta) * p->medium[c] * B[c];
        m.T[c] = (1.0 - p->beta) * p->medium[c];
    }
    return m;
}

static map cover(map m, double c)
{
    map r;
    for (int k = 0; k < 3; k++) {
        r.E[k] = c * m.E[k];
        r.T[k] = 1 - c * (1 - m.T[k]);
    }
    return r;
}

static map over(map front, map back)
{
    map r;
    for (int k = 0; k < 3; k++) {
        r.E[k] = front.E[k] + front.T[k] * back.E[k];
        r.T[k] = front.T[k] * back.T[k];
    }
    return r;
}

static const map clear_map = {{0, 0, 0}, {1, 1, 1}};

static void add_rect(cs_scene *sc, double x0, double x1, cs_fill_rule rule, const cs_paint *p)
{
    cs_error err;
    cs_status st = cs_scene_add_region(sc, rule, p, &err);
    cs_point pts[4] = {{(float)x0, 0, 1}, {(float)x1, 0, 1}, {(float)x1, H, 1}, {(float)x0, H, 1}};
    if (st == CS_OK)
        st = cs_scene_add_contour(sc, 1, 4, pts, NULL, &err);
    CHECK_STATUS(st, CS_OK, "adding a rectangle region");
}

/* Renders and compares column x (every row) with want[x] as out = E + T L. */
static void expect_columns(const char *what, const cs_scene *sc, const map *want, const double L[3])
{
    float *rgb = tl_calloc(3 * W * H, sizeof *rgb);
    if (tc_render_rgb(sc, W, H, CS_AA_SUBSCAN, 4, rgb) == CS_OK) {
        double worst = 0;
        int wx = 0, wy = 0, wc = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++)
                for (int c = 0; c < 3; c++) {
                    double e = want[x].E[c] + want[x].T[c] * L[c];
                    double d = fabs(rgb[3 * (y * W + x) + c] - e);
                    if (!(d <= worst)) {
                        worst = d;
                        wx = x, wy = y, wc = c;
                    }
                }
        double e = want[wx].E[wc] + want[wx].T[wc] * L[wc];
        CHECK(worst <= 1e-5, "%s: pixel (%d,%d) channel %d: expected %.6f, got %.6f", what, wx, wy,
              wc, e, (double)rgb[3 * (wy * W + wx) + wc]);
    }
    free(rgb);
}

static void test_empty_stack(void)
{
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    map want[W];
    for (int x = 0; x < W; x++)
        want[x] = clear_map;
    const float Fs[3] = {0.8f, 0.9f, 1.0f}, Bs[3] = {0.2f, 0.3f, 0.4f};
    cs_scene_init(sc, W, H);
    double zero[3] = {0, 0, 0};
    expect_columns("empty scene, default lights: black", sc, want, zero);
    cs_scene_set_lights(sc, Fs, Bs);
    double Ls[3] = {Bs[0], Bs[1], Bs[2]};
    expect_columns("empty scene, no background: the stack back light", sc, want, Ls);
    const float bg[3] = {0.25f, 0.5f, 0.75f};
    cs_scene_set_background(sc, bg);
    double Lb[3] = {(double)bg[0] * Fs[0], (double)bg[1] * Fs[1], (double)bg[2] * Fs[2]};
    expect_columns("empty scene with background: background * F_s", sc, want, Lb);
    free(sc);
}

static void test_translucent_over_background(void)
{
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    cs_error err;
    const float Fs[3] = {0.8f, 0.9f, 1.0f}, Bs[3] = {0.1f, 0.2f, 0.3f};
    const float bg[3] = {0.25f, 0.5f, 0.75f};
    const float black[3] = {0, 0, 0};
    double L[3];
    for (int c = 0; c < 3; c++)
        L[c] = (double)bg[c] * Fs[c];
    static const cs_paint paints[] = {
        {{0.9f, 0.3f, 0.1f}, {1, 1, 1}, 0.5f},          /* the brief's case: medium 1 */
        {{0.9f, 0.3f, 0.1f}, {0.5f, 1.0f, 0.2f}, 0.5f}, /* coloured medium */
        {{0.2f, 0.7f, 0.4f}, {0.6f, 0.6f, 0.9f}, 0.15f},
        {{0.2f, 0.7f, 0.4f}, {0.6f, 0.6f, 0.9f}, 1.0f}, /* opaque */
        {{0, 0, 0}, {1, 1, 1}, 1.0f},                   /* hold-out matte */
        {{1, 1, 1}, {0.2f, 0.6f, 1.0f}, 0.0f},          /* gel */
    };
    for (size_t i = 0; i < sizeof paints / sizeof paints[0]; i++) {
        cs_scene_init(sc, W, H);
        cs_scene_set_lights(sc, Fs, Bs);
        cs_scene_set_background(sc, bg);
        cs_scene_add_cel(sc, &tc_identity, NULL, NULL, &err);
        add_rect(sc, 0, 10.5, CS_FILL_NONZERO, &paints[i]);
        map m = paint_map(&paints[i], Fs, black); /* front defaults to F_s, back to black */
        map want[W];
        for (int x = 0; x < W; x++)
            want[x] = x < 10 ? m : (x == 10 ? cover(m, 0.5) : clear_map);
        char what[120];
        snprintf(what, sizeof what, "paint %zu (beta %.2f) over a background", i,
                 (double)paints[i].beta);
        expect_columns(what, sc, want, L);
    }
    free(sc);
}

static void test_cel_lights(void)
{
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    cs_error err;
    const float Fs[3] = {0.7f, 0.8f, 0.9f}, Bs[3] = {0.05f, 0.1f, 0.15f};
    const float F[3] = {0.5f, 1.0f, 0.25f}, B[3] = {0.3f, 0.2f, 0.1f};
    const cs_paint p = {{0.9f, 0.5f, 0.3f}, {0.4f, 0.8f, 1.0f}, 0.35f};
    cs_scene_init(sc, W, H);
    cs_scene_set_lights(sc, Fs, Bs);
    cs_scene_add_cel(sc, &tc_identity, F, B, &err);
    add_rect(sc, 4, 20.5, CS_FILL_NONZERO, &p);
    map m = paint_map(&p, F, B);
    map want[W];
    for (int x = 0; x < W; x++)
        want[x] = (x >= 4 && x < 20) ? m : (x == 20 ? cover(m, 0.5) : clear_map);
    double L[3] = {Bs[0], Bs[1], Bs[2]};
    expect_columns("cel with its own front and back light, light box behind", sc, want, L);
    free(sc);
}

static void test_two_cels(void)
{
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    cs_error err;
    const float Fs[3] = {1, 0.9f, 0.8f}, Bs[3] = {0.3f, 0.3f, 0.3f};
    const float B2[3] = {0.5f, 0.25f, 0.125f}, black[3] = {0, 0, 0};
    const cs_paint p1 = {{0.9f, 0.2f, 0.1f}, {0.5f, 0.9f, 0.7f}, 0.4f};
    const cs_paint p2 = {{0.1f, 0.3f, 0.9f}, {0.8f, 0.4f, 0.6f}, 0.3f};
    cs_scene_init(sc, W, H);
    cs_scene_set_lights(sc, Fs, Bs);
    cs_scene_add_cel(sc, &tc_identity, NULL, NULL, &err); /* front cel */
    add_rect(sc, 2, 20.5, CS_FILL_NONZERO, &p1);
    cs_scene_add_cel(sc, &tc_identity, NULL, B2, &err); /* back cel with its own back light */
    add_rect(sc, 10.5, 28, CS_FILL_EVENODD, &p2);
    map m1 = paint_map(&p1, Fs, black), m2 = paint_map(&p2, Fs, B2);
    map want[W];
    for (int x = 0; x < W; x++) {
        double c1 = (x >= 2 && x < 20) ? 1 : (x == 20 ? 0.5 : 0);
        double c2 = (x >= 11 && x < 28) ? 1 : (x == 10 ? 0.5 : 0);
        want[x] = over(cover(m1, c1), cover(m2, c2));
    }
    double L[3] = {Bs[0], Bs[1], Bs[2]};
    expect_columns("two overlapping cels", sc, want, L);

    /* An opaque front cel hides everything behind it. */
    const cs_paint opaque = {{0.6f, 0.5f, 0.4f}, {1, 1, 1}, 1.0f};
    cs_scene_init(sc, W, H);
    cs_scene_set_lights(sc, Fs, Bs);
    cs_scene_add_cel(sc, &tc_identity, NULL, NULL, &err);
    add_rect(sc, 0, W, CS_FILL_NONZERO, &opaque);
    cs_scene_add_cel(sc, &tc_identity, NULL, B2, &err);
    add_rect(sc, 0, W, CS_FILL_NONZERO, &p2);
    map mo = paint_map(&opaque, Fs, black);
    for (int x = 0; x < W; x++)
        want[x] = mo;
    expect_columns("opaque cel in front of a translucent one", sc, want, L);
    free(sc);
}

static void test_shared_edge(void)
{
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    cs_error err;
    const float ones[3] = {1, 1, 1}, black[3] = {0, 0, 0};
    const float bg[3] = {0.1f, 0.6f, 0.3f};
    const cs_paint pa = {{0.9f, 0.8f, 0.1f}, {0.3f, 0.9f, 0.5f}, 0.5f};
    const cs_paint pb = {{0.2f, 0.1f, 0.7f}, {0.9f, 0.5f, 0.4f}, 0.7f};
    double L[3] = {bg[0], bg[1], bg[2]};
    /* Same paint both sides of x = 10.5 (a cut through one pixel): no seam. */
    cs_scene_init(sc, W, H);
    cs_scene_set_background(sc, bg);
    cs_scene_add_cel(sc, &tc_identity, NULL, NULL, &err);
    add_rect(sc, 0, 10.5, CS_FILL_NONZERO, &pa);
    add_rect(sc, 10.5, W, CS_FILL_NONZERO, &pa);
    map ma = paint_map(&pa, ones, black), mb = paint_map(&pb, ones, black);
    map want[W];
    for (int x = 0; x < W; x++)
        want[x] = ma;
    expect_columns("two regions of one cel sharing an edge, same paint: no seam", sc, want, L);
    /* Different paints: the seam pixel is the coverage-weighted sum of the two maps. */
    cs_scene_init(sc, W, H);
    cs_scene_set_background(sc, bg);
    cs_scene_add_cel(sc, &tc_identity, NULL, NULL, &err);
    add_rect(sc, 0, 10.5, CS_FILL_NONZERO, &pa);
    add_rect(sc, 10.5, W, CS_FILL_NONZERO, &pb);
    for (int x = 0; x < W; x++) {
        if (x < 10)
            want[x] = ma;
        else if (x > 10)
            want[x] = mb;
        else
            for (int c = 0; c < 3; c++) {
                want[x].E[c] = 0.5 * ma.E[c] + 0.5 * mb.E[c];
                want[x].T[c] = 1 - 0.5 * (1 - ma.T[c]) - 0.5 * (1 - mb.T[c]);
            }
    }
    expect_columns("two regions of one cel sharing an edge, two paints", sc, want, L);
    /* A front region fully covering a pixel leaves nothing for the regions behind it in the same
     * cel (front-most region first). */
    cs_scene_init(sc, W, H);
    cs_scene_set_background(sc, bg);
    cs_scene_add_cel(sc, &tc_identity, NULL, NULL, &err);
    add_rect(sc, 0, 16, CS_FILL_NONZERO, &pa);
    add_rect(sc, 8, W, CS_FILL_NONZERO, &pb);
    for (int x = 0; x < W; x++)
        want[x] = x < 16 ? ma : mb;
    expect_columns("front region of a cel hides the region behind it", sc, want, L);
    free(sc);
}

int main(int argc, char **argv)
{
    (void)argc;
    TL_RUN(test_empty_stack);
    TL_RUN(test_translucent_over_background);
    TL_RUN(test_cel_lights);
    TL_RUN(test_two_cels);
    TL_RUN(test_shared_edge);
    free(tc_ws_);
    return tl_summary(argv[0]);
}
