/*
 * cs_pixfmt.c - linear light to the pixel formats of PNGs and panels.
 *
 * The renderer works in linear light; displays and PNGs want sRGB codes.
 * Encoding goes through a square-root-indexed table (see cs_srgb_table.c)
 * because the core has no pow(). Every conversion rounds to nearest in
 * float arithmetic that is identical on every target, so a frame's bytes
 * (and the CRC celsim --crc prints) are the same on the host and the MCU.
 *
 * Low-depth panels (RGB565, and the 4- and 3-bit channels of HUB75 boards)
 * band on smooth gradients. cs_pixfmt_convert_dither replaces round-to-
 * nearest by floor(v + threshold), with the threshold from an 8x8 Bayer
 * matrix indexed by the pixel's position: the mean over each 8x8 tile is
 * then the exact value to 1/64 of an output step, the pattern is fixed (so
 * a still frame does not shimmer and its CRC is stable), and a value that
 * lies exactly on an output level is left alone. The plain conversion is
 * untouched: the firmware's frame CRCs are defined on it.
 */
#include "cs_internal.h"

uint16_t cs_srgb_encode16(float linear)
{
    if (!(linear > 0.0f))
        return 0;
    if (linear >= 1.0f)
        return 65535;
    float pos = cs__sqrtf(linear) * 1024.0f;
    int32_t i = (int32_t)pos;
    if (i >= 1024)
        return 65535;
    float frac = pos - (float)i;
    float a = (float)cs__srgb_by_sqrt[i], b = (float)cs__srgb_by_sqrt[i + 1];
    return (uint16_t)(a + (b - a) * frac + 0.5f);
}

/*
 * Inverse of the encoding: the table is increasing, so a binary search
 * finds the interval of the code and the same linear interpolation in
 * sqrt(linear) is undone exactly; encode(decode(v)) returns v's code.
 */
