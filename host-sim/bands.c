/*
 * bands.c - worker threads rendering bands of one frame's lines (bands.h).
 *
 * One mutex guards the frame's bookkeeping: the lines no thread took yet,
 * each thread's span, the lines emitted, how far the caller released. It
 * is taken twice per band, not per line, so a band costs the workers
 * nothing they would notice. Workers wait on `work` (a frame started, the
 * caller released lines, the pool stops); the caller waits on `done`
 * (lines emitted, workers gone idle).
 *
 * For a frame in storage a thread takes a span of lines, not a band: the
 * caller the back half of the frame, the first worker the rest, each later
 * one the back half of the largest span left, and each renders its span
 * band after band, going on where its renderer stopped; a restart (a band
 * that does not follow its renderer's last) comes only with a span taken,
 * about once a thread a frame. For a ring the bands go out from the top in
 * turn (next_band).
 *
 * Each worker shares the frame into its own renderer the first time it
 * takes a band of it, on its own thread, so clearing a workspace's line
 * state runs in parallel too. A caller that helps (bands_help) takes bands
 * the same way and renders them in the renderer that prepared the frame,
 * which needs no share: its workspace is the frame's.
 *
 * bands_prepare hands out the parts of a frame's preparation the same way:
 * part 0 to the caller, in its own renderer, and part k >= 1 to whichever
 * thread takes it first, in worker k - 1's renderer and workspace (free
 * until the frame's bands start); the caller helps with the parts left and
 * joins them (cs_frame_join) once the last one is in. On Many-blobs exact
 * at 1920x1080 with 2 threads the serial 4.6 M instructions of preparation
 * became two parts of 2.0 M and a 0.17 M join, and with the spans the
 * frame took 3-7 % less wall time (medians of interleaved rounds, two
 * cores free).
 */
#define _GNU_SOURCE /* sched_getaffinity */
#include <pthread.h>
#include <sched.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "bands.h"
#include "celscan_private.h"

typedef struct worker {
    bands *pool;
    pthread_t thread;
    cs_workspace *ws;
    cs_renderer r;
    unsigned gen;        /* the frame r was shared from */
} worker;

/* Lines [lo, hi) of the frame a thread goes on with, band after band. */
typedef struct span {
    int lo, hi;
} span;

struct bands {
    pthread_mutex_t mu;
    pthread_cond_t work, done;
    int threads, started;
    worker w[BANDS_MAX_THREADS];
    /* The frame, under mu. */
    const cs_renderer *prepared;
    unsigned gen;        /* counts frames, so a worker knows to share the new one */
    bool running, stop;
    bool helped;         /* the caller renders bands too (bands_help): one more thread */
    int height, chunk, window; /* lines of the window rendered (cs_renderer vh) */
    int top;             /* device row of window line 0 (vy) */
    int next, last;      /* lines [next, last) no thread has taken yet */
    bool ring;           /* window < height: one band at a time from the top */
    span own[BANDS_MAX_THREADS + 1]; /* per worker, and the helping caller's last */
    int released;        /* lines before this the caller is done with */
    int busy;            /* workers inside a band */
    bands_emit emit;     /* after cs_render_line_runs, or */
    bands_render render; /* instead of it */
    void *user;
    unsigned char *ready; /* per line: emitted */
    cs_error err;        /* the first capacity error in line order */
    /* A frame prepared in parts (bands_prepare), under mu: part k is cels
     * [cut[k], cut[k + 1]); parts [next_part, parts) are still to take. */
    const cs_scene *scene;
    const cs_render_opts *opts;
    uint32_t cut[BANDS_MAX_THREADS + 2];
    int parts, next_part, parts_busy;
    cs_status part_st[BANDS_MAX_THREADS + 1];
};

int bands_cores(void)
{
    cpu_set_t set;
    if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0)
        return CPU_COUNT(&set);
    return 1;
}

/*
 * Under mu: the next band thread t (a worker's index, or b->threads for the
 * caller) may start, [*y0, *y1): the next of its own span, which its
 * renderer goes on with at no cost; else, once its span is used up, the
 * lines no thread took yet (for a frame in storage all of them, or their
 * back half for the caller; one band for a ring); else the back half of the largest span another thread still
 * has, if that is more than two bands, at the cost of one restart (the
 * active list rebuilt, a first row of exact ends solved afresh: ~80 k
 * instructions on Many-blobs). So each thread restarts about once a
 * frame, not once a band, and the last band to end holds up the others by
 * at most two bands. Takes it (the spans moved, the band counted busy)
 * when `take`; false if none may start now.
 */
