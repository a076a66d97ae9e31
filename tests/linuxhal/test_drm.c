/*
 * test_drm.c - the DRM/KMS backend against an emulated /dev/dri/card0.
 *
 * Runs under umockdev: the real libdrm talks to fake_drm, which answers the
 * KMS ioctls and the flip events as the kernel does and keeps the dumb
 * buffers in memory the test can read. What the CRTC scans out (the buffer
 * the last SETCRTC or PAGE_FLIP named) must equal the scene rendered
 * directly with the core in this test, converted to the buffer's format
 * here (not with the backend's converter). Also: --mode picks the mode and a
 * missing one is refused, RGB565 when the driver prefers 16-bit buffers,
 * drivers without flips (DirtyFB clips) or without DirtyFB, a flip that
 * never completes, a connector that reports disconnected or a card that
 * answers ENODEV mid-run (a clear error, then a reconnect), and no card.
 */
#include <errno.h>
#include <libgen.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <drm_fourcc.h>

#include "celfw_child.h"
#include "celfw_scenes.h"
#include "fake_drm.h"
#include "kms.h"
#include "lx_scene_source.h"
#include "testlib.h"

#include "display_conformance.h"

/* The truth at time t (the conformance reference, display_conformance.h) in the buffer's format. */
static uint8_t *expected_at(const cs_scene *s, float t, int w, int h, uint32_t fourcc)
{
    hal_pixfmt fmt = fourcc == DRM_FORMAT_RGB565 ? CS_PIX_RGB565_SRGB : HAL_PIX_XRGB8888;
    size_t bpp = fourcc == DRM_FORMAT_RGB565 ? 2 : 4;
    uint8_t *img = conf_reference_image(s, t, w, h, (size_t)w * bpp, conf_encode_fmt, &fmt);
    if (!img)
        abort(); /* out of memory or an unrenderable test scene: nothing to compare with */
    return img;
}

static uint8_t *expected(const cs_scene *s, int w, int h, uint32_t fourcc)
{
    return expected_at(s, 0.0f, w, h, fourcc);
}

typedef struct rig {
    fake_drm_opts o;
    fake_drm *card;
    kms_config cfg;
    hal_display *d;
    lx_scene_source src;
    cs_scene scene;
} rig;

static void rig_defaults(rig *r)
{
    memset(r, 0, sizeof *r);
    r->o.modes[0] = (fake_drm_mode){96, 64, 60, true};
    r->o.modes[1] = (fake_drm_mode){64, 48, 75, false};
    r->o.nmodes = 2;
    r->o.preferred_depth = 24;
    kms_config_default(&r->cfg);
    r->cfg.probe_ms = 0;
    r->cfg.reconnect_ms = 20;
    r->cfg.flip_timeout_ms = 200;
}

static hal_status rig_open(rig *r, UMockdevTestbed *tb, char *err, size_t errlen)
{
    r->card = fake_drm_add(tb, &r->o);
    err[0] = 0;
    hal_status s = kms_open(&r->d, &r->cfg, &hal_clock_monotonic, conf_log, NULL, err, errlen);
    if (s == HAL_OK && lx_scene_source_init(&r->src, r->d->width, r->d->height, CS_AA_SUBSCAN, 4) != HAL_OK)
        s = HAL_ERR_NOMEM;
    return s;
}

/* Waits (bounded) for the fake to see the closed fd: its objects go with it. */
static bool all_freed(fake_drm *card)
{
    for (int i = 0; i < 200; i++) {
        if (fake_drm_live_dumbs(card) == 0 && fake_drm_live_fbs(card) == 0)
            return true;
        usleep(5000);
    }
    return false;
}

static void rig_close(rig *r, bool opened)
{
    if (opened) {
        hal_display_close(r->d);
        lx_scene_source_free(&r->src);
        CHECK(all_freed(r->card),
              "close left %u dumb buffers, %u framebuffers", fake_drm_live_dumbs(r->card),
              fake_drm_live_fbs(r->card));
    }
    fake_drm_free(r->card);
}

/* rig_open, checked: on failure the rig is closed and the caller returns. */
static bool rig_start(rig *r, UMockdevTestbed *tb)
{
    char err[320];
    hal_status s = rig_open(r, tb, err, sizeof err);
    CHECK(s == HAL_OK, "open: %s: %s", hal_status_str(s), err);
    if (s != HAL_OK)
        rig_close(r, false);
    return s == HAL_OK;
}

/* Builds scene `name` at time t and presents it. */
static hal_status show(rig *r, const char *name, float t, hal_frame_stats *st)
{
    memset(st, 0, sizeof *st);
    if (!celfw_scene_build(name, &r->scene, t))
        abort();
    lx_scene_source_set(&r->src, &r->scene, 0.0f);
    return hal_display_present(r->d, &r->src.src, st);
}

/* Compares what the CRTC scans out with the core's rendering of s at t. Returns mismatching pixels. */
static int compare_at(rig *r, const cs_scene *s, float t)
{
    fake_drm_scanout so;
    if (!fake_drm_get_scanout(r->card, &so)) {
        fprintf(stderr, "  nothing scanned out\n");
        return -1;
    }
    size_t bpp = so.fourcc == DRM_FORMAT_RGB565 ? 2 : 4;
    uint8_t *want = expected_at(s, t, so.mode_w, so.mode_h, so.fourcc);
    int bad = 0;
    for (int y = 0; y < so.mode_h; y++)
        for (int x = 0; x < so.mode_w; x++)
            if (memcmp(so.pixels + (size_t)y * so.pitch + (size_t)x * bpp,
                       want + ((size_t)y * (size_t)so.mode_w + (size_t)x) * bpp, bpp) != 0 &&
                bad++ == 0)
                fprintf(stderr, "  first mismatch at pixel (%d,%d)\n", x, y);
    free(want);
    return bad;
}

