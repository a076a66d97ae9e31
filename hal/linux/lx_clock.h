/*
 * lx_clock.h - time for celfw's drivers: a reading and a precise wait.
 *
 * HUB75 colour depth is binary-code modulation: bit plane b is lit for
 * 2^b times a base interval, so its drive loop needs a wait that is accurate
 * to well under a microsecond. Frame pacing and deadlines need a monotonic
 * reading. Both go through this small table so that the emulated-device tests
 * can hand the driver a virtual clock that the emulated GPIO chip also reads:
 * then every recorded wire change carries an exact time, and the panel model
 * can measure OE time per bit plane without scheduler noise.
 */
#ifndef LX_CLOCK_H
#define LX_CLOCK_H

#include <stdint.h>

typedef struct lx_clock {
    void *user;
    uint64_t (*now_ns)(void *user);
    /* Returns at (or just after) time t; returns at once if t has passed. */
    void (*wait_until_ns)(void *user, uint64_t t);
} lx_clock;

/* CLOCK_MONOTONIC: sleeps for long waits and spins for the last stretch. */
extern const lx_clock lx_clock_monotonic;
/* CLOCK_REALTIME, ns since 1970-01-01 UTC: the shared time of a video wall's
 * boards (celfw --clock realtime). It can jump when the time is set, so it
 * never paces anything. */
extern const lx_clock lx_clock_realtime;

static inline uint64_t lx_now(const lx_clock *c) { return c->now_ns(c->user); }
static inline void lx_wait_until(const lx_clock *c, uint64_t t) { c->wait_until_ns(c->user, t); }

#endif /* LX_CLOCK_H */
