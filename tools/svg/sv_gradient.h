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
 * stops' opacity. Nothing is added where one colour suffices. *work is what
 * is left of the document's budget of segment clips (SV_MAX_BAND_WORK); a
 * region that would take more gets no bands and false is returned.
 */
bool sv_gradient_bands(const sv_gradient *g, const sv_path *area, double opacity, sv_region *r,
                       long *work);
/* Opacity-weighted average colour and mean opacity over the filled path (canvas units). */
void sv_gradient_average(const sv_gradient *g, const sv_path *area, int rule, double rgb[3],
                         double *alpha);


/* ------------------------------------------ paint functions (sv_gradfn.c) */

/* Whether a gradient can be the core's paint functions, and if not why. */
typedef enum sv_fn_status {
    SV_FN_OK = 0,
    SV_FN_SOLID,   /* it paints one colour: the region's constant paint is exact */
    SV_FN_STOPS,   /* more than CS_CFG_MAX_STOPS stops after merging */
    SV_FN_ELLIPSE, /* radial, and not a circle in the cel's space */
    SV_FN_FOCAL,   /* SVG 2 focal radius fr > 0 */
    SV_FN_RANGE    /* geometry beyond the core's coordinate range */
} sv_fn_status;

typedef struct sv_gradfn {
    bool has_pigment, has_beta;  /* which fields vary (are functions) */
    cs_paint_func pigment;       /* stop values sRGB-encoded 0..1 */
    cs_paint_func beta;          /* stop opacities, the same offsets and geometry */
    double pigment_const[3];     /* sRGB; the value of a field that does not vary */
    double beta_const;
} sv_gradfn;

/*
 * Gradient g with its stop opacities multiplied by `opacity`, for a region
 * in a cel whose transform (cel space to canvas) is `cel`: functions in cel
 * space. SV_FN_OK fills *out; SV_FN_SOLID fills only the constants.
 */
sv_fn_status sv_gradient_funcs(const sv_gradient *g, double opacity, sv_affine cel,
                               sv_gradfn *out);
const char *sv_fn_status_str(sv_fn_status st);
/* For a radial gradient that is elliptical on the canvas: a cel transform
 * under which it is a circle (false when it is a circle already, is not
 * radial, or is too thin to map). */
bool sv_gradient_circle_space(const sv_gradient *g, sv_affine *cel);
/* Whether g (if radial) is a circle in the space of a cel with transform `cel`. */
bool sv_gradient_circular_in(const sv_gradient *g, sv_affine cel);

#endif /* SV_GRADIENT_H */
