/*
 * celfw_clock.c - the animation clock of celfw (see celfw_clock.h for why).
 *
 * Only differences of clock readings are taken, in uint64_t nanoseconds
 * (584 years before they wrap), and the reduction to the scene's span is
 * done in integers; the single conversion to float happens last, on a value
 * no larger than the scene's last key time plus a second.
 */
#include <string.h>

#include "celfw_clock.h"
#include "celscan_private.h"

#define NS 1000000000u

void celfw_clock_init(celfw_clock *c, const hal_clock *mono, const hal_clock *wall, bool realtime,
                      double step)
{
    memset(c, 0, sizeof *c);
    c->mono = mono;
    c->wall = wall;
    c->realtime = realtime;
    c->step = step;
    c->origin = hal_now(mono);
}

bool celfw_clock_same_animation(const cs_scene *a, const cs_scene *b)
{
    return a->track_count == b->track_count && a->key_count == b->key_count &&
           a->value_count == b->value_count &&
           !memcmp(a->tracks, b->tracks, a->track_count * sizeof a->tracks[0]) &&
           !memcmp(a->key_times, b->key_times, a->key_count * sizeof a->key_times[0]) &&
           !memcmp(a->key_values, b->key_values, a->value_count * sizeof a->key_values[0]);
}

void celfw_clock_show(celfw_clock *c, const cs_scene *before, const cs_scene *after, uint64_t period_ns)
{
    c->has_epoch = after && after->epoch_ns != 0;
    c->epoch_ns = after ? after->epoch_ns : 0;
    c->period_ns = period_ns;
    if (before && after && celfw_clock_same_animation(before, after))
        return;
    c->origin = hal_now(c->mono);
    c->frames = 0;
}

/* The last key time of the scene in whole nanoseconds, rounded up; 0 without keys. */
static uint64_t last_key_ns(const cs_scene *s)
{
    float last = 0.0f;
    for (uint32_t i = 0; i < s->key_count && i < CS_CFG_MAX_KEYS; i++)
        if (s->key_times[i] > last)
            last = s->key_times[i];
    /* key times are validated finite and within the stream's range */
    return (uint64_t)((double)last * 1e9) + 1u;
}

float celfw_clock_seconds(uint64_t elapsed_ns, uint64_t period_ns, const cs_scene *scene)
{
    if (period_ns) {
        elapsed_ns %= period_ns;
    } else if (scene) {
        uint64_t hold = last_key_ns(scene) + NS; /* tracks hold after their last key */
        if (elapsed_ns > hold)
            elapsed_ns = hold;
    }
    return (float)((double)(elapsed_ns / NS) + (double)(elapsed_ns % NS) / 1e9);
}

float celfw_clock_frame(celfw_clock *c, const cs_scene *scene)
{
    uint64_t e;
    if (c->step > 0) {
        e = (uint64_t)((double)c->frames * c->step * 1e9 + 0.5);
    } else if (c->realtime && c->has_epoch) {
        uint64_t now = hal_now(c->wall);
        e = now > c->epoch_ns ? now - c->epoch_ns : 0; /* before its epoch: the first frame */
    } else {
        e = hal_now(c->mono) - c->origin;
    }
    c->frames++;
    float t = celfw_clock_seconds(e, c->period_ns, scene);
    c->elapsed_ns = e;
    return t;
}
