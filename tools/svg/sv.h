/*
 * sv.h - the SVG / text importer: geometry, intermediate representation,
 * back ends. A host library (libc, expat, FreeType, cJSON); never linked
 * into the freestanding core.
 *
 * The flow is
 *
 *   SVG file --expat--> element tree --styles, transforms--> sv_path per shape
 *     --fill: sv_path_to_contours / stroke: sv_stroke_path--> sv_region
 *     --document order reversed, packed into cels--> sv_doc (the IR)
 *     --sv_doc_to_json--> scene JSON      --sv_doc_to_scene--> cs_scene
 *
 * Everything stays exact up to the stroke outliner: lines, quadratic and
 * cubic Béziers and elliptical arcs (split into <= 90 degree rational
 * quadratics with middle weight cos(theta/2)) go into closed contours of one
 * degree each by exact degree elevation, and affine transforms act on control
 * points, which is exact for rational curves. Only offset curves (strokes)
 * are approximated, within a stated tolerance.
 *
 * The IR keeps gradients resolved to canvas units (drawn as the core's paint
 * functions, with solid bands of exact geometry and an area-average colour as
 * fallbacks) and clip paths that are not one convex polygon (drawn as a CSG
 * intersection per region). After packing, sv_doc_plan (sv_plan.c) decides
 * per region how the back ends draw it, within the core's capacities, and
 * warns where that is not exact.
 *
 * Colours in the IR are sRGB-encoded 0..1, as SVG and the scene JSON write
 * them; the cs_scene back end linearises them.
 */
#ifndef SV_H
#define SV_H

#include <stdbool.h>
#include <stddef.h>

#include "celscan.h"

/* ------------------------------------------------------------ geometry */

typedef struct sv_pt {
    double x, y;
} sv_pt;

/* x' = a x + c y + e, y' = b x + d y + f (SVG matrix order). */
typedef struct sv_affine {
    double a, b, c, d, e, f;
} sv_affine;

/*
 * One Bézier segment: degree 1 (line), 2 (quadratic; rational with middle
 * weight w, so w = cos(theta/2) makes a conic arc) or 3 (polynomial cubic).
 * End weights are always 1 (standard form), so segments chain with the
 * shared on-curve point and no reweighting.
 */
typedef struct sv_seg {
    int degree;
    sv_pt p[4];
    double w; /* middle weight of a degree-2 segment; 1 otherwise */
} sv_seg;

typedef struct sv_subpath {
    sv_seg *seg;
    int n, cap;
    bool closed; /* closed by 'Z' (matters to strokes: joins instead of caps) */
} sv_subpath;

typedef struct sv_path {
    sv_subpath *sub;
    int n, cap;
    sv_pt cur, start; /* pen position and start of the current subpath */
    bool open_sub;    /* whether sub[n-1] may still be extended */
} sv_path;

sv_affine sv_affine_identity(void);
/* m1 after m2: (m1 * m2)(p) = m1(m2(p)). */
sv_affine sv_affine_mul(sv_affine m1, sv_affine m2);
sv_pt sv_affine_apply(sv_affine m, sv_pt p);
bool sv_affine_invert(sv_affine m, sv_affine *inv);
/* Largest singular value: how much the map can stretch a length. */
double sv_affine_max_scale(sv_affine m);

void sv_path_init(sv_path *p);
void sv_path_free(sv_path *p);
void sv_path_move(sv_path *p, double x, double y);
void sv_path_line(sv_path *p, double x, double y);
void sv_path_quad(sv_path *p, double x1, double y1, double x, double y);
void sv_path_cubic(sv_path *p, double x1, double y1, double x2, double y2, double x, double y);
/* A rational quadratic (conic) from the pen through control (x1,y1) weight w. */
void sv_path_conic(sv_path *p, double x1, double y1, double w, double x, double y);
/* SVG elliptical arc from the pen (F.6.5 of SVG 1.1), as <= 90 degree conics. */
void sv_path_arc(sv_path *p, double rx, double ry, double x_axis_rotation_deg, bool large_arc,
                 bool sweep, double x, double y);
void sv_path_close(sv_path *p);
/* Appends a segment to the current subpath (the pen moves to its end). */
void sv_path_add_seg(sv_path *p, const sv_seg *s);
void sv_path_append(sv_path *dst, const sv_path *src);
void sv_path_transform(sv_path *p, sv_affine m);
/* Ellipse as 4 exact 90-degree conics, counter-clockwise in y-up terms. */
void sv_path_ellipse(sv_path *p, double cx, double cy, double rx, double ry);

