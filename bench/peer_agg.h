/*
 * peer_agg.h - the scene drawn by Anti-Grain Geometry (peer_agg.cpp), as C.
 *
 * The same calls as the cairo and FreeType peers (bench.h): regions
 * [first, end) of a set drawn back to front over the background colour or,
 * with `over_saved`, over the image kept by peer_agg_save_background.
 * Pixels are 8-bit B, G, R, A in memory, as cairo's ARGB32 on a
 * little-endian host, with alpha 255 (every frame starts opaque).
 */
#ifndef BENCH_PEER_AGG_H
#define BENCH_PEER_AGG_H

#include <stdint.h>

#include "outline.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct peer_agg peer_agg;

peer_agg *peer_agg_new(int width, int height);
void peer_agg_free(peer_agg *p);
void peer_agg_frame(peer_agg *p, const ol_set *set, int first, int end, bool over_saved);
void peer_agg_save_background(peer_agg *p);
const uint32_t *peer_agg_pixels(peer_agg *p); /* stride 4 * width */
/* Coverage of one contour alone over the box [x0, x0+w) x [y0, y0+h), 0..1. */
void peer_agg_coverage(const ol_set *set, const ol_contour *c, bool evenodd, int x0, int y0, int w,
                       int h, double *out);

#ifdef __cplusplus
}
#endif

#endif /* BENCH_PEER_AGG_H */
