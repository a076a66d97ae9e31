/*
 * cs_config.h - compile-time capacities of the celscan core.
 *
 * The core never allocates. Every buffer it uses lives either in the scene
 * store (cs_scene) or in the per-render workspace (cs_workspace), and their
 * sizes are fixed here, in the style of luaconf.h / tusb_config.h. Each knob
 * is guarded by #ifndef so a board can override it on the command line
 * (-DCS_CFG_MAX_WIDTH=480) or in a header named by CS_CFG_FILE.
 *
 * Running out of any capacity is reported as a CS_ERR_CAP_* status; it never
 * writes past a buffer.
 */
#ifndef CS_CONFIG_H
#define CS_CONFIG_H

#ifdef CS_CFG_FILE
#include CS_CFG_FILE
#endif

/*
 * Scene store: how much a committed scene may hold. These defaults are the
 * host's (celsim, celc, the tests), sized for imported animation: Lottie
 * files of 200-odd layers and precomp copies (1643-exploding-star.json
 * needs 248 cels; a cel's parent is one byte, so 254 is the most), and
 * stroked outlines that move (ondas.json: 20,712 control points). Boards set
 * their own (firmware/boards/cs_config_480x272.h: 16 cels) and refuse a
 * scene beyond them with the CS_ERR_CAP_* status naming the capacity.
 */
#ifndef CS_CFG_MAX_CELS
#define CS_CFG_MAX_CELS 254
#endif
#ifndef CS_CFG_MAX_REGIONS
#define CS_CFG_MAX_REGIONS 1024
#endif
#ifndef CS_CFG_MAX_CONTOURS
#define CS_CFG_MAX_CONTOURS 2048
#endif
/* Control points over all contours of a scene (each also carries one knot
 * interval). A frame's segments default to as many, and its pieces to twice
 * that, which cs_crossing numbers in 16 bits: 32768 is the most. */
#ifndef CS_CFG_MAX_POINTS
#define CS_CFG_MAX_POINTS 32768
#endif

/*
 * Animation: keyframe tracks, their keys (one time each) and the floats of
 * all keys together (a transform key takes 6, a paint 7, a control-point key
 * 3 per point). The host's store is sized for imported animation (a Lottie
 * stroke whose outline moves is a points track per outline piece, keyed
 * often): about 33 MB of keys (ondas.json, 7 s of four stroked waves, takes
 * 176,498 keys and 7,008,365 floats); boards set their own. A scene store
 * this size lives on the heap or in static memory, never on a stack.
 */
#ifndef CS_CFG_MAX_TRACKS
#define CS_CFG_MAX_TRACKS 4096
#endif
#ifndef CS_CFG_MAX_KEYS
#define CS_CFG_MAX_KEYS (256 * 1024)
#endif
#ifndef CS_CFG_MAX_KEY_VALUES
#define CS_CFG_MAX_KEY_VALUES (8 * 1024 * 1024)
#endif
/*
 * TRS transform tracks, cubic Bezier easing and cel groups (imported Lottie
 * animation; about 2.5 KB of Cortex-M4 code). Without them a board refuses
 * such tracks (CS_ERR_TRACK) and parents (CS_ERR_GROUP); hold keys stay.
 */
#ifndef CS_CFG_ANIM_PARTS
#define CS_CFG_ANIM_PARTS 1
#endif
/* Longest chain of cel groups (a cel, its parent, the parent's parent...). */
#ifndef CS_CFG_MAX_GROUP_DEPTH
#define CS_CFG_MAX_GROUP_DEPTH 16
#endif
/* Most control points of one animated contour: the workspace holds one such
 * contour evaluated at frame time. */
#ifndef CS_CFG_MAX_ANIM_POINTS
#define CS_CFG_MAX_ANIM_POINTS 1024
#endif

/*
 * Cel stream: the longest transaction body the decoder accepts, in bytes.
 * Nothing is buffered (records stream into the scene store), so this only
 * bounds how long a header can claim the input.
 */
#ifndef CS_CFG_STREAM_MAX_TXN
#define CS_CFG_STREAM_MAX_TXN (64u * 1024u * 1024u)
#endif

