/*
 * vclock.h - a virtual clock shared by a driver under test and its emulated device.
 *
 * Waiting advances the clock at once; the emulated GPIO chip advances it by
 * the cost of each write. Recorded times are then exact and repeatable.
 */
#ifndef VCLOCK_H
#define VCLOCK_H

#include <stdatomic.h>
#include <stdint.h>

#include "clock.h"

static uint64_t vclock_now(void *user)
{
    return atomic_load((_Atomic uint64_t *)user);
}

static void vclock_wait_until(void *user, uint64_t t)
{
    _Atomic uint64_t *c = user;
    uint64_t cur = atomic_load(c);
    while (cur < t && !atomic_compare_exchange_weak(c, &cur, t)) {
    }
}

static inline hal_clock vclock_make(_Atomic uint64_t *c)
{
    hal_clock k = {c, vclock_now, vclock_wait_until};
    return k;
}

#endif /* VCLOCK_H */
