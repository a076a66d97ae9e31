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
 *   - cs_scene      the scene store (what a commit makes visible), with its
 *                   keyframe tracks; a board keeps two for the stream,
 *   - cs_workspace  per-render scratch (segment arena, line buffers),
 *   - cs_renderer   the small context tying them together for one frame,
 *   - cs_stream     the cel stream decoder's state (docs/STREAM.md).
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

/*
 * Functional paints. Any of a paint's three fields may be a function of
 * position instead of a constant: a linear or radial gradient, or a small
 * bilinear colour map (the paper's "colouring mapped from a colour space").
 * Geometry is in the cel's own canvas units, so it moves with the cel
 * transform. Values are linear light in 0..1; a beta function uses value[0].
 */
typedef enum cs_paint_field {
    CS_FIELD_PIGMENT = 0,
    CS_FIELD_MEDIUM = 1,
    CS_FIELD_BETA = 2
} cs_paint_field;

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

/*
 * LINEAR and RADIAL interpolate between stops (1..CS_CFG_MAX_STOPS) at t.
 * MAP places the unit square at origin o with edges u and v (canvas units);
 * stops[row * map_cols + col] is the value at o + u*col/(cols-1) +
 * v*row/(rows-1), rows = stop_count / map_cols, and between nodes values are
 * interpolated bilinearly. Spread applies to t (MAP: to both axes).
 */
typedef struct cs_paint_func {
    uint8_t kind;       /* cs_func_kind */
    uint8_t spread;     /* cs_spread */
    uint8_t stop_count;
    uint8_t map_cols;   /* CS_FUNC_MAP only */
    float geom[6];
    cs_stop stops[CS_CFG_MAX_STOPS];
} cs_paint_func;

/* A closed periodic NURBS: points[first .. first+count) of the scene. */
typedef struct cs_contour {
    uint32_t first_point;
    uint16_t point_count;
    uint8_t degree;
    uint8_t operand;   /* CSG operand it belongs to (0 unless set) */
} cs_contour;

/*
 * CSG programs are RPN: a token >= 0 pushes "inside operand n" (the region's
 * fill rule applied to the winding of the contours of operand n), a
 * negative token pops b then a and pushes the operator applied to a, b.
 */
enum {
    CS_CSG_UNION = -1,      /* a or b */
    CS_CSG_INTERSECT = -2,  /* a and b */
    CS_CSG_DIFFERENCE = -3, /* a and not b */
    CS_CSG_XOR = -4         /* a xor b */
};

typedef struct cs_region {
    uint32_t first_contour;
    uint16_t contour_count;
    uint8_t fill_rule; /* cs_fill_rule */
    uint8_t csg_len;   /* 0: one fill over all contours; else RPN length */
    cs_paint paint;
    uint16_t func[3];  /* per cs_paint_field: 0 constant, else 1 + index in scene funcs */
    uint8_t csg[CS_CFG_MAX_CSG]; /* operand n as n, operator k (-k in the API) as 0x80|k */
} cs_region;

/* An affine map x' = a x + c y + e, y' = b x + d y + f (SVG order a b c d e f). */
typedef struct cs_affine {
    float a, b, c, d, e, f;
} cs_affine;

typedef struct cs_cel {
    uint32_t first_region;
    uint16_t region_count;
    bool has_front;   /* false: the front light defaults to the stack's */
    uint8_t parent;   /* cel group: the cel whose transform and opacity apply after this
                         cel's own (cs_scene_set_cel_parent); CS_NO_PARENT: none. One byte,
                         in what was padding: cels number at most 255 */
    cs_affine transform;
    float front[3];   /* linear light multipliers */
    float back[3];    /* lights only this cel's own paint; default black */
} cs_cel;

/* No parent (cs_cel.parent): the cel is in no group. */
#define CS_NO_PARENT 0xFFu

/*
 * What a keyframe track animates, and the floats of one key (its width):
 *   CS_TRACK_TRANSFORM     a cel's transform          a b c d e f         6
 *   CS_TRACK_CEL_LIGHTS    a cel's lights             front[3] back[3]    6
 *   CS_TRACK_PAINT         a region's paint           pigment[3] medium[3] beta  7
 *   CS_TRACK_POINTS        a contour's control points x y w per point     3 * points
 *   CS_TRACK_STACK_LIGHTS  the stack's lights         front[3] back[3]    6
 *   CS_TRACK_BACKGROUND    the background card        rgb[3] (linear)     3
 *   CS_TRACK_TRS           a cel's transform as parts px py ax ay sx sy       10
 *                          rot skew skew_axis opacity
 * The target is the cel, region or contour index in the store (regions and
 * contours counted over the whole scene), or 0 for the stack-wide kinds. An
 * animated cel front light replaces the stack default, as a static one does.
 *
 * A TRS track interpolates a cel's transform by its parts, so a turn keeps
 * its size: M = T(p) R(rot) K(skew, skew_axis) S(sx, sy) T(-a), angles in
 * degrees (positive turns x towards y), K = R(axis) [1 tan(skew); 0 1]
 * R(-axis), |skew| <= 85. It replaces the cel's transform (static or
 * CS_TRACK_TRANSFORM) while it has keys. `opacity` (0..1) multiplies the
 * beta of the cel's paints (and, through cel groups, of its children's).
 */