/* Workspace: per-frame segment arena and per-line buffers. */
/* Rational polynomial segments of one frame (at most one per control point). */
#ifndef CS_CFG_MAX_SEGMENTS
#define CS_CFG_MAX_SEGMENTS CS_CFG_MAX_POINTS
#endif
/* y-monotone pieces: a rational cubic splits into at most 5 of them. */
#ifndef CS_CFG_MAX_PIECES
#define CS_CFG_MAX_PIECES (2 * CS_CFG_MAX_SEGMENTS)
#endif
/*
 * Unsigned integer type of segment and piece indices in the workspace.
 * uint16_t halves the index arrays on a microcontroller whose workspace
 * holds well under 65536 pieces; the result of rendering is the same.
 */
#ifndef CS_CFG_INDEX_TYPE
#define CS_CFG_INDEX_TYPE uint32_t
#endif
/* Crossings of one region with one sub-scanline; for --aa exact, pieces of
 * one region active on one pixel row. */
#ifndef CS_CFG_MAX_CROSSINGS
#define CS_CFG_MAX_CROSSINGS 4096
#endif
/*
 * Exact-area anti-aliasing (--aa exact) keeps per-piece band state in the
 * workspace; a board that renders with sub-scanlines only can leave it out,
 * and then CS_AA_EXACT is refused by cs_frame_begin with CS_ERR_ARG.
 */
#ifndef CS_CFG_EXACT
#define CS_CFG_EXACT 1
#endif
/*
 * Rounded 8-bit sRGB output (PNGs, GUD bridges) by a 5 KB table instead of
 * an interpolation per channel: the same bytes, faster. A board that sends
 * other formats, or is short of flash, leaves it out.
 */
#ifndef CS_CFG_SRGB8_TABLE
#define CS_CFG_SRGB8_TABLE 1
#endif
/*
 * The same codes from an 8 KB table cut by the float's bits rather than its
 * square root (no square root, multiply or conversion per channel): the
 * same bytes, -1.6 % of a Many-blobs frame on the host (BENCHMARKS.md). On
 * by default on x86-64 hosts only: a board keeps the smaller table. It
 * replaces the square-root table, so it counts as CS_CFG_SRGB8_TABLE.
 */
#ifndef CS_CFG_SRGB8_BITS
#if defined(__x86_64__) && CS_CFG_SRGB8_TABLE
#define CS_CFG_SRGB8_BITS 1
#else
#define CS_CFG_SRGB8_BITS 0
#endif
#endif
/*
 * The sRGB encoding curve (sRGB blending, and formats other than RGB565)
 * from 1.7 KB instead of the 4 KB table: the same floats, each entry
 * rebuilt from an anchor cubic and a one-byte correction (about 25
 * instructions; cs_srgb_compact.c). For a board short of flash; only
 * scenes blended in sRGB pay for it.
 */
#ifndef CS_CFG_SRGB_COMPACT
#define CS_CFG_SRGB_COMPACT 0
#endif
/*
 * CRC-32 a byte a step from a 256-entry table (1 KB of flash); 0: a nibble
 * a step from a 16-entry one (64 B, about twice the instructions a byte).
 * A board whose panel reads its picture back hashes no frame byte while it
 * renders (hal/mcu/mcu_display.c), only stream bytes and the read-back after
 * the frame, and can spend the kilobyte on the line code instead.
 */
#ifndef CS_CFG_CRC32_TABLE
#define CS_CFG_CRC32_TABLE 1
#endif
/* --aa exact: bands one region's pixel row may be cut into where its curves
 * cross or crowd each other (about one per crossing, a few per vertex). */
#ifndef CS_CFG_EXACT_MAX_BANDS
#define CS_CFG_EXACT_MAX_BANDS 4096
#endif
/* Widest output line, in pixels. */
#ifndef CS_CFG_MAX_WIDTH
#define CS_CFG_MAX_WIDTH 4096
#endif
/* Most sub-scanlines per pixel row for --aa N. */
#ifndef CS_CFG_MAX_SUBSCANLINES
#define CS_CFG_MAX_SUBSCANLINES 64
#endif
/* Alignment of a crossing (cs_crossing), which sets its size: 16 makes it
 * 32 bytes, 4 leaves it 24. Crossings are copied whole as they are redone
 * and sorted; unaligned, a quarter of them straddle cache lines, which on
 * a cached host CPU costs the busiest --aa 16 lines a fifth of their time.
 * A board without a data cache saves the memory. The bytes rendered are
 * the same either way. */
