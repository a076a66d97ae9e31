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

/* Scene store: how much a committed scene may hold. */
#ifndef CS_CFG_MAX_CELS
#define CS_CFG_MAX_CELS 64
#endif
#ifndef CS_CFG_MAX_REGIONS
#define CS_CFG_MAX_REGIONS 1024
#endif
#ifndef CS_CFG_MAX_CONTOURS
#define CS_CFG_MAX_CONTOURS 2048
#endif
/* Control points over all contours of a scene (each also carries one knot interval). */
#ifndef CS_CFG_MAX_POINTS
#define CS_CFG_MAX_POINTS 16384
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
/* Crossings of one region with one sub-scanline; for --aa exact, pieces of
 * one region active on one pixel row. */
#ifndef CS_CFG_MAX_CROSSINGS
#define CS_CFG_MAX_CROSSINGS 512
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

/* Operands a region's inside test may combine (CSG); each keeps its own winding. */
#ifndef CS_CFG_MAX_OPERANDS
#define CS_CFG_MAX_OPERANDS 8
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

#endif /* CS_CONFIG_H */
