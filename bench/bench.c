/*
 * bench.c - celscan against cairo, FreeType and AGG, in one process, on one core.
 *
 *   bench [--sections speed,accuracy,beam,scaling] [--scenes blobs,signage,...]
 *         [--size WxH] [--repeat N] [--frames N] [--shapes N] [--out DIR] [--quick]
 *   bench --profile SCENE [--aa none|N|exact] [--size WxH] [--frames N] [--cache]
 *   bench --profile SCENE [--aa ...] [--size WxH] --band K/N | --part K/N
 *   bench --profile SCENE --peer cairo|cairo-fine|freetype|agg [--size WxH] [--frames N]
 *   bench --selftest
 *
 * For each reference scene (BENCHMARKS.md) the same geometry is rendered by
 *
 *   celscan   cs_frame_begin, then cs_render_line_px (8-bit sRGB) for
 *             every line: what celsim does (a board: cs_render_line_runs
 *             and cs_line_pixels);
 *   cairo     an ARGB32 image surface, default antialias and tolerance;
 *   FreeType  FT_Outline_Render (smooth, direct spans) with a span compositor;
 *   AGG       Anti-Grain Geometry's scanline rasterizer with its defaults;
 *
 * and the medians of N interleaved runs are compared (ratio celscan/peer:
 * below 1 means celscan is faster). Quality comes with speed: the accuracy
 * section measures every renderer's coverage against the exact reference
 * (accuracy.c). The beam section times every single line (median over runs
 * per line) against the line period of a display scanned out at 60 Hz. The
 * scaling section varies output height, segment count and sub-scanlines.
 *
 * The peers get their Bezier paths ready-made in device space (outline.c,
 * outside the timing); celscan's timed frame includes its own per-frame
 * preparation from NURBS control points. Every timed path ends with pixels
 * in memory: 8-bit sRGB RGB for celscan, 8-bit premultiplied ARGB for the
 * peers.
 *
 * Tables are printed and, with --out, written as DIR/<section>.txt in
 * Markdown, for tools/bench_md.py to splice into BENCHMARKS.md.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bands.h"
#include "bench.h"
#include "cli_num.h"
#include "ref/ref.h"
#include "scene_json.h"

/* Line periods of the displays the beam report races (60 Hz). */
static const struct {
    int w, h;
    double period_us;
    const char *name;
} displays[] = {
    {1920, 1080, 14.8, "1080p60"},
    {1280, 720, 22.2, "720p60"},
    {480, 272, 61.0, "480x272@60"},
};

typedef struct bench_scene_def {
    const char *name, *title, *path;
} bench_scene_def;

static const bench_scene_def scene_defs[] = {
    {"blobs", "Many-blobs", "scenes/bench/blobs.json"},
    {"signage", "Signage (demo)", "scenes/demo.json"},
    {"thin", "Thin-and-small", "scenes/bench/thin.json"},
    {"rational", "Rational", "scenes/bench/rational.json"},
    {"anim", "Animation", "scenes/bench/anim.json"},
};
#define SCENE_COUNT (int)(sizeof scene_defs / sizeof scene_defs[0])

typedef struct config {
    int width, height;
    int repeat;
    int frames;     /* animation frames */
    int shapes;     /* accuracy sample per scene */
    const char *out_dir;
    bool sections[4];
    bool scenes[SCENE_COUNT];
    bool quick;
} config;

enum { SEC_SPEED, SEC_ACCURACY, SEC_BEAM, SEC_SCALING };
static const char *const section_names[4] = {"speed", "accuracy", "beam", "scaling"};

/* Big state lives here once: the core's scene store and workspace are megabytes. */
static cs_scene *g_scene;
static cs_workspace *g_ws;

/* ---------------------------------------------------------------- utils */

double bench_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double bench_median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static void die(const char *fmt, ...)
{
    va_list ap;
    fputs("bench: ", stderr);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    exit(1);
}

/* Printing to stdout and to the section's results file at once. */
static FILE *g_out;

#if defined(__GNUC__)
__attribute__((format(printf, 1, 2)))
#endif
static void out(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    if (g_out) {
        va_start(ap, fmt);
        vfprintf(g_out, fmt, ap);
        va_end(ap);
    }
    fflush(stdout);
}

static void section_open(const config *cfg, int sec)
{
    g_out = NULL;
    if (!cfg->out_dir)
        return;
    char path[1024];
    snprintf(path, sizeof path, "%s/%s.txt", cfg->out_dir, section_names[sec]);
    g_out = fopen(path, "w");
    if (!g_out)
        die("cannot write %s", path);
}

static void section_close(void)
{
    if (g_out)
        fclose(g_out);
    g_out = NULL;
}

static void load(const bench_scene_def *d)
{
    char err[SCENE_JSON_ERRLEN];
    if (scene_json_load(d->path, g_scene, err, sizeof err) != 0)
        die("%s (run bench/gen_scenes.py first?)", err);
}

static const char *aa_name(cs_aa_mode aa, int n, char *buf, size_t len)
{
    if (aa == CS_AA_NONE)
        return "none";
    if (aa == CS_AA_EXACT)
        return "exact";
    snprintf(buf, len, "%d", n);
    return buf;
}

/* ------------------------------------------------------ celscan frames */

typedef struct cs_target {
    int w, h;
    float *line;
    uint8_t *image;  /* w*h*3 bytes, 8-bit sRGB */
    cs_cache cache;
    void *cache_buf;
    bool cached;
} cs_target;

static void target_init(cs_target *t, int w, int h)
{
    memset(t, 0, sizeof *t);
    t->w = w;
    t->h = h;
    t->line = malloc((size_t)w * 3 * sizeof *t->line);
    t->image = malloc((size_t)w * h * 3);
    if (!t->line || !t->image)
        die("out of memory");
}

static void target_free(cs_target *t)
{
    free(t->line);
    free(t->image);
    free(t->cache_buf);
}

static cs_render_opts opts_for(int w, int h, cs_aa_mode aa, int n)
{
    cs_render_opts o = cs_render_defaults(w, h);
    o.aa = aa;
    if (aa == CS_AA_SUBSCAN)
        o.subscanlines = n;
    return o;
}

/* What callgrind counts by name (--toggle-collect=celscan_frame or
 * peer_frame) must stay one function under that name: not inlined, and
 * not cloned for constant arguments (GCC's "peer_frame.constprop.0"). */
#if defined(__GNUC__) && !defined(__clang__)
#define PROFILED __attribute__((noinline, noclone))
#else
#define PROFILED __attribute__((noinline))
#endif

/* One whole frame, as celsim renders it; returns seconds. */
PROFILED static double celscan_frame(cs_target *t, const cs_render_opts *o)
{
    cs_renderer r;
    cs_error e;
    double t0 = bench_now();
    cs_status st = t->cached ? cs_frame_begin_cached(&r, g_ws, g_scene, o, &t->cache, &e)
                             : cs_frame_begin(&r, g_ws, g_scene, o, &e);
    if (st != CS_OK)
        die("cs_frame_begin: %s", cs_status_str(st));
    for (int y = 0; y < t->h; y++) {
        cs_render_line_px(&r, y, CS_PIX_RGB888_SRGB, t->image + (size_t)y * t->w * 3);
    }
    double dt = bench_now() - t0;
    if (cs_frame_error(&r).status != CS_OK)
        die("frame degraded: %s", cs_status_str(cs_frame_error(&r).status));
    return dt;
}

/*
 * --band K/N, for the critical path of N threads (tools/bench_threads.sh):
 * the frame is prepared once (celscan_prepare), and band K of N equal
 * bands of lines is rendered as a thread of celsim --threads renders its
 * lines, in a workspace of its own sharing the prepared frame
 * (celscan_band: cs_frame_share, then each line's pixels). Callgrind
 * counts each function by name.
 */