#ifndef CS_CFG_CROSSING_ALIGN
#define CS_CFG_CROSSING_ALIGN 16
#endif

/* Operands a region's inside test may combine (CSG); each keeps its own winding. */
#ifndef CS_CFG_MAX_OPERANDS
#define CS_CFG_MAX_OPERANDS 8
#endif

/* RPN tokens of one region's CSG program (the bit stack holds 32). */
#ifndef CS_CFG_MAX_CSG
#define CS_CFG_MAX_CSG 16
#endif

/* Functional paints (gradients, colour maps) in a scene, and stops per function. */
#ifndef CS_CFG_MAX_FUNCS
#define CS_CFG_MAX_FUNCS 64
#endif
#ifndef CS_CFG_MAX_STOPS
#define CS_CFG_MAX_STOPS 16
#endif

/*
 * Frames whose every paint transmits grey (T the same on all channels: any
 * white or grey medium, every opaque paint, so all imported SVG) keep T in
 * one channel, which saves up to ~5 % of a frame. The path is a second
 * copy of the run code, and with it the run code is inlined where a
 * region's runs are folded (~2 % more, grey or not): 81.8 -> 100.7 KB of
 * Cortex-M4 code for the core, flash that a small board may rather keep.
 * The pixels are the same bits either way (docs/BETA.md).
 */
#ifndef CS_CFG_GREY
#define CS_CFG_GREY 1
#endif

/*
 * T snapped to 0 (composite_cel, a lone region's fold) as a select rather
 * than a branch: whether it snaps goes by the data, ~26 k mispredicted
 * branches of a Many-blobs exact frame on x86-64, and on the hosts the
 * select is fewer instructions too; on a Cortex-M4 (no mispredicts to
 * save) it is 20 B more flash, so the boards keep the branch.
 */
#ifndef CS_CFG_SNAP_SELECT
#if defined(__x86_64__)
#define CS_CFG_SNAP_SELECT 1
#else
#define CS_CFG_SNAP_SELECT 0
#endif
#endif

/*
 * A cel's runs that its regions reached are listed as they are reached
 * (ws->cel_runs, 2 bytes a pixel of CS_CFG_MAX_WIDTH), so the cel
 * composites from the list rather than walking every run of the ranges
 * its regions touched and testing each for coverage: ~1 M fewer
 * instructions and ~20 k fewer mispredicted branches in a Many-blobs exact
 * frame. A board whose RAM is spoken for walks the ranges instead.
 */
#ifndef CS_CFG_CEL_LIST
#define CS_CFG_CEL_LIST 1
#endif

/*
 * Pre-combined cel caches (cs_cache_build) need one more line of (E) floats
 * in the workspace; a small board that keeps no cache can leave them out.
 */
#ifndef CS_CFG_CACHE
#define CS_CFG_CACHE 1
#endif

/*
 * Largest absolute coordinate accepted, in canvas units and after transforms
 * in device pixels. Beyond it single-precision polynomials lose sub-pixel
 * accuracy, so such input is an error rather than a silently wrong picture.
 */
#ifndef CS_CFG_COORD_LIMIT
#define CS_CFG_COORD_LIMIT 1.0e6f
#endif
#ifndef CS_CFG_MAX_HEIGHT
#define CS_CFG_MAX_HEIGHT 16384
#endif

/*
 * Largest whole output (a video wall) a viewport may be cut from, on either
 * side. Nothing is sized by it: lines are the viewport's width. It keeps
 * device columns within the int16 segment origins and exact float integers.
 */
#ifndef CS_CFG_MAX_WALL
#define CS_CFG_MAX_WALL 16384
#endif

#endif /* CS_CONFIG_H */
