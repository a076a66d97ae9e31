/*
 * test_runs.c - the run-length line (cs_runs.h) against a per-pixel compositor.
 *
 * The line pipeline keeps the stack, the cel being folded and the finished
 * line as runs of equal pixels. Its truth here is the beta model applied
 * pixel by pixel, in double, by this file: each cel's region is rendered
 * alone as a white coverage image (one region, white paint, front light 1,
 * back light 0: the output is the coverage c itself), then the cels are
 * composited front to back with E_cel = c E, T_cel = 1 - c (1 - T),
 * E += T_s E_cel, T_s *= T_cel and the pixel E + T_s L. Random scenes of
 * overlapping ellipses, opaque and translucent, with coloured lights and
 * with and without a background card, at widths from 1 to 700, in every
 * AA mode.
 *
 * The same scenes (with several regions per cel and gradient paints too)
 * check the ways out of the line: cs_render_line's floats, the runs read
 * with cs_line_run, cs_line_pixels in every pixel format against
 * cs_pixfmt_convert of the floats, and the early-out on and off, which
 * must agree bit for bit, but in exact mode: there an arc behind opaque
 * pixels is stood in for by its height (cs_exact.c, hide), which sums the
 * cover deltas right of it in another order, so a last bit may differ.
 * Half the scenes have grey media, whose frames keep T in one channel;
 * with that path refused (no_grey) they must come out the same bits.
 */
#include <stdlib.h>
#include <string.h>

#include "testlib.h"
#include "common.h"
#include "cs_runs.h"

#define MAX_CELS 24

typedef struct rnd_cel {
    double cx, cy, rx, ry;
    cs_paint paint;
    float front[3], back[3];
} rnd_cel;

typedef struct rnd_scene {
    int n;
    rnd_cel cel[MAX_CELS];
    float stack_front[3], stack_back[3];
    bool has_bg;
    float bg[3];
} rnd_scene;

static float rnd01(void) { return (float)tc_rand(); }

static void make_random(rnd_scene *rs, int W, int H)
{
    rs->n = 1 + (int)(tc_rand() * MAX_CELS);
    for (int ch = 0; ch < 3; ch++) {
        rs->stack_front[ch] = 0.5f + 0.5f * rnd01();
        rs->stack_back[ch] = rnd01();
        rs->bg[ch] = rnd01();
    }
    rs->has_bg = tc_rand() < 0.5;
    /* Half the scenes have grey media only: their frames keep T in one
     * channel (cs_renderer.grey). */
    bool grey_media = tc_rand() < 0.5;
    for (int i = 0; i < rs->n; i++) {
        rnd_cel *c = &rs->cel[i];
        c->cx = tc_uniform(-0.2 * W, 1.2 * W);
        c->cy = tc_uniform(-0.2 * H, 1.2 * H);
        c->rx = tc_uniform(0.3, 0.6 * W + 1);
        c->ry = tc_uniform(0.3, 0.6 * H + 1);
        bool opaque = tc_rand() < 0.5;
        for (int ch = 0; ch < 3; ch++) {
            c->paint.pigment[ch] = rnd01();
            c->paint.medium[ch] = rnd01();
            c->front[ch] = rnd01();
            c->back[ch] = rnd01();
        }
        if (grey_media)
            c->paint.medium[1] = c->paint.medium[2] = c->paint.medium[0];
        c->paint.beta = opaque ? 1.0f : rnd01();
    }
}

static cs_status build_scene(cs_scene *sc, const rnd_scene *rs, int W, int H, int only)
{
    cs_error err;
    cs_status st = cs_scene_init(sc, (float)W, (float)H);
    if (st == CS_OK && only < 0)
        st = cs_scene_set_lights(sc, rs->stack_front, rs->stack_back);
    if (st == CS_OK && only < 0 && rs->has_bg)
        st = cs_scene_set_background(sc, rs->bg);
    for (int i = 0; i < rs->n && st == CS_OK; i++) {
        if (only >= 0 && i != only)
            continue;
        const rnd_cel *c = &rs->cel[i];
        static const float one[3] = {1, 1, 1}, zero[3] = {0, 0, 0};
        cs_paint white = tc_white_paint();
        st = cs_scene_add_cel(sc, &tc_identity, only < 0 ? c->front : one,
                              only < 0 ? c->back : zero, &err);
        if (st == CS_OK)
            st = cs_scene_add_region(sc, CS_FILL_NONZERO, only < 0 ? &c->paint : &white, &err);
        tc_shape *s = tc_shape_new(0);
        tc_add_ellipse(s, c->cx, c->cy, c->rx, c->ry, 0.37 * i, 1);
        if (st == CS_OK)
            st = tc_add_contours(sc, s);
        free(s);
    }
    return st;
}

