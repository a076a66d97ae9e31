/*
 * sv_gradient.c - linearGradient and radialGradient: resolution, evaluation
 * and the solid fallback.
 *
 * A gradient is resolved per painted element: attributes and stops follow
 * the href chain (the first element in the chain that sets an attribute, or
 * has stops, wins), objectBoundingBox units are mapped onto the element's
 * bounding box, and gradientTransform and the element's CTM are folded into
 * one map from gradient space to canvas units. The IR keeps the result so a
 * back end that can draw gradients needs nothing else.
 *
 * The back ends draw a gradient as the core's paint functions (sv_gradfn.c)
 * where those can express it, else as the bands of sv_bands.c; the region's
 * own paint holds the last resort, one colour: the gradient's average over
 * the area actually painted, premultiplied by its opacity, sampled on a grid
 * over the region's bounding box - the solid colour closest (in the mean
 * square, in the blend space) to the gradient there.
 */
#include <math.h>

#include "sv_gradient.h"
#include "sv_internal.h"

/* The attribute as the href chain resolves it (first element that sets it). */
static const char *chain_attr(sv_node *const *chain, int n, const char *name)
{
    for (int i = 0; i < n; i++) {
        const char *v = sv_attr(chain[i], name);
        if (v)
            return v;
    }
    return NULL;
}

/* A geometry attribute: only gradients of the same kind as chain[0] pass it on. */
static double coord(sv_node *const *chain, int n, const char *name, const char *dflt, bool obb,
                    double ref)
{
    const char *v = NULL;
    for (int i = 0; i < n && !v; i++)
        if (!strcmp(chain[i]->name, chain[0]->name))
            v = sv_attr(chain[i], name);
    if (!v)
        v = dflt;
    double x = 0;
    if (obb) { /* fractions of the bounding box; "50%" is 0.5 */
        const char *p = v;
        if (sv_parse_number(&p, &x) && *p == '%')
            x /= 100;
    } else {
        sv_parse_length(v, 12, ref, &x);
    }
    return x;
}

