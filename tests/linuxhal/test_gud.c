/*
 * test_gud.c - the USB (GUD) backend against an emulated USB display.
 *
 * Runs under umockdev: the real libusb enumerates the emulated device through
 * sysfs/udev and talks usbdevfs to fake_gud, which reassembles the
 * rectangles (LZ4-decoding them) into its panel memory. That memory must
 * equal the scene rendered directly with the core in this test and converted
 * to the negotiated format. Also: damage (only changed lines travel), stalls,
 * timeouts, refusals, unplug/replug, odd formats and missing devices; and
 * the display conformance case (display_conformance.h) in both formats.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "celfw_scenes.h"
#include "fake_gud.h"
#include "gud_host.h"
#include "gud_wire.h"
#include "lx_scene_source.h"
#include "testlib.h"

#include "display_conformance.h"

static cs_scene scene;
static int next_pid = 0x7000;

typedef struct rig {
    fake_gud_opts o;
    fake_gud *dev;
    gud_config cfg;
    hal_display *d;
    lx_scene_source src;
    int devnum;
} rig;

static int bus_no = 1;

static hal_status rig_open(rig *r, UMockdevTestbed *tb, char *err, size_t errlen)
{
    r->o.pid = (uint16_t)next_pid++;
    r->devnum = 2;
    r->dev = fake_gud_add(tb, bus_no++, r->devnum, &r->o);
    r->cfg.vid = r->o.vid;
    r->cfg.pid = r->o.pid;
    err[0] = 0;
    hal_status s = gud_open(&r->d, &r->cfg, &hal_clock_monotonic, conf_log, NULL, err, errlen);
    if (s == HAL_OK && lx_scene_source_init(&r->src, r->d->width, r->d->height, CS_AA_SUBSCAN, 4) != HAL_OK)
        s = HAL_ERR_NOMEM;
    return s;
}

static void rig_close(rig *r, bool opened)
{
    if (opened) {
        hal_display_close(r->d);
        lx_scene_source_free(&r->src);
    }
    fake_gud_unplug(r->dev);
    fake_gud_free(r->dev);
}

/* Presents the scene; returns the status and fills st. */
static hal_status show(rig *r, const cs_scene *s, hal_frame_stats *st)
{
    memset(st, 0, sizeof *st);
    lx_scene_source_set(&r->src, s, 0.0f);
    return hal_display_present(r->d, &r->src.src, st);
}

/* Compares the device's panel with the core's rendering at time t. Returns mismatching pixels. */
static int compare_at(rig *r, const cs_scene *s, float t)
{
    gud_info info;
    gud_get_info(r->d, &info);
    unsigned bpp = gud_format_bpp(info.format);
    size_t n = (size_t)info.width * (size_t)info.height * bpp;
    hal_pixfmt fmt = info.format == GUD_FORMAT_RGB565 ? CS_PIX_RGB565_SRGB : HAL_PIX_XRGB8888;
    uint8_t *got = malloc(n),
            *want = conf_reference_image(s, t, info.width, info.height, (size_t)info.width * bpp,
                                         conf_encode_fmt, &fmt);
    if (!want)
        abort(); /* out of memory or an unrenderable test scene: nothing to compare with */
    fake_gud_framebuffer(r->dev, got, n);
    int bad = 0;
    for (size_t i = 0; i < n; i += bpp)
        if (memcmp(got + i, want + i, bpp) != 0 && bad++ == 0)
            fprintf(stderr, "  first mismatch at pixel (%zu,%zu)\n", (i / bpp) % (size_t)info.width,
                    (i / bpp) / (size_t)info.width);
    free(got);
    free(want);
    return bad;
}

static int compare(rig *r, const cs_scene *s)
{
    return compare_at(r, s, 0.0f);
}

static void test_basic(UMockdevTestbed *tb)
{
    rig r = {0};
    fake_gud_opts_default(&r.o);
    gud_config_default(&r.cfg);
    char err[300];
    hal_status s = rig_open(&r, tb, err, sizeof err);
    CHECK(s == HAL_OK, "open: %s", err);
    if (s != HAL_OK)
        return rig_close(&r, false);
    gud_info info;
    gud_get_info(r.d, &info);
    CHECK(info.connected && info.format == GUD_FORMAT_RGB565 && info.lz4 && info.width == 320 &&
              info.height == 180,
          "negotiated %dx%d format 0x%02x lz4 %d", info.width, info.height, info.format, info.lz4);
    fake_gud_stats ds;
    fake_gud_get_stats(r.dev, &ds);
    CHECK(ds.committed && ds.controller_on && ds.display_on && ds.format == GUD_FORMAT_RGB565,
          "device state set: committed %d controller %d display %d", ds.committed, ds.controller_on,
          ds.display_on);

    celfw_scene_build("demo", &scene, 0.0f);
    hal_frame_stats st;
    s = show(&r, &scene, &st);
    CHECK(s == HAL_OK, "present: %s", r.d->err);
    CHECK(compare(&r, &scene) == 0, "demo frame on the panel equals the renderer's");
    CHECK(st.lines_sent == 180 && st.bytes_raw == 180u * 320u * 2u, "first frame sends every line (%llu)",
          (unsigned long long)st.lines_sent);
    CHECK(st.bytes_wire < st.bytes_raw / 2, "LZ4 halves the demo at least (%llu of %llu)",
          (unsigned long long)st.bytes_wire, (unsigned long long)st.bytes_raw);
    fake_gud_get_stats(r.dev, &ds);
    CHECK(ds.protocol_errors == 0 && ds.bulk_bytes == st.bytes_wire && ds.raw_bytes == st.bytes_raw,
          "device saw %llu bulk bytes, %u protocol errors", (unsigned long long)ds.bulk_bytes,
          ds.protocol_errors);

    fake_gud_clear_log(r.dev);
    s = show(&r, &scene, &st);
    CHECK(s == HAL_OK && st.rects == 0 && st.lines_sent == 0 && fake_gud_rects(r.dev, NULL, 0) == 0,
          "an unchanged frame sends nothing (%llu rects)", (unsigned long long)st.rects);
    rig_close(&r, true);
}

