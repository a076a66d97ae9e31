/*
 * cs_cache.c - pre-combination: a cel range rendered once, reused per frame.
 *
 * The beta model's overlay (E1, T1) over (E2, T2) = (E1 + T1 E2, T1 T2) is
 * associative, so a run of cels that does not change (the paper's static
 * background) can be combined once into a single equivalent cel and put
 * back into any stack, with new cels in front of it or behind it. The
 * combined cel is kept in scan-converted form, before pixel conversion: per
 * line, runs of pixels sharing one (E, T) map. Clear pixels (0, 1) are not
 * stored, and neighbours with bit-identical maps share a run, so flat
 * artwork costs a few runs per line and only gradients and edges cost a run
 * per pixel. Nothing is quantised: a frame from the cache differs from the
 * direct render only by the rounding of the regrouped products (~1e-7).
 *
 * The runs live in a buffer the caller owns, of any size. The build always
 * completes its count, so when the runs do not fit it can say how many
 * bytes would have (bytes_needed), and the cache is marked unusable; the
 * caller then renders those cels directly (cs_frame_begin_cached refuses
 * an unusable cache, so the fallback cannot be silent).
 *
 * Layout in the buffer (aligned up to 4 bytes):
 *   uint32_t line_first[height + 1]   index of each line's first run
 *   cs_cache_run runs[]               in line order, x increasing
 */
#include "cs_runs.h"

#if CS_CFG_CACHE
static bool same_map(const cs_cache_run *run, const float *E, const float *T)
{
    for (int ch = 0; ch < 3; ch++)
        if (run->E[ch] != E[ch] || run->T[ch] != T[ch])
            return false;
    return true;
}

/* Stores line y's runs (just stacked by cs__line_stack in ws) from runs[count]
 * on, as far as capacity allows; returns the new count, which goes on past
 * capacity so that bytes_needed is exact, and clears *grey at a coloured T. */