typedef enum cs_track_kind {
    CS_TRACK_TRANSFORM = 0,
    CS_TRACK_CEL_LIGHTS = 1,
    CS_TRACK_PAINT = 2,
    CS_TRACK_POINTS = 3,
    CS_TRACK_STACK_LIGHTS = 4,
    CS_TRACK_BACKGROUND = 5,
    CS_TRACK_TRS = 6,
    CS_TRACK_KIND_COUNT_
} cs_track_kind;

/*
 * Interpolation between two keys, with s = (t - t0) / (t1 - t0) in [0,1]:
 * linear uses s, smooth uses smoothstep 3s^2 - 2s^3 (zero velocity at the
 * keys), hold keeps the earlier key's value until the next key. Before the
 * first key and after the last the value holds.
 *
 * CS_EASE_CUBIC gives every key segment its own easing: each key's values
 * are preceded by four floats x1 y1 x2 y2, the CSS / Lottie cubic Bezier
 * from (0,0) to (1,1) through (x1,y1), (x2,y2) that eases the segment from
 * that key to the next (x1, x2 in 0..1, y1, y2 in -2..3); x1 = -1 with
 * y1 = x2 = y2 = 0 makes the segment a hold. The eased s may leave 0..1
 * (overshoot) on transform, TRS and points tracks; on the others it is
 * clamped to 0..1.
 */
typedef enum cs_ease {
    CS_EASE_LINEAR = 0,
    CS_EASE_SMOOTH = 1,
    CS_EASE_HOLD = 2,
    CS_EASE_CUBIC = 3,
    CS_EASE_COUNT_
} cs_ease;
/* Floats of easing before each key's values on a CS_EASE_CUBIC track. */
#define CS_EASE_CUBIC_FLOATS 4

/* A track's keys: times key_times[first_key ..], values key_values[first_value ..]. */
typedef struct cs_track {
    uint32_t target;
    uint32_t first_key;
    uint32_t first_value;
    uint32_t width;      /* floats per key: the value's, plus CS_EASE_CUBIC_FLOATS on a
                            CS_EASE_CUBIC track */
    uint16_t key_count;
    uint8_t kind;        /* cs_track_kind */
    uint8_t ease;        /* cs_ease */
} cs_track;

/*
 * The scene store. Cels, regions, contours and points are in front-to-back
 * order: cel 0 is front-most, and within a cel region 0 is front-most.
 * Build it with cs_scene_init and the cs_scene_add_* calls; each call
 * validates its input completely before it changes the store, so a rejected
 * call leaves the scene exactly as it was.
 *
 * Tracks are kept sorted by (kind, target), at most one per pair, so the
 * renderer finds a cel's or contour's track by binary search.
 */
