/*
 * cache_anim.c - what pre-combination saves on an animation with a still
 * background (the paper's "static background rendered once").
 *
 * The scene: a sky (opaque, vertical gradient) with a sun (radial glow),
 * hills of closed cubic Beziers, a forest of trees and a translucent mist
 * band make up the background; three characters move in front of it. Each
 * frame moves the characters. The same frames are rendered three ways:
 *
 *   direct    every cel scan-converted every frame (front-to-back early-out on)
 *   no-skip   direct, with the early-out disabled (what front-to-back saves)
 *   cached    the background cels pre-combined once by cs_cache_build and
 *             composited from their (E, T) runs; only the characters are
 *             scan-converted per frame
 *
 * It prints the median time per frame of each, the one-off cost and size of
 * the cache, and the largest difference between cached and direct pixels
 * (the tests hold it to 1/255; it is ~1e-7). It also shows the fallback: a
 * cache buffer too small is reported with the size it would need.
 *
 * Usage: bench_cache_anim [WIDTH HEIGHT [FRAMES]]   (default 1280 720 24)
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "celscan_private.h"
#include "cli_num.h"

static cs_scene scene;
static cs_workspace ws;

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static void die(const char *what, cs_status st)
{
    fprintf(stderr, "bench_cache_anim: %s: %s\n", what, cs_status_str(st));
    exit(1);
}

static void region(float pr, float pg, float pb, float mr, float mg, float mb, float beta)
{
    cs_paint p = {{pr, pg, pb}, {mr, mg, mb}, beta};
    cs_error e;
    cs_status st = cs_scene_add_region(&scene, CS_FILL_NONZERO, &p, &e);
    if (st)
        die("region", st);
}

static void cel(float dx, float dy)
{
    cs_affine m = {1, 0, 0, 1, dx, dy};
    cs_error e;
    cs_status st = cs_scene_add_cel(&scene, &m, NULL, NULL, &e);
    if (st)
        die("cel", st);
}

static void rect(float x0, float y0, float x1, float y1)
{
    cs_point p[4] = {{x0, y0, 1}, {x1, y0, 1}, {x1, y1, 1}, {x0, y1, 1}};
    cs_error e;
    cs_status st = cs_scene_add_contour(&scene, 1, 4, p, NULL, &e);
    if (st)
        die("rect", st);
}

static void circle(float cx, float cy, float r)
{
    const float h = 0.70710678f;
    const float ux[8] = {1, 1, 0, -1, -1, -1, 0, 1}, uy[8] = {0, 1, 1, 1, 0, -1, -1, -1};
    cs_point p[8];
    float iv[8];
    for (int i = 0; i < 8; i++) {
        p[i] = (cs_point){cx + r * ux[i], cy + r * uy[i], (i & 1) ? h : 1.0f};
        iv[i] = (i & 1) ? 0.0f : 1.0f;
    }
    cs_error e;
    cs_status st = cs_scene_add_contour(&scene, 2, 8, p, iv, &e);
    if (st)
        die("circle", st);
}

/* A hill: closed cubic Bezier path of 4 segments over [x0, x1], top at ytop. */
static void hill(float x0, float x1, float ytop, float ybase)
{
    float xm = 0.5f * (x0 + x1), w = x1 - x0;
    cs_point p[12] = {
        {x0, ybase, 1},         {x0 + 0.2f * w, ytop, 1}, {xm - 0.2f * w, ytop, 1},
        {xm, ytop, 1},          {xm + 0.2f * w, ytop, 1}, {x1 - 0.2f * w, ytop, 1},
        {x1, ybase, 1},         {x1, ybase + 30, 1},      {xm, ybase + 30, 1},
        {xm, ybase + 30, 1},    {x0, ybase + 30, 1},      {x0, ybase, 1},
    };
    float iv[12] = {1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0};
    cs_error e;
    cs_status st = cs_scene_add_contour(&scene, 3, 12, p, iv, &e);
    if (st)
        die("hill", st);
}

