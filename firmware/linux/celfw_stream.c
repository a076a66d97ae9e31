/*
 * celfw_stream.c - celfw's stream decoder seam (celfw_stream.h) over the
 * core's cel-stream decoder (cs_stream, core/cs_stream.c).
 *
 * Each frame arrives whole (celfw_frame.c cut it out of its input, the
 * trust check passed it), so the decoder starts afresh on every frame, on
 * celfw's two stores as they are at that moment, with the scene on display
 * as a valid front (patches may edit a built-in or JSON scene); frames from
 * different inputs can then follow one another in any order. The decoder's
 * offsets count from the frame; the frame's place in its input is added,
 * so messages count from the start of the connection or file.
 *
 * Errors are turned into one line of text here (cs_stream_error_text:
 * status, the decoder's explanation, the scene location for validation
 * errors, and what was dropped), so the log says what was wrong and where
 * without celfw knowing the decoder's types.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celfw_stream.h"
#include "celscan_private.h"

struct celfw_stream {
    cs_stream st;
    celfw_stream_check check;
    void *check_user;
};

void celfw_stream_set_check(celfw_stream *s, celfw_stream_check check, void *user)
{
    s->check = check;
    s->check_user = user;
}

celfw_stream *celfw_stream_new(void)
{
    return calloc(1, sizeof(celfw_stream));
}

void celfw_stream_free(celfw_stream *s)
{
    free(s);
}

/* The core's one line (cs_stream_error_text); the fault's offset apart. */
static void describe(const cs_stream_error *e, uint64_t base, celfw_stream_error *out)
{
    out->offset = base + e->at;
    cs_stream_error_text(e, base, out->what, sizeof out->what);
}

void celfw_stream_describe(cs_status status, const char *what, uint64_t offset, uint64_t at,
                           celfw_stream_error *err)
{
    cs_stream_error e;
    memset(&e, 0, sizeof e);
    e.status = status;
    e.offset = offset;
    e.at = at;
    e.what = what;
    e.where.cel = e.where.region = e.where.contour = e.where.item = -1;
    describe(&e, 0, err);
}

celfw_stream_result celfw_stream_frame(celfw_stream *s, const uint8_t *p, size_t n, uint64_t base,
                                       cs_scene *shown, cs_scene *next, celfw_stream_error *err)
{
    if (cs_stream_init(&s->st, shown, true, next) != CS_OK)
        return CELFW_STREAM_MORE;
    celfw_stream_result r = CELFW_STREAM_MORE;
    /* A whole frame gives at most one event worth telling (a commit or the
     * reason it was dropped); the loop only drains what a skipped frame leaves. */
    for (;;) {
        size_t used = 0;
        cs_stream_event ev = cs_stream_feed(&s->st, p, n, &used);
        p += used;
        n -= used;
        if (ev == CS_STREAM_MORE && n == 0)
            ev = cs_stream_finish(&s->st);
        if (ev == CS_STREAM_COMMIT) {
            cs_status why = CS_OK;
            cs_error where;
            const char *no = s->check ? s->check(s->check_user, next, &why, &where) : NULL;
            if (no) {
                cs_stream_refuse(&s->st, why, no, &where);
                describe(cs_stream_last_error(&s->st), base, err);
                return CELFW_STREAM_ERROR;
            }
            cs_stream_swap(&s->st); /* celfw swaps its own two stores in step */
            return CELFW_STREAM_COMMIT;
        }
        if (ev == CS_STREAM_ERROR && r == CELFW_STREAM_MORE) {
            describe(cs_stream_last_error(&s->st), base, err);
            r = CELFW_STREAM_ERROR;
        }
        if (ev == CS_STREAM_MORE && n == 0)
            return r;
    }
}