typedef struct cs_scene {
    float canvas_w, canvas_h;
    bool has_background;
    uint8_t blend;       /* cs_blend the scene asks for (imported SVG: sRGB); see cs_render_opts */
    uint64_t epoch_ns;   /* wall-clock time of animation time 0, ns since 1970 UTC; 0: none */
    float background[3]; /* linear light */
    float stack_front[3];
    float stack_back[3];
    uint32_t cel_count, region_count, contour_count, point_count, func_count;
    uint32_t track_count, key_count, value_count;
    uint32_t open_track; /* the track cs_scene_add_key appends to; UINT32_MAX: none */
    cs_cel cels[CS_CFG_MAX_CELS];
    cs_region regions[CS_CFG_MAX_REGIONS];
    cs_contour contours[CS_CFG_MAX_CONTOURS];
    cs_point points[CS_CFG_MAX_POINTS];
    float intervals[CS_CFG_MAX_POINTS]; /* knot interval k of each contour, parallel to points */
    cs_paint_func funcs[CS_CFG_MAX_FUNCS];
    cs_track tracks[CS_CFG_MAX_TRACKS];
    float key_times[CS_CFG_MAX_KEYS];
    float key_values[CS_CFG_MAX_KEY_VALUES];
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

/*
 * Makes field `field` of the last region's paint the function `fn` (copied
 * into the scene; setting a field again replaces its function). The
 * region's constant value for that field is then unused. Rejects stops out
 * of order or range, degenerate geometry (p0 = p1, r <= 0, focal point not
 * strictly inside the circle, a map with parallel edges) with CS_ERR_FUNC.
 */
cs_status cs_scene_set_region_func(cs_scene *scene, cs_paint_field field, const cs_paint_func *fn,
                                   cs_error *err);

/*
 * Gives the last region a CSG program of `len` (1..CS_CFG_MAX_CSG) RPN
 * tokens: operands 0..CS_CFG_MAX_OPERANDS-1 and CS_CSG_* operators. The
 * program must leave exactly one value on the stack. err->item names the
 * offending token.
 */
cs_status cs_scene_set_region_csg(cs_scene *scene, const int *rpn, int len, cs_error *err);

/* Puts the last contour into CSG operand `operand` (default 0). */
cs_status cs_scene_set_contour_operand(cs_scene *scene, int operand, cs_error *err);
/* ------------------------------------------------------------ animation */

/*
 * Adds a keyframe track for `target` (see cs_track_kind) with no keys yet;
 * cs_scene_add_key then appends its keys. A track of the same kind and
 * target already present is replaced. The target must exist; a points track
 * needs a contour of at most CS_CFG_MAX_ANIM_POINTS points. Errors name the
 * target (cel, region, contour) in `err`.
 */
cs_status cs_scene_add_track(cs_scene *scene, cs_track_kind kind, uint32_t target, cs_ease ease,
                             cs_error *err);

/*
 * Appends a key to the track added last. `values` holds the track's width
 * in floats (cs_scene_track_width; on a CS_EASE_CUBIC track preceded by
 * the key's four easing floats), checked as the static value would be:
 * finite transforms within the coordinate limit, lights >= 0, paints in
 * 0..1, points as for cs_scene_add_contour. Times are finite and strictly
 * increasing; `err->item` is the key's index on failure.
 */
cs_status cs_scene_add_key(cs_scene *scene, float time, const float *values, cs_error *err);

/* Floats per key of a track of `kind` on `target`, or 0 if there cannot be one. */
uint32_t cs_scene_track_width(const cs_scene *scene, cs_track_kind kind, uint32_t target);

/* Removes the track of `kind` on `target`, if there is one (no track is not an error). */
cs_status cs_scene_remove_track(cs_scene *scene, cs_track_kind kind, uint32_t target,
                                cs_error *err);

/* ------------------------------------------------------------- editing */
/*
 * Changes to a built scene, what the cel stream's patch records do. Each
 * validates like the builder calls and leaves the store unchanged on error.
 * Regions and contours are indexed over the whole scene.
 */
cs_status cs_scene_set_canvas(cs_scene *scene, float canvas_w, float canvas_h);
cs_status cs_scene_clear_background(cs_scene *scene);
cs_status cs_scene_set_transform(cs_scene *scene, uint32_t cel, const cs_affine *transform,
                                 cs_error *err);
/* `front` NULL: the cel follows the stack front light; `back` NULL: black. */
cs_status cs_scene_set_cel_lights(cs_scene *scene, uint32_t cel, const float front[3],
                                  const float back[3], cs_error *err);
cs_status cs_scene_set_paint(cs_scene *scene, uint32_t region, cs_fill_rule rule,
                             const cs_paint *paint, cs_error *err);
/*
 * New control points for a contour of the same point count; `intervals`
 * NULL keeps its knot intervals. `points`/`intervals` may be the store's own
 * arrays for that contour (checked in place).
 */
cs_status cs_scene_set_points(cs_scene *scene, uint32_t contour, int count,
                              const cs_point *points, const float *intervals, cs_error *err);
/*
 * Removes a cel with its regions, contours, points and every track on them;
 * later cels, regions and contours move down one index.
 */
cs_status cs_scene_remove_cel(cs_scene *scene, uint32_t cel, cs_error *err);
/*
 * Cel groups: makes cel `parent` the group of cel `cel` (CS_NO_PARENT: none).
 * The cel's device transform is then the parent's (with its parent's, and
 * so on) times its own, and its paints' beta is multiplied by the opacity
 * of every TRS track up the chain. A parent is usually a cel with no
 * regions. Refused with CS_ERR_GROUP if it would make a cycle or a chain of
 * more than CS_CFG_MAX_GROUP_DEPTH cels. Removing a cel leaves its children
 * without a parent.
 */
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

/*
 * The wall-clock instant (ns since 1970-01-01 UTC) at which the scene's
 * animation time is 0, or 0 for none. The renderer never reads it: a board
 * whose clock follows the wall clock (celfw --clock realtime) shows time
 * now - epoch, so the boards of a video wall show the same instant.
 */
cs_status cs_scene_set_epoch(cs_scene *scene, uint64_t epoch_ns);

typedef struct cs_render_opts {
    int width, height;  /* output size in pixels: the whole wall when a viewport is set */
    cs_aa_mode aa;
    int subscanlines;   /* for CS_AA_SUBSCAN: 1..CS_CFG_MAX_SUBSCANLINES */
    float time;         /* seconds, for animation */
    cs_blend blend;     /* zero (linear) unless asked */
    bool no_early_out;  /* true: composite every cel even where the stack is already
                           opaque. Bit-identical output, only slower: for tests and
                           for measuring what front-to-back skipping saves. */
    bool no_grey;       /* true: keep transmittance per channel even when every paint of
                           the frame transmits grey. Bit-identical output, only slower:
                           for tests and for measuring what the grey path saves. */
    /* The viewport: the window [view_x, view_x + view_w) x [view_y, view_y + view_h)
     * of the width x height output is all that is rendered (one board of a video
     * wall). The frame is prepared in the whole output's device coordinates, so
     * every pixel of the window comes out with the bits the whole render gives
     * it (see cs_coverage.c for the one condition, for a window narrower than the
     * output: --aa N with N a power of two);
     * lines are view_w pixels (<= CS_CFG_MAX_WIDTH) while the whole may be up to
     * CS_CFG_MAX_WALL on a side. Line y and the sink's y count from view_y.
     * The frame holds only the contours, segments and pieces that reach the
     * window's rows, so a full-width band of rows is also how a small board
     * renders a scene larger than its segment arena, band by band.
     * view_w = view_h = 0: the whole output. */
    int view_x, view_y, view_w, view_h;
} cs_render_opts;

/*
 * Options with every field set: width x height, 16 sub-scanlines, time 0,
 * linear blending, early-out on. Start from this rather than filling the
 * struct field by field, so that fields added later get their defaults.
 */
cs_render_opts cs_render_defaults(int width, int height);

/*
 * One rational polynomial segment in device space: for u in [0,1)
 * x(u) = ox + X(u)/W(u), y(u) = oy + Y(u)/W(u), with X(u) = sum x[i] u^i.
 * The origin (ox, oy) is the whole pixel at the segment's start (on the
 * curve), so the coefficients hold the segment's own extent rather than
 * its distance from the screen's corner: a float coefficient's rounding
 * then scales with the segment's size, not with where it is, which the
 * exact-area bound needs on the tallest screens (BENCHMARKS.md).
 */
typedef struct cs_segment {
    float x[4], y[4], w[4];
    int16_t ox, oy;    /* the origin, in pixels (clamped far off screen: any origin is exact) */
    uint16_t px_lo, px_hi; /* pixels [px_lo, px_hi) that x(u) over [0,1] can touch (its
                              Bezier hull widened by half a pixel), set by the frame */
    uint16_t region;   /* index into scene regions */
    uint8_t degree;
    bool rational;     /* W varies (w[1..3] not all 0): else x = X / w[0] */
} cs_segment;

/* Index of a segment or piece in the workspace (CS_CFG_INDEX_TYPE). */
typedef CS_CFG_INDEX_TYPE cs_index;

/*
 * A y-monotone piece of a segment, u in [u0, u1], y from y_top to y_bot
 * (y_top < y_bot). The end y values are shared exactly with the neighbouring
 * pieces of the contour, so a half-open test y_top <= y < y_bot gives every
 * closed contour an even number of crossings on every scanline.
 */
typedef struct cs_piece {
    float u0, u1;
    float y_top, y_bot;
    cs_index segment;
    uint16_t region;   /* copied from the segment: spares an indirection per line */
    uint8_t operand;   /* winding counter it moves: always 0 without CSG */
    int8_t dir;        /* +1 if y grows with u, -1 if it falls */
} cs_piece;

/* A crossing of a piece with a sub-scanline. Aligned to
 * CS_CFG_CROSSING_ALIGN (cs_config.h says why). */
typedef struct cs_crossing {
    _Alignas(CS_CFG_CROSSING_ALIGN) float x;
    float guess;      /* where the piece's root on the next sub-scanline is sought;
                         interpolated, x on the line's first sub-scanline */
    float a1, a2, a3; /* interpolated, x on sub-scanline k is guess + k (a1 + k (a2 + k a3));
                         a3 is NaN when not (cs_cross.c: interp_setup) */
    uint16_t piece;   /* the piece's place in its region's active list (cs_cross.c) */
    int8_t dir;
    uint8_t operand;  /* which winding counter of the region it moves (CSG) */
} cs_crossing;

/* One end of an arc within a band, for exact-area coverage (cs_exact.c):
 * the point's parameter and x, and the derivatives that place the arc's
 * inner Bezier control points without another evaluation. */
typedef struct cs_exact_end {
    float u, x;
    float dx, dy;         /* x'(u), y'(u) */
    float w, dwr;         /* W(u), and W'(u) / W(u): 0 for polynomial segments */
} cs_exact_end;

/* A piece's end at the last row boundary placed, kept for the next row
 * (cs_exact.c): y is that boundary, or -1 before any. */
typedef struct cs_exact_level {
    float y;
    cs_exact_end end;
} cs_exact_level;

/* Where one active piece is within the current band of a pixel row, for
 * exact-area coverage (cs_exact.c). */
typedef struct cs_exact_piece {
    cs_exact_end top, bot; /* the arc's ends at the band's top and bottom */
    float u_row;          /* u where the piece leaves the row (its end, or the row's bottom) */
    float dmin, dmax;     /* the arc lies within [dmin, dmax] of its chord, horizontally */
    float xmin, xmax;     /* x range of the arc's control polygon */
    float key;            /* x order within the band: x_top + x_bot */
    uint32_t piece;
    bool monotone;        /* control polygon x-monotone, so the arc is */
    bool row_arc;         /* top, bot and the bounds are those of the whole row's arc */
    bool hidden;          /* behind opaque pixels: only its height counts (cs_exact.c) */
} cs_exact_piece;

/* A contour being converted to segments one knot span at a time
 * (cs_nurbs.c). Private to the core; it lives in the workspace rather than
 * on the stack, which a 64 KiB board keeps small. */
typedef struct cs__contour_iter {
    const cs_point *points;
    const float *intervals;
    const cs_affine *to_device;
    float ymin, ymax;       /* the control points' device y range */
    int count, degree, j;   /* j: the next knot span to look at */
    uint16_t region;
    bool have_basis;        /* basis holds the segment matrix for knots `last` */
    float basis[4][4], last[8];
} cs__contour_iter;

/*
 * A prepared frame: what cs_frame_begin computes once and every line only
 * reads. Contents are private to the core.
 */
typedef struct cs_frame_data {
    cs_segment segments[CS_CFG_MAX_SEGMENTS];
    cs_piece pieces[CS_CFG_MAX_PIECES];
    cs_index order[CS_CFG_MAX_PIECES];   /* pieces sorted by y_top */
    uint16_t region_cel[CS_CFG_MAX_REGIONS];
    float region_E[CS_CFG_MAX_REGIONS][3];
    float region_T[CS_CFG_MAX_REGIONS][3];
    float func_xf[CS_CFG_MAX_FUNCS][6];   /* device pixel -> function space, per frame */
    float cel_opacity[CS_CFG_MAX_CELS];   /* TRS opacity up the group chain, per frame */
    cs__contour_iter contour;             /* the contour being converted (preparation only) */
} cs_frame_data;

/*
 * Per-render scratch memory. Contents are private to the core.
 */
typedef struct cs_workspace {
    cs_frame_data frame; /* the frame prepared in this workspace */
    /* The frame the lines read: this workspace's own (cs_frame_begin), or
     * another's (cs_frame_share), which is then only read. */
    const cs_segment *segments;
    const cs_piece *pieces;
    const cs_index *order;
    const uint16_t *region_cel;
    const float (*region_E)[3];
    const float (*region_T)[3];
    const float (*func_xf)[6];
    const float *cel_opacity;
    cs_index active[CS_CFG_MAX_PIECES];  /* active pieces of the line, in piece order */
    cs_index scratch[CS_CFG_MAX_PIECES]; /* sort scratch */
    cs_crossing crossings[CS_CFG_MAX_CROSSINGS];
#if CS_CFG_EXACT
    cs_exact_piece exact[CS_CFG_MAX_CROSSINGS]; /* a region's pieces on one row (exact AA) */
    uint32_t exact_order[CS_CFG_MAX_CROSSINGS];  /* those in the band, in x order */
    cs_exact_level level_memo[CS_CFG_MAX_PIECES]; /* per piece: its last row bottom */
#endif
    float area[CS_CFG_MAX_WIDTH + 2];     /* partial coverage of the region, per pixel */
    float cover[CS_CFG_MAX_WIDTH + 2];    /* coverage deltas, prefix-summed */
    uint32_t touched[(CS_CFG_MAX_WIDTH + 2 + 31) / 32]; /* area/cover entries written */
    /* The line as runs (cs_runs.h): run_end and the values below are read
     * at run starts only, which run_starts marks. */
    uint32_t run_starts[(CS_CFG_MAX_WIDTH + 32) / 32];
    uint32_t opaque_bits[(CS_CFG_MAX_WIDTH + 32) / 32]; /* pixels whose stack is opaque */
    uint16_t run_end[CS_CFG_MAX_WIDTH + 1]; /* x fits 16 bits: see below */
    float used[CS_CFG_MAX_WIDTH];         /* coverage claimed in the cel so far */
    float cel_E[CS_CFG_MAX_WIDTH * 3];
    float cel_A[CS_CFG_MAX_WIDTH * 3];    /* 1 - T of the cel */
    float stack_E[CS_CFG_MAX_WIDTH * 3];  /* the stack: emitted light, then the pixel */
    float stack_T[CS_CFG_MAX_WIDTH * 3];
    cs_point anim_points[CS_CFG_MAX_ANIM_POINTS]; /* one animated contour at frame time */
} cs_workspace;

/* A cel's parent is one byte (cs_cel.parent), CS_NO_PARENT excluded. */
typedef char cs__cels_fit_parent_[CS_CFG_MAX_CELS < CS_NO_PARENT ? 1 : -1];

/* Pixel positions are kept in 16 bits (run_end). */
typedef char cs__width_fits_[CS_CFG_MAX_WIDTH < 65535 ? 1 : -1];

/* Indices must be able to count every piece and segment. */
typedef char cs__index_fits_[(CS_CFG_MAX_PIECES <= (cs_index)-1 &&
                              CS_CFG_MAX_SEGMENTS <= (cs_index)-1) ? 1 : -1];
/* A region's active pieces are numbered in 16 bits (cs_crossing.piece). */
typedef char cs__piece_fits_[CS_CFG_MAX_PIECES <= 65536 ? 1 : -1];
/*
 * A cel range pre-combined into run-length (E, T) maps per line (the
 * paper's "static background rendered once"). Lives in a caller's buffer;
 * see cs_cache_build. Fields are read-only for the caller.
 */
typedef struct cs_cache_run {
    uint16_t x, len;        /* pixels [x, x+len) share the map */
    float E[3], T[3];
} cs_cache_run;

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
    uint32_t cel_begin, cel_end;  /* cels rendered live: [begin, end) minus the cache's */
    const cs_cache *cache;        /* pre-combined cels composited in their place, or NULL */
    uint32_t opaque_px;           /* pixels of the line whose stack is opaque */
    int32_t vx, vy, vw, vh;       /* the window rendered (the whole output without a viewport);
                                     line pixel i is device column vx + i */
    float clip_lo, clip_hi;       /* crossings are clamped to these device x (see cs_cross.c) */
    bool record;                  /* the early-out is on: opaque runs are skipped */
    bool grey;                    /* every T of the frame is grey: kept in channel 0 alone */
    bool rows_only;               /* a viewport: the frame keeps only the pieces, segments and
                                     contours its rows need (cs_frame.c) */
} cs_renderer;

