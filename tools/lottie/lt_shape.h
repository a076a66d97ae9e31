/*
 * lt_shape.h - the Lottie importer's parsed shape items, shared by the
 * shape walk (lt_shape.c) and the geometry at one frame (lt_geom.c).
 */
#ifndef LT_SHAPE_H
#define LT_SHAPE_H

#include "lt_internal.h"

enum { SH_PATH, SH_ELLIPSE, SH_RECT, SH_STAR };
enum { ST_FILL, ST_STROKE, ST_GFILL, ST_GSTROKE };

/* A repeater ("rp"): copies, offset, and its transform with start and end opacity. */
typedef struct sh_rep {
    lt_prop c, o, a, p, s, r, so, eo;
} sh_rep;

/* A group's transform, or (rep set) one copy of a repeater's items. */
typedef struct sh_node {
    struct sh_node *parent;
    bool has_xf;
    lt_prop a, p, s, r, o, sk, sa;
    const sh_rep *rep;
    int copy;
} sh_node;

typedef struct sh_trim {
    lt_prop s, e, o;
} sh_trim;

typedef struct sh_path {
    int type;
    bool reversed;
    int nverts;
    lt_prop k, p, s, r;             /* sh: k; el: p s; rc: p s r; sr: p r (rotation) */
    lt_prop pt, ir, or_, is, os;    /* sr: points, radii, roundness (percent) */
    int star;                       /* sr: 1 star, 2 polygon */
    bool whole;                     /* sr: the point count floored (it is animated) */
    sh_node *node;
    int ntrims;
    sh_trim *trims[8];
} sh_path;

typedef struct sh_style {
    int type;
    sh_node *node;
    int rule;
    lt_prop c, o, w, gs, ge, gh, ga, g;
    int gtype, gstops, gcount;
    sv_cap cap;
    sv_join join;
    double miter;
    int ndash;
    lt_prop dash[16];
    lt_prop dash_offset;
    bool has_dash;
    int npaths;
    sh_path **paths;
} sh_style;

/* A group's transform at frame f (identity without one), and its opacity 0..1. */
sv_affine lt_node_matrix(const sh_node *n, double f);
double lt_node_opacity(const sh_node *n, double f);
/* The group transforms from node `from` up to (not including) `to`. */
sv_affine lt_chain(const sh_node *from, const sh_node *to, double f);
/* A style's region at frame f as closed contours in the layer's space. */
void lt_region_contours(lt_ctx *c, const sh_style *s, double f, sv_contour **out, int *n);
bool lt_same_layout(const sv_contour *a, int na, const sv_contour *b, int nb);

#endif /* LT_SHAPE_H */
