/*
 * lx_scene_source.c - renders lines of a cs_scene on demand, in lanes, or
 * ahead of demand on a thread pool (see lx_scene_source.h).
 */
#include <stdlib.h>
#include <string.h>

#include "lx_scene_source.h"

/* A pool worker: line y of its renderer's runs, as floats, into its ring slot. */
static void ring_line(void *user, const cs_renderer *r, int y)
{
    lx_scene_source *s = user;
    bands_floats(r, s->ring + (size_t)(y % s->ring_lines) * 3u * (size_t)s->src.width);
}

void lx_scene_source_end(lx_scene_source *s)
{
    if (!s->pooled)
        return;
    s->pooled = false;
    cs_error e = bands_finish(s->pool);
    if (e.status != CS_OK && s->err.status == CS_OK)
        s->err = e;
}

static hal_status begin(void *user, int lanes)
{
    lx_scene_source *s = user;
    lx_scene_source_end(s); /* lane 0's workspace is about to change */
    if (lanes < 1 || lanes > LX_MAX_LANES || !s->scene)
        return HAL_ERR_RENDER;
    s->lanes = lanes;
    memset(&s->err, 0, sizeof s->err);
    if (s->pool && lanes == 1) {
        /* Prepared in parts on the pool's threads, as celsim --threads does. */
        cs_status st = bands_prepare(s->pool, &s->r[0], s->ws[0], s->scene, &s->opts, &s->err);
        if (st == CS_OK)
            st = bands_start(s->pool, &s->r[0], LX_BAND_LINES, s->ring_lines, ring_line, s);
        if (st != CS_OK) {
            s->err.status = st;
            return HAL_ERR_RENDER;
        }
        s->pooled = true;
        s->pool_next = s->win.y0;
        return HAL_OK;
    }
    s->pool_next = -1;
    for (int l = 0; l < lanes; l++) {
        cs_status st = cs_frame_begin(&s->r[l], s->ws[l], s->scene, &s->opts, &s->err);
        if (st != CS_OK)
            return HAL_ERR_RENDER;
    }
    return HAL_OK;
}

/* Line y from the pool's ring; lines only go forward, as in a lane. */
static bool pool_line(lx_scene_source *s, int y, float *rgb)
{
    if (y < s->pool_next || y >= s->win.y1)
        return false; /* its slot may hold a later line already */
    int i = y - s->win.y0; /* the pool counts the window's lines */
    size_t n = 3u * (size_t)(s->win.x1 - s->win.x0);
    bands_wait(s->pool, i);
    memcpy(rgb, s->ring + (size_t)(i % s->ring_lines) * 3u * (size_t)s->src.width, n * sizeof *rgb);
    s->pool_next = y + 1;
    bands_release(s->pool, i + 1); /* its slot may take line i + ring_lines */
    if (y == s->win.y1 - 1)
        lx_scene_source_end(s);
    return true;
}

/* The core's viewport for window w of this display, offset by the wall's if
 * there is one: the one place the two are combined. A whole display with no
 * wall has no viewport, as before windows. */
static void set_view(const lx_scene_source *s, cs_render_opts *o, hal_window w, bool whole)
{
    o->view_x = s->base_x + w.x0;
    o->view_y = s->base_y + w.y0;
    o->view_w = whole && !s->base_w ? 0 : w.x1 - w.x0;
    o->view_h = whole && !s->base_h ? 0 : w.y1 - w.y0;
}

static hal_window whole_window(const lx_scene_source *s)
{
    return (hal_window){0, 0, s->src.width, s->src.height};
}

static hal_status window(void *user, const hal_window *win)
{
    lx_scene_source *s = user;
    lx_scene_source_end(s); /* the workers' frame uses the viewport */
    hal_window w = whole_window(s);
    if (win && (!hal_window_inside(win, w.x1, w.y1) || win->x0 == win->x1 || win->y0 == win->y1))
        return HAL_ERR_CONFIG;
    bool whole = !win || (win->x0 == 0 && win->y0 == 0 && win->x1 == w.x1 && win->y1 == w.y1);
    if (!whole)
        w = *win;
    s->win = w;
    set_view(s, &s->opts, w, whole);
    return HAL_OK;
}

static hal_status line(void *user, int lane, int y, float *rgb)
{
    lx_scene_source *s = user;
    if (lane < 0 || lane >= s->lanes)
        return HAL_ERR_RENDER;
    if (s->pool_next >= 0) {
        if (!pool_line(s, y, rgb))
            return HAL_ERR_RENDER;
    } else {
        cs_status st = cs_render_line(&s->r[lane], s->base_y + y, rgb);
        if (st != CS_OK) {
            s->err.status = st;
            return HAL_ERR_RENDER;
        }
        /* A capacity overflow still gives a line (the region is left out); keep
         * the first one so celfw can report it, but carry on showing frames. */
        if (s->r[lane].sticky.status != CS_OK && s->err.status == CS_OK)
            s->err = s->r[lane].sticky;
    }
    if (s->between_lines)
        s->between_lines(s->between_user);
    return HAL_OK;
}