/*
 * Prepares a frame: evaluates the scene at opts->time (every track sampled,
 * see cs_track_kind and cs_ease), transforms control
 * points to device space, converts every contour to segments and splits them
 * into y-monotone pieces. On failure `err` says which contour.
 */
cs_status cs_frame_begin(cs_renderer *r, cs_workspace *ws, const cs_scene *scene,
                         const cs_render_opts *opts, cs_error *err);

/*
 * Whether `scene` can be rendered with `opts` (its canvas scaled to the
 * output size within the coordinate limit, its segments and pieces within
 * the workspace's capacities): prepares trial frames in r and ws (scratch,
 * as for cs_frame_begin) at opts->time and, if the scene has keys, at its
 * earliest and latest key time. Meant for a commit: a board checks the
 * scene a stream brings before it swaps it in, so a scene that cannot
 * render is refused once instead of failing frame after frame. Time
 * between keys is not sampled (at most three trials, whatever the keys).
 */
cs_status cs_scene_check_render(cs_renderer *r, cs_workspace *ws, const cs_scene *scene,
                                const cs_render_opts *opts, cs_error *err);

/*
 * As cs_frame_begin, but cels [cache->cel_first, +cel_count) are not
 * scan-converted: their pre-combined lines from `cache` are composited in
 * their place in the stack. `cache` may be NULL (render every cel). A cache
 * that was not built successfully, or for other width, height, AA or blend
 * options, is refused with CS_ERR_STATE: the caller falls back to NULL. The
 * cache does not know about animation: it is the caller's promise that the
 * cached cels (and the lights they use) did not change since the build.
 * A frame with a viewport takes no cache (CS_ERR_STATE).
 */
