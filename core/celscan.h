/*
 * celscan.h - the public API of the celscan core renderer.
 *
 * celscan scan-converts stacks of cels (transparent sheets of painted regions
 * bounded by closed NURBS curves) one display line at a time, after Willis &
 * Oddy, "Rendering NURB Regions for 2D Animation" (Eurographics '92): curves
 * become rational polynomial segments, each scanline meets them analytically,
 * spans get exact horizontal coverage, and cels are composited front to back
 * in the beta colour model. No frame buffer: working memory is O(width).
 *
 * The core is freestanding: no libc, no libm, no allocation, no mutable
 * globals. The caller owns all memory, in the four structs declared below
 * and laid out in celscan_private.h (included by a caller that places them
 * or reads a scene's arrays); capacities are compile-time configuration
 * (cs_config.h). Every function that can fail returns a cs_status (CS_OK is
 * zero) and, where the failure has a location, fills a cs_error. This header
 * says what each call does; docs/API.md says the rest (why, and the cases).
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

typedef struct cs_scene cs_scene;         /* the scene store, with its keyframe tracks */
typedef struct cs_workspace cs_workspace; /* per-render scratch (segment arena, line buffers) */
typedef struct cs_renderer cs_renderer;   /* the small context of one frame */
typedef struct cs_stream cs_stream;       /* the cel stream decoder (docs/STREAM.md) */

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
    CS_ERR_INTERVAL,      /* knot interval negative or not finite */
    CS_ERR_ZERO_RUN,      /* more than degree-1 zero knot intervals in a row */
    CS_ERR_DEGENERATE,    /* every knot interval of a contour is zero */
    CS_ERR_FILL_RULE,     /* fill rule is neither nonzero nor evenodd */
    CS_ERR_PAINT,         /* paint component outside [0,1] */
    CS_ERR_SIZE,          /* canvas or output size not > 0, or beyond capacity */
    CS_ERR_CAP_CELS,      /* scene store full: cels */
    CS_ERR_CAP_REGIONS,   /* scene store full: regions */
    CS_ERR_CAP_CONTOURS,  /* scene store full: contours */
    CS_ERR_CAP_POINTS,    /* scene store full: control points */
    CS_ERR_CAP_SEGMENTS,  /* workspace full: segments of one frame */
    CS_ERR_CAP_PIECES,    /* workspace full: monotone pieces of one frame */
    CS_ERR_CAP_CROSSINGS, /* workspace full: crossings on one sub-scanline (--aa exact:
                             pieces or bands of one region on one pixel row) */
    CS_ERR_IO,            /* the line sink (display) refused a line */
    CS_ERR_CAP_FUNCS,     /* scene store full: paint functions */
    CS_ERR_FUNC,          /* paint function malformed (stops, geometry, kind) */
    CS_ERR_CSG,           /* CSG program malformed (operand, operator, stack) */
    CS_ERR_CAP_CACHE,     /* cache buffer too small for the pre-combined cels */
    /* scene editing and animation */
    CS_ERR_INDEX,         /* no such cel, region or contour */
    CS_ERR_COUNT,         /* point count differs from the contour's */
    CS_ERR_TRACK,         /* unknown track kind or ease */
    CS_ERR_KEY_ORDER,     /* key times not strictly increasing */
    CS_ERR_CAP_TRACKS,    /* scene store full: tracks */
    CS_ERR_CAP_KEYS,      /* scene store full: keys or key values */
    CS_ERR_CAP_ANIM,      /* animated contour has more points than CS_CFG_MAX_ANIM_POINTS */
    /* cel stream (cs_stream.c) */
    CS_ERR_STREAM_SYNC,   /* bytes outside any transaction were skipped */
    CS_ERR_STREAM_VERSION,/* unsupported format version */
    CS_ERR_STREAM_CRC,    /* transaction CRC mismatch: the data is damaged */
    CS_ERR_STREAM_TRUNCATED, /* transaction cut short */
    CS_ERR_STREAM_TOO_BIG,/* transaction longer than CS_CFG_STREAM_MAX_TXN */
    CS_ERR_STREAM_RECORD, /* malformed record: length, class, order or layout */
    CS_ERR_GROUP,         /* cel parent makes a cycle or a chain deeper than CS_CFG_MAX_GROUP_DEPTH */
    CS_ERR_STREAM_GAP,    /* bytes lost on the link (receive overrun) */
    CS_ERR_COUNT_
} cs_status;

