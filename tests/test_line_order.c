/*
 * test_line_order.c - a line is the same whichever lines came before it.
 *
 * The core may carry work from one sub-scanline to the next within a line
 * (a piece's root starts the solve one sub-scanline lower), but nothing
 * from line to line that history could change: a board may skip lines, a
 * cache build renders lines in its own order, and the firmware's frame
 * CRCs must not depend on history. (Exact mode keeps each piece's ends at
 * its next eight row boundaries for the rows below, filled from wherever a
 * row finds none, but an end is a pure function of the piece and the
 * height.) So
 * every line rendered alone, right after cs_frame_begin, must be
 * bit-identical to the same line rendered in the middle of the full frame,
 * in every anti-aliasing mode; and two renders of a frame are identical.
 *
 * The scene mixes what the crossing solver meets: exact circles (rational
 * quadratics), cubic blobs, polygons with horizontal edges, a rational cubic
 * with uneven weights and knots, translucent and opaque paints.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "celscan_private.h"
#include "shapes.h"
#include "testlib.h"

enum { W = 203, H = 131 };

static cs_scene scene;
static cs_workspace ws;

static void blob(float cx, float cy, float r, int k)
{
    cs_point p[48];
    float iv[48];
    for (int i = 0; i < k; i++) {
        float a0 = 6.2831853f * (float)i / (float)k, a1 = 6.2831853f * (float)(i + 1) / (float)k;
        float r0 = r * (1.0f + 0.3f * sinf(3.0f * a0)), r1 = r * (1.0f + 0.3f * sinf(3.0f * a1));
        float h = 0.55f * (a1 - a0) / 1.5708f;
        p[3 * i] = (cs_point){cx + r0 * cosf(a0), cy + r0 * sinf(a0), 1};
        p[3 * i + 1] = (cs_point){cx + r0 * (cosf(a0) - h * sinf(a0)), cy + r0 * (sinf(a0) + h * cosf(a0)), 1};
        p[3 * i + 2] = (cs_point){cx + r1 * (cosf(a1) + h * sinf(a1)), cy + r1 * (sinf(a1) - h * cosf(a1)), 1};
        iv[3 * i] = 1;
        iv[3 * i + 1] = iv[3 * i + 2] = 0;
    }
    cs_error e;
    CHECK_STATUS(cs_scene_add_contour(&scene, 3, 3 * k, p, iv, &e), CS_OK, "blob");
}

static void build(void)
{
    cs_error e;
    cs_scene_init(&scene, 100, 64);
    float bg[3] = {0.1f, 0.2f, 0.3f};
    cs_scene_set_background(&scene, bg);
    cs_affine id = {1, 0, 0, 1, 0, 0}, turn = {0.9f, 0.3f, -0.3f, 0.9f, 20.0f, -5.0f};
    cs_paint glass = {{0.9f, 0.8f, 0.2f}, {1, 1, 1}, 0.45f}, red = {{0.9f, 0.1f, 0.1f}, {1, 1, 1}, 1};
    cs_paint teal = {{0.1f, 0.7f, 0.6f}, {0.6f, 0.9f, 0.8f}, 0.7f}, ink = {{0, 0, 0}, {1, 1, 1}, 1};
    cs_scene_add_cel(&scene, &id, NULL, NULL, &e);
    cs_scene_add_region(&scene, CS_FILL_NONZERO, &glass, &e);
    CHECK_STATUS(ts_add_circle(&scene, 30.3f, 30.1f, 18.7f), CS_OK, "circle");
    cs_scene_add_region(&scene, CS_FILL_EVENODD, &ink, &e);
    const cs_point poly[6] = {{55, 10, 1}, {90, 10, 1}, {90, 20.5f, 1}, {70, 20.5f, 1},
                              {70, 40.25f, 1}, {55, 52, 1}};
    CHECK_STATUS(cs_scene_add_contour(&scene, 1, 6, poly, NULL, &e), CS_OK, "polygon");
    cs_scene_add_cel(&scene, &turn, NULL, NULL, &e);
    cs_scene_add_region(&scene, CS_FILL_NONZERO, &teal, &e);
    blob(45.0f, 35.0f, 20.0f, 8);
    const cs_point nurbs[7] = {{60, 5, 1},  {95, 12, 3.0f}, {88, 50, 0.4f}, {70, 60, 1.5f},
                               {40, 58, 1}, {35, 30, 2.2f}, {50, 15, 0.7f}};
    const float iv[7] = {1, 0.5f, 2, 1, 0, 1.5f, 1};
    cs_scene_add_region(&scene, CS_FILL_NONZERO, &red, &e);
    CHECK_STATUS(cs_scene_add_contour(&scene, 3, 7, nurbs, iv, &e), CS_OK, "nurbs");
}

/* Lines first, first + step, ... (while on screen) in one frame: how
 * many differ from the same lines of `full`. */