static bool next_band(bands *b, int t, const cs_renderer *r, bool take, int *y0, int *y1)
{
    if (!b->running)
        return false;
    /* A renderer keeps the first capacity error it meets: once it has one,
     * it takes no lines above its last, so that its error stays the first
     * of its lines in line order (bands_finish). The lines it leaves are a
     * worker's: the untaken ones go whole to the first worker that asks,
     * and one that has met no error yet this frame has no such floor. */
    int floor = r && cs_frame_error(r).status != CS_OK ? r->next_line : 0;
    int lo = b->own[t].lo, hi = b->own[t].hi, from = t;
    if (lo >= hi && b->next < b->last) {
        lo = b->next;
        hi = b->ring && lo + b->chunk < b->last ? lo + b->chunk : b->last;
        /* The caller shows the lines in order as they are done: it takes
         * the back half and leaves the front to a worker, so that it
         * shows the worker's lines while it renders its own, not all of
         * them after. */
        if (!b->ring && t == b->threads && hi - lo > 2 * b->chunk)
            lo = hi - (hi - lo) / 2;
        if (lo < floor)
            return false;
        from = -1;
    } else if (lo >= hi) {
        int most = 2 * b->chunk;
        for (int k = 0; k <= b->threads; k++) {
            int size = b->own[k].hi - b->own[k].lo;
            if (size > most && b->own[k].hi - size / 2 >= floor) {
                most = size;
                from = k;
            }
        }
        if (from == t)
            return false;
        hi = b->own[from].hi;
        lo = hi - most / 2;
    }
    int end = lo + b->chunk < hi ? lo + b->chunk : hi;
    if (end > b->released + b->window)
        return false;
    if (take) {
        if (from < 0 && lo == b->next)
            b->next = hi;
        else if (from < 0)
            b->last = lo;
        else
            b->own[from].hi = from == t ? hi : lo;
        b->own[t] = (span){end, hi};
        *y0 = lo;
        *y1 = end;
        b->busy++;
    }
    return true;
}

/* Renders lines [y0, y1) of the window in r (a renderer of the frame) and emits them; mu not held. */
static void render_band(const bands *b, cs_renderer *r, int y0, int y1)
{
    for (int y = y0; y < y1; y++) {
        if (b->render) {
            b->render(b->user, r, b->top + y, y);
            continue;
        }
        (void)cs_render_line_runs(r, b->top + y); /* y is within the window */
        b->emit(b->user, r, y);
    }
}

/* Under mu: the band [y0, y1) that r rendered is done; its first capacity error counts. */
static void end_band(bands *b, const cs_renderer *r, int y0, int y1)
{
    for (int y = y0; y < y1; y++)
        b->ready[y] = 1;
    cs_error e = cs_frame_error(r);
    if (e.status != CS_OK && (b->err.status == CS_OK || e.item < b->err.item))
        b->err = e;
    b->busy--;
    pthread_cond_broadcast(&b->done);
}

/* Under mu, with parts left: prepares the next part, in worker k - 1's
 * renderer and workspace; mu is released meanwhile. */
static void prepare_part(bands *b)
{
    int k = b->next_part++;
    b->parts_busy++;
    pthread_mutex_unlock(&b->mu);
    worker *w = &b->w[k - 1];
    cs_error e;
    cs_status st = cs_frame_begin_part(&w->r, w->ws, b->scene, b->opts, b->cut[k], b->cut[k + 1], &e);
    pthread_mutex_lock(&b->mu);
    b->part_st[k] = st;
    b->parts_busy--;
    pthread_cond_broadcast(&b->done);
}

static void *worker_main(void *arg)
{
    worker *w = arg;
    bands *b = w->pool;
    pthread_mutex_lock(&b->mu);
    for (;;) {
        int y0, y1, t = (int)(w - b->w);
        const cs_renderer *r = w->gen == b->gen ? &w->r : NULL; /* NULL: to be shared */
        while (!b->stop && b->next_part >= b->parts && !next_band(b, t, r, false, &y0, &y1)) {
            pthread_cond_wait(&b->work, &b->mu);
            r = w->gen == b->gen ? &w->r : NULL;
        }
        if (b->stop)
            break;
        if (b->next_part < b->parts) {
            prepare_part(b);
            continue;
        }
        next_band(b, t, r, true, &y0, &y1);
        bool fresh = w->gen != b->gen;
        w->gen = b->gen;
        pthread_mutex_unlock(&b->mu);

        /* The prepared renderer's workspace is another's: sharing cannot fail.
         * The frame's fields (prepared, top, emit, user) stay until
         * bands_finish, which waits for this band. */
        if (fresh)
            (void)cs_frame_share(&w->r, w->ws, b->prepared);
        render_band(b, &w->r, y0, y1);

        pthread_mutex_lock(&b->mu);
        end_band(b, &w->r, y0, y1);
    }
    pthread_mutex_unlock(&b->mu);
    return NULL;
}

