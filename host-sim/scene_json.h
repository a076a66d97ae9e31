/*
 * scene_json.h - loading authoring JSON (DESIGN.md, "Scene JSON") into a
 * cs_scene.
 *
 * This is the host side of the authoring contract, shared by celsim and by
 * the scene compiler: both build their scene through the core's
 * cs_scene_* calls, so the validation a scene gets on the host is exactly the
 * validation the board applies to a stream. The loader adds what the core
 * cannot know: JSON types, field names, array lengths, the sRGB decoding of
 * colours, and error messages that name the file and the JSON path
 * ("scene.json: cels[2].regions[0].contours[1].points[4]: weight must be > 0").
 * "animate" objects become the store's keyframe tracks (docs/SCENE.md,
 * Animation), checked by the core like every static value.
 *
 * Every function returns 0 on success and -1 on failure with a one-line
 * message in errbuf (always NUL-terminated when errlen > 0). On failure the
 * scene may hold part of the input and must not be rendered.
 */
#ifndef HOST_SIM_SCENE_JSON_H
#define HOST_SIM_SCENE_JSON_H

#include <stddef.h>

#include <cjson/cJSON.h>

#include "celscan.h"

/* A buffer this size holds any message the loader writes without truncation
 * of the path and problem (file names are cut if need be). */
#define SCENE_JSON_ERRLEN 1024

/* Reads and loads the file at `path`; `path` names the file in messages. */
int scene_json_load(const char *path, cs_scene *out, char *errbuf, size_t errlen);

/* Loads `len` bytes of JSON text; `name` names the input in messages. */
int scene_json_load_string(const char *text, size_t len, const char *name, cs_scene *out,
                           char *errbuf, size_t errlen);

/*
 * Loads an already parsed document, for a tool that also reads other parts
 * of the tree itself: it parses once with cJSON and passes the tree here.
 * The scene's "animate" tracks are loaded into the store either way.
 */
int scene_json_load_tree(const cJSON *root, const char *name, cs_scene *out, char *errbuf,
                         size_t errlen);

/* The sRGB transfer function (IEC 61966-2-1), encoded 0..1 to linear light. */
float scene_json_srgb_to_linear(double encoded);

/*
 * Describes a core error with a location as a JSON path plus the problem,
 * e.g. "cels[0].regions[1].contours[0].points[3]: coordinate magnitude ...".
 * Used for the errors cs_frame_begin reports against the loaded scene.
 */
void scene_json_describe_error(const cs_error *err, char *buf, size_t len);

#endif /* HOST_SIM_SCENE_JSON_H */
