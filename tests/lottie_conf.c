/*
 * lottie_conf.c - the Lottie importer against rlottie, file by file.
 *
 *   lottie_conf DIR [--files a.json,b.json] [--frames N] [--table OUT.md]
 *               [--floor RATE] [--speed] [--all] [--dump DIR]
 *
 * For every file of DIR/INVENTORY.tsv whose features are all in issue 25's
 * list (column "mappable" or "mappable_if_trim" yes, or every feature of
 * column "needs" one of precomps, polystars, repeaters, trim paths, track
 * mattes and time remapping; --all: every file), imports
 * it (tools/lottie), loads the scene JSON as celsim does, and renders N
 * evenly spaced frames of rlottie's range (frame index n is time n / fr)
 * with the celscan core and with rlottie (librlottie, the C API) at the
 * file's size. Both are put over white (the core with a white background
 * card, rlottie's premultiplied ARGB composited in 8-bit sRGB, as a player
 * over a white page would) and compared by PSNR over the RGB channels; a
 * frame passes at 30 dB. Per file: frames passed, worst PSNR, warnings, the
 * cel stream's size against the Lottie file's and whether it fits a board's
 * 16 KiB scene store; with --speed, median render times at 480x272 and
 * 1920x1080 of both renderers. The last line is
 *   lottie_conf: N passed, M failed
 * counting two kinds of check: the frames' pass rate against --floor
 * (default 0.9) over every file tried, a refused file's frames counted as
 * failed, and each file accepted (a refused file the inventory marks
 * mappable fails); the exit status is non-zero if any fails. --dump writes each compared frame as DIR/FILE-NNN.png, rlottie
 * on the left and celscan on the right.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <rlottie_capi.h>

#include "../host-sim/png_out.h"
#include "../host-sim/scene_json.h"
#include "../tools/cels_write.h"
#include "../tools/lottie/lt.h"
#include "celscan_private.h"
#include "testlib.h"

#define BOARD_STORE 16384

/* Whether every feature of a "needs" value (comma-separated) is one the issue lists. */
static bool needs_listed(const char *needs)
{
    static const char *const listed[] = {"precomp", "polystar", "repeater", "trim-path",
                                         "track-matte", "time-remap"};
    char buf[512];
    snprintf(buf, sizeof buf, "%s", needs);
    for (char *save = NULL, *f = strtok_r(buf, ",", &save); f; f = strtok_r(NULL, ",", &save)) {
        bool ok = false;
        for (size_t i = 0; i < sizeof listed / sizeof *listed && !ok; i++)
            ok = !strcmp(f, listed[i]);
        if (!ok)
            return false;
    }
    return true;
}
#define BOARD_CONFIG "firmware/boards/cs_config_480x272.h"

/* The 64 KiB boards' capacities, read from their configuration header. */
static long board_cap(const char *name)
{
    FILE *f = fopen(BOARD_CONFIG, "r");
    char line[256], want[80];
    long v = -1;
    snprintf(want, sizeof want, "#define CS_CFG_MAX_%s ", name);
    while (f && fgets(line, sizeof line, f))
        if (!strncmp(line, want, strlen(want)))
            v = strtol(line + strlen(want), NULL, 10);
    if (f)
        fclose(f);
    return v;
}

/* Whether the scene fits a board: stream within its 16 KiB store and every count within
 * the board's capacities; otherwise why not, in `why`. */
static bool board_fits(const cs_scene *sc, size_t stream, char *why, size_t n)
{
    uint32_t anim = 0;
    for (uint32_t i = 0; i < sc->track_count; i++)
        if (sc->tracks[i].kind == CS_TRACK_POINTS)
            anim = anim > sc->tracks[i].width / 3 ? anim : sc->tracks[i].width / 3;
    const struct {
        const char *name;
        long have;
    } c[] = {{"CELS", sc->cel_count},       {"REGIONS", sc->region_count},
             {"CONTOURS", sc->contour_count}, {"POINTS", sc->point_count},
             {"FUNCS", sc->func_count},      {"TRACKS", sc->track_count},
             {"KEYS", sc->key_count},        {"KEY_VALUES", sc->value_count},
             {"ANIM_POINTS", (long)anim}};
    if (stream > BOARD_STORE) {
        snprintf(why, n, "no (%zu B)", stream);
        return false;
    }
    for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
        long cap = board_cap(c[i].name);
        if (cap >= 0 && c[i].have > cap) {
            snprintf(why, n, "no (%s %ld > %ld)", c[i].name, c[i].have, cap);
            return false;
        }
    }
    snprintf(why, n, "yes");
    return true;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static cs_workspace *ws;
