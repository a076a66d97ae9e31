/*
 * celfw_stream_stub.c - stands in for the cel-stream decoder until it lands.
 *
 * It consumes every byte and never commits, so celfw keeps showing its
 * configured scene while the input path (TCP, tty, stdin, file), the byte
 * counts and the reset-on-disconnect logic all run for real. Replace this
 * file with an adapter over the core's decoder (see celfw_stream.h).
 */
#include <stdlib.h>

#include "celfw_stream.h"

struct celfw_stream {
    uint64_t offset;
};

bool celfw_stream_available(void)
{
    return false;
}

celfw_stream *celfw_stream_new(void)
{
    return calloc(1, sizeof(celfw_stream));
}

void celfw_stream_free(celfw_stream *s)
{
    free(s);
}

celfw_stream_result celfw_stream_feed(celfw_stream *s, const uint8_t *p, size_t n, size_t *used,
                                      cs_scene *next, celfw_stream_error *err)
{
    (void)p;
    (void)next;
    (void)err;
    s->offset += n;
    *used = n;
    return CELFW_STREAM_MORE;
}

void celfw_stream_reset(celfw_stream *s)
{
    s->offset = 0;
}