static cs_status render_as(const cs_scene *sc, int W, int H, cs_aa_mode aa, int nsub,
                           bool early_out, bool grey_path, float *rgb)
{
    cs_renderer r;
    cs_render_opts o = {.width = W, .height = H, .aa = aa, .subscanlines = nsub};
    o.no_early_out = !early_out;
    o.no_grey = !grey_path;
    cs_error err;
    cs_status st = cs_frame_begin(&r, tc_workspace(), sc, &o, &err);
    for (int y = 0; y < H && st == CS_OK; y++)
        st = cs_render_line(&r, y, rgb + (size_t)3 * W * y);
    return st;
}

static cs_status render(const cs_scene *sc, int W, int H, cs_aa_mode aa, int nsub, bool early_out,
                        float *rgb)
{
    return render_as(sc, W, H, aa, nsub, early_out, true, rgb);
}

/* One random scene against the per-pixel double compositor. */
static void check_against_pixels(int W, int H, cs_aa_mode aa, int nsub, const char *mode)
{
    rnd_scene rs;
    make_random(&rs, W, H);
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    size_t n = (size_t)W * H;
    float *got = tl_calloc(3 * n, sizeof *got);
    float *cov = tl_calloc(3 * n, sizeof *cov);
    double *E = tl_calloc(3 * n, sizeof *E), *T = tl_calloc(3 * n, sizeof *T);
    for (size_t i = 0; i < 3 * n; i++)
        T[i] = 1.0;
    bool ok = build_scene(sc, &rs, W, H, -1) == CS_OK && render(sc, W, H, aa, nsub, true, got) == CS_OK;
    for (int c = 0; c < rs.n && ok; c++) {
        ok = build_scene(sc, &rs, W, H, c) == CS_OK && render(sc, W, H, aa, nsub, true, cov) == CS_OK;
        const rnd_cel *k = &rs.cel[c];
        for (size_t i = 0; i < n && ok; i++) {
            double cv = cov[3 * i];
            for (int ch = 0; ch < 3; ch++) {
                double beta = k->paint.beta, clear = (1.0 - beta) * k->paint.medium[ch];
                double e = beta * k->paint.pigment[ch] * k->front[ch] + clear * k->back[ch];
                E[3 * i + ch] += T[3 * i + ch] * cv * e;
                T[3 * i + ch] *= 1.0 - cv * (1.0 - clear);
            }
        }
    }
    double worst = 0.0;
    size_t at = 0;
    for (size_t i = 0; i < 3 * n && ok; i++) {
        int ch = (int)(i % 3);
        double L = rs.has_bg ? (double)rs.bg[ch] * rs.stack_front[ch] : rs.stack_back[ch];
        double want = E[i] + T[i] * L;
        want = want < 0.0 ? 0.0 : want > 1.0 ? 1.0 : want;
        double d = fabs(got[i] - want);
        if (d > worst) {
            worst = d;
            at = i / 3;
        }
    }
    CHECK(ok, "%s %dx%d: a scene did not render", mode, W, H);
    CHECK(worst <= 2e-5, "%s %dx%d, %d cels: worst |runs - per-pixel| %.3g at (%d,%d)", mode, W, H,
          rs.n, worst, (int)(at % (size_t)W), (int)(at / (size_t)W));
    free(sc);
    free(got);
    free(cov);
    free(E);
    free(T);
}

