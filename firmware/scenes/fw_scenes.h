/*
 * fw_scenes.h - test scenes built into the firmware image.
 *
 * Besides the scenes it receives as a cel stream, the firmware carries a
 * few scenes of its own, built with the core's cs_scene_add_* calls: the
 * renderer's host-identity check without the decoder in between, and the
 * picture on real glass before the first commit. The same file is compiled for the host (tests/fw_host_ref.c) so
 * that the host build of the core renders the very same scene and the two
 * frame CRCs can be compared bit for bit. Everything here is freestanding
 * (no libc) and uses only IEEE-754 single-precision arithmetic, so the scene
 * itself is identical on both sides.
 *
 * A scene may depend on time: the builder evaluates its own little
 * animation at time t (streamed scenes use keyframe tracks instead).
 */
#ifndef FW_SCENES_H
#define FW_SCENES_H

#include "celscan.h"

typedef struct fw_scene_info {
    const char *name;
    cs_status (*build)(cs_scene *scene, float t, cs_error *err);
} fw_scene_info;

/* Number of built-in scenes and their table, in a fixed order. */
#define FW_SCENE_COUNT 3
extern const fw_scene_info fw_scenes[FW_SCENE_COUNT];

/* Index of the scene called `name`, or -1. */
int fw_scene_find(const char *name);

/*
 * One frame the firmware renders and the host must reproduce: a scene at a
 * time and size with an anti-aliasing setting. Times are whole milliseconds
 * so that both sides turn them into the same float: (float)ms / 1000.0f is
 * the correctly rounded quotient, the same float strtof gives for the
 * decimal text the test passes to the host renderer.
 */
typedef struct fw_job {
    uint8_t scene;       /* index into fw_scenes */
    uint8_t subscan;     /* sub-scanlines (CS_AA_SUBSCAN); 0 means CS_AA_NONE */
    uint16_t width, height;
    uint32_t time_ms;
} fw_job;

#define FW_JOB_COUNT 7
extern const fw_job fw_jobs[FW_JOB_COUNT];

/* The render options of a job. */
cs_render_opts fw_job_opts(const fw_job *job);

#endif /* FW_SCENES_H */
