/*
 * shapes.h - contours for tests that build scenes with cs_scene_add_contour:
 * the exact circle of DESIGN.md (a closed rational quadratic: the eight
 * corners and edge midpoints of the circle's square, weight sqrt(1/2) on
 * the corners, knot intervals 1 0 1 0 ...), axis-aligned rectangles and
 * polygons. Each adds one contour to the scene's last region and returns
 * the core's status; wrap it in TL_MUST when the test cannot go on without
 * it, or CHECK_STATUS when the refusal is what is tested.
 *
 * Points are worked out in double and rounded to float once, so a circle
 * given float centre and radius has the points the float sums would give.
 * (tests/common.h builds shapes for the long double reference instead.)
 */
#ifndef CELSCAN_TEST_SHAPES_H
#define CELSCAN_TEST_SHAPES_H

#include <math.h>

#include "celscan.h"
#include "testlib.h"

static TL_UNUSED cs_status ts_add_circle(cs_scene *s, double cx, double cy, double r)
{
    static const double ux[8] = {1, 1, 0, -1, -1, -1, 0, 1}, uy[8] = {0, 1, 1, 1, 0, -1, -1, -1};
    static const float iv[8] = {1, 0, 1, 0, 1, 0, 1, 0};
    cs_point p[8];
    for (int i = 0; i < 8; i++)
        p[i] = (cs_point){(float)(cx + r * ux[i]), (float)(cy + r * uy[i]),
                          (float)((i & 1) ? sqrt(0.5) : 1.0)};
    cs_error e;
    return cs_scene_add_contour(s, 2, 8, p, iv, &e);
}

/* Corners (x0, y0), (x1, y0), (x1, y1), (x0, y1): degree 1. */
static TL_UNUSED cs_status ts_add_rect(cs_scene *s, double x0, double y0, double x1, double y1)
{
    cs_point p[4] = {{(float)x0, (float)y0, 1}, {(float)x1, (float)y0, 1},
                     {(float)x1, (float)y1, 1}, {(float)x0, (float)y1, 1}};
    cs_error e;
    return cs_scene_add_contour(s, 1, 4, p, NULL, &e);
}

/* n points (x, y) in xy[2n], n <= 64: degree 1. */
static TL_UNUSED cs_status ts_add_polygon(cs_scene *s, const double *xy, int n)
{
    cs_point p[64];
    if (n > 64)
        return CS_ERR_ARG;
    for (int i = 0; i < n; i++)
        p[i] = (cs_point){(float)xy[2 * i], (float)xy[2 * i + 1], 1};
    cs_error e;
    return cs_scene_add_contour(s, 1, n, p, NULL, &e);
}

#endif /* CELSCAN_TEST_SHAPES_H */
