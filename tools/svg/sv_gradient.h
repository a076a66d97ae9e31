/*
 * sv_gradient.h - gradient resolution and evaluation (sv_gradient.c).
 */
#ifndef SV_GRADIENT_H
#define SV_GRADIENT_H

#include "sv_import.h"

typedef sv_node *(*sv_find_fn)(void *ctx, const char *id);

/*
 * Resolves gradient element `g` for an element with user-space bounding box
 * `bbox` and transform `ctm` (user space to canvas). False when SVG says
 * the paint draws nothing (objectBoundingBox on a zero-size box).
 */
bool sv_gradient_resolve(sv_node *g, sv_find_fn find, void *ctx, const sv_style *elem,
                         const double bbox[4], sv_affine ctm, double vp_w, double vp_h,
                         sv_gradient *out, sv_doc *doc);
/* Colour (sRGB 0..1, not premultiplied) and opacity at canvas point q. */
void sv_gradient_eval(const sv_gradient *g, sv_pt q, double rgb[3], double *alpha);
/* Opacity-weighted average colour and mean opacity over the filled path (canvas units). */
void sv_gradient_average(const sv_gradient *g, const sv_path *area, int rule, double rgb[3],
                         double *alpha);

#endif /* SV_GRADIENT_H */
