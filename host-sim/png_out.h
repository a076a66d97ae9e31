/*
 * png_out.h - writing finished frames to PNG files with libpng.
 *
 * The simulator's image is rows of packed RGB in one of the core's pixel
 * formats; this writes it unchanged, with the colour-space chunks that make
 * viewers show it correctly: sRGB for 8-bit sRGB-encoded frames, and gAMA 1.0
 * plus sRGB primaries (cHRM) for 16-bit linear ones.
 */
#ifndef HOST_SIM_PNG_OUT_H
#define HOST_SIM_PNG_OUT_H

#include <stddef.h>
#include <stdint.h>

#include "celscan.h"

/*
 * Writes `height` rows of `width` pixels, each row `stride` bytes apart, in
 * `fmt` (CS_PIX_RGB888_SRGB, CS_PIX_RGB888_LINEAR or CS_PIX_RGB16_LINEAR,
 * which is already big-endian as PNG wants). Returns 0, or -1 with a message
 * naming the file in errbuf; a failed write removes the partial file.
 */
int png_write_rgb(const char *path, int width, int height, cs_pixfmt fmt, const uint8_t *rows,
                  size_t stride, char *errbuf, size_t errlen);

#endif /* HOST_SIM_PNG_OUT_H */
