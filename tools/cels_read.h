/*
 * cels_read.h - reading whole cel streams on the host (celsim, tests).
 *
 * Runs the core's decoder over a file or buffer, swapping every commit in at
 * once (a host has no frame to wait for), and reports each dropped
 * transaction or skipped run on an error stream in one line:
 *
 *   scene.cels: byte 1234: transaction CRC mismatch: data damaged
 *       (transaction at byte 1200 dropped)
 *
 * The result is the scene of the last good commit, so a damaged tail still
 * leaves the valid scene to render; callers exit non-zero only when nothing
 * was committed (the celsim contract in DESIGN.md).
 */
#ifndef CELS_READ_H
#define CELS_READ_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "celscan.h"

typedef struct cels_read_stats {
    unsigned commits;  /* transactions committed */
    unsigned errors;   /* errors reported */
    unsigned long long skipped; /* bytes outside transactions */
} cels_read_stats;

/* One-line description of a decoder error, without the name prefix. */
void cels_format_error(const cs_stream_error *e, char *buf, size_t len);

/*
 * Decodes `len` bytes with two caller-provided stores. Returns the last
 * committed scene (one of `a`, `b`) or NULL if none. Errors go to `errf`
 * (may be NULL) prefixed with `name`; `stats` may be NULL.
 */
const cs_scene *cels_decode_buffer(const uint8_t *data, size_t len, const char *name,
                                   cs_scene *a, cs_scene *b, FILE *errf, cels_read_stats *stats);

/* The same for a file; an unreadable file is reported and gives NULL. */
const cs_scene *cels_read_file(const char *path, cs_scene *a, cs_scene *b, FILE *errf,
                               cels_read_stats *stats);

#endif /* CELS_READ_H */
