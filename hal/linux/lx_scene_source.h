/*
 * lx_scene_source.h - an lx_source that renders a cs_scene with the core.
 *
 * Each lane has its own cs_renderer and cs_workspace, because the core's
 * active-piece list only moves forward: a HUB75 panel that asks for lines
 * 0, 16, 1, 17, ... is served by lane 0 walking the top half and lane 1
 * walking the bottom half. Workspaces are allocated once, at init; nothing is
 * allocated per frame.
 */
#ifndef LX_SCENE_SOURCE_H
#define LX_SCENE_SOURCE_H

#include "celscan.h"
#include "lx_display.h"

#define LX_MAX_LANES 2

typedef struct lx_scene_source {
    lx_source src;            /* hand &s->src to a backend */
    const cs_scene *scene;    /* what the next begin() renders */
    cs_render_opts opts;
    cs_workspace *ws[LX_MAX_LANES];
    cs_renderer r[LX_MAX_LANES];
    int lanes;
    cs_error err;             /* the first error of the frame, if any */
} lx_scene_source;

/* Sets up lanes for width x height output. aa/subscanlines as in cs_render_opts. */
lx_status lx_scene_source_init(lx_scene_source *s, int width, int height, cs_aa_mode aa,
                               int subscanlines);
/*
 * Makes the output one board's viewport of a wall_w x wall_h video wall: the
 * window at (x, y) of the source's width x height, rendered bit for bit as
 * the whole wall's render has it (cs_render_opts.view_*). The display's
 * line y is the wall's line y + y. LX_ERR_CONFIG if it does not fit.
 */
lx_status lx_scene_source_viewport(lx_scene_source *s, int wall_w, int wall_h, int x, int y);
/* Chooses the scene and the animation time of the next frame. */
void lx_scene_source_set(lx_scene_source *s, const cs_scene *scene, float time);
void lx_scene_source_free(lx_scene_source *s);

#endif /* LX_SCENE_SOURCE_H */
