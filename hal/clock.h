/*
 * clock.h - the one clock interface: a reading and a precise wait.
 *
 * The renderer is timeless (a frame is rendered at the time it is given), but
 * the code around it needs a clock: the simulator to time renders, celfw to
 * pick each frame's time and to pace lines, a HUB75 drive loop to hold a bit
 * plane for a few hundred nanoseconds. Each goes through this small table, so
 * a test can hand a driver a virtual clock that its emulated device also
 * reads (then every recorded wire change carries an exact time).
 *
 * Clocks: hal_clock_monotonic and hal_clock_realtime on a POSIX host
 * (hal/host/clock_host.c); on a microcontroller board_clock, the board's
 * timer (declared in firmware/boards/board_api.h, made in firmware/fw_clock.c).
 */
#ifndef HAL_CLOCK_H
#define HAL_CLOCK_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hal_clock {
    void *user;
    /* Nanoseconds since a fixed origin; never goes backwards (monotonic
     * clocks) and only differences are meaningful. */
    uint64_t (*now_ns)(void *user);
    /* Returns at (or just after) time t; returns at once if t has passed. */
    void (*wait_until_ns)(void *user, uint64_t t);
} hal_clock;

static inline uint64_t hal_now(const hal_clock *c) { return c->now_ns(c->user); }
static inline void hal_wait_until(const hal_clock *c, uint64_t t) { c->wait_until_ns(c->user, t); }

/* CLOCK_MONOTONIC: sleeps for long waits and spins for the last stretch. */
extern const hal_clock hal_clock_monotonic;
/* CLOCK_REALTIME, ns since 1970-01-01 UTC: the shared time of a video wall's
 * boards (celfw --clock realtime). It can jump when the time is set, so it
 * never paces anything. */
extern const hal_clock hal_clock_realtime;

#ifdef __cplusplus
}
#endif

#endif /* HAL_CLOCK_H */
