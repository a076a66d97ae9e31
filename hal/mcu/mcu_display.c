/*
 * mcu_display.c - finished lines to panel bytes, with a CRC per frame.
 *
 * The CRC covers exactly the bytes that go to the glass, in the panel's
 * format, rows top to bottom, so a frame's CRC on the board equals the one
 * `celsim --crc` prints for the same scene, time and size. A panel error
 * does not stop the frame (the rest of the lines still go out, and the CRC
 * still describes the frame); it is remembered and reported once.
 *
 * A frame may send only a window of itself (the rows and columns that
 * changed, cs_frame_damage): the panel keeps the rest of its picture. The
 * CRC is a test's check, not something the glass needs: a panel that can
 * read its picture back (read_row) gets no running CRC at all (at 480x272
 * RGB565 it was 1.36 M instructions a frame, 13 % of the board demo's),
 * and the whole frame's CRC, the one the tests compare with celsim's, is
 * read back after the frame (mcu_display_frame_crc). Only a panel that
 * cannot read back, or none, or one that refused the frame's start, has
 * the running CRC of the bytes sent; a frame whose panel failed later has
 * no CRC (the panel error is reported instead).
 */
#include "mcu_display.h"

void mcu_display_init(mcu_display *d, hal_display *panel, uint8_t *pixels)
{
    d->panel = panel;
    d->pixels = pixels;
    d->width = d->height = 0;
    d->crc = 0;
    d->hash = true;
    d->frames = 0;
    d->panel_error = HAL_OK;
}

cs_status mcu_display_begin(mcu_display *d, int width, int height, const hal_window *win)
{
    if (width < 1 || height < 1)
        return CS_ERR_SIZE;
    if (win && !hal_window_inside(win, width, height))
        return CS_ERR_ARG;
    d->width = width;
    d->height = height;
    /* A window that is the whole frame is no window: the panel gets NULL. */
    if (win && win->x0 == 0 && win->y0 == 0 && win->x1 == width && win->y1 == height)
        win = NULL;
    d->win = win ? *win : (hal_window){0, 0, width, height};
    d->crc = 0;
    d->panel_error = HAL_OK;
    if (d->panel)
        d->panel_error = hal_display_begin_frame(d->panel, win);
    /* A panel that refused the frame's start will not read it back either. */
    d->hash = !d->panel || !d->panel->api->read_row || d->panel_error != HAL_OK;
    return CS_OK;
}

bool mcu_display_frame_crc(mcu_display *d, uint8_t *row, uint32_t *crc)
{
    if (!d->panel || d->panel_error != HAL_OK)
        return false;
    size_t bytes = (size_t)d->width * cs_pixfmt_bytes_per_pixel(CS_PANEL_PIXFMT);
    uint32_t c = 0;
    for (int y = 0; y < d->height; y++) {
        if (hal_display_read_row(d->panel, y, row, bytes) != HAL_OK)
            return false;
        c = cs_crc32(c, row, bytes);
    }
    *crc = c;
    return true;
}

cs_status mcu_display_line(void *user, int y, const float *rgb_linear, int width)
{
    mcu_display *d = user;
    if (width != d->win.x1 - d->win.x0 || y < d->win.y0 || y >= d->win.y1)
        return CS_ERR_ARG;
    if (!d->pixels)
        return CS_ERR_ARG;
    cs_pixfmt_convert(CS_PANEL_PIXFMT, rgb_linear, width, d->pixels);
    return mcu_display_line_px(d, y, d->pixels);
}

cs_status mcu_display_line_px(mcu_display *d, int y, const uint8_t *pixels)
{
    if (y < d->win.y0 || y >= d->win.y1 || !pixels)
        return CS_ERR_ARG;
    size_t bytes = (size_t)(d->win.x1 - d->win.x0) * cs_pixfmt_bytes_per_pixel(CS_PANEL_PIXFMT);
    if (d->hash)
        d->crc = cs_crc32(d->crc, pixels, bytes);
    if (d->panel && d->panel_error == HAL_OK)
        d->panel_error = hal_display_line_out(d->panel, y, pixels, bytes);
    return CS_OK;
}

uint32_t mcu_display_end(mcu_display *d)
{
    if (d->panel) {
        hal_status e = hal_display_end_frame(d->panel);
        if (d->panel_error == HAL_OK)
            d->panel_error = e;
    }
    d->frames++;
    return d->crc;
}
