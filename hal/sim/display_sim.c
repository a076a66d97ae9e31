/*
 * display_sim.c - the in-memory display backend (see display_sim.h).
 *
 * It is deliberately strict: a real panel that latches lines as they arrive
 * shows garbage if a driver sends rows twice, out of order or outside a
 * frame, so the simulator rejects those calls instead of quietly storing
 * them, and the bug shows up on the host first.
 */
#include <string.h>

#include "sim/display_sim.h"

static hal_status sim_begin_frame(hal_display *d, const hal_window *win)
{
    sim_display *s = (sim_display *)d;
    /* A frame begun inside a frame abandons that one (display.h): its rows
     * already written stay, as on glass, and it is never reported whole. */
    hal_window all = {0, 0, d->width, d->height};
    if (win && !hal_window_inside(win, d->width, d->height))
        return hal_display_fail(d, HAL_ERR_CONFIG, "window %d,%d..%d,%d is not inside %dx%d", win->x0,
                                win->y0, win->x1, win->y1, d->width, d->height);
    s->win = win ? *win : all;
    if (s->win.x0 == s->win.x1)
        s->win.y1 = s->win.y0; /* an empty window: nothing changed, no row may come */
    s->in_frame = 1;
    s->next_y = s->win.y0;
    s->rows_written = 0;
    return HAL_OK;
}

/* Where row y of the current frame lies in the image: its window's columns. */
static uint8_t *sim_row_at(sim_display *s, int y)
{
    return s->image + (size_t)y * s->line_bytes + hal_line_bytes(s->d.pixfmt, s->win.x0);
}

/* Lends row y of the image only where line_out would take it next: inside a
 * frame, inside the window, not behind a row sent, at the window's length. */
static uint8_t *sim_line_buffer(hal_display *d, int y, size_t len)
{
    sim_display *s = (sim_display *)d;
    if (!s->in_frame || y < s->next_y || y >= s->win.y1 ||
        len != hal_line_bytes(d->pixfmt, s->win.x1 - s->win.x0))
        return NULL;
    return sim_row_at(s, y);
}

static hal_status sim_line_out(hal_display *d, int y, const uint8_t *px, size_t len)
{
    sim_display *s = (sim_display *)d;
    if (!s->in_frame)
        return hal_display_fail(d, HAL_ERR_SEQUENCE, "line %d outside a frame", y);
    size_t want = hal_line_bytes(d->pixfmt, s->win.x1 - s->win.x0);
    if (px == NULL || len != want || y < s->win.y0 || y >= s->win.y1)
        return hal_display_fail(d, HAL_ERR_CONFIG, "line %d of %zu bytes: the frame takes rows %d..%d of %zu",
                                y, len, s->win.y0, s->win.y1 - 1, want);
    /* Rows may be skipped (the core allows it) but never revisited. */
    if (y < s->next_y)
        return hal_display_fail(d, HAL_ERR_SEQUENCE, "line %d after line %d", y, s->next_y - 1);
    /* A row rendered in place (sim_line_buffer) is there already. */
    uint8_t *row = sim_row_at(s, y);
    if (px != row)
        memcpy(row, px, len);
    s->next_y = y + 1;
    s->rows_written++;
    return HAL_OK;
}

static hal_status sim_end_frame(hal_display *d)
{
    sim_display *s = (sim_display *)d;
    if (!s->in_frame)
        return hal_display_fail(d, HAL_ERR_SEQUENCE, "a frame ends outside a frame");
    s->in_frame = 0;
    /* A partial frame would leave stale rows from the last one on the glass. */
    if (s->rows_written != s->win.y1 - s->win.y0)
        return hal_display_fail(d, HAL_ERR_IO, "the frame ended with %d of its %d rows", s->rows_written,
                                s->win.y1 - s->win.y0);
    s->frames_done++;
    return HAL_OK;
}

static const hal_display_api sim_display_api = {
    .name = "sim",
    .begin_frame = sim_begin_frame,
    .line_out = sim_line_out,
    .line_buffer = sim_line_buffer,
    .end_frame = sim_end_frame,
};

size_t sim_display_image_bytes(int width, int height, cs_pixfmt fmt)
{
    if (width <= 0 || height <= 0)
        return 0;
    size_t bpp = cs_pixfmt_bytes_per_pixel(fmt);
    if (bpp == 0)
        return 0;
    size_t w = (size_t)width, h = (size_t)height;
    if (w > SIZE_MAX / bpp || w * bpp > SIZE_MAX / h)
        return 0;
    return w * bpp * h;
}

hal_status sim_display_init(sim_display *s, int width, int height, cs_pixfmt fmt, uint8_t *image,
                            size_t image_len)
{
    size_t need = sim_display_image_bytes(width, height, fmt);
    memset(s, 0, sizeof *s);
    s->d.api = &sim_display_api;
    s->d.width = width;
    s->d.height = height;
    s->d.pixfmt = fmt;
    if (image == NULL || need == 0 || image_len < need)
        return hal_display_fail(&s->d, HAL_ERR_CONFIG, "cannot show %dx%d in format %d with %zu bytes", width,
                                height, (int)fmt, image_len);
    memset(image, 0, need);
    s->image = image;
    s->line_bytes = need / (size_t)height;
    return HAL_OK;
}

const uint8_t *sim_display_row(const sim_display *s, int y)
{
    if (y < 0 || y >= s->d.height)
        return NULL;
    return s->image + (size_t)y * s->line_bytes;
}
