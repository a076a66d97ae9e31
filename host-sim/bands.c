/*
 * bands.c - worker threads rendering bands of one frame's lines (bands.h).
 *
 * One mutex guards the frame's bookkeeping: the next band to hand out, the
 * lines emitted, how far the caller released. It is taken twice per band,
 * not per line, so a band of tens of lines costs the workers nothing they
 * would notice. Workers wait on `work` (a frame started, the caller
 * released lines, the pool stops); the caller waits on `done` (lines
 * emitted, workers gone idle).
 *
 * Each worker shares the frame into its own renderer the first time it
 * takes a band of it, on its own thread, so clearing a workspace's line
 * state runs in parallel too. A caller that helps (bands_help) takes bands
 * from the same queue and renders them in the renderer that prepared the
 * frame, which needs no share: its workspace is the frame's.
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
    int next;            /* first line of the next band to hand out */
    int released;        /* lines before this the caller is done with */
    int busy;            /* workers inside a band */
    bands_emit emit;
    void *user;
    unsigned char *ready; /* per line: emitted */
    cs_error err;        /* the first capacity error in line order */
};

int bands_cores(void)
{
    cpu_set_t set;
    if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0)
        return CPU_COUNT(&set);
    return 1;
}

/* A band may start: the frame runs, lines remain, and the band fits the window. */
static bool band_open(const bands *b)
{
    int end = b->next + b->chunk < b->height ? b->next + b->chunk : b->height;
    return b->running && b->next < b->height && end <= b->released + b->window;
}

/* Under mu: takes the next band, [*y0, *y1), for a renderer of the frame. */
static void take_band(bands *b, int *y0, int *y1)
{
    *y0 = b->next;
    *y1 = *y0 + b->chunk < b->height ? *y0 + b->chunk : b->height;
    b->next = *y1;
    b->busy++;
}

/* Renders lines [y0, y1) of the window in r (a renderer of the frame) and emits them; mu not held. */
static void render_band(const bands *b, cs_renderer *r, int y0, int y1)
{
    for (int y = y0; y < y1; y++) {
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

static void *worker_main(void *arg)
{
    worker *w = arg;
    bands *b = w->pool;
    pthread_mutex_lock(&b->mu);
    for (;;) {
        while (!b->stop && !band_open(b))
            pthread_cond_wait(&b->work, &b->mu);
        if (b->stop)
            break;
        int y0, y1;
        take_band(b, &y0, &y1);
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

cs_status bands_start(bands *b, const cs_renderer *prepared, int chunk, int window,
                      bands_emit emit, void *user)
{
    if (!b || !prepared || !emit || chunk < 0 || prepared->vh > CS_CFG_MAX_HEIGHT)
        return CS_ERR_ARG;
    if (chunk == 0) {
        /* Sixteen bands a thread: a thread the machine slows down takes
         * fewer, and the last band to end holds up the others by half a
         * band on average (Many-blobs exact at 1920x1080 on 2 threads: the
         * renderers' idle time after their last band went from ~1.7 ms a
         * frame with four bands a thread to ~0.3 ms). A band that does not
         * follow its renderer's last one costs a restart: the active list
         * rebuilt and one row of exact-area ends solved afresh, ~80 k
         * instructions (bench --band), ~0.015 ms; 32 bands instead of 8 add
         * at most ~0.4 ms of a core's time a frame. More bands would cost
         * more than the shorter tail saves. */
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
    b->emit = emit;
    b->user = user;
    for (int y = 0; y < b->height; y++)
        b->ready[y] = 0;
    b->err = (cs_error){CS_OK, -1, -1, -1, -1};
    b->running = true;
    pthread_cond_broadcast(&b->work);
    pthread_mutex_unlock(&b->mu);
    return CS_OK;
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
    while (b->running && y >= 0 && y < b->height && !b->ready[y]) {
        if (!band_open(b) || prepared != b->prepared) {
            pthread_cond_wait(&b->done, &b->mu);
            continue;
        }
        int y0, y1;
        take_band(b, &y0, &y1);
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