/* Adds a second, overlapping region and a linear gradient to some cels. */
static cs_status build_rich(cs_scene *sc, const rnd_scene *rs, int W, int H)
{
    cs_error err;
    cs_status st = cs_scene_init(sc, (float)W, (float)H);
    if (st == CS_OK)
        st = cs_scene_set_lights(sc, rs->stack_front, rs->stack_back);
    for (int i = 0; i < rs->n && st == CS_OK; i++) {
        const rnd_cel *c = &rs->cel[i];
        st = cs_scene_add_cel(sc, &tc_identity, c->front, c->back, &err);
        for (int k = 0; k < 1 + (i % 3 == 0) && st == CS_OK; k++) {
            st = cs_scene_add_region(sc, k ? CS_FILL_EVENODD : CS_FILL_NONZERO, &c->paint, &err);
            if (st == CS_OK && i % 4 == 1) {
                cs_paint_func fn;
                memset(&fn, 0, sizeof fn);
                fn.kind = CS_FUNC_LINEAR;
                fn.geom[0] = (float)c->cx;
                fn.geom[2] = (float)(c->cx + c->rx);
                fn.geom[3] = (float)c->ry;
                fn.stop_count = 2;
                fn.stops[1].offset = 1.0f;
                for (int ch = 0; ch < 3; ch++)
                    fn.stops[1].value[ch] = c->paint.pigment[ch];
                st = cs_scene_set_region_func(sc, CS_FIELD_PIGMENT, &fn, &err);
            }
            tc_shape *s = tc_shape_new(0);
            tc_add_ellipse(s, c->cx + 0.3 * k * c->rx, c->cy, c->rx, c->ry * (1.0 - 0.4 * k), 0.37 * i, 1);
            if (st == CS_OK)
                st = tc_add_contours(sc, s);
            free(s);
        }
    }
    return st;
}

static const cs_pixfmt all_formats[] = {CS_PIX_RGB888_SRGB, CS_PIX_RGB888_LINEAR,
                                        CS_PIX_RGB565_SRGB, CS_PIX_RGB444_SRGB,
                                        CS_PIX_RGB332_SRGB, CS_PIX_RGB16_LINEAR};

/* Largest difference between two renders. */
static double max_diff(const float *a, const float *b, size_t n)
{
    double worst = 0.0;
    for (size_t i = 0; i < n; i++) {
        double d = a[i] > b[i] ? a[i] - b[i] : b[i] - a[i];
        worst = d > worst ? d : worst;
    }
    return worst;
}

/* The ways out of a line agree, and the early-out changes no bit (exact
 * mode: none beyond float rounding). */
