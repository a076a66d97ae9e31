/*
 * test_display_conformance.c - the display conformance case for the
 * backends that need no emulated device: the simulator's display (hal/sim),
 * the null display (hal/host/null.c) and the template (hal/template), which
 * is what a new backend copies, so it must pass what every backend passes.
 *
 * The shared case (display_conformance.h) first proves its own truth: the
 * reference CRC of every conformance frame in the panel format equals what
 * the celsim program prints with --crc (the definition of a frame's CRC),
 * run as a separate process. Then each backend shows the frames through the
 * contract and must show exactly that; errors (a source of another size, a
 * line out of order, a bad window, a failed flush) come back as the same
 * hal_status with a "name: ..." message. Windows (frames that touch only
 * rows y0..y1 and columns x0..x1) change what is inside and nothing else.
 * The simulator lends its rows for rendering in place only where line_out
 * would take them next.
 * The GUD, DRM and HUB75 backends run the same case inside their emulated
 * device rigs (tests/linuxhal/test_gud.c, test_drm.c, test_hub75.c).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "testlib.h"

#include "display_conformance.h"
#include "display_template.h"
#include "sim/display_sim.h"

#define W 120
#define H 68

static const char *celsim = "build/host/celsim";

/* The reference equals `celsim render --crc` for every conformance frame, at two sizes. */
static void test_reference_is_celsim(void)
{
    static cs_scene scene;
    hal_pixfmt panel = CS_PANEL_PIXFMT;
    const int sizes[2][2] = {{W, H}, {97, 41}};
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < CONF_NFRAMES; i++) {
            const conf_frame *f = &conf_frame_list[i];
            int w = sizes[k][0], h = sizes[k][1];
            if (!conf_load(f->scene, &scene))
                continue;
            uint32_t want = conf_reference_crc(&scene, f->time, w, h, hal_line_bytes(panel, w),
                                               conf_encode_fmt, &panel);
            char cmd[512], line[128] = "";
            snprintf(cmd, sizeof cmd, "%s render %s --size %dx%d --time %g --aa %d --crc", celsim, f->scene, w,
                     h, (double)f->time, CONF_SUBSCANLINES);
            FILE *p = popen(cmd, "r");
            unsigned got = 0;
            bool read = p && fgets(line, sizeof line, p) && sscanf(line, "frame crc32 %x", &got) == 1;
            if (p)
                pclose(p);
            CHECK(read && got == want, "%s: celsim says %s, the reference %08X", cmd, line, (unsigned)want);
        }
}

static bool sim_shown(void *user, uint8_t *frame)
{
    sim_display *s = user;
    for (int y = 0; y < s->d.height; y++)
        memcpy(frame + (size_t)y * s->line_bytes, sim_display_row(s, y), s->line_bytes);
    return true;
}

static void test_sim(void)
{
    static const cs_pixfmt fmts[] = {CS_PIX_RGB565_SRGB, CS_PIX_RGB888_SRGB, CS_PIX_RGB16_LINEAR};
    for (size_t i = 0; i < sizeof fmts / sizeof fmts[0]; i++) {
        size_t n = sim_display_image_bytes(W, H, fmts[i]);
        uint8_t *img = malloc(n);
        sim_display s;
        if (!CHECK(sim_display_init(&s, W, H, fmts[i], img, n) == HAL_OK, "sim init: %s", s.d.err))
            continue;
        conf_backend b = {.d = &s.d, .shown = sim_shown, .user = &s};
        char name[32];
        snprintf(name, sizeof name, "sim format %d", (int)fmts[i]);
        conf_frames(&b, name);
        conf_geometry_error(&b, name);
        hal_display_close(&s.d);
        free(img);
    }
}

static void test_null(void)
{
    hal_display *d;
    if (!CHECK(hal_null_open(&d, W, H, &hal_clock_monotonic) == HAL_OK, "null open"))
        return;
    conf_backend b = {.d = d};
    conf_frames(&b, "null");
    conf_geometry_error(&b, "null");
    hal_display_close(d);
}

