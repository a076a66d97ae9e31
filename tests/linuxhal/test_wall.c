/*
 * test_wall.c - celfw's board of a video wall, in process and as four real
 * boards.
 *
 * In process: the scene source with a viewport (lx_scene_source_viewport)
 * against the core's whole render. A 2x2 wall of 96x54 boards (a 192x108
 * wall; the panel rows count from the board's own top) at two instants of
 * scenes/motion.json, two lanes as a HUB75 panel pulls them (top half in
 * lane 0, bottom half in lane 1): every line a board's display asks for must
 * be, float for float, the whole wall's line at its place. Viewports that do
 * not fit are refused, and the source keeps rendering the whole output
 * without one. Damage (issue 27) composes with the viewport: each board of
 * the wall, showing board-anim.json frame after frame on a display that keeps
 * its picture, renders only the wall's damage within its viewport, and its
 * picture is every frame its part of the whole wall's render.
 *
 * Four boards (issue 24: "four celfw instances sampling one instant with
 * --clock realtime and a fixed clock produce the tiles of the same frame"):
 * four celfw processes at once, each under the umockdev preload with its own
 * emulated GUD display (a 160x90 panel at its own bus and VID:PID), each
 * with --wall 320x180 and the --viewport of its quadrant, --clock at:T, and
 * the same stream: scenes/motion.json with an EPOCH record. Each panel must
 * be, bit for bit, its quadrant of the core's single render of the whole
 * wall at T - epoch in RGB565; a second instant gives other pixels, again
 * the tiles of one frame.
 */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "celfw_child.h"
#include "cels_write.h"
#include "fake_gud.h"
#include "lx_scene_source.h"
#include "scene_json.h"
#include "testlib.h"

enum { WALL_W = 192, WALL_H = 108, BW = 96, BH = 54 };

static void board(const cs_scene *scene, float t, int bx, int by, const float *whole)
{
    lx_scene_source src;
    CHECK(lx_scene_source_init(&src, BW, BH, CS_AA_SUBSCAN, 16) == HAL_OK, "init");
    CHECK(lx_scene_source_viewport(&src, WALL_W, WALL_H, bx, by) == HAL_OK, "viewport %d,%d", bx, by);
    lx_scene_source_set(&src, scene, t);
    CHECK(src.src.begin(src.src.user, 2) == HAL_OK, "begin");
    float line[3 * BW];
    int bad = 0;
    for (int y = 0; y < BH / 2; y++) {
        for (int lane = 0; lane < 2; lane++) {
            int row = y + lane * BH / 2;
            hal_status s = src.src.line(src.src.user, lane, row, line);
            const float *want = whole + ((size_t)(by + row) * WALL_W + (size_t)bx) * 3;
            if (s != HAL_OK || memcmp(line, want, sizeof line) != 0)
                bad++;
        }
    }
    CHECK(bad == 0, "board at %d,%d, t=%g: %d of %d panel lines differ from the wall's", bx, by,
          (double)t, bad, BH);
    lx_scene_source_free(&src);
}

/* The four boards' wall and tiles; the stream's epoch, ns since 1970. */
enum { FW_WALL_W = 320, FW_WALL_H = 180, FW_TILE_W = 160, FW_TILE_H = 90 };
#define FW_EPOCH_NS (1795000000ull * 1000000000ull)

/*
 * Runs the four boards at the wall-clock instant `at` (celfw's --clock
 * at:SECONDS text) on the stream in `spec`, and checks each panel against
 * its quadrant of the whole wall at animation time t. Returns the wall's
 * RGB565 render (to free) so the caller can compare instants.
 */
/* A display that keeps its picture (RGB888) and takes windows. */
typedef struct memdisp {
    hal_display d;
    hal_window win;
    uint8_t px[BW * BH * 3];
} memdisp;

static hal_status mem_begin(hal_display *d, const hal_window *w)
{
    memdisp *m = (memdisp *)d;
    m->win = w ? *w : (hal_window){0, 0, BW, BH};
    return HAL_OK;
}

