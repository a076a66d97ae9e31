/*
 * sv_render.h - host helpers for the importer's tools and tests: render a
 * cs_scene to an RGB8 image with the core, and read/write PNG with libpng.
 * Not a display HAL: celsim owns that; these only serve tools/svg and tests.
 */
#ifndef SV_RENDER_H
#define SV_RENDER_H

#include <stdint.h>

#include "celscan.h"

/*
 * Renders `scene` at w x h into rgb (3*w*h bytes, sRGB-encoded), compositing
 * in `blend` space (CS_BLEND_SRGB for imported SVG, as SVG renderers do).
 * Returns CS_OK or the first error.
 */
cs_status sv_render_rgb8(const cs_scene *scene, int w, int h, cs_aa_mode aa, int subscanlines,
                         cs_blend blend, uint8_t *rgb);

/* RGBA8, straight alpha; malloc'd into *px. 0 or -1. */
int sv_png_read_rgba(const char *path, uint8_t **px, int *w, int *h);
int sv_png_write_rgb(const char *path, const uint8_t *rgb, int w, int h);

#endif /* SV_RENDER_H */