/* A short English description of a status ("weight not > 0"). Never NULL. */
const char *cs_status_str(cs_status status);

/* Where a failure happened, -1 where an index does not apply; `item` is a
 * point, or a knot interval for CS_ERR_INTERVAL / CS_ERR_ZERO_RUN. */
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

/* A beta-model paint, linear light 0..1: it maps light L from behind to E + T*L,
 * E = beta*pigment*F + (1-beta)*medium*B, T = (1-beta)*medium. */
typedef struct cs_paint {
    float pigment[3];
    float medium[3];
    float beta;
} cs_paint;

/* Functional paints: a paint field as a gradient or colour map of position in
 * the cel's canvas units; values linear light 0..1 (beta: value[0]). */
typedef enum cs_paint_field { CS_FIELD_PIGMENT = 0, CS_FIELD_MEDIUM = 1, CS_FIELD_BETA = 2 }
    cs_paint_field;

typedef enum cs_func_kind {
    CS_FUNC_LINEAR = 1, /* geom: x0 y0 x1 y1; t = 0 at (x0,y0), 1 at (x1,y1) */
    CS_FUNC_RADIAL = 2, /* geom: cx cy r fx fy; t = 0 at focal (fx,fy), 1 on the circle */
    CS_FUNC_MAP = 3     /* geom: ox oy ux uy vx vy; grid of map_cols x rows values */
} cs_func_kind;

typedef enum cs_spread {
    CS_SPREAD_PAD = 0,     /* t clamped to [0,1] */
    CS_SPREAD_REFLECT = 1, /* 0..1..0..1 */
    CS_SPREAD_REPEAT = 2   /* 0..1 0..1 */
} cs_spread;

typedef struct cs_stop {
    float offset;   /* 0..1, non-decreasing (ignored by CS_FUNC_MAP) */
    float value[3]; /* linear light 0..1 */
} cs_stop;

/* LINEAR, RADIAL: stops (1..CS_CFG_MAX_STOPS) interpolated at t. MAP: stops
 * [row * map_cols + col] on the grid o + u*col/(cols-1) + v*row/(rows-1),
 * bilinear between nodes (docs/API.md). Spread applies to t (MAP: both axes). */
typedef struct cs_paint_func {
    uint8_t kind;       /* cs_func_kind */
    uint8_t spread;     /* cs_spread */
    uint8_t stop_count;
    uint8_t map_cols;   /* CS_FUNC_MAP only */
    float geom[6];
    cs_stop stops[CS_CFG_MAX_STOPS];
} cs_paint_func;

/* CSG programs are RPN: a token n >= 0 pushes "inside operand n" (the fill
 * rule on its contours' winding); an operator pops b, a and pushes a op b. */
enum {
    CS_CSG_UNION = -1,      /* a or b */
    CS_CSG_INTERSECT = -2,  /* a and b */
    CS_CSG_DIFFERENCE = -3, /* a and not b */
    CS_CSG_XOR = -4         /* a xor b */
};

/* An affine map x' = a x + c y + e, y' = b x + d y + f (SVG order a b c d e f). */
typedef struct cs_affine {
    float a, b, c, d, e, f;
} cs_affine;

/* No parent (cs_cel.parent): the cel is in no group. */
#define CS_NO_PARENT 0xFFu

