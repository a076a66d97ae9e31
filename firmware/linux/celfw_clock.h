/*
 * celfw_clock.h - the animation clock of celfw: which time each frame shows.
 *
 * A sign runs for months. A float of seconds since start, as celfw once kept,
 * rounds a moving cel to 5 positions a second after 30 days and freezes it
 * after about 200; and a stream's animation was timed from celfw's start, so
 * a scene committed a week in began a week into its tracks. So:
 *
 *  - Time is kept in integer nanoseconds from a clock given as an hal_clock
 *    (injectable: the tests run it at 1, 30 and 400 days of uptime).
 *  - By default (monotonic) an animation's time 0 is the commit that brought
 *    it. A commit that leaves every track and key as they were (a patch
 *    that changes a price, not the animation) keeps the clock running.
 *  - With --clock realtime, time is the wall clock (CLOCK_REALTIME) less the
 *    epoch the stream carries (EPOCH record, docs/STREAM.md), so the boards
 *    of a video wall show the same instant; a scene without an epoch is
 *    timed from its commit as above. --clock at:S fixes that wall clock at
 *    the instant S (celfw.c hands a clock that does not move), so boards can
 *    be checked against one frame of the whole wall.
 *  - Before it becomes a float for the renderer, the time is reduced in
 *    integers to what the scene can show: past the scene's last key nothing
 *    moves (tracks hold), so it stops one second after that key; a periodic
 *    built-in scene wraps at its period. The float then stays as precise as
 *    the scene's own key times, however long celfw has run.
 *  - --time-step makes each frame advance by a fixed step from the commit
 *    (repeatable tests).
 */
#ifndef CELFW_CLOCK_H
#define CELFW_CLOCK_H

#include <stdbool.h>
#include <stdint.h>

#include "celscan.h"
#include "clock.h"

typedef struct celfw_clock {
    const hal_clock *mono; /* paces frames; the origin of commit-relative time */
    const hal_clock *wall; /* ns since 1970-01-01 UTC, for --clock realtime */
    bool realtime;
    double step;          /* > 0: seconds per frame instead of a clock */
    uint64_t origin;      /* mono reading when the shown animation started */
    uint64_t frames;      /* frames since then */
    bool has_epoch;       /* the shown scene carries an epoch (realtime) */
    uint64_t epoch_ns;
    uint64_t period_ns;   /* > 0: the shown scene repeats with this period */
    uint64_t elapsed_ns;  /* of the last frame, after reduction */
} celfw_clock;

void celfw_clock_init(celfw_clock *c, const hal_clock *mono, const hal_clock *wall, bool realtime,
                      double step);
/*
 * A new scene is shown (before: the one it replaces, NULL at start). The
 * animation restarts unless both have the same tracks and keys; its epoch
 * (after->epoch_ns, if not 0) is what --clock realtime counts from.
 * period_ns: 0, or the period of a periodic built-in scene.
 */
void celfw_clock_show(celfw_clock *c, const cs_scene *before, const cs_scene *after, uint64_t period_ns);
/* The animation time of the frame that starts now, in seconds for the renderer. */
float celfw_clock_frame(celfw_clock *c, const cs_scene *scene);
/* What celfw_clock_frame does after it has read the clock: pure, for tests. */
float celfw_clock_seconds(uint64_t elapsed_ns, uint64_t period_ns, const cs_scene *scene);
/* Whether two scenes animate alike (same tracks, keys and values). */
bool celfw_clock_same_animation(const cs_scene *a, const cs_scene *b);

#endif /* CELFW_CLOCK_H */
