/*
 * celfw_stream.h - the seam between celfw's input and the cel-stream decoder.
 *
 * celfw hands every received byte to celfw_stream_feed(), in whatever
 * chunks arrived, with its two scene stores: `shown`, the one on display,
 * and `next`, the other. The decoder (the core's cs_stream, docs/STREAM.md)
 * builds the next scene in `next` (a patch transaction starts from a copy
 * of `shown`, which itself is never written) and stops right after a
 * transaction that arrived whole and valid, returning CELFW_STREAM_COMMIT
 * with the bytes used so far. celfw then makes `next` the scene on display,
 * between frames, and feeds the rest with the two stores exchanged. A
 * damaged, truncated, oversized or invalid transaction, or bytes outside any
 * transaction, give CELFW_STREAM_ERROR with the byte offset of the fault and
 * what was wrong; the decoder has dropped it, resynchronises on the next
 * transaction header, and the scene on display stays as it was.
 *
 * Offsets count from the start of the current byte sequence: a TCP client's
 * connection, a file, stdin. celfw_stream_reset() ends a sequence (client
 * gone): a transaction left open is dropped and reported, and the next
 * sequence counts from 0 again. Whatever scene celfw shows when the stream
 * starts (a built-in or JSON --scene, or an empty canvas) is the one the
 * first patch transactions apply to.
 */
#ifndef CELFW_STREAM_H
#define CELFW_STREAM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "celscan.h"

typedef enum celfw_stream_result {
    CELFW_STREAM_MORE = 0, /* all bytes used; nothing to apply yet */
    CELFW_STREAM_COMMIT,   /* a transaction committed into `next`: show it */
    CELFW_STREAM_ERROR     /* something was dropped; see the error */
} celfw_stream_result;

typedef struct celfw_stream_error {
    uint64_t offset; /* byte offset of the fault (since the start or the last reset) */
    char what[240];  /* what was wrong, and what was dropped from which offset */
} celfw_stream_error;

typedef struct celfw_stream celfw_stream;

/* true when a real decoder is linked. */
bool celfw_stream_available(void);
celfw_stream *celfw_stream_new(void);
void celfw_stream_free(celfw_stream *s);
/*
 * Feeds n bytes; *used says how many were consumed (all, unless COMMIT or
 * ERROR; after either, call again with the rest, even if that is nothing).
 * `shown` and `next` are celfw's two stores, exchanged after every COMMIT.
 */
celfw_stream_result celfw_stream_feed(celfw_stream *s, const uint8_t *p, size_t n, size_t *used,
                                      cs_scene *shown, cs_scene *next, celfw_stream_error *err);
/*
 * A check of every committed scene before it is reported as COMMIT (celfw:
 * can it render at the display's size?). It returns NULL to accept, or why
 * not (valid until the next feed) with a status and scene location; the
 * commit is then dropped and reported as CELFW_STREAM_ERROR at the end of
 * its transaction, and `shown` stays.
 */
typedef const char *(*celfw_stream_check)(void *user, const cs_scene *next, cs_status *status,
                                          cs_error *where);
void celfw_stream_set_check(celfw_stream *s, celfw_stream_check check, void *user);

/*
 * The byte sequence ended (client gone, end of file): drops a partial
 * transaction. Returns CELFW_STREAM_ERROR with `err` for each thing
 * dropped; call until it returns CELFW_STREAM_MORE.
 */
celfw_stream_result celfw_stream_reset(celfw_stream *s, celfw_stream_error *err);

#endif /* CELFW_STREAM_H */
