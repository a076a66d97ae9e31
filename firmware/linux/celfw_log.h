/*
 * celfw_log.h - a rate limit for celfw's repeated log lines.
 *
 * A board writes its log to an SD card or a journal for months. A sender
 * that pushes 60,000 empty patches, or a neighbour knocking with unsigned
 * streams, must not turn into megabytes of identical lines: each kind of
 * line may be written CELFW_LOG_BURST times per CELFW_LOG_WINDOW_S seconds,
 * and the lines held back in a window are then told as one count ("N more
 * 'stream commit' lines"). The limiter only counts; celfw writes the lines.
 */
#ifndef CELFW_LOG_H
#define CELFW_LOG_H

#include <stdbool.h>
#include <stdint.h>

#define CELFW_LOG_BURST 10
#define CELFW_LOG_WINDOW_S 10

/* One kind of line; zero-initialised. */
typedef struct celfw_ratelimit {
    uint64_t window_start; /* ns */
    uint64_t shown, held;  /* lines written and held back in this window */
} celfw_ratelimit;

/*
 * Whether a line of this kind may be written at now_ns. If a window with
 * held-back lines ended before it, *summary is their count (to be written
 * first), else 0.
 */
bool celfw_ratelimit_allow(celfw_ratelimit *r, uint64_t now_ns, uint64_t *summary);
/*
 * The count of held-back lines to tell now: those of a window that has
 * ended by now_ns, or (at exit, `final`) of the current one. 0 if none.
 */
uint64_t celfw_ratelimit_due(celfw_ratelimit *r, uint64_t now_ns, bool final);

#endif /* CELFW_LOG_H */