bool sv_gradient_resolve(sv_node *g, sv_find_fn find, sv_style_fn style, void *ctx,
                         const double bbox[4], sv_affine ctm, double vp_w, double vp_h,
                         sv_gradient *out, sv_doc *doc)
{
    sv_node *chain[16];
    int n = 0;
    for (sv_node *c = g; c && n < 16; n++) {
        for (int k = 0; k < n; k++)
            if (chain[k] == c)
                c = NULL; /* a cycle ends the chain */
        if (!c)
            break;
        chain[n] = c;
        const char *href = sv_attr(c, "href"); /* SVG 2: it takes precedence */
        if (!href)
            href = sv_attr(c, "xlink:href");
        c = (href && href[0] == '#') ? find(ctx, href + 1) : NULL;
        if (c && strcmp(c->name, "linearGradient") != 0 && strcmp(c->name, "radialGradient") != 0)
            c = NULL;
    }
    memset(out, 0, sizeof *out);
    out->type = strcmp(g->name, "radialGradient") == 0 ? SV_GRAD_RADIAL : SV_GRAD_LINEAR;
    const char *units = chain_attr(chain, n, "gradientUnits");
    bool obb = !units || strcmp(units, "userSpaceOnUse") != 0;
    const char *spread = chain_attr(chain, n, "spreadMethod");
    out->spread = !spread                       ? SV_SPREAD_PAD
                  : !strcmp(spread, "reflect") ? SV_SPREAD_REFLECT
                  : !strcmp(spread, "repeat")  ? SV_SPREAD_REPEAT
                                               : SV_SPREAD_PAD;
    double diag = sqrt((vp_w * vp_w + vp_h * vp_h) / 2);
    if (out->type == SV_GRAD_LINEAR) {
        out->x1 = coord(chain, n, "x1", "0%", obb, vp_w);
        out->y1 = coord(chain, n, "y1", "0%", obb, vp_h);
        out->x2 = coord(chain, n, "x2", "100%", obb, vp_w);
        out->y2 = coord(chain, n, "y2", "0%", obb, vp_h);
    } else {
        out->cx = coord(chain, n, "cx", "50%", obb, vp_w);
        out->cy = coord(chain, n, "cy", "50%", obb, vp_h);
        out->r = coord(chain, n, "r", "50%", obb, diag);
        out->fx = chain_attr(chain, n, "fx") ? coord(chain, n, "fx", "50%", obb, vp_w) : out->cx;
        out->fy = chain_attr(chain, n, "fy") ? coord(chain, n, "fy", "50%", obb, vp_h) : out->cy;
        out->fr = coord(chain, n, "fr", "0%", obb, diag);
    }
    sv_affine gt = sv_affine_identity();
    const char *gtr = chain_attr(chain, n, "gradientTransform");
    sv_affine inv;
    if (gtr && !sv_parse_transform(gtr, &gt))
        sv_doc_warn(doc, "<%s> (line %d): bad gradientTransform ignored", g->name, g->line);
    else if (gtr && !sv_affine_invert(gt, &inv)) { /* singular: ignored, as resvg does */
        sv_doc_warn(doc, "<%s> (line %d): singular gradientTransform ignored", g->name, g->line);
        gt = sv_affine_identity();
    }
    sv_affine m = ctm;
    if (obb) {
        double w = bbox[2] - bbox[0], h = bbox[3] - bbox[1];
        if (!(w > 0 && h > 0))
            return false; /* SVG: objectBoundingBox units on a flat box paint nothing */
        sv_affine b = {w, 0, 0, h, bbox[0], bbox[1]};
        m = sv_affine_mul(m, b);
    }
    out->transform = sv_affine_mul(m, gt);
    /* stops from the first element of the chain that has any */
    for (int i = 0; i < n && out->nstops == 0; i++) {
        for (int k = 0; k < chain[i]->nkids; k++) {
            sv_node *st = chain[i]->kids[k];
            if (strcmp(st->name, "stop") != 0)
                continue;
            if (out->nstops == SV_MAX_STOPS) { /* bounds the work a region's paint costs */
                sv_doc_warn(doc, "<%s> (line %d): more than %d stops (SV_MAX_STOPS), the rest "
                            "ignored", g->name, g->line, SV_MAX_STOPS);
                break;
            }
            sv_style ss;
            style(ctx, st, &ss);
            double off = 0;
            const char *ov = sv_attr(st, "offset");
            if (ov) { /* a number or a percentage; anything else ("5mm") is invalid: 0 */
                const char *p = ov;
                if (sv_parse_number(&p, &off) && *p == '%') {
                    off /= 100;
                    p++;
                }
                while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r')
                    p++;
                if (*p)
                    off = 0;
            }
            off = off < 0 ? 0 : (off > 1 ? 1 : off);
            if (out->nstops > 0 && off < out->stops[out->nstops - 1].offset)
                off = out->stops[out->nstops - 1].offset; /* offsets never go back */
            out->stops = sv_xrealloc(out->stops, (size_t)(out->nstops + 1) * sizeof *out->stops);
            sv_stop *s = &out->stops[out->nstops++];
            s->offset = off;
            memcpy(s->rgb, ss.stop_color, sizeof s->rgb);
            s->opacity = ss.stop_opacity;
        }
    }
    return true;
}

