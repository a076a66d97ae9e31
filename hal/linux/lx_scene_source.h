/*
 * lx_scene_source.h - an hal_source that renders a cs_scene with the core.
 *
 * Each lane has its own cs_renderer and cs_workspace, because the core's
 * active-piece list only moves forward: a HUB75 panel that asks for lines
 * 0, 16, 1, 17, ... is served by lane 0 walking the top half and lane 1
 * walking the bottom half. Workspaces are allocated once, at init; nothing is
 * allocated per frame.
 *
 * With threads (lx_scene_source_threads), a one-lane frame is prepared once
 * in lane 0 and its lines are rendered ahead on a pool of worker threads
 * (host-sim/bands.h), in bands of LX_BAND_LINES, into a ring of lines
 * that line() hands out in order: the same floats, at most the ring ahead
 * of the display, never a frame of pixels. Two-lane backends (HUB75) keep
 * the lanes on the calling thread.
 *
 * A one-lane frame may be limited to a window of the output (the source's
 * window operation, from hal_display_present_window): only its rows are
 * rendered, on the pool too, each as wide as the window, with the whole
 * render's bits (the window becomes the core's viewport, inside a video
 * wall's viewport if there is one).
 */
#ifndef LX_SCENE_SOURCE_H
#define LX_SCENE_SOURCE_H

#include "bands.h"
#include "celscan_private.h"
#include "display.h"

#define LX_MAX_LANES 2
#define LX_BAND_LINES 16 /* a band of the thread pool; the ring holds two a thread */

typedef struct lx_scene_source {
    hal_source src;            /* hand &s->src to a backend */
    const cs_scene *scene;    /* what the next begin() renders */
    cs_render_opts opts;
    cs_workspace *ws[LX_MAX_LANES];
    cs_renderer r[LX_MAX_LANES];
    int lanes;
    cs_error err;             /* the first error of the frame, if any */
    /* Called after every rendered line, if set: lets the program serve its
     * input while a slow frame renders (it must not touch the scene). */
    void (*between_lines)(void *user);
    void *between_user;
    /* lx_scene_source_threads: the pool, and its ring of ring_lines lines of 3*width floats. */
    bands *pool;
    float *ring;
    int ring_lines;
    int base_x, base_y, base_w, base_h; /* the viewport without a window (view_w 0: none) */
    hal_window win;           /* the rows and columns the next frame renders */
    bool pooled;              /* workers are rendering lines of the frame */
    int pool_next;            /* the frame's next line from the pool; -1: lines in lanes */
} lx_scene_source;

/* Sets up lanes for width x height output. aa/subscanlines as in cs_render_opts. */
hal_status lx_scene_source_init(lx_scene_source *s, int width, int height, cs_aa_mode aa,
                               int subscanlines);
/*
 * Makes the output one board's viewport of a wall_w x wall_h video wall: the
 * window at (x, y) of the source's width x height, rendered bit for bit as
 * the whole wall's render has it (cs_render_opts.view_*). The display's
 * line y is the wall's line y + y. HAL_ERR_CONFIG if it does not fit.
 */
hal_status lx_scene_source_viewport(lx_scene_source *s, int wall_w, int wall_h, int x, int y);
/* Chooses the scene and the animation time of the next frame. */
void lx_scene_source_set(lx_scene_source *s, const cs_scene *scene, float time);
/*
 * The window of this source's output that the frame lx_scene_source_set
 * chose can change from the last frame passed with d (cs_frame_damage in the
 * whole render, a wall's if there is one, within this source's viewport and
 * counted from its corner): empty if none of it changed, the whole output
 * if the damage cannot be found (d is then reset).
 */
hal_window lx_scene_source_damage(lx_scene_source *s, cs_damage *d);
/*
 * Shows the frame lx_scene_source_set chose on d, as celfw's loop does: only
 * the window lx_scene_source_damage finds when `damage` is given, else the
 * whole output. *win is what was rendered, *st gets the frame's counts. A
 * failed frame resets the damage (the display may not show it: the next
 * frame is whole). No worker reads the scene after it returns.
 */
hal_status lx_scene_source_show(lx_scene_source *s, hal_display *d, cs_damage *damage, hal_window *win,
                                hal_frame_stats *st);
/* Whether `scene` can be rendered at this source's size (cs_scene_check_render
 * in lane 0's workspace): only between frames. */
cs_status lx_scene_source_check(lx_scene_source *s, const cs_scene *scene, cs_error *err);
/*
 * Renders one-lane frames on `threads` worker threads (2..BANDS_MAX_THREADS;
 * 1 leaves the lines on the caller's thread). After init, before frames.
 */
hal_status lx_scene_source_threads(lx_scene_source *s, int threads);
/*
 * Ends the frame: waits for the workers still rendering lines of it (a
 * backend may give up on a frame part way), and keeps its capacity error.
 * Call after present() and before the scene changes; harmless without threads.
 */
void lx_scene_source_end(lx_scene_source *s);
void lx_scene_source_free(lx_scene_source *s);

#endif /* LX_SCENE_SOURCE_H */
