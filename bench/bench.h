/*
 * bench.h - what the parts of the benchmark program share.
 *
 * The benchmark (bench.c) renders the same scene four ways in one process:
 * with the celscan core, with cairo, with FreeType's smooth rasterizer and
 * with Anti-Grain Geometry. The peers cannot read NURBS, so outline.c turns
 * the scene's contours into the Bezier paths a user of those libraries would
 * hand them: exact where the curve is polynomial (lines, quadratics,
 * cubics), cubic approximations within OL_RATIONAL_TOL device pixels where it
 * is rational (circles, weighted NURBS). peer_cairo.c, peer_ft.c and
 * peer_agg.cpp (C++, behind the C interface of peer_agg.h) draw those paths;
 * accuracy.c measures every renderer's coverage against the long double
 * reference of the test suite (tests/ref); anim.c plays the scenes'
 * "animate" transform tracks, which the JSON loader only checks.
 *
 * Everything here is host code: it allocates, uses libm and double
 * precision freely. Only core/ is held to the freestanding rules.
 */
#ifndef BENCH_BENCH_H
#define BENCH_BENCH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "celscan_private.h"

#include "outline.h"
#include "peer_agg.h"

/*
 * Converts `scene` at its current cel transforms, for a width x height
 * output, into peer paths. Regions with a CSG program are skipped (the
 * peers have no such fill); returns the number skipped, or -1 on failure.
 */
int ol_build(ol_set *set, const cs_scene *scene, int width, int height);
void ol_free(ol_set *set);

/* The device transform of cel `ci` at width x height (canvas scale included). */
void ol_cel_device_map(const cs_scene *scene, int ci, int width, int height, double m[6]);

/*
 * Converts one contour of the scene to commands appended to `set` (used by
 * ol_build and by accuracy.c for single shapes). Returns 0 or -1.
 */
int ol_add_contour(ol_set *set, const cs_scene *scene, int contour, const double m[6],
                   ol_contour *out);

/* ---------------------------------------------------------------- peers */

typedef struct peer_cairo peer_cairo;
typedef struct peer_ft peer_ft;

/*
 * Both peers draw regions [first, end) of a set back to front (the set is
 * front-most first) over the background colour, or with `over_saved` over
 * the image kept by the last *_save_background (a peer's own cache of a
 * static background: drawn once, copied in every frame).
 */
/* tolerance: cairo_set_tolerance (cairo's default is 0.1 device px). */
peer_cairo *peer_cairo_new(int width, int height, double tolerance);
void peer_cairo_free(peer_cairo *p);
void peer_cairo_frame(peer_cairo *p, const ol_set *set, int first, int end, bool over_saved);
void peer_cairo_save_background(peer_cairo *p);
/* ARGB32 premultiplied, sRGB-encoded; stride in bytes. */
const uint32_t *peer_cairo_pixels(peer_cairo *p, int *stride_bytes);
/* Coverage of one contour alone over the box [x0, x0+w) x [y0, y0+h), 0..1. */
void peer_cairo_coverage(const ol_set *set, const ol_contour *c, bool evenodd, double tolerance,
                         int x0, int y0, int w, int h, double *out);

peer_ft *peer_ft_new(int width, int height);
void peer_ft_free(peer_ft *p);
/* Converts the set to FreeType outlines (26.6 fixed point, y up): not timed. */
int peer_ft_prepare(peer_ft *p, const ol_set *set);
void peer_ft_frame(peer_ft *p, const ol_set *set, int first, int end, bool over_saved);
void peer_ft_save_background(peer_ft *p);
const uint32_t *peer_ft_pixels(peer_ft *p); /* ARGB32 premultiplied, stride 4*width */
int peer_ft_coverage(peer_ft *p, const ol_set *set, const ol_contour *c, bool evenodd, int x0,
                     int y0, int w, int h, double *out);

/* ---------------------------------------------------------- animation */

typedef struct anim anim;
/* Reads the "animate" transform tracks of the scene file's cels; NULL if none. */
anim *anim_load(const char *path, const cs_scene *scene);
void anim_free(anim *a);
/* Sets every animated cel's transform for time t (seconds). */
void anim_apply(const anim *a, cs_scene *scene, double t);
/* First cel behind every animated cel: the static background is [from, cel_count). */
uint32_t anim_static_from(const anim *a, const cs_scene *scene);

/* ------------------------------------------------------------ accuracy */

typedef struct acc_stats {
    double max_err;     /* largest |coverage - exact| over every pixel, in 1/255 */
    double sum_err;     /* sum over edge pixels (exact strictly between 0 and 1) */
    long edge_pixels;
    long over_1;        /* edge pixels off by more than 1/255 */
    int shapes;
} acc_stats;

enum { ACC_CS_NONE, ACC_CS_16, ACC_CS_EXACT, ACC_CAIRO, ACC_CAIRO_FINE, ACC_FT, ACC_AGG, ACC_COUNT };
extern const char *const acc_names[ACC_COUNT];

/*
 * Coverage of up to max_shapes single contours of `scene` (an even sample),
 * each alone in white on black, by every renderer against tests/ref's exact
 * area, at width x height. Seconds spent in the reference go to *ref_s.
 */
int acc_measure(const cs_scene *scene, int width, int height, int max_shapes, peer_ft *ft,
                acc_stats out[ACC_COUNT], double *ref_s);

/* --------------------------------------------------------------- misc */

double bench_now(void); /* seconds, CLOCK_MONOTONIC */
double bench_median(double *v, int n); /* sorts v */

#endif /* BENCH_BENCH_H */