/* Gradient parameter t of canvas point q (before spreading). */
static double param(const sv_gradient *g, sv_affine inv, sv_pt q)
{
    sv_pt p = sv_affine_apply(inv, q);
    if (g->type == SV_GRAD_LINEAR) {
        double dx = g->x2 - g->x1, dy = g->y2 - g->y1, l2 = dx * dx + dy * dy;
        return l2 > 0 ? ((p.x - g->x1) * dx + (p.y - g->y1) * dy) / l2 : 1;
    }
    /*
     * Two-point conical: the largest t with |p - (f + t (c - f))| = fr + t (r - fr),
     * a quadratic in t (SVG 2 / canvas radial gradients; SVG 1.1 is fr = 0).
     */
    double cdx = g->cx - g->fx, cdy = g->cy - g->fy, dr = g->r - g->fr;
    double px = p.x - g->fx, py = p.y - g->fy;
    double a = cdx * cdx + cdy * cdy - dr * dr;
    double b = px * cdx + py * cdy + g->fr * dr;
    double c = px * px + py * py - g->fr * g->fr;
    if (fabs(a) < 1e-12 * (g->r * g->r + 1e-300)) {
        return b != 0 ? c / (2 * b) : 0;
    }
    double disc = b * b - a * c;
    if (disc < 0)
        return 0;
    double s = sqrt(disc), t1 = (b + s) / a, t2 = (b - s) / a;
    double t = t1 > t2 ? t1 : t2;
    if (g->fr + t * dr < 0)
        t = t1 > t2 ? t2 : t1;
    return t;
}

void sv_gradient_color_at(const sv_gradient *g, double t, double rgb[3], double *alpha)
{
    if (g->spread == SV_SPREAD_REPEAT) {
        t -= floor(t);
    } else if (g->spread == SV_SPREAD_REFLECT) {
        t = fmod(fabs(t), 2);
        if (t > 1)
            t = 2 - t;
    }
    const sv_stop *s = g->stops;
    int n = g->nstops;
    if (t <= s[0].offset) {
        memcpy(rgb, s[0].rgb, 3 * sizeof(double));
        *alpha = s[0].opacity;
        return;
    }
    for (int i = 1; i < n; i++)
        if (t < s[i].offset) {
            double u = (t - s[i - 1].offset) / (s[i].offset - s[i - 1].offset);
            for (int k = 0; k < 3; k++)
                rgb[k] = s[i - 1].rgb[k] + u * (s[i].rgb[k] - s[i - 1].rgb[k]);
            *alpha = s[i - 1].opacity + u * (s[i].opacity - s[i - 1].opacity);
            return;
        }
    memcpy(rgb, s[n - 1].rgb, 3 * sizeof(double));
    *alpha = s[n - 1].opacity;
}

void sv_gradient_eval(const sv_gradient *g, sv_pt q, double rgb[3], double *alpha)
{
    sv_affine inv;
    if (g->nstops == 0) {
        rgb[0] = rgb[1] = rgb[2] = 0;
        *alpha = 0;
        return;
    }
    if (!sv_affine_invert(g->transform, &inv)) {
        sv_gradient_color_at(g, 1, rgb, alpha); /* a degenerate map paints the last stop */
        return;
    }
    sv_gradient_color_at(g, param(g, inv, q), rgb, alpha);
}

static bool inside(const sv_path *p, int rule, sv_pt q)
{
    int w = 0;
    for (int i = 0; i < p->n; i++)
        w += sv_subpath_winding(&p->sub[i], q);
    return rule == CS_FILL_EVENODD ? (w & 1) != 0 : w != 0;
}

void sv_gradient_average(const sv_gradient *g, const sv_path *area, int rule, double rgb[3],
                         double *alpha)
{
    enum { N = 24 };
    double box[4];
    sv_path_bbox(area, box);
    double sum[3] = {0, 0, 0}, asum = 0;
    int count = 0;
    for (int pass = 0; pass < 2 && count == 0; pass++)
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++) {
                sv_pt q = {box[0] + (box[2] - box[0]) * (i + 0.5) / N,
                           box[1] + (box[3] - box[1]) * (j + 0.5) / N};
                /* second pass: the region is too thin for the grid, take the box */
                if (pass == 0 && !inside(area, rule, q))
                    continue;
                double c[3], a;
                sv_gradient_eval(g, q, c, &a);
                for (int k = 0; k < 3; k++)
                    sum[k] += a * c[k];
                asum += a;
                count++;
            }
    if (count == 0 || asum <= 0) {
        rgb[0] = rgb[1] = rgb[2] = 0;
        *alpha = 0;
        return;
    }
    for (int k = 0; k < 3; k++)
        rgb[k] = sum[k] / asum;
    *alpha = asum / count;
}
