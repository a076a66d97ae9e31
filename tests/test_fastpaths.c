/*
 * test_fastpaths.c - the renderer's shortcuts give the pixels the long way would.
 *
 * fold_region composites a run of fully covered pixels of an opaque paint
 * straight into the stack. The run must end exactly where the coverage
 * stops being full, including where that is not visible in the pixel's own
 * accumulators: a pixel can be full through its own partial area (a span
 * starting in it on one sub-scanline) while the running cover alone is
 * not, and the next pixel then has no deltas at all (one sub-scanline's
 * span ends on the pixel boundary, another's starts just left of it). An
 * L-shaped polygon makes exactly that at --aa 2: the upper half-row spans
 * [5, 11), the lower [10.25, 30), so pixel 10 is full (half from each) and
 * pixel 11 is half covered with no delta of its own.
 *
 * Expected values are exact fractions of the two sub-scanlines, the truth
 * of --aa 2 (DESIGN.md: sub-scanline coverage); the same shape is also
 * checked against the early-out turned off, which takes no shortcut.
 */
#include <string.h>

#include "celscan_private.h"
#include "testlib.h"

enum { W = 40, H = 4 };

static cs_scene scene;
static cs_workspace ws;

static void render(int sub, bool no_early_out, float *out)
{
    cs_render_opts o = cs_render_defaults(W, H);
    o.subscanlines = sub;
    o.no_early_out = no_early_out;
    cs_renderer r;
    cs_error e;
    CHECK_STATUS(cs_frame_begin(&r, &ws, &scene, &o, &e), CS_OK, "frame");
    for (int y = 0; y < H; y++)
        cs_render_line(&r, y, &out[3 * W * y]);
}

static void test_solid_run_ends(void)
{
    cs_error e;
    cs_scene_init(&scene, W, H);
    cs_affine id = {1, 0, 0, 1, 0, 0};
    cs_paint white = {{1, 1, 1}, {1, 1, 1}, 1};
    cs_scene_add_cel(&scene, &id, NULL, NULL, &e);
    cs_scene_add_region(&scene, CS_FILL_NONZERO, &white, &e);
    const cs_point l[8] = {{5, 1, 1},     {11, 1, 1},  {11, 1.5f, 1}, {30, 1.5f, 1},
                           {30, 2, 1},    {10.25f, 2, 1}, {10.25f, 1.5f, 1}, {5, 1.5f, 1}};
    CHECK_STATUS(cs_scene_add_contour(&scene, 1, 8, l, NULL, &e), CS_OK, "L shape");

    static float fast[3 * W * H], slow[3 * W * H];
    render(2, false, fast);
    render(2, true, slow);
    const float *row = &fast[3 * W * 1];
    CHECK_NEAR(row[3 * 9], 0.5, 1e-6, "pixel 9: upper half only");
    CHECK_NEAR(row[3 * 10], 0.5 + 0.5 * 0.75, 1e-6, "pixel 10: upper half and 3/4 of the lower");
    CHECK_NEAR(row[3 * 11], 0.5, 1e-6, "pixel 11: lower half only, no delta of its own");
    CHECK_NEAR(row[3 * 20], 0.5, 1e-6, "pixel 20: lower half");
    CHECK(memcmp(fast, slow, sizeof fast) == 0, "early-out and no early-out differ");

    /* The same with the lower span starting on the pixel boundary: pixel 10 is
     * full through its own area, pixel 11 half covered. */
    cs_scene_init(&scene, W, H);
    cs_scene_add_cel(&scene, &id, NULL, NULL, &e);
    cs_scene_add_region(&scene, CS_FILL_NONZERO, &white, &e);
    const cs_point m[8] = {{5, 1, 1},  {11, 1, 1}, {11, 1.5f, 1}, {30, 1.5f, 1},
                           {30, 2, 1}, {10, 2, 1}, {10, 1.5f, 1}, {5, 1.5f, 1}};
    CHECK_STATUS(cs_scene_add_contour(&scene, 1, 8, m, NULL, &e), CS_OK, "L shape on the boundary");
    render(2, false, fast);
    render(2, true, slow);
    row = &fast[3 * W * 1];
    CHECK_NEAR(row[3 * 10], 1.0, 1e-6, "pixel 10: full");
    CHECK_NEAR(row[3 * 11], 0.5, 1e-6, "pixel 11 after a full pixel: half");
    CHECK_NEAR(row[3 * 12], 0.5, 1e-6, "pixel 12: half");
    CHECK(memcmp(fast, slow, sizeof fast) == 0, "early-out and no early-out differ (boundary)");
    for (int sub = 1; sub <= 16; sub *= 2) {
        render(sub, false, fast);
        render(sub, true, slow);
        CHECK(memcmp(fast, slow, sizeof fast) == 0, "--aa %d: early-out and no early-out differ", sub);
    }
}

int main(int argc, char **argv)
{
    (void)argc;
    TL_RUN(test_solid_run_ends);
    return tl_summary(argv[0]);
}
