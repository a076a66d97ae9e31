/*
 * test_svg_rsvg.c - imported icons against librsvg.
 *
 * Icons nobody here drew (the installed Adwaita, Breeze and hicolor
 * scalable themes) are rendered twice at 128 x 128 over white: by
 * rsvg-convert, and by this importer through the cs_scene back end and the
 * core (16 sub-scanlines). librsvg blends in sRGB space, so the render that
 * decides composites with cs_render_opts.blend = CS_BLEND_SRGB (the scene
 * itself is in linear light, as always); the linear-light render is
 * reported beside it.
 *
 * An icon passes at PSNR >= 30 dB. The test's one check is the pass rate
 * (>= 95%); per-icon results, the failures with the warnings that explain
 * them, and statistics by cause are printed as information, and every
 * icon's figures go to OUTDIR/rsvg-results.txt (path, dB with sRGB and with
 * linear blending, uses gradients, uses CSG clips) for comparing runs. The
 * CI run takes an evenly spaced, sorted (so deterministic) subset; --all
 * takes every icon.
 */
#define _XOPEN_SOURCE 700
#include <ftw.h>
#include <math.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>

#include "../tools/svg/sv.h"
#include "../tools/svg/sv_render.h"
#include "svg_test.h"

extern char **environ;

#define SIZE 128
#define PASS_DB 30.0

static char **files;
static int nfiles, capfiles;

static int visit(const char *path, const struct stat *st, int type, struct FTW *ftw)
{
    (void)st;
    (void)ftw;
    size_t n = strlen(path);
    if (type == FTW_F && n > 4 && strcmp(path + n - 4, ".svg") == 0) {
        if (nfiles == capfiles) {
            capfiles = capfiles ? 2 * capfiles : 1024;
            files = realloc(files, (size_t)capfiles * sizeof *files);
        }
        files[nfiles++] = strdup(path);
    }
    return 0;
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static int run_rsvg(const char *svg, const char *png)
{
    char size[16];
    snprintf(size, sizeof size, "%d", SIZE);
    char *argv[] = {"rsvg-convert", "-w", size, "-h", size, "-b", "white", "-f", "png",
                    "-o", (char *)png, (char *)svg, NULL};
    pid_t pid;
    if (posix_spawnp(&pid, "rsvg-convert", NULL, NULL, argv, environ) != 0)
        return -1;
    int status;
    if (waitpid(pid, &status, 0) < 0)
        return -1;
    return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? 0 : -1;
}

typedef struct stats {
    double psnr, mean, max;
} stats;

static stats compare(const uint8_t *a, const uint8_t *rgba, int n)
{
    double se = 0, sum = 0, mx = 0;
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            double d = (double)a[3 * i + k] - (double)rgba[4 * i + k];
            se += d * d;
            sum += fabs(d);
            mx = fmax(mx, fabs(d));
        }
    stats s;
    double mse = se / (3.0 * n);
    s.psnr = mse > 0 ? 10 * log10(255.0 * 255.0 / mse) : 99;
    s.mean = sum / (3.0 * n);
    s.max = mx;
    return s;
}

/* Ours | rsvg | 4x amplified difference, for looking at failures. */
static void save_triptych(const char *dir, const char *svg, const uint8_t *ours,
                          const uint8_t *ref)
{
    uint8_t *img = malloc((size_t)3 * 3 * SIZE * SIZE);
    for (int y = 0; y < SIZE; y++)
        for (int x = 0; x < SIZE; x++)
            for (int k = 0; k < 3; k++) {
                size_t row = (size_t)y * 3 * SIZE;
                int a = ours[3 * (y * SIZE + x) + k], b = ref[4 * (y * SIZE + x) + k];
                int d = 255 - 4 * abs(a - b);
                img[3 * (row + x) + k] = (uint8_t)a;
                img[3 * (row + SIZE + x) + k] = (uint8_t)b;
                img[3 * (row + 2 * SIZE + x) + k] = (uint8_t)(d < 0 ? 0 : d);
            }
    const char *base = strrchr(svg, '/') ? strrchr(svg, '/') + 1 : svg;
    char path[1024];
    snprintf(path, sizeof path, "%s/%.*s.png", dir, (int)(strlen(base) - 4), base);
    sv_png_write_rgb(path, img, 3 * SIZE, SIZE);
    free(img);
}

