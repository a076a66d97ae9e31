/*
 * cs_line.c - one display line out: the line's runs, made by the stages
 * before it (active pieces and crossings in cs_cross.c, spans and coverage
 * in cs_coverage.c or cs_exact.c, compositing in cs_composite.c), become
 * pixels: E + T L per run, in the display's format (cs_line_pixels) or as
 * floats (cs_render_line), and a frame is its lines in order
 * (cs_render_frame). Nothing is carried from line to line but the active
 * list, so a line comes out the same whichever lines were rendered before it.
 */
#include "cs_rgb888.h"
#include "cs_runs.h"

/*
 * Turns the stack of each run into its pixel, E + T L clamped to [0, 1]
 * (decoded to linear light under sRGB blending), in place in stack_E, and
 * joins neighbouring runs whose pixels came out equal.
 */
static CS__SPECIALISE void finish_line_as(cs_renderer *r, bool grey)
{
    cs_workspace *ws = r->ws;
    uint32_t width = (uint32_t)r->vw;
    float L0 = r->behind[0], L1 = r->behind[1], L2 = r->behind[2];
    bool srgb = r->opts.blend == CS_BLEND_SRGB;
    /* The arrays in locals: on a board the workspace is one static object,
     * and GCC otherwise rebuilds each array's address from it per run. */
    float *stack_E = ws->stack_E;
    uint16_t *run_end = ws->run_end;
    /* The previous run's pixel; before the first run one that equals no
     * pixel (NaN), so that the loop needs no test of whether there is one. */
    const float none[3] = {CS__NAN, CS__NAN, CS__NAN};
    const float *P = none;
    uint32_t prev = 0;
    for (uint32_t s = 0; s < width;) {
        float *E = &stack_E[3 * s], T[3];
        cs__run_T(ws, grey, s, T);
        E[0] = cs__clampf(E[0] + T[0] * L0, 0.0f, 1.0f);
        E[1] = cs__clampf(E[1] + T[1] * L1, 0.0f, 1.0f);
        E[2] = cs__clampf(E[2] + T[2] * L2, 0.0f, 1.0f);
        /* sRGB blending composited encoded values; hand back linear light. */
        if (CS__UNLIKELY(srgb))
            for (int ch = 0; ch < 3; ch++)
                E[ch] = cs__srgb_decode(E[ch]);
        uint32_t e = run_end[s];
        if (P[0] == E[0] && P[1] == E[1] && P[2] == E[2]) {
            run_end[prev] = (uint16_t)e; /* same pixels: one run */
            s = e;
            continue;
        }
        P = E;
        prev = s;
        s = e;
    }
}

static void finish_line(cs_renderer *r)
{
    if (CS_CFG_GREY && r->grey)
        finish_line_as(r, true);
    else
        finish_line_as(r, false);
}

#if CS__RGB888_VEC
/*
 * finish_line_as and the 8-bit sRGB conversion of its runs in one pass, for
 * the display path (cs_render_line_px): a second walk over ~100 k runs a
 * Many-blobs frame, reloading each run's floats, and the codes channel by
 * channel cost more than the arithmetic. Each run's pixel is finished as
 * one vector of its three channels (lane 3 is 0 throughout), by the same
 * operations as finish_line_as lane by lane (E + T L unfused, then maxps
 * with 0 and minps with 1, the instructions of cs__clampf), so the same
 * bits, stored back, so the runs hold the line's pixels as after
 * cs_render_line_runs. Equal neighbours are not joined: on Many-blobs 3 k
 * of 94 k runs would be, and their test cost more than their codes and
 * stores. A run is written once the next one's start is known, with its
 * codes from cs__srgb8_lanes.
 */
typedef struct fused_line {
    float *stack_E;
    const float *stack_T;
    uint16_t *run_end;
    uint8_t *out;
    cs__v4f L;
    px16_u8 codes;   /* the previous run's 8-bit codes (cs__srgb8_lanes) */
    uint32_t prev;   /* and its start */
    cs__u16_alias *longs; /* the starts of runs written ahead, longer than 32 pixels */
    uint32_t n_longs;
} fused_line;

