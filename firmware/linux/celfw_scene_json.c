/*
 * celfw_scene_json.c - lets celfw show a scene JSON file, through host-sim's loader.
 *
 * A board normally gets its scenes over the stream; a JSON file given with
 * --scene is for bring-up and kiosks without a host. The loader is the one
 * celsim uses (host-sim/scene_json.c), so a file looks the same on both.
 */
#include "celfw_scenes.h"
#include "scene_json.h"

bool celfw_scene_json(const char *path, cs_scene *scene, char *err, size_t errlen)
{
    return scene_json_load(path, scene, err, errlen) == 0;
}