/*
 * What a keyframe track animates (its target: a cel, region or contour index
 * over the whole store, 0 for the stack), and the floats of one key:
 *   TRANSFORM     a b c d e f (6)          CEL_LIGHTS, STACK_LIGHTS  front[3] back[3] (6)
 *   PAINT         pigment[3] medium[3] beta (7)   BACKGROUND  rgb[3] (3)
 *   POINTS        x y w per point (3 * points)
 *   TRS           px py ax ay sx sy rot skew skew_axis opacity (10): the
 *                 transform by its parts, so a turn keeps its size (docs/API.md)
 */
typedef enum cs_track_kind {
    CS_TRACK_TRANSFORM = 0, CS_TRACK_CEL_LIGHTS = 1, CS_TRACK_PAINT = 2, CS_TRACK_POINTS = 3,
    CS_TRACK_STACK_LIGHTS = 4, CS_TRACK_BACKGROUND = 5, CS_TRACK_TRS = 6, CS_TRACK_KIND_COUNT_
} cs_track_kind;

/* Between keys, s = (t - t0) / (t1 - t0): linear s, smooth 3s^2 - 2s^3, hold the
 * earlier key; CUBIC: each key's values follow x1 y1 x2 y2, the CSS / Lottie
 * cubic Bezier to the next key (docs/API.md). Values hold outside the keys. */
typedef enum cs_ease {
    CS_EASE_LINEAR = 0, CS_EASE_SMOOTH = 1, CS_EASE_HOLD = 2, CS_EASE_CUBIC = 3, CS_EASE_COUNT_
} cs_ease;
/* Floats of easing before each key's values on a CS_EASE_CUBIC track. */
#define CS_EASE_CUBIC_FLOATS 4

/* ------------------------------------------------------ building a scene */
/* Cel 0 is front-most, and within a cel region 0. A rejected call leaves the
 * scene exactly as it was. */

/* Empties the scene and sets its canvas. Lights default to front 1, back 0. */
cs_status cs_scene_init(cs_scene *scene, float canvas_w, float canvas_h);
/* An opaque card lit by the stack front light stands behind every cel. */
cs_status cs_scene_set_background(cs_scene *scene, const float rgb_linear[3]);
cs_status cs_scene_set_lights(cs_scene *scene, const float front[3], const float back[3]);
/* Appends a cel behind the others. `front` NULL: the stack's; `back` NULL: black. */
cs_status cs_scene_add_cel(cs_scene *scene, const cs_affine *transform, const float front[3],
                           const float back[3], cs_error *err);
/* Appends a region to the last cel, behind its earlier regions. */
cs_status cs_scene_add_region(cs_scene *scene, cs_fill_rule rule, const cs_paint *paint,
                              cs_error *err);
/* Appends a closed periodic NURBS of `degree` (1..3) to the last region; `intervals`:
 * `count` knot intervals, NULL for all ones; at most degree-1 zeros in a row. */
cs_status cs_scene_add_contour(cs_scene *scene, int degree, int count, const cs_point *points,
                               const float *intervals, cs_error *err);
/* Makes `field` of the last region's paint the function `fn` (copied; again:
 * replaced). Bad stops or degenerate geometry: CS_ERR_FUNC. */
cs_status cs_scene_set_region_func(cs_scene *scene, cs_paint_field field, const cs_paint_func *fn,
                                   cs_error *err);
/* Gives the last region a CSG program of `len` (1..CS_CFG_MAX_CSG) tokens that
 * leaves one value on the stack; err->item names a bad token. */
cs_status cs_scene_set_region_csg(cs_scene *scene, const int *rpn, int len, cs_error *err);
/* Puts the last contour into CSG operand `operand` (default 0). */
cs_status cs_scene_set_contour_operand(cs_scene *scene, int operand, cs_error *err);

/* ------------------------------------------------------------ animation */

/* Adds a track with no keys yet for an existing target, replacing one of the
 * same kind and target; cs_scene_add_key appends its keys. */
cs_status cs_scene_add_track(cs_scene *scene, cs_track_kind kind, uint32_t target, cs_ease ease,
                             cs_error *err);
