/*
 * display_host.c - what every host display backend shares (display.h): the
 * status words, the one formatter of error messages and log lines ("name:
 * message", so no backend formats its own), pixel conversion including the
 * XRGB8888 layout the core lacks, and the frame driver that shows a
 * hal_source on any backend, push or pull. Deadline accounting lives here
 * once, not in each backend, and so do the push lane's two line buffers:
 * they belong to the display (d->lines, kept from frame to frame and freed
 * by hal_display_close), so showing a frame allocates nothing.
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "display.h"

const char *hal_status_str(hal_status st)
{
    switch (st) {
    case HAL_OK: return "ok";
    case HAL_ERR_CONFIG: return "bad configuration";
    case HAL_ERR_NO_DEVICE: return "device absent";
    case HAL_ERR_IO: return "I/O error";
    case HAL_ERR_TIMEOUT: return "timed out";
    case HAL_ERR_PROTOCOL: return "protocol error";
    case HAL_ERR_RENDER: return "render error";
    case HAL_ERR_NOMEM: return "out of memory";
    case HAL_ERR_SEQUENCE: return "call out of sequence";
    }
    return "unknown status";
}

size_t hal_line_bytes(hal_pixfmt fmt, int width)
{
    if (width < 0)
        return 0;
    size_t bpp = fmt == HAL_PIX_XRGB8888 ? 4u : cs_pixfmt_bytes_per_pixel((cs_pixfmt)fmt);
    return bpp * (size_t)width;
}

/*
 * XRGB8888: the line is converted to RGB888 in the destination itself and
 * then spread to four bytes a pixel from the right end, so no scratch line is
 * needed: pixel x's three source bytes start at 3x, its four at 4x >= 3x, and
 * every pixel to its right was already moved.
 */
void hal_pixfmt_convert(hal_pixfmt fmt, const float *rgb, int width, uint8_t *dst)
{
    if (fmt != HAL_PIX_XRGB8888) {
        cs_pixfmt_convert((cs_pixfmt)fmt, rgb, width, dst);
        return;
    }
    cs_pixfmt_convert(CS_PIX_RGB888_SRGB, rgb, width, dst);
    for (int x = width - 1; x >= 0; x--) {
        uint8_t r = dst[3 * x], g = dst[3 * x + 1], b = dst[3 * x + 2];
        dst[4 * x] = b;
        dst[4 * x + 1] = g;
        dst[4 * x + 2] = r;
        dst[4 * x + 3] = 0;
    }
}

hal_status hal_display_fail(hal_display *d, hal_status st, const char *fmt, ...)
{
    int n = snprintf(d->err, sizeof d->err, "%s: ", d->api->name);
    if (n < 0 || (size_t)n >= sizeof d->err)
        return st;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(d->err + n, sizeof d->err - (size_t)n, fmt, ap);
    va_end(ap);
    return st;
}

