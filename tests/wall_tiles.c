/*
 * wall_tiles.c - video walls: a viewport renders its window of the whole
 * output with the bits the whole render gives it.
 *
 *   wall_tiles SCENES_DIR
 *
 * The truth is the single render of the whole wall (cs_render_opts without a
 * viewport, the code path every other test holds to its references). Each
 * wall is cut into tiles, each tile rendered alone through its viewport as a
 * board would, and every line of every tile must equal the whole render's
 * part of that line float for float (memcmp of the linear floats, so no
 * rounding to 8 bits hides a difference):
 *   - a 2x2 wall and a 3x1 wall whose widths and heights do not divide
 *     evenly (tiles of 213, 214 and 214 columns), in every AA mode (none,
 *     4 and 16 sub-scanlines, exact), at several instants of the animated
 *     scenes/motion.json and of the demo, and every other scene of the
 *     folder once;
 *   - cs_render_frame hands a viewport's lines to the sink counted from the
 *     window's top, view_w wide;
 *   - a wall wider than a line may be (CS_CFG_MAX_WIDTH), which has no
 *     whole render to compare with, renders through viewports, and two
 *     overlapping windows of it agree float for float on their overlap;
 *   - viewports outside the output, empty or wider than a line are refused
 *     with CS_ERR_SIZE, lines outside the window with CS_ERR_ARG, and a
 *     pre-combination cache with a viewport is refused.
 * --aa N for N not a power of two is left out on purpose: the running
 * coverage of a line is then a sum of multiples of 1/N that rounds, and a
 * window starts that sum at its own left edge (cs_coverage.c, add_span).
 * The last line is `wall_tiles: N passed, M failed`.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celscan_private.h"
#include "scene_json.h"
#include "testlib.h"

static cs_workspace *ws;
static cs_scene *scene;
static const char *dir;

typedef struct aa_case {
    const char *name;
    cs_aa_mode aa;
    int sub;
} aa_case;

static const aa_case AA[] = {
    {"none", CS_AA_NONE, 1}, {"4", CS_AA_SUBSCAN, 4}, {"16", CS_AA_SUBSCAN, 16},
    {"exact", CS_AA_EXACT, 1}};

static cs_render_opts opts(int w, int h, const aa_case *a, float t)
{
    cs_render_opts o = cs_render_defaults(w, h);
    o.aa = a->aa;
    o.subscanlines = a->sub;
    o.time = t;
    return o;
}

static bool load(const char *name)
{
    char path[512], err[SCENE_JSON_ERRLEN];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (scene_json_load(path, scene, err, sizeof err) != 0) {
        CHECK(false, "%s: %s", path, err);
        return false;
    }
    return true;
}

/* The whole wall, w*h*3 linear floats. */
static bool render_whole(const cs_render_opts *o, float *out)
{
    cs_renderer r;
    cs_error e;
    if (cs_frame_begin(&r, ws, scene, o, &e) != CS_OK)
        return false;
    for (int y = 0; y < o->height; y++)
        if (cs_render_line(&r, y, out + (size_t)y * (size_t)o->width * 3) != CS_OK)
            return false;
    return true;
}

/*
 * Tiles cut at columns xs[0..nx] and rows ys[0..ny], each rendered through
 * its viewport and compared with the whole render. Returns the number of
 * lines that differ (0 expected); the first is described.
 */
static int compare_tiles(const char *what, const cs_render_opts *whole_o, const float *whole,
                         const int *xs, int nx, const int *ys, int ny)
{
    float *line = malloc(sizeof(float) * 3 * (size_t)whole_o->width);
    int bad = 0;
    for (int ty = 0; ty < ny; ty++) {
        for (int tx = 0; tx < nx; tx++) {
            cs_render_opts o = *whole_o;
            o.view_x = xs[tx];
            o.view_y = ys[ty];
            o.view_w = xs[tx + 1] - xs[tx];
            o.view_h = ys[ty + 1] - ys[ty];
            cs_renderer r;
            cs_error e;
            cs_status st = cs_frame_begin(&r, ws, scene, &o, &e);
            if (!CHECK(st == CS_OK, "%s: tile %d,%d: frame refused: %s", what, tx, ty,
                       cs_status_str(st)))
                continue;
            for (int y = o.view_y; y < o.view_y + o.view_h; y++) {
                st = cs_render_line(&r, y, line);
                const float *want = whole + ((size_t)y * (size_t)whole_o->width + (size_t)o.view_x) * 3;
                if (st != CS_OK || memcmp(line, want, sizeof(float) * 3 * (size_t)o.view_w) != 0) {
                    if (bad == 0) {
                        int x = 0;
                        while (x < o.view_w * 3 && line[x] == want[x])
                            x++;
                        tl_note("%s: tile at %d,%d (%dx%d), row %d: first difference at column "
                                "%d: %.9g, whole %.9g (%s)", what, o.view_x, o.view_y, o.view_w,
                                o.view_h, y, o.view_x + x / 3, x < o.view_w * 3 ? line[x] : 0.0,
                                x < o.view_w * 3 ? want[x] : 0.0, cs_status_str(st));
                    }
                    bad++;
                }
            }
        }
    }
    free(line);
    return bad;
}