cs_status cs_frame_begin_cached(cs_renderer *r, cs_workspace *ws, const cs_scene *scene,
                                const cs_render_opts *opts, const cs_cache *cache,
                                cs_error *err);

/*
 * Makes `r` a renderer of the frame `prepared` holds (set up by
 * cs_frame_begin or cs_frame_begin_cached), with its own workspace `ws` for
 * the lines: the frame's segments, pieces and paints stay in the prepared
 * renderer's workspace and are only read, so several renderers, each with
 * its workspace, can render lines of one frame at once (a band of lines
 * each, on threads), and give the bytes one renderer would. `r` starts at
 * the top of the frame with no capacity error; any lines may follow, in
 * increasing order. The prepared workspace must not begin another frame
 * while `r` renders. CS_ERR_ARG for a null pointer or a workspace already
 * the prepared one's; CS_ERR_STATE if `prepared` is itself a share.
 */
cs_status cs_frame_share(cs_renderer *r, cs_workspace *ws, const cs_renderer *prepared);

/*
 * Renders cels [cel_first, cel_first+cel_count) of `scene` alone at `opts`
 * and stores each line as runs of (E, T) maps in `buffer` (any alignment;
 * `size` bytes). Uses `ws` as scratch, so not while a frame is being
 * rendered with it. If the runs do not fit, returns CS_ERR_CAP_CACHE with
 * cache->bytes_needed set to the size that would have fitted, and the cache
 * is unusable (cache->status != CS_OK): render those cels directly.
 * Options with a viewport are refused (CS_ERR_ARG).
 */
