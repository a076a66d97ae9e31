/*
 * display_conformance.h - the conformance case every display backend passes.
 *
 * A backend is driven only through the contract of hal/display.h (the frame
 * driver hal_display_present, fed by the same hal_source celfw uses), with
 * the same scenes and frames, and what it then shows is read back by the
 * test's own means (the sim's memory, an emulated USB display's panel, an
 * emulated DRM card's scanout buffer, a HUB75 panel model fed by an
 * emulated GPIO chip). Its CRC-32 must equal the CRC of the core's own
 * render (one in-order pass of cs_render_line) put in the backend's format:
 * in the panel format that is exactly `celsim --crc`, which
 * test_display_conformance checks against the celsim program itself.
 * Errors are reported the same way by every backend: a source of another
 * size is HAL_ERR_CONFIG, a device gone is HAL_ERR_NO_DEVICE, a failed
 * write HAL_ERR_IO, each with a message in d->err that starts with the
 * backend's name and a colon.
 *
 * Header-only, like testlib.h (its CHECKs count into the including
 * program): a test program includes it once, after testlib.h, and calls
 * conf_frames and conf_geometry_error with a conf_backend describing its
 * backend. The scenes are read from scenes/ (tests run from the top folder).
 */
#ifndef DISPLAY_CONFORMANCE_H
#define DISPLAY_CONFORMANCE_H

#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celscan.h"
#include "display.h"
#include "lx_scene_source.h"
#include "scene_json.h"
#include "testlib.h"

#define CONF_SUBSCANLINES 4 /* the sources' and the reference's anti-aliasing */

/* The conformance frames: scene files and times (every backend shows them all). */
typedef struct conf_frame {
    const char *scene;
    float time;
} conf_frame;

static const conf_frame conf_frame_list[] = {
    {"scenes/demo.json", 0.0f},
    {"scenes/demo.json", 1.5f},
    {"scenes/beta-stack.json", 0.0f},
    {"scenes/motion.json", 0.75f},
};
#define CONF_NFRAMES ((int)(sizeof conf_frame_list / sizeof conf_frame_list[0]))

/* Puts width pixels of linear floats in the backend's shown layout at dst. */
typedef void (*conf_encode_fn)(const void *user, const float *rgb, int width, uint8_t *dst);

typedef struct conf_backend {
    hal_display *d;
    size_t line_bytes;        /* bytes of a shown line (0: hal_line_bytes of d->pixfmt) */
    conf_encode_fn encode;    /* NULL: hal_pixfmt_convert to d->pixfmt */
    const void *encode_user;
    /* Copies what the display shows now (d->height lines of line_bytes) to
     * frame; false if it cannot be read. NULL: a display that shows nothing,
     * whose frames are only counted. */
    bool (*shown)(void *user, uint8_t *frame);
    void *user;
} conf_backend;

static TL_UNUSED size_t conf_line_bytes(const conf_backend *b)
{
    return b->line_bytes ? b->line_bytes : hal_line_bytes(b->d->pixfmt, b->d->width);
}

/*
 * The truth, whole: the scene at time t rendered in one in-order pass of the
 * core and encoded as the backend shows it, h rows of line_bytes (malloc'd,
 * the caller frees it); NULL if it cannot be made. The backends' own tests
 * compare their devices' pictures with it too.
 */
static TL_UNUSED uint8_t *conf_reference_image(const cs_scene *s, float t, int w, int h, size_t line_bytes,
                                               conf_encode_fn encode, const void *user)
{
    static cs_workspace ws;
    cs_render_opts o = cs_render_defaults(w, h);
    o.aa = CS_AA_SUBSCAN;
    o.subscanlines = CONF_SUBSCANLINES;
    o.blend = CS_BLEND_LINEAR;
    o.time = t;
    cs_renderer r;
    cs_error e;
    float *rgb = calloc((size_t)w * 3u, sizeof *rgb);
    uint8_t *px = calloc(line_bytes + 4u, 1), *img = malloc(line_bytes * (size_t)h);
    if (rgb && px && img && cs_frame_begin(&r, &ws, s, &o, &e) == CS_OK) {
        for (int y = 0; y < h; y++) {
            cs_render_line(&r, y, rgb);
            encode(user, rgb, w, px); /* px has room for an encoder that writes a little past the line */
            memcpy(img + (size_t)y * line_bytes, px, line_bytes);
        }
    } else {
        free(img);
        img = NULL;
    }
    free(rgb);
    free(px);
    return img;
}

/* CRC-32 of conf_reference_image (0xFFFFFFFF, which matches no shown frame, if it cannot be made). */
static TL_UNUSED uint32_t conf_reference_crc(const cs_scene *s, float t, int w, int h, size_t line_bytes,
                                             conf_encode_fn encode, const void *user)
{
    uint8_t *img = conf_reference_image(s, t, w, h, line_bytes, encode, user);
    uint32_t crc = img ? cs_crc32(0, img, line_bytes * (size_t)h) : 0xFFFFFFFFu;
    free(img);
    return crc;
}

