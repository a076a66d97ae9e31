/*
 * cels_read.c - decode a whole cel stream on the host (see cels_read.h).
 *
 * The file is fed in 16 KiB reads: the decoder keeps no input buffer, so the
 * chunk size only trades system calls against nothing.
 */
#include "cels_read.h"
#include "celscan_private.h"

#include <errno.h>
#include <string.h>

void cels_format_error(const cs_stream_error *e, char *buf, size_t len)
{
    int n = snprintf(buf, len, "byte %llu: ", (unsigned long long)e->at);
    if (n >= 0 && (size_t)n < len)
        cs_stream_error_text(e, 0, buf + n, len - (size_t)n);
}

typedef struct reader {
    cs_stream st;
    const char *name;
    FILE *errf;
    cels_read_stats stats;
} reader;

static void handle(reader *r, cs_stream_event ev)
{
    if (ev == CS_STREAM_COMMIT) {
        cs_stream_swap(&r->st);
        r->stats.commits++;
    } else if (ev == CS_STREAM_ERROR) {
        char msg[256];
        cels_format_error(cs_stream_last_error(&r->st), msg, sizeof msg);
        if (r->errf)
            fprintf(r->errf, "%s: %s\n", r->name, msg);
        r->stats.errors++;
    }
}

static void feed(reader *r, const uint8_t *data, size_t len)
{
    size_t off = 0;
    while (off < len) {
        size_t used;
        cs_stream_event ev = cs_stream_feed(&r->st, data + off, len - off, &used);
        off += used;
        handle(r, ev);
    }
}

static const cs_scene *finish(reader *r, cels_read_stats *stats)
{
    cs_stream_event ev;
    size_t used;
    while ((ev = cs_stream_feed(&r->st, NULL, 0, &used)) != CS_STREAM_MORE)
        handle(r, ev);
    while ((ev = cs_stream_finish(&r->st)) != CS_STREAM_MORE)
        handle(r, ev);
    r->stats.skipped = r->st.skipped;
    if (stats)
        *stats = r->stats;
    return cs_stream_scene(&r->st);
}

const cs_scene *cels_decode_buffer(const uint8_t *data, size_t len, const char *name,
                                   cs_scene *a, cs_scene *b, FILE *errf, cels_read_stats *stats)
{
    reader r;
    memset(&r.stats, 0, sizeof r.stats);
    r.name = name ? name : "stream";
    r.errf = errf;
    if (cs_stream_init(&r.st, a, false, b) != CS_OK)
        return NULL;
    feed(&r, data, len);
    return finish(&r, stats);
}

const cs_scene *cels_read_file(const char *path, cs_scene *a, cs_scene *b, FILE *errf,
                               cels_read_stats *stats)
{
    reader r;
    memset(&r.stats, 0, sizeof r.stats);
    r.name = path;
    r.errf = errf;
    if (stats)
        memset(stats, 0, sizeof *stats);
    if (cs_stream_init(&r.st, a, false, b) != CS_OK)
        return NULL;
    FILE *f = fopen(path, "rb");
    if (!f) {
        if (errf)
            fprintf(errf, "%s: cannot open: %s\n", path, strerror(errno));
        return NULL;
    }
    uint8_t chunk[16384];
    size_t n;
    while ((n = fread(chunk, 1, sizeof chunk, f)) > 0)
        feed(&r, chunk, n);
    bool bad = ferror(f) != 0;
    fclose(f);
    if (bad) {
        if (errf)
            fprintf(errf, "%s: read error\n", path);
        return NULL;
    }
    return finish(&r, stats);
}
