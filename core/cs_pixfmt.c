/*
 * cs_pixfmt.c - linear light to the pixel formats of PNGs and panels.
 *
 * The renderer works in linear light; displays and PNGs want sRGB codes.
 * Encoding goes through a square-root-indexed table (see cs_srgb_table.c)
 * because the core has no pow(). Each value is encoded once in float and
 * rounded once to the output depth, in arithmetic that is identical on
 * every target, so a frame's bytes (and the CRC celsim --crc prints) are
 * the same on the host and the MCU. The format switch sits outside the
 * pixel loops: conversion runs once per output pixel and must stay cheap.
 */
#include "cs_internal.h"

/* Rounds v in 0..1 to an integer code 0..max. */
static inline uint32_t code(float v, float max)
{
    return (uint32_t)(v * max + 0.5f);
}

uint16_t cs_srgb_encode16(float linear)
{
    return (uint16_t)code(cs__srgb_encode(linear), 65535.0f);
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

void cs_pixfmt_convert(cs_pixfmt fmt, const float *rgb, int width, uint8_t *out)
{
    int n = 3 * width;
    switch (fmt) {
    case CS_PIX_RGB888_SRGB:
        for (int i = 0; i < n; i++)
            out[i] = (uint8_t)code(cs__srgb_encode(rgb[i]), 255.0f);
        break;
    case CS_PIX_RGB565_SRGB:
        for (int x = 0; x < width; x++) {
            const float *px = &rgb[3 * x];
            uint32_t v = code(cs__srgb_encode(px[0]), 31.0f) << 11 |
                         code(cs__srgb_encode(px[1]), 63.0f) << 5 |
                         code(cs__srgb_encode(px[2]), 31.0f);
            out[2 * x] = (uint8_t)(v & 0xFFu);
            out[2 * x + 1] = (uint8_t)(v >> 8);
        }
        break;
    case CS_PIX_RGB16_LINEAR:
        for (int i = 0; i < n; i++) {
            uint32_t v = code(cs__clampf(rgb[i], 0.0f, 1.0f), 65535.0f);
            out[2 * i] = (uint8_t)(v >> 8);
            out[2 * i + 1] = (uint8_t)(v & 0xFFu);
        }
        break;
    case CS_PIX_RGB888_LINEAR:
        for (int i = 0; i < n; i++)
            out[i] = (uint8_t)code(cs__clampf(rgb[i], 0.0f, 1.0f), 255.0f);
        break;
    }
}
