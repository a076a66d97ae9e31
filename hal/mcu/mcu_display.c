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
 * running CRC then covers the bytes sent; the whole frame's CRC, the one
 * the tests compare with celsim's, comes from reading the panel's picture
 * back (mcu_display_frame_crc) where the panel can.
 */
#include "mcu_display.h"

void mcu_display_init(mcu_display *d, const mcu_panel *panel, uint8_t *pixels)
{
    d->panel = panel;
    d->pixels = pixels;
    d->width = d->height = 0;
    d->crc = 0;
    d->frames = 0;
    d->panel_error = 0;
}

cs_status mcu_display_begin(mcu_display *d, int width, int height)
{
    if (width < 1 || height < 1)
        return CS_ERR_SIZE;
    d->width = d->x1 = width;
    d->height = d->y1 = height;
    d->x0 = d->y0 = 0;
    d->crc = 0;
    d->panel_error = 0;
    const mcu_panel *p = d->panel;
    if (p && p->api->begin_frame)
        d->panel_error = p->api->begin_frame(p->ctx, d->frames, width, height);
    return CS_OK;
}

cs_status mcu_display_window(mcu_display *d, int x0, int y0, int x1, int y1)
{
    if (x0 < 0 || y0 < 0 || x1 > d->width || y1 > d->height || x0 > x1 || y0 > y1)
        return CS_ERR_ARG;
    d->x0 = x0, d->y0 = y0, d->x1 = x1, d->y1 = y1;
    if (x0 == 0 && y0 == 0 && x1 == d->width && y1 == d->height)
        return CS_OK;
    const mcu_panel *p = d->panel;
    if (p && d->panel_error == 0)
        d->panel_error = p->api->set_window ? p->api->set_window(p->ctx, x0, y0, x1, y1) : -1;
    return CS_OK;
}

bool mcu_display_frame_crc(const mcu_display *d, uint8_t *row, uint32_t *crc)
{
    const mcu_panel *p = d->panel;
    if (!p || !p->api->read_row || d->panel_error)
        return false;
    size_t bytes = (size_t)d->width * cs_pixfmt_bytes_per_pixel(CS_PANEL_PIXFMT);
    uint32_t c = 0;
    for (int y = 0; y < d->height; y++) {
        if (p->api->read_row(p->ctx, y, row, bytes) != 0)
            return false;
        c = cs_crc32(c, row, bytes);
    }
    *crc = c;
    return true;
}

cs_status mcu_display_line(void *user, int y, const float *rgb_linear, int width)
{
    mcu_display *d = user;
    if (width != d->x1 - d->x0 || y < d->y0 || y >= d->y1)
        return CS_ERR_ARG;
    if (!d->pixels)
        return CS_ERR_ARG;
    cs_pixfmt_convert(CS_PANEL_PIXFMT, rgb_linear, width, d->pixels);
    return mcu_display_line_px(d, y, d->pixels);
}

cs_status mcu_display_line_px(mcu_display *d, int y, const uint8_t *pixels)
{
    if (y < d->y0 || y >= d->y1 || !pixels)
        return CS_ERR_ARG;
    size_t bytes = (size_t)(d->x1 - d->x0) * cs_pixfmt_bytes_per_pixel(CS_PANEL_PIXFMT);
    d->crc = cs_crc32(d->crc, pixels, bytes);
    const mcu_panel *p = d->panel;
    if (p && d->panel_error == 0)
        d->panel_error = p->api->line_out(p->ctx, y, pixels, bytes);
    return CS_OK;
}

uint32_t mcu_display_end(mcu_display *d)
{
    const mcu_panel *p = d->panel;
    if (p && p->api->end_frame) {
        int e = p->api->end_frame(p->ctx);
        if (d->panel_error == 0)
            d->panel_error = e;
    }
    d->frames++;
    return d->crc;
}
