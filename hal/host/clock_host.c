/*
 * clock_host.c - the host's clocks (clock.h): monotonic, which paces and
 * times everything, and realtime, a video wall's shared time.
 *
 * nanosleep() on a loaded board overshoots by tens of microseconds, far more
 * than the shortest HUB75 bit plane, so the wait sleeps only while the target
 * is comfortably far away and spins on clock_gettime() for the rest.
 */
#include <errno.h>
#include <time.h>

#include "clock.h"

/* Below this the scheduler's wake-up latency would overshoot the target. */
#define HOST_SPIN_NS 80000u

static uint64_t mono_now(void *user)
{
    (void)user;
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

static void mono_wait_until(void *user, uint64_t t)
{
    uint64_t now = mono_now(user);
    if (t > now + HOST_SPIN_NS) {
        uint64_t d = t - now - HOST_SPIN_NS;
        struct timespec ts = {(time_t)(d / 1000000000u), (long)(d % 1000000000u)};
        nanosleep(&ts, NULL);
    }
    while (mono_now(user) < t) {
    }
}

const hal_clock hal_clock_monotonic = {NULL, mono_now, mono_wait_until};

static uint64_t real_now(void *user)
{
    (void)user;
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

static void real_wait_until(void *user, uint64_t t)
{
    (void)user;
    struct timespec ts = {(time_t)(t / 1000000000u), (long)(t % 1000000000u)};
    while (clock_nanosleep(CLOCK_REALTIME, TIMER_ABSTIME, &ts, NULL) == EINTR) {
    }
}

const hal_clock hal_clock_realtime = {NULL, real_now, real_wait_until};
