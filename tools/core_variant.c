/*
 * core_variant.c - the forwarders of libcelscan_host.a (see core_variant.h):
 * each of the frame's entry points calls the same function of the chosen
 * build of the core through a table. mk/variant.mk links the baseline build
 * with these functions renamed base_cs_* and the x86-64-v3 build with every
 * symbol renamed v3_*, so the two builds sit side by side in one program.
 * An indirect call per line costs nothing next to the line.
 *
 * CORE_VARIANT_V3 (set by mk/variant.mk on x86-64 hosts) adds the second
 * build; without it the table has the baseline alone.
 */
#include "core_variant.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celscan.h"

#ifndef CORE_VARIANT_V3
#define CORE_VARIANT_V3 0
#endif
#if CORE_VARIANT_V3
#define CORE_VARIANT_CHOICES "auto|baseline|x86-64-v3"
#else
#define CORE_VARIANT_CHOICES "auto|baseline"
#endif

/* The frame's entry points: return type, name, parameters, arguments. */
#define CORE_VARIANT_FUNCS(X)                                                                      \
    X(cs_status, cs_frame_begin,                                                                   \
      (cs_renderer *r, cs_workspace *ws, const cs_scene *scene, const cs_render_opts *opts,        \
       cs_error *err),                                                                             \
      (r, ws, scene, opts, err))                                                                   \
    X(cs_status, cs_frame_begin_cached,                                                            \
      (cs_renderer *r, cs_workspace *ws, const cs_scene *scene, const cs_render_opts *opts,        \
       const cs_cache *cache, cs_error *err),                                                      \
      (r, ws, scene, opts, cache, err))                                                            \
    X(cs_status, cs_frame_begin_part,                                                              \
      (cs_renderer *r, cs_workspace *ws, const cs_scene *scene, const cs_render_opts *opts,        \
       uint32_t cel_begin, uint32_t cel_end, cs_error *err),                                       \
      (r, ws, scene, opts, cel_begin, cel_end, err))                                               \
    X(cs_status, cs_frame_join, (cs_renderer *r, const cs_renderer *const *parts, int n),          \
      (r, parts, n))                                                                               \
    X(cs_status, cs_cache_build,                                                                   \
      (cs_cache *cache, void *buffer, size_t size, cs_workspace *ws, const cs_scene *scene,        \
       const cs_render_opts *opts, uint32_t cel_first, uint32_t cel_count, cs_error *err),         \
      (cache, buffer, size, ws, scene, opts, cel_first, cel_count, err))                           \
    X(cs_status, cs_render_line, (cs_renderer *r, int y, float *rgb_linear), (r, y, rgb_linear))   \
    X(cs_status, cs_render_line_runs, (cs_renderer *r, int y), (r, y))                             \
    X(cs_status, cs_render_line_px, (cs_renderer *r, int y, cs_pixfmt fmt, uint8_t *out),          \
      (r, y, fmt, out))                                                                            \
    X(cs_status, cs_render_frame, (cs_renderer *r, float *line, cs_line_sink sink, void *user),    \
      (r, line, sink, user))                                                                       \
    X(const uint8_t *, cs_line_pixels_scratch, (cs_renderer *r, cs_pixfmt fmt), (r, fmt))          \
    X(int, cs_line_run, (const cs_renderer *r, int x, float rgb_linear[3]), (r, x, rgb_linear))

/* cs_line_pixels returns nothing, so it cannot share the forwarders' `return f(...)`. */
#define CORE_VARIANT_VOID(X)                                                                       \
    X(void, cs_line_pixels, (const cs_renderer *r, cs_pixfmt fmt, uint8_t *out), (r, fmt, out))

#define ALL_FUNCS(X) CORE_VARIANT_FUNCS(X) CORE_VARIANT_VOID(X)

/* The builds' own names for them. */
#define DECLARE(ret, name, params, args) ret base_##name params;
ALL_FUNCS(DECLARE)
#undef DECLARE

typedef struct core_variant_fns {
#define FIELD(ret, name, params, args) ret (*name) params;
    ALL_FUNCS(FIELD)
#undef FIELD
} core_variant_fns;

static const core_variant_fns base_fns = {
#define INIT(ret, name, params, args) .name = base_##name,
    ALL_FUNCS(INIT)
#undef INIT
};

#if CORE_VARIANT_V3
#define DECLARE(ret, name, params, args) ret v3_##name params;
ALL_FUNCS(DECLARE)
#undef DECLARE

static const core_variant_fns v3_fns = {
#define INIT(ret, name, params, args) .name = v3_##name,
    ALL_FUNCS(INIT)
#undef INIT
};

/* libgcc's cpuid reading, here in the host program where libgcc is linked. */
static int cpu_has_v3(void)
{
    __builtin_cpu_init();
    return __builtin_cpu_supports("x86-64-v3");
}
#endif

static int cpu_any(void)
{
    return 1;
}

typedef struct core_variant {
    const char *name;
    int (*runs_here)(void);
    const core_variant_fns *fns;
} core_variant;

/* Fastest last: "auto" takes the last one this CPU runs. */
static const core_variant variants[] = {
    {"baseline", cpu_any, &base_fns},
#if CORE_VARIANT_V3
    {"x86-64-v3", cpu_has_v3, &v3_fns},
#endif
};
#define N_VARIANTS (sizeof variants / sizeof variants[0])

/* Set before main (core_variant_init) and by core_variant_select before
 * rendering starts, read by every forwarder. */
static const core_variant *current = &variants[0];

const char *core_variant_select(const char *name)
{
    if (strcmp(name, "auto") == 0) {
        for (size_t i = N_VARIANTS; i-- > 0;)
            if (variants[i].runs_here()) {
                current = &variants[i];
                return NULL;
            }
    }
    for (size_t i = 0; i < N_VARIANTS; i++) {
        if (strcmp(name, variants[i].name) != 0)
            continue;
        if (!variants[i].runs_here())
            return "this CPU cannot run that build of the core";
        current = &variants[i];
        return NULL;
    }
    return "unknown build of the core (expected " CORE_VARIANT_CHOICES ")";
}

const char *core_variant_name(void)
{
    return current->name;
}

const char *core_variant_choices(void)
{
    return CORE_VARIANT_CHOICES;
}

/* Before main, so that every program linking the forwarders starts with the
 * CPU's choice, or the environment's. */
__attribute__((constructor)) static void core_variant_init(void)
{
    const char *env = getenv("CELSCAN_CORE");
    const char *why = core_variant_select(env != NULL && env[0] != '\0' ? env : "auto");
    if (why != NULL) {
        fprintf(stderr, "celscan: CELSCAN_CORE=%s: %s; choosing from the CPU\n", env, why);
        (void)core_variant_select("auto");
    }
}

#define FORWARD(ret, name, params, args) \
    ret name params { return current->fns->name args; }
CORE_VARIANT_FUNCS(FORWARD)
#undef FORWARD

void cs_line_pixels(const cs_renderer *r, cs_pixfmt fmt, uint8_t *out)
{
    current->fns->cs_line_pixels(r, fmt, out);
}
