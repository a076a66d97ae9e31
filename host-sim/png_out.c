/*
 * png_out.c - PNG output for the simulator (see png_out.h).
 *
 * libpng reports errors by longjmp; everything that must survive the jump
 * (the FILE, the message) is set up before setjmp and declared volatile
 * where the jump could clobber it.
 */
#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <string.h>

#include "png_out.h"

typedef struct png_err_ctx {
    char *buf;
    size_t len;
    const char *path;
} png_err_ctx;

static void on_png_error(png_structp png, png_const_charp msg)
{
    png_err_ctx *ctx = png_get_error_ptr(png);
    snprintf(ctx->buf, ctx->len, "%s: PNG write failed: %s", ctx->path, msg);
    png_longjmp(png, 1);
}

static void on_png_warning(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg; /* warnings (e.g. about chunk order) do not affect the pixels */
}

int png_write_rgb(const char *path, int width, int height, cs_pixfmt fmt, const uint8_t *rows,
                  size_t stride, char *errbuf, size_t errlen)
{
    png_err_ctx ctx = {errbuf, errlen, path};
    int depth;
    switch (fmt) {
    case CS_PIX_RGB888_SRGB:
    case CS_PIX_RGB888_LINEAR:
        depth = 8;
        break;
    case CS_PIX_RGB16_LINEAR:
        depth = 16;
        break;
    default:
        snprintf(errbuf, errlen, "%s: pixel format %d cannot be written as PNG", path, (int)fmt);
        return -1;
    }
    if (width <= 0 || height <= 0) {
        snprintf(errbuf, errlen, "%s: empty image %dx%d", path, width, height);
        return -1;
    }

    FILE *f = fopen(path, "wb");
    if (f == NULL) {
        snprintf(errbuf, errlen, "%s: cannot create: %s", path, strerror(errno));
        return -1;
    }
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &ctx, on_png_error,
                                              on_png_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (png == NULL || info == NULL) {
        snprintf(errbuf, errlen, "%s: out of memory for the PNG writer", path);
        png_destroy_write_struct(&png, NULL);
        fclose(f);
        remove(path);
        return -1;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        fclose(f);
        remove(path);
        return -1;
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)width, (png_uint_32)height, depth, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (fmt == CS_PIX_RGB888_SRGB) {
        /* Writes sRGB plus the matching gAMA/cHRM for older decoders. */
        png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    } else {
        /* Linear light with sRGB (BT.709) primaries and D65 white. */
        png_set_gAMA(png, info, 1.0);
        png_set_cHRM(png, info, 0.3127, 0.3290, 0.64, 0.33, 0.30, 0.60, 0.15, 0.06);
    }
    png_write_info(png, info);
    for (int y = 0; y < height; y++)
        png_write_row(png, rows + (size_t)y * stride);
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    if (fclose(f) != 0) {
        snprintf(errbuf, errlen, "%s: cannot write: %s", path, strerror(errno));
        remove(path);
        return -1;
    }
    return 0;
}