static size_t cache_line(const cs_renderer *r, const cs_workspace *ws, int width,
                         cs_cache_run *runs, size_t capacity, size_t count, bool *grey)
{
    /* The open run is built here and stored when it closes, so that the
     * count (and bytes_needed) is exact even when nothing fits. The
     * line's own runs may split pixels of one map; they are joined. */
    cs_cache_run cur = {0, 0, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
    bool open = false;
    for (uint32_t x = 0; x <= (uint32_t)width;) {
        uint32_t end = x < (uint32_t)width ? ws->run_end[x] : x + 1u;
        const float *E = &ws->stack_E[3 * x];
        float T[3];
        cs__run_T(ws, r->grey, x, T);
        bool clear = x == (uint32_t)width ||
                     (E[0] == 0.0f && E[1] == 0.0f && E[2] == 0.0f && T[0] == 1.0f &&
                      T[1] == 1.0f && T[2] == 1.0f);
        if (open && !clear && same_map(&cur, E, T)) {
            cur.len = (uint16_t)(cur.len + (end - x));
            x = end;
            continue;
        }
        if (open) {
            if (count < capacity) {
                cs_cache_run *d = &runs[count];
                d->x = cur.x;
                d->len = cur.len;
                for (int ch = 0; ch < 3; ch++) {
                    d->E[ch] = cur.E[ch];
                    d->T[ch] = cur.T[ch];
                }
            }
            *grey = *grey && cs__grey3(cur.T);
            count++;
            open = false;
        }
        if (!clear) {
            open = true;
            cur.x = (uint16_t)x;
            cur.len = (uint16_t)(end - x);
            for (int ch = 0; ch < 3; ch++) {
                cur.E[ch] = E[ch];
                cur.T[ch] = T[ch];
            }
        }
        x = end;
    }
    return count;
}
#endif

cs_status cs_cache_build(cs_cache *cache, void *buffer, size_t size, cs_workspace *ws,
                         const cs_scene *scene, const cs_render_opts *opts, uint32_t cel_first,
                         uint32_t cel_count, cs_error *err)
{
    cs__error(err, CS_OK, -1, -1, -1, -1);
    if (!cache) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    cache->status = CS_ERR_STATE;
    cache->bytes_used = cache->bytes_needed = 0;
    cache->run_count = 0;
    cache->cel_first = cel_first;
    cache->cel_count = cel_count;
    cache->line_first = 0;
    cache->runs = 0;
    cache->grey = false;
    /* A viewport's board renders a window of the lines: no cache for it. */
    if (!ws || !scene || !opts || (!buffer && size > 0) || cel_count == 0 || opts->view_w ||
        opts->view_h ||
        cel_first >= scene->cel_count || cel_count > scene->cel_count - cel_first) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    cache->opts = *opts;
    if (opts->blend == CS_BLEND_SCENE) /* the cache holds resolved options */
        cache->opts.blend = (cs_blend)scene->blend;
#if !CS_CFG_CACHE
    (void)buffer;
    (void)size;
    cs__error(err, CS_ERR_STATE, -1, -1, -1, -1);
    return CS_ERR_STATE; /* built without CS_CFG_CACHE */
#else
    cs_renderer r;
    cs_status st = cs__frame_prepare(&r, ws, scene, opts, cel_first, cel_first + cel_count, 0, err);
    if (st != CS_OK)
        return st;

    /* Carve the buffer: the line index first, then the runs. */
    uintptr_t base = (uintptr_t)buffer;
    size_t pad = (size_t)((4u - (base & 3u)) & 3u);
    size_t header = pad + ((size_t)opts->height + 1u) * sizeof(uint32_t);
    uint32_t *line_first = 0;
    cs_cache_run *runs = 0;
    size_t capacity = 0;
    if (size >= header) {
        line_first = (uint32_t *)(base + pad);
        runs = (cs_cache_run *)(base + header);
        capacity = (size - header) / sizeof(cs_cache_run);
    }

    int width = opts->width;
    size_t count = 0;
    bool grey = true; /* every stored T is */
    for (int y = 0; y < opts->height; y++) {
        cs__line_stack(&r, y);
        if (line_first)
            line_first[y] = (uint32_t)count;
        count = cache_line(&r, ws, width, runs, capacity, count, &grey);
    }
    if (line_first)
        line_first[opts->height] = (uint32_t)count;
    cache->bytes_needed = header + count * sizeof(cs_cache_run);
    if (count > capacity || !line_first || count > UINT32_MAX) {
        cs__error(err, CS_ERR_CAP_CACHE, (int32_t)cel_first, -1, -1, -1);
        return CS_ERR_CAP_CACHE;
    }
    cache->bytes_used = cache->bytes_needed;
    cache->run_count = (uint32_t)count;
    cache->line_first = line_first;
    cache->runs = runs;
    cache->grey = grey;
    cache->status = CS_OK;
    /* A capacity error met while rendering the range degrades the cached
     * picture just as it would the direct one; report it, keep the cache. */
    if (r.sticky.status != CS_OK) {
        if (err)
            *err = r.sticky;
        return r.sticky.status;
    }
    return CS_OK;
#endif
}

/* The cached runs of line y put behind the stack; compiled once per case
 * (CS__SPECIALISE), a grey frame and a coloured one, as the line code is. */
static CS__SPECIALISE void cache_composite_as(cs_renderer *r, int y, bool grey)
{
    const cs_cache *cache = r->cache;
    cs_workspace *ws = r->ws;
    uint32_t s = 0; /* a run start left of the cached run */
    for (uint32_t k = cache->line_first[y]; k < cache->line_first[y + 1]; k++) {
        const cs_cache_run *run = &cache->runs[k];
        uint32_t a = run->x, b = (uint32_t)run->x + run->len;
        s = cs__run_seek(ws, s, a);
        for (;;) {
            uint32_t e = ws->run_end[s];
            if (!cs__run_opaque(r, s)) {
                e = cs__run_clip(ws, grey, &s, a, b);
                /* An opaque run's T is 0: finite T_s times 0 leaves 0 behind it. */
                cs__run_join(r, grey, s, e, run->E, run->T);
            }
            if (e >= b)
                break;
            s = e;
        }
    }
}

void cs__cache_composite(cs_renderer *r, int y)
{
    if (CS_CFG_GREY && r->grey)
        cache_composite_as(r, y, true);
    else
        cache_composite_as(r, y, false);
}
