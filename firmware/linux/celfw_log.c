/*
 * celfw_log.c - the per-kind rate limit of celfw's log lines (celfw_log.h).
 *
 * Windows are fixed, not sliding: the first line of a kind opens one, and
 * the first line or check after it ends closes it with its count. So a
 * steady flood writes BURST lines and one summary per window, and a quiet
 * kind costs nothing.
 */
#include "celfw_log.h"

static const uint64_t window_ns = (uint64_t)CELFW_LOG_WINDOW_S * 1000000000u;

uint64_t celfw_ratelimit_due(celfw_ratelimit *r, uint64_t now_ns, bool final)
{
    if (!final && now_ns - r->window_start < window_ns)
        return 0;
    uint64_t held = r->held;
    r->held = 0;
    if (!final) {
        r->shown = 0;
        r->window_start = now_ns;
    }
    return held;
}

bool celfw_ratelimit_allow(celfw_ratelimit *r, uint64_t now_ns, uint64_t *summary)
{
    *summary = 0;
    if (r->shown == 0 && r->held == 0)
        r->window_start = now_ns; /* a quiet kind: this line opens a window */
    else
        *summary = celfw_ratelimit_due(r, now_ns, false);
    if (r->shown < CELFW_LOG_BURST) {
        r->shown++;
        return true;
    }
    r->held++;
    return false;
}