void hal_display_say(const hal_display *d, const char *fmt, ...)
{
    if (!d->log)
        return;
    char msg[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    d->log(d->log_user, "%s: %s", d->api->name, msg);
}

/* The push lane's line buffers: a line of floats and one in the display's format. */
struct hal_push_lines {
    int width;
    hal_pixfmt pixfmt;
    float *rgb;
    uint8_t *px;
};

static void free_lines(hal_display *d)
{
    if (d->lines) {
        free(d->lines->rgb);
        free(d->lines->px);
        free(d->lines);
        d->lines = NULL;
    }
}

/* d->lines for d's width and format: kept from frame to frame, so a frame
 * allocates nothing; made again only when a hot-plugged display changed. */
static hal_status push_lines(hal_display *d)
{
    if (d->lines && d->lines->width == d->width && d->lines->pixfmt == d->pixfmt)
        return HAL_OK;
    free_lines(d);
    struct hal_push_lines *l = calloc(1, sizeof *l);
    if (l) {
        l->rgb = malloc((size_t)d->width * 3u * sizeof *l->rgb);
        l->px = malloc(hal_line_bytes(d->pixfmt, d->width) + 4u);
        l->width = d->width;
        l->pixfmt = d->pixfmt;
        d->lines = l;
    }
    if (!l || !l->rgb || !l->px) {
        free_lines(d);
        return hal_display_fail(d, HAL_ERR_NOMEM, "no line buffer for a width of %d", d->width);
    }
    return HAL_OK;
}

/* The push lane: the window's lines rendered, converted and handed to line_out. */
static hal_status push_frame(hal_display *d, const hal_source *src, hal_frame_stats *st,
                             const hal_window *w)
{
    int cols = w->x1 - w->x0;
    if (cols <= 0 || w->y1 <= w->y0)
        return hal_display_end_frame(d); /* nothing changed: nothing is rendered */
    hal_status s = push_lines(d);
    if (s != HAL_OK)
        return s;
    float *rgb = d->lines->rgb;
    uint8_t *px = d->lines->px;
    size_t len = hal_line_bytes(d->pixfmt, cols);
    s = src->begin(src->user, 1);
    if (s != HAL_OK)
        return hal_display_fail(d, s, "the renderer could not start the frame");
    for (int y = w->y0; y < w->y1; y++) {
        if ((s = src->line(src->user, 0, y, rgb)) != HAL_OK)
            return hal_display_fail(d, s, "the renderer failed on line %d", y);
        st->lines_rendered++;
        st->pixels_rendered += (uint64_t)cols;
        uint8_t *out = hal_display_line_buffer(d, y, len); /* in place, where lent */
        if (out == NULL)
            out = px;
        hal_pixfmt_convert(d->pixfmt, rgb, cols, out);
        if ((s = d->api->line_out(d, y, out, len)) != HAL_OK)
            return s;
        if (d->frame_period_ns && d->clock) {
            uint64_t due = d->frame_start_ns + (uint64_t)(y + 1) * d->frame_period_ns / (uint64_t)d->height;
            if (hal_now(d->clock) > due)
                st->line_misses++;
        }
    }
    return hal_display_end_frame(d);
}

/* Whether w lies within d and leaves part of it out. */
static bool window_narrows(const hal_display *d, const hal_window *w)
{
    return hal_window_inside(w, d->width, d->height) &&
           (w->x0 > 0 || w->y0 > 0 || w->x1 < d->width || w->y1 < d->height);
}

hal_status hal_display_present(hal_display *d, const hal_source *src, hal_frame_stats *st)
{
    return hal_display_present_window(d, src, NULL, st);
}

/*
 * A window the backend refuses (HAL_ERR_CONFIG) or that does not fit the
 * display (a hot-plugged one changed) becomes a whole frame: a whole frame
 * is always right, a window only while the display holds the last frame.
 */
hal_status hal_display_present_window(hal_display *d, const hal_source *src, hal_window *win,
                                      hal_frame_stats *st)
{
    bool narrow = win && src->window && !d->api->present && window_narrows(d, win);
    hal_status s = HAL_OK;
    d->st = st;
    /* Backends add their counts (rectangles, bytes) to *d->st during the frame.
     * begin_frame first: a display that was away learns its size there (a
     * backend that is away refuses a window, so it reconnects below). */
    if (narrow && (s = hal_display_begin_frame(d, win)) == HAL_ERR_CONFIG) {
        narrow = false;
        s = HAL_OK;
    }
    bool empty = narrow && (win->x0 == win->x1 || win->y0 == win->y1); /* renders nothing */
    if (s == HAL_OK && src->window && !empty && (s = src->window(src->user, narrow ? win : NULL)) != HAL_OK)
        s = hal_display_fail(d, s, "the renderer cannot take the window");
    if (s == HAL_OK && d->api->present) {
        d->st = NULL;
        if (win)
            *win = (hal_window){0, 0, d->width, d->height};
        return d->api->present(d, src, st);
    }
    if (s == HAL_OK && !narrow) {
        s = hal_display_begin_frame(d, NULL);
        if (win)
            *win = (hal_window){0, 0, d->width, d->height};
    }
    if (s == HAL_OK && (src->width != d->width || src->height != d->height))
        s = hal_display_fail(d, HAL_ERR_CONFIG, "source is %dx%d, %s %dx%d", src->width, src->height,
                             d->api->noun ? d->api->noun : "the display", d->width, d->height);
    hal_window whole = {0, 0, d->width, d->height};
    if (s == HAL_OK)
        s = push_frame(d, src, st, narrow ? win : &whole);
    d->st = NULL;
    return s;
}

void hal_display_close(hal_display *d)
{
    if (!d)
        return;
    free_lines(d);
    if (d->api->close)
        d->api->close(d);
}
