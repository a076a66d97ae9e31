/*
 * sv_mask.c - SVG masks mapped onto regions, clips and paint functions.
 *
 * A mask multiplies the masked content by a value per point: the luminance
 * (or, for mask-type alpha, the opacity) of the mask's own content, rendered
 * like any drawing, times its opacity. On the beta model, coverage c applied
 * to a paint gives (c E, 1 - c (1 - T)): scaling beta by the mask value is
 * exactly the mask, for white medium. So each painted region of the mask's
 * content (a mask region) lets through one copy of each content region: its
 * contours intersected with the mask region's (a CSG clip whose parent is
 * the content's own clip), with beta times the mask value. A solid mask
 * region has one value; a gradient one gives the copy a beta function with
 * the gradient's geometry and its value (luminance times opacity, which is
 * quadratic between stops, hence sampled at up to CS_CFG_MAX_STOPS stops).
 *
 * A content region with a gradient of its own under a gradient mask region
 * is exact in form when both are linear with parallel iso-lines (the product
 * varies along one axis: a linear gradient of 16 samples across the region).
 * What stays approximate, each warned by the importer or here: other pairs
 * of gradients (the content takes its average colour), and mask regions that overlap with
 * values below 1 (the importer puts the copies in one layer, where the front
 * copy hides the back one: exact for opaque mask shapes over others, as a
 * white shape on a black backdrop is).
 */
#include <math.h>

#include "sv_gradient.h"
#include "sv_internal.h"
#include "sv_mask.h"

double sv_mask_value(const double rgb[3], double alpha, sv_mask_mode mode)
{
    if (!mode.luminance)
        return alpha;
    /* luminanceToAlpha's coefficients (SVG 1.1 section 15.10) */
    double l = 0.2125 * rgb[0] + 0.7154 * rgb[1] + 0.0721 * rgb[2];
    return fmin(fmax(l * alpha, 0), 1);
}

static void copy_contours(const sv_region *src, sv_region *dst)
{
    dst->ncontours = src->ncontours;
    dst->contours = sv_xrealloc(NULL, (size_t)(src->ncontours ? src->ncontours : 1) *
                                          sizeof *dst->contours);
    for (int i = 0; i < src->ncontours; i++) {
        const sv_contour *c = &src->contours[i];
        sv_contour *d = &dst->contours[i];
        *d = *c;
        d->pts = sv_xrealloc(NULL, (size_t)c->count * 3 * sizeof *d->pts);
        d->intervals = sv_xrealloc(NULL, (size_t)c->count * sizeof *d->intervals);
        memcpy(d->pts, c->pts, (size_t)c->count * 3 * sizeof *d->pts);
        memcpy(d->intervals, c->intervals, (size_t)c->count * sizeof *d->intervals);
    }
}

/* A new IR clip: the mask region's contours, under its fill rule. */
static int mask_clip(sv_doc *doc, const sv_region *mask, int parent)
{
    sv_clip clip;
    memset(&clip, 0, sizeof clip);
    clip.parent = parent;
    clip.nparts = 1;
    clip.parts = sv_xrealloc(NULL, sizeof *clip.parts);
    sv_region tmp;
    memset(&tmp, 0, sizeof tmp);
    copy_contours(mask, &tmp);
    clip.parts[0].clip = -1;
    clip.parts[0].fill_rule = mask->fill_rule;
    clip.parts[0].ncontours = tmp.ncontours;
    clip.parts[0].contours = tmp.contours;
    doc->clips = sv_xrealloc(doc->clips, (size_t)(doc->nclips + 1) * sizeof clip);
    doc->clips[doc->nclips] = clip;
    return doc->nclips++;
}

/*
 * The mask region's gradient as a gradient of mask values times `beta`,
 * colour `rgb`: the same geometry and spread, stops at the original offsets
 * and evenly between them, as many as the core takes.
 */
