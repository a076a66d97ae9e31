/*
 * lx_pixel.c - XRGB8888 lines from the core's sRGB conversion.
 *
 * The line is converted to RGB888 in the destination itself and then spread
 * to four bytes a pixel from the right end, so no scratch line is needed:
 * pixel x's three source bytes start at 3x, its four at 4x >= 3x, and every
 * pixel to its right was already moved.
 */
#include "celscan.h"
#include "lx_pixel.h"

void lx_line_xrgb8888(const float *rgb, int width, uint8_t *dst)
{
    cs_pixfmt_convert(CS_PIX_RGB888_SRGB, rgb, width, dst);
    for (int x = width - 1; x >= 0; x--) {
        uint8_t r = dst[3 * x], g = dst[3 * x + 1], b = dst[3 * x + 2];
        dst[4 * x] = b;
        dst[4 * x + 1] = g;
        dst[4 * x + 2] = r;
        dst[4 * x + 3] = 0;
    }
}