static int compare(rig *r)
{
    return compare_at(r, &r->scene, 0.0f);
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
 * Damage windows (issue 27): board-anim at 480x272, with flips and atomic
 * FB_DAMAGE_CLIPS on two render threads (XRGB8888 or RGB565), or in one
 * buffer with DirtyFB on one.
 * Every frame the CRTC scans out the core's whole render at that time (so
 * the back buffer was brought up to date outside the window), only the
 * window's lines are rendered, the clips lie within it, a still frame
 * renders nothing and commits nothing, and after a lost screen the frame is
 * whole.
 */
static void test_damage_window(UMockdevTestbed *tb, bool no_flip, bool rgb565)
{
    static rig r;
    static cs_scene anim;
    static cs_damage dmg;
    char err[300];
    if (!celfw_scene_json("scenes/board-anim.json", &anim, err, sizeof err)) {
        CHECK(false, "board-anim: %s", err);
        return;
    }
    rig_defaults(&r);
    r.o.modes[0] = (fake_drm_mode){480, 272, 60, true};
    r.o.no_flip = no_flip;
    r.o.atomic = !no_flip;
    r.o.damage_clips = !no_flip;
    if (rgb565)
        r.o.preferred_depth = 16; /* a window's columns start at 2 bytes a pixel */
    if (!rig_start(&r, tb))
        return;
    CHECK((r.d->pixfmt == CS_PIX_RGB565_SRGB) == rgb565, "pixel format %d", r.d->pixfmt);
    /* the window on the thread pool with flips, in the calling thread's lane without */
    CHECK(lx_scene_source_threads(&r.src, no_flip ? 1 : 2) == HAL_OK, "render threads");
    cs_damage_reset(&dmg);
    enum { FRAMES = 20 };
    uint64_t lines = 0;
    int wrong = 0, unbounded = 0, outside = 0;
    hal_frame_stats st;
    hal_window w;
    hal_status s = HAL_OK;
    for (int i = 0; i < FRAMES; i++) {
        float t = (float)i / 30.0f;
        s = show_damage(&r, &dmg, &anim, t, &w, &st);
        CHECK(s == HAL_OK, "frame %d: %s (%s)", i, hal_status_str(s), r.d->err);
        int rows = w.x1 > w.x0 ? w.y1 - w.y0 : 0;
        if (st.lines_rendered != (uint64_t)rows)
            unbounded++;
        if (compare_at(&r, &anim, t) != 0 && wrong++ == 0)
            fprintf(stderr, "  frame %d at t=%g (window %d,%d..%d,%d) differs from the core's render\n", i,
                    (double)t, w.x0, w.y0, w.x1, w.y1);
        int clips[128];
        int n = i > 0 && st.lines_sent ? fake_drm_last_clips(r.card, clips, 64) : 0;
        for (int j = 0; j < n && j < 64; j++)
            if (clips[2 * j] < w.y0 || clips[2 * j + 1] > w.y1)
                outside++;
        lines += st.lines_rendered;
    }
    CHECK(wrong == 0, "no_flip %d rgb565 %d: every frame scanned out equals the core's whole render (%d differ)",
          no_flip, rgb565, wrong);
    CHECK(unbounded == 0 && outside == 0, "lines rendered are the window's (%d frames not), clips in it (%d not)",
          unbounded, outside);
    CHECK(lines * 4 < (uint64_t)FRAMES * 272, "a quarter of the lines or fewer (%llu of %d)",
          (unsigned long long)lines, FRAMES * 272);
    float t = (float)FRAMES / 30.0f;
    s = show_damage(&r, &dmg, &anim, t, &w, &st);
    unsigned commits = fake_drm_count(r.card, FAKE_DRM_ATOMIC) + fake_drm_count(r.card, FAKE_DRM_FLIP) +
                       fake_drm_count(r.card, FAKE_DRM_DIRTY);
    s = s == HAL_OK ? show_damage(&r, &dmg, &anim, t, &w, &st) : s;
    CHECK(s == HAL_OK && st.lines_rendered == 0 &&
              commits == fake_drm_count(r.card, FAKE_DRM_ATOMIC) + fake_drm_count(r.card, FAKE_DRM_FLIP) +
                             fake_drm_count(r.card, FAKE_DRM_DIRTY),
          "a still frame renders and commits nothing (%s, %llu lines)", hal_status_str(s),
          (unsigned long long)st.lines_rendered);

    fake_drm_set_connected(r.card, false);
    t += 1.0f / 30.0f;
    s = show_damage(&r, &dmg, &anim, t, &w, &st);
    CHECK(s == HAL_ERR_NO_DEVICE, "unplugged: %s", hal_status_str(s));
    fake_drm_set_connected(r.card, true);
    for (int i = 0; i < 100; i++) {
        usleep(10000);
        t += 1.0f / 30.0f;
        if ((s = show_damage(&r, &dmg, &anim, t, &w, &st)) == HAL_OK)
            break;
    }
    CHECK(s == HAL_OK && st.lines_rendered == 272 && compare_at(&r, &anim, t) == 0,
          "the frame after a replug is whole and right (%s, %llu lines)", hal_status_str(s),
          (unsigned long long)st.lines_rendered);
    t += 1.0f / 30.0f;
    s = show_damage(&r, &dmg, &anim, t, &w, &st);
    CHECK(s == HAL_OK && st.lines_rendered < 272 && compare_at(&r, &anim, t) == 0,
          "then windows again (%llu lines), still right", (unsigned long long)st.lines_rendered);
    rig_close(&r, true);
}

