/*
 * cs_pixfmt.c - linear light to the pixel formats of PNGs and panels.
 *
 * The renderer works in linear light; displays and PNGs want sRGB codes.
 * Encoding goes through a square-root-indexed table (see cs_srgb_table.c)
 * because the core has no pow(). Each value is encoded once in float and
 * rounded once to the output depth, in arithmetic that is identical on
 * every target, so a frame's bytes (and the CRC celsim --crc prints) are
 * the same on the host and the MCU. Conversion runs once per output pixel,
 * so the format switch sits outside the pixel loops.
 *
 * Low-depth panels (RGB565, and the 4- and 3-bit channels of HUB75 boards)
 * band on smooth gradients. cs_pixfmt_convert_dither replaces round-to-
 * nearest by floor(v + threshold), with the threshold from an 8x8 Bayer
 * matrix indexed by the pixel's position: the mean over each 8x8 tile is
 * then the exact value to 1/64 of an output step, the pattern is fixed (so
 * a still frame does not shimmer and its CRC is stable), and a value that
 * lies exactly on an output level is left alone. The plain conversion is
 * untouched by it: the firmware's frame CRCs are defined on that one.
 *
 * Flat artwork makes long runs of bit-identical pixels, and the encoding
 * (a square root and a table interpolation per channel) costs more than the
 * rest of a flat pixel's rendering, so the undithered conversions reuse the
 * previous pixel's code when its three floats are equal: the same bytes
 * (equal floats encode equally; NaN never compares equal), a fraction of
 * the work.
 */
#include "cs_internal.h"

/* 8x8 Bayer matrix: thresholds (2 b + 1) / 128 in (0, 1), never 0 or 1. */
static const uint8_t bayer8[8][8] = {
    {0, 32, 8, 40, 2, 34, 10, 42},  {48, 16, 56, 24, 50, 18, 58, 26},
    {12, 44, 4, 36, 14, 46, 6, 38}, {60, 28, 52, 20, 62, 30, 54, 22},
    {3, 35, 11, 43, 1, 33, 9, 41},  {51, 19, 59, 27, 49, 17, 57, 25},
    {15, 47, 7, 39, 13, 45, 5, 37}, {63, 31, 55, 23, 61, 29, 53, 21},
};

/* v in 0..1 to an integer code 0..max: rounded when bias is 0.5, dithered
 * when bias is a Bayer threshold in (0, 1). */
static inline uint32_t code(float v, float max, float bias)
{
    uint32_t c = (uint32_t)(v * max + bias);
    return c > (uint32_t)max ? (uint32_t)max : c;
}

uint16_t cs_srgb_encode16(float linear)
{
    return (uint16_t)code(cs__srgb_encode(linear), 65535.0f, 0.5f);
}

/*
 * Inverse of the encoding, for --blend srgb: a binary search for the table
 * cell holding the value, then the inverse of its linear interpolation, so
 * decode(encode(v)) returns v to float precision.
 */
float cs_srgb_decode(float encoded)
{
    if (!(encoded > 0.0f))
        return 0.0f;
    if (encoded >= 1.0f)
        return 1.0f;
    uint32_t lo = 0, hi = 1024; /* table[lo] <= encoded < table[hi] */
    while (hi - lo > 1u) {
        uint32_t mid = (lo + hi) / 2u;
        if (cs__srgb_by_sqrt[mid] <= encoded)
            lo = mid;
        else
            hi = mid;
    }
    float a = cs__srgb_by_sqrt[lo], b = cs__srgb_by_sqrt[hi];
    float s = ((float)lo + (encoded - a) / (b - a)) * (1.0f / 1024.0f);
    return s * s;
}

size_t cs_pixfmt_bytes_per_pixel(cs_pixfmt fmt)
{
    switch (fmt) {
    case CS_PIX_RGB888_SRGB:
    case CS_PIX_RGB888_LINEAR:
        return 3;
    case CS_PIX_RGB565_SRGB:
    case CS_PIX_RGB444_SRGB:
        return 2;
    case CS_PIX_RGB332_SRGB:
        return 1;
    case CS_PIX_RGB16_LINEAR:
        return 6;
    }
    return 0;
}

