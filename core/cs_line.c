/*
 * cs_line.c - one display line out: the line's runs, made by the stages
 * before it (active pieces and crossings in cs_cross.c, spans and coverage
 * in cs_coverage.c or cs_exact.c, compositing in cs_composite.c), become
 * pixels: E + T L per run, in the display's format (cs_line_pixels) or as
 * floats (cs_render_line), and a frame is its lines in order
 * (cs_render_frame). Nothing is carried from line to line but the active
 * list, so a line comes out the same whichever lines were rendered before it.
 */
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

cs_status cs_render_line_runs(cs_renderer *r, int y)
{
    if (!r || !r->ws || y < r->vy || y - r->vy >= r->vh)
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
