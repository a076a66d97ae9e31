/*
 * lx_null.c - a display that renders every line and shows nothing.
 *
 * It gives celfw a backend for dry runs and for measuring render time alone,
 * with the same deadline accounting as the real backends.
 */
#include <stdlib.h>

#include "lx_display.h"

typedef struct lx_null {
    lx_display d;
    float *line;
} lx_null;

static lx_status null_present(lx_display *d, const lx_source *src, lx_frame_stats *st)
{
    lx_null *n = (lx_null *)d;
    lx_status s = src->begin(src->user, 1);
    if (s != LX_OK)
        return s;
    for (int y = 0; y < d->height; y++) {
        s = src->line(src->user, 0, y, n->line);
        if (s != LX_OK)
            return s;
        st->lines_rendered++;
        uint64_t due = d->frame_start_ns + (uint64_t)(y + 1) * d->frame_period_ns / (uint64_t)d->height;
        if (d->frame_period_ns && lx_now(d->clock) > due)
            st->line_misses++;
    }
    return LX_OK;
}

static bool null_connected(lx_display *d)
{
    (void)d;
    return true;
}

static void null_close(lx_display *d)
{
    lx_null *n = (lx_null *)d;
    free(n->line);
    free(n);
}

static const lx_display_ops null_ops = {"null", 1, null_present, null_connected, null_close};

lx_status lx_null_open(lx_display **out, int width, int height, const lx_clock *clock)
{
    lx_null *n = calloc(1, sizeof *n);
    if (!n)
        return LX_ERR_NOMEM;
    n->line = calloc((size_t)width * 3u, sizeof(float));
    if (!n->line) {
        free(n);
        return LX_ERR_NOMEM;
    }
    n->d.ops = &null_ops;
    n->d.width = width;
    n->d.height = height;
    n->d.clock = clock;
    *out = &n->d;
    return LX_OK;
}