static void check_outputs(int W, int H, cs_aa_mode aa, int nsub, const char *mode)
{
    rnd_scene rs;
    make_random(&rs, W, H);
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    size_t n = (size_t)W * H;
    float *a = tl_calloc(3 * n, sizeof *a), *b = tl_calloc(3 * n, sizeof *b);
    float *line = tl_calloc(3 * (size_t)W, sizeof *line);
    uint8_t *want = tl_calloc(6 * (size_t)W, 1), *px = tl_calloc(6 * (size_t)W, 1);
    bool ok = build_rich(sc, &rs, W, H) == CS_OK && render(sc, W, H, aa, nsub, true, a) == CS_OK &&
              render(sc, W, H, aa, nsub, false, b) == CS_OK;
    CHECK(ok, "%s %dx%d: the rich scene did not render", mode, W, H);
    if (aa == CS_AA_EXACT)
        CHECK(!ok || max_diff(a, b, 3 * n) <= 1e-6, "%s %dx%d: early-out on and off differ by %g",
              mode, W, H, max_diff(a, b, 3 * n));
    else
        CHECK(!ok || memcmp(a, b, 3 * n * sizeof *a) == 0,
              "%s %dx%d: early-out on and off differ", mode, W, H);
    /* The grey path (grey media, half the scenes) and the three channels:
     * the same bits. */
    ok = ok && render_as(sc, W, H, aa, nsub, true, false, b) == CS_OK;
    CHECK(!ok || memcmp(a, b, 3 * n * sizeof *a) == 0,
          "%s %dx%d: the grey path and three channels differ", mode, W, H);
    int bad_runs = 0, bad_px = 0, bad_walk = 0, bad_guard = 0;
    cs_renderer r;
    cs_render_opts o = {.width = W, .height = H, .aa = aa, .subscanlines = nsub};
    cs_error err;
    ok = ok && cs_frame_begin(&r, tc_workspace(), sc, &o, &err) == CS_OK;
    for (int y = 0; y < H && ok; y++) {
        ok = cs_render_line_runs(&r, y) == CS_OK;
        const float *row = a + (size_t)3 * W * y;
        int x = 0;
        while (x < W && ok) {
            float c[3];
            int next = cs_line_run(&r, x, c);
            if (next <= x || next > W) {
                bad_walk++;
                break;
            }
            for (int k = x; k < next; k++)
                if (memcmp(&row[3 * k], c, sizeof c) != 0)
                    bad_runs++;
            x = next;
        }
        if (x != W)
            bad_walk++;
        for (size_t f = 0; f < sizeof all_formats / sizeof all_formats[0]; f++) {
            size_t bytes = (size_t)W * cs_pixfmt_bytes_per_pixel(all_formats[f]);
            cs_pixfmt_convert(all_formats[f], row, W, want);
            /* The bytes past the line are guards (the 8-bit runs may write
             * ahead of a run, within the line only: cs_pixfmt.c). */
            memset(px, 0xA5, 6 * (size_t)W);
            cs_line_pixels(&r, all_formats[f], px);
            if (memcmp(want, px, bytes) != 0)
                bad_px++;
            for (size_t k = bytes; k < 6 * (size_t)W; k++)
                bad_guard += px[k] != 0xA5;
        }
    }
    CHECK(ok && bad_walk == 0, "%s %dx%d: the runs do not tile the line (%d lines)", mode, W, H,
          bad_walk);
    CHECK(bad_runs == 0, "%s %dx%d: %d pixels of cs_line_run differ from cs_render_line", mode, W,
          H, bad_runs);
    CHECK(bad_px == 0, "%s %dx%d: cs_line_pixels differs from cs_pixfmt_convert on %d lines", mode,
          W, H, bad_px);
    CHECK(bad_guard == 0, "%s %dx%d: cs_line_pixels wrote %d bytes past the line", mode, W, H,
          bad_guard);
    /* cs_render_line_px is the two steps in one, on every line: its bytes,
     * none past the line, and the runs it leaves (in 8-bit sRGB the x86-64-v3
     * build finishes and converts in one pass: make test-runs-v3). */
    static const cs_pixfmt px_formats[] = {CS_PIX_RGB888_SRGB, CS_PIX_RGB565_SRGB};
    for (size_t f = 0; f < 2 && ok; f++) {
        size_t bytes = (size_t)W * cs_pixfmt_bytes_per_pixel(px_formats[f]);
        int bad_line = 0, bad_left = 0;
        ok = cs_frame_begin(&r, tc_workspace(), sc, &o, &err) == CS_OK;
        for (int y = 0; y < H && ok; y++) {
            const float *row = a + (size_t)3 * W * y;
            memset(px, 0xA5, 6 * (size_t)W);
            ok = cs_render_line_px(&r, y, px_formats[f], px) == CS_OK;
            cs_pixfmt_convert(px_formats[f], row, W, want);
            bool same = memcmp(want, px, bytes) == 0;
            for (size_t k = bytes; k < 6 * (size_t)W; k++)
                same = same && px[k] == 0xA5;
            bad_line += !same;
            for (int x = 0, next; x < W && ok; x = next) {
                float c[3];
                next = cs_line_run(&r, x, c);
                bad_left += next <= x || next > W || memcmp(&row[3 * x], c, sizeof c) != 0;
                next = next <= x ? W : next;
            }
        }
        CHECK(ok && bad_line == 0, "%s %dx%d: cs_render_line_px (format %d) differs on %d lines",
              mode, W, H, (int)px_formats[f], bad_line);
        CHECK(bad_left == 0, "%s %dx%d: cs_render_line_px (format %d) left %d wrong runs", mode,
              W, H, (int)px_formats[f], bad_left);
    }
    free(sc);
    free(a);
    free(b);
    free(line);
    free(want);
    free(px);
}

/* A random bitmap of `nw` words: bits set with probability p, and a few
 * stretches of whole set words, so that long spans can be all set. */