hal_status lx_scene_source_init(lx_scene_source *s, int width, int height, cs_aa_mode aa,
                               int subscanlines)
{
    memset(s, 0, sizeof *s);
    s->pool_next = -1;
    if (width <= 0 || height <= 0 || width > CS_CFG_MAX_WIDTH || height > CS_CFG_MAX_HEIGHT)
        return HAL_ERR_CONFIG;
    for (int l = 0; l < LX_MAX_LANES; l++) {
        s->ws[l] = calloc(1, sizeof(cs_workspace));
        if (!s->ws[l]) {
            lx_scene_source_free(s);
            return HAL_ERR_NOMEM;
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
    s->src.window = window;
    s->win = whole_window(s);
    return HAL_OK;
}

hal_status lx_scene_source_viewport(lx_scene_source *s, int wall_w, int wall_h, int x, int y)
{
    int w = s->src.width, h = s->src.height;
    if (wall_w < 1 || wall_h < 1 || wall_w > CS_CFG_MAX_WALL || wall_h > CS_CFG_MAX_WALL || x < 0 ||
        y < 0 || x > wall_w - w || y > wall_h - h)
        return HAL_ERR_CONFIG;
    s->opts.width = wall_w;
    s->opts.height = wall_h;
    s->base_x = x;
    s->base_y = y;
    s->base_w = w;
    s->base_h = h;
    s->win = whole_window(s);
    set_view(s, &s->opts, s->win, true);
    return HAL_OK;
}

void lx_scene_source_set(lx_scene_source *s, const cs_scene *scene, float time)
{
    s->scene = scene;
    s->opts.time = time;
}

hal_window lx_scene_source_damage(lx_scene_source *s, cs_damage *d)
{
    hal_window whole = whole_window(s);
    cs_rect r;
    if (!s->scene || cs_frame_damage(d, s->scene, &s->opts, &r) != CS_OK) {
        cs_damage_reset(d);
        return whole;
    }
    int x0 = r.x0 - s->base_x, y0 = r.y0 - s->base_y;
    int x1 = r.x1 - s->base_x, y1 = r.y1 - s->base_y;
    x0 = x0 < 0 ? 0 : x0;
    y0 = y0 < 0 ? 0 : y0;
    x1 = x1 > whole.x1 ? whole.x1 : x1;
    y1 = y1 > whole.y1 ? whole.y1 : y1;
    if (x0 >= x1 || y0 >= y1)
        return (hal_window){0, 0, 0, 0}; /* nothing of this viewport changed */
    return (hal_window){x0, y0, x1, y1};
}

hal_status lx_scene_source_show(lx_scene_source *s, hal_display *d, cs_damage *damage, hal_window *win,
                                hal_frame_stats *st)
{
    *win = damage ? lx_scene_source_damage(s, damage) : whole_window(s);
    hal_status res = hal_display_present_window(d, &s->src, win, st);
    if (res != HAL_OK && damage)
        cs_damage_reset(damage);
    lx_scene_source_end(s);
    return res;
}

cs_status lx_scene_source_check(lx_scene_source *s, const cs_scene *scene, cs_error *err)
{
    lx_scene_source_end(s);
    cs_render_opts o = s->opts;
    o.time = 0.0f;
    set_view(s, &o, whole_window(s), true);
    return cs_scene_check_render(&s->r[0], s->ws[0], scene, &o, err);
}

hal_status lx_scene_source_threads(lx_scene_source *s, int threads)
{
    if (threads < 1 || threads > BANDS_MAX_THREADS)
        return HAL_ERR_CONFIG;
    if (threads == 1 || s->pool)
        return HAL_OK;
    s->ring_lines = 2 * threads * LX_BAND_LINES;
    s->ring = malloc((size_t)s->ring_lines * 3u * (size_t)s->src.width * sizeof *s->ring);
    s->pool = s->ring ? bands_new(threads) : NULL;
    if (!s->pool) {
        free(s->ring);
        s->ring = NULL;
        return HAL_ERR_NOMEM;
    }
    return HAL_OK;
}

void lx_scene_source_free(lx_scene_source *s)
{
    lx_scene_source_end(s);
    bands_free(s->pool);
    s->pool = NULL;
    free(s->ring);
    s->ring = NULL;
    for (int l = 0; l < LX_MAX_LANES; l++) {
        free(s->ws[l]);
        s->ws[l] = NULL;
    }
}
