/*
 * celscan.h - the public API of the celscan core renderer.
 *
 * celscan scan-converts stacks of cels (transparent sheets of painted regions
 * bounded by closed NURBS curves) one display line at a time, following Willis
 * & Oddy, "Rendering NURB Regions for 2D Animation" (Eurographics '92). Every
 * curve becomes rational polynomial segments (X(u), Y(u), W(u)); each
 * scanline is intersected analytically with the segments; crossings become
 * spans with real endpoints; spans become exact horizontal coverage; cels are
 * composited front to back in the beta colour model. No frame buffer exists:
 * working memory is O(width).
 *
 * The core is freestanding: no libc, no libm, no allocation, no mutable
 * globals. The caller owns all memory:
 *   - cs_scene      the scene store (what a commit makes visible),
 *   - cs_workspace  per-render scratch (segment arena, line buffers),
 *   - cs_renderer   the small context tying them together for one frame.
 * Capacities are compile-time configuration (cs_config.h).
 *
 * Every function that can fail returns a cs_status; CS_OK is zero. Where the
 * failure has a location (a cel, region, contour, point), a cs_error filled by
 * the call says where.
 */
#ifndef CELSCAN_H
#define CELSCAN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cs_config.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------- status */

typedef enum cs_status {
    CS_OK = 0,
    CS_ERR_ARG,           /* null pointer or argument outside its documented range */
    CS_ERR_STATE,         /* call out of order (e.g. a region before any cel) */
    CS_ERR_NONFINITE,     /* NaN or infinity in a number */
    CS_ERR_RANGE,         /* coordinate magnitude beyond CS_CFG_COORD_LIMIT */
    CS_ERR_DEGREE,        /* NURBS degree not 1, 2 or 3 */
    CS_ERR_TOO_FEW_POINTS,/* contour has fewer than degree+1 control points */
    CS_ERR_WEIGHT,        /* weight not > 0 */
    CS_ERR_INTERVAL,      /* knot interval negative */
    CS_ERR_ZERO_RUN,      /* more than degree-1 zero knot intervals in a row */
    CS_ERR_DEGENERATE,    /* all knot intervals zero, or a zero-size canvas */
    CS_ERR_FILL_RULE,     /* fill rule is neither nonzero nor evenodd */
    CS_ERR_PAINT,         /* paint component outside [0,1] */
    CS_ERR_SIZE,          /* output size zero, negative or beyond capacity */
    CS_ERR_CAP_CELS,      /* scene store full: cels */
    CS_ERR_CAP_REGIONS,   /* scene store full: regions */
    CS_ERR_CAP_CONTOURS,  /* scene store full: contours */
    CS_ERR_CAP_POINTS,    /* scene store full: control points */
    CS_ERR_CAP_SEGMENTS,  /* workspace full: segments of one frame */
    CS_ERR_CAP_PIECES,    /* workspace full: monotone pieces of one frame */
    CS_ERR_CAP_CROSSINGS, /* workspace full: crossings on one sub-scanline (--aa exact:
                             pieces or bands of one region on one pixel row) */
    CS_ERR_COUNT_
} cs_status;

/* A short English description of a status ("weight not > 0"). Never NULL. */
const char *cs_status_str(cs_status status);

/*
 * Where a failure happened. Indices are -1 where they do not apply: a bad
 * control point of cel 2, region 0, contour 1, point 4 has cel=2 region=0
 * contour=1 item=4. `item` indexes points, or knot intervals for
 * CS_ERR_INTERVAL / CS_ERR_ZERO_RUN.
 */
typedef struct cs_error {
    cs_status status;
    int32_t cel, region, contour, item;
} cs_error;

/* ----------------------------------------------------------- scene store */

typedef enum cs_fill_rule { CS_FILL_NONZERO = 0, CS_FILL_EVENODD = 1 } cs_fill_rule;

/* A control point in canvas units with its rational weight (w > 0). */
typedef struct cs_point {
    float x, y, w;
} cs_point;

/*
 * A beta-model paint, every component in linear light, 0..1.
 * Seen by the camera it maps light L from behind to
 *   E + T*L with E = beta*pigment*F + (1-beta)*medium*B, T = (1-beta)*medium.
 */
typedef struct cs_paint {
    float pigment[3];
    float medium[3];
    float beta;
} cs_paint;

/* A closed periodic NURBS: points[first .. first+count) of the scene. */
typedef struct cs_contour {
    uint32_t first_point;
    uint16_t point_count;
    uint8_t degree;
} cs_contour;

typedef struct cs_region {
    uint32_t first_contour;
    uint16_t contour_count;
    uint8_t fill_rule; /* cs_fill_rule */
    cs_paint paint;
} cs_region;

/* An affine map x' = a x + c y + e, y' = b x + d y + f (SVG order a b c d e f). */
typedef struct cs_affine {
    float a, b, c, d, e, f;
} cs_affine;