/* Appends a key to the track added last: cs_scene_track_width floats, checked
 * as static values are; times strictly increasing (err->item: the key). */
cs_status cs_scene_add_key(cs_scene *scene, float time, const float *values, cs_error *err);
/* Floats per key of a track of `kind` on `target`, or 0 if there cannot be one. */
uint32_t cs_scene_track_width(const cs_scene *scene, cs_track_kind kind, uint32_t target);
/* Removes the track of `kind` on `target`, if there is one (no track is not an error). */
cs_status cs_scene_remove_track(cs_scene *scene, cs_track_kind kind, uint32_t target,
                                cs_error *err);

/* ------------------------------------------------------------- editing */
/* Changes to a built scene (what stream patches do), validated as the builder
 * calls are. Regions and contours are indexed over the whole scene. */
cs_status cs_scene_set_canvas(cs_scene *scene, float canvas_w, float canvas_h);
cs_status cs_scene_clear_background(cs_scene *scene);
cs_status cs_scene_set_transform(cs_scene *scene, uint32_t cel, const cs_affine *transform,
                                 cs_error *err);
/* `front` NULL: the cel follows the stack front light; `back` NULL: black. */
cs_status cs_scene_set_cel_lights(cs_scene *scene, uint32_t cel, const float front[3],
                                  const float back[3], cs_error *err);
cs_status cs_scene_set_paint(cs_scene *scene, uint32_t region, cs_fill_rule rule,
                             const cs_paint *paint, cs_error *err);
/* New points for a contour of the same count (`intervals` NULL: kept); they
 * may be the store's own arrays. */
cs_status cs_scene_set_points(cs_scene *scene, uint32_t contour, int count,
                              const cs_point *points, const float *intervals, cs_error *err);
/* Removes a cel with its regions, contours, points and tracks; later ones move down. */
cs_status cs_scene_remove_cel(cs_scene *scene, uint32_t cel, cs_error *err);
/* Cel groups: cel `cel` moves and fades with cel `parent` (CS_NO_PARENT: none);
 * a cycle or a chain deeper than CS_CFG_MAX_GROUP_DEPTH is CS_ERR_GROUP. */
cs_status cs_scene_set_cel_parent(cs_scene *scene, uint32_t cel, uint32_t parent, cs_error *err);
/* Moves cel `from` to stack position `to` (0 = front-most); others keep their order. */
cs_status cs_scene_move_cel(cs_scene *scene, uint32_t from, uint32_t to, cs_error *err);
/* Copies the used part of `src` into `dst` (no library calls; O(scene size)). */
void cs_scene_copy(cs_scene *dst, const cs_scene *src);

/* --------------------------------------------------------------- render */

typedef enum cs_aa_mode {
    CS_AA_NONE = 0,    /* one sample per pixel, at its centre */
    CS_AA_SUBSCAN = 1, /* N sub-scanlines, exact horizontal coverage */
    CS_AA_EXACT = 2    /* exact area of the pixel square */
} cs_aa_mode;

typedef enum cs_blend {
    CS_BLEND_LINEAR = 0, /* composite in linear light (the beta model's own space) */
    CS_BLEND_SRGB = 1,   /* composite sRGB-encoded values, as SVG renderers do */
    CS_BLEND_SCENE = 2   /* as the scene asks (cs_scene_set_blend): cs_render_defaults' choice */
} cs_blend;

/* The blending space the scene asks for: CS_BLEND_LINEAR (the default) or CS_BLEND_SRGB. */
cs_status cs_scene_set_blend(cs_scene *scene, cs_blend blend);
/* The wall-clock instant (ns since 1970 UTC) of animation time 0, 0 for none:
 * for boards that share a clock; the renderer never reads it. */
cs_status cs_scene_set_epoch(cs_scene *scene, uint64_t epoch_ns);