cs_status cs_cache_build(cs_cache *cache, void *buffer, size_t size, cs_workspace *ws,
                         const cs_scene *scene, const cs_render_opts *opts, uint32_t cel_first,
                         uint32_t cel_count, cs_error *err);

/*
 * Renders line y (0 = top) into rgb_linear (3*width floats, linear light).
 * The line is built as runs of equal pixels in the workspace and expanded
 * into rgb_linear at the end; a display is better served by
 * cs_render_line_runs and cs_line_pixels, which convert once per run.
 * Lines must be requested in increasing order (the active list only moves
 * forward); skipping lines is allowed. A capacity overflow on the line is
 * recorded in r->sticky and the line is still produced, with the overflowing
 * region left out of that sub-scanline.
 */
cs_status cs_render_line(cs_renderer *r, int y, float *rgb_linear);

/*
 * The first capacity error met while rendering lines of this frame (status
 * CS_OK if none): which cel and region overflowed, with item = the line.
 */
cs_error cs_frame_error(const cs_renderer *r);

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
    CS_PIX_RGB888_LINEAR = 3,/* 3 bytes per pixel, linear */
    CS_PIX_RGB444_SRGB = 4,  /* 2 bytes per pixel, little-endian 0x0RGB, sRGB-encoded */
    CS_PIX_RGB332_SRGB = 5   /* 1 byte per pixel, RRRGGGBB, sRGB-encoded */
} cs_pixfmt;

/* The pixel format of the firmware panels; `celsim --crc` hashes frames in it. */
#define CS_PANEL_PIXFMT CS_PIX_RGB565_SRGB

size_t cs_pixfmt_bytes_per_pixel(cs_pixfmt fmt);

