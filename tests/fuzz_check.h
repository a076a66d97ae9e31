/*
 * fuzz_check.h - the checks of the libFuzzer targets (tests/fuzz_*.c).
 *
 * A target defines FUZZ_NAME (its name in messages) before including this.
 * A violated check prints what failed and where, then aborts, which
 * libFuzzer reports as a crash and saves the input that caused it.
 * fuzz_render is the check every target makes of a scene it got through.
 */
#ifndef TESTS_FUZZ_CHECK_H
#define TESTS_FUZZ_CHECK_H

#include <stdio.h>
#include <stdlib.h>

#include "celscan.h"

#define REQUIRE(cond)                                                                             \
    do {                                                                                          \
        if (!(cond)) {                                                                            \
            fprintf(stderr, FUZZ_NAME ": check failed: %s (line %d)\n", #cond, __LINE__);       \
            abort();                                                                              \
        }                                                                                         \
    } while (0)

/*
 * Renders frame `o` of scene s through r into `frame` (o->width * o->height
 * * 3 floats), requiring every line CS_OK and every value in [0, 1].
 * Returns cs_frame_begin's status: unless it is CS_OK (err then says why),
 * nothing is rendered. The frame's own status is r->sticky.status.
 */
static inline cs_status fuzz_render(cs_renderer *r, cs_workspace *ws, const cs_scene *s,
                                    const cs_render_opts *o, float *frame, cs_error *err)
{
    cs_status st = cs_frame_begin(r, ws, s, o, err);
    if (st != CS_OK)
        return st;
    size_t row = (size_t)o->width * 3;
    for (int y = 0; y < o->height; y++) {
        REQUIRE(cs_render_line(r, y, frame + (size_t)y * row) == CS_OK);
        for (size_t i = 0; i < row; i++)
            REQUIRE(frame[(size_t)y * row + i] >= 0.0f && frame[(size_t)y * row + i] <= 1.0f);
    }
    return CS_OK;
}

#endif /* TESTS_FUZZ_CHECK_H */
