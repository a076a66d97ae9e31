/*
 * sv_gradient.h - gradient resolution and evaluation (sv_gradient.c).
 */
#ifndef SV_GRADIENT_H
#define SV_GRADIENT_H

#include "sv_import.h"

typedef sv_node *(*sv_find_fn)(void *ctx, const char *id);
/* The computed style of any element, through its own ancestors. */
typedef void (*sv_style_fn)(void *ctx, const sv_node *n, sv_style *out);

/*
 * Resolves gradient element `g` for an element with user-space bounding box
 * `bbox` and transform `ctm` (user space to canvas). Stops take their style
 * from the cascade through the gradient's own ancestors (`style`), as SVG
 * says, not from the element being painted. False when SVG says
 * the paint draws nothing (objectBoundingBox on a zero-size box).
 */
bool sv_gradient_resolve(sv_node *g, sv_find_fn find, sv_style_fn style, void *ctx,
                         const double bbox[4], sv_affine ctm, double vp_w, double vp_h,
                         sv_gradient *out, sv_doc *doc);
/* Colour (sRGB 0..1, not premultiplied) and opacity at canvas point q. */
void sv_gradient_eval(const sv_gradient *g, sv_pt q, double rgb[3], double *alpha);
/* Colour and opacity at gradient parameter t, after the spread method. */
void sv_gradient_color_at(const sv_gradient *g, double t, double rgb[3], double *alpha);
/*
 * Solid bands approximating gradient g over the filled canvas-space path
 * `area`, appended to r->bands (see sv_bands.c); `opacity` multiplies the
 * stops' opacity. Nothing is added where one colour suffices.
 */
void sv_gradient_bands(const sv_gradient *g, const sv_path *area, double opacity, sv_region *r);
/* Opacity-weighted average colour and mean opacity over the filled path (canvas units). */
void sv_gradient_average(const sv_gradient *g, const sv_path *area, int rule, double rgb[3],
                         double *alpha);

#endif /* SV_GRADIENT_H */