/*
 * user points to a hal_pixfmt. XRGB8888 is made here from the core's RGB888
 * as the little-endian word 0x00RRGGBB, pixel by pixel, not by
 * hal_pixfmt_convert (which is under test).
 */
static TL_UNUSED void conf_encode_fmt(const void *user, const float *rgb, int width, uint8_t *dst)
{
    hal_pixfmt fmt = *(const hal_pixfmt *)user;
    if (fmt != HAL_PIX_XRGB8888) {
        cs_pixfmt_convert((cs_pixfmt)fmt, rgb, width, dst);
        return;
    }
    for (int x = 0; x < width; x++) {
        uint8_t c[3];
        cs_pixfmt_convert(CS_PIX_RGB888_SRGB, rgb + 3 * x, 1, c);
        uint32_t v = (uint32_t)c[0] << 16 | (uint32_t)c[1] << 8 | c[2];
        for (int b = 0; b < 4; b++)
            dst[4 * x + b] = (uint8_t)(v >> (8 * b));
    }
}

/* The log of a backend under test (a hal_log_fn): its messages on stderr, indented. */
static TL_UNUSED __attribute__((format(printf, 2, 3))) void conf_log(void *user, const char *fmt, ...)
{
    (void)user;
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "  [log] ");
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

/* Loads a conformance scene; false (with a CHECK failed) if it cannot. */
static TL_UNUSED bool conf_load(const char *path, cs_scene *s)
{
    char err[256];
    return CHECK(scene_json_load(path, s, err, sizeof err) == 0, "load %s: %s", path, err);
}

/* The reference CRC of the scene at time t as backend b shows it. */
static TL_UNUSED uint32_t conf_backend_crc(const conf_backend *b, const cs_scene *s, float t)
{
    hal_pixfmt fmt = b->d->pixfmt;
    return conf_reference_crc(s, t, b->d->width, b->d->height, conf_line_bytes(b),
                              b->encode ? b->encode : conf_encode_fmt, b->encode ? b->encode_user : &fmt);
}

/*
 * Shows every conformance frame through hal_display_present and compares
 * what the display shows with the core's render: one CHECK per frame (and
 * one for the source). `name` labels the messages.
 */
static TL_UNUSED void conf_frames(const conf_backend *b, const char *name)
{
    hal_display *d = b->d;
    size_t lb = conf_line_bytes(b);
    lx_scene_source src;
    if (!CHECK(lx_scene_source_init(&src, d->width, d->height, CS_AA_SUBSCAN, CONF_SUBSCANLINES) == HAL_OK,
               "%s: conformance source of %dx%d", name, d->width, d->height))
        return;
    uint8_t *frame = malloc(lb * (size_t)d->height);
    static cs_scene scene;
    for (int i = 0; i < CONF_NFRAMES; i++) {
        const conf_frame *f = &conf_frame_list[i];
        if (!conf_load(f->scene, &scene))
            continue;
        lx_scene_source_set(&src, &scene, f->time);
        hal_frame_stats st = {0};
        hal_status s = hal_display_present(d, &src.src, &st);
        lx_scene_source_end(&src);
        uint32_t want = conf_backend_crc(b, &scene, f->time);
        if (!b->shown) {
            CHECK(s == HAL_OK && st.lines_rendered == (uint64_t)d->height,
                  "%s: %s at t=%g: %s, %llu of %d lines taken", name, f->scene, (double)f->time,
                  hal_status_str(s), (unsigned long long)st.lines_rendered, d->height);
            continue;
        }
        bool read = s == HAL_OK && frame && b->shown(b->user, frame);
        uint32_t got = read ? cs_crc32(0, frame, lb * (size_t)d->height) : 0;
        CHECK(read && got == want, "%s: %s at t=%g %dx%d: shown crc32 %08X, the core's %08X (%s: %s)", name,
              f->scene, (double)f->time, d->width, d->height, (unsigned)got, (unsigned)want,
              hal_status_str(s), s == HAL_OK ? "" : d->err);
    }
    free(frame);
    lx_scene_source_free(&src);
}

/* status is want and d->err is "NAME: ..." containing needle (if given). */
static TL_UNUSED bool conf_error_is(const hal_display *d, hal_status status, hal_status want,
                                    const char *needle)
{
    size_t n = strlen(d->api->name);
    return status == want && strncmp(d->err, d->api->name, n) == 0 && d->err[n] == ':' &&
           (!needle || strstr(d->err, needle));
}

