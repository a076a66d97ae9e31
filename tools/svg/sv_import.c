/*
 * sv_import.c - SVG element tree to the IR.
 *
 * The walk follows SVG's rendering model: each element computes its style
 * (sv_style.c) and current transformation matrix, containers pass both on,
 * and shapes become paths in user space. A fill is the path mapped to canvas
 * units; a stroke is outlined in user space (so a non-uniform transform
 * distorts it as SVG says) and then mapped. Each painted fill or stroke is
 * one region, collected in document order (back to front).
 *
 * Cels. celscan sums the coverage of the regions of one cel, each region
 * claiming only what the regions in front of it left. For opaque regions
 * that is painter's order without conflation seams; but a translucent region
 * would hide what lies behind it in the same cel. So after the walk the
 * regions are reversed (front-most first) and packed into cels: a region
 * joins the current cel unless it overlaps a translucent region already in
 * it. Group opacity uses the same mechanism on purpose: everything inside a
 * group with opacity < 1 (or a shape with both fill and stroke and opacity
 * < 1) goes into one cel of its own with the opacity multiplied into each
 * paint, and since front regions hide back ones within the cel, that is the
 * group rendered opaque and then made translucent - SVG's semantics, exact
 * for opaque content, approximate only where the group's own children are
 * translucent and overlap.
 *
 * A cel also has a space. The core's radial function is a circle in its
 * cel's space, so a radial gradient that is an ellipse on the canvas
 * (objectBoundingBox on a box that is not square, a skewing
 * gradientTransform) gives its cel a transform under which it is a circle;
 * a later region whose radial gradient is no circle in that space starts a
 * new cel, within CS_CFG_MAX_CELS.
 *
 * Paint maps to the beta model with medium white and beta = alpha: with
 * front light 1 and back light 0 this is exactly premultiplied "over".
 * Clip paths that are one convex polygon are cut into the geometry; others
 * go into the IR (sv_doc.clips) for the back ends' CSG. sv_doc_plan then
 * decides how each region is drawn.
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>

#include "sv_font.h"
#include "sv_gradient.h"
#include "sv_import.h"
#include "sv_internal.h"
#include "sv_mask.h"
#include "sv_pattern.h"
#include "sv_text.h"

typedef struct item {
    sv_region reg;
    int layer; /* 0, or the group-opacity layer the region belongs to */
    bool translucent;
    bool stroke; /* a stroke's outline (not in an objectBoundingBox) */
} item;

typedef struct clip_poly {
    sv_pt *v;
    int n;
} clip_poly;

#define MAX_CLIPS 8
typedef struct ctx {
    sv_affine ctm;
    bool via_use; /* inside a <use> instance: counts against SV_MAX_USE_COPIES */
    int layer;
    double alpha; /* opacities of enclosing layers, multiplied into paints */
    const clip_poly *clips[MAX_CLIPS];
    int nclips;
    int ir_clip;
    double vp_w, vp_h; /* viewport, for percentages */
    const double *obj_box; /* the next shape's objectBoundingBox if not its outline's (text) */
} ctx;

typedef struct imp {
    sv_doc *doc;
    sv_import_opts opts;
    sv_css css;
    /* id -> element, open addressing (a file may hold 10^5 ids), capids a power of 2 */
    struct idmap {
        const char *id;
        sv_node *node;
    } *ids;
    size_t nids, capids;
    item *items;
    int nitems, capitems;
    int next_layer;
    const sv_node *stack[SV_MAX_DEPTH];
    int depth;
    /* elements whose mask reference closed a cycle: drawn unmasked from then on, as resvg
     * drops such a reference once for the whole document */
    const sv_node **unmasked;
    int nunmasked, capunmasked;
    sv_fonts *fonts; /* fontconfig's choices and open faces, made at the first <text> */
    /* regions made and tiles visited inside patterns and masks, over the whole import:
     * nested expansions multiply, so one budget bounds them all (SV_EXPAND_BUDGET) */
    long expanded;
    double tol; /* stroke tolerance, canvas units */
    /* what the limits of sv.h count */
    long use_copies, points, contours, clip_points, text_bytes;
    long band_work; /* left of SV_MAX_BAND_WORK */
    const sv_node *clipping[MAX_CLIPS]; /* clipPaths being applied: references back are cycles */
    int nclipping;
    /* the first error; once set, the walk only returns */
    char *err;
    size_t errlen;
    bool failed;
} imp;

static void render(imp *im, sv_node *n, const sv_style *ps, const ctx *pc);

/* The import's font cache, made at the first <text>. */
static sv_fonts *fonts_of(imp *im)
{
    if (!im->fonts)
        im->fonts = sv_fonts_new(im->opts.font_path);
    return im->fonts;
}
static void add_clip_part(sv_clip *clip, const sv_path *p, int rule);

/* Ends the import: a limit of sv.h was reached (the first error is kept). */
static void __attribute__((format(printf, 2, 3))) fail(imp *im, const char *fmt, ...)
{
    if (im->failed)
        return;
    im->failed = true;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(im->err, im->errlen, fmt, ap);
    va_end(ap);
}

static void desc(const sv_node *n, char *buf, size_t len)
{
    const char *id = sv_attr(n, "id");
    if (id)
        snprintf(buf, len, "<%s id=\"%s\"> (line %d)", n->name, id, n->line);
    else
        snprintf(buf, len, "<%s> (line %d)", n->name, n->line);
}

static size_t id_hash(const char *s)
{
    size_t h = 14695981039346656037u; /* FNV-1a */
    for (; *s; s++)
        h = (h ^ (unsigned char)*s) * 1099511628211u;
    return h;
}

/* The slot of `id`: where it is, or the empty one where it would go. */
static struct idmap *id_slot(const imp *im, const char *id)
{
    size_t mask = im->capids - 1;
    for (size_t i = id_hash(id) & mask;; i = (i + 1) & mask)
        if (!im->ids[i].id || strcmp(im->ids[i].id, id) == 0)
            return &im->ids[i];
}

static sv_node *find_id(void *ctxp, const char *id)
{
    imp *im = ctxp;
    return im->capids ? id_slot(im, id)->node : NULL;
}

static void add_id(imp *im, const char *id, sv_node *n)
{
    if (2 * (im->nids + 1) > im->capids) { /* at most half full */
        struct idmap *old = im->ids;
        size_t oldcap = im->capids;
        im->capids = oldcap ? 2 * oldcap : 64;
        im->ids = sv_xrealloc(NULL, im->capids * sizeof *im->ids);
        memset(im->ids, 0, im->capids * sizeof *im->ids);
        for (size_t i = 0; i < oldcap; i++)
            if (old[i].id)
                *id_slot(im, old[i].id) = old[i];
        free(old);
    }
    struct idmap *slot = id_slot(im, id);
    if (!slot->id) { /* the first of duplicate ids wins */
        slot->id = id;
        slot->node = n;
        im->nids++;
    }
}

static sv_node *find_href(imp *im, const sv_node *n)
{
    const char *h = sv_attr(n, "href"); /* SVG 2: it takes precedence over xlink:href */
    if (!h)
        h = sv_attr(n, "xlink:href");
    return (h && h[0] == '#') ? find_id(im, h + 1) : NULL;
}

/*
 * The computed style of an element through its own ancestors: what gradient
 * stops use (they inherit from where the gradient is defined). Percentages
 * in it refer to the root viewport.
 */
static void style_of(void *ctxp, const sv_node *n, sv_style *out)
{
    imp *im = ctxp;
    if (!n->parent) {
        sv_style s0;
        sv_style_initial(&s0);
        memcpy(s0.color, im->opts.current_color, sizeof s0.color);
        sv_style_compute(out, &s0, n, &im->css, 0, NULL);
        return;
    }
    sv_style parent;
    style_of(ctxp, n->parent, &parent);
    sv_style_compute(out, &parent, n, &im->css, 0, NULL);
}

/* Ids and style sheets of the whole document, before anything is drawn. */
static void collect(imp *im, sv_node *n)
{
    const char *id = sv_attr(n, "id");
    if (id)
        add_id(im, id, n);
    if (strcmp(n->name, "style") == 0 && n->text) {
        const char *type = sv_attr(n, "type");
        if (!type || strcmp(type, "text/css") == 0)
            sv_css_parse_sheet(&im->css, n->text, im->doc);
    }
    for (int i = 0; i < n->nkids; i++)
        collect(im, n->kids[i]);
}

static double attr_len(const sv_node *n, const char *name, const sv_style *s, double ref,
                       double dflt)
{
    const char *v = sv_attr(n, name);
    double x;
    if (v && sv_parse_length(v, s->font_size, ref, &x))
        return x;
    return dflt;
}

/* SVG 1.1 section 7.8: the viewBox onto the viewport under preserveAspectRatio. */
sv_affine sv_viewbox_map(const double vb[4], const char *par, double x, double y, double w,
                         double h)
{
    double sx = w / vb[2], sy = h / vb[3];
    char align[16] = "xMidYMid";
    bool slice = false;
    if (par) {
        const char *p = par;
        while (isspace((unsigned char)*p))
            p++;
        if (strncmp(p, "defer", 5) == 0)
            p += 5;
        while (isspace((unsigned char)*p))
            p++;
        sscanf(p, "%15s", align);
        slice = strstr(p, "slice") != NULL;
    }
    double tx = x - vb[0] * sx, ty = y - vb[1] * sy;
    if (strcmp(align, "none") != 0) {
        double s = slice ? fmax(sx, sy) : fmin(sx, sy);
        sx = sy = s;
        tx = x - vb[0] * s;
        ty = y - vb[1] * s;
        if (strstr(align, "xMid"))
            tx += (w - vb[2] * s) / 2;
        else if (strstr(align, "xMax"))
            tx += w - vb[2] * s;
        if (strstr(align, "YMid"))
            ty += (h - vb[3] * s) / 2;
        else if (strstr(align, "YMax"))
            ty += h - vb[3] * s;
    }
    sv_affine m = {sx, 0, 0, sy, tx, ty};
    return m;
}

static bool get_viewbox(const sv_node *n, double vb[4])
{
    const char *v = sv_attr(n, "viewBox");
    return v && sv_parse_numbers(v, vb, 4) == 4 && vb[2] > 0 && vb[3] > 0;
}

/* ------------------------------------------------------------- shapes */

/* Geometry of a basic shape or path in user space; false if it draws nothing. */
static bool shape_path(imp *im, const sv_node *n, const sv_style *s, const ctx *c, sv_path *p)
{
    double vw = c->vp_w, vh = c->vp_h, vd = sqrt((vw * vw + vh * vh) / 2);
    const char *name = n->name;
    char d[160], err[200];
    if (!strcmp(name, "path")) {
        const char *data = sv_attr(n, "d");
        if (!data)
            return false;
        if (sv_parse_path(data, p, err, sizeof err) < 0) {
            desc(n, d, sizeof d);
            sv_doc_warn(im->doc, "%s: %s; drawn up to the error", d, err);
        }
    } else if (!strcmp(name, "rect")) {
        double x = attr_len(n, "x", s, vw, 0), y = attr_len(n, "y", s, vh, 0);
        double w = attr_len(n, "width", s, vw, 0), h = attr_len(n, "height", s, vh, 0);
        double rx = attr_len(n, "rx", s, vw, -1), ry = attr_len(n, "ry", s, vh, -1);
        if (!(w > 0 && h > 0))
            return false;
        if (rx < 0)
            rx = ry;
        if (ry < 0)
            ry = rx;
        rx = fmin(fmax(rx, 0), w / 2);
        ry = fmin(fmax(ry, 0), h / 2);
        if (rx > 0 && ry > 0) { /* corners: exact quarter ellipses, weight sqrt(1/2) */
            double k = sqrt(0.5);
            sv_path_move(p, x + rx, y);
            sv_path_line(p, x + w - rx, y);
            sv_path_conic(p, x + w, y, k, x + w, y + ry);
            sv_path_line(p, x + w, y + h - ry);
            sv_path_conic(p, x + w, y + h, k, x + w - rx, y + h);
            sv_path_line(p, x + rx, y + h);
            sv_path_conic(p, x, y + h, k, x, y + h - ry);
            sv_path_line(p, x, y + ry);
            sv_path_conic(p, x, y, k, x + rx, y);
        } else {
            sv_path_move(p, x, y);
            sv_path_line(p, x + w, y);
            sv_path_line(p, x + w, y + h);
            sv_path_line(p, x, y + h);
        }
        sv_path_close(p);
    } else if (!strcmp(name, "circle") || !strcmp(name, "ellipse")) {
        double cx = attr_len(n, "cx", s, vw, 0), cy = attr_len(n, "cy", s, vh, 0), rx, ry;
        if (name[0] == 'c') {
            rx = ry = attr_len(n, "r", s, vd, 0);
        } else {
            rx = attr_len(n, "rx", s, vw, -1);
            ry = attr_len(n, "ry", s, vh, -1);
            if (rx < 0) /* SVG 2: auto takes the other radius */
                rx = ry;
            if (ry < 0)
                ry = rx;
        }
        if (!(rx > 0 && ry > 0))
            return false;
        sv_path_ellipse(p, cx, cy, rx, ry);
    } else if (!strcmp(name, "line")) {
        sv_path_move(p, attr_len(n, "x1", s, vw, 0), attr_len(n, "y1", s, vh, 0));
        sv_path_line(p, attr_len(n, "x2", s, vw, 0), attr_len(n, "y2", s, vh, 0));
    } else if (!strcmp(name, "polyline") || !strcmp(name, "polygon")) {
        const char *pts = sv_attr(n, "points");
        if (!pts)
            return false;
        if (sv_parse_points(pts, p, name[4] == 'g') < 0) {
            desc(n, d, sizeof d);
            sv_doc_warn(im->doc, "%s: odd number of coordinates, last one ignored", d);
        }
    } else {
        return false;
    }
    return p->n > 0;
}

