/*
 * test_wall.c - celfw's board of a video wall: the scene source with a
 * viewport (lx_scene_source_viewport) against the core's whole render.
 *
 * A 2x2 wall of 96x54 boards (a 192x108 wall; the panel rows count from the
 * board's own top) at two instants of scenes/motion.json, two lanes as a
 * HUB75 panel pulls them (top half in lane 0, bottom half in lane 1): every
 * line a board's display asks for must be, float for float, the whole
 * wall's line at its place. Viewports that do not fit are refused, and the
 * source keeps rendering the whole output without one.
 */
#include <stdlib.h>
#include <string.h>

#include "lx_scene_source.h"
#include "lx_test.h"
#include "scene_json.h"

enum { WALL_W = 192, WALL_H = 108, BW = 96, BH = 54 };

static void board(const cs_scene *scene, float t, int bx, int by, const float *whole)
{
    lx_scene_source src;
    CHECK(lx_scene_source_init(&src, BW, BH, CS_AA_SUBSCAN, 16) == LX_OK, "init");
    CHECK(lx_scene_source_viewport(&src, WALL_W, WALL_H, bx, by) == LX_OK, "viewport %d,%d", bx, by);
    lx_scene_source_set(&src, scene, t);
    CHECK(src.src.begin(src.src.user, 2) == LX_OK, "begin");
    float line[3 * BW];
    int bad = 0;
    for (int y = 0; y < BH / 2; y++) {
        for (int lane = 0; lane < 2; lane++) {
            int row = y + lane * BH / 2;
            lx_status s = src.src.line(src.src.user, lane, row, line);
            const float *want = whole + ((size_t)(by + row) * WALL_W + (size_t)bx) * 3;
            if (s != LX_OK || memcmp(line, want, sizeof line) != 0)
                bad++;
        }
    }
    CHECK(bad == 0, "board at %d,%d, t=%g: %d of %d panel lines differ from the wall's", bx, by,
          (double)t, bad, BH);
    lx_scene_source_free(&src);
}

int main(void)
{
    cs_scene *scene = calloc(1, sizeof *scene);
    cs_workspace *ws = calloc(1, sizeof *ws);
    float *whole = malloc(sizeof(float) * 3 * WALL_W * WALL_H);
    char err[SCENE_JSON_ERRLEN];
    if (!scene || !ws || !whole || scene_json_load("scenes/motion.json", scene, err, sizeof err)) {
        fprintf(stderr, "test_wall: cannot load scenes/motion.json: %s\n", err);
        return 1;
    }
    static const float times[] = {0.4f, 1.7f};
    for (size_t k = 0; k < sizeof times / sizeof times[0]; k++) {
        cs_render_opts o = cs_render_defaults(WALL_W, WALL_H);
        o.time = times[k];
        cs_renderer r;
        cs_error e;
        CHECK(cs_frame_begin(&r, ws, scene, &o, &e) == CS_OK, "whole frame");
        for (int y = 0; y < WALL_H; y++)
            cs_render_line(&r, y, whole + (size_t)y * WALL_W * 3);
        for (int by = 0; by < WALL_H; by += BH)
            for (int bx = 0; bx < WALL_W; bx += BW)
                board(scene, times[k], bx, by, whole);
    }
    lx_scene_source src;
    CHECK(lx_scene_source_init(&src, BW, BH, CS_AA_SUBSCAN, 16) == LX_OK, "init");
    CHECK(lx_scene_source_viewport(&src, WALL_W, WALL_H, WALL_W - BW + 1, 0) == LX_ERR_CONFIG,
          "a viewport past the wall's right edge");
    CHECK(lx_scene_source_viewport(&src, WALL_W, WALL_H, 0, -1) == LX_ERR_CONFIG, "negative y");
    CHECK(lx_scene_source_viewport(&src, BW - 1, BH, 0, 0) == LX_ERR_CONFIG,
          "a wall narrower than the board");
    lx_scene_source_free(&src);
    free(scene);
    free(ws);
    free(whole);
    return lx_test_report("test_wall");
}