/* The runs from s on while s < limit; a run is written ahead of its end
 * (`ahead`: limit leaves 31 pixels of room) or exactly. Returns the next s.
 * Ahead, a run gets its first 32 pixels only (three 32-byte stores, as
 * many as 16 pixels take in 16-byte ones), with no test of its length,
 * and its start goes to f->longs if it has more: a store per run and a
 * count that grows by a comparison, so that the loop over long runs'
 * pixels (cs__rgb888_rest) runs apart from the runs of one or two pixels
 * between them. In one loop, its exit was mispredicted ~56 k times a
 * Many-blobs exact frame (callgrind --branch-sim), an edge pixel's run
 * and an interior's alternating. */
static CS__SPECIALISE uint32_t fused_runs(fused_line *f, bool grey, uint32_t s, uint32_t limit,
                                          bool ahead)
{
    const cs__v4f zero = {0.0f, 0.0f, 0.0f, 0.0f}, one = {1.0f, 1.0f, 1.0f, 1.0f};
    const cs__v4i three = {-1, -1, -1, 0}; /* the lanes of a pixel's channels */
    while (s < limit) {
        const float *t = &f->stack_T[3 * s];
        float *e3 = &f->stack_E[3 * s];
        /* Ahead, pixel s + 1 is on the line: its first channel comes in as
         * lane 3 and goes back as it was, by a plain load and store, since
         * masked stores are slow on some x86 cores (AMD's). Lane 3 is
         * clamped to [0, 1] like the others, so its gathers stay within
         * the tables; its codes are not used. */
        cs__v4f E0 = ahead ? (cs__v4f)*(const cs__v4f_u *)e3
                           : __builtin_ia32_maskloadps((const cs__v4f *)e3, three);
        cs__v4f T = grey ? (cs__v4f){t[0], t[0], t[0], t[0]}
                         : __builtin_ia32_maskloadps((const cs__v4f *)t, three);
        cs__v4f E = __builtin_ia32_minps(__builtin_ia32_maxps(E0 + T * f->L, zero), one);
        if (ahead)
            *(cs__v4f_u *)e3 = (cs__v4f_u)__builtin_ia32_blendps(E, E0, 8);
        else
            __builtin_ia32_maskstoreps((cs__v4f *)e3, three, E);
        /* The run before, written now that its end is known; the first
         * time, an empty run at 0 (written ahead, then over). */
        uint8_t *p = f->out + 3u * f->prev;
        if (ahead) {
            cs__rgb888_first_lanes(p, f->codes);
            f->longs[f->n_longs] = (uint16_t)f->prev;
            f->n_longs += (f->prev + 32u - s) >> 31; /* s - prev > 32, in four instructions */
        } else
            cs__rgb888_fill(p, s - f->prev, f->codes[0], f->codes[4], f->codes[8]);
        f->codes = cs__srgb8_lanes(E);
        f->prev = s;
        s = f->run_end[s];
    }
    return s;
}

static CS__SPECIALISE void finish_rgb888_as(cs_renderer *r, bool grey, uint8_t *out)
{
    cs_workspace *ws = r->ws;
    uint32_t width = (uint32_t)r->vw;
    /* Like cel_E, cel_A is read only where the line has set `used` (see
     * cs_line_pixels_scratch), so free now: 2 bytes of it per long run, of
     * more than 32 pixels. */
    fused_line f = {ws->stack_E, ws->stack_T, ws->run_end, out,
                    (cs__v4f){r->behind[0], r->behind[1], r->behind[2], 0.0f}, (px16_u8){0}, 0,
                    (cs__u16_alias *)(void *)ws->cel_A, 0};
    /* A run found at s >= width - 30 ends the one before within 31 pixels
     * of the line's end: that one and those after are written exactly. */
    uint32_t s = fused_runs(&f, grey, 0, width > 30u ? width - 30u : 0u, true);
    fused_runs(&f, grey, s, width, false);
    cs__rgb888_fill(out + 3u * f.prev, width - f.prev, f.codes[0], f.codes[4], f.codes[8]);
    /* The long runs' pixels after their first 32, within each run (the
     * runs written after one start at or beyond its end). */
    for (uint32_t k = 0; k < f.n_longs; k++) {
        uint32_t a = f.longs[k];
        cs__rgb888_rest(out + 3u * a, f.run_end[a] - a);
    }
}
#endif

