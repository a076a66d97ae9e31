/*
 * fw_tracks_scene.h - an animated test scene with keyframe tracks, built in
 * C, for the firmware's stream tests.
 *
 * It is built with the cs_scene_* calls, not loaded from scene JSON, so
 * the firmware test's reference depends on no JSON loader: it uses
 * every track kind (cel transform, cel lights, region paint, contour
 * points, stack lights, background) with both eases, keys at t = 0, 1, 2 s.
 * tests/fw_cels_gen.c encodes it into a cel stream for the firmware, and
 * tests/fw_host_ref.c renders it directly from this builder (no decoder in
 * between) as the host reference. It fits the 480x272 board's capacities.
 */
#ifndef FW_TRACKS_SCENE_H
#define FW_TRACKS_SCENE_H

#include "celscan.h"

cs_status fw_tracks_scene(cs_scene *scene, cs_error *err);

#endif /* FW_TRACKS_SCENE_H */