float cs_srgb_decode(float encoded)
{
    if (!(encoded > 0.0f))
        return 0.0f;
    if (encoded >= 1.0f)
        return 1.0f;
    float code = encoded * 65535.0f;
    uint32_t lo = 0, hi = 1024; /* table[lo] <= code < table[hi] */
    while (hi - lo > 1u) {
        uint32_t mid = (lo + hi) / 2u;
        if ((float)cs__srgb_by_sqrt[mid] <= code)
            lo = mid;
        else
            hi = mid;
    }
    float a = (float)cs__srgb_by_sqrt[lo], b = (float)cs__srgb_by_sqrt[hi];
    float s = ((float)lo + (code - a) / (b - a)) * (1.0f / 1024.0f);
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

/* Rounds a 16-bit code to `bits` bits. */
static uint32_t narrow(uint32_t code16, uint32_t bits)
{
    uint32_t max = (1u << bits) - 1u;
    return (code16 * max + 32767u) / 65535u;
}

static uint32_t linear_code(float v, float max)
{
    v = cs__clampf(v, 0.0f, 1.0f);
    return (uint32_t)(v * max + 0.5f);
}

/* 8x8 Bayer matrix: thresholds (2 b + 1) / 128 in (0, 1), never 0 or 1. */
static const uint8_t bayer8[8][8] = {
    {0, 32, 8, 40, 2, 34, 10, 42},  {48, 16, 56, 24, 50, 18, 58, 26},
    {12, 44, 4, 36, 14, 46, 6, 38}, {60, 28, 52, 20, 62, 30, 54, 22},
    {3, 35, 11, 43, 1, 33, 9, 41},  {51, 19, 59, 27, 49, 17, 57, 25},
    {15, 47, 7, 39, 13, 45, 5, 37}, {63, 31, 55, 23, 61, 29, 53, 21},
};

/*
 * floor(code16 * max / 65535 + (2 b + 1) / 128) in integers: exact, and the
 * intermediate stays below 2^32 for max <= 255.
 */
static uint32_t narrow_dither(uint32_t code16, uint32_t bits, uint32_t b)
{
    uint32_t max = (1u << bits) - 1u;
    uint32_t v = (code16 * max * 128u + (2u * b + 1u) * 65535u) / (65535u * 128u);
    return v > max ? max : v;
}

/* The linear formats' codes, dithered the same way. */
static uint32_t linear_dither(float v, uint32_t max, uint32_t b)
{
    float t = cs__clampf(v, 0.0f, 1.0f) * (float)max + (float)(2u * b + 1u) * (1.0f / 128.0f);
    uint32_t c = (uint32_t)t;
    return c > max ? max : c;
}

/* The rounding step of each format: nearest, or dithered with threshold b. */
static uint32_t code_srgb(float v, uint32_t bits, bool dither, uint32_t b)
{
    uint32_t c = cs_srgb_encode16(v);
    return dither ? narrow_dither(c, bits, b) : narrow(c, bits);
}

static void convert(cs_pixfmt fmt, const float *rgb, int width, bool dither, int y, uint8_t *out)
{
    for (int x = 0; x < width; x++) {
        const float *px = &rgb[3 * x];
        uint32_t b = dither ? bayer8[(uint32_t)y & 7u][(uint32_t)x & 7u] : 0u;
        switch (fmt) {
        case CS_PIX_RGB444_SRGB: {
            uint32_t v = (code_srgb(px[0], 4, dither, b) << 8) |
                         (code_srgb(px[1], 4, dither, b) << 4) | code_srgb(px[2], 4, dither, b);
            out[2 * x] = (uint8_t)(v & 0xFFu);
            out[2 * x + 1] = (uint8_t)(v >> 8);
            continue;
        }
        case CS_PIX_RGB332_SRGB:
            out[x] = (uint8_t)((code_srgb(px[0], 3, dither, b) << 5) |
                               (code_srgb(px[1], 3, dither, b) << 2) |
                               code_srgb(px[2], 2, dither, b));
            continue;
        default:
            break;
        }
        if (!dither) {
            cs_pixfmt_convert(fmt, px, 1, out + cs_pixfmt_bytes_per_pixel(fmt) * (size_t)x);
            continue;
        }
        switch (fmt) {
        case CS_PIX_RGB888_SRGB:
            for (int ch = 0; ch < 3; ch++)
                out[3 * x + ch] = (uint8_t)code_srgb(px[ch], 8, true, b);
            break;
        case CS_PIX_RGB565_SRGB: {
            uint32_t v = (code_srgb(px[0], 5, true, b) << 11) | (code_srgb(px[1], 6, true, b) << 5) |
                         code_srgb(px[2], 5, true, b);
            out[2 * x] = (uint8_t)(v & 0xFFu);
            out[2 * x + 1] = (uint8_t)(v >> 8);
            break;
        }
        case CS_PIX_RGB888_LINEAR:
            for (int ch = 0; ch < 3; ch++)
                out[3 * x + ch] = (uint8_t)linear_dither(px[ch], 255u, b);
            break;
        default: /* 16-bit linear: fine enough already */
            cs_pixfmt_convert(fmt, px, 1, out + 6 * (size_t)x);
            break;
        }
    }
}

void cs_pixfmt_convert_dither(cs_pixfmt fmt, const float *rgb, int width, int y, uint8_t *out)
{
    convert(fmt, rgb, width, true, y, out);
}

void cs_pixfmt_convert(cs_pixfmt fmt, const float *rgb, int width, uint8_t *out)
{
    if (fmt == CS_PIX_RGB444_SRGB || fmt == CS_PIX_RGB332_SRGB) {
        convert(fmt, rgb, width, false, 0, out);
        return;
    }
    for (int x = 0; x < width; x++) {
        const float *px = &rgb[3 * x];
        switch (fmt) {
        case CS_PIX_RGB888_SRGB:
            for (int ch = 0; ch < 3; ch++)
                out[3 * x + ch] = (uint8_t)narrow(cs_srgb_encode16(px[ch]), 8);
            break;
        case CS_PIX_RGB565_SRGB: {
            uint32_t r = narrow(cs_srgb_encode16(px[0]), 5);
            uint32_t g = narrow(cs_srgb_encode16(px[1]), 6);
            uint32_t b = narrow(cs_srgb_encode16(px[2]), 5);
            uint32_t v = (r << 11) | (g << 5) | b;
            out[2 * x] = (uint8_t)(v & 0xFFu);
            out[2 * x + 1] = (uint8_t)(v >> 8);
            break;
        }
        case CS_PIX_RGB16_LINEAR:
            for (int ch = 0; ch < 3; ch++) {
                uint32_t v = linear_code(px[ch], 65535.0f);
                out[6 * x + 2 * ch] = (uint8_t)(v >> 8);
                out[6 * x + 2 * ch + 1] = (uint8_t)(v & 0xFFu);
            }
            break;
        case CS_PIX_RGB888_LINEAR:
            for (int ch = 0; ch < 3; ch++)
                out[3 * x + ch] = (uint8_t)linear_code(px[ch], 255.0f);
            break;
        default:
            break;
        }
    }
}