/* Evaluation (de Casteljau in homogeneous coordinates) and derivative. */
sv_pt sv_seg_eval(const sv_seg *s, double t);
sv_pt sv_seg_deriv(const sv_seg *s, double t);
/* Splits at t into a (0..t) and b (t..1), both renormalised to end weights 1. */
void sv_seg_split(const sv_seg *s, double t, sv_seg *a, sv_seg *b);
/* The piece of s for t in [t0, t1], exactly (rational segments included). */
sv_seg sv_seg_sub(const sv_seg *s, double t0, double t1);
void sv_seg_reverse(sv_seg *s);
/* Bounding box of the control points (contains the curve: weights > 0). */
void sv_path_bbox(const sv_path *p, double box[4]);

/*
 * Signed area of a subpath taken as closed (y down: positive is clockwise on
 * screen), by Gauss-Legendre quadrature of Green's theorem per segment.
 */
double sv_subpath_area(const sv_subpath *s);
/* Winding number of point q about the subpath taken as closed. */
int sv_subpath_winding(const sv_subpath *s, sv_pt q);

/*
 * Exact clipping (sv_clip.c): keeps the part of the filled path where
 * a x + b y + c >= 0, every subpath taken as closed, for any fill rule.
 */
void sv_path_clip_halfplane(sv_path *p, double a, double b, double c);
/* If `clip` is one convex polygon, its vertices (malloc'd) and true. */
bool sv_path_convex_polygon(const sv_path *clip, sv_pt **poly, int *n);
/* Clips the filled path to a convex polygon (either orientation). */
void sv_path_clip_polygon(sv_path *p, const sv_pt *v, int n);
/* Reverses every subpath (closing it first), negating every winding number. */
void sv_path_reverse(sv_path *p);

/* ------------------------------------------------------------------ IR */

/* A closed periodic NURBS, as in the scene JSON contract. */
typedef struct sv_contour {
    int degree;        /* 1..3 */
    int count;         /* control points = knot intervals */
    double *pts;       /* count * 3: x, y, w */
    double *intervals; /* count */
} sv_contour;

typedef enum sv_grad_type { SV_GRAD_LINEAR = 1, SV_GRAD_RADIAL = 2 } sv_grad_type;
typedef enum sv_spread { SV_SPREAD_PAD = 0, SV_SPREAD_REFLECT = 1, SV_SPREAD_REPEAT = 2 } sv_spread;

typedef struct sv_stop {
    double offset;
    double rgb[3]; /* sRGB 0..1 */
    double opacity;
} sv_stop;

/*
 * A gradient resolved for one region: geometry in its own gradient space,
 * `transform` maps gradient space to canvas units (objectBoundingBox units
 * and gradientTransform and the element's CTM are all folded in).
 */
typedef struct sv_gradient {
    sv_grad_type type;
    double x1, y1, x2, y2;        /* linear */
    double cx, cy, r, fx, fy, fr; /* radial */
    sv_affine transform;
    sv_spread spread;
    int nstops;
    sv_stop *stops;
} sv_gradient;

/* A beta-model paint, sRGB-encoded 0..1 (see the colour note above). */
typedef struct sv_paint {
    double pigment[3];
    double medium[3];
    double beta;
    int gradient; /* index into sv_doc.gradients, or -1; pigment/beta are its average */
    double gradient_opacity; /* multiplies the gradient's stop opacities (fill-opacity etc.) */
} sv_paint;

/*
 * A clip path: the union of its parts. Children with clip-rule nonzero share
 * one part (each child oriented so its winding is not negative, so the sum
 * of windings is non-zero exactly on their union); each evenodd child is a
 * part of its own.
 */
typedef struct sv_clip {
    int nparts;
    struct sv_clip_part {
        int fill_rule;
        int ncontours;
        sv_contour *contours;
        /* -1, or an IR clip (with its chain) this part is first intersected with: the
         * clip-path of a clipPath's child; always an earlier clip than this one */
        int clip;
    } *parts;
    int parent; /* the enclosing context's clip (nested clip-path), or -1 */
} sv_clip;

/* How the back ends draw a region (sv_doc_plan decides; zero is solid). */
typedef enum sv_draw {
    SV_DRAW_SOLID = 0, /* the paint's constants (a gradient's average colour) */
    SV_DRAW_FUNC = 1,  /* the gradient as the core's paint functions */
    SV_DRAW_BANDS = 2  /* the gradient's solid bands */
} sv_draw;