/* The template's frame buffer, with guard bytes after each row's pixels (pitch > line). */
typedef struct tpl_rig {
    tpl_config cfg;
    tpl_display t;
    int flush_fail; /* the next flushes that fail */
    int flushes;
    hal_window last;
} tpl_rig;

static bool tpl_flush(void *user, const hal_window *win)
{
    tpl_rig *r = user;
    r->flushes++;
    r->last = *win;
    if (r->flush_fail > 0) {
        r->flush_fail--;
        return false;
    }
    return true;
}

static bool tpl_shown(void *user, uint8_t *frame)
{
    tpl_rig *r = user;
    size_t lb = hal_line_bytes(r->cfg.pixfmt, r->cfg.width);
    for (int y = 0; y < r->cfg.height; y++)
        memcpy(frame + (size_t)y * lb, r->cfg.fb + (size_t)y * r->cfg.pitch, lb);
    return true;
}

static bool tpl_rig_open(tpl_rig *r, hal_pixfmt fmt)
{
    memset(r, 0, sizeof *r);
    size_t lb = hal_line_bytes(fmt, W);
    r->cfg = (tpl_config){W, H, fmt, malloc((lb + 16u) * H), lb + 16u, tpl_flush, r};
    memset(r->cfg.fb, 0xA5, (lb + 16u) * H);
    return CHECK(tpl_open(&r->t, &r->cfg, &hal_clock_monotonic) == HAL_OK, "template open: %s", r->t.d.err);
}

/* Bytes of the template's guard areas (after each row's pixels) still 0xA5. */
static bool guards_intact(const tpl_rig *r)
{
    size_t lb = hal_line_bytes(r->cfg.pixfmt, r->cfg.width);
    for (int y = 0; y < r->cfg.height; y++)
        for (size_t i = lb; i < r->cfg.pitch; i++)
            if (r->cfg.fb[(size_t)y * r->cfg.pitch + i] != 0xA5)
                return false;
    return true;
}

static void test_template(void)
{
    static const hal_pixfmt fmts[] = {HAL_PIX_XRGB8888, CS_PIX_RGB565_SRGB, CS_PIX_RGB332_SRGB};
    for (size_t i = 0; i < sizeof fmts / sizeof fmts[0]; i++) {
        tpl_rig r;
        if (!tpl_rig_open(&r, fmts[i]))
            continue;
        conf_backend b = {.d = &r.t.d, .shown = tpl_shown, .user = &r};
        char name[32];
        snprintf(name, sizeof name, "template format 0x%x", (unsigned)fmts[i]);
        conf_frames(&b, name);
        conf_geometry_error(&b, name);
        CHECK(r.flushes == CONF_NFRAMES && r.last.y1 == H && guards_intact(&r),
              "%s: a whole-frame flush per frame (%d), guards intact", name, r.flushes);
        hal_display_close(&r.t.d);
        free(r.cfg.fb);
    }
}

static void tpl_fail_flush(void *user)
{
    ((tpl_rig *)user)->flush_fail = 1;
}

/* A failed write (the flush) is HAL_ERR_IO through the frame driver, and the next frame goes. */
static void test_failed_write(void)
{
    tpl_rig r;
    if (!tpl_rig_open(&r, CS_PANEL_PIXFMT))
        return;
    conf_backend b = {.d = &r.t.d, .shown = tpl_shown, .user = &r};
    conf_failed_write(&b, "template", tpl_fail_flush, "flushing rows 0..67 failed");
    hal_display_close(&r.t.d);
    free(r.cfg.fb);
}

/* Out-of-order calls: the same HAL_ERR_SEQUENCE from every strict backend. */
/* The two push displays that need no device, in the panel format: the simulator and the template. */
typedef struct push_pair {
    sim_display s;
    tpl_rig r;
    uint8_t *img;
} push_pair;