static void test_frames(UMockdevTestbed *tb)
{
    static rig r; /* holds a scene store: too big for a stack */
    rig_defaults(&r);
    if (!rig_start(&r, tb))
        return;
    hal_status s;
    kms_info info;
    kms_get_info(r.d, &info);
    CHECK(info.width == 96 && info.height == 64 && info.refresh == 60, "preferred mode: got %dx%d@%d",
          info.width, info.height, info.refresh);
    CHECK(!strcmp(info.device, "/dev/dri/card0") && !strcmp(info.connector, "HDMI-A-1"),
          "found %s %s", info.device, info.connector);
    CHECK(info.fourcc == DRM_FORMAT_XRGB8888, "format %08x", info.fourcc);
    hal_frame_stats st;
    const struct { const char *scene; float t; } frames[] = {{"demo", 0.0f}, {"anim", 0.3f}, {"anim", 0.7f},
                                                             {"bars", 0.0f}, {"anim", 1.1f}};
    for (size_t i = 0; i < sizeof frames / sizeof frames[0]; i++) {
        s = show(&r, frames[i].scene, frames[i].t, &st);
        CHECK(s == HAL_OK, "frame %zu: %s: %s", i, hal_status_str(s), r.d->err);
        int bad = compare(&r);
        CHECK(bad == 0, "frame %zu (%s t=%g): %d pixels differ from the core's rendering", i, frames[i].scene,
              (double)frames[i].t, bad);
        CHECK(st.lines_rendered == 64, "frame %zu rendered %llu lines", i, (unsigned long long)st.lines_rendered);
    }
    CHECK(fake_drm_count(r.card, FAKE_DRM_SETCRTC) == 1, "%u mode sets (want 1, then flips)",
          fake_drm_count(r.card, FAKE_DRM_SETCRTC));
    CHECK(fake_drm_count(r.card, FAKE_DRM_FLIP) == 4, "%u flips (want 4)", fake_drm_count(r.card, FAKE_DRM_FLIP));
    CHECK(fake_drm_count(r.card, FAKE_DRM_DIRTY) == 0, "DirtyFB with flips");
    /* The same frame again: nothing differs from the screen, so no flip; the
     * back buffer is brought up to date once, then not written at all. */
    for (int i = 0; i < 2; i++) {
        s = show(&r, "anim", 1.1f, &st);
        CHECK(s == HAL_OK && st.lines_sent == 0 && fake_drm_count(r.card, FAKE_DRM_FLIP) == 4,
              "unchanged frame: %s, %llu lines changed, %u flips", hal_status_str(s),
              (unsigned long long)st.lines_sent, fake_drm_count(r.card, FAKE_DRM_FLIP));
    }
    CHECK(st.bytes_raw == 0, "unchanged frame again: %llu bytes written", (unsigned long long)st.bytes_raw);
    kms_get_info(r.d, &info);
    CHECK(info.flips_done == 4 && fake_drm_count(r.card, FAKE_DRM_EVENTS_READ) == 4,
          "flip events: %llu handled, %u read", (unsigned long long)info.flips_done,
          fake_drm_count(r.card, FAKE_DRM_EVENTS_READ));
    /* A source of another size is the caller's error, not the screen's. */
    lx_scene_source other;
    lx_scene_source_init(&other, 64, 48, CS_AA_SUBSCAN, 4);
    lx_scene_source_set(&other, &r.scene, 0.0f);
    s = hal_display_present(r.d, &other.src, &st);
    char want[80]; /* the text users saw before the one contract: "the screen" */
    snprintf(want, sizeof want, "drm: source is 64x48, the screen %dx%d", r.d->width, r.d->height);
    CHECK(s == HAL_ERR_CONFIG && !strcmp(r.d->err, want), "size mismatch: %s: '%s', want '%s'",
          hal_status_str(s), r.d->err, want);
    lx_scene_source_free(&other);
    hal_display_close(r.d);
    fake_drm_scanout so;
    CHECK(all_freed(r.card) && !fake_drm_get_scanout(r.card, &so),
          "after close the CRTC (off when found) still shows fb %u", so.fb_id);
    lx_scene_source_free(&r.src);
    fake_drm_free(r.card);
}

