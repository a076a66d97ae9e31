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
 *
 * bands_prepare hands out the parts of a frame's preparation the same way:
 * part 0 to the caller, in its own renderer, and part k >= 1 to whichever
 * thread takes it first, in worker k - 1's renderer and workspace (free
 * until the frame's bands start); the caller helps with the parts left and
 * joins them (cs_frame_join) once the last one is in.
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
        while (!b->stop && !band_open(b) && b->next_part >= b->parts)
            pthread_cond_wait(&b->work, &b->mu);
        if (b->stop)
            break;
        if (b->next_part < b->parts) {
            prepare_part(b);
            continue;
        }
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

/*
 * The cels' cuts into `parts` parts of about equal work: a cel weighs the
 * control points of its contours (what cs__contour_next and the splitting
 * go through) and a few more for itself and each region.
 */
static void cut_cels(bands *b, const cs_scene *scene, int parts)
{
    uint64_t total = 0;
    for (int pass = 0; pass < 2; pass++) {
        uint64_t sum = 0;
        int k = 1;
        b->cut[0] = 0;
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
                b->cut[k++] = ci + 1;
        }
        total = sum;
        while (k <= parts)
            b->cut[k++] = scene->cel_count;
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
    cut_cels(b, scene, parts);
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
