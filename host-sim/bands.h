/*
 * bands.h - the lines of one frame rendered on several threads (Linux hosts).
 *
 * The frame is prepared once, in the caller's renderer and workspace
 * (cs_frame_begin, or bands_prepare: in parts on the pool's threads). Each
 * worker thread then renders lines of that frame in a renderer of its own
 * over a workspace of its own (cs_frame_share): the segments, pieces and
 * paints are only read, so the preparation is not repeated per thread, and
 * every line comes out with the bytes one thread would give it (the core's
 * lines are pure functions of the frame and y).
 *
 * Threads render bands of `chunk` lines; for a frame in storage each goes
 * on through a span of its own and, when done, takes the back half of the
 * largest span left; for a ring they take bands from the top in turn. Either
 * way a thread that the machine slows down renders fewer lines instead of
 * holding up the frame. A line is handed to the caller's `emit` on the worker that
 * rendered it, straight after rendering, to be converted out of that
 * worker's runs into the caller's storage for that line; the caller waits
 * for lines in order (bands_wait), so a display still gets them top to
 * bottom. `window` bounds how far ahead of the caller the workers may go:
 * lines y < released + window (bands_release), so a caller that keeps a
 * ring of `window` lines instead of a frame reuses line y's slot for line
 * y + window once it released y.
 *
 * The core stays free of threads: this file is host code (pthreads). The
 * scene and the prepared renderer must stay unchanged until bands_finish.
 */
#ifndef HOST_SIM_BANDS_H
#define HOST_SIM_BANDS_H

#include "celscan.h"

typedef struct bands bands;

/*
 * Line y was rendered into r's runs: convert it out (called on a worker
 * thread). Lines count from the top of the window rendered: device row
 * view_y + y with a viewport (cs_render_opts), row y without.
 */
typedef void (*bands_emit)(void *user, const cs_renderer *r, int y);

/* Starts `threads` worker threads (1..BANDS_MAX_THREADS), each with its workspace; NULL if out of memory. */
bands *bands_new(int threads);
#define BANDS_MAX_THREADS 64

/* The number of cores this process may run on (at least 1): the default thread count. */
int bands_cores(void);

/*
 * The cuts of a frame's cels into `parts` parts of about equal preparation
 * work, as bands_prepare cuts them: part k is cels [cut[k], cut[k + 1]), so
 * `cut` holds parts + 1 entries (for bench's critical path too).
 */
void bands_cut(const cs_scene *scene, int parts, uint32_t *cut);

/*
 * cs_frame_begin on the pool: the frame's cels prepared in one part a thread
 * (the workers' and this one's, cs_frame_begin_part) and joined in r and ws
 * (cs_frame_join), which then hold what cs_frame_begin gives, bit for bit;
 * an error is cs_frame_begin's, with its location. Ends the frame before,
 * if one runs.
 */
cs_status bands_prepare(bands *b, cs_renderer *r, cs_workspace *ws, const cs_scene *scene,
                        const cs_render_opts *opts, cs_error *err);

/*
 * Starts rendering the frame `prepared` holds on the workers, in bands of
 * `chunk` lines (0: four lines for a frame, window >= its height; sixteen
 * bands a thread for a ring), at most `window` lines ahead of
 * the caller's releases. Returns CS_ERR_ARG for a negative chunk, or a
 * window smaller than a band. Ends the frame before, if one runs.
 */
cs_status bands_start(bands *b, const cs_renderer *prepared, int chunk, int window,
                      bands_emit emit, void *user);

/*
 * Line y (device row `row`) to be rendered in r and converted out by the
 * callback itself, on a worker thread: where one call does both in one
 * pass (cs_render_line_px). Lines count as for bands_emit.
 */
typedef void (*bands_render)(void *user, cs_renderer *r, int row, int y);

/* bands_start with the frame's lines rendered by `render` instead of
 * cs_render_line_runs and then emitted. */
cs_status bands_start_render(bands *b, const cs_renderer *prepared, int chunk, int window,
                             bands_render render, void *user);

/* Blocks until line y of the frame (of its window) has been emitted. */
void bands_wait(bands *b, int y);

/*
 * bands_wait that works meanwhile: while line y is not emitted and a band
 * is open, the caller takes it and renders it in `prepared` (the renderer
 * given to bands_start, which it may then no longer use for anything else
 * until bands_finish), emitting its lines as a worker would, on this
 * thread. A pool of N - 1 workers and a helping caller keep N cores busy
 * without a third thread waking to copy lines; from the first helped
 * frame on, chunk 0 counts the caller as a thread.
 */
void bands_help(bands *b, cs_renderer *prepared, int y);
/* The caller is done with every line before y: workers may go on to y + window. */
void bands_release(bands *b, int y);

/*
 * Ends the frame: waits for the lines in hand, lets no more start, and
 * returns the first capacity error in line order (what cs_frame_error of
 * one renderer drawing every line would say), CS_OK if none. Safe to call
 * when no frame runs.
 */
cs_error bands_finish(bands *b);

/* The line in r's runs as 3 * view width linear floats, what cs_render_line gives (for an emit). */
void bands_floats(const cs_renderer *r, float *rgb);

/* Stops and joins the threads, frees everything (NULL is fine). */
void bands_free(bands *b);

#endif /* HOST_SIM_BANDS_H */