static bool push_pair_open(push_pair *p)
{
    size_t n = sim_display_image_bytes(W, H, CS_PANEL_PIXFMT);
    p->img = malloc(n);
    if (!CHECK(sim_display_init(&p->s, W, H, CS_PANEL_PIXFMT, p->img, n) == HAL_OK, "sim init") ||
        !tpl_rig_open(&p->r, CS_PANEL_PIXFMT)) {
        free(p->img);
        return false;
    }
    return true;
}

static void push_pair_close(push_pair *p)
{
    free(p->img);
    free(p->r.cfg.fb);
}

static void test_sequence_errors(void)
{
    uint8_t line[W * 4] = {0};
    push_pair p;
    if (!push_pair_open(&p))
        return;
    hal_display *ds[2] = {&p.s.d, &p.r.t.d};
    size_t lb = hal_line_bytes(CS_PANEL_PIXFMT, W);
    for (int i = 0; i < 2; i++) {
        hal_display *d = ds[i];
        hal_status st = hal_display_begin_frame(d, NULL);
        CHECK(st == HAL_OK, "%s: begin", d->api->name);
        st = hal_display_line_out(d, 5, line, lb);
        CHECK(st == HAL_OK, "%s: line 5", d->api->name);
        st = hal_display_line_out(d, 5, line, lb);
        CHECK(conf_error_is(d, st, HAL_ERR_SEQUENCE, "line 5"), "%s: line 5 twice: %s: %s", d->api->name,
              hal_status_str(st), d->err);
        st = hal_display_line_out(d, H, line, lb);
        CHECK(st != HAL_OK && conf_error_is(d, st, st, "line 68"), "%s: line %d past the end: %s: %s",
              d->api->name, H, hal_status_str(st), d->err);
        hal_window bad = {0, 10, W + 1, 20};
        hal_display_end_frame(d);
        st = hal_display_begin_frame(d, &bad);
        CHECK(conf_error_is(d, st, HAL_ERR_CONFIG, "not inside"), "%s: window wider than the display: %s: %s",
              d->api->name, hal_status_str(st), d->err);
    }
    push_pair_close(&p);
}

/*
 * An abandoned frame (begin_frame again without end_frame, as after a failed
 * line) does not stop the display: the next frame begins and shows the
 * core's render. An empty window is a frame where nothing changed: taken,
 * no row may come, and the picture stays.
 */
static void test_abandon_and_empty(void)
{
    push_pair p;
    if (!push_pair_open(&p))
        return;
    conf_backend bs[2] = {{.d = &p.s.d, .shown = sim_shown, .user = &p.s},
                          {.d = &p.r.t.d, .shown = tpl_shown, .user = &p.r}};
    uint8_t line[W * 4] = {0};
    size_t lb = hal_line_bytes(CS_PANEL_PIXFMT, W);
    for (int i = 0; i < 2; i++) {
        hal_display *d = bs[i].d;
        CHECK(hal_display_begin_frame(d, NULL) == HAL_OK && hal_display_line_out(d, 0, line, lb) == HAL_OK,
              "%s: half a frame", d->api->name);
        conf_frames(&bs[i], d->api->name); /* begins again: the half frame is abandoned */
        size_t fb = lb * H;
        uint8_t *before = malloc(fb), *after = malloc(fb);
        bs[i].shown(bs[i].user, before);
        const hal_window empty = {3, 4, 3, 9};
        hal_status st = hal_display_begin_frame(d, &empty);
        CHECK(st == HAL_OK, "%s: an empty window refused: %s", d->api->name, d->err);
        st = hal_display_line_out(d, 4, line, 0);
        CHECK(st != HAL_OK, "%s: a row in an empty window taken", d->api->name);
        CHECK(hal_display_end_frame(d) == HAL_OK, "%s: end of an empty frame: %s", d->api->name, d->err);
        bs[i].shown(bs[i].user, after);
        CHECK(memcmp(before, after, fb) == 0, "%s: an empty window changed the picture", d->api->name);
        free(before);
        free(after);
    }
    push_pair_close(&p);
}