typedef struct cs_render_opts {
    int width, height;  /* output size in pixels: the whole wall when a viewport is set */
    cs_aa_mode aa;
    int subscanlines;   /* for CS_AA_SUBSCAN: 1..CS_CFG_MAX_SUBSCANLINES */
    float time;         /* seconds, for animation */
    cs_blend blend;     /* zero (linear) unless asked */
    bool no_early_out;  /* true: composite even where the stack is opaque (same bits, slower) */
    bool no_grey;       /* true: no grey-transmittance path (same bits, slower) */
    /* The viewport: only [view_x, +view_w) x [view_y, +view_h) of the output is
     * rendered, with the whole render's bits (docs/API.md); lines are view_w
     * wide and count from view_y. view_w = view_h = 0: the whole output. */
    int view_x, view_y, view_w, view_h;
} cs_render_opts;

/* Options with every field set (16 sub-scanlines, time 0, linear blending):
 * start from these, so that fields added later get their defaults. */
cs_render_opts cs_render_defaults(int width, int height);
/* A cel range pre-combined into runs of (E, T) maps per line, in a caller's
 * buffer (cs_cache_build). Fields are read-only for the caller. */
typedef struct cs_cache_run cs_cache_run; /* one run (celscan_private.h) */
typedef struct cs_cache {
    cs_status status;       /* CS_OK once built and usable */
    size_t bytes_used;      /* of the buffer */
    size_t bytes_needed;    /* what the build needed (also when it did not fit) */
    uint32_t cel_first, cel_count, run_count;
    cs_render_opts opts;    /* the cache is valid for these (time aside) */
    const uint32_t *line_first; /* height + 1 run indices */
    const cs_cache_run *runs;
    bool grey;              /* every run's T is grey (the same on all channels) */
} cs_cache;

/* Prepares a frame: samples every track at opts->time, converts the contours
 * to device-space segments and y-monotone pieces. `err`: which contour. */
cs_status cs_frame_begin(cs_renderer *r, cs_workspace *ws, const cs_scene *scene,
                         const cs_render_opts *opts, cs_error *err);
/* Whether `scene` renders with `opts`: trial frames in r and ws at opts->time
 * and its first and last key time, before a commit is swapped in. */
cs_status cs_scene_check_render(cs_renderer *r, cs_workspace *ws, const cs_scene *scene,
                                const cs_render_opts *opts, cs_error *err);
/* As cs_frame_begin, with the cached cels' runs composited in their place
 * (NULL: none). A cache built for other options is CS_ERR_STATE. */
cs_status cs_frame_begin_cached(cs_renderer *r, cs_workspace *ws, const cs_scene *scene,
                                const cs_render_opts *opts, const cs_cache *cache,
                                cs_error *err);
/* Makes `r` a renderer of the frame `prepared` holds, with its own workspace
 * for the lines: threads render bands of one frame with one renderer's bytes. */
cs_status cs_frame_share(cs_renderer *r, cs_workspace *ws, const cs_renderer *prepared);
/* A frame prepared in parts on several threads: cs_frame_begin_part prepares
 * cels [cel_begin, cel_end) as cs_frame_begin would, each part in its own
 * renderer and workspace; cs_frame_join appends parts[0 .. n) (cels following
 * on to the last one) to r (cels from 0), which then holds cs_frame_begin's
 * frame bit for bit. CS_ERR_CAP_*: the whole overflows; cs_frame_begin says where. */
#define CS_FRAME_MAX_PARTS 128
cs_status cs_frame_begin_part(cs_renderer *r, cs_workspace *ws, const cs_scene *scene,
                              const cs_render_opts *opts, uint32_t cel_begin, uint32_t cel_end,
                              cs_error *err);
cs_status cs_frame_join(cs_renderer *r, const cs_renderer *const *parts, int n);
/* Renders cels [cel_first, +cel_count) alone into runs in `buffer` (ws: scratch).
 * Too small: CS_ERR_CAP_CACHE, with cache->bytes_needed the size that fits. */
cs_status cs_cache_build(cs_cache *cache, void *buffer, size_t size, cs_workspace *ws,
                         const cs_scene *scene, const cs_render_opts *opts, uint32_t cel_first,
                         uint32_t cel_count, cs_error *err);