static bool line_ok(const cs_renderer *r, int y)
{
    return r && r->ws && y >= r->vy && y - r->vy < r->vh;
}

cs_status cs_render_line_runs(cs_renderer *r, int y)
{
    if (!line_ok(r, y))
        return CS_ERR_ARG;
    cs__line_stack(r, y);
    finish_line(r);
    return CS_OK;
}

int cs_line_run(const cs_renderer *r, int x, float rgb_linear[3])
{
    const cs_workspace *ws = r->ws;
    for (int ch = 0; ch < 3; ch++)
        rgb_linear[ch] = ws->stack_E[3 * x + ch];
    return ws->run_end[x];
}

void cs_line_pixels(const cs_renderer *r, cs_pixfmt fmt, uint8_t *out)
{
    const cs_workspace *ws = r->ws;
    cs__pixfmt_runs(fmt, ws->stack_E, ws->run_end, (uint32_t)r->vw, out);
}

const uint8_t *cs_line_pixels_scratch(cs_renderer *r, cs_pixfmt fmt)
{
    /* A cel value is read only where the line has set `used`, after it
     * wrote the value: between lines the memory is free. 12 bytes a pixel
     * hold any format. */
    uint8_t *out = (uint8_t *)(void *)r->ws->cel_E;
    cs_line_pixels(r, fmt, out);
    return out;
}

cs_status cs_render_line(cs_renderer *r, int y, float *rgb_linear)
{
    if (!rgb_linear)
        return CS_ERR_ARG;
    cs_status st = cs_render_line_runs(r, y);
    if (st != CS_OK)
        return st;
    const cs_workspace *ws = r->ws;
    uint32_t width = (uint32_t)r->vw;
    for (uint32_t s = 0; s < width;) {
        uint32_t e = ws->run_end[s];
        float c0 = ws->stack_E[3 * s], c1 = ws->stack_E[3 * s + 1], c2 = ws->stack_E[3 * s + 2];
        for (uint32_t x = s; x < e; x++) {
            rgb_linear[3 * x] = c0;
            rgb_linear[3 * x + 1] = c1;
            rgb_linear[3 * x + 2] = c2;
        }
        s = e;
    }
    return CS_OK;
}

cs_status cs_render_line_px(cs_renderer *r, int y, cs_pixfmt fmt, uint8_t *out)
{
    if (!out)
        return CS_ERR_ARG;
#if CS__RGB888_VEC
    if (fmt == CS_PIX_RGB888_SRGB && line_ok(r, y) && r->opts.blend != CS_BLEND_SRGB) {
        cs__line_stack(r, y);
        if (CS_CFG_GREY && r->grey)
            finish_rgb888_as(r, true, out);
        else
            finish_rgb888_as(r, false, out);
        return CS_OK;
    }
#endif
    cs_status st = cs_render_line_runs(r, y);
    if (st == CS_OK)
        cs_line_pixels(r, fmt, out);
    return st;
}

cs_error cs_frame_error(const cs_renderer *r)
{
    return r->sticky;
}

cs_status cs_render_frame(cs_renderer *r, float *line, cs_line_sink sink, void *user)
{
    if (!r || !line || !sink)
        return CS_ERR_ARG;
    for (int y = r->vy; y < r->vy + r->vh; y++) {
        cs_status st = cs_render_line(r, y, line);
        if (st == CS_OK)
            st = sink(user, y - r->vy, line, r->vw);
        if (st != CS_OK)
            return st;
    }
    return r->sticky.status;
}