/*
 * The simulator lends its image's rows (display.h's line_buffer) only where
 * line_out would take them next: inside a frame and its window, not behind a
 * row sent (rows ahead too: threads fill them out of order), at the window's
 * length. A row written in place and handed back
 * to line_out is shown as written, and nothing outside the window moves.
 */
static void test_sim_line_buffer(void)
{
    size_t n = sim_display_image_bytes(W, H, CS_PIX_RGB888_SRGB);
    uint8_t *img = malloc(n);
    sim_display s;
    if (!CHECK(sim_display_init(&s, W, H, CS_PIX_RGB888_SRGB, img, n) == HAL_OK, "sim init: %s", s.d.err)) {
        free(img);
        return;
    }
    hal_display *d = &s.d;
    const hal_window win = {10, 20, 50, 30};
    size_t lw = hal_line_bytes(d->pixfmt, win.x1 - win.x0);
    CHECK(hal_display_line_buffer(d, 20, lw) == NULL, "a row lent outside a frame");
    CHECK(hal_display_begin_frame(d, &win) == HAL_OK, "begin a window: %s", d->err);
    CHECK(hal_display_line_buffer(d, 19, lw) == NULL, "row 19, above the window, lent");
    CHECK(hal_display_line_buffer(d, 30, lw) == NULL, "row 30, below the window, lent");
    CHECK(hal_display_line_buffer(d, 20, lw + 3) == NULL, "a row of another length lent");
    CHECK(hal_display_line_buffer(d, 29, lw) == img + 29 * s.line_bytes + 3u * (size_t)win.x0,
          "the window's last row not lent ahead of the others (threads fill rows out of order)");
    for (int y = win.y0; y < win.y1; y++) {
        uint8_t *row = hal_display_line_buffer(d, y, lw);
        if (!CHECK(row == img + (size_t)y * s.line_bytes + 3u * (size_t)win.x0, "row %d lent elsewhere", y))
            break;
        memset(row, 0x40 + y, lw);
        CHECK(hal_display_line_out(d, y, row, lw) == HAL_OK, "row %d handed back: %s", y, d->err);
        CHECK(hal_display_line_buffer(d, y, lw) == NULL, "row %d lent again after it was sent", y);
    }
    CHECK(hal_display_end_frame(d) == HAL_OK, "end of the window: %s", d->err);
    CHECK(hal_display_line_buffer(d, 25, lw) == NULL, "a row lent after the frame");
    long bad = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < 3 * W; x++) {
            bool in = y >= win.y0 && y < win.y1 && x / 3 >= win.x0 && x / 3 < win.x1;
            bad += img[(size_t)y * s.line_bytes + (size_t)x] != (in ? 0x40 + y : 0);
        }
    CHECK(bad == 0, "%ld bytes of the picture are not what was written in place", bad);
    const hal_window empty = {3, 4, 3, 9};
    CHECK(hal_display_begin_frame(d, &empty) == HAL_OK && hal_display_line_buffer(d, 4, 0) == NULL,
          "a row lent in an empty window");
    hal_display_end_frame(d);
    free(img);
}

/* A windowed frame changes its window and nothing else, and is flushed as that window. */
static void test_window(void)
{
    tpl_rig r;
    if (!tpl_rig_open(&r, CS_PANEL_PIXFMT))
        return;
    conf_backend b = {.d = &r.t.d, .shown = tpl_shown, .user = &r};
    int rows = conf_window(&b, "template", (hal_window){10, 20, 50, 30});
    CHECK(rows == 5 && guards_intact(&r) && r.last.y0 == 20 && r.last.y1 == 30 && r.last.x0 == 10 &&
              r.last.x1 == 50,
          "window 10,20..50,30: %d rows, flushed %d,%d..%d,%d", rows, r.last.x0, r.last.y0, r.last.x1, r.last.y1);
    hal_display_close(&r.t.d);
    free(r.cfg.fb);
}