PROFILED static void celscan_prepare(cs_renderer *r, const cs_render_opts *o)
{
    cs_error e;
    if (cs_frame_begin(r, g_ws, g_scene, o, &e) != CS_OK)
        die("cs_frame_begin failed");
}

PROFILED static void celscan_band(cs_target *t, const cs_renderer *prepared, cs_workspace *ws,
                                  int y0, int y1)
{
    cs_renderer r;
    if (cs_frame_share(&r, ws, prepared) != CS_OK)
        die("cs_frame_share failed");
    for (int y = y0; y < y1; y++) {
        cs_render_line_px(&r, y, CS_PIX_RGB888_SRGB, t->image + (size_t)y * t->w * 3);
    }
    if (cs_frame_error(&r).status != CS_OK)
        die("band degraded: %s", cs_status_str(cs_frame_error(&r).status));
}

static void profile_band(cs_target *t, const cs_render_opts *o, long k, long n)
{
    cs_workspace *ws = calloc(1, sizeof *ws);
    if (!ws)
        die("out of memory");
    cs_renderer prepared;
    celscan_prepare(&prepared, o);
    celscan_band(t, &prepared, ws, (int)(t->h * k / n), (int)(t->h * (k + 1) / n));
    free(ws);
}

/*
 * --part K/N, the frame prepared as celsim --threads N prepares it
 * (host-sim/bands.c, bands_prepare): the cels cut into N parts (bands_cut),
 * each prepared in a renderer and workspace of its own, part K by
 * celscan_part, then the parts joined into part 0's renderer by
 * celscan_join. On N idle cores the preparation takes the largest part and
 * the join.
 */
static void begin_part(cs_renderer *r, cs_workspace *ws, const cs_render_opts *o, uint32_t lo,
                       uint32_t hi)
{
    cs_error e;
    if (cs_frame_begin_part(r, ws, g_scene, o, lo, hi, &e) != CS_OK)
        die("cs_frame_begin_part failed");
}

PROFILED static void celscan_part(cs_renderer *r, cs_workspace *ws, const cs_render_opts *o,
                                  uint32_t lo, uint32_t hi)
{
    begin_part(r, ws, o, lo, hi);
}

PROFILED static void celscan_join(cs_renderer *r, const cs_renderer *const *parts, int n)
{
    if (cs_frame_join(r, parts, n) != CS_OK)
        die("cs_frame_join failed");
}

static void profile_part(const cs_render_opts *o, long k, long n)
{
    uint32_t cut[BANDS_MAX_THREADS + 1];
    bands_cut(g_scene, (int)n, cut);
    cs_renderer *r = calloc((size_t)n, sizeof *r);
    cs_workspace **ws = calloc((size_t)n, sizeof *ws);
    const cs_renderer **rest = calloc((size_t)n, sizeof *rest);
    if (!r || !ws || !rest)
        die("out of memory");
    for (long i = 0; i < n; i++) {
        ws[i] = i == 0 ? g_ws : calloc(1, sizeof *ws[i]);
        if (!ws[i])
            die("out of memory");
        if (i == k)
            celscan_part(&r[i], ws[i], o, cut[i], cut[i + 1]);
        else
            begin_part(&r[i], ws[i], o, cut[i], cut[i + 1]);
        if (i > 0)
            rest[i - 1] = &r[i];
    }
    celscan_join(&r[0], rest, (int)n - 1);
    for (long i = 1; i < n; i++)
        free(ws[i]);
    free(rest);
    free(ws);
    free(r);
}

/* Pre-combines cels [from, cel_count) into t's cache; returns the build time. */
static double celscan_cache(cs_target *t, const cs_render_opts *o, uint32_t from)
{
    cs_error e;
    free(t->cache_buf);
    t->cache_buf = NULL;
    t->cached = false;
    uint32_t count = g_scene->cel_count - from;
    if (count == 0)
        return 0.0;
    cs_cache_build(&t->cache, NULL, 0, g_ws, g_scene, o, from, count, &e);
    size_t need = t->cache.bytes_needed;
    t->cache_buf = malloc(need ? need : 1);
    double t0 = bench_now();
    cs_status st = cs_cache_build(&t->cache, t->cache_buf, need, g_ws, g_scene, o, from, count, &e);
    double dt = bench_now() - t0;
    if (st != CS_OK)
        die("cs_cache_build: %s", cs_status_str(st));
    t->cached = true;
    return dt;
}

/* --------------------------------------------------------------- speed */

enum { V_CS16, V_CSX, V_CAIRO, V_CAIRO_FINE, V_FT, V_AGG, V_COUNT };

typedef struct peers {
    peer_cairo *cairo, *cairo_fine;
    peer_ft *ft;
    peer_agg *agg;
    ol_set set;
} peers;

static void peers_init(peers *p, int w, int h)
{
    memset(p, 0, sizeof *p);
    p->cairo = peer_cairo_new(w, h, 0.1);
    p->cairo_fine = peer_cairo_new(w, h, 0.01);
    p->ft = peer_ft_new(w, h);
    p->agg = peer_agg_new(w, h);
    if (!p->cairo || !p->cairo_fine || !p->ft || !p->agg)
        die("cannot set up cairo / FreeType / AGG at %dx%d", w, h);
}

static void peers_prepare(peers *p, int w, int h)
{
    ol_free(&p->set);
    if (ol_build(&p->set, g_scene, w, h) < 0 || peer_ft_prepare(p->ft, &p->set) != 0)
        die("cannot convert the scene to peer outlines");
}

static void peers_free(peers *p)
{
    peer_cairo_free(p->cairo);
    peer_cairo_free(p->cairo_fine);
    peer_ft_free(p->ft);
    peer_agg_free(p->agg);
    ol_free(&p->set);
}

/*
 * Peer `which` (V_CAIRO, V_CAIRO_FINE, V_FT or V_AGG) draws regions [first, end)
 * of its outlines; returns seconds. PROFILED, so that callgrind can count
 * a peer's frame alone (--toggle-collect=peer_frame, bench --profile
 * SCENE --peer NAME), as it counts celscan_frame.
 */
PROFILED static double peer_frame(peers *p, int which, int first, int end, bool over_saved)
{
    double t0 = bench_now();
    if (which == V_CAIRO)
        peer_cairo_frame(p->cairo, &p->set, first, end, over_saved);
    else if (which == V_CAIRO_FINE)
        peer_cairo_frame(p->cairo_fine, &p->set, first, end, over_saved);
    else if (which == V_FT)
        peer_ft_frame(p->ft, &p->set, first, end, over_saved);
    else
        peer_agg_frame(p->agg, &p->set, first, end, over_saved);
    return bench_now() - t0;
}

static double time_variant(int v, cs_target *t16, cs_target *tx, peers *p, int first, int end,
                           bool over_saved)
{
    if (v == V_CS16) {
        cs_render_opts o = opts_for(t16->w, t16->h, CS_AA_SUBSCAN, 16);
        return celscan_frame(t16, &o);
    }
    if (v == V_CSX) {
        cs_render_opts o = opts_for(tx->w, tx->h, CS_AA_EXACT, 0);
        return celscan_frame(tx, &o);
    }
    return peer_frame(p, v, first, end, over_saved);
}

/* How far apart two pixels are: the mean of their R, G and B differences
 * (of 255), the one measure of "the same picture" here. */
static double rgb_diff(uint32_t argb, int r, int g, int b)
{
    return (abs((int)((argb >> 16) & 255u) - r) + abs((int)((argb >> 8) & 255u) - g) +
            abs((int)(argb & 255u) - b)) / 3.0;
}

