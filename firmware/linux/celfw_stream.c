/*
 * celfw_stream.c - celfw's stream decoder seam (celfw_stream.h) over the
 * core's cel-stream decoder (cs_stream, core/cs_stream.c).
 *
 * The core decoder works on two scene stores it is given once; celfw owns
 * its two stores and exchanges them at every commit. The two agree because
 * the adapter swaps the decoder's stores (cs_stream_swap) at the same moment
 * it tells celfw to swap its own, so from then on `shown` and `next` are the
 * decoder's front and back. The decoder starts on the first bytes, with
 * celfw's scene on display as a valid front (patches may edit a built-in or
 * JSON scene), and again after each reset, so offsets in messages count
 * from the start of the current connection or file.
 *
 * Errors are turned into one line of text here (status, the decoder's
 * explanation, the scene location for validation errors, and what was
 * dropped), so the log says what was wrong and where without celfw knowing
 * the decoder's types.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celfw_stream.h"

struct celfw_stream {
    cs_stream st;
    bool started;
    celfw_stream_check check;
    void *check_user;
};

bool celfw_stream_available(void)
{
    return true;
}

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

/* "<status>[: <explanation>][ (cel c, region r, ...)] (<what was dropped>)" */
static void describe(const cs_stream_error *e, celfw_stream_error *out)
{
    char *b = out->what;
    size_t len = sizeof out->what, n = 0;
    out->offset = e->at;
#define ADD(...)                                                                                   \
    do {                                                                                           \
        if (n < len) {                                                                             \
            int k_ = snprintf(b + n, len - n, __VA_ARGS__);                                        \
            n = k_ < 0 ? len : n + (size_t)k_;                                                     \
        }                                                                                          \
    } while (0)
    const char *status = cs_status_str(e->status);
    ADD("%s", status);
    if (e->what && strcmp(e->what, status) != 0)
        ADD(": %s", e->what);
    if (e->where.cel >= 0) {
        ADD(" (cel %d", (int)e->where.cel);
        if (e->where.region >= 0)
            ADD(", region %d", (int)e->where.region);
        if (e->where.contour >= 0)
            ADD(", contour %d", (int)e->where.contour);
        if (e->where.item >= 0)
            ADD(", item %d", (int)e->where.item);
        ADD(")");
    }
    if (e->status == CS_ERR_STREAM_SYNC)
        ADD(" (bytes skipped from byte %llu)", (unsigned long long)e->offset);
    else
        ADD(" (transaction at byte %llu dropped)", (unsigned long long)e->offset);
#undef ADD
}

celfw_stream_result celfw_stream_feed(celfw_stream *s, const uint8_t *p, size_t n, size_t *used,
                                      cs_scene *shown, cs_scene *next, celfw_stream_error *err)
{
    *used = 0;
    if (!s->started || s->st.front != shown || s->st.back != next) {
        /* First bytes, or stores celfw replaced behind the decoder's back:
         * start over on the stores as they are now. */
        if (cs_stream_init(&s->st, shown, true, next) != CS_OK)
            return CELFW_STREAM_MORE;
        s->started = true;
    }
    cs_stream_event ev = cs_stream_feed(&s->st, p, n, used);
    if (ev == CS_STREAM_COMMIT) {
        cs_status why = CS_OK;
        cs_error where;
        const char *no = s->check ? s->check(s->check_user, next, &why, &where) : NULL;
        if (no) {
            cs_stream_refuse(&s->st, why, no, &where);
            describe(cs_stream_last_error(&s->st), err);
            return CELFW_STREAM_ERROR;
        }
        cs_stream_swap(&s->st); /* celfw swaps its own two stores in step */
        return CELFW_STREAM_COMMIT;
    }
    if (ev == CS_STREAM_ERROR) {
        describe(cs_stream_last_error(&s->st), err);
        return CELFW_STREAM_ERROR;
    }
    return CELFW_STREAM_MORE;
}

celfw_stream_result celfw_stream_reset(celfw_stream *s, celfw_stream_error *err)
{
    if (!s->started)
        return CELFW_STREAM_MORE;
    cs_stream_event ev = cs_stream_finish(&s->st);
    if (ev == CS_STREAM_ERROR) {
        describe(cs_stream_last_error(&s->st), err);
        return CELFW_STREAM_ERROR;
    }
    /* Nothing more to report: the next sequence starts afresh, at offset 0.
     * (A commit cannot wait here: every commit was swapped in when fed.) */
    s->started = false;
    return CELFW_STREAM_MORE;
}
