/*
 * outline.h - the scene as the peers' Bezier paths: the types alone.
 *
 * bench.h declares the functions that build these from a cs_scene
 * (outline.c). The types are kept apart, free of the core's header, so that
 * the C++ peer (peer_agg.cpp) can read a set without compiling celscan.h,
 * which is C11.
 */
#ifndef BENCH_OUTLINE_H
#define BENCH_OUTLINE_H

#include <stdbool.h>

/* Largest distance, in device pixels, between a rational curve and the
 * cubic Beziers that stand for it in the peers' paths. */
#define OL_RATIONAL_TOL 0.01

/* ------------------------------------------------------------ outlines */

enum { OL_LINE = 1, OL_QUAD = 2, OL_CUBIC = 3 };

/* One path command in device pixels (y down): LINE p[0..1], QUAD control
 * p[0..1] end p[2..3], CUBIC controls p[0..3] end p[4..5]. */
typedef struct ol_cmd {
    int op;
    double p[6];
} ol_cmd;

typedef struct ol_contour {
    double x0, y0;     /* start point */
    int first, count;  /* commands [first, first+count) of the set */
    int scene_contour; /* index into cs_scene contours */
} ol_contour;

typedef struct ol_region {
    int first, count;  /* contours [first, first+count) of the set */
    int scene_region;
    int cel;
    bool evenodd;
    double rgba[4];    /* sRGB-encoded straight colour and alpha, for the peers */
    double bx0, by0, bx1, by1; /* device bounds of the control polygon */
} ol_region;

/* The scene as peer paths, regions in scene order (front-most first). */
typedef struct ol_set {
    ol_region *regions;
    int region_count;
    ol_contour *contours;
    int contour_count;
    ol_cmd *cmds;
    int cmd_count, cmd_cap;
    double background[4]; /* sRGB, alpha 1 */
    int width, height;
    int rational_segments, approx_cubics; /* how much was approximated */
} ol_set;

#endif /* BENCH_OUTLINE_H */
