/*
 * frame_drive.c - core lines to HAL display lines (see frame_drive.h).
 *
 * Begin and end frame are optional display operations; the wrappers in
 * display.h make an absent one succeed.
 */
#include <string.h>

#include "frame_drive.h"

static size_t panel_bytes(const frame_drive *d)
{
    return (size_t)d->dev->width * cs_pixfmt_bytes_per_pixel(CS_PANEL_PIXFMT);
}

/* Line y, converted to display bytes (and panel pixels to hash, if any), to the display. */
static cs_status show_line(frame_drive *d, int y, const uint8_t *bytes, const uint8_t *panel)
{
    if (panel != NULL)
        d->crc = cs_crc32(d->crc, panel, panel_bytes(d));
    hal_status hs = hal_display_line_out(d->dev, y, bytes, d->line_bytes);
    if (hs != HAL_OK) {
        d->hal_st = hs;
        d->hal_y = y;
        /* Any refusal stops the frame; dev->err says why. */
        return CS_ERR_IO;
    }
    return CS_OK;
}

/* Line y of the display, row `row` of the frame, rendered and shown: its
 * display bytes straight from the line's finish (cs_render_line_px, one
 * pass over the runs in 8-bit sRGB), into the display's own row where it
 * lends one (the simulator's image: no copy), the panel's pixels from the
 * runs. */
static cs_status drive_line(frame_drive *d, cs_renderer *r, int y, int row)
{
    uint8_t *bytes = hal_display_line_buffer(d->dev, y, d->line_bytes);
    if (bytes == NULL)
        bytes = d->bytes;
    cs_status st = cs_render_line_px(r, row, d->pixfmt, bytes);
    if (st != CS_OK)
        return st;
    if (d->panel != NULL)
        cs_line_pixels(r, CS_PANEL_PIXFMT, d->panel);
    return show_line(d, y, bytes, d->panel);
}

/* Line y (device row `row`) on a worker: rendered, its display bytes and
 * panel pixels into the frame's storage. */
static void band_line(void *user, cs_renderer *r, int row, int y)
{
    frame_drive *d = user;
    (void)cs_render_line_px(r, row, d->pixfmt, d->band_bytes + (size_t)y * d->line_bytes);
    if (d->panel != NULL)
        cs_line_pixels(r, CS_PANEL_PIXFMT, d->frame_panel + (size_t)y * panel_bytes(d));
}

/* Where the pool renders the frame's lines: the display's own rows if it
 * lends every row of the frame, one line_bytes after another (the
 * simulator's image), so that no line is copied; else frame_bytes. */
static uint8_t *band_storage(frame_drive *d)
{
    uint8_t *first = hal_display_line_buffer(d->dev, 0, d->line_bytes);
    if (first == NULL)
        return d->frame_bytes;
    for (int y = 1; y < d->dev->height; y++)
        if (hal_display_line_buffer(d->dev, y, d->line_bytes) != first + (size_t)y * d->line_bytes)
            return d->frame_bytes;
    return first;
}

/* The lines of the frame r prepared, rendered by the pool and by this thread
 * (in r itself, while it waits for a line), and shown in order. */
static cs_status drive_bands(frame_drive *d, cs_renderer *r, cs_error *sticky)
{
    d->band_bytes = band_storage(d);
    cs_status st = bands_start_render(d->pool, r, 0, d->dev->height, band_line, d);
    for (int y = 0; y < d->dev->height && st == CS_OK; y++) {
        bands_help(d->pool, r, y);
        st = show_line(d, y, d->band_bytes + (size_t)y * d->line_bytes,
                       d->panel ? d->frame_panel + (size_t)y * panel_bytes(d) : NULL);
    }
    *sticky = bands_finish(d->pool);
    return st;
}

int frame_drive_render(frame_drive *d, cs_renderer *r, cs_workspace *ws, const cs_scene *scene,
                       const cs_render_opts *opts)
{
    d->crc = 0;
    d->hal_st = HAL_OK;
    d->hal_y = -1;
    d->err = (cs_error){CS_OK, -1, -1, -1, -1};

    /* With a viewport the display is the window, and its rows count from view_y. */
    bool win = opts->view_w != 0 || opts->view_h != 0;
    int y0 = win ? opts->view_y : 0, rows = win ? opts->view_h : opts->height;
    hal_display *dev = d->dev;
    d->pixfmt = (cs_pixfmt)dev->pixfmt;
    d->line_bytes = hal_line_bytes(dev->pixfmt, dev->width);
    if (dev->width != (win ? opts->view_w : opts->width) || dev->height != rows) {
        d->hal_st = hal_display_fail(dev, HAL_ERR_CONFIG, "the frame is %dx%d, the display %dx%d",
                                     win ? opts->view_w : opts->width, rows, dev->width, dev->height);
        return FRAME_DRIVE_HAL;
    }
    if (dev->pixfmt == HAL_PIX_XRGB8888) {
        d->hal_st = hal_display_fail(dev, HAL_ERR_CONFIG, "the core does not render XRGB8888 lines");
        return FRAME_DRIVE_HAL;
    }

    cs_status st = d->pool ? bands_prepare(d->pool, r, ws, scene, opts, &d->err)
                           : cs_frame_begin(r, ws, scene, opts, &d->err);
    if (st != CS_OK) {
        d->err.status = st;
        return FRAME_DRIVE_CORE;
    }
    if ((d->hal_st = hal_display_begin_frame(dev, NULL)) != HAL_OK)
        return FRAME_DRIVE_HAL;
    /* Lines go from the core's runs straight to display bytes: each run of
     * equal pixels is converted once (cs_render_line_px, cs_line_pixels). */
    cs_error sticky;
    if (d->pool != NULL) {
        st = drive_bands(d, r, &sticky); /* window lines, as the display's rows */
    } else {
        for (int y = 0; y < rows && st == CS_OK; y++)
            st = drive_line(d, r, y, y0 + y);
        sticky = cs_frame_error(r);
    }
    if (st == CS_OK)
        st = sticky.status;
    if (d->hal_st != HAL_OK)
        return FRAME_DRIVE_HAL;
    if ((d->hal_st = hal_display_end_frame(dev)) != HAL_OK)
        return FRAME_DRIVE_HAL;
    if (st >= CS_ERR_CAP_CELS && st <= CS_ERR_CAP_CROSSINGS) {
        d->err = sticky;
        d->err.status = st;
        return FRAME_DRIVE_DEGRADED;
    }
    if (st != CS_OK) {
        d->err = (cs_error){st, -1, -1, -1, -1};
        return FRAME_DRIVE_CORE;
    }
    return FRAME_DRIVE_OK;
}