static hal_status mem_line(hal_display *d, int y, const uint8_t *px, size_t len)
{
    memdisp *m = (memdisp *)d;
    if (y < m->win.y0 || y >= m->win.y1 || len != 3u * (size_t)(m->win.x1 - m->win.x0))
        return HAL_ERR_SEQUENCE;
    memcpy(m->px + ((size_t)y * BW + (size_t)m->win.x0) * 3, px, len);
    return HAL_OK;
}

static const hal_display_api mem_api = {.name = "mem", .begin_frame = mem_begin, .line_out = mem_line};

/* The wall's whole render at t, as floats. */
static void render_wall(const cs_scene *scene, cs_workspace *ws, float t, float *whole)
{
    cs_render_opts o = cs_render_defaults(WALL_W, WALL_H);
    o.time = t;
    cs_renderer r;
    cs_error e;
    CHECK(cs_frame_begin(&r, ws, scene, &o, &e) == CS_OK, "whole frame");
    for (int y = 0; y < WALL_H; y++)
        cs_render_line(&r, y, whole + (size_t)y * WALL_W * 3);
}

/*
 * The board at bx, by shows the scene for `frames` frames with damage
 * windows (on `threads` render threads): every frame its picture is its
 * part of the whole wall's render. Returns the lines it rendered.
 */
static uint64_t board_damage(const cs_scene *scene, cs_workspace *ws, float *whole, int bx, int by, int threads,
                             int frames)
{
    static memdisp m;
    static cs_damage dmg;
    memset(&m, 0, sizeof m);
    m.d.api = &mem_api;
    m.d.width = BW;
    m.d.height = BH;
    m.d.pixfmt = CS_PIX_RGB888_SRGB;
    cs_damage_reset(&dmg);
    lx_scene_source src;
    CHECK(lx_scene_source_init(&src, BW, BH, CS_AA_SUBSCAN, 16) == HAL_OK, "init");
    CHECK(lx_scene_source_viewport(&src, WALL_W, WALL_H, bx, by) == HAL_OK, "viewport %d,%d", bx, by);
    CHECK(lx_scene_source_threads(&src, threads) == HAL_OK, "%d threads", threads);
    uint64_t lines = 0;
    int wrong = 0, unbounded = 0;
    for (int k = 0; k < frames; k++) {
        float t = 0.3f + (float)k * 0.05f;
        lx_scene_source_set(&src, scene, t);
        hal_window w = lx_scene_source_damage(&src, &dmg);
        hal_frame_stats st = {0};
        hal_status s = hal_display_present_window(&m.d, &src.src, &w, &st);
        lx_scene_source_end(&src);
        CHECK(s == HAL_OK, "board %d,%d frame %d: %s", bx, by, k, m.d.err);
        if (st.lines_rendered != (uint64_t)(w.x1 > w.x0 ? w.y1 - w.y0 : 0))
            unbounded++;
        lines += st.lines_rendered;
        render_wall(scene, ws, t, whole);
        uint8_t want[BW * 3];
        for (int y = 0; y < BH; y++) {
            hal_pixfmt_convert(CS_PIX_RGB888_SRGB, whole + ((size_t)(by + y) * WALL_W + (size_t)bx) * 3, BW, want);
            if (memcmp(want, m.px + (size_t)y * BW * 3, sizeof want) != 0) {
                if (wrong++ == 0)
                    fprintf(stderr, "  board %d,%d frame %d (window %d,%d..%d,%d): row %d differs\n", bx, by, k,
                            w.x0, w.y0, w.x1, w.y1, y);
                break;
            }
        }
    }
    CHECK(wrong == 0 && unbounded == 0,
          "board %d,%d with damage: %d frames differ from the wall's render, %d render beyond the window", bx, by,
          wrong, unbounded);
    lx_scene_source_free(&src);
    hal_display_close(&m.d);
    return lines;
}