static sv_gradient value_gradient(const sv_gradient *g, double opacity, sv_mask_mode mode,
                                  const double rgb[3], double beta, double *mean)
{
    sv_gradient out = *g;
    int n = g->nstops, per = n < 2 || n >= CS_CFG_MAX_STOPS ? 0 : (CS_CFG_MAX_STOPS - n) / (n - 1);
    int total = n + (n - 1) * per;
    out.stops = sv_xrealloc(NULL, (size_t)total * sizeof *out.stops);
    out.nstops = 0;
    double sum = 0;
    for (int i = 0; i < n; i++)
        for (int k = 0; k <= (i < n - 1 ? per : 0); k++) {
            double t = g->stops[i].offset;
            if (k > 0)
                t += (g->stops[i + 1].offset - t) * k / (per + 1);
            double c[3], a;
            if (k == 0) { /* at a stop, its own colour (hard steps keep both sides) */
                memcpy(c, g->stops[i].rgb, sizeof c);
                a = g->stops[i].opacity;
            } else {
                sv_gradient_color_at(g, t, c, &a);
            }
            sv_stop *s = &out.stops[out.nstops++];
            s->offset = t;
            memcpy(s->rgb, rgb, sizeof s->rgb);
            s->opacity = beta * sv_mask_value(c, a * opacity, mode);
            sum += s->opacity;
        }
    *mean = sum / out.nstops;
    return out;
}

/* The canvas gradient of t for a linear gradient (t = n . q + const); false if degenerate. */
static bool linear_normal(const sv_gradient *g, sv_pt *n)
{
    sv_affine inv;
    double dx = g->x2 - g->x1, dy = g->y2 - g->y1, l2 = dx * dx + dy * dy;
    if (g->type != SV_GRAD_LINEAR || !(l2 > 0) || !sv_affine_invert(g->transform, &inv))
        return false;
    /* t = d . (inv q) / |d|^2 + const: n is inv's linear part transposed times d */
    n->x = (inv.a * dx + inv.b * dy) / l2;
    n->y = (inv.c * dx + inv.d * dy) / l2;
    return true;
}

/*
 * Content gradient `gc` under mask gradient `gm` when both are linear with
 * parallel iso-lines: then their product varies along one axis only, and is
 * a linear gradient of samples taken across `box` (canvas units) along it.
 */
static bool product_gradient(const sv_gradient *gc, double opacity_c, const sv_gradient *gm,
                             double opacity_m, sv_mask_mode mode, const double box[4],
                             sv_gradient *out, double *mean)
{
    sv_pt nc, nm;
    if (!linear_normal(gc, &nc) || !linear_normal(gm, &nm))
        return false;
    double lm = sv_len(nm), lc = sv_len(nc);
    if (fabs(sv_cross(nc, nm)) > 1e-9 * lc * lm)
        return false;
    sv_pt u = sv_scale(nm, 1 / lm);
    double s0 = INFINITY, s1 = -INFINITY;
    for (int k = 0; k < 4; k++) {
        double s = sv_dot(u, sv_pt_make(box[k & 1 ? 2 : 0], box[k & 2 ? 3 : 1]));
        s0 = fmin(s0, s);
        s1 = fmax(s1, s);
    }
    if (!(s1 > s0) || !isfinite(s0) || !isfinite(s1))
        return false;
    memset(out, 0, sizeof *out);
    out->type = SV_GRAD_LINEAR;
    out->x1 = u.x * s0;
    out->y1 = u.y * s0;
    out->x2 = u.x * s1;
    out->y2 = u.y * s1;
    out->transform = sv_affine_identity();
    out->spread = SV_SPREAD_PAD;
    out->nstops = CS_CFG_MAX_STOPS;
    out->stops = sv_xrealloc(NULL, (size_t)out->nstops * sizeof *out->stops);
    double sum = 0;
    for (int i = 0; i < out->nstops; i++) {
        double t = (double)i / (out->nstops - 1);
        sv_pt q = sv_scale(u, s0 + t * (s1 - s0));
        double c[3], a, mc[3], ma;
        sv_gradient_eval(gc, q, c, &a);
        sv_gradient_eval(gm, q, mc, &ma);
        out->stops[i].offset = t;
        memcpy(out->stops[i].rgb, c, sizeof c);
        out->stops[i].opacity = fmin(a * opacity_c, 1) * sv_mask_value(mc, ma * opacity_m, mode);
        sum += out->stops[i].opacity;
    }
    *mean = sum / out->nstops;
    return true;
}