bands *bands_new(int threads)
{
    if (threads < 1 || threads > BANDS_MAX_THREADS)
        return NULL;
    bands *b = calloc(1, sizeof *b);
    if (!b)
        return NULL;
    b->threads = threads;
    b->ready = calloc(CS_CFG_MAX_HEIGHT, 1);
    if (!b->ready || pthread_mutex_init(&b->mu, NULL) != 0) {
        free(b->ready);
        free(b);
        return NULL;
    }
    pthread_cond_init(&b->work, NULL);
    pthread_cond_init(&b->done, NULL);
    for (int i = 0; i < threads; i++) {
        worker *w = &b->w[i];
        w->pool = b;
        w->ws = calloc(1, sizeof *w->ws);
        if (!w->ws || pthread_create(&w->thread, NULL, worker_main, w) != 0) {
            free(w->ws);
            w->ws = NULL;
            bands_free(b);
            return NULL;
        }
        b->started++;
    }
    return b;
}

/* bands_start or bands_start_render: one of emit and render is set. */
static cs_status start(bands *b, const cs_renderer *prepared, int chunk, int window,
                       bands_emit emit, bands_render render, void *user)
{
    if (!b || !prepared || (!emit && !render) || chunk < 0 || prepared->vh > CS_CFG_MAX_HEIGHT)
        return CS_ERR_ARG;
    if (chunk == 0 && window >= prepared->vh) {
        /* A frame in storage: bands of four lines. A thread goes on with
         * its own span band after band and restarts only when it takes
         * half of another's (next_band), so small bands cost a lock each
         * (~0.1 us) and no restart, and the threads end within two bands
         * of each other. Before the spans, bands were handed out in turn
         * from the top and nearly every one was a restart (~80 k
         * instructions, bench --band): sixteen a thread were the balance
         * between those and the idle tail. */
        chunk = 4;
    } else if (chunk == 0) {
        /* A ring: bands from the top in turn, each a restart; sixteen a
         * thread, so a thread the machine slows down takes fewer, and the
         * last band to end holds up the others by half a band on average
         * (Many-blobs exact at 1920x1080 on 2 threads: the renderers' idle
         * time after their last band went from ~1.7 ms a frame with four
         * bands a thread to ~0.3 ms), while 32 restarts instead of 8 add
         * at most ~0.4 ms of a core's time a frame. */
        int bands_n = 16 * (b->threads + (b->helped ? 1 : 0));
        chunk = (prepared->vh + bands_n - 1) / bands_n;
    }
    if (chunk > prepared->vh)
        chunk = prepared->vh; /* one band: the frame */
    if (window < chunk)
        return CS_ERR_ARG;
    (void)bands_finish(b);
    pthread_mutex_lock(&b->mu);
    b->prepared = prepared;
    b->gen++;
    b->height = prepared->vh;
    b->top = prepared->vy;
    b->chunk = chunk;
    b->window = window;
    b->next = b->released = 0;
    b->last = b->height;
    b->ring = window < b->height;
    for (int t = 0; t <= b->threads; t++)
        b->own[t] = (span){0, 0};
    b->emit = emit;
    b->render = render;
    b->user = user;
    for (int y = 0; y < b->height; y++)
        b->ready[y] = 0;
    b->err = (cs_error){CS_OK, -1, -1, -1, -1};
    b->running = true;
    pthread_cond_broadcast(&b->work);
    pthread_mutex_unlock(&b->mu);
    return CS_OK;
}

cs_status bands_start(bands *b, const cs_renderer *prepared, int chunk, int window,
                      bands_emit emit, void *user)
{
    return start(b, prepared, chunk, window, emit, NULL, user);
}

cs_status bands_start_render(bands *b, const cs_renderer *prepared, int chunk, int window,
                             bands_render render, void *user)
{
    return start(b, prepared, chunk, window, NULL, render, user);
}

/*
 * A cel weighs the control points of its contours (what cs__contour_next
 * and the splitting go through) and a few more for itself and each region.
 */
void bands_cut(const cs_scene *scene, int parts, uint32_t *cut)
{
    uint64_t total = 0;
    for (int pass = 0; pass < 2; pass++) {
        uint64_t sum = 0;
        int k = 1;
        cut[0] = 0;
        for (uint32_t ci = 0; ci < scene->cel_count; ci++) {
            const cs_cel *cel = &scene->cels[ci];
            uint64_t wgt = 4;
            for (uint32_t ri = cel->first_region; ri < cel->first_region + cel->region_count; ri++) {
                const cs_region *reg = &scene->regions[ri];
                wgt += 4;
                for (uint32_t c = 0; c < reg->contour_count; c++)
                    wgt += scene->contours[reg->first_contour + c].point_count;
            }
            sum += wgt;
            /* Part k - 1 ends after the cel that takes the sum to k / parts of the whole. */
            while (pass == 1 && k < parts && sum * (uint64_t)parts >= total * (uint64_t)k)
                cut[k++] = ci + 1;
        }
        total = sum;
        while (k <= parts)
            cut[k++] = scene->cel_count;
    }
}