/*
 * Converts one line of linear RGB floats (clamped to 0..1) to `fmt`. `out`
 * may be the memory of `rgb_linear` itself (every format is smaller than
 * the floats, and each pixel is read before its bytes are written), so a
 * board can convert in place and keep no separate line of panel pixels.
 */
void cs_pixfmt_convert(cs_pixfmt fmt, const float *rgb_linear, int width, uint8_t *out);

/*
 * As cs_pixfmt_convert (in place too), with ordered dithering for line y: an 8x8 Bayer
 * threshold by pixel position spreads the rounding of each channel so that
 * smooth gradients do not band on low-depth panels. Deterministic (no
 * state); a value exactly on an output level is never disturbed. For
 * CS_PIX_RGB16_LINEAR it is the same as cs_pixfmt_convert.
 */
void cs_pixfmt_convert_dither(cs_pixfmt fmt, const float *rgb_linear, int width, int y,
                              uint8_t *out);

/*
 * Renders line y into the renderer's own run list, without writing pixels:
 * the line is then read with cs_line_pixels or cs_line_run until the next
 * line is rendered. Same ordering rules and errors as cs_render_line, which
 * is this followed by expanding the runs into floats.
 */
cs_status cs_render_line_runs(cs_renderer *r, int y);

/* The rendered line in pixel format `fmt` (width * bytes-per-pixel bytes
 * of `out`): the bytes cs_pixfmt_convert would make of cs_render_line's
 * floats, converted once per run of equal pixels. */
void cs_line_pixels(const cs_renderer *r, cs_pixfmt fmt, uint8_t *out);

/*
 * As cs_line_pixels, into memory of the workspace that is idle between
 * lines (the cel accumulators), so that a board needs no line buffer of its
 * own. The pointer is valid until the next line is rendered.
 */
const uint8_t *cs_line_pixels_scratch(cs_renderer *r, cs_pixfmt fmt);

/* cs_render_line_runs, then cs_line_pixels. */
cs_status cs_render_line_px(cs_renderer *r, int y, cs_pixfmt fmt, uint8_t *out);

/*
 * The run of the rendered line that starts at pixel x: its colour (linear
 * light) in rgb_linear, and the pixel after it as the return value. Runs
 * are walked from x = 0 to the width: for (x = 0; x < w; x = next) ...
 */
int cs_line_run(const cs_renderer *r, int x, float rgb_linear[3]);

/* sRGB encoding of one linear value in 0..1, as a 16-bit code (0..65535). */
uint16_t cs_srgb_encode16(float linear);

/* Linear light of an sRGB-encoded value in 0..1 (the inverse of the above). */
float cs_srgb_decode(float encoded);
/* ------------------------------------------------------------ cel stream */
/*
 * The streaming decoder of the cel stream (docs/STREAM.md). It takes bytes
 * in any chunking, with fixed memory (this struct and two scene stores), and
 * builds the next scene in the back store while the front store stays on
 * display. A transaction that decodes, validates and passes its CRC ends in
 * CS_STREAM_COMMIT; the caller then calls cs_stream_swap between frames.
 * A damaged, truncated, oversized or invalid transaction is dropped whole
 * and reported (CS_STREAM_ERROR, cs_stream_last_error); the front scene is
 * untouched and the decoder resynchronises on the next transaction header.
 *
 * The fields are private; the struct is public so the caller can place it.
 */
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

typedef struct cs_stream {
    cs_scene *front, *back;
    uint64_t offset;            /* stream offset of the next byte */
    uint64_t txn_offset;        /* start of the current transaction */
    uint64_t rec_offset;        /* start of the current record */
    uint64_t garbage_offset;    /* start of the current run of skipped bytes */
    uint64_t skipped;           /* bytes outside transactions, in total */
    uint64_t skip_left;         /* bytes left of a transaction being skipped */
    uint64_t env_end;           /* where the open signed envelope's trailer starts, or 0 */
    uint32_t commits, dropped;  /* transactions committed and dropped, in total */
    uint32_t body_len, body_pos, crc, trailer;
    uint32_t rec_len, rec_pos, fixed_len, fill, word;
    uint32_t float_count, float_index, base, count, width, slot;
    float key_time;
    uint16_t rec_type;
    uint8_t state, parse, mode, rec_flags;
    uint8_t win_pos, win_count, queued;
    bool has_scene, commit_ready, in_garbage, seen_commit, txn_failed;
    uint8_t win[16];            /* the last 16 bytes: header detection */
    uint8_t buf[52];            /* a record header or a record's fixed part */
    cs_stream_error txn_err;    /* first failure inside the current transaction */
    cs_stream_error queue[2];   /* errors not yet returned */
    cs_stream_error last;       /* the error of the last CS_STREAM_ERROR */
} cs_stream;

/*
 * Starts a decoder on two scene stores. If `front_valid`, `front` holds a
 * scene already on display (e.g. one built into the firmware) that patch
 * transactions may change; otherwise the first transaction must define a
 * whole scene. `back` is scratch until a commit. CS_ERR_ARG if a pointer is
 * NULL or the two stores are one.
 */
cs_status cs_stream_init(cs_stream *s, cs_scene *front, bool front_valid, cs_scene *back);