typedef struct sv_region {
    int fill_rule; /* CS_FILL_NONZERO / CS_FILL_EVENODD */
    sv_paint paint;
    int clip;      /* index into sv_doc.clips (to intersect with), or -1 */
    int ncontours;
    sv_contour *contours;
    double bbox[4]; /* x0 y0 x1 y1 of the control points, canvas units */
    char *source;   /* "path#id line 12 (stroke)": for messages */
    /*
     * For a gradient paint: solid bands with exact geometry that approximate
     * it (sv_bands.c), in the order they go into the cel. Back ends without
     * gradient paints draw these instead of the region; empty when the
     * average colour is all there is to draw.
     */
    int nbands;
    struct sv_region *bands;
    sv_draw draw;
    /* Clips of the chain from `clip` that the back ends intersect by CSG
     * (innermost first); 0 draws the region unclipped. */
    int csg_clips;
} sv_region;

typedef struct sv_cel {
    char *name;
    int nregions;
    sv_region *regions; /* front-most first */
    /*
     * Cel space to canvas. Contours in the IR stay in canvas units; a back
     * end writes them mapped by the inverse. Set when a radial gradient is
     * elliptical on the canvas: in cel space it is a circle, which the core's
     * radial function can draw.
     */
    bool has_transform;
    sv_affine transform;
} sv_cel;

typedef struct sv_doc {
    double width, height; /* canvas units */
    int ncels;
    sv_cel *cels; /* front-most first */
    int ngradients;
    sv_gradient *gradients;
    int nclips;
    sv_clip *clips;
    int nwarnings;
    char **warnings;
    /* Ask for sRGB blending (SVG's) in the scene JSON: "canvas": {"blend": "srgb"}. */
    bool blend_srgb;
} sv_doc;

