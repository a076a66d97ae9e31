/*
 * celfw_stream.h - the seam between celfw's input and the cel-stream decoder.
 *
 * celfw hands every received byte to celfw_stream_feed(), in whatever
 * chunks arrived. The decoder builds the next scene in `next` (a second
 * scene store: the one on display is never touched) and stops right after a
 * commit record, returning CELFW_STREAM_COMMIT with the bytes used so far;
 * celfw then swaps the two stores between frames, copies the new front into
 * the back (later transactions may be edits of it) and feeds the rest. A
 * damaged or truncated transaction gives CELFW_STREAM_ERROR with the byte
 * offset and what was wrong; the decoder has dropped it and resynchronises,
 * and the scene on display stays as it was.
 *
 * The decoder itself (core, freestanding) is being written on another branch.
 * Until it lands, celfw links celfw_stream_stub.c, which counts the bytes and
 * decodes nothing; replacing that one file with an adapter over the core's
 * decoder is all celfw needs.
 */
#ifndef CELFW_STREAM_H
#define CELFW_STREAM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "celscan.h"

typedef enum celfw_stream_result {
    CELFW_STREAM_MORE = 0, /* all bytes used; nothing to apply yet */
    CELFW_STREAM_COMMIT,   /* a transaction committed into `next` */
    CELFW_STREAM_ERROR     /* a transaction was dropped; see the error */
} celfw_stream_result;

typedef struct celfw_stream_error {
    uint64_t offset; /* byte offset in the stream (since start or the last reset) */
    char what[160];
} celfw_stream_error;

typedef struct celfw_stream celfw_stream;

/* true when a real decoder is linked (false for the stub). */
bool celfw_stream_available(void);
celfw_stream *celfw_stream_new(void);
void celfw_stream_free(celfw_stream *s);
/* Feeds n bytes; *used says how many were consumed (all, unless COMMIT). */
celfw_stream_result celfw_stream_feed(celfw_stream *s, const uint8_t *p, size_t n, size_t *used,
                                      cs_scene *next, celfw_stream_error *err);
/* The byte sequence ended (client gone): drop any partial transaction. */
void celfw_stream_reset(celfw_stream *s);

#endif /* CELFW_STREAM_H */
