/*
 * celfw_wall.c - one board of a video wall (see celfw_wall.h).
 *
 * The display may have chosen its own size (a USB display's mode), so the
 * match between it and the viewport can only be checked once it is open.
 */
#include <stdio.h>

#include "celfw_wall.h"

int celfw_wall_setup(lx_scene_source *src, const celfw_config *cfg, const hal_display *disp,
                     char *err, size_t errlen)
{
    const int *v = cfg->view;
    if (v[2] == 0)
        return 0;
    if (disp->width != v[2] || disp->height != v[3]) {
        snprintf(err, errlen, "viewport %d,%d,%d,%d: the display is %dx%d, not %dx%d", v[0], v[1],
                 v[2], v[3], disp->width, disp->height, v[2], v[3]);
        return 2;
    }
    if (lx_scene_source_viewport(src, cfg->wall_w, cfg->wall_h, v[0], v[1]) != HAL_OK) {
        snprintf(err, errlen, "viewport %d,%d,%d,%d does not fit in the %dx%d wall", v[0], v[1],
                 v[2], v[3], cfg->wall_w, cfg->wall_h);
        return 2;
    }
    return 0;
}
