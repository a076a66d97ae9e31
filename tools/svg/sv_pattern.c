/*
 * sv_pattern.c - the geometry of <pattern> paint servers.
 *
 * A pattern is a tile (x, y, width, height, in patternUnits: by default
 * fractions of the painted element's bounding box) repeated over the plane
 * of pattern space, which patternTransform maps into the element's user
 * space. The tile's content is drawn in a space whose origin is the tile's
 * corner, mapped by the viewBox (with preserveAspectRatio) when there is
 * one, else scaled by the bounding box when patternContentUnits is
 * objectBoundingBox. Attributes and children come through the href chain
 * (the first element that sets each), as for gradients.
 *
 * This file only resolves the geometry; the importer (sv_import.c) draws
 * each tile that meets the painted area as the content's own regions,
 * clipped to the tile and to the area.
 */
#include <math.h>

#include "sv_import.h"
#include "sv_internal.h"
#include "sv_pattern.h"

#define CHAIN_MAX 16

static const char *chain_attr(const sv_node *const *chain, int n, const char *name)
{
    for (int i = 0; i < n; i++) {
        const char *v = sv_attr(chain[i], name);
        if (v)
            return v;
    }
    return NULL;
}

/* A length in the pattern's units: fractions of the box (obb) or user units. */
static double coord(const sv_node *const *chain, int n, const char *name, bool obb, double ref)
{
    const char *v = chain_attr(chain, n, name);
    double x = 0;
    if (!v)
        return 0;
    if (obb) {
        const char *p = v;
        if (sv_parse_number(&p, &x) && *p == '%')
            x /= 100;
    } else if (!sv_parse_length(v, 12, ref, &x)) {
        x = 0;
    }
    return isfinite(x) ? x : 0;
}

sv_pattern_status sv_pattern_resolve(const sv_node *p, sv_find_fn find, void *ctx, const double bbox[4],
                        double vp_w, double vp_h, sv_pattern *out, sv_doc *doc)
{
    const sv_node *chain[CHAIN_MAX];
    int n = 0;
    for (const sv_node *c = p; c && n < CHAIN_MAX; n++) {
        for (int k = 0; k < n; k++)
            if (chain[k] == c)
                c = NULL; /* a cycle ends the chain */
        if (!c)
            break;
        chain[n] = c;
        const char *href = sv_attr(c, "xlink:href");
        if (!href)
            href = sv_attr(c, "href");
        c = (href && href[0] == '#') ? find(ctx, href + 1) : NULL;
        if (c && strcmp(c->name, "pattern") != 0)
            c = NULL;
    }
    memset(out, 0, sizeof *out);
    memcpy(out->bbox, bbox, sizeof out->bbox);
    const char *units = chain_attr(chain, n, "patternUnits");
    const char *cunits = chain_attr(chain, n, "patternContentUnits");
    bool obb = !units || strcmp(units, "userSpaceOnUse") != 0;
    double bw = bbox[2] - bbox[0], bh = bbox[3] - bbox[1];
    out->x = coord(chain, n, "x", obb, vp_w);
    out->y = coord(chain, n, "y", obb, vp_h);
    out->w = coord(chain, n, "width", obb, vp_w);
    out->h = coord(chain, n, "height", obb, vp_h);
    if (obb) {
        if (!(bw > 0 && bh > 0))
            return SV_PATTERN_INVALID;
        out->x = bbox[0] + out->x * bw;
        out->y = bbox[1] + out->y * bh;
        out->w *= bw;
        out->h *= bh;
    }
    if (!(out->w > 0 && out->h > 0 && isfinite(out->w) && isfinite(out->h)))
        return SV_PATTERN_NONE;
    out->transform = sv_affine_identity();
    const char *tr = chain_attr(chain, n, "patternTransform");
    sv_affine inv;
    if (tr && (!sv_parse_transform(tr, &out->transform) ||
               !sv_affine_invert(out->transform, &inv))) {
        /* as resvg does with a singular matrix too */
        sv_doc_warn(doc, "<pattern> (line %d): bad patternTransform ignored", p->line);
        out->transform = sv_affine_identity();
    }
    const char *vb = chain_attr(chain, n, "viewBox");
    out->has_viewbox = vb && sv_parse_numbers(vb, out->viewbox, 4) == 4 && out->viewbox[2] > 0 &&
                       out->viewbox[3] > 0;
    out->par = chain_attr(chain, n, "preserveAspectRatio");
    out->content_bbox = !out->has_viewbox && cunits && !strcmp(cunits, "objectBoundingBox");
    if (out->content_bbox && !(bw > 0 && bh > 0))
        return SV_PATTERN_INVALID;
    for (int i = 0; i < n && !out->content; i++)
        for (int k = 0; k < chain[i]->nkids && !out->content; k++)
            if (chain[i]->kids[k]->name[0] != '#')
                out->content = chain[i];
    return out->content ? SV_PATTERN_OK : SV_PATTERN_NONE;
}

sv_affine sv_pattern_content_map(const sv_pattern *p, long i, long j)
{
    double tx = p->x + (double)i * p->w, ty = p->y + (double)j * p->h;
    sv_affine m;
    if (p->has_viewbox) {
        m = sv_viewbox_map(p->viewbox, p->par, tx, ty, p->w, p->h);
    } else {
        sv_affine t = {1, 0, 0, 1, tx, ty};
        m = t;
        if (p->content_bbox) {
            sv_affine s = {p->bbox[2] - p->bbox[0], 0, 0, p->bbox[3] - p->bbox[1], 0, 0};
            m = sv_affine_mul(m, s);
        }
    }
    return sv_affine_mul(p->transform, m);
}

bool sv_pattern_tile_range(const sv_pattern *p, const double box[4], long *i0, long *i1,
                           long *j0, long *j1)
{
    sv_affine inv;
    if (!sv_affine_invert(p->transform, &inv))
        return false;
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (int k = 0; k < 4; k++) {
        sv_pt q = sv_affine_apply(inv, sv_pt_make(box[k & 1 ? 2 : 0], box[k & 2 ? 3 : 1]));
        x0 = fmin(x0, q.x);
        y0 = fmin(y0, q.y);
        x1 = fmax(x1, q.x);
        y1 = fmax(y1, q.y);
    }
    double a = floor((x0 - p->x) / p->w), b = ceil((x1 - p->x) / p->w);
    double c = floor((y0 - p->y) / p->h), d = ceil((y1 - p->y) / p->h);
    if (!(isfinite(a) && isfinite(b) && isfinite(c) && isfinite(d)) || fabs(a) > 1e9 ||
        fabs(b) > 1e9 || fabs(c) > 1e9 || fabs(d) > 1e9)
        return false;
    *i0 = (long)a;
    *i1 = (long)b > (long)a ? (long)b : (long)a + 1;
    *j0 = (long)c;
    *j1 = (long)d > (long)c ? (long)d : (long)c + 1;
    return true;
}
