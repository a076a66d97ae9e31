/*
 * sv_render.c - render a cs_scene to RGB8 and PNG input/output for the
 * importer's tools and tests (libpng's simplified API).
 */
#include <png.h>
#include <stdlib.h>
#include <string.h>

#include "celscan_private.h"
#include "sv_render.h"

cs_status sv_render_rgb8(const cs_scene *scene, int w, int h, cs_aa_mode aa, int subscanlines,
                         cs_blend blend, uint8_t *rgb)
{
    cs_workspace *ws = malloc(sizeof *ws);
    float *line = malloc(sizeof(float) * 3 * (size_t)w);
    if (!ws || !line) {
        free(ws);
        free(line);
        return CS_ERR_ARG;
    }
    cs_renderer r;
    cs_render_opts o = cs_render_defaults(w, h);
    o.aa = aa;
    o.subscanlines = subscanlines;
    o.blend = blend;
    cs_error e;
    cs_status st = cs_frame_begin(&r, ws, scene, &o, &e);
    for (int y = 0; st == CS_OK && y < h; y++) {
        st = cs_render_line(&r, y, line);
        cs_pixfmt_convert(CS_PIX_RGB888_SRGB, line, w, rgb + (size_t)3 * w * y);
    }
    if (st == CS_OK)
        st = r.sticky.status;
    free(ws);
    free(line);
    return st;
}

int sv_png_read_rgba(const char *path, uint8_t **px, int *w, int *h)
{
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&img, path))
        return -1;
    img.format = PNG_FORMAT_RGBA;
    *px = malloc(PNG_IMAGE_SIZE(img));
    if (!*px || !png_image_finish_read(&img, NULL, *px, 0, NULL)) {
        free(*px);
        *px = NULL;
        png_image_free(&img);
        return -1;
    }
    *w = (int)img.width;
    *h = (int)img.height;
    return 0;
}

int sv_png_write_rgb(const char *path, const uint8_t *rgb, int w, int h)
{
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    img.width = (png_uint_32)w;
    img.height = (png_uint_32)h;
    img.format = PNG_FORMAT_RGB;
    return png_image_write_to_file(&img, path, 0, rgb, 0, NULL) ? 0 : -1;
}
