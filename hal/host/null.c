/*
 * null.c - a display that takes every line and shows nothing.
 *
 * It gives celfw a backend for dry runs and for measuring render time alone,
 * with the same deadline accounting as the real backends (the frame driver,
 * hal_display_present, does it for every push backend).
 */
#include <stdlib.h>

#include "display.h"

static hal_status null_line_out(hal_display *d, int y, const uint8_t *px, size_t len)
{
    (void)d;
    (void)y;
    (void)px;
    (void)len;
    return HAL_OK;
}

static void null_close(hal_display *d)
{
    free(d);
}

static const hal_display_api null_api = {
    .name = "null",
    .line_out = null_line_out,
    .close = null_close,
};

hal_status hal_null_open(hal_display **out, int width, int height, const hal_clock *clock)
{
    hal_display *d = calloc(1, sizeof *d);
    if (!d)
        return HAL_ERR_NOMEM;
    d->api = &null_api;
    d->width = width;
    d->height = height;
    d->pixfmt = CS_PIX_RGB888_SRGB;
    d->clock = clock;
    *out = d;
    return HAL_OK;
}
