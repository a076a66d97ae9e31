/*
 * sv_pattern.h - <pattern> paint servers resolved to tiles (sv_pattern.c).
 */
#ifndef SV_PATTERN_H
#define SV_PATTERN_H

#include "sv_gradient.h"

/* A pattern for one painted element: its tile and how the content maps into it. */
typedef struct sv_pattern {
    const sv_node *content; /* the element of the href chain whose children draw the tile */
    double x, y, w, h;      /* tile (0, 0) in pattern space, units resolved */
    sv_affine transform;    /* pattern space to the element's user space (patternTransform) */
    bool has_viewbox;
    double viewbox[4];
    const char *par;        /* preserveAspectRatio, or NULL */
    bool content_bbox;      /* patternContentUnits objectBoundingBox (without a viewBox) */
    double bbox[4];         /* the element's user-space bounding box */
} sv_pattern;

typedef enum sv_pattern_status {
    SV_PATTERN_OK = 0,
    SV_PATTERN_NONE,   /* paints nothing: a zero-size tile, no children in the chain */
    SV_PATTERN_INVALID /* objectBoundingBox units on a flat box: the paint's fallback applies */
} sv_pattern_status;

/*
 * Resolves pattern element `p` (attributes and children through its href
 * chain, first element that sets each) for an element with user-space
 * bounding box `bbox`, in a viewport of vp_w x vp_h.
 */
sv_pattern_status sv_pattern_resolve(const sv_node *p, sv_find_fn find, void *ctx, const double bbox[4],
                        double vp_w, double vp_h, sv_pattern *out, sv_doc *doc);

/* Pattern space of tile (i, j)'s content to the element's user space. */
sv_affine sv_pattern_content_map(const sv_pattern *p, long i, long j);

/*
 * The tiles that meet a user-space box: i in [i0, i1), j in [j0, j1).
 * False when the pattern transform cannot be inverted.
 */
bool sv_pattern_tile_range(const sv_pattern *p, const double box[4], long *i0, long *i1,
                           long *j0, long *j1);

#endif /* SV_PATTERN_H */