/* Bounding box of the curve itself (objectBoundingBox wants the tight box). */
static void tight_bbox(const sv_path *p, double box[4])
{
    box[0] = box[1] = INFINITY;
    box[2] = box[3] = -INFINITY;
    for (int i = 0; i < p->n; i++)
        for (int k = 0; k < p->sub[i].n; k++) {
            const sv_seg *s = &p->sub[i].seg[k];
            int m = s->degree == 1 ? 1 : 256;
            for (int j = 0; j <= m; j++) {
                sv_pt q = j == 0 ? s->p[0] : j == m ? s->p[s->degree] : sv_seg_eval(s, (double)j / m);
                box[0] = fmin(box[0], q.x);
                box[1] = fmin(box[1], q.y);
                box[2] = fmax(box[2], q.x);
                box[3] = fmax(box[3], q.y);
            }
        }
}

/* A paint spec to a beta paint; false when nothing is to be painted. */
static bool resolve_paint(imp *im, const sv_node *n, const sv_paint_spec *ps, const sv_style *s,
                          double opacity, const double ubox[4], const ctx *c,
                          const sv_path *area, int rule, const char *what, sv_paint *out)
{
    char d[160];
    double rgb[3], a = ps->alpha;
    sv_paint_kind kind = ps->kind;
    out->gradient = -1;
    out->gradient_opacity = opacity;
    if (kind == SV_PAINT_URL) {
        sv_node *t = find_id(im, ps->url);
        bool grad = t && (!strcmp(t->name, "linearGradient") || !strcmp(t->name, "radialGradient"));
        if (grad) {
            sv_gradient g;
            if (!sv_gradient_resolve(t, find_id, style_of, im, ubox, c->ctm, c->vp_w, c->vp_h, &g,
                                     im->doc) ||
                g.nstops == 0) {
                free(g.stops);
                if (!ps->fallback_kind)
                    return false;
                /*
                 * No stops, or objectBoundingBox units on a flat box: the
                 * gradient is invalid and the fallback colour paints (as resvg).
                 */
                kind = ps->fallback_kind;
                memcpy(rgb, ps->fallback_rgb, sizeof rgb);
                a = 1;
            } else if (g.nstops == 1) { /* one stop is a solid colour, exactly */
                memcpy(rgb, g.stops[0].rgb, sizeof rgb);
                a = g.stops[0].opacity;
                free(g.stops);
                kind = SV_PAINT_COLOR;
            } else {
                sv_gradient_average(&g, area, rule, rgb, &a);
                im->doc->gradients = sv_xrealloc(
                    im->doc->gradients, (size_t)(im->doc->ngradients + 1) * sizeof g);
                im->doc->gradients[im->doc->ngradients] = g;
                out->gradient = im->doc->ngradients++;
                kind = SV_PAINT_COLOR;
            }
        } else {
            desc(n, d, sizeof d);
            if (t)
                sv_doc_warn(im->doc, "%s: %s paint server <%s> not supported%s", d, what, t->name,
                            ps->fallback_kind ? ", fallback colour used" : ", not painted");
            else
                sv_doc_warn(im->doc, "%s: %s paint #%s not found%s", d, what, ps->url,
                            ps->fallback_kind ? ", fallback colour used" : ", not painted");
            kind = ps->fallback_kind;
            memcpy(rgb, ps->fallback_rgb, sizeof rgb);
            a = 1;
        }
    } else if (kind == SV_PAINT_COLOR) {
        memcpy(rgb, ps->rgb, sizeof rgb);
    }
    if (kind == SV_PAINT_CURRENT)
        memcpy(rgb, s->color, sizeof rgb);
    else if (kind == SV_PAINT_NONE)
        return false;
    a *= opacity;
    if (!(a > 0))
        return false;
    memcpy(out->pigment, rgb, sizeof rgb);
    out->medium[0] = out->medium[1] = out->medium[2] = 1;
    out->beta = a > 1 ? 1 : a;
    return true;
}

/*
 * Adds a region (canvas-space path) with the context's convex clips applied.
 * A gradient paint also gets its solid bands, the fallback sv_doc_plan uses
 * where the core's paint functions cannot draw it; `opacity` is what
 * multiplies the gradient's own stop opacities.
 */
/*
 * Geometry beyond the core's coordinate limit (a huge stroke-width, a far
 * transform) is cut to the canvas and as much again around it: nothing
 * outside is ever seen. The cut computes points between far ends, whose
 * rounding grows with their distance (2^-52 of it), so it is done up to
 * FAR_LIMIT (1e-7 canvas units of error); geometry reaching further, or not
 * finite, is left out. All of it is warned. False when nothing is left.
 */
#define FAR_LIMIT 1e9
static bool within_limits(imp *im, sv_path *cp, const sv_node *n, const char *what)
{
    double box[4], lim = 0.5 * CS_CFG_COORD_LIMIT;
    sv_path_bbox(cp, box);
    double far = fmax(fmax(fabs(box[0]), fabs(box[1])), fmax(fabs(box[2]), fabs(box[3])));
    if (far <= lim)
        return true;
    char d[160];
    desc(n, d, sizeof d);
    if (!(far <= FAR_LIMIT)) {
        sv_doc_warn(im->doc, "%s: %s reaches %g canvas units, too far to cut to the canvas "
                    "exactly (limit %g), not drawn", d, what, far, FAR_LIMIT);
        return false;
    }
    double w = im->doc->width, h = im->doc->height;
    sv_path_clip_halfplane(cp, 1, 0, fmin(w, lim));          /* x >= -w */
    sv_path_clip_halfplane(cp, -1, 0, fmin(2 * w, lim));     /* x <= 2w */
    sv_path_clip_halfplane(cp, 0, 1, fmin(h, lim));          /* y >= -h */
    sv_path_clip_halfplane(cp, 0, -1, fmin(2 * h, lim));     /* y <= 2h */
    sv_doc_warn(im->doc, "%s: %s reaches %g canvas units, beyond the core's limit of %g: cut to "
                "the canvas and its surroundings", d, what, far, (double)CS_CFG_COORD_LIMIT);
    return cp->n > 0;
}

/* Counts a region against the scene store's capacities; false (and the import fails) beyond. */
static bool within_capacity(imp *im, const sv_region *r, const sv_node *n)
{
    long pts = 0;
    for (int i = 0; i < r->ncontours; i++)
        pts += r->contours[i].count;
    im->points += pts;
    im->contours += r->ncontours;
    const char *what = NULL;
    long cap = 0;
    if (im->nitems + 1 > CS_CFG_MAX_REGIONS)
        what = "regions (CS_CFG_MAX_REGIONS)", cap = CS_CFG_MAX_REGIONS;
    else if (im->contours > CS_CFG_MAX_CONTOURS)
        what = "contours (CS_CFG_MAX_CONTOURS)", cap = CS_CFG_MAX_CONTOURS;
    else if (im->points > CS_CFG_MAX_POINTS)
        what = "control points (CS_CFG_MAX_POINTS)", cap = CS_CFG_MAX_POINTS;
    if (!what)
        return true;
    char d[160];
    desc(n, d, sizeof d);
    fail(im, "%s: the drawing needs more than the scene store's %ld %s", d, cap, what);
    return false;
}

/* Takes a region that leaves the list (or is replaced) off the counts within_capacity keeps. */
static void uncount(imp *im, const sv_region *r)
{
    for (int i = 0; i < r->ncontours; i++)
        im->points -= r->contours[i].count;
    im->contours -= r->ncontours;
}

static void add_region(imp *im, sv_path *cp, int rule, const sv_paint *paint, double opacity,
                       const ctx *c, const sv_node *n, const char *what)
{
    for (int k = 0; k < c->nclips; k++)
        sv_path_clip_polygon(cp, c->clips[k]->v, c->clips[k]->n);
    if (!within_limits(im, cp, n, what))
        return;
    sv_region r;
    memset(&r, 0, sizeof r);
    sv_path_to_contours(cp, &r.contours, &r.ncontours);
    if (r.ncontours == 0)
        return;
    if (!within_capacity(im, &r, n)) {
        for (int i = 0; i < r.ncontours; i++)
            sv_contour_free(&r.contours[i]);
        free(r.contours);
        return;
    }
    r.fill_rule = rule;
    r.paint = *paint;
    r.clip = c->ir_clip;
    r.bbox[0] = r.bbox[1] = INFINITY;
    r.bbox[2] = r.bbox[3] = -INFINITY;
    for (int i = 0; i < r.ncontours; i++)
        for (int k = 0; k < r.contours[i].count; k++) {
            const double *q = &r.contours[i].pts[3 * k];
            r.bbox[0] = fmin(r.bbox[0], q[0]);
            r.bbox[1] = fmin(r.bbox[1], q[1]);
            r.bbox[2] = fmax(r.bbox[2], q[0]);
            r.bbox[3] = fmax(r.bbox[3], q[1]);
        }
    char d[160], src[220];
    desc(n, d, sizeof d);
    snprintf(src, sizeof src, "%s %s", d, what);
    r.source = sv_xstrdup(src);
    bool translucent = paint->beta < 1;
    if (paint->gradient >= 0) {
        const sv_gradient *g = &im->doc->gradients[paint->gradient];
        if (!sv_gradient_bands(g, cp, opacity, &r, &im->band_work))
            sv_doc_warn(im->doc, "%s: no solid bands for the gradient (over SV_MAX_BAND_WORK): "
                        "where the core's paint functions cannot draw it, its average colour "
                        "is used", src);
        for (int i = 0; i < r.nbands; i++)
            r.bands[i].source = sv_xstrdup(src);
        /* translucent wherever any stop is (the bands may skip the clear ones) */
        for (int i = 0; i < g->nstops; i++)
            translucent |= g->stops[i].opacity * opacity < 1;
    }
    SV_GROW(im->items, im->nitems, im->capitems);
    item *it = &im->items[im->nitems++];
    it->reg = r;
    it->layer = c->layer;
    it->translucent = translucent;
    it->stroke = !strcmp(what, "stroke");
}

/* ------------------------------------------------------------ patterns */

/*
 * A <pattern> paint is drawn as its content: for every tile that meets the
 * painted area, the pattern's children are rendered as ordinary regions
 * with the tile's transform, clipped exactly to the tile (a convex polygon
 * cut into the geometry) and to the area: cut in too when the area is one
 * convex polygon; else, in tiles at the area's edge, a solid convex polygon
 * of content becomes the area cut to it, and other content is intersected
 * with the area by CSG (an IR clip). Opacity multiplies into the content as
 * group opacity does (one layer). The expansion is bounded: at most
 * SV_PATTERN_MAX_TILES tiles, no tile once another like the last would
 * pass the scene store's CS_CFG_MAX_REGIONS, half its control points per
 * paint, else the paint is left out with a warning naming the limit; and
 * SV_EXPAND_BUDGET for all patterns and masks of a drawing.
 */
#define SV_PATTERN_MAX_TILES 4096
#define SV_EXPAND_BUDGET (1L << 15)
#define SV_PATTERN_MAX_POINTS (CS_CFG_MAX_POINTS / 2)

static bool inside_area(const sv_path *p, int rule, sv_pt q)
{
    int w = 0;
    for (int i = 0; i < p->n; i++)
        w += sv_subpath_winding(&p->sub[i], q);
    return rule == CS_FILL_EVENODD ? (w & 1) != 0 : w != 0;
}