static void test_xrgb_uncompressed(UMockdevTestbed *tb)
{
    rig r = {0};
    fake_gud_opts_default(&r.o);
    r.o.formats[0] = GUD_FORMAT_XRGB8888;
    r.o.nformats = 1;
    r.o.compression = 0;
    r.o.width = 200;
    r.o.height = 120;
    gud_config_default(&r.cfg);
    char err[300];
    hal_status s = rig_open(&r, tb, err, sizeof err);
    CHECK(s == HAL_OK, "open: %s", err);
    if (s != HAL_OK)
        return rig_close(&r, false);
    gud_info info;
    gud_get_info(r.d, &info);
    CHECK(info.format == GUD_FORMAT_XRGB8888 && !info.lz4, "XRGB8888 without compression");
    celfw_scene_build("bars", &scene, 0.0f);
    hal_frame_stats st;
    CHECK(show(&r, &scene, &st) == HAL_OK, "present: %s", r.d->err);
    CHECK(compare(&r, &scene) == 0, "XRGB8888 frame equals the renderer's");
    CHECK(st.bytes_wire == st.bytes_raw && st.bytes_raw == 200u * 120u * 4u, "raw bytes on the wire");
    rig_close(&r, true);
}

/* Damage: an animation where one small disc moves sends only the lines it touches. */
static void test_damage(UMockdevTestbed *tb)
{
    rig r = {0};
    fake_gud_opts_default(&r.o);
    r.o.width = 480;
    r.o.height = 270;
    gud_config_default(&r.cfg);
    char err[300];
    hal_status s = rig_open(&r, tb, err, sizeof err);
    CHECK(s == HAL_OK, "open: %s", err);
    if (s != HAL_OK)
        return rig_close(&r, false);
    hal_frame_stats st;
    float sy = 270.0f / 180.0f;
    uint64_t lines = 0, raw = 0, wire = 0;
    int frames = 0;
    for (int f = 0; f < 6; f++) {
        float t = 0.40f + 0.04f * (float)f; /* 10.4 canvas units (15.6 px) per frame */
        celfw_scene_build("anim", &scene, t);
        fake_gud_clear_log(r.dev);
        s = show(&r, &scene, &st);
        CHECK(s == HAL_OK, "anim frame %d: %s", f, r.d->err);
        CHECK(compare(&r, &scene) == 0, "anim frame %d on the panel equals the renderer's", f);
        if (f == 0)
            continue;
        /* the disc of this and the previous frame covers rows [y0, y1) */
        float dx, dy;
        celfw_anim_disc(t, &dx, &dy);
        int y0 = (int)floorf((dy - CELFW_ANIM_R) * sy), y1 = (int)ceilf((dy + CELFW_ANIM_R) * sy);
        fake_gud_rect rects[64];
        size_t n = fake_gud_rects(r.dev, rects, 64);
        int outside = 0;
        for (size_t i = 0; i < n && i < 64; i++)
            if ((int)rects[i].y < y0 || (int)(rects[i].y + rects[i].h) > y1)
                outside++;
        CHECK(n > 0 && outside == 0, "frame %d: %zu rects, %d reach beyond the disc's rows %d..%d", f, n,
              outside, y0, y1 - 1);
        CHECK(st.lines_sent <= (uint64_t)(y1 - y0), "frame %d: %llu lines sent for a %d-row disc", f,
              (unsigned long long)st.lines_sent, y1 - y0);
        lines += st.lines_sent;
        raw += st.bytes_raw;
        wire += st.bytes_wire;
        frames++;
    }
    printf("gud damage: anim 480x270 RGB565: %.1f of 270 lines/frame, %.0f bytes raw, %.0f bytes LZ4 per frame\n",
           (double)lines / frames, (double)raw / frames, (double)wire / frames);
    rig_close(&r, true);
}