/* A source one pixel wider than the display: HAL_ERR_CONFIG naming both sizes, nothing shown. */
static TL_UNUSED void conf_geometry_error(const conf_backend *b, const char *name)
{
    hal_display *d = b->d;
    lx_scene_source src;
    if (!CHECK(lx_scene_source_init(&src, d->width + 1, d->height, CS_AA_SUBSCAN, CONF_SUBSCANLINES) == HAL_OK,
               "%s: source", name))
        return;
    static cs_scene scene;
    if (conf_load(conf_frame_list[0].scene, &scene)) {
        lx_scene_source_set(&src, &scene, 0.0f);
        hal_frame_stats st = {0};
        hal_status s = hal_display_present(d, &src.src, &st);
        char size[32];
        snprintf(size, sizeof size, "%dx%d", d->width + 1, d->height);
        CHECK(conf_error_is(d, s, HAL_ERR_CONFIG, size) && st.lines_rendered == 0,
              "%s: a %s source: %s: %s (%llu lines)", name, size, hal_status_str(s), d->err,
              (unsigned long long)st.lines_rendered);
    }
    lx_scene_source_free(&src);
}

/*
 * A write that fails for good: fail(user) makes the device fail the next
 * frame's writes (past the backend's retries, where it has them). That frame
 * ends in HAL_ERR_IO with a "name: ..." message containing needle; the next
 * frame goes, and the display then shows the core's render (conformance
 * frames 0 and 1 differ, so a backend that sends only changed lines writes).
 */
static TL_UNUSED void conf_failed_write(const conf_backend *b, const char *name, void (*fail)(void *user),
                                        const char *needle)
{
    hal_display *d = b->d;
    size_t lb = conf_line_bytes(b);
    lx_scene_source src;
    if (!CHECK(lx_scene_source_init(&src, d->width, d->height, CS_AA_SUBSCAN, CONF_SUBSCANLINES) == HAL_OK,
               "%s: source", name))
        return;
    static cs_scene scene;
    uint8_t *frame = malloc(lb * (size_t)d->height);
    const conf_frame *f = &conf_frame_list[1];
    if (frame && conf_load(f->scene, &scene)) {
        hal_status s[3];
        hal_frame_stats st = {0};
        for (int i = 0; i < 3; i++) {
            if (i == 1)
                fail(b->user);
            lx_scene_source_set(&src, &scene, i ? f->time : conf_frame_list[0].time);
            s[i] = hal_display_present(d, &src.src, &st);
            lx_scene_source_end(&src);
            if (i == 1) {
                CHECK(conf_error_is(d, s[1], HAL_ERR_IO, needle), "%s: a failed write: %s: %s", name,
                      hal_status_str(s[1]), d->err);
                b->shown(b->user, frame); /* what the failed frame left: any part of it, not checked */
            }
        }
        uint32_t want = conf_backend_crc(b, &scene, f->time);
        bool read = s[2] == HAL_OK && b->shown(b->user, frame);
        CHECK(s[0] == HAL_OK && read && cs_crc32(0, frame, lb * (size_t)d->height) == want,
              "%s: the frames around the failed write: %s, %s (shown %s the core's)", name,
              hal_status_str(s[0]), hal_status_str(s[2]), read ? "differs from" : "unread, not");
    }
    free(frame);
    lx_scene_source_free(&src);
}

/*
 * A frame limited to win, with every other row of it sent (rows may be
 * skipped), row y's bytes all 0x30 + y % 16: exactly those rows' window
 * columns change, to what was sent, and nothing else, which holds for a
 * panel that keeps its picture and shows lines in its own format (no
 * encode). Returns the number of rows sent (0 if the frame failed).
 */
static TL_UNUSED int conf_window(const conf_backend *b, const char *name, hal_window win)
{
    hal_display *d = b->d;
    size_t lb = conf_line_bytes(b), n = lb * (size_t)d->height;
    size_t xa = hal_line_bytes(d->pixfmt, win.x0), wb = hal_line_bytes(d->pixfmt, win.x1 - win.x0);
    uint8_t *before = malloc(n), *after = malloc(n), *line = malloc(wb);
    int rows = 0;
    if (!CHECK(before && after && line && b->shown(b->user, before), "%s: the picture before the window", name))
        goto out;
    hal_status s = hal_display_begin_frame(d, &win);
    for (int y = win.y0; y < win.y1 && s == HAL_OK; y += 2, rows++) {
        memset(line, 0x30 + y % 16, wb);
        s = hal_display_line_out(d, y, line, wb);
    }
    if (s == HAL_OK)
        s = hal_display_end_frame(d);
    long wrong = 0;
    if (s == HAL_OK && b->shown(b->user, after))
        for (int y = 0; y < d->height; y++)
            for (size_t x = 0; x < lb; x++) {
                size_t i = (size_t)y * lb + x;
                bool in = y >= win.y0 && y < win.y1 && (y - win.y0) % 2 == 0 && x >= xa && x < xa + wb;
                wrong += after[i] != (in ? 0x30 + y % 16 : before[i]);
            }
    if (!CHECK(s == HAL_OK && wrong == 0, "%s: window %d,%d..%d,%d: %ld wrong bytes (%s: %s)", name, win.x0,
               win.y0, win.x1, win.y1, wrong, hal_status_str(s), d->err))
        rows = 0;
out:
    free(before);
    free(after);
    free(line);
    return rows;
}

#endif /* DISPLAY_CONFORMANCE_H */