/* Renders line y (0 = top, increasing; skips allowed) into 3*width linear floats.
 * A capacity overflow leaves the region out and is kept for cs_frame_error. */
cs_status cs_render_line(cs_renderer *r, int y, float *rgb_linear);
/* The frame's first capacity error (CS_OK if none): cel, region, item = line. */
cs_error cs_frame_error(const cs_renderer *r);
/* Where finished lines go: the seam the display HAL plugs into. */
typedef cs_status (*cs_line_sink)(void *user, int y, const float *rgb_linear, int width);
/* Renders every line into `line` (3*width floats) for `sink`; stops at the sink's
 * first error, else returns the frame's capacity error, if any. */
cs_status cs_render_frame(cs_renderer *r, float *line, cs_line_sink sink, void *user);

/* ---------------------------------------------------------- pixel output */

typedef enum cs_pixfmt {
    CS_PIX_RGB888_SRGB = 0,  /* 3 bytes per pixel, sRGB-encoded */
    CS_PIX_RGB565_SRGB = 1,  /* 2 bytes per pixel, little-endian, sRGB-encoded */
    CS_PIX_RGB16_LINEAR = 2, /* 6 bytes per pixel, big-endian 16-bit linear (PNG order) */
    CS_PIX_RGB888_LINEAR = 3,/* 3 bytes per pixel, linear */
    CS_PIX_RGB444_SRGB = 4,  /* 2 bytes per pixel, little-endian 0x0RGB, sRGB-encoded */
    CS_PIX_RGB332_SRGB = 5   /* 1 byte per pixel, RRRGGGBB, sRGB-encoded */
} cs_pixfmt;

/* The pixel format of the firmware panels; `celsim --crc` hashes frames in it. */
#define CS_PANEL_PIXFMT CS_PIX_RGB565_SRGB

size_t cs_pixfmt_bytes_per_pixel(cs_pixfmt fmt);
/* Converts a line of linear floats (clamped to 0..1) to `fmt`; `out` may be
 * `rgb_linear` itself (in place). */
void cs_pixfmt_convert(cs_pixfmt fmt, const float *rgb_linear, int width, uint8_t *out);
/* As cs_pixfmt_convert, with 8x8 Bayer dithering for line y (no state). */
void cs_pixfmt_convert_dither(cs_pixfmt fmt, const float *rgb_linear, int width, int y,
                              uint8_t *out);
/* Renders line y as runs, read with cs_line_pixels or cs_line_run until the
 * next line; ordering and errors as cs_render_line. */
cs_status cs_render_line_runs(cs_renderer *r, int y);
/* The rendered line in `fmt`: cs_pixfmt_convert's bytes, converted once per run. */
void cs_line_pixels(const cs_renderer *r, cs_pixfmt fmt, uint8_t *out);
/* As cs_line_pixels, into workspace memory idle between lines; valid until the next. */
const uint8_t *cs_line_pixels_scratch(cs_renderer *r, cs_pixfmt fmt);
/* cs_render_line_runs, then cs_line_pixels (the runs it leaves hold the
 * same pixels; equal neighbours may stay apart). */
cs_status cs_render_line_px(cs_renderer *r, int y, cs_pixfmt fmt, uint8_t *out);
/* The run starting at pixel x: its linear colour, and the pixel after it
 * returned (for (x = 0; x < w; x = next) ...). */
int cs_line_run(const cs_renderer *r, int x, float rgb_linear[3]);
/* sRGB encoding of one linear value in 0..1, as a 16-bit code (0..65535). */
uint16_t cs_srgb_encode16(float linear);
/* Linear light of an sRGB-encoded value in 0..1 (the inverse of the above). */
float cs_srgb_decode(float encoded);

