/*
 * celfw_scene_json.c - lets celfw show a scene JSON file, through host-sim's loader.
 *
 * The loader (host-sim/scene_json.c, scene_json_load(path, scene, err, len))
 * is being written with the simulator; build with CELFW_JSON=1 once it is in
 * the tree. It is taken to have succeeded when it left the error buffer
 * empty, which holds whichever success convention its return value uses.
 */
#include <stdio.h>

#include "celfw_scenes.h"

#ifdef CELFW_HAVE_SCENE_JSON
#include "scene_json.h"
#endif

bool celfw_scene_json(const char *path, cs_scene *scene, char *err, size_t errlen)
{
#ifdef CELFW_HAVE_SCENE_JSON
    err[0] = 0;
    (void)scene_json_load(path, scene, err, errlen);
    return err[0] == 0;
#else
    (void)scene;
    snprintf(err, errlen,
             "%s: this celfw has no JSON scene loader (build with CELFW_JSON=1 once host-sim/scene_json.c exists); "
             "use --scene builtin:demo|anim|bars",
             path);
    return false;
#endif
}
