/*
 * svg_refscan.h - an independent reference for coverage: closed polygons in
 * long double, scanned with nonzero winding on many sub-scanlines per pixel
 * row with exact horizontal span coverage (midpoint rule vertically: a
 * pixel's error is at most 1/(2 S) and only where an edge runs horizontally
 * through it). Curves are fed to it finely flattened by the tests, from
 * their own definitions, never from the importer's output.
 */
#ifndef SVG_REFSCAN_H
#define SVG_REFSCAN_H

typedef struct ref_edge {
    long double x0, y0, x1, y1; /* y0 < y1 */
    int dir;
} ref_edge;

typedef struct ref_raster {
    int w, h;
    ref_edge *e;
    int n, cap;
} ref_raster;

void ref_init(ref_raster *r, int w, int h);
void ref_free(ref_raster *r);
/* A closed polygon of n points (x, y interleaved) in device pixels. */
void ref_add_poly(ref_raster *r, const long double *xy, int n);
/* Coverage 0..1 of every pixel (w*h doubles) under the nonzero rule. */
void ref_render(const ref_raster *r, int subs, double *cov);

#endif /* SVG_REFSCAN_H */