/* Bands never exceed the device's buffer. */
static void test_small_buffer(UMockdevTestbed *tb)
{
    rig r = {0};
    fake_gud_opts_default(&r.o);
    r.o.max_buffer_size = 320u * 2u * 7u + 100u; /* seven lines */
    gud_config_default(&r.cfg);
    char err[300];
    hal_status s = rig_open(&r, tb, err, sizeof err);
    CHECK(s == HAL_OK, "open: %s", err);
    if (s != HAL_OK)
        return rig_close(&r, false);
    celfw_scene_build("demo", &scene, 0.0f);
    hal_frame_stats st;
    CHECK(show(&r, &scene, &st) == HAL_OK, "present: %s", r.d->err);
    fake_gud_rect rects[64];
    size_t n = fake_gud_rects(r.dev, rects, 64);
    int big = 0;
    for (size_t i = 0; i < n && i < 64; i++)
        big += rects[i].length > r.o.max_buffer_size;
    CHECK(n == 26 && big == 0, "%zu rects of at most 7 lines (%d too big)", n, big);
    CHECK(compare(&r, &scene) == 0, "banded frame equals the renderer's");
    rig_close(&r, true);
}

static void test_faults(UMockdevTestbed *tb)
{
    rig r = {0};
    fake_gud_opts_default(&r.o);
    gud_config_default(&r.cfg);
    r.cfg.timeout_ms = 150;
    char err[300];
    hal_status s = rig_open(&r, tb, err, sizeof err);
    CHECK(s == HAL_OK, "open: %s", err);
    if (s != HAL_OK)
        return rig_close(&r, false);
    hal_frame_stats st;
    fake_gud_stats ds;

    /* a stalled bulk endpoint: clear the halt, send again */
    celfw_scene_build("anim", &scene, 0.0f);
    fake_gud_stall_bulk(r.dev, 1);
    s = show(&r, &scene, &st);
    fake_gud_get_stats(r.dev, &ds);
    CHECK(s == HAL_OK && st.retries >= 1 && st.errors == 0 && ds.stalls == 1 && ds.clear_halts >= 1,
          "stall: status %d, %llu retries, %u clear-halts", s, (unsigned long long)st.retries,
          ds.clear_halts);
    CHECK(compare(&r, &scene) == 0, "frame after a stall equals the renderer's");

    /* a refused SET_BUFFER: the status explains, the retry goes through */
    celfw_scene_build("anim", &scene, 0.5f);
    fake_gud_refuse(r.dev, GUD_REQ_SET_BUFFER, GUD_STATUS_BUSY, 1);
    s = show(&r, &scene, &st);
    CHECK(s == HAL_OK && st.retries >= 1 && st.errors == 0, "refused SET_BUFFER retried");
    CHECK(compare(&r, &scene) == 0, "frame after a refusal equals the renderer's");

    /* a hung endpoint: libusb times out and discards, the retry goes through */
    celfw_scene_build("anim", &scene, 1.0f);
    fake_gud_hang_bulk(r.dev, 1);
    s = show(&r, &scene, &st);
    fake_gud_get_stats(r.dev, &ds);
    CHECK(s == HAL_OK && st.retries >= 1 && st.errors == 0 && ds.discards >= 1,
          "timeout: %llu retries, %u discards", (unsigned long long)st.retries, ds.discards);
    CHECK(compare(&r, &scene) == 0, "frame after a timeout equals the renderer's");

    /* stalls beyond the retries: the frame goes on, the lines travel next time */
    celfw_scene_build("anim", &scene, 1.5f);
    fake_gud_stall_bulk(r.dev, 1 + r.cfg.retries);
    s = show(&r, &scene, &st);
    CHECK(s == HAL_ERR_IO && st.errors >= 1 && st.lines_rendered == (uint64_t)r.d->height &&
              strstr(r.d->err, "LIBUSB_ERROR_PIPE, 3 attempts; sent again next frame"),
          "persistent stall: frame finished with %llu failed bands: %s: %s", (unsigned long long)st.errors,
          hal_status_str(s), r.d->err);
    CHECK(compare(&r, &scene) != 0, "the failed band is missing from the panel");
    s = show(&r, &scene, &st);
    CHECK(s == HAL_OK && st.errors == 0 && st.lines_sent > 0, "the failed lines are sent again");
    CHECK(compare(&r, &scene) == 0, "and then the panel equals the renderer's");
    rig_close(&r, true);
}