bool sv_mask_region(sv_doc *doc, const sv_region *content, const sv_region *mask,
                    sv_mask_mode mode, const char *what, sv_region *out)
{
    memset(out, 0, sizeof *out);
    out->fill_rule = content->fill_rule;
    out->paint = content->paint;
    int parent = content->clip;
    if (mask->clip >= 0) {
        if (parent >= 0)
            sv_doc_warn(doc, "%s: a clip-path inside the mask and one on the content: the "
                        "mask's left out", what);
        else
            parent = mask->clip;
    }
    if (mask->paint.gradient < 0) {
        double v = sv_mask_value(mask->paint.pigment, mask->paint.beta, mode);
        if (!(v > 0))
            return false;
        out->paint.beta *= v;
        out->paint.gradient_opacity *= v;
        out->nbands = content->nbands;
        if (content->nbands > 0) {
            out->bands = sv_xrealloc(NULL, (size_t)content->nbands * sizeof *out->bands);
            for (int b = 0; b < content->nbands; b++) {
                sv_region *d = &out->bands[b];
                *d = content->bands[b];
                copy_contours(&content->bands[b], d);
                d->bands = NULL;
                d->nbands = 0;
                d->paint.beta *= v;
                d->source = sv_xstrdup(content->bands[b].source ? content->bands[b].source : "");
            }
        }
    } else {
        double mean, box[4] = {fmax(content->bbox[0], mask->bbox[0]),
                               fmax(content->bbox[1], mask->bbox[1]),
                               fmin(content->bbox[2], mask->bbox[2]),
                               fmin(content->bbox[3], mask->bbox[3])};
        sv_gradient g;
        const sv_gradient *gm = &doc->gradients[mask->paint.gradient];
        if (content->paint.gradient < 0) {
            g = value_gradient(gm, mask->paint.gradient_opacity, mode, content->paint.pigment,
                               content->paint.beta, &mean);
        } else if (!product_gradient(&doc->gradients[content->paint.gradient],
                                     content->paint.gradient_opacity, gm,
                                     mask->paint.gradient_opacity, mode, box, &g, &mean)) {
            sv_doc_warn(doc, "%s: gradient under a gradient mask of another direction "
                        "approximated by its average colour", what);
            g = value_gradient(gm, mask->paint.gradient_opacity, mode, content->paint.pigment,
                               content->paint.beta, &mean);
        }
        if (!(mean > 0)) {
            free(g.stops);
            return false;
        }
        doc->gradients = sv_xrealloc(doc->gradients, (size_t)(doc->ngradients + 1) * sizeof g);
        doc->gradients[doc->ngradients] = g;
        out->paint.gradient = doc->ngradients++;
        out->paint.gradient_opacity = 1;
        out->paint.beta = fmin(mean, 1);
    }
    copy_contours(content, out);
    /* what it can cover: both boxes (the packer looks at it for overlaps) */
    out->bbox[0] = fmax(content->bbox[0], mask->bbox[0]);
    out->bbox[1] = fmax(content->bbox[1], mask->bbox[1]);
    out->bbox[2] = fmin(content->bbox[2], mask->bbox[2]);
    out->bbox[3] = fmin(content->bbox[3], mask->bbox[3]);
    out->clip = mask_clip(doc, mask, parent);
    out->source = sv_xstrdup(content->source ? content->source : "");
    return true;
}
