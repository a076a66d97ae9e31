/*
 * display_template.c - a commented display backend (display_template.h).
 *
 * What each operation must do, for any panel:
 *  - begin_frame: get the panel ready for a frame, or for a window of it.
 *    Check the window; a backend that cannot narrow its writes refuses one
 *    with HAL_ERR_CONFIG. An empty window is a frame where nothing changed. A panel that can be absent (USB, HDMI) reconnects
 *    here and returns HAL_ERR_NO_DEVICE, cheaply, while it is away.
 *  - line_out: put one row, already in d->pixfmt, where the panel shows it.
 *    Rows come in increasing order and only inside the frame's window; a
 *    call out of order is the caller's bug: HAL_ERR_SEQUENCE.
 *  - end_frame: make the frame visible (flush, flip, latch) and report what
 *    failed.
 * Every failure goes through hal_display_fail, which writes "name: what" into
 * d->err: say what and where (the row, the window, the device's answer).
 * Leave out what the panel does not need: NULL operations succeed.
 */
#include <string.h>

#include "display_template.h"

static hal_status tpl_begin_frame(hal_display *d, const hal_window *win)
{
    tpl_display *t = (tpl_display *)d;
    hal_window all = {0, 0, d->width, d->height};
    if (win && !hal_window_inside(win, d->width, d->height))
        return hal_display_fail(d, HAL_ERR_CONFIG, "window %d,%d..%d,%d is not inside %dx%d", win->x0,
                                win->y0, win->x1, win->y1, d->width, d->height);
    t->win = win ? *win : all;
    if (t->win.x0 == t->win.x1)
        t->win.y1 = t->win.y0; /* an empty window: nothing changed, no row may come */
    t->next_y = t->win.y0;
    t->in_frame = true;
    return HAL_OK;
}

static hal_status tpl_line_out(hal_display *d, int y, const uint8_t *px, size_t len)
{
    tpl_display *t = (tpl_display *)d;
    size_t want = hal_line_bytes(d->pixfmt, t->win.x1 - t->win.x0);
    if (!t->in_frame || y < t->next_y || y >= t->win.y1 || len != want)
        return hal_display_fail(d, HAL_ERR_SEQUENCE, "line %d of %zu bytes: the frame takes rows %d..%d of %zu",
                                y, len, t->next_y, t->win.y1 - 1, want);
    /* Your panel's bus write goes here (SPI, 8080, DMA): this one is memory. */
    memcpy(t->cfg->fb + (size_t)y * t->cfg->pitch + hal_line_bytes(d->pixfmt, t->win.x0), px, len);
    t->next_y = y + 1;
    return HAL_OK;
}

static hal_status tpl_end_frame(hal_display *d)
{
    tpl_display *t = (tpl_display *)d;
    t->in_frame = false;
    const tpl_config *c = t->cfg;
    if (c->flush && !c->flush(c->flush_user, &t->win))
        return hal_display_fail(d, HAL_ERR_IO, "flushing rows %d..%d failed", t->win.y0, t->win.y1 - 1);
    return HAL_OK;
}

/* In ROM; connected and close are left out: this panel is always there and
 * holds nothing to free. */
static const hal_display_api tpl_api = {
    .name = "template",
    .begin_frame = tpl_begin_frame,
    .line_out = tpl_line_out,
    .end_frame = tpl_end_frame,
};

hal_status tpl_open(tpl_display *t, const tpl_config *cfg, const hal_clock *clock)
{
    memset(t, 0, sizeof *t);
    t->d.api = &tpl_api;
    t->d.clock = clock;
    t->cfg = cfg;
    size_t line = hal_line_bytes(cfg->pixfmt, cfg->width);
    if (cfg->width <= 0 || cfg->height <= 0 || line == 0 || !cfg->fb || cfg->pitch < line)
        return hal_display_fail(&t->d, HAL_ERR_CONFIG, "%dx%d in format %d with a pitch of %zu bytes",
                                cfg->width, cfg->height, cfg->pixfmt, cfg->pitch);
    t->d.width = cfg->width;
    t->d.height = cfg->height;
    t->d.pixfmt = cfg->pixfmt;
    return HAL_OK;
}