static bool box_meets(const double a[4], const double b[4])
{
    return a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
}

/* The tile (box tb, corners q) lies in the area: corners inside, no boundary near. */
static bool tile_inside(const sv_path *area, int rule, const sv_pt q[4], const double tb[4])
{
    for (int k = 0; k < 4; k++)
        if (!inside_area(area, rule, q[k]))
            return false;
    for (int i = 0; i < area->n; i++)
        for (int k = 0; k < area->sub[i].n; k++) {
            const sv_seg *g = &area->sub[i].seg[k];
            double sb[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
            for (int m = 0; m <= g->degree; m++) {
                sb[0] = fmin(sb[0], g->p[m].x);
                sb[1] = fmin(sb[1], g->p[m].y);
                sb[2] = fmax(sb[2], g->p[m].x);
                sb[3] = fmax(sb[3], g->p[m].y);
            }
            if (sb[0] <= tb[2] && tb[0] <= sb[2] && sb[1] <= tb[3] && tb[1] <= sb[3])
                return false;
        }
    return true;
}

static int area_clip(imp *im, const sv_path *area, int rule, int parent)
{
    sv_clip clip;
    memset(&clip, 0, sizeof clip);
    clip.parent = parent;
    add_clip_part(&clip, area, rule);
    im->doc->clips = sv_xrealloc(im->doc->clips, (size_t)(im->doc->nclips + 1) * sizeof clip);
    im->doc->clips[im->doc->nclips] = clip;
    return im->doc->nclips++;
}

/*
 * A tile region at the area's edge, cut to the area: a solid convex polygon
 * (a tile's rectangle, the usual content) becomes the area clipped exactly
 * to it; anything else is intersected with the area by CSG (the clip made
 * once per paint). Returns the control points the CSG adds.
 */
static long clip_to_area(imp *im, item *it, const sv_path *area, int rule, int *shape_clip,
                         const ctx *pc, const char *d)
{
    sv_region *r = &it->reg;
    if (r->clip != pc->ir_clip) {
        sv_doc_warn(im->doc, "%s: pattern content with a clip-path of its own is not cut to "
                    "the painted area", d);
        return 0;
    }
    if (r->ncontours == 1 && r->contours[0].degree == 1 && r->paint.gradient < 0) {
        const sv_contour *k = &r->contours[0];
        sv_path poly;
        sv_path_init(&poly);
        for (int i = 0; i < k->count; i++)
            (i ? sv_path_line : sv_path_move)(&poly, k->pts[3 * i], k->pts[3 * i + 1]);
        sv_path_close(&poly);
        sv_pt *v;
        int nv;
        bool cvx = sv_path_convex_polygon(&poly, &v, &nv);
        sv_path_free(&poly);
        if (cvx) {
            sv_path cut;
            sv_path_init(&cut);
            sv_path_append(&cut, area);
            sv_path_clip_polygon(&cut, v, nv);
            free(v);
            uncount(im, r);
            for (int i = 0; i < r->ncontours; i++)
                sv_contour_free(&r->contours[i]);
            free(r->contours);
            r->contours = NULL;
            r->ncontours = 0;
            sv_path_to_contours(&cut, &r->contours, &r->ncontours);
            sv_path_free(&cut);
            for (int i = 0; i < r->ncontours; i++)
                im->points += r->contours[i].count;
            im->contours += r->ncontours;
            r->fill_rule = rule;
            return 0;
        }
    }
    if (*shape_clip < 0)
        *shape_clip = area_clip(im, area, rule, pc->ir_clip);
    r->clip = *shape_clip;
    long n = 0;
    const sv_clip *c = &im->doc->clips[*shape_clip];
    for (int p = 0; p < c->nparts; p++)
        for (int i = 0; i < c->parts[p].ncontours; i++)
            n += c->parts[p].contours[i].count;
    return n;
}

/*
 * True when the paint is a pattern: drawn here, or left out with a warning.
 * A pattern that cannot apply (objectBoundingBox on a flat box) turns *ps
 * into its fallback colour (or none) and returns false.
 */
static bool paint_pattern(imp *im, const sv_node *n, sv_paint_spec *ps, double opacity,
                          const double ubox[4], const ctx *pc, const sv_path *area, int rule,
                          const char *what)
{
    sv_node *t = ps->kind == SV_PAINT_URL ? find_id(im, ps->url) : NULL;
    if (!t || strcmp(t->name, "pattern") != 0)
        return false;
    char d[160];
    desc(n, d, sizeof d);
    sv_pattern pat;
    if (!(opacity > 0) || area->n == 0)
        return true;
    sv_pattern_status st = sv_pattern_resolve(t, find_id, im, ubox, pc->vp_w, pc->vp_h, &pat,
                                              im->doc);
    if (st == SV_PATTERN_INVALID) {
        ps->kind = ps->fallback_kind;
        memcpy(ps->rgb, ps->fallback_rgb, sizeof ps->rgb);
        ps->alpha = 1;
        return false;
    }
    if (st != SV_PATTERN_OK)
        return true; /* SVG: such a pattern paints nothing */
    for (int i = 0; i < im->depth; i++)
        if (im->stack[i] == pat.content) {
            sv_doc_warn(im->doc, "%s: %s pattern #%s is used inside itself, not painted", d,
                        what, ps->url);
            return true;
        }
    if (im->depth >= SV_MAX_DEPTH - 1)
        return true; /* render() fails on the depth */
    /* the tiles meeting the area's box, taken back to user space */
    double abox[4], ub[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    sv_path_bbox(area, abox);
    for (int k = 0; k < pc->nclips; k++) { /* only what the context's convex clips let show */
        double cb[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
        for (int m = 0; m < pc->clips[k]->n; m++) {
            cb[0] = fmin(cb[0], pc->clips[k]->v[m].x);
            cb[1] = fmin(cb[1], pc->clips[k]->v[m].y);
            cb[2] = fmax(cb[2], pc->clips[k]->v[m].x);
            cb[3] = fmax(cb[3], pc->clips[k]->v[m].y);
        }
        abox[0] = fmax(abox[0], cb[0]);
        abox[1] = fmax(abox[1], cb[1]);
        abox[2] = fmin(abox[2], cb[2]);
        abox[3] = fmin(abox[3], cb[3]);
    }
    if (!(abox[0] < abox[2] && abox[1] < abox[3]))
        return true;
    sv_affine inv;
    if (!sv_affine_invert(pc->ctm, &inv))
        return true;
    for (int k = 0; k < 4; k++) {
        sv_pt q = sv_affine_apply(inv, sv_pt_make(abox[k & 1 ? 2 : 0], abox[k & 2 ? 3 : 1]));
        ub[0] = fmin(ub[0], q.x);
        ub[1] = fmin(ub[1], q.y);
        ub[2] = fmax(ub[2], q.x);
        ub[3] = fmax(ub[3], q.y);
    }
    long i0, i1, j0, j1;
    if (!sv_pattern_tile_range(&pat, ub, &i0, &i1, &j0, &j1) ||
        (double)(i1 - i0) * (double)(j1 - j0) > SV_PATTERN_MAX_TILES) {
        sv_doc_warn(im->doc, "%s: %s pattern #%s needs more than %d tiles, not painted", d, what,
                    ps->url, SV_PATTERN_MAX_TILES);
        return true;
    }
    ctx c = *pc;
    c.alpha = opacity;
    if (opacity < 1 && c.layer == 0)
        c.layer = ++im->next_layer; /* the tile's content is translucent as a group */
    clip_poly whole = {NULL, 0};
    bool convex = c.nclips < MAX_CLIPS - 1 && sv_path_convex_polygon(area, &whole.v, &whole.n);
    if (convex)
        c.clips[c.nclips++] = &whole;
    int shape_clip = -1, start = im->nitems, last = 0; /* regions the last tile added */
    long points = 0;
    sv_style cs;
    style_of(im, pat.content, &cs);
    sv_affine tm = sv_affine_mul(pc->ctm, pat.transform);
    im->stack[im->depth++] = pat.content;
    for (long j = j0; j < j1; j++)
        for (long i = i0; i < i1; i++) {
            double tx = pat.x + (double)i * pat.w, ty = pat.y + (double)j * pat.h;
            sv_pt q[4] = {sv_affine_apply(tm, sv_pt_make(tx, ty)),
                          sv_affine_apply(tm, sv_pt_make(tx + pat.w, ty)),
                          sv_affine_apply(tm, sv_pt_make(tx + pat.w, ty + pat.h)),
                          sv_affine_apply(tm, sv_pt_make(tx, ty + pat.h))};
            double tb[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
            for (int k = 0; k < 4; k++) {
                tb[0] = fmin(tb[0], q[k].x);
                tb[1] = fmin(tb[1], q[k].y);
                tb[2] = fmax(tb[2], q[k].x);
                tb[3] = fmax(tb[3], q[k].y);
            }
            if (!box_meets(tb, abox))
                continue;
            ctx tc = c;
            tc.ctm = sv_affine_mul(pc->ctm, sv_pattern_content_map(&pat, i, j));
            clip_poly tile = {q, 4};
            if (tc.nclips < MAX_CLIPS)
                tc.clips[tc.nclips++] = &tile;
            if (im->failed)
                break;
            if (im->expanded > SV_EXPAND_BUDGET) {
                sv_doc_warn(im->doc, "%s: %s pattern #%s: patterns and masks of the drawing "
                            "expand to more than %ld regions and tiles, the rest not painted",
                            d, what, ps->url, SV_EXPAND_BUDGET);
                break;
            }
            int before = im->nitems;
            long p0 = points;
            for (int k = 0; k < pat.content->nkids; k++)
                render(im, pat.content->kids[k], &cs, &tc);
            im->expanded += 1 + im->nitems - before;
            if (!convex && !tile_inside(area, rule, q, tb)) {
                int kept = before;
                for (int k = before; k < im->nitems; k++) {
                    points += clip_to_area(im, &im->items[k], area, rule, &shape_clip, pc, d);
                    if (im->items[k].reg.ncontours > 0)
                        im->items[kept++] = im->items[k];
                    else
                        sv_region_free(&im->items[k].reg);
                }
                im->nitems = kept;
            }
            for (int k = before; k < im->nitems; k++)
                for (int m = 0; m < im->items[k].reg.ncontours; m++)
                    points += im->items[k].reg.contours[m].count;
            /* stop before the scene store overflows: another tile like this one would */
            last = im->nitems - before;
            if (im->nitems + last > CS_CFG_MAX_REGIONS || points > SV_PATTERN_MAX_POINTS ||
                im->points + (points - p0) > CS_CFG_MAX_POINTS) {
                for (int k = start; k < im->nitems; k++) {
                    uncount(im, &im->items[k].reg);
                    sv_region_free(&im->items[k].reg);
                }
                im->nitems = start;
                sv_doc_warn(im->doc, "%s: %s pattern #%s expands past the scene store's %d "
                            "regions or %d control points, not painted", d, what, ps->url,
                            CS_CFG_MAX_REGIONS, SV_PATTERN_MAX_POINTS);
                i = i1;
                j = j1;
            }
        }
    im->depth--;
    free(whole.v);
    return true;
}

static void add_clip_part(sv_clip *clip, const sv_path *p, int rule)
{
    struct sv_clip_part part = {rule, 0, NULL, -1};
    sv_path_to_contours(p, &part.contours, &part.ncontours);
    if (part.ncontours == 0)
        return;
    clip->parts = sv_xrealloc(clip->parts, (size_t)(clip->nparts + 1) * sizeof part);
    clip->parts[clip->nparts++] = part;
}

/* The fill; its canvas-space path also goes to `keep` when given. */
static void paint_fill(imp *im, const sv_node *n, const sv_style *s, const ctx *pc,
                       const sv_path *up, double opacity, const double ubox[4], sv_path *keep)
{
    const ctx c = *pc;
    sv_path cp;
    sv_path_init(&cp);
    sv_path_append(&cp, up);
    sv_path_transform(&cp, c.ctm);
    sv_paint paint;
    sv_paint_spec spec = s->fill;
    if (!paint_pattern(im, n, &spec, s->fill_opacity * opacity, ubox, &c, &cp, s->fill_rule,
                       "fill") &&
        resolve_paint(im, n, &spec, s, s->fill_opacity * opacity, ubox, &c, &cp, s->fill_rule,
                      "fill", &paint))
        add_region(im, &cp, s->fill_rule, &paint, s->fill_opacity * opacity, &c, n, "fill");
    if (keep)
        sv_path_append(keep, &cp);
    sv_path_free(&cp);
}

/* The stroke; its canvas-space outline also goes to `keep` when given. */
static void paint_stroke(imp *im, const sv_node *n, const sv_style *s, const ctx *pc,
                         const sv_path *up, double opacity, const double ubox[4], sv_path *keep)
{
    const ctx c = *pc;
    char d[160];
    /* a negative dash length is an error, and SVG then strokes solid */
    bool dashed = s->has_dash;
    for (int i = 0; i < s->ndash; i++)
        dashed &= s->dash[i] >= 0;
    sv_path dashes;
    sv_path_init(&dashes);
    if (dashed && sv_path_dash(up, s->dash, s->ndash, s->dash_offset, SV_MAX_DASHES,
                               &dashes) < 0) {
        sv_path_free(&dashes);
        desc(n, d, sizeof d);
        fail(im, "%s: stroke-dasharray makes more than %d dashes (SV_MAX_DASHES: the scene "
             "store's control points hold no more)", d, SV_MAX_DASHES);
        return;
    }
    double scale = sv_affine_max_scale(c.ctm);
    sv_stroke_style st = {s->stroke_width, s->cap, s->join, s->miter_limit,
                          scale > 0 ? im->tol / scale : im->tol,
                          CS_CFG_MAX_POINTS - im->points + 1};
    sv_path outline;
    sv_path_init(&outline);
    int missed = sv_stroke_path(dashed ? &dashes : up, &st, &outline);
    sv_path_free(&dashes);
    if (missed < 0) {
        sv_path_free(&outline);
        desc(n, d, sizeof d);
        fail(im, "%s: the stroke's outline needs more than the scene store's %ld control "
             "points left (CS_CFG_MAX_POINTS)", d, CS_CFG_MAX_POINTS - im->points);
        return;
    }
    if (missed) {
        desc(n, d, sizeof d);
        sv_doc_warn(im->doc, "%s: stroke outline above tolerance in %d pieces", d, missed);
    }
    sv_path_transform(&outline, c.ctm);
    /* objectBoundingBox for strokes is still the fill's box (SVG 1.1) */
    sv_paint paint;
    sv_paint_spec spec = s->stroke;
    if (!paint_pattern(im, n, &spec, s->stroke_opacity * opacity, ubox, &c, &outline,
                       CS_FILL_NONZERO, "stroke") &&
        resolve_paint(im, n, &spec, s, s->stroke_opacity * opacity, ubox, &c, &outline,
                      CS_FILL_NONZERO, "stroke", &paint))
        add_region(im, &outline, CS_FILL_NONZERO, &paint, s->stroke_opacity * opacity, &c, n,
                   "stroke");
    if (keep)
        sv_path_append(keep, &outline);
    sv_path_free(&outline);
}

/*
 * Markers (SVG 1.1 11.6) on the vertices of a path, line, polyline or
 * polygon: each an instance of the marker's content, oriented and scaled at
 * the vertex and clipped to the marker's viewport.
 */
static void render_markers(imp *im, const sv_node *n, const sv_style *s, const ctx *c,
                           const sv_path *up);

/*
 * Fill, stroke and markers of one shape, given its user-space path, in the
 * order paint-order says; `markers` for the shapes that take them.
 */
static void paint_shape(imp *im, const sv_node *n, const sv_style *s, const ctx *pc,
                        sv_path *up, bool markers)
{
    if (!s->visible)
        return;
    ctx c = *pc;
    double opacity = c.alpha * s->opacity;
    bool fill = s->fill.kind != SV_PAINT_NONE, stroke = s->stroke.kind != SV_PAINT_NONE &&
                                                          s->stroke_width > 0;
    bool marked = markers && (s->marker[0][0] || s->marker[1][0] || s->marker[2][0]);
    if (((fill && stroke) || marked) && s->opacity < 1 && c.layer == 0)
        c.layer = ++im->next_layer; /* fill, stroke and markers composite as a group */
    if (marked && s->opacity < 1) { /* the markers' content takes it from the context */
        c.alpha *= s->opacity;
        opacity = c.alpha;
    }
    double ubox[4]; /* the tight box costs 256 samples a curve: only paint servers use it */
    if (c.obj_box)
        memcpy(ubox, c.obj_box, sizeof ubox);
    else if (s->fill.kind == SV_PAINT_URL || s->stroke.kind == SV_PAINT_URL)
        tight_bbox(up, ubox);
    else
        sv_path_bbox(up, ubox);
    c.obj_box = NULL;
    /*
     * A translucent group of a solid fill and a solid stroke where the upper
     * one is translucent: in one cel the upper region would hide the lower
     * one where they overlap. The overlap gets a region of its own in front,
     * painted with the two composited (upper over lower), and drawn as the
     * upper geometry intersected with the lower (CSG).
     */
    const sv_paint_spec *upper = strchr(s->paint_order, 'F') > strchr(s->paint_order, 'S')
                                     ? &s->fill : &s->stroke;
    double ua = upper == &s->fill ? s->fill_opacity : s->stroke_opacity;
    bool overlap = fill && stroke && c.layer != 0 && ua * upper->alpha < 1 &&
                   s->fill.kind != SV_PAINT_URL && s->stroke.kind != SV_PAINT_URL;
    sv_path geo[2]; /* fill, stroke */
    sv_path_init(&geo[0]);
    sv_path_init(&geo[1]);
    for (const char *o = s->paint_order; *o && !im->failed; o++) {
        if (*o == 'F' && fill)
            paint_fill(im, n, s, &c, up, opacity, ubox, overlap ? &geo[0] : NULL);
        else if (*o == 'S' && stroke)
            paint_stroke(im, n, s, &c, up, opacity, ubox, overlap ? &geo[1] : NULL);
        else if (*o == 'M' && marked)
            render_markers(im, n, s, &c, up);
    }
    if (overlap && !im->failed && geo[0].n > 0 && geo[1].n > 0) {
        bool fill_up = upper == &s->fill;
        const sv_paint_spec *lower = fill_up ? &s->stroke : &s->fill;
        double la = (fill_up ? s->stroke_opacity : s->fill_opacity) * lower->alpha;
        double uc[3], lc[3];
        memcpy(uc, upper->kind == SV_PAINT_CURRENT ? s->color : upper->rgb, sizeof uc);
        memcpy(lc, lower->kind == SV_PAINT_CURRENT ? s->color : lower->rgb, sizeof lc);
        ua *= upper->alpha;
        double a = ua + la * (1 - ua);
        sv_paint paint = {{0, 0, 0}, {1, 1, 1}, a * opacity, -1, 1};
        for (int k = 0; k < 3; k++)
            paint.pigment[k] = a > 0 ? (uc[k] * ua + lc[k] * la * (1 - ua)) / a : 0;
        sv_clip clip; /* the lower geometry, as the clip of the upper */
        memset(&clip, 0, sizeof clip);
        clip.parent = c.ir_clip;
        add_clip_part(&clip, &geo[fill_up ? 1 : 0], fill_up ? CS_FILL_NONZERO : s->fill_rule);
        im->doc->clips = sv_xrealloc(im->doc->clips, (size_t)(im->doc->nclips + 1) * sizeof clip);
        im->doc->clips[im->doc->nclips] = clip;
        ctx oc = c;
        oc.ir_clip = im->doc->nclips++;
        oc.nclips = 0; /* the convex clips are in both geometries already */
        add_region(im, &geo[fill_up ? 0 : 1], fill_up ? s->fill_rule : CS_FILL_NONZERO, &paint,
                   a * opacity, &oc, n, "fill and stroke overlap");
    }
    sv_path_free(&geo[0]);
    sv_path_free(&geo[1]);
}

/* --------------------------------------------------------------- masks */

/*
 * mask="url(#m)" on an element (sv_mask.c has the model): the element's
 * regions, items [start, nitems), are replaced by their parts under each
 * painted region of the mask's content, which is rendered like any drawing
 * (user space or the bounding box for its units, clipped to the mask's x,
 * y, width, height), with the mask's own mask applied to it first. The
 * copies share one layer (cel), so front content hides back content as in
 * the group SVG masks as a whole.
 */
static double frac_attr(const sv_node *n, const char *name, double dflt)
{
    const char *v = sv_attr(n, name);
    double x;
    if (!v || !sv_parse_number(&v, &x) || !isfinite(x))
        return dflt;
    return *v == '%' ? x / 100 : x;
}

static bool mask_alpha(const sv_node *m)
{
    const char *t = sv_attr(m, "mask-type"), *st = sv_attr(m, "style");
    const char *p = st ? strstr(st, "mask-type") : NULL;
    if (p) {
        p += strlen("mask-type");
        while (*p == ' ' || *p == ':')
            p++;
        t = p;
    }
    return t && !strncmp(t, "alpha", 5);
}

/* User-space box of the fills among items [start, nitems) (all of them if none is a fill). */
static bool items_box(const imp *im, int start, sv_affine ctm, double box[4])
{
    sv_affine inv;
    if (!sv_affine_invert(ctm, &inv))
        return false;
    bool fills = false;
    for (int i = start; i < im->nitems; i++)
        fills |= !im->items[i].stroke;
    box[0] = box[1] = INFINITY;
    box[2] = box[3] = -INFINITY;
    for (int i = start; i < im->nitems; i++) {
        const sv_region *r = &im->items[i].reg;
        if (fills && im->items[i].stroke)
            continue;
        for (int k = 0; k < r->ncontours; k++)
            for (int j = 0; j < r->contours[k].count; j++) {
                const double *q = &r->contours[k].pts[3 * j];
                sv_pt u = sv_affine_apply(inv, sv_pt_make(q[0], q[1]));
                box[0] = fmin(box[0], u.x);
                box[1] = fmin(box[1], u.y);
                box[2] = fmax(box[2], u.x);
                box[3] = fmax(box[3], u.y);
            }
    }
    return box[0] <= box[2];
}

static void drop_items(imp *im, int start)
{
    for (int i = start; i < im->nitems; i++) {
        uncount(im, &im->items[i].reg);
        sv_region_free(&im->items[i].reg);
    }
    im->nitems = start;
}

/* Whether the masks on masks from `id` lead back to mask m (resvg then drops m's own mask). */
static bool mask_chain_returns(imp *im, const sv_node *m, const char *id)
{
    char cur[128];
    snprintf(cur, sizeof cur, "%s", id);
    for (int step = 0; step < 16; step++) {
        sv_node *e = find_id(im, cur);
        if (!e || strcmp(e->name, "mask") != 0)
            return false;
        if (e == m) {
            char d[160];
            desc(m, d, sizeof d);
            sv_doc_warn(im->doc, "%s: its mask leads back to itself, ignored", d);
            return true;
        }
        sv_style es;
        style_of(im, e, &es);
        if (!es.mask[0])
            return false;
        snprintf(cur, sizeof cur, "%s", es.mask);
    }
    return true; /* a chain that long is a cycle that does not pass through m */
}

static bool is_unmasked(const imp *im, const sv_node *n)
{
    for (int i = 0; i < im->nunmasked; i++)
        if (im->unmasked[i] == n)
            return true;
    return false;
}

static void apply_mask(imp *im, const sv_node *n, const char *id, const ctx *c, int start,
                       const sv_path *up)
{
    char d[160];
    desc(n, d, sizeof d);
    sv_node *m = find_id(im, id);
    if (!m || strcmp(m->name, "mask") != 0) {
        sv_doc_warn(im->doc, "%s: mask #%s not found, drawn unmasked", d, id);
        return;
    }
    for (int i = 0; i < im->depth; i++)
        if (im->stack[i] == m) {
            sv_doc_warn(im->doc, "%s: mask #%s used inside itself, drawn unmasked", d, id);
            SV_GROW(im->unmasked, im->nunmasked, im->capunmasked);
            im->unmasked[im->nunmasked++] = n;
            return;
        }
    if (im->depth >= SV_MAX_DEPTH - 1) {
        drop_items(im, start);
        return;
    }
    double bbox[4] = {0, 0, 0, 0};
    bool have_box = up ? true : items_box(im, start, c->ctm, bbox);
    if (up)
        tight_bbox(up, bbox);
    const char *units = sv_attr(m, "maskUnits"), *cunits = sv_attr(m, "maskContentUnits");
    bool obb = !units || strcmp(units, "userSpaceOnUse") != 0;
    bool content_obb = cunits && !strcmp(cunits, "objectBoundingBox");
    double bw = bbox[2] - bbox[0], bh = bbox[3] - bbox[1];
    if ((obb || content_obb) && !(have_box && bw > 0 && bh > 0)) {
        drop_items(im, start); /* objectBoundingBox on a flat box: nothing shows */
        return;
    }
    sv_style ms;
    style_of(im, m, &ms);
    double x, y, w, h;
    if (obb) {
        x = bbox[0] + frac_attr(m, "x", -0.1) * bw;
        y = bbox[1] + frac_attr(m, "y", -0.1) * bh;
        w = frac_attr(m, "width", 1.2) * bw;
        h = frac_attr(m, "height", 1.2) * bh;
    } else {
        x = attr_len(m, "x", &ms, c->vp_w, -0.1 * c->vp_w);
        y = attr_len(m, "y", &ms, c->vp_h, -0.1 * c->vp_h);
        w = attr_len(m, "width", &ms, c->vp_w, 1.2 * c->vp_w);
        h = attr_len(m, "height", &ms, c->vp_h, 1.2 * c->vp_h);
    }
    if (!(w > 0 && h > 0)) {
        drop_items(im, start);
        return;
    }
    /* the mask's content, clipped to its region */
    sv_pt q[4] = {sv_affine_apply(c->ctm, sv_pt_make(x, y)),
                  sv_affine_apply(c->ctm, sv_pt_make(x + w, y)),
                  sv_affine_apply(c->ctm, sv_pt_make(x + w, y + h)),
                  sv_affine_apply(c->ctm, sv_pt_make(x, y + h))};
    clip_poly region = {q, 4};
    ctx mc;
    memset(&mc, 0, sizeof mc);
    mc.ctm = c->ctm;
    if (content_obb) {
        sv_affine b = {bw, 0, 0, bh, bbox[0], bbox[1]};
        mc.ctm = sv_affine_mul(mc.ctm, b);
    }
    mc.alpha = 1;
    mc.ir_clip = -1;
    mc.vp_w = c->vp_w;
    mc.vp_h = c->vp_h;
    mc.clips[mc.nclips++] = &region;
    if (im->expanded > SV_EXPAND_BUDGET) {
        sv_doc_warn(im->doc, "%s: mask #%s: patterns and masks of the drawing expand to more "
                    "than %ld regions and tiles, not drawn", d, id, SV_EXPAND_BUDGET);
        drop_items(im, start);
        return;
    }
    int mstart = im->nitems;
    im->stack[im->depth++] = m;
    for (int i = 0; i < m->nkids; i++)
        render(im, m->kids[i], &ms, &mc);
    im->expanded += 1 + im->nitems - mstart;
    /* a mask on the mask masks its content, in the masked element's user space */
    if (ms.mask[0] && !mask_chain_returns(im, m, ms.mask))
        apply_mask(im, m, ms.mask, c, mstart, NULL);
    im->depth--;

    /* take the content and the mask's regions out of the list, put the copies in */
    int ncontent = mstart - start, nmask = im->nitems - mstart;
    item *content = sv_xrealloc(NULL, (size_t)(ncontent + nmask + 1) * sizeof *content);
    if (ncontent + nmask > 0) /* im->items may still be NULL */
        memcpy(content, im->items + start, (size_t)(ncontent + nmask) * sizeof *content);
    const item *mask = content + ncontent;
    im->nitems = start;
    for (int i = 0; i < ncontent + nmask; i++)
        uncount(im, &content[i].reg);
    sv_mask_mode mode = {!mask_alpha(m)};
    for (int k = 1; k < nmask; k++) /* a front mask shape that lets some through hides the back one */
        for (int j = 0; j < k; j++)
            if (box_meets(mask[j].reg.bbox, mask[k].reg.bbox) && mask[k].translucent) {
                sv_doc_warn(im->doc, "%s: mask #%s has overlapping translucent shapes: "
                            "approximated (the front one decides)", d, id);
                j = k = nmask;
            }
    if ((long)ncontent * nmask > CS_CFG_MAX_REGIONS) {
        sv_doc_warn(im->doc, "%s: mask #%s needs %ld regions (%d masked by %d mask shapes; "
                    "limit %d), not drawn", d, id, (long)ncontent * nmask, ncontent, nmask,
                    CS_CFG_MAX_REGIONS);
        ncontent = 0;
    }
    int layer = c->layer ? c->layer : ++im->next_layer;
    for (int i = 0; i < ncontent && !im->failed; i++)
        for (int k = 0; k < nmask && !im->failed; k++) {
            sv_region r;
            if (!sv_mask_region(im->doc, &content[i].reg, &mask[k].reg, mode, d, &r))
                continue;
            if (!within_capacity(im, &r, n)) {
                sv_region_free(&r);
                break;
            }
            SV_GROW(im->items, im->nitems, im->capitems);
            item *it = &im->items[im->nitems++];
            it->reg = r;
            it->layer = layer;
            it->translucent = r.paint.beta < 1 || r.paint.gradient >= 0;
            it->stroke = content[i].stroke;
        }
    for (int i = 0; i < mstart - start + nmask; i++)
        sv_region_free(&content[i].reg);
    free(content);
}

/* ------------------------------------------------------------ clipping */

/*
 * The clip path's children in canvas units, as parts of an IR clip (see
 * sv_clip in sv.h): a clipPath is the union of its children, each under its
 * own clip-rule. Nonzero children go into one part, each turned so its
 * largest subpath winds positively: with no child winding negatively, their
 * summed winding is non-zero exactly on the union. An evenodd child joins
 * an evenodd part whose children's boxes its box does not meet (without
 * overlap, parity is union), or starts one. `all` gets every child unchanged
 * (the convex test).
 */
typedef struct eo_part {
    sv_path path;
    double (*boxes)[4]; /* of its children */
    int nboxes;
} eo_part;

typedef struct clip_parts {
    sv_path all;
    sv_path nz; /* the shared nonzero part */
    eo_part *eo;
    int neo;
    int nchildren;
    bool only_shapes;
    /* clip-path on the clipPath: it intersects the clip */
    char self_clip[128];
    /* children with a clip-path of their own: a part each, intersected with that clip */
    struct own_part {
        sv_path path;
        int rule, clip;
    } *own;
    int nown;
} clip_parts;

static void add_evenodd(clip_parts *out, sv_path *p)
{
    double box[4];
    sv_path_bbox(p, box);
    int k = 0;
    for (; k < out->neo; k++) {
        bool apart = true;
        for (int i = 0; i < out->eo[k].nboxes && apart; i++) {
            const double *b = out->eo[k].boxes[i];
            apart = box[2] < b[0] || b[2] < box[0] || box[3] < b[1] || b[3] < box[1];
        }
        if (apart)
            break;
    }
    if (k == out->neo) {
        out->eo = sv_xrealloc(out->eo, (size_t)(out->neo + 1) * sizeof *out->eo);
        memset(&out->eo[out->neo++], 0, sizeof *out->eo);
        sv_path_init(&out->eo[k].path);
    }
    eo_part *e = &out->eo[k];
    sv_path_append(&e->path, p);
    e->boxes = sv_xrealloc(e->boxes, (size_t)(e->nboxes + 1) * sizeof *e->boxes);
    memcpy(e->boxes[e->nboxes++], box, sizeof box);
}

static void orient_positive(sv_path *p)
{
    double best = 0;
    for (int i = 0; i < p->n; i++) {
        double a = sv_subpath_area(&p->sub[i]);
        if (fabs(a) > fabs(best))
            best = a;
    }
    if (best < 0)
        sv_path_reverse(p);
}

/* A clip child's path into the parts (in canvas units by km) under its clip-rule. */
static void add_clip_child(clip_parts *out, sv_path *p, sv_affine km, int rule)
{
    sv_path_transform(p, km);
    sv_path_append(&out->all, p);
    out->nchildren++;
    if (rule == CS_FILL_EVENODD) { /* even one contour: it may cross itself */
        add_evenodd(out, p);
        return;
    }
    orient_positive(p);
    sv_path_append(&out->nz, p);
}

static void apply_clip(imp *im, const sv_node *n, const char *id, ctx *c, const sv_path *up,
                       clip_poly *slot, bool *used_slot);

static void clip_geometry(imp *im, sv_node *cp, sv_affine ctm, const double ubox[4],
                          const ctx *pc, clip_parts *out)
{
    const char *units = sv_attr(cp, "clipPathUnits");
    sv_affine m = ctm, t;
    const char *tr = sv_attr(cp, "transform");
    if (tr && sv_parse_transform(tr, &t))
        m = sv_affine_mul(m, t);
    if (units && !strcmp(units, "objectBoundingBox")) {
        sv_affine b = {ubox[2] - ubox[0], 0, 0, ubox[3] - ubox[1], ubox[0], ubox[1]};
        m = sv_affine_mul(m, b);
    }
    char d[160];
    sv_style cs; /* its properties come from where it is defined, not from where it is used */
    style_of(im, cp, &cs);
    snprintf(out->self_clip, sizeof out->self_clip, "%s", cs.clip_path);
    for (int i = 0; i < cp->nkids && !im->failed; i++) {
        sv_node *k = cp->kids[i];
        sv_node *shape = k;
        sv_affine km = m;
        const char *ktr = sv_attr(k, "transform");
        if (ktr && sv_parse_transform(ktr, &t))
            km = sv_affine_mul(km, t);
        if (!strcmp(k->name, "use")) {
            shape = find_href(im, k);
            if (!shape)
                continue;
            sv_affine tu = {1, 0, 0, 1, attr_len(k, "x", &cs, pc->vp_w, 0),
                            attr_len(k, "y", &cs, pc->vp_h, 0)};
            km = sv_affine_mul(km, tu);
            const char *str = sv_attr(shape, "transform");
            if (str && sv_parse_transform(str, &t))
                km = sv_affine_mul(km, t);
        }
        sv_style ks;
        sv_style_compute(&ks, &cs, shape, &im->css, 0, NULL);
        if (ks.display_none || !ks.visible)
            continue;
        sv_path p;
        sv_path_init(&p);
        if (ks.clip_path[0] && shape == k && shape_path(im, shape, &ks, pc, &p)) {
            /* (child AND its clip) in a part of its own: the clip in the child's space */
            ctx kc = *pc;
            kc.ctm = km;
            kc.nclips = 0;
            kc.ir_clip = -1;
            apply_clip(im, k, ks.clip_path, &kc, &p, NULL, NULL);
            out->own = sv_xrealloc(out->own, (size_t)(out->nown + 1) * sizeof *out->own);
            struct own_part *o = &out->own[out->nown++];
            sv_path_init(&o->path);
            sv_path_transform(&p, km);
            sv_path_append(&o->path, &p);
            sv_path_append(&out->all, &p);
            o->rule = ks.clip_rule;
            o->clip = kc.ir_clip;
            out->nchildren++;
            out->only_shapes = false; /* never a convex cut */
        } else if (shape_path(im, shape, &ks, pc, &p)) {
            add_clip_child(out, &p, km, ks.clip_rule);
        } else if (!strcmp(shape->name, "text")) {
            /* glyph outlines; the clip takes their union, as of any shapes */
            sv_text_run *runs;
            int nr = sv_svg_text_layout(shape, &ks, &im->css, pc->vp_w, pc->vp_h, fonts_of(im),
                                        &runs, im->doc);
            sv_path glyphs;
            sv_path_init(&glyphs);
            for (int r = 0; r < nr; r++)
                sv_path_append(&glyphs, &runs[r].path);
            sv_text_runs_free(runs, nr);
            if (glyphs.n > 0) {
                out->only_shapes = false; /* several contours: never a convex cut */
                add_clip_child(out, &glyphs, km, CS_FILL_NONZERO);
            }
            sv_path_free(&glyphs);
        } else if (strcmp(shape->name, "title") && strcmp(shape->name, "desc") &&
                   shape->name[0] != '#' && strncmp(shape->name, "ns:", 3) != 0) {
            out->only_shapes = false;
            desc(shape, d, sizeof d);
            sv_doc_warn(im->doc, "%s: not supported in a clipPath, left out of the clip", d);
        }
        sv_path_free(&p);
    }
}


/*
 * Applies clip-path to the context: a single convex polygon is clipped
 * exactly into the geometry; anything else becomes an IR clip that the back
 * ends intersect by CSG (sv_doc_plan warns where they cannot).
 */
/*
 * Applies clip-path #id to the context. A clip path's own clip-path (on the
 * clipPath, or on its only child) intersects it too, so it joins the chain;
 * a reference back into a clip path being applied is ignored, as resvg
 * does, and warned. `slot` NULL: no convex cut (the nested ones).
 */
static void apply_clip(imp *im, const sv_node *n, const char *id, ctx *c, const sv_path *up,
                       clip_poly *slot, bool *used_slot)
{
    if (im->failed)
        return;
    char d[160];
    desc(n, d, sizeof d);
    sv_node *cp = find_id(im, id);
    if (!cp || strcmp(cp->name, "clipPath") != 0) {
        /* SVG 1.1: a reference to a non-existent object is an error; rsvg ignores it */
        sv_doc_warn(im->doc, "%s: clip-path #%s not found, ignored", d, id);
        return;
    }
    for (int i = 0; i < im->nclipping; i++)
        if (im->clipping[i] == cp) {
            sv_doc_warn(im->doc, "%s: clip-path #%s refers back to itself, reference ignored", d,
                        id);
            return;
        }
    if (im->nclipping == MAX_CLIPS) {
        sv_doc_warn(im->doc, "%s: clip-path #%s nested more than %d deep, ignored", d, id,
                    MAX_CLIPS);
        return;
    }
    double ubox[4] = {0, 0, 0, 0};
    if (up)
        tight_bbox(up, ubox);
    clip_parts parts;
    memset(&parts, 0, sizeof parts);
    parts.only_shapes = true;
    sv_path_init(&parts.all);
    sv_path_init(&parts.nz);
    im->clipping[im->nclipping++] = cp; /* its children's clips may not come back to it */
    clip_geometry(im, cp, c->ctm, ubox, c, &parts);
    for (int i = 0; i < parts.all.n; i++)
        im->clip_points += parts.all.sub[i].n;
    if (im->clip_points > SV_MAX_CLIP_POINTS)
        fail(im, "%s: clip paths applied take more than %d control points (SV_MAX_CLIP_POINTS)",
             d, SV_MAX_CLIP_POINTS);
    sv_pt *poly;
    int np;
    if (im->failed) {
        /* nothing more is drawn */
    } else if (slot && parts.only_shapes && parts.nchildren == 1 && c->nclips < MAX_CLIPS &&
               sv_path_convex_polygon(&parts.all, &poly, &np)) {
        slot->v = poly;
        slot->n = np;
        *used_slot = true;
        c->clips[c->nclips++] = slot;
    } else {
        /* an IR clip for CSG; an empty one clips everything away */
        sv_clip clip;
        memset(&clip, 0, sizeof clip);
        clip.parent = c->ir_clip;
        add_clip_part(&clip, &parts.nz, CS_FILL_NONZERO);
        for (int i = 0; i < parts.neo; i++)
            add_clip_part(&clip, &parts.eo[i].path, CS_FILL_EVENODD);
        for (int i = 0; i < parts.nown; i++) {
            int before = clip.nparts;
            add_clip_part(&clip, &parts.own[i].path, parts.own[i].rule);
            if (clip.nparts > before)
                clip.parts[before].clip = parts.own[i].clip;
        }
        im->doc->clips = sv_xrealloc(im->doc->clips, (size_t)(im->doc->nclips + 1) * sizeof clip);
        im->doc->clips[im->doc->nclips] = clip;
        c->ir_clip = im->doc->nclips++;
    }
    if (parts.self_clip[0])
        apply_clip(im, cp, parts.self_clip, c, up, NULL, NULL);
    im->nclipping--;
    for (int i = 0; i < parts.nown; i++)
        sv_path_free(&parts.own[i].path);
    free(parts.own);
    sv_path_free(&parts.all);
    sv_path_free(&parts.nz);
    for (int i = 0; i < parts.neo; i++) {
        sv_path_free(&parts.eo[i].path);
        free(parts.eo[i].boxes);
    }
    free(parts.eo);
}

/* ----------------------------------------------------------- elements */

static void render_children(imp *im, sv_node *n, const sv_style *s, const ctx *c)
{
    for (int i = 0; i < n->nkids; i++)
        render(im, n->kids[i], s, c);
}

static bool is_nonrendering(const char *name)
{
    static const char *const names[] = {
        "defs", "clipPath", "mask", "linearGradient", "radialGradient", "pattern", "marker",
        "symbol", "style", "title", "desc", "metadata", "filter", "stop", "font", "font-face",
        "cursor", "view", "script", "animate", "set", "animateMotion", "animateTransform",
        "animateColor", "color-profile", "missing-glyph", "glyph", NULL};
    for (int i = 0; names[i]; i++)
        if (!strcmp(name, names[i]))
            return true;
    return false;
}

/*
 * A property the style computation does not keep (it matters on one kind of
 * element only): the style attribute's declaration, else the attribute.
 * Malloc'd, or NULL.
 */
static char *own_property(const sv_node *n, const char *name)
{
    const char *st = sv_attr(n, "style");
    char *own = NULL;
    if (st) {
        sv_decl *d;
        int nd = sv_css_parse_decls(st, &d);
        for (int i = 0; i < nd; i++)
            if (!strcmp(d[i].name, name)) {
                free(own);
                own = sv_xstrdup(d[i].value);
            }
        sv_decls_free(d, nd);
    }
    const char *v = sv_attr(n, name);
    return own ? own : v ? sv_xstrdup(v) : NULL;
}

/* The overflow property: whether it lets content show. */
static bool overflow_visible(const sv_node *n)
{
    char *v = own_property(n, "overflow");
    bool vis = v && (!strcmp(v, "visible") || !strcmp(v, "auto"));
    free(v);
    return vis;
}

/*
 * A nested viewport (svg element or an instantiated symbol). Its content is
 * clipped to the viewport (overflow hidden, the default there): a
 * parallelogram on the canvas, so a convex clip cut into the geometry.
 */
static void render_viewport(imp *im, sv_node *n, const sv_style *s, ctx *c, double x, double y,
                            double w, double h)
{
    if (!(w > 0 && h > 0))
        return;
    sv_pt corner[4];
    clip_poly vp = {corner, 4};
    if (n->parent && !overflow_visible(n)) {
        double cx[4] = {x, x + w, x + w, x}, cy[4] = {y, y, y + h, y + h};
        for (int i = 0; i < 4; i++)
            corner[i] = sv_affine_apply(c->ctm, sv_pt_make(cx[i], cy[i]));
        if (c->nclips < MAX_CLIPS) {
            c->clips[c->nclips++] = &vp;
        } else {
            char d[160];
            desc(n, d, sizeof d);
            sv_doc_warn(im->doc, "%s: more than %d nested clips, viewport not clipped", d,
                        MAX_CLIPS);
        }
    }
    double vb[4];
    const char *vbs = sv_attr(n, "viewBox");
    if (vbs && sv_parse_numbers(vbs, vb, 4) == 4 && (vb[2] == 0 || vb[3] == 0)) {
        /* SVG 1.1 7.7: a zero width or height disables rendering of the element */
        char d[160];
        desc(n, d, sizeof d);
        sv_doc_warn(im->doc, "%s: viewBox \"%s\" has a zero width or height, nothing drawn", d, vbs);
        return;
    }
    if (vbs && !get_viewbox(n, vb)) {
        char d[160];
        desc(n, d, sizeof d);
        sv_doc_warn(im->doc, "%s: viewBox \"%s\" is not four numbers with a positive size, "
                    "ignored", d, vbs);
    }
    if (get_viewbox(n, vb)) {
        c->ctm = sv_affine_mul(
            c->ctm, sv_viewbox_map(vb, sv_attr(n, "preserveAspectRatio"), x, y, w, h));
        c->vp_w = vb[2];
        c->vp_h = vb[3];
    } else {
        sv_affine t = {1, 0, 0, 1, x, y};
        c->ctm = sv_affine_mul(c->ctm, t);
        c->vp_w = w;
        c->vp_h = h;
    }
    render_children(im, n, s, c);
}

/* Character data in a <text> element and its descendants (bounded by SV_MAX_DEPTH). */
static size_t text_bytes(const sv_node *n)
{
    size_t sum = 0;
    for (int i = 0; i < n->nkids; i++)
        sum += !strcmp(n->kids[i]->name, "#text") ? n->kids[i]->textlen : text_bytes(n->kids[i]);
    return sum;
}

/* Direction (radians) a segment leaves its start / reaches its end, from its control points. */
static double seg_dir(const sv_seg *g, bool at_end)
{
    int d = g->degree;
    for (int k = 1; k <= d; k++) {
        sv_pt a = at_end ? g->p[d - k] : g->p[0], b = at_end ? g->p[d] : g->p[k];
        if (a.x != b.x || a.y != b.y)
            return atan2(b.y - a.y, b.x - a.x);
    }
    return 0;
}

/* The bisector of an incoming and an outgoing direction. */
static double bisect(double in, double out)
{
    if (out - in > M_PI)
        out -= 2 * M_PI;
    else if (in - out > M_PI)
        out += 2 * M_PI;
    return 0.5 * (in + out);
}

/* One instance of marker `mk` at p, direction `dir` (radians). */
static void render_marker(imp *im, sv_node *mk, const sv_style *s, const ctx *pc, sv_pt p,
                          double dir, bool start)
{
    if (++im->use_copies > SV_MAX_USE_COPIES) { /* each instance counts, content or not */
        fail(im, "<marker> (line %d): markers instantiate more than %d elements "
             "(SV_MAX_USE_COPIES)", mk->line, SV_MAX_USE_COPIES);
        return;
    }
    sv_style ms; /* marker content inherits from the marker's ancestors, not from the shape */
    style_of(im, mk, &ms);
    const char *orient = sv_attr(mk, "orient"), *units = sv_attr(mk, "markerUnits");
    double angle = 0;
    if (orient && !strcmp(orient, "auto"))
        angle = dir;
    else if (orient && !strcmp(orient, "auto-start-reverse"))
        angle = start ? dir + M_PI : dir;
    else if (orient && sv_parse_numbers(orient, &angle, 1) == 1)
        angle *= M_PI / 180;
    double scale = units && !strcmp(units, "userSpaceOnUse") ? 1 : s->stroke_width;
    double mw = attr_len(mk, "markerWidth", &ms, pc->vp_w, 3);
    double mh = attr_len(mk, "markerHeight", &ms, pc->vp_h, 3);
    if (!(mw > 0 && mh > 0))
        return;
    double vb[4];
    sv_affine content = sv_affine_identity();
    if (get_viewbox(mk, vb))
        content = sv_viewbox_map(vb, sv_attr(mk, "preserveAspectRatio"), 0, 0, mw, mh);
    sv_pt ref = sv_affine_apply(content, sv_pt_make(attr_len(mk, "refX", &ms, pc->vp_w, 0),
                                                    attr_len(mk, "refY", &ms, pc->vp_h, 0)));
    double ca = cos(angle), sa = sin(angle);
    sv_affine place = {ca * scale, sa * scale, -sa * scale, ca * scale, p.x, p.y};
    sv_affine shift = {1, 0, 0, 1, -ref.x, -ref.y};
    ctx c = *pc;
    c.ctm = sv_affine_mul(sv_affine_mul(pc->ctm, place), shift); /* the viewport's space */
    c.via_use = true; /* instances count as <use> copies do */
    sv_pt corner[4];
    clip_poly vp = {corner, 4};
    if (!overflow_visible(mk) && c.nclips < MAX_CLIPS) {
        double cx[4] = {0, mw, mw, 0}, cy[4] = {0, 0, mh, mh};
        for (int i = 0; i < 4; i++)
            corner[i] = sv_affine_apply(c.ctm, sv_pt_make(cx[i], cy[i]));
        c.clips[c.nclips++] = &vp;
    }
    c.ctm = sv_affine_mul(c.ctm, content);
    if (get_viewbox(mk, vb)) {
        c.vp_w = vb[2];
        c.vp_h = vb[3];
    }
    im->stack[im->depth++] = mk;
    render_children(im, mk, &ms, &c);
    im->depth--;
}

static void render_markers(imp *im, const sv_node *n, const sv_style *s, const ctx *c,
                           const sv_path *up)
{
    sv_node *mk[3];
    for (int i = 0; i < 3; i++) {
        mk[i] = s->marker[i][0] ? find_id(im, s->marker[i]) : NULL;
        if (mk[i] && strcmp(mk[i]->name, "marker") != 0)
            mk[i] = NULL;
        for (int k = 0; mk[i] && k < im->depth; k++)
            if (im->stack[k] == mk[i])
                mk[i] = NULL; /* a marker drawn inside itself */
        if (s->marker[i][0] && !mk[i]) {
            char d[160];
            desc(n, d, sizeof d);
            sv_doc_warn(im->doc, "%s: marker #%s not found or recursive, not drawn", d,
                        s->marker[i]);
        }
    }
    /* the vertices: every segment's start, and the end of every subpath */
    int nsub = 0;
    for (int i = 0; i < up->n; i++)
        nsub += up->sub[i].n > 0;
    int seen = 0;
    for (int i = 0; i < up->n && !im->failed; i++) {
        const sv_subpath *sp = &up->sub[i];
        if (sp->n == 0)
            continue;
        seen++;
        sv_pt first = sp->seg[0].p[0], last = sp->seg[sp->n - 1].p[sp->seg[sp->n - 1].degree];
        sv_seg closing = {1, {last, first}, 1};
        bool has_closing = sp->closed && (first.x != last.x || first.y != last.y);
        int nseg = sp->n + has_closing;
        const sv_seg *lastseg = has_closing ? &closing : &sp->seg[sp->n - 1];
        for (int k = 0; k <= nseg && !im->failed; k++) {
            const sv_seg *in = k > 0 ? (k - 1 < sp->n ? &sp->seg[k - 1] : &closing) : NULL;
            const sv_seg *out = k < nseg ? (k < sp->n ? &sp->seg[k] : &closing) : NULL;
            sv_pt p = out ? out->p[0] : lastseg->p[lastseg->degree];
            double dir;
            if (in && out)
                dir = bisect(seg_dir(in, true), seg_dir(out, false));
            else if (sp->closed) /* the start and end meet: both directions count */
                dir = bisect(seg_dir(lastseg, true), seg_dir(&sp->seg[0], false));
            else
                dir = out ? seg_dir(out, false) : seg_dir(in, true);
            bool start = seen == 1 && k == 0, end = seen == nsub && k == nseg;
            int which = start ? 0 : end ? 2 : 1;
            if (mk[which])
                render_marker(im, mk[which], s, c, p, dir, start);
        }
    }
}

static void element_box(imp *im, sv_node *n, const sv_style *ps, sv_affine m, const ctx *c,
                        double box[4], int depth);

/* The union of the children's boxes (see element_box). */
static void children_box(imp *im, sv_node *n, const sv_style *s, sv_affine m, const ctx *c,
                         double box[4], int depth)
{
    for (int i = 0; i < n->nkids && !im->failed; i++)
        element_box(im, n->kids[i], s, m, c, box, depth + 1);
}

/*
 * The bounding box (SVG's: fill geometry, strokes and opacity aside) of an
 * element mapped by m, grown into box[4]: what objectBoundingBox units of a
 * clip on a group need. Each element visited counts against
 * SV_MAX_USE_COPIES, as instances do: clipped groups inside clipped groups
 * would otherwise be walked again and again.
 */
static void element_box(imp *im, sv_node *n, const sv_style *ps, sv_affine m, const ctx *c,
                        double box[4], int depth)
{
    const char *name = n->name;
    if (strncmp(name, "ns:", 3) == 0 || name[0] == '#' || is_nonrendering(name))
        return;
    if (++im->use_copies > SV_MAX_USE_COPIES || depth >= SV_MAX_DEPTH) {
        fail(im, "<%s> (line %d): bounding boxes visit more than %d elements "
             "(SV_MAX_USE_COPIES) or nest deeper than %d", name, n->line, SV_MAX_USE_COPIES,
             SV_MAX_DEPTH);
        return;
    }
    sv_style s;
    sv_style_compute(&s, ps, n, &im->css, 0, NULL);
    if (s.display_none)
        return;
    sv_affine t;
    const char *tr = sv_attr(n, "transform");
    if (s.has_transform)
        m = sv_affine_mul(m, s.transform);
    else if (tr && sv_parse_transform(tr, &t))
        m = sv_affine_mul(m, t);
    sv_path p;
    sv_path_init(&p);
    if (!strcmp(name, "text")) {
        if (im->text_bytes + (long)text_bytes(n) <= SV_MAX_TEXT_BYTES) {
            sv_text_run *runs;
            int nr = sv_svg_text_layout(n, &s, &im->css, c->vp_w, c->vp_h, fonts_of(im), &runs,
                                        im->doc);
            for (int i = 0; i < nr; i++)
                sv_path_append(&p, &runs[i].path);
            sv_text_runs_free(runs, nr);
        }
    } else if (!strcmp(name, "g") || !strcmp(name, "a") || !strcmp(name, "switch")) {
        children_box(im, n, &s, m, c, box, depth);
    } else if (!strcmp(name, "use")) {
        sv_node *target = find_href(im, n);
        for (int i = 0; target && i < im->depth; i++)
            if (im->stack[i] == target)
                target = NULL;
        if (target && strcmp(target->name, "symbol") != 0 && strcmp(target->name, "svg") != 0) {
            sv_affine tu = {1, 0, 0, 1, attr_len(n, "x", &s, c->vp_w, 0),
                            attr_len(n, "y", &s, c->vp_h, 0)};
            element_box(im, target, &s, sv_affine_mul(m, tu), c, box, depth + 1);
        }
    } else {
        shape_path(im, n, &s, c, &p);
    }
    if (p.n > 0) {
        double b[4];
        sv_path_transform(&p, m);
        tight_bbox(&p, b);
        box[0] = fmin(box[0], b[0]);
        box[1] = fmin(box[1], b[1]);
        box[2] = fmax(box[2], b[2]);
        box[3] = fmax(box[3], b[3]);
    }
    sv_path_free(&p);
}

static bool switch_accepts(const sv_node *k)
{
    if (sv_attr(k, "requiredExtensions"))
        return false;
    const char *lang = sv_attr(k, "systemLanguage");
    return !lang || strstr(lang, "en") != NULL;
}

static void render(imp *im, sv_node *n, const sv_style *ps, const ctx *pc)
{
    if (im->failed)
        return;
    char d[160];
    if (pc->via_use && ++im->use_copies > SV_MAX_USE_COPIES) {
        desc(n, d, sizeof d);
        fail(im, "%s: <use> instantiates more than %d elements (SV_MAX_USE_COPIES)", d,
             SV_MAX_USE_COPIES);
        return;
    }
    const char *name = n->name;
    if (strncmp(name, "ns:", 3) == 0 || name[0] == '#' || is_nonrendering(name))
        return; /* editor metadata, character data and definitions draw nothing by themselves */
    if (im->depth >= SV_MAX_DEPTH - 1) { /* a <use> of a symbol takes two levels */
        desc(n, d, sizeof d);
        fail(im, "%s: elements nested deeper than %d through <use> (SV_MAX_DEPTH)", d,
             SV_MAX_DEPTH);
        return;
    }
    sv_style s;
    sv_style_compute(&s, ps, n, &im->css, sqrt((pc->vp_w * pc->vp_w + pc->vp_h * pc->vp_h) / 2),
                     im->doc);
    if (s.display_none)
        return;
    ctx c = *pc;
    const char *tr = sv_attr(n, "transform");
    sv_affine t;
    if (s.has_transform) { /* the CSS property replaces the attribute */
        c.ctm = sv_affine_mul(c.ctm, s.transform);
    } else if (tr) {
        if (sv_parse_transform(tr, &t)) {
            c.ctm = sv_affine_mul(c.ctm, t);
        } else { /* an invalid attribute is as if not given (SVG 2), as resvg does */
            desc(n, d, sizeof d);
            sv_doc_warn(im->doc, "%s: bad transform \"%s\" ignored", d, tr);
        }
    }
    bool shape = !strcmp(name, "path") || !strcmp(name, "rect") || !strcmp(name, "circle") ||
                 !strcmp(name, "ellipse") || !strcmp(name, "line") || !strcmp(name, "polyline") ||
                 !strcmp(name, "polygon");
    if (s.filter[0]) {
        desc(n, d, sizeof d);
        sv_doc_warn(im->doc, "%s: filter #%s not supported, drawn unfiltered", d, s.filter);
    }
    /* group opacity: one layer (cel) for the whole subtree */
    if (!shape && s.opacity < 1) {
        if (c.layer == 0)
            c.layer = ++im->next_layer;
        c.alpha *= s.opacity;
        s.opacity = 1;
    }
    sv_path up;
    sv_path_init(&up);
    bool have_path = shape && shape_path(im, n, &s, &c, &up);
    if (have_path && c.via_use) { /* a copy costs its geometry too */
        for (int i = 0; i < up.n; i++)
            im->use_copies += up.sub[i].n;
        if (im->use_copies > SV_MAX_USE_COPIES) {
            desc(n, d, sizeof d);
            fail(im, "%s: <use> and markers instantiate more than %d elements and path "
                 "segments (SV_MAX_USE_COPIES)", d, SV_MAX_USE_COPIES);
            sv_path_free(&up);
            return;
        }
    }
    if (!strcmp(name, "text") && s.clip_path[0] &&
        im->text_bytes + (long)text_bytes(n) <= SV_MAX_TEXT_BYTES) {
        /* objectBoundingBox units of its clip need its box: the glyph cells' (sv_text.h) */
        sv_text_run *runs;
        int nr = sv_svg_text_layout(n, &s, &im->css, c.vp_w, c.vp_h, fonts_of(im), &runs,
                                    im->doc); /* its warnings come again when it is set: kept once */
        if (nr > 0 && runs[0].cell_box[2] > runs[0].cell_box[0]) {
            const double *b = runs[0].cell_box;
            sv_path_move(&up, b[0], b[1]);
            sv_path_line(&up, b[2], b[1]);
            sv_path_line(&up, b[2], b[3]);
            sv_path_line(&up, b[0], b[3]);
            sv_path_close(&up);
        }
        sv_text_runs_free(runs, nr);
        have_path = up.n > 0;
    }
    sv_node *clip_el = s.clip_path[0] ? find_id(im, s.clip_path) : NULL;
    const char *cunits = clip_el ? sv_attr(clip_el, "clipPathUnits") : NULL;
    if (!have_path && cunits && !strcmp(cunits, "objectBoundingBox") &&
        (!strcmp(name, "g") || !strcmp(name, "a") || !strcmp(name, "use"))) {
        /* a container's box: its content's, in its own user space, as a rectangle */
        double box[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
        sv_node *target = !strcmp(name, "use") ? find_href(im, n) : NULL;
        if (target) { /* the instance's box, x and y included */
            sv_affine tu = {1, 0, 0, 1, attr_len(n, "x", &s, c.vp_w, 0),
                            attr_len(n, "y", &s, c.vp_h, 0)};
            element_box(im, target, &s, tu, &c, box, im->depth);
        } else {
            children_box(im, n, &s, sv_affine_identity(), &c, box, im->depth);
        }
        if (box[0] <= box[2] && box[1] <= box[3]) {
            sv_path_move(&up, box[0], box[1]);
            sv_path_line(&up, box[2], box[1]);
            sv_path_line(&up, box[2], box[3]);
            sv_path_line(&up, box[0], box[3]);
            sv_path_close(&up);
            have_path = true;
        }
    }
    clip_poly slot = {NULL, 0};
    bool used_slot = false;
    if (s.clip_path[0])
        apply_clip(im, n, s.clip_path, &c, have_path ? &up : NULL, &slot, &used_slot);
    int mask_start = im->nitems;
    im->stack[im->depth++] = n;
    if (shape) {
        if (have_path)
            paint_shape(im, n, &s, &c, &up, true);
    } else if (!strcmp(name, "g") || !strcmp(name, "a")) {
        render_children(im, n, &s, &c);
    } else if (!strcmp(name, "switch")) {
        for (int i = 0; i < n->nkids; i++)
            if (strncmp(n->kids[i]->name, "ns:", 3) != 0 && n->kids[i]->name[0] != '#' &&
                switch_accepts(n->kids[i])) {
                render(im, n->kids[i], &s, &c);
                break;
            }
    } else if (!strcmp(name, "svg")) {
        render_viewport(im, n, &s, &c, attr_len(n, "x", &s, c.vp_w, 0),
                        attr_len(n, "y", &s, c.vp_h, 0), attr_len(n, "width", &s, c.vp_w, c.vp_w),
                        attr_len(n, "height", &s, c.vp_h, c.vp_h));
    } else if (!strcmp(name, "use")) {
        sv_node *target = find_href(im, n);
        bool cycle = false;
        for (int i = 0; i < im->depth; i++)
            cycle |= im->stack[i] == target;
        desc(n, d, sizeof d);
        if (!target) {
            sv_doc_warn(im->doc, "%s: href target not found, nothing drawn", d);
        } else if (cycle) {
            sv_doc_warn(im->doc, "%s: reference cycle, not drawn", d);
        } else {
            sv_affine tu = {1, 0, 0, 1, attr_len(n, "x", &s, c.vp_w, 0),
                            attr_len(n, "y", &s, c.vp_h, 0)};
            c.ctm = sv_affine_mul(c.ctm, tu);
            c.via_use = true;
            if (!strcmp(target->name, "symbol") || !strcmp(target->name, "svg")) {
                sv_style ts;
                sv_style_compute(&ts, &s, target, &im->css, 0, im->doc);
                if (ts.opacity < 1) { /* the instance is a group: its opacity as a layer */
                    if (c.layer == 0)
                        c.layer = ++im->next_layer;
                    c.alpha *= ts.opacity;
                    ts.opacity = 1;
                }
                im->stack[im->depth++] = target;
                render_viewport(im, target, &ts, &c, attr_len(target, "x", &s, c.vp_w, 0),
                                attr_len(target, "y", &s, c.vp_h, 0),
                                attr_len(n, "width", &s, c.vp_w,
                                         attr_len(target, "width", &s, c.vp_w, c.vp_w)),
                                attr_len(n, "height", &s, c.vp_h,
                                         attr_len(target, "height", &s, c.vp_h, c.vp_h)));
                im->depth--;
            } else {
                render(im, target, &s, &c);
            }
        }
    } else if (!strcmp(name, "text")) {
        im->text_bytes += (long)text_bytes(n);
        if (im->text_bytes > SV_MAX_TEXT_BYTES) {
            desc(n, d, sizeof d);
            fail(im, "%s: more than %d bytes of text in the drawing (SV_MAX_TEXT_BYTES)", d,
                 SV_MAX_TEXT_BYTES);
            goto done;
        }
        sv_text_run *runs;
        int nr = sv_svg_text_layout(n, &s, &im->css, c.vp_w, c.vp_h, fonts_of(im), &runs,
                                    im->doc);
        for (int i = 0; i < nr; i++)
            if (runs[i].path.n > 0) {
                ctx rc = c;
                rc.obj_box = runs[i].cell_box;
                paint_shape(im, runs[i].node, runs[i].style, &rc, &runs[i].path, false);
            }
        sv_text_runs_free(runs, nr);
    } else {
        desc(n, d, sizeof d);
        sv_doc_warn(im->doc, "%s: element not supported, not drawn", d);
    }
done:
    im->depth--;
    if (s.mask[0] && !is_unmasked(im, n))
        apply_mask(im, n, s.mask, &c, mask_start, have_path ? &up : NULL);
    if (used_slot)
        free(slot.v);
    sv_path_free(&up);
}

/* ------------------------------------------------------ cel packing */

static bool boxes_meet(const double a[4], const double b[4])
{
    return a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
}

/*
 * The cel space a region's radial gradient needs to be a circle there (the
 * core's radial function is one): false when it needs none (no radial
 * gradient, or one too thin for any cel space: bands).
 */
static bool wanted_space(const imp *im, const item *it, sv_affine *space)
{
    int gi = it->reg.paint.gradient;
    if (gi < 0 || im->doc->gradients[gi].type != SV_GRAD_RADIAL)
        return false;
    const sv_gradient *g = &im->doc->gradients[gi];
    if (sv_gradient_circular_in(g, sv_affine_identity())) {
        *space = sv_affine_identity();
        return true;
    }
    return sv_gradient_circle_space(g, space);
}

/*
 * Packs the items (front-most first) into cels; returns the cel count. With
 * `doc` NULL it only counts. A cel's space is fixed by its first region that
 * wants one; a later region whose radial gradient is no circle there starts
 * a new cel (SVG's own "over" per shape, so nothing changes) while `splits`
 * lasts, or else joins and is drawn by its bands. Group layers never split.
 */
static int pack(imp *im, item **order, sv_doc *doc, int splits)
{
    int cel_layer = -1, first = 0, ncels = 0; /* items of the current cel: [first, i) */
    bool fixed = false;
    sv_affine space = sv_affine_identity();
    for (int i = 0; i < im->nitems; i++) {
        item *it = order[i];
        bool join = ncels > 0 && it->layer == cel_layer;
        if (join && it->layer == 0 && im->opts.one_cel_per_shape)
            join = false;
        if (join && it->layer == 0)
            for (int k = first; k < i && join; k++)
                if (order[k]->translucent && boxes_meet(order[k]->reg.bbox, it->reg.bbox))
                    join = false;
        sv_affine want;
        bool wants = wanted_space(im, it, &want);
        int gi = it->reg.paint.gradient;
        if (join && it->layer == 0 && wants && fixed && splits > 0 &&
            !sv_gradient_circular_in(&im->doc->gradients[gi], space)) {
            join = false;
            splits--;
        }
        if (!join) {
            ncels++;
            cel_layer = it->layer;
            first = i;
            fixed = false;
            space = sv_affine_identity();
            if (doc) {
                doc->cels = sv_xrealloc(doc->cels, (size_t)ncels * sizeof *doc->cels);
                sv_cel *cel = &doc->cels[ncels - 1];
                memset(cel, 0, sizeof *cel);
                char nm[32];
                snprintf(nm, sizeof nm, "svg%d", ncels - 1);
                cel->name = sv_xstrdup(nm);
                doc->ncels = ncels;
            }
        }
        if (wants && !fixed) {
            fixed = true;
            space = want;
        }
        if (doc) {
            sv_cel *cel = &doc->cels[ncels - 1];
            cel->regions = sv_xrealloc(cel->regions, (size_t)(cel->nregions + 1) * sizeof(sv_region));
            cel->regions[cel->nregions++] = it->reg;
            sv_affine id = sv_affine_identity();
            cel->has_transform = memcmp(&space, &id, sizeof id) != 0;
            cel->transform = space;
        }
    }
    return ncels;
}

static void pack_cels(imp *im)
{
    item **order = sv_xrealloc(NULL, (size_t)(im->nitems + 1) * sizeof *order);
    for (int i = 0; i < im->nitems; i++)
        order[i] = &im->items[im->nitems - 1 - i];
    /* each split adds at most one cel to the packing without splits */
    int base = pack(im, order, NULL, 0);
    pack(im, order, im->doc, base < CS_CFG_MAX_CELS ? CS_CFG_MAX_CELS - base : 0);
    free(order);
}

/* ------------------------------------------------------------ entry */

int sv_import_buffer(const char *data, size_t len, const sv_import_opts *opts, sv_doc *doc,
                     char *err, size_t errlen)
{
    sv_doc_init(doc);
    sv_node *root = sv_xml_parse(data, len, err, errlen);
    if (!root)
        return -1;
    if (strcmp(root->name, "svg") != 0) {
        snprintf(err, errlen, "root element is <%s>, not <svg> in the SVG namespace", root->name);
        sv_xml_free(root);
        return -1;
    }
    imp im;
    memset(&im, 0, sizeof im);
    im.doc = doc;
    im.err = err;
    im.errlen = errlen;
    im.band_work = SV_MAX_BAND_WORK;
    if (opts)
        im.opts = *opts;
    collect(&im, root);

    sv_style s0;
    sv_style_initial(&s0);
    memcpy(s0.color, im.opts.current_color, sizeof s0.color);
    double vb[4];
    bool has_vb = get_viewbox(root, vb);
    /* Intrinsic size: width/height, percentages falling back to the viewBox. */
    double w = has_vb ? vb[2] : 100, h = has_vb ? vb[3] : 100;
    const char *ws = sv_attr(root, "width"), *hs = sv_attr(root, "height");
    double x;
    if (ws && !strchr(ws, '%') && sv_parse_length(ws, 12, 0, &x) && x > 0)
        w = x;
    if (hs && !strchr(hs, '%') && sv_parse_length(hs, 12, 0, &x) && x > 0)
        h = x;
    if (has_vb && ws && !strchr(ws, '%') && !(hs && !strchr(hs, '%')))
        h = w * vb[3] / vb[2]; /* one dimension given: keep the viewBox's aspect */
    if (has_vb && hs && !strchr(hs, '%') && !(ws && !strchr(ws, '%')))
        w = h * vb[2] / vb[3];
    /* neither a viewBox nor a usable width and height: the drawing's extent decides (below) */
    bool sized = has_vb || (ws && !strchr(ws, '%') && sv_parse_length(ws, 12, 0, &x) && x > 0 &&
                            hs && !strchr(hs, '%') && sv_parse_length(hs, 12, 0, &x) && x > 0);
    doc->width = w;
    doc->height = h;
    double nominal = im.opts.nominal_px > 0 ? im.opts.nominal_px : 1024;
    im.tol = im.opts.tolerance > 0 ? im.opts.tolerance : 0.01 * fmax(w, h) / nominal;

    ctx c;
    memset(&c, 0, sizeof c);
    c.ctm = sv_affine_identity();
    c.alpha = 1;
    c.ir_clip = -1;
    c.vp_w = w;
    c.vp_h = h;
    /* the root svg is a viewport at the origin whatever its x and y */
    sv_style rs;
    sv_style_compute(&rs, &s0, root, &im.css, sqrt((w * w + h * h) / 2), doc);
    if (rs.opacity < 1) {
        c.layer = ++im.next_layer;
        c.alpha = rs.opacity;
    }
    if (rs.filter[0])
        sv_doc_warn(doc, "<svg>: filter #%s not supported, drawn unfiltered", rs.filter);
    if (rs.mask[0])
        sv_doc_warn(doc, "<svg>: mask #%s not supported, drawn unmasked", rs.mask);
    im.stack[im.depth++] = root;
    /* SVG 1.1 7.1: zero disables rendering, a negative size is an error */
    bool empty = (ws && sv_parse_length(ws, 12, 0, &x) && x <= 0) ||
                 (hs && sv_parse_length(hs, 12, 0, &x) && x <= 0);
    if (empty)
        sv_doc_warn(doc, "<svg>: width \"%s\" height \"%s\" is not a positive size, nothing "
                    "drawn", ws ? ws : "", hs ? hs : "");
    clip_poly slot = {NULL, 0};
    bool used_slot = false;
    if (rs.clip_path[0] && !empty)
        apply_clip(&im, root, rs.clip_path, &c, NULL, &slot, &used_slot);
    char *bg = own_property(root, "background-color");
    double bg_rgb[3], bg_a = 1;
    if (bg && !empty && sv_parse_color(bg, bg_rgb, &bg_a) == SV_COLOR_RGB && bg_a > 0) {
        /* the root's background-color (as resvg draws it): the canvas, behind everything */
        sv_path bp;
        sv_path_init(&bp);
        sv_path_move(&bp, 0, 0);
        sv_path_line(&bp, w, 0);
        sv_path_line(&bp, w, h);
        sv_path_line(&bp, 0, h);
        sv_path_close(&bp);
        sv_paint paint = {{bg_rgb[0], bg_rgb[1], bg_rgb[2]}, {1, 1, 1}, bg_a, -1, 1};
        ctx bc = c;
        bc.nclips = 0;
        bc.ir_clip = -1;
        add_region(&im, &bp, CS_FILL_NONZERO, &paint, bg_a, &bc, root, "background-color");
        sv_path_free(&bp);
    }
    free(bg);
    if (!rs.display_none && !empty)
        render_viewport(&im, root, &rs, &c, 0, 0, w, h);
    if (used_slot)
        free(slot.v);
    if (!sized && im.nitems > 0) {
        double ew = 0, eh = 0;
        for (int i = 0; i < im.nitems; i++) {
            ew = fmax(ew, im.items[i].reg.bbox[2]);
            eh = fmax(eh, im.items[i].reg.bbox[3]);
        }
        if (ew > 0 && eh > 0) {
            doc->width = ew;
            doc->height = eh;
            sv_doc_warn(doc, "<svg>: no viewBox and no usable width and height: the canvas is "
                        "the drawing's extent, %g x %g", ew, eh);
        }
    }
    pack_cels(&im);
    doc->blend_srgb = true; /* SVG blends in sRGB: the scene JSON asks for it */
    if (!im.failed)
        sv_doc_plan(doc);
    else
        sv_doc_free(doc); /* the error says why; a part of the drawing is no result */

    free(im.items);
    free(im.ids);
    free(im.unmasked);
    sv_fonts_free(im.fonts);
    sv_css_free(&im.css);
    sv_xml_free(root);
    return im.failed ? -1 : 0;
}

int sv_import_file(const char *path, const sv_import_opts *opts, sv_doc *doc, char *err,
                   size_t errlen)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        sv_doc_init(doc);
        return -1;
    }
    char *buf = NULL;
    size_t len = 0, cap = 0;
    for (;;) {
        if (len == cap) {
            cap = cap ? 2 * cap : 65536;
            buf = sv_xrealloc(buf, cap);
        }
        size_t got = fread(buf + len, 1, cap - len, f);
        if (got == 0)
            break;
        len += got;
    }
    fclose(f);
    char e2[400];
    int rc = sv_import_buffer(buf, len, opts, doc, e2, sizeof e2);
    if (rc < 0)
        snprintf(err, errlen, "%s: %s", path, e2);
    free(buf);
    return rc;
}
