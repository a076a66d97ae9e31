/*
 * aa_modes.c - render time of --aa exact against --aa 5 and --aa 16.
 *
 * Two scenes built in code at 1920x1080 (so the bench needs no loader):
 *   demo   a few cels like the demo's: discs and a ring, rational blobs, an
 *          even-odd curved star, a wavy banner, partly translucent paints;
 *   heavy  300 cubic blobs of 8 Bezier segments each, 10 cels of 30.
 * Each mode renders the whole frame (cs_frame_begin and every line) `runs`
 * times, the modes taking turns so that a busy machine slows them alike.
 * Times are CPU time of the process (the machine is shared), printed as
 * median and minimum ms/frame.
 *
 *   build/host/bench_aa_modes [runs]
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#endif
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "celscan_private.h"
#include "cli_num.h"

#define PI 3.14159265358979323846
#define W 1920
#define H 1080

static unsigned rng = 1u;
static float rnd(float lo, float hi)
{
    rng = rng * 1664525u + 1013904223u;
    return lo + (hi - lo) * (float)(rng >> 8) / 16777216.0f;
}

static void must(cs_status st, const char *what)
{
    if (st != CS_OK) {
        fprintf(stderr, "aa_modes: %s: %s\n", what, cs_status_str(st));
        exit(1);
    }
}

static void region(cs_scene *s, cs_fill_rule rule, float beta)
{
    cs_paint p = {{rnd(0.1f, 1), rnd(0.1f, 1), rnd(0.1f, 1)}, {rnd(0.5f, 1), rnd(0.5f, 1), 1}, beta};
    cs_error err;
    must(cs_scene_add_region(s, rule, &p, &err), "region");
}

static void cel(cs_scene *s, float angle, float dx, float dy)
{
    cs_affine m = {cosf(angle), sinf(angle), -sinf(angle), cosf(angle), dx, dy};
    cs_error err;
    must(cs_scene_add_cel(s, &m, NULL, NULL, &err), "cel");
}

static void circle(cs_scene *s, float cx, float cy, float r, int reverse)
{
    cs_point p[8];
    float iv[8];
    for (int k = 0; k < 8; k++) {
        float a = (reverse ? -1.0f : 1.0f) * (float)k * (float)PI / 4.0f;
        float m = (k & 1) ? sqrtf(2.0f) : 1.0f;
        p[k] = (cs_point){cx + r * m * cosf(a), cy + r * m * sinf(a), (k & 1) ? sqrtf(0.5f) : 1.0f};
        iv[k] = (k & 1) ? 0.0f : 1.0f;
    }
    cs_error err;
    must(cs_scene_add_contour(s, 2, 8, p, iv, &err), "circle");
}

/* A closed path of `segs` cubic Beziers around (cx, cy), radius jittered. */
static void bezier_blob(cs_scene *s, float cx, float cy, float r, int segs, float w)
{
    cs_point p[3 * 16];
    float iv[3 * 16];
    for (int k = 0; k < segs; k++) {
        float a = 2.0f * (float)PI * (float)k / (float)segs;
        float da = 2.0f * (float)PI / (float)segs / 3.0f;
        float rr = r * rnd(0.75f, 1.2f), t = rr * da * rnd(0.8f, 1.4f);
        float x = cx + rr * cosf(a), y = cy + rr * sinf(a);
        float tx = -sinf(a) * t, ty = cosf(a) * t;
        p[3 * k] = (cs_point){x, y, 1.0f};
        p[3 * k + 1] = (cs_point){x + tx, y + ty, w};
        p[(3 * k + 3 * segs - 1) % (3 * segs)] = (cs_point){x - tx, y - ty, w};
        iv[3 * k] = 1.0f;
        iv[3 * k + 1] = iv[3 * k + 2] = 0.0f;
    }
    cs_error err;
    must(cs_scene_add_contour(s, 3, 3 * segs, p, iv, &err), "blob");
}