/*
 * How alike celscan's picture (blended in sRGB, as cairo blends) and
 * cairo's are: a check that both drew the same scene, not a quality figure.
 */
static void agreement(cs_target *t, peers *p, double *mean, double *big)
{
    cs_render_opts o = opts_for(t->w, t->h, CS_AA_SUBSCAN, 16);
    o.blend = CS_BLEND_SRGB;
    bool was = t->cached;
    t->cached = false;
    celscan_frame(t, &o);
    t->cached = was;
    int stride;
    const uint32_t *px = peer_cairo_pixels(p->cairo, &stride);
    double sum = 0;
    long n = 0, over = 0;
    for (int y = 0; y < t->h; y++)
        for (int x = 0; x < t->w; x++) {
            const uint8_t *s = &t->image[((size_t)y * t->w + x) * 3];
            double d = rgb_diff(px[(size_t)y * (stride / 4) + x], s[0], s[1], s[2]);
            sum += d;
            over += d > 8.0;
            n++;
        }
    *mean = sum / (double)n;
    *big = 100.0 * (double)over / (double)n;
}

typedef struct speed_row {
    double ms[V_COUNT];
    double agree_mean, agree_big;
} speed_row;

static void speed_static(const config *cfg, const bench_scene_def *d, speed_row *row)
{
    int w = cfg->width, h = cfg->height, n = cfg->repeat;
    load(d);
    cs_target t16, tx;
    target_init(&t16, w, h);
    target_init(&tx, w, h);
    peers p;
    peers_init(&p, w, h);
    peers_prepare(&p, w, h);
    double *s = malloc((size_t)V_COUNT * n * sizeof *s);
    /* One warm-up of each, then n interleaved runs: load on a shared machine
     * then falls on every variant alike. */
    for (int v = 0; v < V_COUNT; v++)
        time_variant(v, &t16, &tx, &p, 0, p.set.region_count, false);
    for (int k = 0; k < n; k++)
        for (int v = 0; v < V_COUNT; v++)
            s[v * n + k] = time_variant(v, &t16, &tx, &p, 0, p.set.region_count, false);
    for (int v = 0; v < V_COUNT; v++)
        row->ms[v] = 1e3 * bench_median(&s[v * n], n);
    agreement(&t16, &p, &row->agree_mean, &row->agree_big);
    free(s);
    peers_free(&p);
    target_free(&t16);
    target_free(&tx);
}

/*
 * The animation: frames at 60 Hz, each variant once per frame (interleaved),
 * direct and with a static-background cache (celscan: cs_cache_build of the
 * cels behind every animated one; peers: that background drawn once and
 * copied into each frame).
 */
typedef struct anim_row {
    double direct[V_COUNT], cached[V_COUNT]; /* median ms per frame */
    double cache_ms[2];                      /* celscan cache builds: aa 16, exact */
    int frames;
    uint32_t static_from;
} anim_row;

static void speed_anim(const config *cfg, const bench_scene_def *d, anim_row *row)
{
    int w = cfg->width, h = cfg->height, nf = cfg->frames;
    load(d);
    anim *a = anim_load(d->path, g_scene);
    row->frames = nf;
    row->static_from = anim_static_from(a, g_scene);
    cs_target t16, tx;
    target_init(&t16, w, h);
    target_init(&tx, w, h);
    peers p;
    peers_init(&p, w, h);
    /* The backgrounds: celscan caches, and the peers' saved images. */
    anim_apply(a, g_scene, 0.0);
    cs_render_opts o16 = opts_for(w, h, CS_AA_SUBSCAN, 16), ox = opts_for(w, h, CS_AA_EXACT, 0);
    row->cache_ms[0] = 1e3 * celscan_cache(&t16, &o16, row->static_from);
    row->cache_ms[1] = 1e3 * celscan_cache(&tx, &ox, row->static_from);
    peers_prepare(&p, w, h);
    int static_region = p.set.region_count;
    for (int i = 0; i < p.set.region_count; i++)
        if ((uint32_t)p.set.regions[i].cel >= row->static_from) {
            static_region = i;
            break;
        }
    peer_cairo_frame(p.cairo, &p.set, static_region, p.set.region_count, false);
    peer_cairo_save_background(p.cairo);
    peer_cairo_frame(p.cairo_fine, &p.set, static_region, p.set.region_count, false);
    peer_cairo_save_background(p.cairo_fine);
    peer_ft_frame(p.ft, &p.set, static_region, p.set.region_count, false);
    peer_ft_save_background(p.ft);
    peer_agg_frame(p.agg, &p.set, static_region, p.set.region_count, false);
    peer_agg_save_background(p.agg);

    double *sd = malloc((size_t)V_COUNT * nf * sizeof *sd);
    double *sc = malloc((size_t)V_COUNT * nf * sizeof *sc);
    for (int f = 0; f < nf; f++) {
        anim_apply(a, g_scene, f / 60.0);
        peers_prepare(&p, w, h);
        for (int v = 0; v < V_COUNT; v++) {
            bool c16 = t16.cached, cx = tx.cached;
            t16.cached = tx.cached = false;
            sd[v * nf + f] = time_variant(v, &t16, &tx, &p, 0, p.set.region_count, false);
            t16.cached = c16;
            tx.cached = cx;
            sc[v * nf + f] = time_variant(v, &t16, &tx, &p, 0, static_region, true);
        }
    }
    for (int v = 0; v < V_COUNT; v++) {
        row->direct[v] = 1e3 * bench_median(&sd[v * nf], nf);
        row->cached[v] = 1e3 * bench_median(&sc[v * nf], nf);
    }
    free(sd);
    free(sc);
    anim_free(a);
    peers_free(&p);
    target_free(&t16);
    target_free(&tx);
}