void sv_doc_init(sv_doc *doc);
void sv_doc_free(sv_doc *doc);
/* Frees what a region owns (contours, bands, source), not the struct itself. */
void sv_region_free(sv_region *r);
void sv_doc_warn(sv_doc *doc, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
size_t sv_doc_point_count(const sv_doc *doc);
size_t sv_doc_region_count(const sv_doc *doc);

/*
 * Closed contours of a path, for filling: every subpath is closed (SVG fills
 * open subpaths as if closed), zero-length segments and subpaths without
 * area are dropped, and each contour gets the lowest degree that holds all
 * its segments exactly (1 for polygons). Appends to *out (realloc'd).
 */
void sv_path_to_contours(const sv_path *p, sv_contour **out, int *n);
void sv_contour_free(sv_contour *c);

/* ------------------------------------------------------------- strokes */

typedef enum sv_cap { SV_CAP_BUTT = 0, SV_CAP_ROUND = 1, SV_CAP_SQUARE = 2 } sv_cap;
typedef enum sv_join { SV_JOIN_MITER = 0, SV_JOIN_ROUND = 1, SV_JOIN_BEVEL = 2 } sv_join;

typedef struct sv_stroke_style {
    double width;       /* full width, user units */
    sv_cap cap;
    sv_join join;
    double miter_limit; /* ratio of miter length to width, SVG default 4 */
    double tolerance;   /* largest distance of an outline from the true offset, user units */
    long max_points;    /* most control points to emit (0: no limit) */
} sv_stroke_style;

/*
 * Outlines the stroke of `in` into closed subpaths appended to `out`, to be
 * filled with the nonzero rule: every piece (segment bodies, joins, caps) is
 * its own positively oriented contour, so overlaps only add winding and the
 * union is the stroke, self-overlaps included. Straight lines and circular
 * arcs offset exactly; other curves are offset by cubic Béziers, subdivided
 * until every outline point lies within `tolerance` of the true offset.
 * Returns the number of offset-curve pieces that hit the subdivision limit
 * (0 when the tolerance holds everywhere), or -1 when the outline would
 * need more than st->max_points control points (it stops there; `out`
 * then holds a part of it).
 */
int sv_stroke_path(const sv_path *in, const sv_stroke_style *st, sv_path *out);

/*
 * Cuts `in` into its dashes (sv_dash.c): `dash` holds `n` lengths (> 0 sum,
 * none negative), restarted on each subpath at `offset`. Appends open
 * subpaths, exact pieces of the original segments, to `out`. Returns the
 * number of dashes, or -1 as soon as there would be more than max_dashes
 * (`out` then holds the first ones).
 */
int sv_path_dash(const sv_path *in, const double *dash, int n, double offset, int max_dashes,
                 sv_path *out);

/* ---------------------------------------------------------- SVG import */

/*
 * Limits that bound the work on untrusted files; each one, reached, ends the
 * import with an error naming it (tools/svg/README.md states the bounds).
 * The output is also capped at the scene store's capacities
 * (CS_CFG_MAX_REGIONS, CS_CFG_MAX_CONTOURS, CS_CFG_MAX_POINTS): a drawing
 * beyond them could never be loaded.
 */
#define SV_MAX_DEPTH 256         /* element nesting, in the file and through <use> */
/* elements instantiated by <use> and markers, and the path segments of the shapes among
 * them, all told (a copy of a long path costs its length) */
#define SV_MAX_USE_COPIES 500000
/* dashes of one stroke: each takes at least 4 of the scene's control points */
#define SV_MAX_DASHES (CS_CFG_MAX_POINTS / 4)
/* control points of every clip path applied (each element's clip is its own copy) */
#define SV_MAX_CLIP_POINTS (4 * CS_CFG_MAX_POINTS)
/* stops of one gradient; beyond, the rest are warned and ignored (every region
 * painted with it costs each stop a style computation and a copy) */
#define SV_MAX_STOPS 128
/* text set in the drawing, all told: a glyph with ink takes a contour at
 * least, and UTF-8 and white space take up to about 4 bytes a glyph */
#define SV_MAX_TEXT_BYTES (4 * CS_CFG_MAX_CONTOURS)
/* segment clips for all gradients' solid bands (the fallback of paint functions);
 * regions beyond get none, warned */
#define SV_MAX_BAND_WORK 2000000L
#define SV_MAX_WARNINGS 1000 /* kept in sv_doc.warnings; one more says how many were left out */

typedef struct sv_import_opts {
    /*
     * Stroke tolerance in canvas units. 0 picks 0.01 px at `nominal_px`
     * pixels on the canvas's longer side.
     */
    double tolerance;
    double nominal_px; /* 0 = 1024 */
    double current_color[3]; /* for a root-level currentColor; default black */
    const char *font_path;   /* for <text>: every glyph from this file; NULL = fontconfig's choice */
    /* One cel per painted fill or stroke (SVG's per-shape "over", conflation
     * seams included) instead of packing opaque regions into shared cels. */
    bool one_cel_per_shape;
} sv_import_opts;

/*
 * Parses an SVG file into `doc` (initialised by the call). Returns 0, or -1
 * with a message in err (unreadable file, XML error with line and column).
 * Everything the importer does not draw exactly becomes a warning in
 * doc->warnings naming the element; nothing is dropped silently.
 */
int sv_import_file(const char *path, const sv_import_opts *opts, sv_doc *doc, char *err,
                   size_t errlen);
int sv_import_buffer(const char *data, size_t len, const sv_import_opts *opts, sv_doc *doc,
                     char *err, size_t errlen);

/* ----------------------------------------------------------- back ends */

/*
 * Decides how each region is drawn (sv_region.draw, .csg_clips) within the
 * default scene store's capacities, and warns for every fallback
 * (sv_plan.c). sv_import_* call it; call it again after editing the IR.
 */
void sv_doc_plan(sv_doc *doc);

/*
 * A region's CSG program with the first `nclips` clips of its chain (see
 * sv_plan.c): the fill rule for all operands, the RPN (CS_CSG_* operators),
 * and every contour to write - the region's own first, then the clips' -
 * with its operand. False when the core's capacity does not hold it.
 */
typedef struct sv_csg {
    int rule;
    int nrpn;
    int rpn[CS_CFG_MAX_CSG];
    int nops;
    int ncontours, nown;
    const sv_contour **contours;
    int *ops;
} sv_csg;

bool sv_csg_build(const sv_doc *doc, const sv_region *r, int nclips, sv_csg *out);
void sv_csg_free(sv_csg *c);
/* How many clips enclose the region (its clip and their parents). */
int sv_clip_chain_length(const sv_doc *doc, const sv_region *r);

typedef struct sv_scene_opts {
    bool has_background;
    double background[3]; /* sRGB 0..1 */
    /* One average colour per gradient instead of its functions or bands. */
    bool gradient_average;
} sv_scene_opts;

/*
 * Builds `scene` (cs_scene_init'ed by the call) with every colour in linear
 * light, as the core wants. Render it with cs_render_opts.blend =
 * CS_BLEND_SRGB to blend as SVG renderers do (doc->blend_srgb). Returns 0
 * or -1 with err.
 */
int sv_doc_to_scene(const sv_doc *doc, const sv_scene_opts *opts, cs_scene *scene, char *err,
                    size_t errlen);

/*
 * Writes the scene JSON of DESIGN.md and docs/SCENE.md (paint functions,
 * CSG, cel transforms; "canvas": {"blend": "srgb"} when doc->blend_srgb).
 * Returns a malloc'd string (caller frees) or NULL. `background` may be NULL.
 */
char *sv_doc_to_json(const sv_doc *doc, const double *background_srgb);

/* sRGB-encoded 0..1 to linear light (the IEC 61966-2-1 curve). */
double sv_srgb_to_linear(double v);

#endif /* SV_H */
