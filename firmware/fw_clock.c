/*
 * fw_clock.c - a board's timer as the one clock interface (hal/clock.h).
 *
 * Boards keep board_time_us() (board_api.h) for the main loop, which costs
 * no indirection; board_clock is the same timer for code written against
 * the contract (a panel's reset delays, a driver shared with the host),
 * where a test can hand in a virtual clock instead. A board that does not use
 * it pays nothing: --gc-sections drops it.
 */
#include "board_api.h"

static uint64_t board_now_ns(void *user)
{
    (void)user;
    return board_time_us() * 1000u;
}

/* Spins: a board has no scheduler to sleep in, and the waits are short. */
static void board_wait_until_ns(void *user, uint64_t t)
{
    while (board_now_ns(user) < t) {
    }
}

const hal_clock board_clock = {0, board_now_ns, board_wait_until_ns};