static void func(cs_paint_field field, int kind, const float *geom, int nstops,
                 const float (*stops)[4])
{
    cs_paint_func f;
    memset(&f, 0, sizeof f);
    f.kind = (uint8_t)kind;
    f.stop_count = (uint8_t)nstops;
    f.map_cols = 1;
    for (int i = 0; i < 6; i++)
        f.geom[i] = geom[i];
    for (int i = 0; i < nstops; i++) {
        f.stops[i].offset = stops[i][0];
        for (int k = 0; k < 3; k++)
            f.stops[i].value[k] = stops[i][k + 1];
    }
    cs_error e;
    cs_status st = cs_scene_set_region_func(&scene, field, &f, &e);
    if (st)
        die("gradient", st);
}

enum { CHARACTERS = 3 };

static void build(void)
{
    const float W = 1280, H = 720;
    cs_scene_init(&scene, W, H);
    /* Front: three characters (body, head, eye), each its own cel. */
    for (int c = 0; c < CHARACTERS; c++) {
        cel(0, 0);
        region(0.02f, 0.02f, 0.02f, 0, 0, 0, 1); /* eye, front-most */
        circle(300 + 350 * c + 12, 430, 7);
        region(0.9f, 0.7f - 0.2f * c, 0.3f + 0.2f * c, 0, 0, 0, 1); /* head */
        circle(300 + 350 * c, 440, 40);
        region(0.2f + 0.3f * c, 0.3f, 0.8f - 0.2f * c, 0, 0, 0, 1); /* body */
        circle(300 + 350 * c, 540, 80);
    }
    /* Background, front to back: mist, forest, hills, sky with sun. */
    cel(0, 0);
    region(0.9f, 0.92f, 0.95f, 1, 1, 1, 0.3f); /* mist: foggy band */
    rect(0, 520, W, 600);
    srand(7);
    for (int t = 0; t < 36; t++) {
        float x = 20 + 35.0f * (float)t + (float)(rand() % 20), s = 0.7f + 0.02f * (float)(t % 15);
        float base = 560 + (float)(rand() % 60);
        cel(0, 0);
        region(0.1f, 0.35f + 0.01f * (float)(t % 10), 0.12f, 0.2f, 0.4f, 0.2f, 0.9f);
        circle(x, base - 120 * s, 45 * s);
        region(0.12f, 0.4f, 0.15f, 0, 0, 0, 1);
        circle(x - 25 * s, base - 80 * s, 35 * s);
        region(0.35f, 0.2f, 0.1f, 0, 0, 0, 1); /* trunk */
        rect(x - 6 * s, base - 60 * s, x + 6 * s, base);
    }
    for (int h = 0; h < 3; h++) {
        cel(0, 0);
        region(0.15f + 0.1f * (float)h, 0.45f - 0.05f * (float)h, 0.2f, 0, 0, 0, 1);
        hill(-200 + 500 * (float)h, 500 + 500 * (float)h, 330 + 40 * (float)h, 560);
        rect(-10, 600, W + 10, H + 10);
    }
    cel(0, 0);
    region(1, 0.9f, 0.6f, 1, 1, 1, 1); /* sun glow: radial beta over the sky */
    circle(1000, 140, 120);
    const float sun[6] = {1000, 140, 120, 1000, 140, 0};
    const float sun_beta[2][4] = {{0.2f, 1, 1, 1}, {1, 0, 0, 0}};
    func(CS_FIELD_BETA, CS_FUNC_RADIAL, sun, 2, sun_beta);
    region(0.3f, 0.5f, 0.9f, 0, 0, 0, 1); /* sky: vertical gradient, opaque */
    rect(0, 0, W, H);
    const float sky[6] = {0, 0, 0, 600, 0, 0};
    const float sky_stops[3][4] = {{0, 0.05f, 0.15f, 0.5f}, {0.7f, 0.5f, 0.7f, 0.95f},
                                   {1, 0.9f, 0.8f, 0.6f}};
    func(CS_FIELD_PIGMENT, CS_FUNC_LINEAR, sky, 3, sky_stops);
}

static void animate(int frame)
{
    for (int c = 0; c < CHARACTERS; c++) {
        double ph = 0.21 * frame + 2.1 * c;
        scene.cels[c].transform.e = (float)(60 * sin(ph) + 3.7 * frame);
        scene.cels[c].transform.f = (float)(25 * cos(1.3 * ph));
    }
}

static float *frame_buf;