/* Every AA mode, the 2x2 and the 3x1 wall of one scene at time t. */
static void walls(const char *name, float t)
{
    static const int W = 641, H = 363;
    static const int x22[] = {0, 320, 641}, y22[] = {0, 181, 363};
    static const int x31[] = {0, 213, 427, 641}, y31[] = {0, 363};
    float *whole = malloc(sizeof(float) * 3 * (size_t)W * (size_t)H);
    for (size_t k = 0; k < sizeof AA / sizeof AA[0]; k++) {
        cs_render_opts o = opts(W, H, &AA[k], t);
        char what[160];
        snprintf(what, sizeof what, "%s at t=%g, --aa %s", name, (double)t, AA[k].name);
        if (!CHECK(render_whole(&o, whole), "%s: the whole render failed", what))
            continue;
        int bad = compare_tiles(what, &o, whole, x22, 2, y22, 2);
        CHECK(bad == 0, "%s: 2x2 wall: %d tile lines differ from the whole render", what, bad);
        bad = compare_tiles(what, &o, whole, x31, 3, y31, 1);
        CHECK(bad == 0, "%s: 3x1 wall: %d tile lines differ from the whole render", what, bad);
    }
    free(whole);
}

static void test_motion_and_demo(void)
{
    static const float motion_t[] = {0.0f, 0.35f, 1.1f, 2.7f};
    if (load("motion.json"))
        for (size_t k = 0; k < sizeof motion_t / sizeof motion_t[0]; k++)
            walls("motion.json", motion_t[k]);
    static const float demo_t[] = {0.0f, 1.25f};
    if (load("demo.json"))
        for (size_t k = 0; k < sizeof demo_t / sizeof demo_t[0]; k++)
            walls("demo.json", demo_t[k]);
}

static void test_other_scenes(void)
{
    static const char *const names[] = {"beta-csg.json", "beta-stack.json", "demo-board.json",
                                        "sign.json"};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
        if (load(names[k]))
            walls(names[k], 0.5f);
}

/* cs_render_frame: the sink's rows count from the window's top. */
typedef struct sink_log {
    int calls, first_y, last_y, width;
} sink_log;

static cs_status log_sink(void *user, int y, const float *rgb, int width)
{
    (void)rgb;
    sink_log *l = user;
    if (l->calls++ == 0)
        l->first_y = y;
    l->last_y = y;
    l->width = width;
    return CS_OK;
}

static void test_frame_sink(void)
{
    if (!load("motion.json"))
        return;
    cs_render_opts o = opts(400, 300, &AA[2], 0.0f);
    o.view_x = 100;
    o.view_y = 50;
    o.view_w = 120;
    o.view_h = 70;
    cs_renderer r;
    cs_error e;
    float line[3 * 120];
    sink_log l = {0, -1, -1, 0};
    CHECK_STATUS(cs_frame_begin(&r, ws, scene, &o, &e), CS_OK, "viewport frame");
    CHECK_STATUS(cs_render_frame(&r, line, log_sink, &l), CS_OK, "cs_render_frame");
    CHECK(l.calls == 70 && l.first_y == 0 && l.last_y == 69 && l.width == 120,
          "sink: expected 70 lines 0..69 of 120 px, got %d lines %d..%d of %d px", l.calls,
          l.first_y, l.last_y, l.width);
    CHECK_STATUS(cs_render_line(&r, 49, line), CS_ERR_ARG, "a line above the window");
    CHECK_STATUS(cs_render_line(&r, 120, line), CS_ERR_ARG, "a line below the window");
}