static void test_unplug(UMockdevTestbed *tb)
{
    rig r = {0};
    fake_gud_opts_default(&r.o);
    gud_config_default(&r.cfg);
    r.cfg.reconnect_ms = 30;
    char err[300];
    hal_status s = rig_open(&r, tb, err, sizeof err);
    CHECK(s == HAL_OK, "open: %s", err);
    if (s != HAL_OK)
        return rig_close(&r, false);
    hal_frame_stats st;
    celfw_scene_build("anim", &scene, 0.2f);
    CHECK(show(&r, &scene, &st) == HAL_OK, "present before unplug");

    fake_gud_unplug(r.dev);
    celfw_scene_build("anim", &scene, 0.7f);
    s = show(&r, &scene, &st);
    CHECK(s == HAL_ERR_NO_DEVICE && !hal_display_connected(r.d), "unplugged: present says %s (%s)",
          hal_status_str(s), r.d->err);
    for (int i = 0; i < 5; i++)
        s = show(&r, &scene, &st);
    CHECK(s == HAL_ERR_NO_DEVICE, "still away: %s", hal_status_str(s));

    fake_gud_replug(r.dev, 5);
    for (int i = 0; i < 100; i++) {
        g_usleep(10000);
        s = show(&r, &scene, &st);
        if (s == HAL_OK)
            break;
    }
    gud_info info;
    gud_get_info(r.d, &info);
    CHECK(s == HAL_OK && info.connects == 2 && info.address == 5, "reconnected at address %d (%s)",
          info.address, r.d->err);
    CHECK(st.lines_sent == 180, "the whole frame is resent after a reconnect (%llu lines)",
          (unsigned long long)st.lines_sent);
    CHECK(compare(&r, &scene) == 0, "frame after replug equals the renderer's");
    rig_close(&r, true);
}

/* One frame of s at t with its damage window (celfw's loop); *win is what was rendered. */
static hal_status show_damage(rig *r, cs_damage *dmg, const cs_scene *s, float t, hal_window *win,
                              hal_frame_stats *st)
{
    memset(st, 0, sizeof *st);
    lx_scene_source_set(&r->src, s, t);
    return lx_scene_source_show(&r->src, r->d, dmg, win, st);
}

/*
 * Damage windows (issue 27): board-anim's movers over its still sign, on two
 * render threads. Every frame the panel equals the core's whole render at
 * that time, while only the window's lines are rendered and its rectangles
 * travel; a still frame renders nothing; an unplug forgets the last frame
 * and the frame after the replug is whole.
 */
static void test_damage_window(UMockdevTestbed *tb)
{
    static cs_scene anim;
    static cs_damage dmg;
    char err[300];
    if (!celfw_scene_json("scenes/board-anim.json", &anim, err, sizeof err)) {
        CHECK(false, "board-anim: %s", err);
        return;
    }
    rig r = {0};
    fake_gud_opts_default(&r.o);
    r.o.width = 480;
    r.o.height = 272;
    gud_config_default(&r.cfg);
    r.cfg.reconnect_ms = 30;
    hal_status s = rig_open(&r, tb, err, sizeof err);
    CHECK(s == HAL_OK, "open: %s", err);
    if (s != HAL_OK)
        return rig_close(&r, false);
    CHECK(lx_scene_source_threads(&r.src, 2) == HAL_OK, "two render threads");
    cs_damage_reset(&dmg);
    enum { FRAMES = 24 };
    uint64_t lines = 0, pixels = 0;
    int wrong = 0, unbounded = 0, narrow = 0;
    for (int i = 0; i < FRAMES; i++) {
        float t = (float)i / 30.0f;
        hal_frame_stats st;
        hal_window w;
        s = show_damage(&r, &dmg, &anim, t, &w, &st);
        CHECK(s == HAL_OK, "frame %d: %s (%s)", i, hal_status_str(s), r.d->err);
        int rows = w.x1 > w.x0 ? w.y1 - w.y0 : 0;
        if (st.lines_rendered != (uint64_t)rows ||
            st.pixels_rendered != (uint64_t)rows * (uint64_t)(w.x1 - w.x0))
            unbounded++;
        if (i > 0 && rows < 272)
            narrow++;
        if (compare_at(&r, &anim, t) != 0 && wrong++ == 0)
            fprintf(stderr, "  frame %d at t=%g (window %d,%d..%d,%d) differs from the core's render\n", i,
                    (double)t, w.x0, w.y0, w.x1, w.y1);
        lines += st.lines_rendered;
        pixels += st.pixels_rendered;
        if (i == 0)
            CHECK(st.lines_rendered == 272, "the first frame is whole (%llu lines)",
                  (unsigned long long)st.lines_rendered);
    }
    CHECK(wrong == 0, "every frame equals the core's whole render (%d differ)", wrong);
    CHECK(unbounded == 0, "lines and pixels rendered are the window's (%d frames not)", unbounded);
    CHECK(narrow == FRAMES - 1, "frames after the first render a window (%d of %d)", narrow, FRAMES - 1);
    fprintf(stderr, "  board-anim 480x272, %d frames: %.1f lines, %.0f pixels rendered a frame (whole: 272, "
            "130560)\n", FRAMES, (double)lines / FRAMES, (double)pixels / FRAMES);
    CHECK(lines * 4 < (uint64_t)FRAMES * 272, "a quarter of the lines or fewer (%llu of %d)",
          (unsigned long long)lines, FRAMES * 272);

    hal_frame_stats st;
    hal_window w;
    float t = (float)FRAMES / 30.0f;
    s = show_damage(&r, &dmg, &anim, t, &w, &st);
    s = s == HAL_OK ? show_damage(&r, &dmg, &anim, t, &w, &st) : s;
    CHECK(s == HAL_OK && st.lines_rendered == 0 && st.lines_sent == 0 && st.rects == 0,
          "a still frame renders and sends nothing (%s, %llu lines, %llu sent)", hal_status_str(s),
          (unsigned long long)st.lines_rendered, (unsigned long long)st.lines_sent);

    fake_gud_unplug(r.dev);
    for (int i = 0; i < 3; i++)
        s = show_damage(&r, &dmg, &anim, t + (float)(i + 1) / 30.0f, &w, &st);
    CHECK(s == HAL_ERR_NO_DEVICE, "unplugged: %s", hal_status_str(s));
    hal_window part = {0, 0, 10, 10};
    memset(&st, 0, sizeof st);
    lx_scene_source_set(&r.src, &anim, t);
    s = hal_display_present_window(r.d, &r.src.src, &part, &st);
    CHECK(s == HAL_ERR_NO_DEVICE && part.x1 == 480 && part.y1 == 272,
          "an absent display refuses a window: the frame is whole (%s, %d,%d)", hal_status_str(s), part.x1,
          part.y1);
    fake_gud_replug(r.dev, 6);
    t += 0.5f;
    for (int i = 0; i < 100; i++) {
        g_usleep(10000);
        s = show_damage(&r, &dmg, &anim, t, &w, &st);
        if (s == HAL_OK)
            break;
    }
    CHECK(s == HAL_OK && st.lines_rendered == 272 && st.lines_sent == 272,
          "the frame after a replug is whole (%s, %llu rendered, %llu sent)", hal_status_str(s),
          (unsigned long long)st.lines_rendered, (unsigned long long)st.lines_sent);
    CHECK(compare_at(&r, &anim, t) == 0, "the frame after the replug equals the core's render");
    t += 1.0f / 30.0f;
    s = show_damage(&r, &dmg, &anim, t, &w, &st);
    CHECK(s == HAL_OK && st.lines_rendered < 272 && compare_at(&r, &anim, t) == 0,
          "then windows again (%llu lines), still equal", (unsigned long long)st.lines_rendered);
    rig_close(&r, true);
}

