/*
 * lx_pixel.h - rendered lines in the pixel layouts Linux display APIs take.
 *
 * The core converts a line to packed sRGB formats (cs_pixfmt_convert); the
 * kernel's DRM formats add one it lacks, XRGB8888: 32 bits per pixel,
 * little-endian, so the bytes in memory are B, G, R, X. (DRM's RGB565 is the
 * core's CS_PIX_RGB565_SRGB as it is.)
 */
#ifndef LX_PIXEL_H
#define LX_PIXEL_H

#include <stdint.h>

/* Converts width pixels of linear RGB floats to XRGB8888 at dst (4*width bytes, X = 0). */
void lx_line_xrgb8888(const float *rgb, int width, uint8_t *dst);

#endif /* LX_PIXEL_H */