static double render_frame(const cs_render_opts *o, const cs_cache *cache, float *out)
{
    cs_renderer r;
    cs_error e;
    double t0 = now_ms();
    cs_status st = cs_frame_begin_cached(&r, &ws, &scene, o, cache, &e);
    if (st)
        die("frame", st);
    for (int y = 0; y < o->height; y++) {
        st = cs_render_line(&r, y, out + (size_t)3 * o->width * y);
        if (st)
            die("line", st);
    }
    return now_ms() - t0;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int main(int argc, char **argv)
{
    long w = 1280, h = 720, n = 24;
    if ((argc > 2 && (!cli_int(argv[1], 10, '\0', 16, CS_CFG_MAX_WIDTH, &w) ||
                      !cli_int(argv[2], 10, '\0', 16, CS_CFG_MAX_HEIGHT, &h))) ||
        (argc > 3 && !cli_int(argv[3], 10, '\0', 1, 100000, &n)) || argc == 2 || argc > 4) {
        fprintf(stderr, "usage: bench_cache_anim [WIDTH HEIGHT [FRAMES]]\n");
        return 2;
    }
    int W = (int)w, H = (int)h, frames = (int)n;
    build();
    cs_render_opts o;
    memset(&o, 0, sizeof o);
    o.width = W;
    o.height = H;
    o.aa = CS_AA_SUBSCAN;
    o.subscanlines = 5;
    size_t px = (size_t)3 * W * H;
    frame_buf = malloc(px * sizeof(float));
    float *ref = malloc(px * sizeof(float));
    double *t_direct = malloc(sizeof(double) * frames), *t_noskip = malloc(sizeof(double) * frames);
    double *t_cached = malloc(sizeof(double) * frames);
    if (!frame_buf || !ref || !t_direct || !t_noskip || !t_cached)
        return 1;
    uint32_t bg_first = CHARACTERS, bg_count = scene.cel_count - CHARACTERS;
    printf("scene: %u cels (%u still background), %u regions, %u contours, %dx%d, aa 5\n",
           scene.cel_count, bg_count, scene.region_count, scene.contour_count, W, H);

    /* The fallback: a buffer too small is reported, with what it needs. */
    static unsigned char small[64 * 1024];
    cs_cache cache;
    cs_error e;
    cs_status st = cs_cache_build(&cache, small, sizeof small, &ws, &scene, &o, bg_first,
                                  bg_count, &e);
    printf("cache in %zu KiB: %s (needs %zu KiB) -> frames render directly\n",
           sizeof small / 1024, cs_status_str(st), cache.bytes_needed / 1024);
    size_t size = cache.bytes_needed;
    void *buf = malloc(size);
    double t0 = now_ms();
    st = cs_cache_build(&cache, buf, size, &ws, &scene, &o, bg_first, bg_count, &e);
    double t_build = now_ms() - t0;
    if (st)
        die("cache", st);
    printf("cache build: %.2f ms once, %u runs, %.1f KiB (%.1f runs/line)\n", t_build,
           cache.run_count, cache.bytes_used / 1024.0, (double)cache.run_count / H);

    double worst = 0;
    for (int f = 0; f < frames; f++) {
        animate(f);
        o.no_early_out = true;
        t_noskip[f] = render_frame(&o, NULL, ref);
        o.no_early_out = false;
        t_direct[f] = render_frame(&o, NULL, ref);
        t_cached[f] = render_frame(&o, &cache, frame_buf);
        for (size_t i = 0; i < px; i++) {
            double d = fabs((double)ref[i] - frame_buf[i]);
            worst = d > worst ? d : worst;
        }
    }
    double md = median(t_direct, frames), mn = median(t_noskip, frames);
    double mc = median(t_cached, frames);
    printf("no-skip : %8.3f ms/frame (median of %d)\n", mn, frames);
    printf("direct  : %8.3f ms/frame  (front-to-back early-out saves %.0f%%)\n", md,
           100 * (1 - md / mn));
    printf("cached  : %8.3f ms/frame  (%.1fx faster than direct; build pays off after %.1f "
           "frames)\n",
           mc, md / mc, t_build / (md - mc));
    printf("cached vs direct: max pixel difference %.2e (linear; limit 1/255 = %.2e)\n", worst,
           1.0 / 255);
    free(buf);
    free(frame_buf);
    free(ref);
    free(t_direct);
    free(t_noskip);
    free(t_cached);
    return worst <= 1.0 / 255 ? 0 : 1;
}