/* ------------------------------------------------------------ cel stream */
/* The cel stream decoder (docs/STREAM.md): bytes in any chunking into the back
 * store while the front one is shown; a valid transaction ends in
 * CS_STREAM_COMMIT (then cs_stream_swap), a bad one is dropped and reported. */
typedef struct cs_stream_error {
    cs_status status;    /* CS_ERR_STREAM_* or the scene validation status */
    uint64_t offset;     /* stream offset of the dropped transaction (or skipped bytes) */
    uint64_t at;         /* stream offset of the fault: record, CRC field, cut */
    cs_error where;      /* scene location for validation failures, else -1s */
    const char *what;    /* a short English explanation; never NULL */
} cs_stream_error;

typedef enum cs_stream_event {
    CS_STREAM_MORE = 0,   /* every byte given was consumed; feed more */
    CS_STREAM_COMMIT = 1, /* a new scene is ready: cs_stream_swap between frames */
    CS_STREAM_ERROR = 2   /* something was dropped: see cs_stream_last_error */
} cs_stream_event;

/* Starts a decoder on two stores; `front_valid`: `front` is a scene on display
 * that patches may change. `back` is scratch until a commit. */
cs_status cs_stream_init(cs_stream *s, cs_scene *front, bool front_valid, cs_scene *back);
/* Consumes bytes until they run out or an event (*used: how many). After an
 * ERROR call again with the rest, even if empty: a second error may wait. */
cs_stream_event cs_stream_feed(cs_stream *s, const uint8_t *data, size_t len, size_t *used);
/* End of input: reports a transaction cut short or trailing bytes, then resets to hunting. */
cs_stream_event cs_stream_finish(cs_stream *s);
/* The link lost bytes here (a UART overrun): an open transaction is dropped
 * (CS_ERR_STREAM_GAP) and nothing is pieced together across the gap. Call
 * until CS_STREAM_MORE. */
cs_stream_event cs_stream_gap(cs_stream *s);
/* Makes the ready commit the front scene (between frames). CS_ERR_STATE if none is ready. */
cs_status cs_stream_swap(cs_stream *s);
/* Drops the ready commit instead (e.g. cs_scene_check_render failed): reported
 * as the last error with `what` (which must outlive the next feed). */
cs_status cs_stream_refuse(cs_stream *s, cs_status status, const char *what, const cs_error *where);
/* Whether the back store is in use (a transaction open or a commit waiting);
 * while not, a board short of RAM may lend it out. */
bool cs_stream_busy(const cs_stream *s);
/* The scene on display: the last swapped-in commit, or NULL if there is none. */
const cs_scene *cs_stream_scene(const cs_stream *s);
/* The error behind the last CS_STREAM_ERROR. */
const cs_stream_error *cs_stream_last_error(const cs_stream *s);
/* A decoder error as the one line every program prints (docs/API.md), offsets
 * plus `base`; cut to fit len bytes, NUL included; returns the length needed. */
size_t cs_stream_error_text(const cs_stream_error *e, uint64_t base, char *buf, size_t len);
/* CRC-32 (IEEE 802.3, reflected, as zlib) of frames and streams. Start with crc = 0. */
uint32_t cs_crc32(uint32_t crc, const void *data, size_t len);

/* --------------------------------------------------------------- damage */

/* A window of the output: columns [x0, x1) of rows [y0, y1); empty when x0 >= x1. */
typedef struct cs_rect {
    int x0, y0, x1, y1;
} cs_rect;

/* What the last frame showed, cel by cel (layout in celscan_private.h). */
typedef struct cs_damage cs_damage;
void cs_damage_reset(cs_damage *d); /* the next cs_frame_damage reports everything */

/* The window of the output that can differ from the frame last passed with
 * `d`: rendered as the viewport, it gives the whole render's bits there. An
 * empty window: nothing changed. docs/API.md has the rules. */
cs_status cs_frame_damage(cs_damage *d, const cs_scene *scene, const cs_render_opts *opts,
                          cs_rect *window);

#ifdef __cplusplus
}
#endif

#endif /* CELSCAN_H */