static void build_demo(cs_scene *s)
{
    must(cs_scene_init(s, W, H), "init");
    const float bg[3] = {0.02f, 0.03f, 0.05f};
    must(cs_scene_set_background(s, bg), "background");
    rng = 7u;
    /* banner: a wide band with wavy cubic edges, in front, translucent */
    cel(s, 0.0f, 0.0f, 0.0f);
    region(s, CS_FILL_NONZERO, 0.7f);
    {
        cs_point p[3 * 12];
        float iv[3 * 12];
        int n = 0;
        for (int k = 0; k < 6; k++) { /* top edge, left to right */
            float x = 100.0f + 1720.0f * (float)k / 6.0f, y = 860.0f + 25.0f * sinf((float)k);
            p[n] = (cs_point){x, y, 1};
            p[n + 1] = (cs_point){x + 95.0f, y - 60.0f, 1};
            p[n + 2] = (cs_point){x + 192.0f, y + 60.0f, 1};
            n += 3;
        }
        for (int k = 0; k < 6; k++) { /* bottom edge, right to left */
            float x = 1820.0f - 1720.0f * (float)k / 6.0f, y = 1010.0f + 25.0f * cosf((float)k);
            p[n] = (cs_point){x, y, 1};
            p[n + 1] = (cs_point){x - 95.0f, y + 50.0f, 1};
            p[n + 2] = (cs_point){x - 192.0f, y - 50.0f, 1};
            n += 3;
        }
        for (int k = 0; k < n; k++)
            iv[k] = (k % 3) ? 0.0f : 1.0f;
        cs_error err;
        must(cs_scene_add_contour(s, 3, n, p, iv, &err), "banner");
    }
    /* star: even-odd, curved, rotated */
    cel(s, 0.3f, 700.0f, -150.0f);
    region(s, CS_FILL_EVENODD, 1.0f);
    {
        cs_point p[7];
        for (int k = 0; k < 7; k++) {
            float a = 2.0f * (float)PI * (float)((3 * k) % 7) / 7.0f;
            p[k] = (cs_point){960.0f + 330.0f * cosf(a), 420.0f + 330.0f * sinf(a),
                              (k & 1) ? 2.0f : 1.0f};
        }
        cs_error err;
        must(cs_scene_add_contour(s, 2, 7, p, NULL, &err), "star");
    }
    /* blobs */
    cel(s, 0.0f, 0.0f, 0.0f);
    for (int b = 0; b < 5; b++) {
        region(s, CS_FILL_NONZERO, b & 1 ? 0.6f : 1.0f);
        bezier_blob(s, rnd(200, 1700), rnd(150, 800), rnd(80, 200), 8, rnd(0.6f, 1.8f));
    }
    /* discs and a ring, at the back */
    cel(s, 0.0f, 0.0f, 0.0f);
    region(s, CS_FILL_NONZERO, 1.0f);
    circle(s, 400.0f, 300.0f, 230.0f, 0);
    circle(s, 400.0f, 300.0f, 150.0f, 1);
    region(s, CS_FILL_NONZERO, 1.0f);
    circle(s, 1500.0f, 600.0f, 320.0f, 0);
    region(s, CS_FILL_NONZERO, 0.5f);
    circle(s, 900.0f, 850.0f, 120.0f, 0);
}

static void build_heavy(cs_scene *s)
{
    must(cs_scene_init(s, W, H), "init");
    const float bg[3] = {1, 1, 1};
    must(cs_scene_set_background(s, bg), "background");
    rng = 11u;
    for (int c = 0; c < 10; c++) {
        cel(s, 0.0f, 0.0f, 0.0f);
        for (int b = 0; b < 30; b++) {
            region(s, CS_FILL_NONZERO, rnd(0.3f, 1.0f));
            bezier_blob(s, rnd(0, W), rnd(0, H), rnd(20, 110), 8, 1.0f);
        }
    }
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static int cmp_d(const void *a, const void *b)
{
    double p = *(const double *)a, q = *(const double *)b;
    return p < q ? -1 : (p > q ? 1 : 0);
}

static double frame_ms(const cs_scene *s, cs_workspace *ws, cs_aa_mode aa, int sub, float *line)
{
    cs_render_opts o = cs_render_defaults(W, H);
    o.aa = aa;
    o.subscanlines = sub;
    cs_renderer r;
    cs_error err;
    double t0 = now_ms();
    must(cs_frame_begin(&r, ws, s, &o, &err), "frame");
    for (int y = 0; y < H; y++)
        must(cs_render_line(&r, y, line), "line");
    double t = now_ms() - t0;
    must(r.sticky.status, "render");
    return t;
}

int main(int argc, char **argv)
{
    long runs = 5;
    if (argc > 1 && !cli_int(argv[1], 10, '\0', 1, 64, &runs)) {
        fprintf(stderr, "usage: bench_aa_modes [RUNS 1..64]\n");
        return 2;
    }
    cs_scene *s = malloc(sizeof *s);
    cs_workspace *ws = malloc(sizeof *ws);
    float *line = malloc(sizeof(float) * 3 * W);
    if (!s || !ws || !line)
        return 1;
    const char *names[2] = {"demo", "heavy"};
    const cs_aa_mode modes[3] = {CS_AA_EXACT, CS_AA_SUBSCAN, CS_AA_SUBSCAN};
    const int subs[3] = {0, 5, 16};
    printf("1920x1080, %ld runs, CPU ms/frame (cs_frame_begin + all lines): median (min)\n", runs);
    printf("%-6s %18s %18s %18s\n", "scene", "exact", "aa 5", "aa 16");
    for (int sc = 0; sc < 2; sc++) {
        if (sc == 0)
            build_demo(s);
        else
            build_heavy(s);
        double t[3][64];
        frame_ms(s, ws, CS_AA_EXACT, 0, line); /* warm-up: first touch of the workspace */
        for (int k = 0; k < runs; k++)
            for (int m = 0; m < 3; m++)
                t[m][k] = frame_ms(s, ws, modes[m], subs[m], line);
        printf("%-6s", names[sc]);
        for (int m = 0; m < 3; m++) {
            qsort(t[m], (size_t)runs, sizeof t[m][0], cmp_d);
            printf(" %9.2f (%6.2f)", t[m][runs / 2], t[m][0]);
        }
        printf("\n");
    }
    free(s);
    free(ws);
    free(line);
    return 0;
}