static void run_speed(const config *cfg)
{
    section_open(cfg, SEC_SPEED);
    out("### Speed at %dx%d: median ms per frame over %d interleaved runs\n\n", cfg->width,
        cfg->height, cfg->repeat);
    out("| scene | celscan aa 16 | celscan exact | cairo | cairo tol 0.01 | FreeType | AGG "
        "| aa16/cairo | exact/cairo | aa16/FT | exact/FT | exact/AGG | picture vs cairo |\n");
    out("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    anim_row ar;
    bool have_anim = false;
    for (int i = 0; i < SCENE_COUNT; i++) {
        if (!cfg->scenes[i])
            continue;
        if (strcmp(scene_defs[i].name, "anim") == 0) {
            speed_anim(cfg, &scene_defs[i], &ar);
            have_anim = true;
            continue;
        }
        speed_row r;
        speed_static(cfg, &scene_defs[i], &r);
        out("| %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f "
            "| %.1f (%.2f%% > 8) |\n",
            scene_defs[i].title, r.ms[V_CS16], r.ms[V_CSX], r.ms[V_CAIRO], r.ms[V_CAIRO_FINE],
            r.ms[V_FT], r.ms[V_AGG], r.ms[V_CS16] / r.ms[V_CAIRO], r.ms[V_CSX] / r.ms[V_CAIRO],
            r.ms[V_CS16] / r.ms[V_FT], r.ms[V_CSX] / r.ms[V_FT], r.ms[V_CSX] / r.ms[V_AGG],
            r.agree_mean, r.agree_big);
    }
    out("\nRatios are celscan time / peer time: below 1 celscan is faster. \"picture vs cairo\" is the "
        "mean absolute difference (of 255) between celscan blending in sRGB and cairo, and the share "
        "of pixels off by more than 8: a check that both drew the same scene. The renderers take "
        "turns frame by frame, so each peer frame, drawn into a whole frame in memory, starts with "
        "caches the others left cold (celscan keeps one line); the celsim row below runs each "
        "renderer alone, as the issue's command line does.\n");
    if (have_anim) {
        out("\n### Animation at %dx%d: median ms per frame over %d frames (t = 0 .. %.3f s at 60 Hz)\n\n",
            cfg->width, cfg->height, ar.frames, (ar.frames - 1) / 60.0);
        out("| | celscan aa 16 | celscan exact | cairo | cairo tol 0.01 | FreeType | AGG | aa16/cairo "
            "| exact/cairo | aa16/FT | exact/FT | exact/AGG |\n");
        out("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
        const char *names[2] = {"every cel every frame", "static background cached"};
        for (int k = 0; k < 2; k++) {
            const double *m = k ? ar.cached : ar.direct;
            out("| %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n",
                names[k], m[V_CS16], m[V_CSX], m[V_CAIRO], m[V_CAIRO_FINE], m[V_FT], m[V_AGG],
                m[V_CS16] / m[V_CAIRO], m[V_CSX] / m[V_CAIRO], m[V_CS16] / m[V_FT],
                m[V_CSX] / m[V_FT], m[V_CSX] / m[V_AGG]);
        }
        out("\nCached: celscan pre-combines cels %u.. (the static background) once with "
            "cs_cache_build (%.1f ms at aa 16, %.1f ms exact) and composites its runs per frame; "
            "the peers draw the same background once and copy it into every frame.\n",
            ar.static_from, ar.cache_ms[0], ar.cache_ms[1]);
    }
    section_close();
}

/* ------------------------------------------------------------ accuracy */

static void run_accuracy(const config *cfg)
{
    section_open(cfg, SEC_ACCURACY);
    out("### Coverage error against the exact area at %dx%d (in 1/255)\n\n", cfg->width,
        cfg->height);
    out("Up to %d single shapes per scene (an even sample of the contours), each alone in white "
        "on black; reference: tests/ref exact area (long double, flattened to 2e-6 px). Mean over "
        "edge pixels (exact coverage strictly inside 0..1); max over every pixel; \">1\" is the "
        "share of edge pixels off by more than 1/255.\n\n",
        cfg->shapes);
    out("| scene | shapes | edge px |");
    for (int k = 0; k < ACC_COUNT; k++)
        out(" %s mean / max / >1 |", acc_names[k]);
    out("\n|---|---:|---:|");
    for (int k = 0; k < ACC_COUNT; k++)
        out("---:|");
    out("\n");
    peer_ft *ft = peer_ft_new(16, 16);
    double ref_total = 0.0;
    for (int i = 0; i < SCENE_COUNT; i++) {
        if (!cfg->scenes[i])
            continue;
        load(&scene_defs[i]);
        acc_stats st[ACC_COUNT];
        double ref_s;
        if (acc_measure(g_scene, cfg->width, cfg->height, cfg->shapes, ft, st, &ref_s) != 0)
            die("accuracy: %s failed", scene_defs[i].name);
        ref_total += ref_s;
        out("| %s | %d | %ld |", scene_defs[i].title, st[0].shapes, st[0].edge_pixels);
        for (int k = 0; k < ACC_COUNT; k++)
            out(" %.2f / %.2f / %.1f%% |",
                st[k].edge_pixels ? st[k].sum_err / (double)st[k].edge_pixels : 0.0, st[k].max_err,
                st[k].edge_pixels ? 100.0 * (double)st[k].over_1 / (double)st[k].edge_pixels : 0.0);
        out("\n");
    }
    out("\ncelscan coverage is its float coverage; cairo's and FreeType's are their 8-bit "
        "coverage (so at least 0.5/255 of rounding is theirs by format). Rational curves reach "
        "the peers as cubics within %.2f px (outline.c). The reference took %.1f s.\n",
        OL_RATIONAL_TOL, ref_total);
    peer_ft_free(ft);
    section_close();
}

/* ---------------------------------------------------------------- beam */

typedef struct beam_result {
    double worst_us, median_us, prep_us;
    int worst_line;
    int fifo_lines; /* lines of render-ahead buffer that keep the display fed; 0: none do */
    int fifo2;      /* the same for two threads taking the lines in turn */
} beam_result;

/* One sweep of a frame, every line timed on its own (render + pixel
 * conversion): run k of `runs` (k = 0 warms up and is not kept). */
static void beam_sweep(int w, int h, cs_aa_mode aa, int n, int runs, int k, double *s, double *prep)
{
    cs_render_opts o = opts_for(w, h, aa, n);
    uint8_t *px = malloc((size_t)w * 3);
    cs_renderer r;
    cs_error e;
    double t0 = bench_now();
    if (cs_frame_begin(&r, g_ws, g_scene, &o, &e) != CS_OK)
        die("cs_frame_begin failed");
    double t1 = bench_now();
    if (k)
        prep[k - 1] = t1 - t0;
    for (int y = 0; y < h; y++) {
        double a = bench_now();
        cs_render_line_px(&r, y, CS_PIX_RGB888_SRGB, px);
        double b = bench_now();
        if (k)
            s[(size_t)y * runs + k - 1] = b - a;
    }
    free(px);
}

/*
 * The lines of buffer a board needs to race the beam with these line times
 * (us). The display takes a line every `period`; the renderer runs ahead
 * as far as a FIFO of K lines lets it (it fills the FIFO in the vertical
 * blanking and while cheaper lines are shown) and must never fall behind.
 * A renderer that waits only for a free slot finishes line n by
 * max over m <= n of (m - K) periods + the time of lines m..n, so it keeps
 * up exactly when every run of lines [m, n] renders within (n - m + K)
 * periods: K is 1 plus the largest excess of any run of lines over its
 * own periods, in whole periods, found as a maximum-sum run of
 * (t - period) by Kadane's scan. With no excess K is 1: each line is
 * rendered while the one before it is shown. Returns 0 when the lines
 * take longer in total than their periods: no buffer keeps up. (The first
 * lines' lead comes from the blanking, 45 lines at 1080p60; a K beyond
 * what it can fill holds only for runs that start after cheaper lines.)
 */
static int beam_fifo_lines(const double *t_us, int h, double period)
{
    double best = 0.0, here = 0.0, total = 0.0;
    for (int y = 0; y < h; y++) {
        here = here > 0.0 ? here + (t_us[y] - period) : t_us[y] - period;
        if (here > best)
            best = here;
        total += t_us[y] - period;
    }
    if (total > 0.0)
        return 0;
    return 1 + (int)ceil(best / period);
}

/*
 * The smallest FIFO of K lines with which `threads` threads, taking the
 * lines in turn (line n on thread n mod threads, as a board with that many
 * cores would race the beam), keep up, found by running it: the display
 * takes line n at n periods; line n may start once its thread has finished
 * line n - threads and the display has taken line n - K (at the start, K
 * lines before the display starts), and takes t[n]. Returns 0 if no K up
 * to h does, or a thread's lines take longer than the frame. With one thread it is beam_fifo_lines' K (the self-test
 * compares the two); with more it assumes that the cores render as fast
 * side by side as one alone.
 */
static int beam_fifo_simulated(const double *t, int h, double period, int threads)
{
    /* As beam_fifo_lines: a thread whose lines take longer in total than
     * the frame's active lines falls behind, whatever lead the blanking
     * (or a FIFO filled before the frame) gives it. */
    for (int j = 0; j < threads; j++) {
        double sum = 0.0;
        for (int n = j; n < h; n += threads)
            sum += t[n];
        if (sum > (double)h * period)
            return 0;
    }
    double *done = malloc((size_t)h * sizeof *done);
    int found = 0;
    for (int k = threads; k <= h && found == 0; k++) {
        bool kept_up = true;
        for (int n = 0; n < h && kept_up; n++) {
            double slot_free = (double)(n - k) * period;
            double thread_free = n >= threads ? done[n - threads] : slot_free;
            done[n] = (thread_free > slot_free ? thread_free : slot_free) + t[n];
            kept_up = done[n] <= (double)n * period;
        }
        if (kept_up)
            found = k;
    }
    free(done);
    return found;
}

/* The median per line over the runs, the slowest of those, and the buffer
 * the medians need on one thread (beam_fifo_lines) and on two. */
static void beam_summarize(int h, int runs, double period, double *s, double *prep,
                           beam_result *res)
{
    res->worst_us = -1;
    res->worst_line = 0;
    double *med = malloc((size_t)h * sizeof *med);
    for (int y = 0; y < h; y++) {
        med[y] = 1e6 * bench_median(&s[(size_t)y * runs], runs); /* sorts them: not read again */
        if (med[y] > res->worst_us) {
            res->worst_us = med[y];
            res->worst_line = y;
        }
    }
    res->fifo_lines = beam_fifo_lines(med, h, period);
    res->fifo2 = beam_fifo_simulated(med, h, period, 2);
    res->median_us = bench_median(med, h);
    res->prep_us = 1e6 * bench_median(prep, runs);
    free(med);
}

/* aa 5 is celsim's default and the paper's; aa 16 and exact are the modes
 * of the speed table. */
static const struct {
    cs_aa_mode aa;
    int n;
    const char *name;
} beam_modes[] = {{CS_AA_SUBSCAN, 5, "aa 5"}, {CS_AA_SUBSCAN, 16, "aa 16"}, {CS_AA_EXACT, 1, "exact"}};
#define BEAM_MODES (sizeof beam_modes / sizeof beam_modes[0])

/* A buffer size for the table: lines, or that none keeps up (0). */
static void beam_fifo_text(int lines, char *buf, size_t size)
{
    if (lines > 0)
        snprintf(buf, size, "%d", lines);
    else
        snprintf(buf, size, "none keeps up");
}
#define BEAM_DISPLAYS (sizeof displays / sizeof displays[0])

static void run_beam(const config *cfg)
{
    section_open(cfg, SEC_BEAM);
    int runs = cfg->quick ? 1 : (cfg->repeat < 5 ? cfg->repeat : 5);
    out("### Beam racing: the slowest single line (render + 8-bit sRGB conversion), median of %d "
        "runs per line\n\n",
        runs);
    out("| scene | display | mode | worst line us | at line | median line us | line period us "
        "| margin us | buffer lines | frame prep us | 2 threads: margin us | 2 threads: buffer "
        "lines |\n");
    out("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (int i = 0; i < SCENE_COUNT; i++) {
        if (!cfg->scenes[i])
            continue;
        load(&scene_defs[i]);
        anim *a = anim_load(scene_defs[i].path, g_scene);
        anim_apply(a, g_scene, 0.0);
        anim_free(a);
        /* The runs are interleaved: round k sweeps every display and mode
         * once, so a line's samples lie seconds apart and a burst of load
         * from the machine's other tenants (they last a second or more)
         * spoils one of them, which the median drops, not all five. */
        double *s[BEAM_DISPLAYS][BEAM_MODES], *prep[BEAM_DISPLAYS][BEAM_MODES];
        for (size_t d = 0; d < BEAM_DISPLAYS; d++)
            for (size_t m = 0; m < BEAM_MODES; m++) {
                s[d][m] = malloc((size_t)displays[d].h * runs * sizeof(double));
                prep[d][m] = malloc((size_t)runs * sizeof(double));
            }
        for (int k = 0; k <= runs; k++)
            for (size_t d = 0; d < BEAM_DISPLAYS; d++) {
                if (cfg->quick && d + 1 < BEAM_DISPLAYS)
                    continue;
                for (size_t m = 0; m < BEAM_MODES; m++)
                    beam_sweep(displays[d].w, displays[d].h, beam_modes[m].aa, beam_modes[m].n,
                               runs, k, s[d][m], prep[d][m]);
            }
        for (size_t d = 0; d < BEAM_DISPLAYS; d++) {
            for (size_t m = 0; m < BEAM_MODES; m++) {
                if (!(cfg->quick && d + 1 < BEAM_DISPLAYS)) {
                    beam_result r;
                    beam_summarize(displays[d].h, runs, displays[d].period_us, s[d][m],
                                   prep[d][m], &r);
                    char fifo[32], fifo2[32];
                    beam_fifo_text(r.fifo_lines, fifo, sizeof fifo);
                    beam_fifo_text(r.fifo2, fifo2, sizeof fifo2);
                    double p = displays[d].period_us;
                    out("| %s | %s | %s | %.2f | %d | %.2f | %.1f | %+.2f%s | %s | %.0f | %+.2f%s "
                        "| %s |\n",
                        scene_defs[i].title, displays[d].name, beam_modes[m].name, r.worst_us,
                        r.worst_line, r.median_us, p, p - r.worst_us,
                        r.worst_us > p ? " **over**" : "", fifo, r.prep_us, 2.0 * p - r.worst_us,
                        r.worst_us > 2.0 * p ? " **over**" : "", fifo2);
                }
                free(s[d][m]);
                free(prep[d][m]);
            }
        }
    }
    out("\nMargin = line period - worst line (negative: that line would miss the beam). Buffer "
        "lines = the smallest render-ahead FIFO (K lines of O(width) memory) with which these "
        "median line times never fall behind the display: the renderer runs ahead as far as the "
        "FIFO lets it, while the display is blanked or cheaper lines are shown, so any run of "
        "lines [m, n] has (n - m + K) line periods; 1 is no buffer beyond the line being "
        "rendered; \"none keeps up\" means the lines take longer in total than the frame's "
        "active lines. The 5 runs "
        "of each line are interleaved with those of the other displays and modes. Frame prep "
        "(cs_frame_begin: NURBS to monotone pieces) runs in the vertical blanking, 45 lines "
        "(666 us) at 1080p60. The Animation row is its frame at t = 0. The 2-thread columns are "
        "for two threads taking the lines in turn (line n on thread n mod 2), as two cores of a "
        "board would race the beam: a line then has two line periods (margin = 2 periods - "
        "worst line), and the buffer is the smallest FIFO with which the same median line times "
        "keep up, found by running the FIFO (at least 2: a line in flight per thread); they "
        "assume that two cores render as fast side by side as one alone.\n");
    section_close();
}

/* ------------------------------------------------------------- scaling */

/* A blob of k cubic segments on a smooth radial outline (Catmull-Rom handles). */
static void add_blob(cs_scene *s, double cx, double cy, double r, double ph, int k)
{
    cs_point *pt = malloc((size_t)3 * k * sizeof *pt);
    float *iv = malloc((size_t)3 * k * sizeof *iv);
    double x[64 + 2], y[64 + 2];
    for (int i = 0; i < k; i++) {
        double a = 2 * 3.14159265358979323846 * i / k;
        double rr = r * (1.0 + 0.25 * sin(3 * a + ph) + 0.1 * cos(5 * a + 2 * ph));
        x[i] = cx + rr * cos(a);
        y[i] = cy + rr * sin(a);
    }
    for (int i = 0; i < k; i++) {
        int ip = (i + k - 1) % k, in = (i + 1) % k, in2 = (i + 2) % k;
        pt[3 * i] = (cs_point){(float)x[i], (float)y[i], 1};
        pt[3 * i + 1] = (cs_point){(float)(x[i] + (x[in] - x[ip]) / 6), (float)(y[i] + (y[in] - y[ip]) / 6), 1};
        pt[3 * i + 2] = (cs_point){(float)(x[in] - (x[in2] - x[i]) / 6), (float)(y[in] - (y[in2] - y[i]) / 6), 1};
        iv[3 * i] = 1;
        iv[3 * i + 1] = iv[3 * i + 2] = 0;
    }
    cs_error e;
    if (cs_scene_add_contour(s, 3, 3 * k, pt, iv, &e) != CS_OK)
        die("scaling blob: %s", cs_status_str(e.status));
    free(pt);
    free(iv);
}

static void blob_scene(int k, int count)
{
    srand(8005);
    cs_scene_init(g_scene, 1920, 1080);
    float bg[3] = {0.02f, 0.02f, 0.03f};
    cs_scene_set_background(g_scene, bg);
    cs_error e;
    cs_affine id = {1, 0, 0, 1, 0, 0};
    cs_scene_add_cel(g_scene, &id, NULL, NULL, &e);
    for (int i = 0; i < count; i++) {
        double u = rand() / (double)RAND_MAX, v = rand() / (double)RAND_MAX;
        double r = 30 + 90 * (rand() / (double)RAND_MAX), ph = 6.28 * rand() / (double)RAND_MAX;
        cs_paint p = {{(float)u, (float)v, 0.5f}, {1, 1, 1}, 1.0f};
        cs_scene_add_region(g_scene, CS_FILL_NONZERO, &p, &e);
        add_blob(g_scene, 1920 * u, 1080 * v, r, ph, k);
    }
}

typedef struct frame_arg {
    cs_target *t;
    cs_render_opts o;
    peers *p;
    int which; /* V_CSX for celscan (in mode o), or a peer's V_ code */
} frame_arg;

static double frame_fn(frame_arg *a)
{
    if (a->which == V_CSX)
        return celscan_frame(a->t, &a->o);
    return peer_frame(a->p, a->which, 0, a->p->set.region_count, false);
}

/* A renderer and mode of one scaling row. */
typedef struct variant {
    int which; /* as in frame_arg */
    cs_aa_mode aa;
    int sub;
} variant;

/*
 * Median ms per frame of each of v[0..count) over n rounds. The variants
 * take turns within a round (after one warm-up frame each), so a slow
 * spell of the shared machine falls on all of them alike, as in the speed
 * section; one after another, a spell skewed a whole row.
 */
static void measure_row(int n, int w, int h, const variant *v, int count, peers *p, double *ms)
{
    cs_target *t = malloc((size_t)count * sizeof *t);
    frame_arg *a = malloc((size_t)count * sizeof *a);
    double *s = malloc((size_t)count * (size_t)n * sizeof *s);
    if (!t || !a || !s)
        die("out of memory");
    for (int i = 0; i < count; i++) {
        target_init(&t[i], w, h);
        a[i] = (frame_arg){&t[i], opts_for(w, h, v[i].aa, v[i].sub), p, v[i].which};
        frame_fn(&a[i]);
    }
    for (int k = 0; k < n; k++)
        for (int i = 0; i < count; i++)
            s[(size_t)i * (size_t)n + (size_t)k] = frame_fn(&a[i]);
    for (int i = 0; i < count; i++) {
        ms[i] = 1e3 * bench_median(&s[(size_t)i * (size_t)n], n);
        target_free(&t[i]);
    }
    free(s);
    free(a);
    free(t);
}

static void run_scaling(const config *cfg)
{
    section_open(cfg, SEC_SCALING);
    int n = cfg->repeat < 5 ? cfg->repeat : 5;
    int w = cfg->width;

    out("### Time against output height (Many-blobs, width %d, shapes stretched): median ms over %d interleaved runs\n\n",
        w, n);
    out("| height | celscan aa 16 ms | us/line | celscan exact ms | us/line | cairo ms | us/line |\n");
    out("|---:|---:|---:|---:|---:|---:|---:|\n");
    const int heights[] = {135, 270, 540, 1080, 2160};
    for (size_t i = 0; i < sizeof heights / sizeof heights[0]; i++) {
        int h = heights[i];
        if (cfg->quick && h > 270)
            break;
        load(&scene_defs[0]);
        peers p;
        peers_init(&p, w, h);
        peers_prepare(&p, w, h);
        const variant v[3] = {{V_CSX, CS_AA_SUBSCAN, 16}, {V_CSX, CS_AA_EXACT, 0},
                              {V_CAIRO, CS_AA_SUBSCAN, 0}};
        double ms[3];
        measure_row(n, w, h, v, 3, &p, ms);
        out("| %d | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n", h, ms[0], 1e3 * ms[0] / h, ms[1],
            1e3 * ms[1] / h, ms[2], 1e3 * ms[2] / h);
        peers_free(&p);
    }

    int h = cfg->height;
    out("\n### Time against segment count (64 blobs of k cubic segments on the same smooth outlines, "
        "%dx%d): median ms over %d interleaved runs\n\n", w, h, n);
    out("| segments per blob | total segments | celscan aa 16 ms | celscan exact ms | cairo ms | FreeType ms | AGG ms |\n");
    out("|---:|---:|---:|---:|---:|---:|---:|\n");
    const int ks[] = {4, 8, 16, 32, 64};
    for (size_t i = 0; i < sizeof ks / sizeof ks[0]; i++) {
        if (cfg->quick && ks[i] > 8)
            break;
        blob_scene(ks[i], 64);
        peers p;
        peers_init(&p, w, h);
        peers_prepare(&p, w, h);
        const variant v[5] = {{V_CSX, CS_AA_SUBSCAN, 16}, {V_CSX, CS_AA_EXACT, 0},
                              {V_CAIRO, CS_AA_SUBSCAN, 0}, {V_FT, CS_AA_SUBSCAN, 0},
                              {V_AGG, CS_AA_SUBSCAN, 0}};
        double ms[5];
        measure_row(n, w, h, v, 5, &p, ms);
        out("| %d | %d | %.2f | %.2f | %.2f | %.2f | %.2f |\n", ks[i], 64 * ks[i], ms[0], ms[1],
            ms[2], ms[3], ms[4]);
        peers_free(&p);
    }

    out("\n### Time against sub-scanlines (Many-blobs, %dx%d): median ms over %d interleaved runs\n\n",
        w, h, n);
    out("| --aa | ms | ms per sub-scanline |\n|---|---:|---:|\n");
    load(&scene_defs[0]);
    const int subs[] = {0, 1, 2, 4, 8, 16, 32, 64, -1};
    variant v[sizeof subs / sizeof subs[0]];
    int count = 0;
    for (size_t i = 0; i < sizeof subs / sizeof subs[0]; i++) {
        if (cfg->quick && (subs[i] > 4))
            continue;
        cs_aa_mode aa = subs[i] == 0 ? CS_AA_NONE : subs[i] < 0 ? CS_AA_EXACT : CS_AA_SUBSCAN;
        v[count++] = (variant){V_CSX, aa, subs[i]};
    }
    double ms[sizeof subs / sizeof subs[0]];
    measure_row(n, w, h, v, count, NULL, ms);
    for (int i = 0; i < count; i++) {
        char buf[16];
        if (v[i].sub > 0)
            out("| %s | %.2f | %.2f |\n", aa_name(v[i].aa, v[i].sub, buf, sizeof buf), ms[i],
                ms[i] / v[i].sub);
        else
            out("| %s | %.2f | |\n", aa_name(v[i].aa, v[i].sub, buf, sizeof buf), ms[i]);
    }
    section_close();
}

/* ------------------------------------------------------------ selftest */

/* beam_fifo_lines against beam_fifo_simulated on random line times, and
 * the two-thread buffer on cases whose answer is known. */
static int selftest_fifo(int *checked)
{
    int failed = 0;
    unsigned seed = 12345u;
    const double period = displays[0].period_us;
    for (int trial = 0; trial < 2000; trial++) {
        double t[64];
        int h = 1 + trial % 64;
        double total = 0.0;
        for (int y = 0; y < h; y++) {
            seed = seed * 1103515245u + 12345u;
            /* mostly cheap lines with a few up to 4 periods long */
            double u = (double)(seed >> 8) / 16777216.0;
            t[y] = u < 0.8 ? 10.0 * u : 60.0 * u;
            total += t[y] - period;
        }
        int formula = beam_fifo_lines(t, h, period);
        int want = total > 0.0 ? 0 : beam_fifo_simulated(t, h, period, 1);
        (*checked)++;
        if (formula != want) {
            failed++;
            fprintf(stderr, "selftest: buffer lines for %d line times: formula %d, simulation %d\n",
                    h, formula, want);
        }
    }
    /* Two threads with every line 1.5 periods long: each line has two
     * periods, so two lines in flight keep up, where one thread cannot;
     * at 2.5 periods a line two threads cannot either. */
    double t[100];
    for (int slow = 0; slow < 2; slow++) {
        for (int y = 0; y < 100; y++)
            t[y] = (slow ? 2.5 : 1.5) * period;
        int one = beam_fifo_simulated(t, 100, period, 1), two = beam_fifo_simulated(t, 100, period, 2);
        int want2 = slow ? 0 : 2;
        (*checked)++;
        if (one != 0 || two != want2) {
            failed++;
            fprintf(stderr, "selftest: lines of %.1f periods: buffer %d on one thread (want 0), %d "
                    "on two (want %d)\n", slow ? 2.5 : 1.5, one, two, want2);
        }
    }
    return failed;
}

/*
 * The Bezier paths the peers get must be the scene's curves: every span's
 * start point is checked against tests/ref's de Boor evaluation, and for
 * polynomial spans the middle point too (rational spans are cubic
 * approximations, whose error the accuracy table shows).
 */
static int selftest(void)
{
    int failed = 0, checked = 0;
    for (int i = 0; i < SCENE_COUNT; i++) {
        load(&scene_defs[i]);
        int w = 1920, h = 1080;
        for (uint32_t ci = 0; ci < g_scene->cel_count; ci++) {
            const cs_cel *cel = &g_scene->cels[ci];
            double m[6];
            ol_cel_device_map(g_scene, (int)ci, w, h, m);
            for (uint32_t ri = cel->first_region; ri < cel->first_region + cel->region_count; ri++)
                for (uint32_t k = 0; k < g_scene->regions[ri].contour_count; k++) {
                    uint32_t cn = g_scene->regions[ri].first_contour + k;
                    const cs_contour *c = &g_scene->contours[cn];
                    ol_set set;
                    memset(&set, 0, sizeof set);
                    ol_contour oc;
                    if (ol_add_contour(&set, g_scene, (int)cn, m, &oc) != 0)
                        return 1;
                    float *xyw = malloc((size_t)c->point_count * 3 * sizeof *xyw);
                    for (int q = 0; q < c->point_count; q++) {
                        const cs_point *p = &g_scene->points[c->first_point + q];
                        xyw[3 * q] = p->x;
                        xyw[3 * q + 1] = p->y;
                        xyw[3 * q + 2] = p->w;
                    }
                    ref_region *rr = ref_region_new(0);
                    ref_region_add(rr, c->degree, c->point_count, xyw,
                                   &g_scene->intervals[c->first_point]);
                    const cs_affine *t = &cel->transform;
                    long double mt[6] = {t->a, t->b, t->c, t->d, t->e, t->f};
                    ref_region_transform(rr, mt, (long double)w / g_scene->canvas_w,
                                         (long double)h / g_scene->canvas_h);
                    const ref_contour *rc = &rr->contours[0];
                    /* Walk the commands span by span: each span's first command starts at
                     * the previous end point. */
                    double px = oc.x0, py = oc.y0;
                    int cmd = oc.first;
                    for (int j = 0; j < c->point_count; j++) {
                        if (!(rc->iv[j] > 0))
                            continue;
                        long double ref[2];
                        ref_eval_span(rc, j, 0, ref);
                        double err = hypot(px - (double)ref[0], py - (double)ref[1]);
                        checked++;
                        if (err > 1e-6) {
                            if (failed++ < 5)
                                fprintf(stderr, "selftest: %s contour %u span %d start off by %g px\n",
                                        scene_defs[i].name, cn, j, err);
                        }
                        /* Skip this span's commands: up to the one ending at the next span start. */
                        long double nxt[2];
                        int jn = j + 1;
                        while (jn < c->point_count && !(rc->iv[jn] > 0))
                            jn++;
                        if (jn < c->point_count)
                            ref_eval_span(rc, jn, 0, nxt);
                        else
                            ref_eval_span(rc, j, 1, nxt);
                        while (cmd < oc.first + oc.count) {
                            const ol_cmd *cm = &set.cmds[cmd++];
                            px = cm->p[2 * cm->op - 2];
                            py = cm->p[2 * cm->op - 1];
                            if (hypot(px - (double)nxt[0], py - (double)nxt[1]) < 1e-6)
                                break;
                        }
                    }
                    free(xyw);
                    ref_region_free(rr);
                    ol_free(&set);
                }
        }
    }
    /* The peers draw the same pictures: FreeType's and AGG's frames against
     * cairo's (all three blend 8-bit sRGB values), so that a peer drawing
     * nothing, or the wrong thing, cannot pass for a fast one. Cell-based
     * rasterizers apply the fill rule to a pixel's summed area, which
     * differs from cairo where an outline crosses itself: hence a share of
     * pixels, not none, allowed to differ. */
    for (int i = 0; i < SCENE_COUNT; i++) {
        load(&scene_defs[i]);
        int w = 480, h = 272;
        peers p;
        peers_init(&p, w, h);
        peers_prepare(&p, w, h);
        peer_frame(&p, V_CAIRO, 0, p.set.region_count, false);
        peer_frame(&p, V_FT, 0, p.set.region_count, false);
        peer_frame(&p, V_AGG, 0, p.set.region_count, false);
        int stride;
        const uint32_t *c = peer_cairo_pixels(p.cairo, &stride);
        const uint32_t *other[2] = {peer_ft_pixels(p.ft), peer_agg_pixels(p.agg)};
        const char *names[2] = {"FreeType", "AGG"};
        for (int k = 0; k < 2; k++) {
            double sum = 0.0;
            long over = 0;
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w; x++) {
                    uint32_t b = other[k][(size_t)y * (size_t)w + (size_t)x];
                    double d = rgb_diff(c[(size_t)y * (size_t)(stride / 4) + (size_t)x],
                                        (int)((b >> 16) & 255u), (int)((b >> 8) & 255u),
                                        (int)(b & 255u));
                    sum += d;
                    over += d > 8.0;
                }
            double mean = sum / (double)(w * h), share = 100.0 * (double)over / (double)(w * h);
            checked++;
            if (!(mean < 1.0 && share < 2.0)) {
                failed++;
                fprintf(stderr, "selftest: %s, %s differs from cairo: mean %.2f/255, %.2f%% > 8\n",
                        scene_defs[i].name, names[k], mean, share);
            }
            printf("bench selftest: %-8s %-8s vs cairo: mean %.2f/255, %.2f%% of pixels > 8\n",
                   scene_defs[i].name, names[k], mean, share);
        }
        peers_free(&p);
    }
    failed += selftest_fifo(&checked);
    printf("bench selftest: %d passed, %d failed\n", checked - failed, failed);
    return failed != 0;
}

/* ------------------------------------------------------------- profile */

/* --profile SCENE --peer NAME: frames of one peer on the loaded scene, so
 * that its instructions per frame can be counted as celscan's are. */
static void profile_peer(const char *name, int w, int h, int frames)
{
    int which = strcmp(name, "cairo") == 0        ? V_CAIRO
                : strcmp(name, "cairo-fine") == 0 ? V_CAIRO_FINE
                : strcmp(name, "freetype") == 0   ? V_FT
                : strcmp(name, "agg") == 0        ? V_AGG
                                                  : -1;
    if (which < 0)
        die("unknown peer '%s' (cairo, cairo-fine, freetype, agg)", name);
    peers p;
    peers_init(&p, w, h);
    peers_prepare(&p, w, h);
    double *s = malloc((size_t)frames * sizeof *s);
    if (!s)
        die("out of memory");
    for (int f = 0; f < frames; f++)
        s[f] = peer_frame(&p, which, 0, p.set.region_count, false);
    printf("%.3f ms/frame\n", 1e3 * bench_median(s, frames));
    free(s);
    peers_free(&p);
}

/* --------------------------------------------------------------- main */

static void usage(void)
{
    fputs("usage: bench [--sections speed,accuracy,beam,scaling] [--scenes blobs,signage,thin,"
          "rational,anim]\n"
          "             [--size WxH] [--repeat N] [--frames N] [--shapes N] [--out DIR] [--quick]\n"
          "       bench --profile SCENE [--aa none|N|exact] [--size WxH] [--frames N] [--cache]\n"
          "       bench --profile SCENE [--aa none|N|exact] [--size WxH] --band K/N | --part K/N\n"
          "       bench --profile SCENE --peer cairo|cairo-fine|freetype|agg [--size WxH] [--frames N]\n"
          "       bench --selftest\n",
          stderr);
    exit(2);
}

/* A count option (--repeat, --frames, --shapes): 1 up to a million. */
static int count_arg(const char *v)
{
    long n = 0;
    if (!cli_int(v, 10, '\0', 1, 1000000, &n))
        usage();
    return (int)n;
}

static void parse_list(const char *arg, const char *const *names, int n, bool *set, size_t stride)
{
    for (int i = 0; i < n; i++)
        set[i] = false;
    char buf[256];
    snprintf(buf, sizeof buf, "%s", arg);
    for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
        int found = -1;
        for (int i = 0; i < n; i++)
            if (strcmp(*(const char *const *)((const char *)names + (size_t)i * stride), tok) == 0)
                found = i;
        if (found < 0)
            die("unknown name '%s'", tok);
        set[found] = true;
    }
}