static void random_bits(uint32_t *bits, size_t nw, double p)
{
    for (size_t w = 0; w < nw; w++) {
        uint32_t v = 0;
        for (int k = 0; k < 32; k++)
            if (tc_rand() < p)
                v |= 1u << k;
        bits[w] = v;
    }
    for (int k = 0; k < 3; k++) {
        size_t w0 = (size_t)(tc_rand() * (double)nw), n = (size_t)(tc_rand() * 8.0);
        for (size_t w = w0; w < w0 + n && w < nw; w++)
            bits[w] = 0xFFFFFFFFu;
    }
}

/* cs_runs.h's bitmap tests against a bit at a time: cs__span_opaque (the
 * clear bits shifted past the span's ends) on spans of every length from
 * 1 to the width, cs__mark_opaque (the same spans set on a clear bitmap)
 * and cs__run_start (a backward scan, two words a step on x86-64) on
 * sparse and dense run starts. */
static void check_bitmaps(void)
{
    tl_current = "bitmaps";
    cs_workspace *ws = calloc(1, sizeof *ws);
    cs_renderer r;
    memset(&r, 0, sizeof r);
    r.ws = ws;
    r.opaque_px = 1; /* anything but 0: the bits decide */
    const uint32_t W = CS_CFG_MAX_WIDTH;
    const size_t nw = (W + 31u) / 32u;
    static const double density[] = {0.002, 0.05, 0.5, 0.97, 0.999};
    int bad_span = 0, bad_start = 0;
    for (int rep = 0; rep < 100; rep++) {
        double p = density[rep % 5];
        random_bits(ws->opaque_bits, nw, p);
        for (int q = 0; q < 400; q++) {
            uint32_t a = (uint32_t)(tc_rand() * W);
            uint32_t most = q & 1 ? 70u : W - a;
            uint32_t b = a + 1u + (uint32_t)(tc_rand() * most);
            b = b > W ? W : b;
            bool want = true;
            for (uint32_t x = a; x < b && want; x++)
                want = (ws->opaque_bits[x >> 5] >> (x & 31u)) & 1u;
            bad_span += cs__span_opaque(&r, a, b) != want;
        }
        random_bits(ws->run_starts, nw, p < 0.5 ? p / 10.0 : 0.0);
        ws->run_starts[0] |= 1u; /* pixel 0 starts a run */
        for (int q = 0; q < 400; q++) {
            uint32_t x = (uint32_t)(tc_rand() * W), want = x;
            while (!((ws->run_starts[want >> 5] >> (want & 31u)) & 1u))
                want--;
            bad_start += cs__run_start(ws, x) != want;
        }
    }
    int bad_mark = 0;
    for (int q = 0; q < 4000; q++) { /* cs__mark_opaque sets [a, b) alone */
        uint32_t a = (uint32_t)(tc_rand() * W);
        uint32_t b = a + 1u + (uint32_t)(tc_rand() * (q & 1 ? 70u : W - a));
        b = b > W ? W : b;
        memset(ws->opaque_bits, 0, sizeof ws->opaque_bits);
        cs__mark_opaque(ws, a, b);
        for (uint32_t x = 0; x < nw * 32u; x++)
            bad_mark += ((ws->opaque_bits[x >> 5] >> (x & 31u)) & 1u) != (x >= a && x < b);
    }
    CHECK(bad_span == 0, "cs__span_opaque: %d of 40000 spans wrong", bad_span);
    CHECK(bad_mark == 0, "cs__mark_opaque: %d wrong bits in 4000 spans", bad_mark);
    CHECK(bad_start == 0, "cs__run_start: %d of 40000 pixels wrong", bad_start);
    free(ws);
    tl_current = "";
}

int main(void)
{
    check_bitmaps();
    static const int sizes[][2] = {{1, 9}, {7, 5}, {33, 20}, {64, 48}, {97, 61}, {700, 40}};
    tc_seed(20261121);
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        int W = sizes[s][0], H = sizes[s][1];
        for (int rep = 0; rep < 4; rep++) {
            check_against_pixels(W, H, CS_AA_NONE, 1, "none");
            check_against_pixels(W, H, CS_AA_SUBSCAN, 5, "aa5");
            check_against_pixels(W, H, CS_AA_EXACT, 1, "exact");
            check_outputs(W, H, CS_AA_SUBSCAN, 16, "aa16");
            check_outputs(W, H, CS_AA_EXACT, 1, "exact");
        }
    }
    return tl_summary("test_runs");
}
