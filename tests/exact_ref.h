/*
 * exact_ref.h - an independent, high-precision coverage reference for the
 * exact anti-aliasing tests.
 *
 * It shares nothing with the core: NURBS are evaluated point by point with
 * de Boor's algorithm in long double (not converted to power basis),
 * flattened adaptively to a polygon within 1e-7 px, and each pixel's
 * coverage is integrated with many sub-scanlines per pixel (exact
 * horizontal spans in long double, never straddling a polygon vertex),
 * under the region's fill rule. Its own
 * error is checked against closed forms (test_exact's test_ref_circle_points
 * and test_ref_accuracy).
 *
 * Its names start with xref_, apart from tests/ref/ref.h's ref_, the
 * reference of the other image tests, whose contours and regions are laid
 * out differently (float input, owned arrays).
 */
#ifndef EXACT_REF_H
#define EXACT_REF_H

/* A closed periodic NURBS in canvas units: xyw[3*i..] = x, y, w. */
typedef struct xref_contour {
    int degree, count;
    const double *xyw;
    const double *intervals; /* count knot intervals; NULL for all ones */
} xref_contour;

typedef struct xref_region {
    int evenodd;
    int contour_count;
    const xref_contour *contours;
} xref_region;

/* Canvas to device: (x, y) -> affine (SVG order a b c d e f) -> scale (sx, sy). */
typedef struct xref_view {
    double a, b, c, d, e, f;
    double sx, sy;
} xref_view;

/*
 * Coverage of each pixel [i, i+1) x [j, j+1) of a width x height image by
 * the region, into out[j*width + i], with at least `subscan` sub-scanlines
 * per pixel row (1024 keeps its error near 1e-7 on the test scenes).
 * Returns 0, or -1 if memory ran out.
 */
int xref_coverage(const xref_region *reg, const xref_view *view, int width, int height, int subscan,
                 double *out);

/* A point of contour c at knot parameter t in span j, in device space. */
void xref_contour_point(const xref_contour *c, const xref_view *view, int span, long double t,
                       long double *x, long double *y);

/*
 * Flattened contour, for checks: up to `cap` device points (x, y pairs)
 * into pts; returns the count, or -1 if it did not fit.
 */
long xref_flatten(const xref_contour *c, const xref_view *view, long double *pts, long cap);

/* Area of polygon poly (n points) inside the pixel square at (i, j),
 * signed by orientation: Sutherland-Hodgman clipping, for self-tests. */
long double xref_polygon_pixel_area(const long double *poly, int n, int i, int j);

#endif /* EXACT_REF_H */