static void expect_open_error(UMockdevTestbed *tb, const char *what, fake_gud_opts *o, const char *needle)
{
    rig r = {0};
    r.o = *o;
    gud_config_default(&r.cfg);
    char err[300];
    hal_status s = rig_open(&r, tb, err, sizeof err);
    CHECK(s != HAL_OK && strstr(err, needle), "%s: status %s, message '%s'", what, hal_status_str(s), err);
    rig_close(&r, s == HAL_OK);
}

static void test_odd_devices(UMockdevTestbed *tb)
{
    fake_gud_opts o;
    fake_gud_opts_default(&o);
    uint8_t odd[3] = {GUD_FORMAT_R1, GUD_FORMAT_RGB332, 0x7f};
    memcpy(o.formats, odd, 3);
    o.nformats = 3;
    expect_open_error(tb, "formats R1 RGB332 0x7f", &o, "RGB332(0x30)");

    fake_gud_opts_default(&o);
    o.nformats = 0;
    expect_open_error(tb, "no formats", &o, "offers: nothing");

    fake_gud_opts_default(&o);
    o.magic = 0x12345678;
    expect_open_error(tb, "wrong magic", &o, "not a GUD display");

    fake_gud_opts_default(&o);
    o.version = 2;
    expect_open_error(tb, "version 2", &o, "version 2");

    /* unknown and duplicate codes around a usable one: take it, ignore the rest */
    rig r = {0};
    fake_gud_opts_default(&r.o);
    uint8_t mix[5] = {0x7f, GUD_FORMAT_R8, GUD_FORMAT_XRGB8888, GUD_FORMAT_XRGB8888, GUD_FORMAT_ARGB8888};
    memcpy(r.o.formats, mix, 5);
    r.o.nformats = 5;
    r.o.width = 160;
    r.o.height = 90;
    gud_config_default(&r.cfg);
    char err[300];
    hal_status s = rig_open(&r, tb, err, sizeof err);
    CHECK(s == HAL_OK, "mixed formats: %s", err);
    if (s == HAL_OK) {
        hal_frame_stats st;
        celfw_scene_build("demo", &scene, 0.0f);
        CHECK(show(&r, &scene, &st) == HAL_OK && compare(&r, &scene) == 0, "mixed formats: XRGB8888 frame matches");
    }
    rig_close(&r, s == HAL_OK);

    /* an EDID-only device: no mode list, the configured size is used */
    rig q = {0};
    fake_gud_opts_default(&q.o);
    q.o.no_modes = true;
    q.o.width = 128;
    q.o.height = 64;
    gud_config_default(&q.cfg);
    q.cfg.width = 128;
    q.cfg.height = 64;
    s = rig_open(&q, tb, err, sizeof err);
    CHECK(s == HAL_OK, "no modes, size given: %s", err);
    if (s == HAL_OK) {
        hal_frame_stats st;
        celfw_scene_build("bars", &scene, 0.0f);
        CHECK(show(&q, &scene, &st) == HAL_OK && compare(&q, &scene) == 0, "no-modes device frame matches");
    }
    rig_close(&q, s == HAL_OK);

    /* FULL_UPDATE: whole frames, SET_BUFFER only before the first */
    rig f = {0};
    fake_gud_opts_default(&f.o);
    f.o.flags = GUD_FLAG_FULL_UPDATE;
    f.o.compression = 0;
    f.o.width = 96;
    f.o.height = 48;
    gud_config_default(&f.cfg);
    s = rig_open(&f, tb, err, sizeof err);
    CHECK(s == HAL_OK, "full-update device: %s", err);
    if (s == HAL_OK) {
        hal_frame_stats st;
        celfw_scene_build("demo", &scene, 0.0f);
        show(&f, &scene, &st);
        show(&f, &scene, &st);
        fake_gud_stats ds;
        fake_gud_get_stats(f.dev, &ds);
        CHECK(ds.rects == 2 && ds.set_buffers == 1 && st.lines_sent == 48 && compare(&f, &scene) == 0,
              "full update: %u rects, %u SET_BUFFERs", ds.rects, ds.set_buffers);
        /* a window is refused: the frame driver sends the whole frame */
        hal_window w = {8, 8, 20, 20};
        memset(&st, 0, sizeof st);
        celfw_scene_build("anim", &scene, 0.3f);
        lx_scene_source_set(&f.src, &scene, 0.0f);
        s = hal_display_present_window(f.d, &f.src.src, &w, &st);
        CHECK(s == HAL_OK && w.x0 == 0 && w.y1 == 48 && st.lines_rendered == 48 && compare(&f, &scene) == 0,
              "full update takes no window: %s, rendered %d,%d..%d,%d (%llu lines)", hal_status_str(s), w.x0,
              w.y0, w.x1, w.y1, (unsigned long long)st.lines_rendered);
        s = HAL_OK;
    }
    rig_close(&f, s == HAL_OK);
}

