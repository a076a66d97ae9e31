/*
 * celscan_private.h - the layouts of the core's structs, kept out of
 * celscan.h in the way LVGL keeps its *_private.h headers.
 *
 * celscan.h declares cs_scene, cs_workspace, cs_renderer and cs_stream as
 * incomplete types: a caller that only passes pointers to them needs nothing
 * more. Include this header instead of celscan.h (it includes it) to place
 * them yourself, statically on a board without malloc (`static cs_workspace
 * ws;`) or with sizeof, or to read the scene store's arrays, as a stream
 * writer or a test does. The fields are not an interface: they change when
 * the core does, and only the cs_* calls keep a scene consistent.
 */
#ifndef CELSCAN_PRIVATE_H
#define CELSCAN_PRIVATE_H

#include "celscan.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ----------------------------------------------------------- scene store */

/* A closed periodic NURBS: points[first .. first+count) of the scene. */
typedef struct cs_contour {
    uint32_t first_point;
    uint16_t point_count;
    uint8_t degree;
    uint8_t operand;   /* CSG operand it belongs to (0 unless set) */
} cs_contour;

typedef struct cs_region {
    uint32_t first_contour;
    uint16_t contour_count;
    uint8_t fill_rule; /* cs_fill_rule */
    uint8_t csg_len;   /* 0: one fill over all contours; else RPN length */
    cs_paint paint;
    uint16_t func[3];  /* per cs_paint_field: 0 constant, else 1 + index in scene funcs */
    uint8_t csg[CS_CFG_MAX_CSG]; /* operand n as n, operator k (-k in the API) as 0x80|k */
} cs_region;

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

/* --------------------------------------------------------------- render */

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

/*
 * A piece's ends at consecutive row boundaries from the first, kept for
 * the rows that reach them (cs_exact_place.c); y is the first plus
 * CS_EXACT_LEVELS (memo_key), or -1 before any. A polynomial piece's are
 * solved CS_EXACT_LEVELS at a time, up to its bottom; a rational piece
 * keeps one, with its w and W'/W (a polynomial end's W'/W is 0, its w
 * unread). end[i] holds u, x, x', y' of level i (the first four fields of
 * a cs_exact_end).
 */
#define CS_EXACT_LEVELS 8
typedef struct cs_exact_level {
    float y;
    uint32_t spare;  /* keeps end[] on 16 bytes */
    float w, dwr;
    float end[CS_EXACT_LEVELS][4];
} cs_exact_level;

/* Where one active piece is within the current band of a pixel row, for
 * exact-area coverage (cs_exact.c). */
typedef struct cs_exact_piece {
    cs_exact_end top, bot; /* the arc's ends at the band's top and bottom */
    float u_row;          /* u where the piece leaves the row (its end, or the row's bottom) */
    float dmin, dmax;     /* the arc lies within [dmin, dmax] of its chord, horizontally */
    float xmin, xmax;     /* x range of the arc's control polygon */
    float key;            /* x order within the band: x_top + x_bot */
    const cs_segment *segment; /* the piece's, found once a row */
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
    cs_index order[CS_CFG_MAX_PIECES];   /* pieces by where they start (cs_frame.c) */
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
    cs_exact_level level_memo[CS_CFG_MAX_PIECES]; /* per piece: its next row ends */
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
#if CS_CFG_CEL_LIST
    uint16_t cel_runs[CS_CFG_MAX_WIDTH];  /* the run starts where used != 0 (cs_runs.h) */
    uint32_t cel_run_count;
#endif
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

/* A run of a cache line (cs_cache): pixels [x, x+len) share the (E, T) map. */
typedef struct cs_cache_run {
    uint16_t x, len;        /* pixels [x, x+len) share the map */
    float E[3], T[3];
} cs_cache_run;

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

/* ------------------------------------------------------------ cel stream */

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
    uint8_t rec_kind;           /* the record's row in cs__rec_kinds (cs_stream_apply.c) */
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
 * What the last frame showed, cel by cel, so that the next frame can render
 * only what changed (cs_frame_damage). The caller places it; the fields are
 * private: a signature of each cel's state at the frame's time (transform,
 * opacity, lights, paints, contours and control points, as sampled) and the
 * rows and columns its contours' control points reach.
 */
struct cs_damage {
    uint32_t valid;       /* 0: the next frame is damaged everywhere */
    uint32_t frame_sig;   /* size, AA, blending, background, stack lights */
    uint32_t cel_count;
    struct {
        uint32_t sig;
        /* The output pixels the cel can touch, in units of (max(width, height) + 254) / 255
         * pixels rounded outward (8 bytes a cel on a board); empty when x0 >= x1. */
        uint8_t x0, y0, x1, y1;
    } cels[CS_CFG_MAX_CELS];
};

#ifdef __cplusplus
}
#endif

#endif /* CELSCAN_PRIVATE_H */