static void test_modes(UMockdevTestbed *tb)
{
    const struct { const char *spec; hal_status want; int w, h, hz; const char *needle; } cases[] = {
        {"64x48", HAL_OK, 64, 48, 75, NULL},
        {"64x48@75", HAL_OK, 64, 48, 75, NULL},
        {"96x64@60", HAL_OK, 96, 64, 60, NULL},
        {"64x48@60", HAL_ERR_CONFIG, 0, 0, 0, "no mode 64x48@60 (it has 96x64@60, 64x48@75)"},
        {"100x100", HAL_ERR_CONFIG, 0, 0, 0, "no mode 100x100"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        static rig r; /* holds a scene store: too big for a stack */
        rig_defaults(&r);
        CHECK(kms_parse_mode(cases[i].spec, &r.cfg), "parse %s", cases[i].spec);
        char err[320];
        hal_status s = rig_open(&r, tb, err, sizeof err);
        CHECK(s == cases[i].want, "mode %s: %s: %s", cases[i].spec, hal_status_str(s), err);
        if (s == HAL_OK) {
            kms_info info;
            kms_get_info(r.d, &info);
            CHECK(info.width == cases[i].w && info.height == cases[i].h && info.refresh == cases[i].hz,
                  "mode %s chose %dx%d@%d", cases[i].spec, info.width, info.height, info.refresh);
            hal_frame_stats st;
            s = show(&r, "demo", 0.0f, &st);
            fake_drm_scanout so = {0};
            fake_drm_get_scanout(r.card, &so);
            CHECK(s == HAL_OK && so.mode_w == cases[i].w && so.mode_h == cases[i].h && so.mode_hz == cases[i].hz,
                  "mode %s: the CRTC runs %dx%d@%d", cases[i].spec, so.mode_w, so.mode_h, so.mode_hz);
            CHECK(compare(&r) == 0, "mode %s: frame differs", cases[i].spec);
        } else if (cases[i].needle) {
            CHECK(strstr(err, cases[i].needle) != NULL, "mode %s: message '%s'", cases[i].spec, err);
            CHECK(fake_drm_live_dumbs(r.card) == 0, "a refused mode left buffers");
        }
        rig_close(&r, s == HAL_OK);
    }
    static const char *bad[] = {"", "64", "64x", "x48", "64x48@", "64x48@0", "64x48@60Hz", "0x48", "64x48x2"};
    kms_config c;
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        CHECK(!kms_parse_mode(bad[i], &c), "mode '%s' accepted", bad[i]);
}

/* RGB565 when the driver prefers 16-bit dumb buffers, or when the plane takes nothing else. */
static void test_rgb565(UMockdevTestbed *tb, bool plane_only)
{
    static rig r; /* holds a scene store: too big for a stack */
    rig_defaults(&r);
    if (plane_only)
        r.o.plane_formats[0] = DRM_FORMAT_RGB565;
    else
        r.o.preferred_depth = 16;
    char err[320];
    hal_status s = rig_open(&r, tb, err, sizeof err);
    CHECK(s == HAL_OK, "open: %s", err);
    if (s == HAL_OK) {
        kms_info info;
        kms_get_info(r.d, &info);
        CHECK(info.fourcc == DRM_FORMAT_RGB565, "format %08x, want RGB565", info.fourcc);
        hal_frame_stats st;
        for (int i = 0; i < 3; i++) {
            s = show(&r, "anim", 0.4f * (float)i, &st);
            CHECK(s == HAL_OK && compare(&r) == 0, "RGB565 frame %d: %s", i, r.d->err);
        }
    }
    rig_close(&r, s == HAL_OK);
}

/* Bands of lines that differ between two images: the damage a frame must report. */
static int diff_bands(const uint8_t *a, const uint8_t *b, int w, int h, int *y)
{
    int n = 0;
    for (int row = 0; row < h; row++) {
        if (!memcmp(a + (size_t)row * (size_t)w * 4u, b + (size_t)row * (size_t)w * 4u, (size_t)w * 4u))
            continue;
        if (n && y[2 * n - 1] == row)
            y[2 * n - 1] = row + 1;
        else if (n < 32) {
            y[2 * n] = row;
            y[2 * n + 1] = row + 1;
            n++;
        }
    }
    return n;
}

static void test_no_flips(UMockdevTestbed *tb, bool dirty)
{
    static rig r; /* holds a scene store: too big for a stack */
    rig_defaults(&r);
    r.o.no_flip = true;
    r.o.no_dirty = !dirty;
    if (!rig_start(&r, tb))
        return;
    hal_status s;
    hal_frame_stats st;
    s = show(&r, "anim", 0.0f, &st);
    CHECK(s == HAL_OK && compare(&r) == 0, "no flips, frame 0: %s", r.d->err);
    s = show(&r, "anim", 0.5f, &st); /* the flip is refused: a mode set, then one buffer */
    CHECK(s == HAL_OK && compare(&r) == 0, "no flips, frame 1: %s", r.d->err);
    kms_info info;
    kms_get_info(r.d, &info);
    CHECK(!info.flips && fake_drm_count(r.card, FAKE_DRM_SETCRTC) == 2, "flips %d, %u mode sets", info.flips,
          fake_drm_count(r.card, FAKE_DRM_SETCRTC));
    uint8_t *before = expected(&r.scene, 96, 64, DRM_FORMAT_XRGB8888);
    s = show(&r, "anim", 0.6f, &st);
    CHECK(s == HAL_OK && compare(&r) == 0, "no flips, frame 2: %s", r.d->err);
    uint8_t *after = expected(&r.scene, 96, 64, DRM_FORMAT_XRGB8888);
    int want[64], got[128];
    int nwant = diff_bands(before, after, 96, 64, want);
    CHECK(nwant > 0, "frames 1 and 2 are equal: no damage to test");
    kms_get_info(r.d, &info);
    CHECK(fake_drm_count(r.card, FAKE_DRM_SETCRTC) == 2, "%u mode sets in single-buffer mode",
          fake_drm_count(r.card, FAKE_DRM_SETCRTC));
    if (dirty) {
        int ngot = fake_drm_last_clips(r.card, got, 64);
        bool same = ngot == nwant;
        for (int i = 0; same && i < 2 * nwant; i++)
            same = got[i] == want[i];
        CHECK(same && info.dirty_fb, "DirtyFB clips: %d bands (first y %d..%d), changed lines form %d (first %d..%d)",
              ngot, ngot ? got[0] : -1, ngot ? got[1] : -1, nwant, want[0], want[1]);
        CHECK(st.rects == (uint64_t)nwant, "%llu rects counted", (unsigned long long)st.rects);
    } else {
        CHECK(!info.dirty_fb && fake_drm_count(r.card, FAKE_DRM_DIRTY) == 0, "a driver without DirtyFB was asked");
    }
    free(before);
    free(after);
    rig_close(&r, true);
}

static void test_unplug(UMockdevTestbed *tb)
{
    static rig r; /* holds a scene store: too big for a stack */
    rig_defaults(&r);
    if (!rig_start(&r, tb))
        return;
    hal_status s;
    hal_frame_stats st;
    CHECK(show(&r, "demo", 0.0f, &st) == HAL_OK && show(&r, "anim", 0.2f, &st) == HAL_OK, "frames before unplug");

    /* The connector reports nothing connected (HDMI cable pulled). */
    fake_drm_set_connected(r.card, false);
    s = show(&r, "anim", 0.4f, &st);
    CHECK(s == HAL_ERR_NO_DEVICE && strstr(r.d->err, "reports no screen connected"), "unplugged: %s: %s",
          hal_status_str(s), r.d->err);
    CHECK(!hal_display_connected(r.d) && all_freed(r.card),
          "after the loss: connected %d, %u buffers left", hal_display_connected(r.d), fake_drm_live_dumbs(r.card));
    usleep(30 * 1000);
    s = show(&r, "anim", 0.4f, &st); /* still unplugged: the reconnect fails cleanly */
    CHECK(s == HAL_ERR_NO_DEVICE && strstr(r.d->err, "no connector has a screen connected"), "still away: %s: %s",
          hal_status_str(s), r.d->err);
    fake_drm_set_connected(r.card, true);
    usleep(30 * 1000);
    s = show(&r, "anim", 0.5f, &st);
    CHECK(s == HAL_OK && compare(&r) == 0, "after replug: %s: %s", hal_status_str(s), r.d->err);
    kms_info info;
    kms_get_info(r.d, &info);
    CHECK(info.connects == 2 && info.connected, "connects %llu", (unsigned long long)info.connects);

    /* The card answers ENODEV (the device is gone), mid-run. */
    fake_drm_set_gone(r.card, true);
    s = show(&r, "anim", 0.6f, &st);
    CHECK(s == HAL_ERR_NO_DEVICE && strstr(r.d->err, strerror(ENODEV)), "ENODEV: %s: %s", hal_status_str(s),
          r.d->err);
    s = show(&r, "anim", 0.6f, &st); /* before reconnect_ms: cheap, the same answer */
    CHECK(s == HAL_ERR_NO_DEVICE && strstr(r.d->err, "screen absent"), "absent: %s: %s", hal_status_str(s),
          r.d->err);
    fake_drm_set_gone(r.card, false);
    usleep(30 * 1000);
    s = show(&r, "anim", 0.7f, &st);
    CHECK(s == HAL_OK && compare(&r) == 0, "after ENODEV: %s: %s", hal_status_str(s), r.d->err);

    /* Another program takes the screen (DRM master): lost until it lets go. */
    fake_drm_set_not_master(r.card, true);
    s = show(&r, "bars", 0.0f, &st);
    CHECK(s == HAL_ERR_NO_DEVICE && strstr(r.d->err, strerror(EACCES)), "master taken: %s: %s", hal_status_str(s),
          r.d->err);
    usleep(30 * 1000);
    s = show(&r, "bars", 0.0f, &st);
    CHECK(s == HAL_ERR_NO_DEVICE && strstr(r.d->err, "holds the screen as DRM master"), "still taken: %s: %s",
          hal_status_str(s), r.d->err);
    fake_drm_set_not_master(r.card, false);
    usleep(30 * 1000);
    s = show(&r, "anim", 0.8f, &st);
    CHECK(s == HAL_OK && compare(&r) == 0, "master back: %s: %s", hal_status_str(s), r.d->err);
    rig_close(&r, true);
}

/* Gone after the connector check (checked once a minute here): the flip's ENODEV is a loss too. */
static void test_gone_at_flip(UMockdevTestbed *tb)
{
    static rig r; /* holds a scene store: too big for a stack */
    rig_defaults(&r);
    r.cfg.probe_ms = 60000;
    if (!rig_start(&r, tb))
        return;
    hal_status s;
    hal_frame_stats st;
    CHECK(show(&r, "demo", 0.0f, &st) == HAL_OK, "first frame: %s", r.d->err);
    fake_drm_set_gone(r.card, true);
    s = show(&r, "bars", 0.0f, &st);
    CHECK(s == HAL_ERR_NO_DEVICE && strstr(r.d->err, "page flip: No such device"), "gone at the flip: %s: %s",
          hal_status_str(s), r.d->err);
    CHECK(!hal_display_connected(r.d) && all_freed(r.card), "after the loss: buffers left");
    fake_drm_set_gone(r.card, false);
    usleep(30 * 1000);
    s = show(&r, "bars", 0.0f, &st);
    CHECK(s == HAL_OK && compare(&r) == 0, "back again: %s: %s", hal_status_str(s), r.d->err);
    rig_close(&r, true);
}

static void test_flip_timeout(UMockdevTestbed *tb)
{
    static rig r; /* holds a scene store: too big for a stack */
    rig_defaults(&r);
    r.cfg.flip_timeout_ms = 50;
    if (!rig_start(&r, tb))
        return;
    hal_status s;
    hal_frame_stats st;
    fake_drm_hold_flips(r.card, true);
    CHECK(show(&r, "anim", 0.0f, &st) == HAL_OK && show(&r, "anim", 0.3f, &st) == HAL_OK, "mode set and a flip");
    s = show(&r, "anim", 0.6f, &st);
    CHECK(s == HAL_ERR_TIMEOUT && strstr(r.d->err, "page flip not completed after 50 ms"), "stuck flip: %s: %s",
          hal_status_str(s), r.d->err);
    s = show(&r, "anim", 0.6f, &st); /* the CRTC is still busy: a frame error, not a crash or a loss */
    CHECK(s == HAL_ERR_IO && strstr(r.d->err, "page flip"), "busy CRTC: %s: %s", hal_status_str(s), r.d->err);
    fake_drm_hold_flips(r.card, false);
    s = show(&r, "anim", 0.9f, &st);
    CHECK(s == HAL_OK && compare(&r) == 0, "after the vblank: %s: %s", hal_status_str(s), r.d->err);
    rig_close(&r, true);
}

static void test_missing(UMockdevTestbed *tb)
{
    kms_config c;
    kms_config_default(&c);
    hal_display *d = NULL;
    char err[320];
    hal_status s = kms_open(&d, &c, &hal_clock_monotonic, conf_log, NULL, err, sizeof err);
    CHECK(s == HAL_ERR_NO_DEVICE && strstr(err, "no DRM card with a connected screen"), "no card: %s: %s",
          hal_status_str(s), err);
    snprintf(c.device, sizeof c.device, "/dev/dri/card5");
    s = kms_open(&d, &c, &hal_clock_monotonic, conf_log, NULL, err, sizeof err);
    CHECK(s == HAL_ERR_NO_DEVICE && strstr(err, "/dev/dri/card5"), "named card absent: %s: %s", hal_status_str(s),
          err);
    static rig r; /* holds a scene store: too big for a stack */
    rig_defaults(&r);
    r.o.disconnected = true;
    s = rig_open(&r, tb, err, sizeof err);
    CHECK(s == HAL_ERR_NO_DEVICE && strstr(err, "no connector has a screen connected"), "nothing connected: %s: %s",
          hal_status_str(s), err);
    rig_close(&r, s == HAL_OK);
}

/* A driver with atomic modesetting: flips are commits whose FB_DAMAGE_CLIPS are the changed bands. */
static void test_atomic(UMockdevTestbed *tb, bool damage_clips)
{
    static rig r; /* holds a scene store: too big for a stack */
    rig_defaults(&r);
    r.o.atomic = true;
    r.o.damage_clips = damage_clips;
    if (!rig_start(&r, tb))
        return;
    hal_status s;
    kms_info info;
    kms_get_info(r.d, &info);
    CHECK(info.atomic == damage_clips, "atomic path %d with damage clips %d", info.atomic, damage_clips);
    hal_frame_stats st;
    uint8_t *before = NULL;
    const float times[] = {0.0f, 0.3f, 0.35f, 0.9f};
    for (int i = 0; i < 4; i++) {
        s = show(&r, "anim", times[i], &st);
        CHECK(s == HAL_OK && compare(&r) == 0, "atomic %d, frame %d: %s: %s", damage_clips, i, hal_status_str(s),
              r.d->err);
        uint8_t *after = expected(&r.scene, 96, 64, DRM_FORMAT_XRGB8888);
        if (before && damage_clips) {
            int want[64], got[128];
            int nwant = diff_bands(before, after, 96, 64, want);
            int ngot = fake_drm_last_clips(r.card, got, 64);
            bool same = ngot == nwant;
            for (int j = 0; same && j < 2 * nwant; j++)
                same = got[j] == want[j];
            CHECK(same, "frame %d: FB_DAMAGE_CLIPS %d bands (first %d..%d), changed lines %d bands (first %d..%d)",
                  i, ngot, ngot ? got[0] : -1, ngot ? got[1] : -1, nwant, want[0], want[1]);
        }
        free(before);
        before = after;
    }
    free(before);
    unsigned atomic = fake_drm_count(r.card, FAKE_DRM_ATOMIC), legacy_flips = fake_drm_count(r.card, FAKE_DRM_FLIP);
    unsigned legacy_sets = fake_drm_count(r.card, FAKE_DRM_SETCRTC);
    if (damage_clips)
        CHECK(atomic == 4 && legacy_flips == 0 && legacy_sets == 0, "atomic commits %u, legacy flips %u, sets %u",
              atomic, legacy_flips, legacy_sets);
    else
        CHECK(atomic == 0 && legacy_flips == 3 && legacy_sets == 1, "no damage property: atomic %u, legacy flips "
              "%u, sets %u", atomic, legacy_flips, legacy_sets);
    kms_get_info(r.d, &info);
    /* each flip's event is taken when the next frame needs its buffer: the last is still unread */
    CHECK(info.flips_done == 2, "%llu flip events handled", (unsigned long long)info.flips_done);
    /* A lost screen and its return go through the same commits. */
    fake_drm_set_connected(r.card, false);
    CHECK(show(&r, "bars", 0.0f, &st) == HAL_ERR_NO_DEVICE, "unplugged: %s", r.d->err);
    fake_drm_set_connected(r.card, true);
    usleep(30 * 1000);
    s = show(&r, "bars", 0.0f, &st);
    CHECK(s == HAL_OK && compare(&r) == 0, "replugged: %s: %s", hal_status_str(s), r.d->err);
    rig_close(&r, true);
}

/* With no card named, the first card with a connected connector is taken. */
static void test_scan(UMockdevTestbed *tb)
{
    static rig a, b; /* a rig holds a scene: two are too big for the stack */
    rig_defaults(&a);
    rig_defaults(&b);
    a.o.disconnected = true;   /* card0: an HDMI port with nothing plugged in */
    b.o.index = 1;             /* card1: the screen, with one mode only */
    b.o.modes[0] = (fake_drm_mode){64, 48, 50, true};
    b.o.nmodes = 1;
    a.card = fake_drm_add(tb, &a.o);
    char err[320];
    hal_status s = rig_open(&b, tb, err, sizeof err);
    CHECK(s == HAL_OK, "scan: %s: %s", hal_status_str(s), err);
    if (s == HAL_OK) {
        kms_info info;
        kms_get_info(b.d, &info);
        CHECK(!strcmp(info.device, "/dev/dri/card1") && info.width == 64 && info.refresh == 50,
              "scan chose %s %dx%d@%d", info.device, info.width, info.height, info.refresh);
        hal_frame_stats st;
        s = show(&b, "demo", 0.0f, &st);
        CHECK(s == HAL_OK && compare(&b) == 0, "card1 frame: %s", b.d->err);
        fake_drm_scanout so;
        CHECK(!fake_drm_get_scanout(a.card, &so), "card0 lit");
    }
    rig_close(&b, s == HAL_OK);
    fake_drm_free(a.card);
}

/* Started with no screen: waiting, then the screen comes. */
static void test_wait(UMockdevTestbed *tb)
{
    static rig r; /* holds a scene store: too big for a stack */
    rig_defaults(&r);
    r.o.disconnected = true;
    r.cfg.wait = true;
    char err[320];
    hal_status s = rig_open(&r, tb, err, sizeof err);
    CHECK(s == HAL_ERR_CONFIG && strstr(err, "need a size"), "waiting without a size: %s: %s", hal_status_str(s),
          err);
    fake_drm_free(r.card);
    kms_parse_mode("96x64", &r.cfg);
    s = rig_open(&r, tb, err, sizeof err);
    CHECK(s == HAL_OK && !hal_display_connected(r.d), "waiting: %s: %s", hal_status_str(s), err);
    if (s != HAL_OK) {
        rig_close(&r, false);
        return;
    }
    hal_frame_stats st;
    s = show(&r, "demo", 0.0f, &st);
    CHECK(s == HAL_ERR_NO_DEVICE && strstr(r.d->err, "no connector has a screen connected"), "no screen: %s: %s",
          hal_status_str(s), r.d->err);
    fake_drm_set_connected(r.card, true);
    usleep(30 * 1000);
    s = show(&r, "demo", 0.0f, &st);
    CHECK(s == HAL_OK && compare(&r) == 0, "the screen came: %s: %s", hal_status_str(s), r.d->err);
    rig_close(&r, true);
}

/* Drivers and situations that must be refused with a reason, not crash. */
static void test_refusals(UMockdevTestbed *tb)
{
    const struct { const char *what; fake_drm_opts o; hal_status want; const char *needle; int w; } cases[] = {
        {"not master", {.modes = {{96, 64, 60, true}}, .nmodes = 1, .not_master = true}, HAL_ERR_NO_DEVICE,
         "holds the screen as DRM master", 0},
        {"short pitch", {.modes = {{96, 64, 60, true}}, .nmodes = 1, .pitch_short = 4}, HAL_ERR_PROTOCOL,
         "dumb buffer of pitch 380", 0},
        {"0x0 preferred", {.modes = {{0, 0, 60, true}, {64, 48, 75, false}}, .nmodes = 2}, HAL_OK, NULL, 64},
        {"too wide preferred", {.modes = {{5000, 100, 60, true}, {64, 48, 75, false}}, .nmodes = 2}, HAL_OK, NULL,
         64},
        {"only unusable modes", {.modes = {{0, 0, 60, true}, {9000, 9000, 30, false}}, .nmodes = 2}, HAL_ERR_CONFIG,
         "offers no usable mode (it has 0x0@60, 9000x9000@30)", 0},
        {"no modes", {.nmodes = 0}, HAL_ERR_CONFIG, "offers no usable mode (it has none)", 0},
        {"plane takes NV12 only", {.modes = {{96, 64, 60, true}}, .nmodes = 1, .plane_formats = {DRM_FORMAT_NV12}},
         HAL_ERR_NO_DEVICE, "the primary plane takes neither XRGB8888 nor RGB565 (it takes NV12)", 0},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        static rig r; /* holds a scene store: too big for a stack */
        rig_defaults(&r);
        r.o = cases[i].o;
        char err[320];
        hal_status s = rig_open(&r, tb, err, sizeof err);
        CHECK(s == cases[i].want && (!cases[i].needle || strstr(err, cases[i].needle)), "%s: %s: %s",
              cases[i].what, hal_status_str(s), err);
        if (s == HAL_OK) {
            hal_frame_stats st;
            CHECK(r.d->width == cases[i].w, "%s: chose width %d", cases[i].what, r.d->width);
            s = show(&r, "demo", 0.0f, &st);
            CHECK(s == HAL_OK && compare(&r) == 0, "%s: frame: %s", cases[i].what, r.d->err);
        } else {
            CHECK(all_freed(r.card), "%s: a refused card kept buffers", cases[i].what);
        }
        rig_close(&r, s == HAL_OK);
    }
}

/*
 * The real celfw with --backend drm on the emulated card: it shows the scene
 * (the buffer on the CRTC equals the core's rendering), keeps running while
 * the screen is unplugged and shows it again once it is back, and gives the
 * CRTC back at SIGTERM. celfw maps the dumb buffers through the preloaded
 * shim/drm_mmap.c (build/host/tests/drm_mmap.so, next to celfw's tests).
 */
static void test_celfw(UMockdevTestbed *tb)
{
    char dir[512], shim[600], preload[1200];
    snprintf(dir, sizeof dir, "%s", celfw_child_path());
    snprintf(shim, sizeof shim, "%s/tests/drm_mmap.so", dirname(dir));
    if (access(shim, R_OK) != 0 || access(celfw_child_path(), X_OK) != 0) {
        CHECK(false, "celfw test: %s or %s missing (make test-linuxhal builds both)", shim, celfw_child_path());
        return;
    }
    static rig r; /* holds a scene store: too big for a stack */
    rig_defaults(&r);
    r.card = fake_drm_add(tb, &r.o);
    const char *old = getenv("LD_PRELOAD");
    char *saved = old ? strdup(old) : NULL;
    snprintf(preload, sizeof preload, "%s%s%s", old ? old : "", old ? " " : "", shim);
    char pid[24];
    snprintf(pid, sizeof pid, "%d", (int)getpid());
    setenv("LD_PRELOAD", preload, 1);
    setenv("FAKE_DRM_PID", pid, 1);
    child c;
    bool ok = spawn(&c, (const char *[]){"--backend", "drm", "--scene", "builtin:demo", "--fps", "30",
                                         "--duration", "20", "--log-interval", "0.2", NULL}, false);
    if (saved)
        setenv("LD_PRELOAD", saved, 1);
    else
        unsetenv("LD_PRELOAD");
    free(saved);
    CHECK(ok, "spawn celfw");
    if (!ok) {
        fake_drm_free(r.card);
        return;
    }
    char line[1024] = "";
    bool started = wait_line(&c, "celfw: start", 10.0, line, sizeof line);
    CHECK(started && strstr(line, "backend=drm display=96x64") && strstr(line, "display_state=up"), "start: %s",
          started ? line : c.log);
    celfw_scene_build("demo", &r.scene, 0.0f);
    usleep(300 * 1000); /* a static scene: after two frames nothing is written or flipped */
    int bad = compare(&r);
    CHECK(bad == 0, "celfw's frame differs from the core's rendering in %d pixels", bad);

    fake_drm_set_connected(r.card, false);
    CHECK(wait_line(&c, "display lost: drm: screen lost: connector HDMI-A-1 reports no screen connected", 5.0,
                    line, sizeof line), "celfw reports the unplugged screen: %s", c.log);
    CHECK(wait_line(&c, "celfw: status", 5.0, line, sizeof line) && strstr(line, "display=absent"),
          "celfw runs on without the screen: %s", line);
    fake_drm_set_connected(r.card, true);
    CHECK(wait_line(&c, "drm: screen connected: /dev/dri/card0 connector HDMI-A-1, 96x64@60", 5.0, line,
                    sizeof line), "celfw reconnects: %s", c.log);
    usleep(300 * 1000);
    bad = compare(&r);
    CHECK(bad == 0, "after the replug celfw's frame differs in %d pixels", bad);
    kill(c.pid, SIGTERM);
    int rc = wait_exit(&c, 10.0);
    CHECK(rc == 0 && strstr(c.log, "reason=signal"), "celfw exit %d: %s", rc, c.log);
    fake_drm_scanout so;
    CHECK(all_freed(r.card) && !fake_drm_get_scanout(r.card, &so), "celfw left buffers or a lit CRTC");
    fake_drm_free(r.card);
}

/* What the CRTC scans out, for the conformance case. */
static bool drm_shown(void *user, uint8_t *frame)
{
    rig *r = user;
    fake_drm_scanout so;
    if (!fake_drm_get_scanout(r->card, &so))
        return false;
    size_t lb = hal_line_bytes(r->d->pixfmt, r->d->width);
    for (int y = 0; y < r->d->height; y++)
        memcpy(frame + (size_t)y * lb, so.pixels + (size_t)y * so.pitch, lb);
    return true;
}

/* The conformance case every backend passes, in XRGB8888 and RGB565; then a card gone. */
static void test_conformance(UMockdevTestbed *tb)
{
    for (int k = 0; k < 2; k++) {
        static rig r; /* holds a scene store: too big for a stack */
        rig_defaults(&r);
        if (k)
            r.o.preferred_depth = 16;
        if (!rig_start(&r, tb))
            return;
        conf_backend b = {.d = r.d, .shown = drm_shown, .user = &r};
        const char *name = k ? "drm RGB565" : "drm XRGB8888";
        CHECK(r.d->pixfmt == (k ? CS_PIX_RGB565_SRGB : HAL_PIX_XRGB8888), "%s: format %#x", name, r.d->pixfmt);
        conf_frames(&b, name);
        conf_geometry_error(&b, name);
        fake_drm_set_gone(r.card, true);
        hal_frame_stats st;
        hal_status s = show(&r, "demo", 0.0f, &st);
        CHECK(conf_error_is(r.d, s, HAL_ERR_NO_DEVICE, strerror(ENODEV)), "%s: card gone: %s: %s", name,
              hal_status_str(s), r.d->err);
        fake_drm_set_gone(r.card, false);
        rig_close(&r, true);
    }
}

int main(void)
{
    UMockdevTestbed *tb = umockdev_testbed_new();
    if (!umockdev_in_mock_environment()) {
        fprintf(stderr, "test_drm: run under umockdev-wrapper (LD_PRELOAD=libumockdev-preload.so)\n");
        return 2;
    }
    test_frames(tb);
    test_modes(tb);
    test_rgb565(tb, false);
    test_rgb565(tb, true);
    test_no_flips(tb, true);
    test_no_flips(tb, false);
    test_unplug(tb);
    test_gone_at_flip(tb);
    test_flip_timeout(tb);
    test_missing(tb);
    test_wait(tb);
    test_scan(tb);
    test_atomic(tb, true);
    test_damage_window(tb, false, false);
    test_damage_window(tb, true, false);
    test_damage_window(tb, false, true);
    test_atomic(tb, false);
    test_refusals(tb);
    test_conformance(tb);
    test_celfw(tb);
    g_object_unref(tb);
    return tl_summary("test_drm");
}
