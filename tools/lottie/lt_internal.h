/*
 * lt_internal.h - what the Lottie importer's files share (not its API).
 *
 * The importer evaluates every animated value of a Lottie file the way
 * rlottie does (lt_prop.c), samples the scene it maps onto at every frame
 * of the composition, and turns each sampled value back into a keyframe
 * track (lt_track.c): one cubic key per stretch where a Lottie easing
 * reproduces the samples, linear keys where the samples lie on a line, and
 * a key per frame only where neither holds (several properties eased
 * differently at once). Geometry and styles (lt_shape.c) become regions
 * through the SVG importer's path and stroke code (tools/svg); layers,
 * parenting and precomps (lt_layer.c) become cels and cel groups.
 *
 * Sampling keeps every frame the reference player shows exact, whatever
 * the property; the cost of a hostile file is bounded by the work budget
 * (LT_MAX_WORK sampled floats, which also bounds the memory the samples
 * take) checked as the samples are taken.
 */
#ifndef LT_INTERNAL_H
#define LT_INTERNAL_H

#include <cjson/cJSON.h>
#include <stdbool.h>
#include <stddef.h>

#include "../svg/sv.h"
#include "lt.h"

/* Bounds that keep a hostile file's cost in check (each refused with an error). */
#define LT_MAX_FRAMES 20000     /* frames of the composition sampled */
#define LT_MAX_KEYFRAMES 100000 /* keyframes of one property */
#define LT_MAX_DEPTH 32         /* nested groups, precomps, parent chains */
#define LT_MAX_VERTICES 100000  /* vertices of one path */
#define LT_MAX_COPIES 1000      /* copies of one repeater */
#define LT_MAX_ITEMS 100000     /* shape items of a layer, repeated copies included */
#define LT_MAX_WORK 2e7         /* floats sampled over the whole import (the conformance
                                   set's largest needs 6.6e6) */
#define LT_MAX_DIMS 4

/* One keyframe of a property: value s at frame t, easing to the next. */
typedef struct lt_key {
    double t;
    double *s;          /* dims values (a path: its flattened vertices) */
    double *e;          /* old-format end value, or NULL (then the next key's s) */
    double ox[LT_MAX_DIMS], oy[LT_MAX_DIMS], ix[LT_MAX_DIMS], iy[LT_MAX_DIMS];
    bool hold;
    bool spatial;       /* to/ti tangents make the motion a curve */
    double to[2], ti[2];
} lt_key;

/* A property: static (nkeys 0, value) or keyframed. */
typedef struct lt_prop {
    int dims;
    double *value; /* static value, or the value at the last evaluation */
    int nkeys;
    lt_key *keys;
    bool split;    /* position with separate x and y properties */
    struct lt_prop *sx, *sy;
} lt_prop;

/* A Lottie path value: n vertices, closed or not; v, i, o as x y pairs. */
typedef struct lt_path {
    int n;
    bool closed;
    double *v, *in, *out; /* 2n each, tangents relative to the vertex */
} lt_path;

typedef struct lt_ctx lt_ctx;

/* Parses a property object (NULL: the default). Returns 0 or -1 (error in ctx). */
int lt_prop_parse(lt_ctx *c, const cJSON *j, int dims, const double *dflt, const char *what,
                  lt_prop *p);
/* A path property ("ks" of an "sh" item): values of 1 + 6n numbers (closed flag, v, i, o). */
int lt_prop_parse_path(lt_ctx *c, const cJSON *j, const char *what, lt_prop *p, int *nverts);
void lt_prop_free(lt_prop *p);
/* The property at frame f into out[dims]. */
void lt_prop_eval(const lt_prop *p, double f, double *out);
bool lt_prop_animated(const lt_prop *p);
/* A path property's value as a path (out->v etc. point into buf of 6n doubles). */
void lt_path_from_values(const double *vals, int n, lt_path *out);

/* Cubic Bezier easing (x1 y1 x2 y2) at u, solved in double. */
double lt_ease(const double *e, double u);

/* ---------------------------------------------------------------- tracks */

/*
 * A sampled value: nframes x width floats, frame n at time n / fr. The
 * easings seen on the properties it depends on are candidates for cubic
 * keys: a stretch between two breaks (keyframe frames) that one of them
 * reproduces within `tol` becomes one key.
 */
typedef struct lt_signal {
    int nframes, width;
    double *v;          /* nframes * width */
    double tol;         /* per float, absolute */
    int nbreaks;
    double *breaks;     /* frame indices (may be fractional), sorted */
    double tail;        /* the first keyframe after the last sample (0: none), where the
                           last stretch's easing ends */
    int neases;
    double (*eases)[4];
} lt_signal;

void lt_signal_init(lt_signal *s, int nframes, int width, double tol);
void lt_signal_free(lt_signal *s);
/* Records keyframes and easings of property p (evaluated at frame f = f0 + n * fscale). */
void lt_signal_note_prop(lt_signal *s, const lt_prop *p, double f0, double fscale);
bool lt_signal_static(const lt_signal *s);
/* Adds a break at sample n (a frame where a value may change its course). */
void lt_signal_break(lt_signal *s, double n);
/*
 * Writes {"keys": [...], "ease": ...} for the signal into a new cJSON
 * object; value_fn turns one frame's floats into the key's JSON value.
 * Returns the track, or NULL when the signal is static.
 */