typedef struct cs_cel {
    uint32_t first_region;
    uint16_t region_count;
    bool has_front;   /* false: the front light defaults to the stack's */
    cs_affine transform;
    float front[3];   /* linear light multipliers */
    float back[3];    /* lights only this cel's own paint; default black */
} cs_cel;

/*
 * The scene store. Cels, regions, contours and points are in front-to-back
 * order: cel 0 is front-most, and within a cel region 0 is front-most.
 * Build it with cs_scene_init and the cs_scene_add_* calls; each call
 * validates its input completely before it changes the store, so a rejected
 * call leaves the scene exactly as it was.
 */
typedef struct cs_scene {
    float canvas_w, canvas_h;
    bool has_background;
    float background[3]; /* linear light */
    float stack_front[3];
    float stack_back[3];
    uint32_t cel_count, region_count, contour_count, point_count;
    cs_cel cels[CS_CFG_MAX_CELS];
    cs_region regions[CS_CFG_MAX_REGIONS];
    cs_contour contours[CS_CFG_MAX_CONTOURS];
    cs_point points[CS_CFG_MAX_POINTS];
    float intervals[CS_CFG_MAX_POINTS]; /* knot interval k of each contour, parallel to points */
} cs_scene;

/* Empties the scene and sets its canvas. Lights default to front 1, back 0. */
cs_status cs_scene_init(cs_scene *scene, float canvas_w, float canvas_h);

/* An opaque card lit by the stack front light stands behind every cel. */
cs_status cs_scene_set_background(cs_scene *scene, const float rgb_linear[3]);
cs_status cs_scene_set_lights(cs_scene *scene, const float front[3], const float back[3]);

/*
 * Appends a cel behind those already present. `front` may be NULL (use the
 * stack front light), `back` may be NULL (black).
 */
cs_status cs_scene_add_cel(cs_scene *scene, const cs_affine *transform, const float front[3],
                           const float back[3], cs_error *err);

/* Appends a region to the last cel, behind its earlier regions. */
cs_status cs_scene_add_region(cs_scene *scene, cs_fill_rule rule, const cs_paint *paint,
                              cs_error *err);

/*
 * Appends a closed periodic NURBS contour of `degree` (1..3) with `count`
 * control points to the last region. `intervals` holds `count` knot intervals
 * (t(k+1) - t(k) = intervals[k mod count]) or is NULL for all ones. At most
 * degree-1 zero intervals may stand in a row, cyclically.
 */
cs_status cs_scene_add_contour(cs_scene *scene, int degree, int count, const cs_point *points,
                               const float *intervals, cs_error *err);

/* --------------------------------------------------------------- render */

typedef enum cs_aa_mode {
    CS_AA_NONE = 0,    /* one sample per pixel, at its centre */
    CS_AA_SUBSCAN = 1, /* N sub-scanlines, exact horizontal coverage */
    CS_AA_EXACT = 2    /* exact area of the pixel square */
} cs_aa_mode;

typedef struct cs_render_opts {
    int width, height;  /* output size in pixels */
    cs_aa_mode aa;
    int subscanlines;   /* for CS_AA_SUBSCAN: 1..CS_CFG_MAX_SUBSCANLINES */
    float time;         /* seconds, for animation */
} cs_render_opts;

/*
 * One rational polynomial segment in device space: for u in [0,1)
 * x(u) = X(u)/W(u), y(u) = Y(u)/W(u), with X(u) = sum x[i] u^i.
 */
typedef struct cs_segment {
    float x[4], y[4], w[4];
    uint16_t region;   /* index into scene regions */
    uint8_t degree;
} cs_segment;

/*
 * A y-monotone piece of a segment, u in [u0, u1], y from y_top to y_bot
 * (y_top < y_bot). The end y values are shared exactly with the neighbouring
 * pieces of the contour, so a half-open test y_top <= y < y_bot gives every
 * closed contour an even number of crossings on every scanline.
 */
typedef struct cs_piece {
    float u0, u1;
    float y_top, y_bot;
    uint32_t segment;
    uint16_t region;   /* copied from the segment: spares an indirection per line */
    uint8_t operand;   /* winding counter it moves: always 0 without CSG */
    int8_t dir;        /* +1 if y grows with u, -1 if it falls */
} cs_piece;

typedef struct cs_crossing {
    float x;
    int16_t dir;
    uint16_t operand; /* which winding counter of the region it moves (CSG) */
} cs_crossing;

/* Where one active piece is within the current band of a pixel row, for
 * exact-area coverage (cs_exact.c). */
typedef struct cs_exact_piece {
    float u_top, x_top;   /* parameter and x at the band's top */
    float u_bot, x_bot;   /* and at its bottom */
    float dmin, dmax;     /* the arc lies within [dmin, dmax] of its chord, horizontally */
    float xmin, xmax;     /* x range of the arc's control polygon */
    float key;            /* x order within the band: x_top + x_bot */
    uint32_t piece;
    bool monotone;        /* control polygon x-monotone, so the arc is */
} cs_exact_piece;

