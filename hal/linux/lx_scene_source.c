/*
 * lx_scene_source.c - renders lines of a cs_scene on demand, in lanes.
 */
#include <stdlib.h>
#include <string.h>

#include "lx_scene_source.h"

static lx_status begin(void *user, int lanes)
{
    lx_scene_source *s = user;
    if (lanes < 1 || lanes > LX_MAX_LANES || !s->scene)
        return LX_ERR_RENDER;
    s->lanes = lanes;
    memset(&s->err, 0, sizeof s->err);
    for (int l = 0; l < lanes; l++) {
        cs_status st = cs_frame_begin(&s->r[l], s->ws[l], s->scene, &s->opts, &s->err);
        if (st != CS_OK)
            return LX_ERR_RENDER;
    }
    return LX_OK;
}

static lx_status line(void *user, int lane, int y, float *rgb)
{
    lx_scene_source *s = user;
    if (lane < 0 || lane >= s->lanes)
        return LX_ERR_RENDER;
    cs_status st = cs_render_line(&s->r[lane], s->opts.view_y + y, rgb);
    if (st != CS_OK) {
        s->err.status = st;
        return LX_ERR_RENDER;
    }
    /* A capacity overflow still gives a line (the region is left out); keep
     * the first one so celfw can report it, but carry on showing frames. */
    if (s->r[lane].sticky.status != CS_OK && s->err.status == CS_OK)
        s->err = s->r[lane].sticky;
    return LX_OK;
}

lx_status lx_scene_source_init(lx_scene_source *s, int width, int height, cs_aa_mode aa,
                               int subscanlines)
{
    memset(s, 0, sizeof *s);
    if (width <= 0 || height <= 0 || width > CS_CFG_MAX_WIDTH || height > CS_CFG_MAX_HEIGHT)
        return LX_ERR_CONFIG;
    for (int l = 0; l < LX_MAX_LANES; l++) {
        s->ws[l] = calloc(1, sizeof(cs_workspace));
        if (!s->ws[l]) {
            lx_scene_source_free(s);
            return LX_ERR_NOMEM;
        }
    }
    s->opts.width = width;
    s->opts.height = height;
    s->opts.aa = aa;
    s->opts.subscanlines = subscanlines;
    s->src.width = width;
    s->src.height = height;
    s->src.user = s;
    s->src.begin = begin;
    s->src.line = line;
    return LX_OK;
}

lx_status lx_scene_source_viewport(lx_scene_source *s, int wall_w, int wall_h, int x, int y)
{
    int w = s->src.width, h = s->src.height;
    if (wall_w < 1 || wall_h < 1 || wall_w > CS_CFG_MAX_WALL || wall_h > CS_CFG_MAX_WALL || x < 0 ||
        y < 0 || x > wall_w - w || y > wall_h - h)
        return LX_ERR_CONFIG;
    s->opts.width = wall_w;
    s->opts.height = wall_h;
    s->opts.view_x = x;
    s->opts.view_y = y;
    s->opts.view_w = w;
    s->opts.view_h = h;
    return LX_OK;
}

void lx_scene_source_set(lx_scene_source *s, const cs_scene *scene, float time)
{
    s->scene = scene;
    s->opts.time = time;
}

void lx_scene_source_free(lx_scene_source *s)
{
    for (int l = 0; l < LX_MAX_LANES; l++) {
        free(s->ws[l]);
        s->ws[l] = NULL;
    }
}
