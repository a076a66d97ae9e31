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
 * Rounded 8-bit sRGB, the commonest output, takes its codes from a table
 * made by running this very arithmetic on every float (cs__srgb8): the
 * same bytes for a comparison in place of an interpolation. Rounded RGB565,
 * the boards' panel format, likewise takes each channel's code from the
 * thresholds where the arithmetic's code changes (cs__rgb5, cs__rgb6: a
 * cell lookup and two comparisons), and its runs have a loop of their own.
 *
 * Flat artwork makes long runs of bit-identical pixels, and the encoding
 * (a square root and a table interpolation per channel) costs more than the
 * rest of a flat pixel's rendering, so the undithered conversions reuse the
 * previous pixel's code when its three floats are equal: the same bytes
 * (equal floats encode equally; NaN never compares equal), a fraction of
 * the work.
 */
#include "cs_rgb888.h"

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

static float table_at(uint32_t i)
{
    return cs__srgb_by_sqrt[i];
}

/* Inverse of the encoding, for --blend srgb (cs__srgb_decode_in). */
float cs_srgb_decode(float encoded)
{
    if (!(encoded > 0.0f))
        return 0.0f;
    if (encoded >= 1.0f)
        return 1.0f;
    return cs__srgb_decode_in(table_at, 0u, 1024u, encoded);
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

/* Panel formats that pack three sRGB channels into 1 or 2 little-endian bytes. */
typedef struct packed_layout {
    float max[3];       /* channel code maxima: 31 63 31 for RGB565 */
    uint32_t shift[3];  /* bit positions of R, G and B */
    uint32_t bytes;     /* 1 or 2 */
} packed_layout;

static const packed_layout rgb565 = {{31.0f, 63.0f, 31.0f}, {11, 5, 0}, 2};
static const packed_layout rgb444 = {{15.0f, 15.0f, 15.0f}, {8, 4, 0}, 2};
static const packed_layout rgb332 = {{7.0f, 7.0f, 3.0f}, {5, 2, 0}, 1};

/* The rounded RGB565 pixel of linear r g b, from the threshold tables. */
static inline uint32_t rgb565_of(const float *px)
{
    return cs__rgb5(px[0]) << 11 | cs__rgb6(px[1]) << 5 | cs__rgb5(px[2]);
}

static inline void convert_packed(const packed_layout *L, const float *rgb, int width, int y,
                                  uint8_t *out)
{
    const uint8_t *row = bayer8[(uint32_t)(y < 0 ? 0 : y) & 7u];
    uint32_t v = 0;
    float last[3] = {-1.0f, -1.0f, -1.0f}; /* no light value is negative */
    for (int x = 0; x < width; x++) {
        const float *px = &rgb[3 * x];
        /* Without dithering a pixel equal to its left neighbour has its code.
         * The neighbour is kept in locals: converting in place (2 bytes over
         * 12) overwrites the floats behind. */
        float r = px[0], g = px[1], b = px[2];
        if (y >= 0 || r != last[0] || g != last[1] || b != last[2]) {
            last[0] = r;
            last[1] = g;
            last[2] = b;
            float bias = y < 0 ? 0.5f : (float)(2u * row[(uint32_t)x & 7u] + 1u) * (1.0f / 128.0f);
            if (y < 0 && L == &rgb565)
                v = rgb565_of(px);
            else
                v = code(cs__srgb_encode(px[0]), L->max[0], bias) << L->shift[0] |
                    code(cs__srgb_encode(px[1]), L->max[1], bias) << L->shift[1] |
                    code(cs__srgb_encode(px[2]), L->max[2], bias) << L->shift[2];
        }
        if (L->bytes == 1) {
            out[x] = (uint8_t)v;
        } else {
            out[2 * x] = (uint8_t)(v & 0xFFu);
            out[2 * x + 1] = (uint8_t)(v >> 8);
        }
    }
}

/* One line; `y` < 0 means round to nearest, else dither with row y's thresholds. */
static void convert(cs_pixfmt fmt, const float *rgb, int width, int y, uint8_t *out)
{
    const uint8_t *row = bayer8[(uint32_t)(y < 0 ? 0 : y) & 7u];
#define BIAS(x) (y < 0 ? 0.5f : (float)(2u * row[(uint32_t)(x) & 7u] + 1u) * (1.0f / 128.0f))
    switch (fmt) {
    case CS_PIX_RGB888_SRGB: {
        float last[3] = {-1.0f, -1.0f, -1.0f}; /* no light value is negative */
        uint8_t code8[3] = {0, 0, 0};
        for (int x = 0; x < width; x++) {
            const float *px = &rgb[3 * x];
            /* Kept in locals: converting in place overwrites the floats behind. */
            float r = px[0], g = px[1], b = px[2];
            if (y >= 0 || r != last[0] || g != last[1] || b != last[2]) {
                for (int ch = 0; ch < 3; ch++)
                    code8[ch] = (uint8_t)(y < 0 ? cs__srgb8(px[ch])
                                                : code(cs__srgb_encode(px[ch]), 255.0f, BIAS(x)));
                last[0] = r;
                last[1] = g;
                last[2] = b;
            }
            out[3 * x] = code8[0];
            out[3 * x + 1] = code8[1];
            out[3 * x + 2] = code8[2];
        }
        break;
    }
    case CS_PIX_RGB565_SRGB:
        convert_packed(&rgb565, rgb, width, y, out);
        break;
    case CS_PIX_RGB444_SRGB:
        convert_packed(&rgb444, rgb, width, y, out);
        break;
    case CS_PIX_RGB332_SRGB:
        convert_packed(&rgb332, rgb, width, y, out);
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
}

void cs_pixfmt_convert(cs_pixfmt fmt, const float *rgb, int width, uint8_t *out)
{
    convert(fmt, rgb, width, -1, out);
}

void cs_pixfmt_convert_dither(cs_pixfmt fmt, const float *rgb, int width, int y, uint8_t *out)
{
    convert(fmt, rgb, width, y < 0 ? 0 : y, out);
}

/* n pixels of the RGB565 value v at p, little-endian: short runs pixel by
 * pixel, long ones two pixels (a word) a step. */
static inline void fill_rgb565(uint8_t *p, uint32_t n, uint32_t v)
{
    for (uint32_t w = v | v << 16; n >= 4u; n -= 4u, p += 8) {
        cs__put32(p, w);
        cs__put32(p + 4, w);
    }
    for (; n > 0u; n--, p += 2) {
        p[0] = (uint8_t)v;
        p[1] = (uint8_t)(v >> 8);
    }
}

/* A whole line of runs in RGB565, the boards' panel format. */
static void runs_rgb565(const float *rgb, const uint16_t *run_end, uint32_t width, uint8_t *out)
{
    for (uint32_t s = 0; s < width;) {
        uint32_t e = run_end[s];
        fill_rgb565(out + 2u * s, e - s, rgb565_of(&rgb[3 * s]));
        s = e;
    }
}

/*
 * A whole line of runs in 8-bit sRGB, the format of PNGs, GUD bridges and
 * the bench: the common case, so it has a loop of its own rather than a
 * call and a format switch per run.
 */
static void runs_rgb888(const float *rgb, const uint16_t *run_end, uint32_t width, uint8_t *out)
{
    for (uint32_t s = 0; s < width;) {
        uint32_t e = run_end[s];
        const float *v = &rgb[3 * s];
        cs__rgb888_run(out, s, e, width, cs__srgb8(v[0]), cs__srgb8(v[1]), cs__srgb8(v[2]));
        s = e;
    }
}

/* A run of equal pixels: converted once, then written 12 bytes (a whole
 * number of pixels in every format) at a time. */
void cs__pixfmt_fill(cs_pixfmt fmt, const float rgb[3], uint32_t x0, uint32_t x1, uint8_t *out)
{
    if (fmt == CS_PIX_RGB888_SRGB) { /* convert() on one pixel, without its loop */
        cs__rgb888_fill(out + 3u * x0, x1 - x0, cs__srgb8(rgb[0]), cs__srgb8(rgb[1]),
                    cs__srgb8(rgb[2]));
        return;
    }
    if (fmt == CS_PIX_RGB565_SRGB) {
        fill_rgb565(out + 2u * x0, x1 - x0, rgb565_of(rgb));
        return;
    }
    uint8_t one[6];
    convert(fmt, rgb, 1, -1, one);
    uint32_t bpp = (uint32_t)cs_pixfmt_bytes_per_pixel(fmt);
    if (bpp == 0u)
        return;
    uint8_t *p = out + (size_t)x0 * bpp;
    size_t bytes = (size_t)(x1 - x0) * bpp;
    if (bytes < 24u) { /* edge pixels: most runs are short */
        for (size_t k = 0, j = 0; k < bytes; k++, j = j + 1u == bpp ? 0u : j + 1u)
            p[k] = one[j];
        return;
    }
    uint8_t pat[12];
    for (uint32_t k = 0, j = 0; k < 12u; k++, j = j + 1u == bpp ? 0u : j + 1u)
        pat[k] = one[j];
    uint32_t w[3];
    for (int k = 0; k < 3; k++)
        w[k] = (uint32_t)pat[4 * k] | (uint32_t)pat[4 * k + 1] << 8 |
               (uint32_t)pat[4 * k + 2] << 16 | (uint32_t)pat[4 * k + 3] << 24;
    for (; bytes >= 12u; bytes -= 12u, p += 12) {
        cs__put32(p, w[0]);
        cs__put32(p + 4, w[1]);
        cs__put32(p + 8, w[2]);
    }
    for (size_t k = 0; k < bytes; k++)
        p[k] = pat[k];
}

void cs__pixfmt_runs(cs_pixfmt fmt, const float *rgb, const uint16_t *run_end, uint32_t width,
                     uint8_t *out)
{
    if (fmt == CS_PIX_RGB888_SRGB) {
        runs_rgb888(rgb, run_end, width, out);
        return;
    }
    if (fmt == CS_PIX_RGB565_SRGB) {
        runs_rgb565(rgb, run_end, width, out);
        return;
    }
    for (uint32_t s = 0; s < width; s = run_end[s])
        cs__pixfmt_fill(fmt, &rgb[3 * s], s, run_end[s], out);
}