/* Per-render scratch memory. Contents are private to the core. */
typedef struct cs_workspace {
    cs_segment segments[CS_CFG_MAX_SEGMENTS];
    cs_piece pieces[CS_CFG_MAX_PIECES];
    uint32_t order[CS_CFG_MAX_PIECES];   /* pieces sorted by y_top */
    uint32_t active[CS_CFG_MAX_PIECES];  /* active pieces of the line, in piece order */
    uint32_t scratch[CS_CFG_MAX_PIECES]; /* sort scratch */
    cs_crossing crossings[CS_CFG_MAX_CROSSINGS];
    cs_exact_piece exact[CS_CFG_MAX_CROSSINGS]; /* a region's pieces on one row (exact AA) */
    uint32_t exact_order[CS_CFG_MAX_CROSSINGS];  /* those in the band, in x order */
    uint16_t region_cel[CS_CFG_MAX_REGIONS];
    float region_E[CS_CFG_MAX_REGIONS][3];
    float region_T[CS_CFG_MAX_REGIONS][3];
    float area[CS_CFG_MAX_WIDTH + 2];     /* partial coverage of the region, per pixel */
    float cover[CS_CFG_MAX_WIDTH + 2];    /* coverage deltas, prefix-summed */
    float used[CS_CFG_MAX_WIDTH];         /* coverage claimed in the cel so far */
    float cel_E[CS_CFG_MAX_WIDTH * 3];
    float cel_A[CS_CFG_MAX_WIDTH * 3];    /* 1 - T of the cel */
    float stack_E[CS_CFG_MAX_WIDTH * 3];
    float stack_T[CS_CFG_MAX_WIDTH * 3];
} cs_workspace;

/* The context of one frame. Set up by cs_frame_begin; fields are private. */
typedef struct cs_renderer {
    const cs_scene *scene;
    cs_workspace *ws;
    cs_render_opts opts;
    uint32_t segment_count, piece_count, active_count, next_order;
    float behind[3];     /* light arriving from behind the whole stack */
    float sx, sy;        /* canvas to device scale */
    int next_line;
    cs_error sticky;     /* first capacity error met while rendering lines */
} cs_renderer;

/*
 * Prepares a frame: evaluates the scene at opts->time, transforms control
 * points to device space, converts every contour to segments and splits them
 * into y-monotone pieces. On failure `err` says which contour.
 */
cs_status cs_frame_begin(cs_renderer *r, cs_workspace *ws, const cs_scene *scene,
                         const cs_render_opts *opts, cs_error *err);

/*
 * Renders line y (0 = top) into rgb_linear (3*width floats, linear light).
 * Lines must be requested in increasing order (the active list only moves
 * forward); skipping lines is allowed. A capacity overflow on the line is
 * recorded in r->sticky and the line is still produced, with the overflowing
 * region left out of that sub-scanline.
 */
cs_status cs_render_line(cs_renderer *r, int y, float *rgb_linear);

/* Where finished lines go: the seam the display HAL plugs into. */
typedef cs_status (*cs_line_sink)(void *user, int y, const float *rgb_linear, int width);

/*
 * Renders every line of the frame in order into `line` (3*width floats) and
 * hands each to `sink`. Stops at the first error of the sink. Returns the
 * sticky capacity error, if any, after the whole frame was produced.
 */
cs_status cs_render_frame(cs_renderer *r, float *line, cs_line_sink sink, void *user);

/* ---------------------------------------------------------- pixel output */

typedef enum cs_pixfmt {
    CS_PIX_RGB888_SRGB = 0,  /* 3 bytes per pixel, sRGB-encoded */
    CS_PIX_RGB565_SRGB = 1,  /* 2 bytes per pixel, little-endian, sRGB-encoded */
    CS_PIX_RGB16_LINEAR = 2, /* 6 bytes per pixel, big-endian 16-bit linear (PNG order) */
    CS_PIX_RGB888_LINEAR = 3 /* 3 bytes per pixel, linear */
} cs_pixfmt;

/* The pixel format of the firmware panels; `celsim --crc` hashes frames in it. */
#define CS_PANEL_PIXFMT CS_PIX_RGB565_SRGB

size_t cs_pixfmt_bytes_per_pixel(cs_pixfmt fmt);

/* Converts one line of linear RGB floats (clamped to 0..1) to `fmt`. */
void cs_pixfmt_convert(cs_pixfmt fmt, const float *rgb_linear, int width, uint8_t *out);

/* sRGB encoding of one linear value in 0..1, as a 16-bit code (0..65535). */
uint16_t cs_srgb_encode16(float linear);

/* ----------------------------------------------------------------- misc */

/* CRC-32 (IEEE 802.3, reflected, as zlib). Start with crc = 0. */
uint32_t cs_crc32(uint32_t crc, const void *data, size_t len);

#ifdef __cplusplus
}
#endif

#endif /* CELSCAN_H */