/* The cause a warning stands for (coarse, for the statistics). */
static const char *cause_of(const char *w)
{
    if (strstr(w, "paint functions are taken"))
        return "gradient: over CS_CFG_MAX_FUNCS (bands)";
    if (strstr(w, "gradient approximated"))
        return "gradient: not a paint function (bands)";
    if (strstr(w, "filter"))
        return "filter (blur etc.)";
    if (strstr(w, "mask"))
        return "mask";
    if (strstr(w, "clip path"))
        return "clip-path beyond CSG capacity";
    if (strstr(w, "clip-path") || strstr(w, "clipPath"))
        return "clip-path reference or content";
    if (strstr(w, "dasharray"))
        return "stroke-dasharray";
    if (strstr(w, "<text>") || strstr(w, "<tspan>") || strstr(w, "<flowRoot>"))
        return "text";
    if (strstr(w, "element not supported"))
        return "unsupported element";
    if (strstr(w, "paint"))
        return "paint server (pattern)";
    if (strstr(w, "CSS"))
        return "CSS";
    return "other warning";
}

#define MAX_CAUSES 16
typedef struct cause_count {
    const char *name;
    int fail, pass;
} cause_count;

static void count_cause(cause_count *cc, int *n, const char *name, bool failed)
{
    for (int i = 0; i < *n; i++)
        if (!strcmp(cc[i].name, name)) {
            if (failed)
                cc[i].fail++;
            else
                cc[i].pass++;
            return;
        }
    if (*n < MAX_CAUSES) {
        cc[*n].name = name;
        cc[*n].fail = failed;
        cc[*n].pass = !failed;
        (*n)++;
    }
}

