/*
 * mcu_display.c - finished lines to panel bytes, with a CRC per frame.
 *
 * The CRC covers exactly the bytes that go to the glass, in the panel's
 * format, rows top to bottom, so a frame's CRC on the board equals the one
 * `celsim --crc` prints for the same scene, time and size. A panel error
 * does not stop the frame (the rest of the lines still go out, and the CRC
 * still describes the frame); it is remembered and reported once.
 */
#include "mcu_display.h"

void mcu_display_init(mcu_display *d, hal_display *panel, uint8_t *pixels)
{
    d->panel = panel;
    d->pixels = pixels;
    d->width = d->height = 0;
    d->crc = 0;
    d->frames = 0;
    d->panel_error = HAL_OK;
}

cs_status mcu_display_begin(mcu_display *d, int width, int height)
{
    if (width < 1 || height < 1)
        return CS_ERR_SIZE;
    d->width = width;
    d->height = height;
    d->crc = 0;
    d->panel_error = HAL_OK;
    if (d->panel) {
        const hal_window win = {0, 0, width, height};
        d->panel_error = hal_display_begin_frame(d->panel, &win);
    }
    return CS_OK;
}

cs_status mcu_display_line(void *user, int y, const float *rgb_linear, int width)
{
    mcu_display *d = user;
    if (width != d->width || y < 0 || y >= d->height)
        return CS_ERR_ARG;
    if (!d->pixels)
        return CS_ERR_ARG;
    cs_pixfmt_convert(CS_PANEL_PIXFMT, rgb_linear, width, d->pixels);
    return mcu_display_line_px(d, y, d->pixels);
}

cs_status mcu_display_line_px(mcu_display *d, int y, const uint8_t *pixels)
{
    if (y < 0 || y >= d->height || !pixels)
        return CS_ERR_ARG;
    size_t bytes = (size_t)d->width * cs_pixfmt_bytes_per_pixel(CS_PANEL_PIXFMT);
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
