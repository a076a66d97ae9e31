/*
 * celfw_scenes.h - scenes built into celfw, made with the core's builder calls.
 *
 * They give celfw something to show with no stream or scene file (--scene
 * NAME), and the emulated-device tests scenes of their own: a signage-like
 * still and an animation in which one small shape moves over a still
 * background. The animation is rebuilt by its builder at each frame's
 * time, not keyed with tracks.
 */
#ifndef CELFW_SCENES_H
#define CELFW_SCENES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "celscan.h"

/* Builds the named scene ("demo", "anim", "bars") at time t into scene.
 * Returns false for an unknown name. */
bool celfw_scene_build(const char *name, cs_scene *scene, float t);

/* true if the named scene changes with time (must be rebuilt per frame). */
bool celfw_scene_animated(const char *name);

/* The period of a built-in scene that repeats (celfw's clock wraps its time), else 0. */
uint64_t celfw_scene_period_ns(const char *name);

/* The names, space separated, for messages. */
const char *celfw_scene_names(void);

/*
 * The moving shape of "anim" at time t, in canvas units (canvas 320 x 180):
 * a disc of radius ANIM_R centred at (x, y). Tests use it to predict which
 * lines a frame touches.
 */
#define CELFW_ANIM_R 6.0f
void celfw_anim_disc(float t, float *x, float *y);

/* Loads a scene JSON file (see celfw_scene_json.c). false with a message on failure. */
bool celfw_scene_json(const char *path, cs_scene *scene, char *err, size_t errlen);

#endif /* CELFW_SCENES_H */
