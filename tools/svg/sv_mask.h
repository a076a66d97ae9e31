/*
 * sv_mask.h - <mask> on the beta model (sv_mask.c).
 */
#ifndef SV_MASK_H
#define SV_MASK_H

#include "sv.h"

/* mask-type: luminance (the default) or alpha. color-interpolation is not
 * honoured (luminance of the sRGB values), as browsers and resvg do. */
typedef struct sv_mask_mode {
    bool luminance;
} sv_mask_mode;

/* The mask value of a colour with opacity `alpha` (0..1). */
double sv_mask_value(const double rgb[3], double alpha, sv_mask_mode mode);

/*
 * The part of region `content` that mask region `mask` lets through, into
 * *out (a new region the caller owns): the content's contours, intersected
 * with the mask region's by a new IR clip, and its paint scaled by the mask
 * value - a constant for a solid mask region, a beta function sampled from
 * the mask region's gradient otherwise. False when the mask value is 0 there
 * (nothing to draw). Approximations are warned in doc naming `what`.
 */
bool sv_mask_region(sv_doc *doc, const sv_region *content, const sv_region *mask,
                    sv_mask_mode mode, const char *what, sv_region *out);

#endif /* SV_MASK_H */