/* A wall wider than a line: two overlapping windows agree where they overlap. */
static void test_wide_wall(void)
{
    if (!load("demo.json"))
        return;
    int W = CS_CFG_MAX_WIDTH + 1904, H = 90; /* 6000 x 90 with the default configuration */
    cs_render_opts o = opts(W, H, &AA[3], 0.5f);
    int vw = 1000;
    float *a = malloc(sizeof(float) * 3 * (size_t)vw), *b = malloc(sizeof(float) * 3 * (size_t)vw);
    cs_renderer ra, rb;
    cs_error e;
    cs_render_opts oa = o, ob = o;
    oa.view_x = W - 1600;
    ob.view_x = W - 1100; /* overlaps oa's last 500 columns */
    oa.view_w = ob.view_w = vw;
    oa.view_y = ob.view_y = 0;
    oa.view_h = ob.view_h = H;
    int bad = 0;
    cs_status sa = cs_frame_begin(&ra, ws, scene, &oa, &e);
    CHECK(sa == CS_OK, "6000-wide wall: viewport refused: %s", cs_status_str(sa));
    float *rows = malloc(sizeof(float) * 3 * (size_t)vw * (size_t)H);
    for (int y = 0; y < H && sa == CS_OK; y++) {
        cs_render_line(&ra, y, a);
        memcpy(rows + (size_t)y * (size_t)vw * 3, a, sizeof(float) * 3 * (size_t)vw);
    }
    cs_status sb = cs_frame_begin(&rb, ws, scene, &ob, &e);
    CHECK(sb == CS_OK, "6000-wide wall: second viewport refused: %s", cs_status_str(sb));
    bool any_paint = false;
    for (int y = 0; y < H && sa == CS_OK && sb == CS_OK; y++) {
        cs_render_line(&rb, y, b);
        const float *ra_row = rows + (size_t)y * (size_t)vw * 3 + 500 * 3;
        if (memcmp(ra_row, b, sizeof(float) * 3 * 500) != 0)
            bad++;
        for (int x = 0; x < 500 * 3; x++)
            any_paint = any_paint || b[x] != b[0];
    }
    CHECK(bad == 0, "6000-wide wall: %d rows differ on the overlap of two viewports", bad);
    CHECK(any_paint, "6000-wide wall: the overlap shows nothing but one colour");
    free(a);
    free(b);
    free(rows);
}

static void test_refusals(void)
{
    if (!load("motion.json"))
        return;
    cs_renderer r;
    cs_error e;
    static const struct {
        int w, h, x, y, vw, vh;
        const char *what;
    } bad[] = {
        {400, 300, 300, 0, 101, 10, "past the right edge"},
        {400, 300, 0, 250, 10, 51, "past the bottom"},
        {400, 300, -1, 0, 10, 10, "negative x"},
        {400, 300, 0, 0, 0, 10, "zero width"},
        {400, 300, 0, 0, 10, 0, "zero height"},
        {CS_CFG_MAX_WIDTH + 10, 300, 0, 0, CS_CFG_MAX_WIDTH + 1, 10, "wider than a line"},
        {CS_CFG_MAX_WALL + 1, 300, 0, 0, 10, 10, "a wall beyond CS_CFG_MAX_WALL"},
        {CS_CFG_MAX_WIDTH + 1, 300, 0, 0, 0, 0, "no viewport, wider than a line"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        cs_render_opts o = opts(bad[k].w, bad[k].h, &AA[1], 0.0f);
        o.view_x = bad[k].x;
        o.view_y = bad[k].y;
        o.view_w = bad[k].vw;
        o.view_h = bad[k].vh;
        CHECK_STATUS(cs_frame_begin(&r, ws, scene, &o, &e), CS_ERR_SIZE, bad[k].what);
    }
#if CS_CFG_CACHE
    static unsigned char buf[1 << 16];
    cs_cache cache;
    cs_render_opts o = opts(100, 50, &AA[1], 0.0f);
    o.view_w = o.view_h = 10;
    CHECK_STATUS(cs_cache_build(&cache, buf, sizeof buf, ws, scene, &o, 0, 1, &e), CS_ERR_ARG,
                 "a cache for a viewport");
#endif
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: wall_tiles SCENES_DIR\n");
        return 2;
    }
    dir = argv[1];
    ws = calloc(1, sizeof *ws);
    scene = calloc(1, sizeof *scene);
    if (!ws || !scene)
        return 2;
    TL_RUN(test_motion_and_demo);
    TL_RUN(test_other_scenes);
    TL_RUN(test_frame_sink);
    TL_RUN(test_wide_wall);
    TL_RUN(test_refusals);
    free(ws);
    free(scene);
    return tl_summary("wall_tiles");
}