/*
 * The allocation counter: the test is linked with -Wl,--wrap=malloc and
 * --wrap=calloc (mk/display.mk), so every allocation made by the program's
 * own code (the frame driver, the backends, the source, the core) passes here.
 */
void *__real_malloc(size_t n);
void *__real_calloc(size_t n, size_t size);
void *__wrap_malloc(size_t n);
void *__wrap_calloc(size_t n, size_t size);
static long allocations;

void *__wrap_malloc(size_t n)
{
    allocations++;
    return __real_malloc(n);
}

void *__wrap_calloc(size_t n, size_t size)
{
    allocations++;
    return __real_calloc(n, size);
}

/* After a display's first rendered frame, showing frames allocates nothing:
 * the push lane's line buffers are the display's (d->lines), made once, freed
 * by close, and not made at all for a frame in which nothing changed. */
static void test_no_allocation_per_frame(void)
{
    static cs_scene scene;
    if (!conf_load(conf_frame_list[0].scene, &scene))
        return;
    lx_scene_source src;
    TL_MUST(lx_scene_source_init(&src, W, H, CS_AA_SUBSCAN, CONF_SUBSCANLINES));
    tpl_rig r;
    hal_display *null = NULL;
    size_t n = sim_display_image_bytes(W, H, CS_PANEL_PIXFMT);
    uint8_t *img = malloc(n);
    sim_display sim;
    if (tpl_rig_open(&r, CS_PANEL_PIXFMT) &&
        CHECK(hal_null_open(&null, W, H, &hal_clock_monotonic) == HAL_OK, "null open") &&
        CHECK(sim_display_init(&sim, W, H, CS_PANEL_PIXFMT, img, n) == HAL_OK, "sim init")) {
        hal_display *ds[3] = {&r.t.d, null, &sim.d};
        for (int i = 0; i < 3; i++) {
            hal_frame_stats st = {0};
            hal_status s = HAL_OK;
            long before = allocations;
            const hal_window empty = {3, 4, 3, 9}; /* nothing changed: nothing to render into */
            s = hal_display_present_window(ds[i], &src.src, (hal_window[]){empty}, &st);
            CHECK(s == HAL_OK && allocations == before, "%s: an empty first frame made %ld allocations (%s: %s)",
                  ds[i]->api->name, allocations - before, hal_status_str(s), ds[i]->err);
            for (int k = 0; k < 4 && s == HAL_OK; k++) {
                if (k == 1)
                    before = allocations; /* the first frame made the buffers */
                lx_scene_source_set(&src, &scene, 0.5f * (float)k);
                s = hal_display_present(ds[i], &src.src, &st);
                lx_scene_source_end(&src);
            }
            long made = allocations - before;
            CHECK(s == HAL_OK && made == 0 && st.lines_rendered == 4u * H,
                  "%s: %ld allocations in frames 2..4 (%s: %s)", ds[i]->api->name, made, hal_status_str(s),
                  ds[i]->err);
        }
        hal_display_close(&sim.d);
        hal_display_close(&r.t.d);
    }
    hal_display_close(null);
    lx_scene_source_free(&src);
    free(img);
    free(r.cfg.fb);
}

int main(void)
{
    if (getenv("CELSIM"))
        celsim = getenv("CELSIM");
    TL_RUN(test_reference_is_celsim);
    TL_RUN(test_sim);
    TL_RUN(test_null);
    TL_RUN(test_template);
    TL_RUN(test_failed_write);
    TL_RUN(test_sequence_errors);
    TL_RUN(test_abandon_and_empty);
    TL_RUN(test_window);
    TL_RUN(test_sim_line_buffer);
    TL_RUN(test_no_allocation_per_frame);
    return tl_summary("test_display_conformance");
}
