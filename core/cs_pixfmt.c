/*
 * cs_pixfmt.c - linear light to the pixel formats of PNGs and panels.
 *
 * The renderer works in linear light; displays and PNGs want sRGB codes.
 * Encoding goes through a square-root-indexed table (see cs_srgb_table.c)
 * because the core has no pow(). Every conversion rounds to nearest in
 * float arithmetic that is identical on every target, so a frame's bytes
 * (and the CRC celsim --crc prints) are the same on the host and the MCU.
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

size_t cs_pixfmt_bytes_per_pixel(cs_pixfmt fmt)
{
    switch (fmt) {
    case CS_PIX_RGB888_SRGB:
    case CS_PIX_RGB888_LINEAR:
        return 3;
    case CS_PIX_RGB565_SRGB:
        return 2;
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

void cs_pixfmt_convert(cs_pixfmt fmt, const float *rgb, int width, uint8_t *out)
{
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
        }
    }
}