static uint8_t *four_boards(fake_gud *dev[4], const cs_scene *scene, const char *spec, const char *at,
                            float t)
{
    child c[4];
    char view[4][40], usb[4][16], line[1024];
    /* Started one after another, each once the one before has its display
     * open; then all four run together. Started at the same moment, one
     * libusb_init failed with LIBUSB_ERROR_OTHER in about a dozen runs:
     * presumably the umockdev preload, which emulates libusb's uevent
     * socket at a path in the shared testbed named by its fd number
     * ("%s/event%i"), so that processes opening it at once collide. */
    for (int i = 0; i < 4; i++) {
        snprintf(view[i], sizeof view[i], "%d,%d,%d,%d", i % 2 * FW_TILE_W, i / 2 * FW_TILE_H, FW_TILE_W,
                 FW_TILE_H);
        snprintf(usb[i], sizeof usb[i], "1d50:%04x", 0x7301 + i);
        spawn(&c[i],
              (const char *[]){"--backend", "usb", "--usb-device", usb[i], "--usb-format", "rgb565", "--wall",
                               "320x180", "--viewport", view[i], "--clock", at, "--scene", "none", "--input",
                               spec, "--fps", "50", "--log-interval", "0.05", NULL},
              false);
        CHECK(wait_line(&c[i], "celfw: start", 10.0, line, sizeof line) && strstr(line, "display=160x90"),
              "board %d (%s) starts on its own 160x90 panel: %s", i, view[i], c[i].log);
    }
    /* A status line after the commit, then one at least two frames later: a
     * whole frame was drawn after the commit (and every frame after it shows
     * the same instant). */
    for (int i = 0; i < 4; i++) {
        bool ok = wait_line(&c[i], "stream commit 1 applied", 10.0, line, sizeof line) &&
                  wait_line(&c[i], "celfw: status", 5.0, line, sizeof line);
        unsigned long long f0 = ok ? field(line, "frames") : 0;
        while (ok && field(line, "frames") < f0 + 2)
            ok = wait_line(&c[i], "celfw: status", 5.0, line, sizeof line);
        CHECK(ok, "board %d (%s) commits the stream and draws frames after it: %s", i, view[i], c[i].log);
    }
    uint8_t *want = render_panel_rgb565(scene, t, FW_WALL_W, FW_WALL_H);
    CHECK(want != NULL, "the whole wall renders at t=%g", (double)t);
    for (int i = 0; i < 4; i++) {
        kill(c[i].pid, SIGTERM);
        int rc = wait_exit(&c[i], 10.0);
        const char *ex = strstr(c[i].log, "celfw: exit");
        const char *tt = ex ? strstr(ex, "anim_t=") : NULL;
        CHECK(rc == 0 && ex && field(ex, "commits") == 1 && field(ex, "errors") == 0 && tt &&
                  strtof(tt + 7, NULL) == t,
              "board %d: clean exit, one commit, frames at t=%g: rc %d, %s", i, (double)t, rc, ex ? ex : c[i].log);
        int bad = compare_panel_tile(dev[i], want, FW_WALL_W, i % 2 * FW_TILE_W, i / 2 * FW_TILE_H, FW_TILE_W,
                                     FW_TILE_H);
        CHECK(bad == 0, "board %d (viewport %s), --clock %s: %d of %d pixels differ from the wall's frame at t=%g", i,
              view[i], at, bad, FW_TILE_W * FW_TILE_H, (double)t);
    }
    return want;
}

