/*
 * celfw_wall.h - one board of a video wall: celfw's --wall and --viewport.
 *
 * A wall of several panels, each on its own board, shows one scene: every
 * board renders its window of the wall's output (cs_render_opts.view_*),
 * whose pixels are bit for bit those of one big render, so the tiles meet
 * without seams. Which instant each board shows is the animation clock's
 * business (a shared clock makes the tiles one frame).
 */
#ifndef CELFW_WALL_H
#define CELFW_WALL_H

#include <stddef.h>

#include "celfw_config.h"
#include "display.h"
#include "lx_scene_source.h"

/*
 * Points the scene source at the configured viewport of the wall, after
 * checking that the display is the viewport's size. Without a wall it does
 * nothing. Returns 0, or celfw's configuration exit status (2) with the
 * reason in err.
 */
int celfw_wall_setup(lx_scene_source *src, const celfw_config *cfg, const hal_display *disp,
                     char *err, size_t errlen);

#endif /* CELFW_WALL_H */