/*
 * Hostile devices: every size, length and limit the device reports is
 * checked before it sizes anything. Each of these once could crash the host
 * (a 0-wide mode divided by a zero pitch) or make it allocate what the
 * device asked for; each must be refused with a message naming the value.
 */
static void test_hostile(UMockdevTestbed *tb)
{
    static const struct {
        const char *what;
        int w, h, descriptor_len, modes_len;
        uint32_t max_buffer;
        const char *needle;
    } bad[] = {
        {"0 wide", 0, 180, 0, 0, 0, "mode 0x180 has no pixels"},
        {"0 high", 320, 0, 0, 0, 0, "mode 320x0 has no pixels"},
        {"0 by 0", 0, 0, 0, 0, 0, "mode 0x0 has no pixels"},
        {"0 wide at most", 0, 180, 0, 0, 0, "unusable display descriptor (version 1, 0x180..0x180)"},
        {"65535 wide", 65535, 180, 0, 0, 0, "mode 65535x180 is larger than celfw renders"},
        {"65535 high", 320, 65535, 0, 0, 0, "mode 320x65535 is larger than celfw renders"},
        {"short descriptor", 320, 180, 12, 0, 0, "descriptor of 12 bytes"},
        {"empty descriptor", 320, 180, 1, 0, 0, "descriptor of 1 bytes"},
        {"mode list of 30 bytes", 320, 180, 0, 30, 0, "the mode list is 30 bytes"},
        {"mode list of 7 bytes", 320, 180, 0, 7, 0, "the mode list is 7 bytes"},
        {"buffer of 16 bytes", 320, 180, 0, 0, 16, "the device buffer (16 bytes) cannot take one 640-byte line"},
        {"buffer of 1 byte", 320, 180, 0, 0, 1, "the device buffer (1 bytes)"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        fake_gud_opts o;
        fake_gud_opts_default(&o);
        o.width = bad[i].w;
        o.height = bad[i].h;
        o.descriptor_len = bad[i].descriptor_len;
        o.modes_len = bad[i].modes_len;
        o.max_buffer_size = bad[i].max_buffer;
        o.any_size = i < 3; /* limits that let the empty modes through to their own check */
        expect_open_error(tb, bad[i].what, &o, bad[i].needle);
    }
    fake_gud_opts o;
    fake_gud_opts_default(&o);
    o.formats[0] = 0x7f;
    o.formats[1] = 0xee;
    expect_open_error(tb, "unknown formats only", &o, "no pixel format celfw can send");

    /* A full-update device whose frame would be 4096 x 16384 x 4 bytes. */
    fake_gud_opts_default(&o);
    o.flags = GUD_FLAG_FULL_UPDATE;
    o.compression = 0;
    o.width = 4096;
    o.height = 16384;
    o.formats[0] = GUD_FORMAT_XRGB8888;
    o.nformats = 1;
    expect_open_error(tb, "full update of 256 MiB", &o, "more than celfw buffers");

    /* No mode list and a descriptor of 100000 x 8: more than a uint16 mode holds. */
    fake_gud_opts_default(&o);
    o.no_modes = true;
    o.width = 100000;
    o.height = 8;
    expect_open_error(tb, "EDID-only 100000 wide", &o, "the device's size 100000x8 is larger than celfw renders");

    /* max_buffer_size 0 means no limit (as in the kernel driver): usable. */
    rig z = {0};
    fake_gud_opts_default(&z.o);
    z.o.max_buffer_size = 0;
    gud_config_default(&z.cfg);
    char err[300];
    hal_status s = rig_open(&z, tb, err, sizeof err);
    hal_frame_stats st;
    CHECK(s == HAL_OK, "max buffer 0 (no limit): %s", err);
    if (s == HAL_OK) {
        celfw_scene_build("demo", &scene, 0.0f);
        CHECK(show(&z, &scene, &st) == HAL_OK && compare(&z, &scene) == 0, "no buffer limit: frame matches");
    }
    rig_close(&z, s == HAL_OK);

    /*
     * A device that comes back with another face: first RGB565, then
     * XRGB8888 only (twice the bytes per line, the same band of lines: the
     * band must grow with it), then 0 wide (refused; the display stays down
     * and is retried), then itself again.
     */
    rig r = {0};
    fake_gud_opts_default(&r.o);
    r.o.width = 96;
    r.o.height = 48;
    r.o.formats[0] = GUD_FORMAT_RGB565;
    r.o.nformats = 1;
    gud_config_default(&r.cfg);
    r.cfg.reconnect_ms = 10;
    s = rig_open(&r, tb, err, sizeof err);
    CHECK(s == HAL_OK, "replug rig: %s", err);
    if (s != HAL_OK)
        return rig_close(&r, false);
    /* a moving scene, so that every frame talks to the device and finds it gone */
    float t = 0.0f;
    celfw_scene_build("anim", &scene, t);
    CHECK(show(&r, &scene, &st) == HAL_OK && compare(&r, &scene) == 0, "RGB565 frame");
    fake_gud_opts next = r.o;
    next.formats[0] = GUD_FORMAT_XRGB8888;
    fake_gud_unplug(r.dev);
    celfw_scene_build("anim", &scene, t += 0.1f);
    CHECK(show(&r, &scene, &st) == HAL_ERR_NO_DEVICE, "unplugged");
    fake_gud_set_opts(r.dev, &next);
    fake_gud_replug(r.dev, 6);
    for (int i = 0; i < 100 && (s = show(&r, &scene, &st)) != HAL_OK; i++)
        g_usleep(10000);
    gud_info info;
    gud_get_info(r.d, &info);
    CHECK(s == HAL_OK && info.format == GUD_FORMAT_XRGB8888 && compare(&r, &scene) == 0,
          "back as XRGB8888: %s, format 0x%02x", hal_status_str(s), info.format);

    next.width = 0;
    next.any_size = true;
    fake_gud_unplug(r.dev);
    celfw_scene_build("anim", &scene, t += 0.1f);
    CHECK(show(&r, &scene, &st) == HAL_ERR_NO_DEVICE, "unplugged again");
    fake_gud_set_opts(r.dev, &next);
    fake_gud_replug(r.dev, 7);
    for (int i = 0; i < 10; i++) {
        g_usleep(15000);
        s = show(&r, &scene, &st);
    }
    CHECK(s == HAL_ERR_NO_DEVICE && strstr(r.d->err, "mode 0x48 has no pixels"),
          "back 0 wide: down, and says why: %s (%s)", hal_status_str(s), r.d->err);

    next.width = 96;
    next.any_size = false;
    fake_gud_unplug(r.dev);
    fake_gud_set_opts(r.dev, &next);
    fake_gud_replug(r.dev, 8);
    for (int i = 0; i < 100 && (s = show(&r, &scene, &st)) != HAL_OK; i++)
        g_usleep(10000);
    CHECK(s == HAL_OK && compare(&r, &scene) == 0, "back whole: %s (%s)", hal_status_str(s), r.d->err);
    rig_close(&r, true);
}

static void test_missing(void)
{
    gud_config c;
    gud_config_default(&c);
    c.vid = 0x1234;
    c.pid = 0x5678;
    hal_display *d = NULL;
    char err[300] = "";
    hal_status s = gud_open(&d, &c, &hal_clock_monotonic, NULL, NULL, err, sizeof err);
    CHECK(s == HAL_ERR_NO_DEVICE && strstr(err, "no USB device 1234:5678"), "missing: '%s'", err);

    c.wait = true;
    s = gud_open(&d, &c, &hal_clock_monotonic, NULL, NULL, err, sizeof err);
    CHECK(s == HAL_ERR_CONFIG && strstr(err, "size"), "wait without size: '%s'", err);
    c.width = 64;
    c.height = 32;
    c.reconnect_ms = 10;
    s = gud_open(&d, &c, &hal_clock_monotonic, NULL, NULL, err, sizeof err);
    CHECK(s == HAL_OK && !hal_display_connected(d), "wait: opens without the device");
    if (s == HAL_OK) {
        lx_scene_source src;
        lx_scene_source_init(&src, 64, 32, CS_AA_SUBSCAN, 4);
        celfw_scene_build("demo", &scene, 0.0f);
        lx_scene_source_set(&src, &scene, 0.0f);
        hal_frame_stats st = {0};
        CHECK(hal_display_present(d, &src.src, &st) == HAL_ERR_NO_DEVICE && st.lines_rendered == 0,
              "absent display: nothing rendered");
        hal_display_close(d);
        lx_scene_source_free(&src);
    }
}

/* Bytes per frame of the demo scene over USB, for the report. */
static void measure(UMockdevTestbed *tb, int w, int h, uint8_t format)
{
    rig r = {0};
    fake_gud_opts_default(&r.o);
    r.o.width = w;
    r.o.height = h;
    r.o.formats[0] = format;
    r.o.nformats = 1;
    gud_config_default(&r.cfg);
    char err[300];
    if (rig_open(&r, tb, err, sizeof err) != HAL_OK) {
        CHECK(0, "measure open: %s", err);
        return rig_close(&r, false);
    }
    hal_frame_stats st;
    celfw_scene_build("demo", &scene, 0.0f);
    show(&r, &scene, &st);
    CHECK(compare(&r, &scene) == 0, "demo %dx%d %s matches", w, h, gud_format_name(format));
    printf("gud bytes/frame: demo %dx%d %s full frame: %llu raw, %llu LZ4 (%.1f%%) in %llu rects\n", w, h,
           gud_format_name(format), (unsigned long long)st.bytes_raw, (unsigned long long)st.bytes_wire,
           100.0 * (double)st.bytes_wire / (double)st.bytes_raw, (unsigned long long)st.rects);
    rig_close(&r, true);
}

/* What the emulated panel shows, for the conformance case. */
static bool gud_shown(void *user, uint8_t *frame)
{
    rig *r = user;
    fake_gud_framebuffer(r->dev, frame, hal_line_bytes(r->d->pixfmt, r->d->width) * (size_t)r->d->height);
    return true;
}

/* Every bulk write of the next frame stalls, past the retries. */
static void gud_fail_writes(void *user)
{
    rig *r = user;
    fake_gud_stall_bulk(r->dev, 1 + r->cfg.retries);
}

/* The conformance case every backend passes, in RGB565 and XRGB8888; a failed write; then a device gone. */
static void test_conformance(UMockdevTestbed *tb)
{
    for (int k = 0; k < 2; k++) {
        rig r = {0};
        fake_gud_opts_default(&r.o);
        r.o.formats[0] = k ? GUD_FORMAT_XRGB8888 : GUD_FORMAT_RGB565;
        r.o.nformats = 1;
        gud_config_default(&r.cfg);
        char err[300];
        hal_status s = rig_open(&r, tb, err, sizeof err);
        CHECK(s == HAL_OK, "conformance open: %s", err);
        if (s != HAL_OK)
            return rig_close(&r, false);
        conf_backend b = {.d = r.d, .shown = gud_shown, .user = &r};
        const char *name = k ? "usb XRGB8888" : "usb RGB565";
        conf_frames(&b, name);
        conf_geometry_error(&b, name);
        conf_failed_write(&b, name, gud_fail_writes, "LIBUSB_ERROR_PIPE");
        fake_gud_unplug(r.dev);
        hal_frame_stats st;
        celfw_scene_build("demo", &scene, 0.0f);
        s = show(&r, &scene, &st);
        CHECK(conf_error_is(r.d, s, HAL_ERR_NO_DEVICE, "disconnected"), "%s: device gone: %s: %s", name,
              hal_status_str(s), r.d->err);
        rig_close(&r, true);
    }
}

int main(void)
{
    UMockdevTestbed *tb = umockdev_testbed_new();
    if (!umockdev_in_mock_environment()) {
        fprintf(stderr, "test_gud: run under umockdev-wrapper (LD_PRELOAD=libumockdev-preload.so)\n");
        return 2;
    }
    /* libusb wants /dev/bus/usb to exist before any device does */
    char *root = umockdev_testbed_get_root_dir(tb);
    char path[600];
    snprintf(path, sizeof path, "%s/dev/bus/usb", root);
    g_mkdir_with_parents(path, 0755);
    g_free(root);

    test_missing();
    test_basic(tb);
    test_xrgb_uncompressed(tb);
    test_damage(tb);
    test_small_buffer(tb);
    test_faults(tb);
    test_unplug(tb);
    test_damage_window(tb);
    test_odd_devices(tb);
    test_hostile(tb);
    test_conformance(tb);
    measure(tb, 480, 272, GUD_FORMAT_RGB565);
    measure(tb, 800, 480, GUD_FORMAT_RGB565);
    measure(tb, 800, 480, GUD_FORMAT_XRGB8888);
    g_object_unref(tb);
    return tl_summary("test_gud");
}