int main(int argc, char **argv)
{
    config cfg = {.width = 1920, .height = 1080, .repeat = 7, .frames = 120, .shapes = 24};
    for (int i = 0; i < 4; i++)
        cfg.sections[i] = true;
    for (int i = 0; i < SCENE_COUNT; i++)
        cfg.scenes[i] = true;
    const char *profile = NULL, *prof_peer = NULL;
    cs_aa_mode prof_aa = CS_AA_SUBSCAN;
    int prof_sub = 16;
    bool self = false, prof_cache = false;
    long band_k = -1, band_n = 0;
    bool part = false; /* --part K/N, not --band */
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--sections") == 0 && v) {
            parse_list(v, section_names, 4, cfg.sections, sizeof section_names[0]);
            i++;
        } else if (strcmp(a, "--scenes") == 0 && v) {
            parse_list(v, &scene_defs[0].name, SCENE_COUNT, cfg.scenes, sizeof scene_defs[0]);
            i++;
        } else if (strcmp(a, "--size") == 0 && v) {
            if (!cli_size(v, CS_CFG_MAX_WIDTH, CS_CFG_MAX_HEIGHT, &cfg.width, &cfg.height))
                usage();
            i++;
        } else if (strcmp(a, "--repeat") == 0 && v) {
            cfg.repeat = count_arg(v);
            i++;
        } else if (strcmp(a, "--frames") == 0 && v) {
            cfg.frames = count_arg(v);
            i++;
        } else if (strcmp(a, "--shapes") == 0 && v) {
            cfg.shapes = count_arg(v);
            i++;
        } else if (strcmp(a, "--out") == 0 && v) {
            cfg.out_dir = v;
            i++;
        } else if (strcmp(a, "--quick") == 0) {
            cfg.quick = true;
        } else if (strcmp(a, "--profile") == 0 && v) {
            profile = v;
            i++;
        } else if (strcmp(a, "--aa") == 0 && v) {
            if (!cli_aa(v, &prof_aa, &prof_sub))
                usage();
            i++;
        } else if (strcmp(a, "--peer") == 0 && v) {
            prof_peer = v;
            i++;
        } else if ((strcmp(a, "--band") == 0 || strcmp(a, "--part") == 0) && v) {
            const char *slash = strchr(v, '/');
            char kbuf[16];
            if (!slash || (size_t)(slash - v) >= sizeof kbuf)
                usage();
            memcpy(kbuf, v, (size_t)(slash - v));
            kbuf[slash - v] = '\0';
            if (!cli_int(slash + 1, 10, '\0', 1, 64, &band_n) ||
                !cli_int(kbuf, 10, '\0', 0, band_n - 1, &band_k))
                usage();
            part = a[2] == 'p';
            i++;
        } else if (strcmp(a, "--cache") == 0) {
            prof_cache = true;
        } else if (strcmp(a, "--selftest") == 0) {
            self = true;
        } else {
            usage();
        }
    }
    if (cfg.repeat < 1 || cfg.frames < 1 || cfg.shapes < 1)
        usage();
    g_scene = calloc(1, sizeof *g_scene);
    g_ws = calloc(1, sizeof *g_ws);
    if (!g_scene || !g_ws)
        die("out of memory");
    if (self)
        return selftest();
    if (profile) {
        /* One scene, cfg.frames frames of celscan only: for callgrind and perf. */
        int idx = -1;
        for (int i = 0; i < SCENE_COUNT; i++)
            if (strcmp(scene_defs[i].name, profile) == 0)
                idx = i;
        anim *a = NULL;
        if (strcmp(profile, "blobs64") == 0) { /* the segment-scaling scene, 8 segments */
            blob_scene(8, 64);
        } else {
            if (idx < 0)
                die("unknown scene '%s'", profile);
            load(&scene_defs[idx]);
            a = anim_load(scene_defs[idx].path, g_scene);
            anim_apply(a, g_scene, 0.0);
        }
        if (prof_peer) {
            anim_free(a);
            profile_peer(prof_peer, cfg.width, cfg.height, cfg.frames);
            return 0;
        }
        cs_target t;
        target_init(&t, cfg.width, cfg.height);
        cs_render_opts o = opts_for(cfg.width, cfg.height, prof_aa, prof_sub);
        if (prof_cache) /* the static background pre-combined, as the animation runs it */
            celscan_cache(&t, &o, a ? anim_static_from(a, g_scene) : 0);
        if (a)
            anim_free(a);
        if (band_n > 0) {
            if (part)
                profile_part(&o, band_k, band_n);
            else
                profile_band(&t, &o, band_k, band_n);
            target_free(&t);
            return 0;
        }
        double *s = malloc((size_t)cfg.frames * sizeof *s);
        for (int f = 0; f < cfg.frames; f++)
            s[f] = celscan_frame(&t, &o);
        printf("%.3f ms/frame\n", 1e3 * bench_median(s, cfg.frames));
        free(s);
        target_free(&t);
        return 0;
    }
    if (cfg.quick) {
        cfg.repeat = 1;
        cfg.frames = cfg.frames < 3 ? cfg.frames : 3;
        cfg.shapes = cfg.shapes < 3 ? cfg.shapes : 3;
    }
    if (cfg.sections[SEC_SPEED])
        run_speed(&cfg);
    if (cfg.sections[SEC_ACCURACY])
        run_accuracy(&cfg);
    if (cfg.sections[SEC_BEAM])
        run_beam(&cfg);
    if (cfg.sections[SEC_SCALING])
        run_scaling(&cfg);
    free(g_scene);
    free(g_ws);
    return 0;
}