void test_svg_rsvg(const svg_test_opts *o)
{
    static const char *const roots[] = {"/usr/share/icons/Adwaita/scalable",
                                        "/usr/share/icons/breeze",
                                        "/usr/share/icons/hicolor/scalable", NULL};
    for (int i = 0; roots[i]; i++)
        nftw(roots[i], visit, 16, FTW_PHYS);
    if (nfiles == 0) {
        CHECK(false, "no icon theme installed (tools/install-deps.sh installs them)");
        return;
    }
    qsort(files, (size_t)nfiles, sizeof *files, cmp_str);
    int take = o->all || o->limit >= nfiles ? nfiles : o->limit;
    char tmp[1024];
    snprintf(tmp, sizeof tmp, "%s/rsvg.png", o->outdir);
    cs_scene *scene = malloc(sizeof *scene);
    uint8_t *ours = malloc(3 * SIZE * SIZE), *lin = malloc(3 * SIZE * SIZE);
    int tested = 0, passed = 0, passed_lin = 0, skipped = 0, clean = 0,
        clean_pass = 0, grad_n = 0, grad_pass = 0, csg_n = 0, csg_pass = 0;
    double sum_db = 0, sum_db_lin = 0, grad_db = 0, csg_db = 0;
    snprintf(tmp, sizeof tmp, "%s/rsvg-results.txt", o->outdir);
    FILE *log = fopen(tmp, "w");
    snprintf(tmp, sizeof tmp, "%s/rsvg.png", o->outdir);
    cause_count cc[MAX_CAUSES];
    int ncc = 0;
    clock_t t0 = clock();
    printf("svg-rsvg: %d icons installed, testing %d at %dx%d (pass: PSNR >= %.0f dB, "
           "sRGB blending)\n", nfiles, take, SIZE, SIZE, PASS_DB);
    for (int j = 0; j < take; j++) {
        const char *svg = files[(long)j * nfiles / take];
        if (run_rsvg(svg, tmp) < 0) {
            skipped++;
            if (o->verbose)
                printf("  skip %s: rsvg-convert failed\n", svg);
            continue;
        }
        uint8_t *ref;
        int rw, rh;
        if (sv_png_read_rgba(tmp, &ref, &rw, &rh) < 0 || rw != SIZE || rh != SIZE) {
            skipped++;
            continue;
        }
        sv_import_opts io;
        memset(&io, 0, sizeof io);
        io.nominal_px = SIZE;
        io.one_cel_per_shape = o->one_cel;
        sv_doc doc;
        char err[512];
        const char *fail_cause = NULL;
        stats s = {0, 255, 255}, sl = {0, 255, 255};
        bool has_grad = false, has_csg = false;
        if (sv_import_file(svg, &io, &doc, err, sizeof err) < 0) {
            fail_cause = "import error";
        } else {
            has_grad = doc.ngradients > 0;
            for (int c = 0; c < doc.ncels; c++)
                for (int r = 0; r < doc.cels[c].nregions; r++)
                    has_csg |= doc.cels[c].regions[r].csg_clips > 0;
            sv_scene_opts so = {.has_background = true, .background = {1, 1, 1}};
            if (sv_doc_to_scene(&doc, &so, scene, err, sizeof err) < 0 ||
                sv_render_rgb8(scene, SIZE, SIZE, CS_AA_SUBSCAN, 16, CS_BLEND_SRGB, ours) !=
                    CS_OK) {
                fail_cause = "core capacity / render error";
            } else {
                s = compare(ours, ref, SIZE * SIZE);
                if (sv_render_rgb8(scene, SIZE, SIZE, CS_AA_SUBSCAN, 16, CS_BLEND_LINEAR, lin) ==
                    CS_OK)
                    sl = compare(lin, ref, SIZE * SIZE);
            }
        }
        bool pass = !fail_cause && s.psnr >= PASS_DB;
        tested++;
        passed += pass;
        passed_lin += !fail_cause && sl.psnr >= PASS_DB;
        sum_db += fmin(s.psnr, 60);
        sum_db_lin += fmin(sl.psnr, 60);
        if (has_grad) {
            grad_n++;
            grad_pass += pass;
            grad_db += fmin(s.psnr, 60);
        }
        if (has_csg) {
            csg_n++;
            csg_pass += pass;
            csg_db += fmin(s.psnr, 60);
        }
        if (log)
            fprintf(log, "%s %.2f %.2f %d %d\n", svg, s.psnr, sl.psnr, has_grad, has_csg);
        int nw = fail_cause ? 0 : doc.nwarnings;
        if (nw == 0 && !fail_cause) {
            clean++;
            clean_pass += pass;
        }
        /* causes: each distinct one once per icon */
        const char *seen[MAX_CAUSES];
        int nseen = 0;
        if (fail_cause)
            seen[nseen++] = fail_cause;
        for (int w = 0; w < nw; w++) {
            const char *c = cause_of(doc.warnings[w]);
            bool dup = false;
            for (int k = 0; k < nseen; k++)
                dup |= seen[k] == c;
            if (!dup && nseen < MAX_CAUSES)
                seen[nseen++] = c;
        }
        if (nseen == 0 && !pass)
            seen[nseen++] = "unexplained (no warning)";
        for (int k = 0; k < nseen; k++)
            count_cause(cc, &ncc, seen[k], !pass);
        if (!pass || o->verbose) {
            printf("  %s %s: %.1f dB (linear %.1f dB), mean %.2f max %.0f", pass ? "pass" : "FAIL",
                   svg, s.psnr, sl.psnr, s.mean, s.max);
            for (int k = 0; k < nseen; k++)
                printf("%s%s", k ? "; " : " - ", seen[k]);
            if (fail_cause)
                printf(" (%s)", err);
            printf("\n");
            if (!pass && !fail_cause)
                save_triptych(o->outdir, svg, ours, ref);
        }
        if (!fail_cause)
            sv_doc_free(&doc);
        free(ref);
    }
    remove(tmp);
    double rate = tested ? (double)passed / tested : 0;
    printf("svg-rsvg: causes (icons with the cause: failed / passed):\n");
    for (int k = 0; k < ncc; k++)
        printf("  %-44s %4d / %4d\n", cc[k].name, cc[k].fail, cc[k].pass);
    printf("svg-rsvg: icons without any warning: %d of %d pass\n", clean_pass, clean);
    printf("svg-rsvg: icons with gradients: %d of %d pass, mean %.1f dB; with CSG clips: %d "
           "of %d pass, mean %.1f dB\n", grad_pass, grad_n, grad_n ? grad_db / grad_n : 0,
           csg_pass, csg_n, csg_n ? csg_db / csg_n : 0);
    printf("svg-rsvg: linear-light blending would pass %d of %d (mean %.1f dB vs %.1f dB "
           "with sRGB blending)\n", passed_lin, tested, tested ? sum_db_lin / tested : 0,
           tested ? sum_db / tested : 0);
    if (log)
        fclose(log);
    printf("svg-rsvg: %d of %d icons pass (%.1f%%), %d skipped (rsvg-convert failed), %.1f s\n",
           passed, tested, 100 * rate, skipped, (double)(clock() - t0) / CLOCKS_PER_SEC);
    CHECK(tested > 0 && rate >= 0.95, "icon pass rate %.1f%% is below 95%%", 100 * rate);
    for (int i = 0; i < nfiles; i++)
        free(files[i]);
    free(files);
    files = NULL;
    nfiles = capfiles = 0;
    free(scene);
    free(ours);
    free(lin);
}