/*
 * Consumes bytes until they run out or something happens; *used says how
 * many were consumed. After CS_STREAM_COMMIT no byte is consumed until
 * cs_stream_swap; after CS_STREAM_ERROR feeding may go on at once (call
 * again with the rest, even if that is nothing: a second error may wait).
 */
cs_stream_event cs_stream_feed(cs_stream *s, const uint8_t *data, size_t len, size_t *used);

/* End of input: reports a transaction cut short or trailing bytes, then resets to hunting. */
cs_stream_event cs_stream_finish(cs_stream *s);

/*
 * The link lost bytes between the last byte fed and the next one (a UART
 * receive overrun, a full receive buffer): an open transaction is dropped
 * (CS_ERR_STREAM_GAP, `at` the offset of the gap, which counts the bytes
 * fed, not the ones lost), and the decoder hunts for the next header, so
 * no header or transaction is ever pieced together across the gap. A
 * commit waiting for cs_stream_swap or an error waiting to be returned is
 * returned first; call again until CS_STREAM_MORE.
 */
cs_stream_event cs_stream_gap(cs_stream *s);

/* Makes the ready commit the front scene (between frames). CS_ERR_STATE if none is ready. */
cs_status cs_stream_swap(cs_stream *s);

/*
 * Drops the ready commit instead of swapping it in (the caller found it
 * unusable, e.g. cs_scene_check_render failed): the front scene stays, the
 * transaction counts as dropped, and cs_stream_last_error reports `status`
 * with `what` (which must outlive the next feed) and `where`, at the end of
 * the transaction. CS_ERR_STATE if no commit is ready.
 */
cs_status cs_stream_refuse(cs_stream *s, cs_status status, const char *what, const cs_error *where);

/*
 * Whether the back store is in use: a transaction is being decoded into it,
 * or a commit in it waits for cs_stream_swap. Between transactions the
 * back store holds nothing the decoder needs (every transaction starts it
 * afresh, from SCENE or from a copy of the front), so a board short of RAM
 * may lend it out while this is false, e.g. let it share memory with the
 * render workspace and render only while the decoder is not busy. The
 * decoder writes to the back store only inside cs_stream_feed.
 */
bool cs_stream_busy(const cs_stream *s);

/* The scene on display: the last swapped-in commit, or NULL if there is none. */
const cs_scene *cs_stream_scene(const cs_stream *s);

/* The error behind the last CS_STREAM_ERROR. */
const cs_stream_error *cs_stream_last_error(const cs_stream *s);

/*
 * A decoder error as one line of text, the way every program reports it:
 *   <status>[: <explanation>][ (cel c, region r, contour k, item i)]
 *       (transaction at byte N dropped)      or      (skipping from byte N)
 * where N is base + e->offset (base: bytes before the decoder started). The
 * fault's own offset (base + e->at) is left to the caller's prefix. The text
 * is cut to fit len bytes, NUL included; returns the length it needed.
 */
size_t cs_stream_error_text(const cs_stream_error *e, uint64_t base, char *buf, size_t len);

/* ----------------------------------------------------------------- misc */

/* CRC-32 (IEEE 802.3, reflected, as zlib). Start with crc = 0. */
uint32_t cs_crc32(uint32_t crc, const void *data, size_t len);

/* --------------------------------------------------------------- damage */

/* A window of the output: columns [x0, x1) of rows [y0, y1); empty when x0 >= x1. */
typedef struct cs_rect {
    int x0, y0, x1, y1;
} cs_rect;

/*
 * What the last frame showed, cel by cel, so that the next frame can render
 * only what changed (cs_frame_damage). The caller places it; the fields are
 * private: a signature of each cel's state at the frame's time (transform,
 * opacity, lights, paints, contours and control points, as sampled) and the
 * rows and columns its contours' control points reach.
 */
typedef struct cs_damage {
    uint32_t valid;       /* 0: the next frame is damaged everywhere */
    uint32_t frame_sig;   /* size, AA, blending, background, stack lights */
    uint32_t cel_count;
    struct {
        uint32_t sig;
        /* The output pixels the cel can touch, in units of (max(width, height) + 254) / 255
         * pixels rounded outward (8 bytes a cel on a board); empty when x0 >= x1. */
        uint8_t x0, y0, x1, y1;
    } cels[CS_CFG_MAX_CELS];
} cs_damage;

/* Forgets the last frame: the next cs_frame_damage reports the whole output. */
void cs_damage_reset(cs_damage *d);

/*
 * The window of the opts->width x opts->height output that can differ from
 * the frame last passed to this call with `d` (the whole output the first
 * time, after cs_damage_reset, or when the size, AA, blending, background or
 * stack lights changed): the union of the old and the new extents of every
 * cel whose state changed, or that came or went. A window rendered with it
 * as the viewport (opts.view_*) gives the whole render's bits, so a frame is
 * the last frame with that window replaced. Columns start at 0 unless the
 * AA makes a narrower window exact (CS_AA_NONE, or sub-scanlines a power of
 * two). An empty window: nothing changed. opts' own viewport is not used.
 */
cs_status cs_frame_damage(cs_damage *d, const cs_scene *scene, const cs_render_opts *opts,
                          cs_rect *window);

#ifdef __cplusplus
}
#endif

#endif /* CELSCAN_H */
