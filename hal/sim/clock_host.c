/*
 * clock_host.c - hal/clock.h on a POSIX host, from CLOCK_MONOTONIC.
 *
 * The simulator times its renders with this; CLOCK_MONOTONIC is immune to
 * NTP steps, which would otherwise show up as absurd frame times.
 */
#include <time.h>

#include "clock.h"

uint64_t hal_clock_now_ns(void)
{
    struct timespec ts;
    /* Cannot fail for CLOCK_MONOTONIC on Linux with a valid pointer. */
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}