/* One line; `y` < 0 means round to nearest, else dither with row y's thresholds. */
static void convert(cs_pixfmt fmt, const float *rgb, int width, int y, uint8_t *out)
{
    const uint8_t *row = bayer8[(uint32_t)(y < 0 ? 0 : y) & 7u];
#define BIAS(x) (y < 0 ? 0.5f : (float)(2u * row[(uint32_t)(x) & 7u] + 1u) * (1.0f / 128.0f))
    /* Pixel x repeats pixel x-1 exactly (rounding only: dithering depends on x). */
#define SAME(x)                                                                                   \
    (y < 0 && (x) > 0 && rgb[3 * (x)] == rgb[3 * (x)-3] && rgb[3 * (x) + 1] == rgb[3 * (x)-2] && \
     rgb[3 * (x) + 2] == rgb[3 * (x)-1])
    switch (fmt) {
    case CS_PIX_RGB888_SRGB:
        for (int x = 0; x < width; x++) {
            if (SAME(x)) {
                out[3 * x] = out[3 * x - 3];
                out[3 * x + 1] = out[3 * x - 2];
                out[3 * x + 2] = out[3 * x - 1];
                continue;
            }
            for (int ch = 0; ch < 3; ch++)
                out[3 * x + ch] = (uint8_t)code(cs__srgb_encode(rgb[3 * x + ch]), 255.0f, BIAS(x));
        }
        break;
    case CS_PIX_RGB565_SRGB:
        for (int x = 0; x < width; x++) {
            if (SAME(x)) {
                out[2 * x] = out[2 * x - 2];
                out[2 * x + 1] = out[2 * x - 1];
                continue;
            }
            const float *px = &rgb[3 * x];
            float bias = BIAS(x);
            uint32_t v = code(cs__srgb_encode(px[0]), 31.0f, bias) << 11 |
                         code(cs__srgb_encode(px[1]), 63.0f, bias) << 5 |
                         code(cs__srgb_encode(px[2]), 31.0f, bias);
            out[2 * x] = (uint8_t)(v & 0xFFu);
            out[2 * x + 1] = (uint8_t)(v >> 8);
        }
        break;
    case CS_PIX_RGB444_SRGB:
        for (int x = 0; x < width; x++) {
            if (SAME(x)) {
                out[2 * x] = out[2 * x - 2];
                out[2 * x + 1] = out[2 * x - 1];
                continue;
            }
            const float *px = &rgb[3 * x];
            float bias = BIAS(x);
            uint32_t v = code(cs__srgb_encode(px[0]), 15.0f, bias) << 8 |
                         code(cs__srgb_encode(px[1]), 15.0f, bias) << 4 |
                         code(cs__srgb_encode(px[2]), 15.0f, bias);
            out[2 * x] = (uint8_t)(v & 0xFFu);
            out[2 * x + 1] = (uint8_t)(v >> 8);
        }
        break;
    case CS_PIX_RGB332_SRGB:
        for (int x = 0; x < width; x++) {
            if (SAME(x)) {
                out[x] = out[x - 1];
                continue;
            }
            const float *px = &rgb[3 * x];
            float bias = BIAS(x);
            out[x] = (uint8_t)(code(cs__srgb_encode(px[0]), 7.0f, bias) << 5 |
                               code(cs__srgb_encode(px[1]), 7.0f, bias) << 2 |
                               code(cs__srgb_encode(px[2]), 3.0f, bias));
        }
        break;
    case CS_PIX_RGB16_LINEAR: /* fine enough not to need dithering */
        for (int i = 0; i < 3 * width; i++) {
            uint32_t v = code(cs__clampf(rgb[i], 0.0f, 1.0f), 65535.0f, 0.5f);
            out[2 * i] = (uint8_t)(v >> 8);
            out[2 * i + 1] = (uint8_t)(v & 0xFFu);
        }
        break;
    case CS_PIX_RGB888_LINEAR:
        for (int x = 0; x < width; x++)
            for (int ch = 0; ch < 3; ch++)
                out[3 * x + ch] = (uint8_t)code(cs__clampf(rgb[3 * x + ch], 0.0f, 1.0f), 255.0f,
                                                BIAS(x));
        break;
    }
#undef BIAS
#undef SAME
}

void cs_pixfmt_convert(cs_pixfmt fmt, const float *rgb, int width, uint8_t *out)
{
    convert(fmt, rgb, width, -1, out);
}

void cs_pixfmt_convert_dither(cs_pixfmt fmt, const float *rgb, int width, int y, uint8_t *out)
{
    convert(fmt, rgb, width, y < 0 ? 0 : y, out);
}