static int lines_differing(const cs_render_opts *o, const float *full, int first, int step)
{
    static float line[3 * W];
    cs_renderer r;
    cs_error e;
    int differ = 0;
    cs_frame_begin(&r, &ws, &scene, o, &e);
    for (int y = first; y >= 0 && y < H; y += step) {
        cs_render_line(&r, y, line);
        differ += memcmp(line, &full[3 * W * y], sizeof line) != 0;
    }
    return differ;
}

static void check_mode(const char *what, cs_aa_mode aa, int sub)
{
    cs_render_opts o = cs_render_defaults(W, H);
    o.aa = aa;
    if (aa == CS_AA_SUBSCAN)
        o.subscanlines = sub;
    static float full[3 * W * H], again[3 * W * H], line[3 * W];
    cs_renderer r;
    cs_error e;
    CHECK_STATUS(cs_frame_begin(&r, &ws, &scene, &o, &e), CS_OK, what);
    for (int y = 0; y < H; y++)
        cs_render_line(&r, y, &full[3 * W * y]);
    CHECK_STATUS(cs_frame_begin(&r, &ws, &scene, &o, &e), CS_OK, what);
    for (int y = 0; y < H; y++)
        cs_render_line(&r, y, &again[3 * W * y]);
    CHECK(memcmp(full, again, sizeof full) == 0, "%s: two renders of the frame differ", what);

    int differ = 0, first = -1;
    for (int y = 0; y < H; y++) {
        cs_frame_begin(&r, &ws, &scene, &o, &e);
        cs_render_line(&r, y, line);
        if (memcmp(line, &full[3 * W * y], sizeof line) != 0) {
            if (first < 0)
                first = y;
            differ++;
        }
    }
    CHECK(differ == 0, "%s: %d lines rendered alone differ from the full frame (first: %d)", what,
          differ, first);

    /* Every third line, in order but skipping: the same bytes again. */
    differ = lines_differing(&o, full, 1, 3);
    CHECK(differ == 0, "%s: %d lines differ when lines are skipped", what, differ);

    /* Every seventh line from the third: exact mode's level memo (eight
     * row boundaries per piece) is filled from other levels than in order. */
    differ = lines_differing(&o, full, 2, 7);
    CHECK(differ == 0, "%s: %d lines differ when every seventh is rendered", what, differ);

    /* Bottom to top in one frame: whatever the line before left behind. */
    differ = lines_differing(&o, full, H - 1, -1);
    CHECK(differ == 0, "%s: %d lines differ when rendered bottom to top", what, differ);
}

static void test_line_order(void)
{
    build();
    check_mode("--aa none", CS_AA_NONE, 1);
    check_mode("--aa 3", CS_AA_SUBSCAN, 3);
    check_mode("--aa 16", CS_AA_SUBSCAN, 16);
    check_mode("--aa exact", CS_AA_EXACT, 0);
}

int main(int argc, char **argv)
{
    (void)argc;
    TL_RUN(test_line_order);
    return tl_summary(argv[0]);
}