cs_status bands_prepare(bands *b, cs_renderer *r, cs_workspace *ws, const cs_scene *scene,
                        const cs_render_opts *opts, cs_error *err)
{
    int parts = b->threads + 1 < CS_FRAME_MAX_PARTS ? b->threads + 1 : CS_FRAME_MAX_PARTS;
    if (!scene || scene->cel_count < 2)
        return cs_frame_begin(r, ws, scene, opts, err);
    (void)bands_finish(b); /* the last frame's bands read r's workspace */
    pthread_mutex_lock(&b->mu);
    b->scene = scene;
    b->opts = opts;
    bands_cut(scene, parts, b->cut);
    b->parts = parts;
    b->next_part = 1;
    pthread_cond_broadcast(&b->work);
    pthread_mutex_unlock(&b->mu);

    cs_status st = cs_frame_begin_part(r, ws, scene, opts, 0, b->cut[1], err);
    const cs_renderer *done[BANDS_MAX_THREADS];
    pthread_mutex_lock(&b->mu);
    while (b->next_part < b->parts)
        prepare_part(b);
    while (b->parts_busy > 0)
        pthread_cond_wait(&b->done, &b->mu);
    for (int k = 1; k < parts; k++) {
        if (b->part_st[k] != CS_OK)
            st = b->part_st[k];
        done[k - 1] = &b->w[k - 1].r;
    }
    b->parts = b->next_part = 0;
    pthread_mutex_unlock(&b->mu);
    if (st == CS_OK && cs_frame_join(r, done, parts - 1) == CS_OK)
        return CS_OK;
    /* A part failed or the whole overflows: one call says where, as without parts. */
    return cs_frame_begin(r, ws, scene, opts, err);
}

void bands_wait(bands *b, int y)
{
    pthread_mutex_lock(&b->mu);
    while (b->running && y >= 0 && y < b->height && !b->ready[y])
        pthread_cond_wait(&b->done, &b->mu);
    pthread_mutex_unlock(&b->mu);
}

void bands_help(bands *b, cs_renderer *prepared, int y)
{
    pthread_mutex_lock(&b->mu);
    b->helped = true;
    int y0, y1;
    while (b->running && y >= 0 && y < b->height && !b->ready[y]) {
        if (prepared != b->prepared || !next_band(b, b->threads, prepared, true, &y0, &y1)) {
            pthread_cond_wait(&b->done, &b->mu);
            continue;
        }
        pthread_mutex_unlock(&b->mu);
        render_band(b, prepared, y0, y1);
        pthread_mutex_lock(&b->mu);
        end_band(b, prepared, y0, y1);
    }
    pthread_mutex_unlock(&b->mu);
}

void bands_release(bands *b, int y)
{
    pthread_mutex_lock(&b->mu);
    if (y > b->released) {
        b->released = y;
        pthread_cond_broadcast(&b->work);
    }
    pthread_mutex_unlock(&b->mu);
}

cs_error bands_finish(bands *b)
{
    pthread_mutex_lock(&b->mu);
    b->running = false; /* no band starts; those in hand end */
    while (b->busy > 0)
        pthread_cond_wait(&b->done, &b->mu);
    cs_error e = b->err;
    pthread_mutex_unlock(&b->mu);
    return e;
}

void bands_floats(const cs_renderer *r, float *rgb)
{
    for (int x = 0; x < r->vw;) {
        float c[3];
        int e = cs_line_run(r, x, c);
        for (; x < e; x++)
            memcpy(&rgb[3 * x], c, sizeof c);
    }
}

void bands_free(bands *b)
{
    if (!b)
        return;
    pthread_mutex_lock(&b->mu);
    b->stop = true;
    b->running = false;
    pthread_cond_broadcast(&b->work);
    pthread_mutex_unlock(&b->mu);
    for (int i = 0; i < b->started; i++)
        pthread_join(b->w[i].thread, NULL);
    for (int i = 0; i < b->threads; i++)
        free(b->w[i].ws);
    pthread_cond_destroy(&b->work);
    pthread_cond_destroy(&b->done);
    pthread_mutex_destroy(&b->mu);
    free(b->ready);
    free(b);
}