static void test_four_boards(UMockdevTestbed *tb)
{
    static cs_scene motion;
    char err[SCENE_JSON_ERRLEN];
    int rc = scene_json_load("scenes/motion.json", &motion, err, sizeof err);
    CHECK(rc == 0, "scenes/motion.json: %s", err);
    if (rc != 0)
        return;
    CHECK(cs_scene_set_epoch(&motion, FW_EPOCH_NS) == CS_OK, "epoch");
    cels_buf b;
    cels_buf_init(&b);
    cels_stream_header(&b);
    cels_encode_scene(&b, &motion);
    char path[] = "/tmp/test_wall-XXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0 && write(fd, b.data, b.len) == (ssize_t)b.len, "write the stream to %s", path);
    if (fd >= 0)
        close(fd);
    char spec[64];
    snprintf(spec, sizeof spec, "file:%s", path);

    fake_gud *dev[4];
    for (int i = 0; i < 4; i++) {
        fake_gud_opts o;
        fake_gud_opts_default(&o);
        o.pid = (uint16_t)(0x7301 + i);
        o.width = FW_TILE_W;
        o.height = FW_TILE_H;
        dev[i] = fake_gud_add(tb, 50 + i, 2, &o);
    }
    /* Instants whose distance from the epoch is exact in ns and in float. */
    uint8_t *a = four_boards(dev, &motion, spec, "at:1795000000.5", 0.5f);
    uint8_t *z = four_boards(dev, &motion, spec, "at:1795000002", 2.0f);
    int moved = 0;
    for (size_t i = 0; a && z && i < (size_t)FW_WALL_W * FW_WALL_H; i++)
        moved += memcmp(a + 2 * i, z + 2 * i, 2) != 0;
    CHECK(moved > FW_WALL_W * FW_WALL_H / 10, "the two instants differ: %d of %d pixels", moved,
          FW_WALL_W * FW_WALL_H);
    fprintf(stderr, "  four boards: 2x2 of 160x90 at t=0.5 and t=2 (%d pixels apart), each panel its quadrant\n",
            moved);
    free(a);
    free(z);
    for (int i = 0; i < 4; i++) {
        fake_gud_unplug(dev[i]);
        fake_gud_free(dev[i]);
    }
    unlink(path);
    cels_buf_free(&b);
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
    enum { FRAMES = 16 };
    uint64_t lines = 0;
    if (scene_json_load("scenes/board-anim.json", scene, err, sizeof err)) {
        fprintf(stderr, "test_wall: cannot load scenes/board-anim.json: %s\n", err);
        return 1;
    }
    for (int by = 0; by < WALL_H; by += BH)
        for (int bx = 0; bx < WALL_W; bx += BW)
            lines += board_damage(scene, ws, whole, bx, by, bx ? 2 : 1, FRAMES);
    fprintf(stderr, "  wall boards with damage: %.1f of %d lines rendered a frame\n", (double)lines / (4 * FRAMES),
            BH);
    CHECK(lines < (uint64_t)4 * FRAMES * BH, "damage renders fewer lines than whole frames (%llu of %d)",
          (unsigned long long)lines, 4 * FRAMES * BH);
    lx_scene_source src;
    CHECK(lx_scene_source_init(&src, BW, BH, CS_AA_SUBSCAN, 16) == HAL_OK, "init");
    CHECK(lx_scene_source_viewport(&src, WALL_W, WALL_H, WALL_W - BW + 1, 0) == HAL_ERR_CONFIG,
          "a viewport past the wall's right edge");
    CHECK(lx_scene_source_viewport(&src, WALL_W, WALL_H, 0, -1) == HAL_ERR_CONFIG, "negative y");
    CHECK(lx_scene_source_viewport(&src, BW - 1, BH, 0, 0) == HAL_ERR_CONFIG,
          "a wall narrower than the board");
    lx_scene_source_free(&src);
    free(scene);
    free(ws);
    free(whole);

    UMockdevTestbed *tb = umockdev_testbed_new();
    if (!umockdev_in_mock_environment() || access(celfw_child_path(), X_OK) != 0) {
        fprintf(stderr, "test_wall: the four boards need umockdev-wrapper and %s (set CELFW)\n",
                celfw_child_path());
        return 2;
    }
    char *root = umockdev_testbed_get_root_dir(tb);
    char path[600];
    snprintf(path, sizeof path, "%s/dev/bus/usb", root); /* libusb wants it before any device */
    g_mkdir_with_parents(path, 0755);
    g_free(root);
    test_four_boards(tb);
    g_object_unref(tb);
    return tl_summary("test_wall");
}