cJSON *lt_signal_track(const lt_signal *s, double fr,
                       cJSON *(*value_fn)(const double *v, int width));

/* ---------------------------------------------------------------- context */

typedef enum lt_feature {
    LT_F_EXPRESSION, LT_F_EFFECT, LT_F_TEXT, LT_F_IMAGE, LT_F_MERGE, LT_F_3D, LT_F_REPEATER,
    LT_F_ROUND, LT_F_MATTE, LT_F_MASK, LT_F_AUTO_ORIENT, LT_F_STAR_POINTS,
    LT_F_STROKE_ANIM, LT_F_GRADIENT, LT_F_BLEND, LT_F_OTHER, LT_F_COUNT_
} lt_feature;

/* A track matte over a precomp, for the composition's layers: the source's
 * shapes, the matte type, and the source's space in the composition's at
 * every sample. */
typedef struct lt_matte_ctx {
    const cJSON *shapes;
    int tt;
    sv_affine *xf;
} lt_matte_ctx;

struct lt_fold; /* a precomp layer folded into its composition's one layer (lt_layer.c) */

struct lt_ctx {
    const cJSON *root;
    const cJSON *assets;
    double fr, ip, op, w, h;
    int nframes;
    double work, max_work;
    double tolerance; /* stroke outline tolerance, canvas units */
    char *err;
    size_t errlen;
    bool failed;
    unsigned warned;        /* lt_feature bits already warned */
    lt_warnings *warnings;
    cJSON *cels;            /* the scene's "cels", front to back */
    int depth;
    const lt_matte_ctx *matte; /* the matte of the precomp being read, or NULL */
    const struct lt_fold *fold; /* the precomp layer being folded, or NULL */
};

/* Records an error (the first one wins); returns -1. */
int lt_fail(lt_ctx *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* One warning per feature and file. */
void lt_warn(lt_ctx *c, lt_feature f, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* Charges n floats of sampling to the work budget; false (and an error) once exhausted. */
bool lt_charge(lt_ctx *c, double n);
/* A member that must be a number, within [lo, hi], else dflt when absent. */
int lt_num(lt_ctx *c, const cJSON *obj, const char *key, double lo, double hi, double dflt,
           double *out);

/* Shape layer contents into regions of the cel `cel` (lt_shape.c). */
typedef struct lt_time {
    int nframes;
    const double *frame; /* the composition's frame at sample n (rlottie: whole frames) */
    double f0, fscale;   /* frame ~ f0 + n * fscale: where keyframes fall among the samples */
    const sv_affine *xf; /* NULL, or a matrix per sample carrying the shapes into another
                            layer's space (a track matte's source into its layer's) */
} lt_time;

int lt_shapes(lt_ctx *c, const cJSON *shapes, const lt_time *tm, cJSON *regions);
/* A solid layer's rectangle. */
int lt_solid(lt_ctx *c, const cJSON *layer, const lt_time *tm, cJSON *regions);
/* Masks of a layer as CSG operands over each of its regions (lt_shape.c). */
int lt_masks(lt_ctx *c, const cJSON *masks, const lt_time *tm, cJSON *regions);
/*
 * A track matte (tt 1 alpha, 2 alpha inverted, 3 luma, 4 luma inverted) as
 * CSG over each of the matted layer's regions, with the regions of the
 * matte's source (already in the matted layer's space) as operands, and a
 * single source region's constant beta as the matted paints' (lt_mask.c). Returns 1 when expressed, 0 when not (warned: drawn
 * unmatted), -1 on error.
 */
int lt_matte(lt_ctx *c, int tt, const cJSON *src_regions, cJSON *regions);
/* A transform's matrix at frame f, in After Effects' order (lt_shape.c). */
void lt_xf_eval(const lt_prop *a, const lt_prop *p, const lt_prop *s, const lt_prop *r,
                const lt_prop *sk, const lt_prop *sa, double f, sv_affine *m);

/* Layers of a composition (lt_layer.c). */
int lt_layers(lt_ctx *c, const cJSON *layers, const lt_time *tm, int parent_cel);

/* JSON helpers. */
cJSON *lt_num_array(const double *v, int n);
/* Control points (x y w per point, width floats) as a contour's "points" (lt_shape.c). */
cJSON *lt_points_value(const double *v, int width);
cJSON *lt_contour_json(const sv_contour *ct);
/* Closed contours of a path with a layout fixed by its segments (lt_shape.c). */
void lt_fixed_contours(const sv_path *p, sv_contour **out, int *n);
void lt_free_contours(sv_contour *c, int n);
/* Gives every frame's contours one layout, shapes unchanged (lt_layout.c). */
void lt_unify_layout(sv_contour **frames, int *counts, int nframes);
/* A Lottie path (closed flag, v, i, o) as an sv_path. */
void lt_path_build(const double *vals, int n, sv_path *out);

#endif /* LT_INTERNAL_H */