static cs_status render_err; /* the last frame the core could not render, or CS_OK */

/* The core's frame at time t, W x H, as 8-bit sRGB RGB. */
static int render_cs(const cs_scene *sc, int W, int H, double t, uint8_t *rgb)
{
    cs_renderer r;
    cs_render_opts o = cs_render_defaults(W, H);
    o.time = (float)t;
    cs_error e;
    cs_status st = cs_frame_begin(&r, ws, sc, &o, &e);
    for (int y = 0; y < H && st == CS_OK; y++)
        st = cs_render_line_px(&r, y, CS_PIX_RGB888_SRGB, rgb + (size_t)3 * W * y);
    if (st != CS_OK)
        render_err = st;
    return st == CS_OK ? 0 : -1;
}

/* rlottie's frame n over white, as 8-bit sRGB RGB. */
static void render_rl(Lottie_Animation *a, size_t n, int W, int H, uint32_t *buf, uint8_t *rgb)
{
    lottie_animation_render(a, n, buf, (size_t)W, (size_t)H, (size_t)W * 4);
    for (size_t i = 0; i < (size_t)W * H; i++) {
        uint32_t p = buf[i];
        unsigned al = p >> 24, c[3] = {(p >> 16) & 255, (p >> 8) & 255, p & 255};
        for (int k = 0; k < 3; k++) {
            unsigned v = c[k] + (255 - al); /* premultiplied over white */
            rgb[3 * i + k] = (uint8_t)(v > 255 ? 255 : v);
        }
    }
}

static double psnr(const uint8_t *a, const uint8_t *b, size_t n)
{
    double se = 0;
    for (size_t i = 0; i < n; i++) {
        double d = (double)a[i] - b[i];
        se += d * d;
    }
    if (se == 0)
        return 99.0;
    return 10 * log10(255.0 * 255.0 / (se / n));
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *b = malloc((size_t)n + 1);
    if (b && fread(b, 1, (size_t)n, f) != (size_t)n) {
        free(b);
        b = NULL;
    }
    fclose(f);
    if (b) {
        b[n] = 0;
        *len = (size_t)n;
    }
    return b;
}

/* Median seconds per frame of `reps` renders of frame n by each renderer at W x H. */
static void speed(const cs_scene *sc, Lottie_Animation *a, double fr, size_t n, int W, int H,
                  double *t_cs, double *t_rl)
{
    uint8_t *rgb = malloc((size_t)3 * W * H);
    uint32_t *buf = malloc((size_t)4 * W * H);
    double tc[5], tr[5];
    for (int k = 0; k < 5; k++) {
        double t0 = now();
        render_cs(sc, W, H, n / fr, rgb);
        double t1 = now();
        /* A different frame each time: rlottie would otherwise reuse its last one. */
        lottie_animation_render(a, n + (size_t)k % 2, buf, (size_t)W, (size_t)H, (size_t)W * 4);
        double t2 = now();
        tc[k] = t1 - t0;
        tr[k] = t2 - t1;
    }
    qsort(tc, 5, sizeof *tc, cmp_double);
    qsort(tr, 5, sizeof *tr, cmp_double);
    *t_cs = tc[2];
    *t_rl = tr[2];
    free(rgb);
    free(buf);
}

