/*
 * sv_internal.h - helpers shared by the importer's files (not its API).
 *
 * Growable arrays, allocation that stops the program on exhaustion (a host
 * tool importing a drawing has nothing sensible to do without memory), and
 * small string helpers.
 */
#ifndef SV_INTERNAL_H
#define SV_INTERNAL_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sv.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define SV_STR_(x) #x
#define SV_STR(x) SV_STR_(x)

void *sv_xrealloc(void *p, size_t size);
char *sv_xstrdup(const char *s);
char *sv_xstrndup(const char *s, size_t n);

/* Makes room for one more element in a growable array (ptr, n, cap). */
#define SV_GROW(ptr, n, cap)                                                                     \
    do {                                                                                         \
        if ((n) >= (cap)) {                                                                      \
            (cap) = (cap) ? 2 * (cap) : 8;                                                       \
            (ptr) = sv_xrealloc((ptr), (size_t)(cap) * sizeof *(ptr));                           \
        }                                                                                        \
    } while (0)

static inline double sv_hypot(double x, double y)
{
    return __builtin_sqrt(x * x + y * y);
}
static inline sv_pt sv_pt_make(double x, double y)
{
    sv_pt p = {x, y};
    return p;
}
static inline sv_pt sv_sub(sv_pt a, sv_pt b)
{
    return sv_pt_make(a.x - b.x, a.y - b.y);
}
static inline sv_pt sv_add(sv_pt a, sv_pt b)
{
    return sv_pt_make(a.x + b.x, a.y + b.y);
}
static inline sv_pt sv_scale(sv_pt a, double s)
{
    return sv_pt_make(a.x * s, a.y * s);
}
static inline double sv_dot(sv_pt a, sv_pt b)
{
    return a.x * b.x + a.y * b.y;
}
static inline double sv_cross(sv_pt a, sv_pt b)
{
    return a.x * b.y - a.y * b.x;
}
static inline double sv_len(sv_pt a)
{
    return sv_hypot(a.x, a.y);
}

/* Homogeneous control points of a segment: (w x, w y, w). */
void sv_seg_homogeneous(const sv_seg *s, double h[4][3]);
/* The same segment at a higher degree (exactly), as homogeneous points. */
void sv_seg_elevate(const sv_seg *s, int degree, double h[4][3]);

/* Point, first and second derivative of a segment at t (exact, rational). */
void sv_seg_derivs(const sv_seg *s, double t, sv_pt *c, sv_pt *c1, sv_pt *c2);

/* Flattens a subpath (taken as closed) into a polygon, `per_seg` lines per curve. */
void sv_subpath_flatten(const sv_subpath *s, int per_seg, sv_pt **pts, int *n);

#endif /* SV_INTERNAL_H */
