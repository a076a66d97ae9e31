/*
 * celfw_stream.h - the seam between celfw's input and the cel-stream decoder.
 *
 * celfw's framers (celfw_frame.h) cut each input into whole frames; after
 * the trust check (celfw_trust.h) every stream header and transaction goes
 * to celfw_stream_frame() with celfw's two scene stores: `shown`, the one on
 * display, and `next`, the other. The decoder (the core's cs_stream,
 * docs/STREAM.md) builds the next scene in `next` (a patch transaction
 * starts from a copy of `shown`, which itself is never written) and returns
 * CELFW_STREAM_COMMIT when the transaction is valid; celfw then makes `next`
 * the scene on display, between frames. A damaged, oversized or invalid
 * transaction gives CELFW_STREAM_ERROR with the byte offset of the fault and
 * what was wrong; the scene on display stays as it was.
 *
 * Offsets count from the start of the frame's byte sequence (a TCP client's
 * connection, a file, stdin): the caller says where the frame began. Whatever
 * scene celfw shows when the stream starts (a built-in or JSON --scene, or an
 * empty canvas) is the one the first patch transactions apply to.
 */
#ifndef CELFW_STREAM_H
#define CELFW_STREAM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "celscan.h"

typedef enum celfw_stream_result {
    CELFW_STREAM_MORE = 0, /* nothing to apply (a stream header) */
    CELFW_STREAM_COMMIT,   /* a transaction committed into `next`: show it */
    CELFW_STREAM_ERROR     /* something was dropped; see the error */
} celfw_stream_result;

typedef struct celfw_stream_error {
    uint64_t offset; /* byte offset of the fault (since the start of the sequence) */
    char what[240];  /* what was wrong, and what was dropped from which offset */
} celfw_stream_error;

typedef struct celfw_stream celfw_stream;

celfw_stream *celfw_stream_new(void);
void celfw_stream_free(celfw_stream *s);
/*
 * Decodes one whole frame of n bytes whose first byte was byte `base` of its
 * sequence. `shown` and `next` are celfw's two stores, exchanged after every
 * COMMIT.
 */
celfw_stream_result celfw_stream_frame(celfw_stream *s, const uint8_t *p, size_t n, uint64_t base,
                                       cs_scene *shown, cs_scene *next, celfw_stream_error *err);
/*
 * A check of every committed scene before it is reported as COMMIT (celfw:
 * can it render at the display's size?). It returns NULL to accept, or why
 * not (valid until the next frame) with a status and scene location; the
 * commit is then dropped and reported as CELFW_STREAM_ERROR, and `shown`
 * stays.
 */
typedef const char *(*celfw_stream_check)(void *user, const cs_scene *next, cs_status *status,
                                          cs_error *where);
void celfw_stream_set_check(celfw_stream *s, celfw_stream_check check, void *user);

/*
 * Words a fault found outside the decoder (by the framer: `offset` is the
 * start of what was dropped, `at` the fault) as the decoder's are worded.
 */
void celfw_stream_describe(cs_status status, const char *what, uint64_t offset, uint64_t at,
                           celfw_stream_error *err);

#endif /* CELFW_STREAM_H */