int main(int argc, char **argv)
{
    const char *dir = NULL, *files = NULL, *table = NULL, *dump = NULL;
    int frames = 10;
    double floor_rate = 0.9;
    bool do_speed = false, all = false;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--files") && i + 1 < argc)
            files = argv[++i];
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc)
            frames = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--table") && i + 1 < argc)
            table = argv[++i];
        else if (!strcmp(argv[i], "--floor") && i + 1 < argc)
            floor_rate = atof(argv[++i]);
        else if (!strcmp(argv[i], "--dump") && i + 1 < argc)
            dump = argv[++i];
        else if (!strcmp(argv[i], "--speed"))
            do_speed = true;
        else if (!strcmp(argv[i], "--all"))
            all = true;
        else
            dir = argv[i];
    }
    if (!dir || frames < 1 || frames > 1000) {
        fprintf(stderr, "usage: lottie_conf DIR [--files a,b] [--frames N] [--table OUT.md] "
                        "[--floor RATE] [--speed] [--all]\n");
        return 2;
    }
    ws = calloc(1, sizeof *ws);
    cs_scene *sc = calloc(1, sizeof *sc);
    char path[1024], line[4096];
    snprintf(path, sizeof path, "%s/INVENTORY.tsv", dir);
    FILE *inv = fopen(path, "r");
    if (!ws || !sc || !inv) {
        fprintf(stderr, "lottie_conf: cannot read %s\n", path);
        return 2;
    }
    FILE *tab = table ? fopen(table, "w") : NULL;
    if (tab) {
        fprintf(tab, "| file | frames ≥ 30 dB | worst PSNR | warnings | Lottie bytes | stream bytes "
                     "| fits a board |%s\n",
                do_speed ? " celscan / rlottie ms, 480×272 | celscan / rlottie ms, 1920×1080 |" : "");
        fprintf(tab, "|---|---:|---:|---:|---:|---:|:---:|%s\n", do_speed ? "---:|---:|" : "");
    }
    int passed = 0, failed = 0, accepted = 0, tried = 0, refused_mappable = 0, fits = 0;
    int refused = 0;
    bool header = true;
    while (fgets(line, sizeof line, inv)) {
        if (header) {
            header = false;
            continue;
        }
        char *col[32];
        int nc = 0;
        for (char *p = strtok(line, "\t\n"); p && nc < 32; p = strtok(NULL, "\t\n"))
            col[nc++] = p;
        if (nc < 23)
            continue;
        const char *name = col[0];
        bool mappable = !strcmp(col[21], "yes") || !strcmp(col[22], "yes");
        bool listed = mappable || needs_listed(col[20]);
        if (files) {
            char pat[300];
            snprintf(pat, sizeof pat, ",%s,", name);
            char list[4096];
            snprintf(list, sizeof list, ",%s,", files);
            if (!strstr(list, pat))
                continue;
        } else if (!listed && !all) {
            continue;
        }
        tried++;
        snprintf(path, sizeof path, "%s/%s", dir, name);
        size_t len = 0;
        char *text = slurp(path, &len);
        cJSON *root = text ? cJSON_ParseWithLength(text, len) : NULL;
        free(text);
        lt_warnings w = {0, NULL};
        char err[512] = "";
        cJSON *scene = root ? lt_import(root, NULL, &w, err, sizeof err) : NULL;
        cJSON_Delete(root);
        char lerr[SCENE_JSON_ERRLEN] = "";
        int loaded = scene ? scene_json_load_tree(scene, name, sc, lerr, sizeof lerr) : -1;
        cJSON_Delete(scene);
        /* a check per file accepted, and per refused file the inventory marks mappable */
        if (loaded == 0 || mappable)
            CHECK(loaded == 0, "%s: refused, but the inventory marks it mappable", name);
        if (loaded != 0) {
            printf("%-40s refused: %s\n", name, scene ? lerr : err);
            /* Its frames count as failed: the floor is over every file tried. */
            Lottie_Animation *ra = lottie_animation_from_file(path);
            size_t rt = ra ? lottie_animation_get_totalframe(ra) : (size_t)frames;
            failed += frames < (int)rt ? frames : (int)rt;
            if (ra)
                lottie_animation_destroy(ra);
            refused++;
            if (mappable)
                refused_mappable++;
            if (tab)
                fprintf(tab, "| %s | refused: %.80s | | %d | %zu | | |%s\n", name,
                        scene ? lerr : err, w.n, len, do_speed ? " | |" : "");
            lt_warnings_free(&w);
            continue;
        }
        accepted++;
        const float white[3] = {1, 1, 1};
        cs_scene_set_background(sc, white);
        cels_buf b;
        cels_buf_init(&b);
        cels_stream_header(&b);
        cels_encode_scene(&b, sc);
        size_t stream = b.len;
        cels_buf_free(&b);
        char why[80];
        bool fit = board_fits(sc, stream, why, sizeof why);
        fits += fit;
        Lottie_Animation *a = lottie_animation_from_file(path);
        if (!a) {
            printf("%-40s rlottie cannot load it\n", name);
            lt_warnings_free(&w);
            continue;
        }
        size_t rw, rh;
        lottie_animation_get_size(a, &rw, &rh);
        int W = (int)rw, H = (int)rh;
        size_t total = lottie_animation_get_totalframe(a);
        double fr = lottie_animation_get_framerate(a);
        uint8_t *c1 = malloc((size_t)3 * W * H), *c2 = malloc((size_t)3 * W * H);
        uint32_t *buf = malloc((size_t)4 * W * H);
        int ok = 0, nf = frames < (int)total ? frames : (int)total;
        double worst = 99;
        render_err = CS_OK;
        for (int k = 0; k < nf; k++) {
            size_t n = nf > 1 ? (size_t)llround((double)k * (double)(total - 1) / (nf - 1)) : 0;
            render_rl(a, n, W, H, buf, c1);
            double p = 0;
            if (render_cs(sc, W, H, n / fr, c2) == 0)
                p = psnr(c1, c2, (size_t)3 * W * H);
            worst = p < worst ? p : worst;
            if (dump) {
                /* rlottie on the left, celscan on the right */
                uint8_t *both = malloc((size_t)6 * W * H);
                for (int y = 0; both && y < H; y++) {
                    memcpy(both + (size_t)6 * W * y, c1 + (size_t)3 * W * y, (size_t)3 * W);
                    memcpy(both + (size_t)6 * W * y + 3 * W, c2 + (size_t)3 * W * y, (size_t)3 * W);
                }
                char pp[1200], perr[200];
                snprintf(pp, sizeof pp, "%s/%s-%03zu.png", dump, name, n);
                if (both)
                    png_write_rgb(pp, 2 * W, H, CS_PIX_RGB888_SRGB, both, (size_t)6 * W, perr,
                                  sizeof perr);
                free(both);
            }
            ok += p >= 30;
        }
        passed += ok;
        failed += nf - ok;
        printf("%-40s %2d/%2d frames >= 30 dB, worst %5.1f dB, %d warnings, %zu -> %zu bytes, "
               "board: %s\n",
               name, ok, nf, worst, w.n, len, stream, why);
        for (int i = 0; i < w.n; i++)
            printf("    warning: %s\n", w.text[i]);
        if (render_err != CS_OK)
            printf("    celscan could not render a frame: %s\n", cs_status_str(render_err));
        double s1c = 0, s1r = 0, s2c = 0, s2r = 0;
        if (do_speed) {
            speed(sc, a, fr, total / 2, 480, 272, &s1c, &s1r);
            speed(sc, a, fr, total / 2, 1920, 1080, &s2c, &s2r);
            printf("    speed: 480x272 celscan %.2f ms, rlottie %.2f ms; 1920x1080 celscan %.2f ms, "
                   "rlottie %.2f ms\n",
                   s1c * 1e3, s1r * 1e3, s2c * 1e3, s2r * 1e3);
        }
        if (tab) {
            fprintf(tab, "| %s | %d/%d | %.1f dB | %d | %zu | %zu | %s |", name, ok, nf, worst, w.n,
                    len, stream, why);
            if (do_speed)
                fprintf(tab, " %.1f / %.1f | %.1f / %.1f |", s1c * 1e3, s1r * 1e3, s2c * 1e3,
                        s2r * 1e3);
            fprintf(tab, "\n");
        }
        lt_warnings_free(&w);
        lottie_animation_destroy(a);
        free(c1);
        free(c2);
        free(buf);
    }
    fclose(inv);
    double rate = passed + failed ? (double)passed / (passed + failed) : 0;
    printf("files: %d tried, %d accepted, %d refused (%d marked mappable) (%d fit a 64 KiB board); "
           "frames: %d of %d pass (%.1f%%)\n",
           tried, accepted, refused, refused_mappable, fits, passed, passed + failed, 100 * rate);
    if (tab) {
        fprintf(tab, "\n%d files tried, %d accepted (%d refused, %d of them marked mappable by the "
                     "inventory), %d of them fit a 64 KiB board (its 16 KiB store and capacities); "
                     "%d of %d frames (%.1f %%) within 30 dB of rlottie (a refused file's frames "
                     "count as failed).\n",
                tried, accepted, refused, refused_mappable, fits, passed, passed + failed,
                100 * rate);
        fclose(tab);
    }
    /* The other check: the pass rate's floor. */
    CHECK(rate >= floor_rate, "%.1f%% of frames within 30 dB, below the floor of %.1f%%", 100 * rate,
          100 * floor_rate);
    free(ws);
    free(sc);
    return tl_summary("lottie_conf");
}
