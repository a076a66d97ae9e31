/*
 * ref.h - the test suite's independent truth: a high-precision evaluator of
 * closed periodic rational NURBS regions and their pixel coverage.
 *
 * Nothing here shares code or method with core/. The core turns each knot
 * span into a power-basis rational polynomial in single precision and
 * intersects scanlines with it analytically; the reference instead
 *
 *   - evaluates the curve in long double straight from the knot vector, by
 *     de Boor's algorithm on homogeneous points (ref_eval_span) and, as a
 *     cross-check of itself, by summing Cox-de Boor basis functions
 *     (ref_eval_basis);
 *   - flattens every contour densely and adaptively in long double until no
 *     chord is farther than REF_FLAT_TOL device pixels from the curve (the
 *     deviation is tested at the quarter, half and three-quarter parameters of
 *     each chord, after at least REF_MIN_DEPTH halvings per span);
 *   - computes pixel coverage of the resulting polygons.
 *
 * Coverage methods and their error bounds (for coverage in 0..1):
 *
 *   ref_coverage_area    Exact area of (polygon interior by fill rule) inside
 *                        each pixel square. Each pixel row is cut into strips
 *                        at every polygon vertex and every edge-edge
 *                        intersection, so within a strip the edges are straight,
 *                        do not cross, and keep their left-to-right order; the
 *                        fill rule then selects trapezoids whose area per pixel
 *                        column is integrated in closed form (FreeType-style
 *                        cells plus a cover prefix sum). The only error left is
 *                        the flattening: at most REF_FLAT_TOL times the boundary
 *                        length inside the pixel, i.e. below 1e-5 for any pixel
 *                        crossed by less than 5 px of boundary, which is under
 *                        0.003/255 - far inside the 0.2/255 the tests need.
 *                        Works for nonzero and evenodd, with holes, overlaps and
 *                        self-intersections.
 *   ref_coverage_subscan nsub sub-scanlines per pixel row at y = j + (k+0.5)/nsub,
 *                        exact horizontal span coverage per pixel. This is a
 *                        model of what --aa N should compute; its distance
 *                        from the true area is up to 1/(2*nsub) per boundary
 *                        edge crossing the pixel.
 *   ref_coverage_centre  Inside/outside at each pixel centre (i+0.5, j+0.5)
 *                        by winding number of the dense polygon, plus a flag
 *                        for pixels whose centre lies within `eps` of the
 *                        polygon (where the dense polygon, REF_FLAT_TOL away
 *                        from the curve, cannot decide).
 *
 * All geometry is in device pixels, y down; pixel (i, j) is [i,i+1) x [j,j+1).
 * Inputs are taken as the floats the core receives, so input rounding is not
 * counted against the core.
 */
#ifndef CELSCAN_TEST_REF_H
#define CELSCAN_TEST_REF_H

#include <stddef.h>

#define REF_FLAT_TOL 2e-6L /* device px: largest chord-to-curve distance */
#define REF_MIN_DEPTH 4     /* every span is cut into at least 16 chords */
#define REF_MAX_CONTOURS 1024

typedef struct ref_contour {
    int degree; /* 1..3 */
    int count;  /* N control points == N knot intervals */
    long double *x, *y, *w;
    long double *iv; /* knot intervals, t(k+1) - t(k) = iv[k mod N] */
} ref_contour;

typedef struct ref_poly {
    int contour_count;
    int *start; /* contour c is vertices start[c] .. start[c+1]-1, closed */
    long double *x, *y;
    int total;
} ref_poly;

typedef struct ref_region {
    int evenodd; /* 0 nonzero, 1 evenodd */
    int contour_count;
    ref_contour contours[REF_MAX_CONTOURS];
    ref_poly poly; /* dense flattening, built on first use */
    int flattened;
} ref_region;

/* Region lifetime. ref_region is large: allocate it (ref_region_new). */
ref_region *ref_region_new(int evenodd);
void ref_region_free(ref_region *r);

/*
 * Appends a contour. xyw holds count triples (x, y, w) as given to the core
 * (floats); intervals holds count knot intervals or is NULL for all ones.
 * Returns the contour index or -1 when full.
 */
int ref_region_add(ref_region *r, int degree, int count, const float *xyw, const float *intervals);

/*
 * Maps every control point by x' = a x + c y + e, y' = b x + d y + f, then
 * scales by (sx, sy): the canvas-to-device map. Weights are unchanged (a
 * rational curve is affinely invariant in homogeneous form).
 */
void ref_region_transform(ref_region *r, const long double m[6], long double sx, long double sy);

/* Knot t(k) for any integer k, with t(0) = 0. */
long double ref_knot(const ref_contour *c, long k);

/*
 * The curve on knot span j (0 <= j < N, iv[j] > 0) at t = t(j) + u*iv[j],
 * u in [0, 1], by de Boor's algorithm in homogeneous long double.
 * out[0] = x, out[1] = y.
 */
void ref_eval_span(const ref_contour *c, int j, long double u, long double out[2]);

/* The same point by explicit Cox-de Boor basis sums, for u in [0, 1). */
void ref_eval_basis(const ref_contour *c, int j, long double u, long double out[2]);

/* The dense polygon of the region (flattened on first use). */
const ref_poly *ref_region_poly(ref_region *r);

/* Signed area of the winding integral (sum over contours of shoelace areas). */
long double ref_poly_signed_area(const ref_poly *p);

/* Coverage per pixel, row-major W*H, values in 0..1. */
void ref_coverage_area(ref_region *r, int W, int H, double *out);
void ref_coverage_subscan(ref_region *r, int W, int H, int nsub, double *out);

/*
 * inside[i] = 1 where the pixel centre is inside by the fill rule;
 * ambiguous[i] = 1 where it lies within eps of the dense polygon (may be NULL).
 */
void ref_coverage_centre(ref_region *r, int W, int H, double eps, unsigned char *inside,
                         unsigned char *ambiguous);

/* Winding number of the dense polygon at (x, y) (half-open in y). */
int ref_winding(ref_region *r, long double x, long double y);

#endif /* CELSCAN_TEST_REF_H */
