/*
 * svg_conformance.c - the importer on resvg's conformance suite.
 *
 * The suite (../shared/conformance/resvg beside the project, never copied
 * in) holds SVG files with resvg's reference rendering beside each as a PNG.
 * Every test goes through the product's own path, one process each, under
 * a time and memory limit so that a crash or a runaway import is a result
 * and not the end of the run:
 *
 *   celc import T.svg -o T.json --background '#ffffff' --nominal MAX(W,H)
 *   celsim render T.json --size WxH -o T.png       (W x H: the reference's)
 *
 * and the render is compared with the reference composited over white, by
 * PSNR over the 8-bit sRGB channels; a test passes at >= 30 dB. Printed:
 * one line per test that fails (its PSNR or error, and the importer's
 * warnings, which name what it left out), the pass count per category and
 * the total. With --report, the same as a Markdown page (docs/SVG-
 * CONFORMANCE.md), where a hand-written note (--notes: lines
 * "category/name: reason") explains a failure better than the warnings can.
 *
 * The checks (the last line is "svg-conformance: N passed, M failed" for
 * tests/run.sh): no test crashed or ran out of its limits, and, with
 * --floor N, at least N tests passed.
 *
 *   svg_conformance SUITE --celc PATH --celsim PATH [--outdir DIR]
 *       [--every K] [--floor N] [--report FILE.md] [--notes FILE] [-v]
 */
#define _XOPEN_SOURCE 700
#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <math.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "../tools/cli_num.h"
#include "../tools/svg/sv_render.h"
#include "testlib.h"

#define PASS_DB 30.0
/* Per process: the bounds the issue sets for hostile files hold here too. */
#define LIMIT_SECONDS 10
#define LIMIT_BYTES (512L << 20)

typedef enum outcome { PASS, FAIL, ERROR, CRASH } outcome;

typedef struct result {
    char *rel;      /* category/name, without .svg */
    outcome what;
    double psnr;
    char why[600];  /* error text, or the importer's warnings */
} result;

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
            char **f = realloc(files, (size_t)capfiles * sizeof *files);
            if (!f)
                return -1;
            files = f;
        }
        files[nfiles++] = strdup(path);
    }
    return 0;
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/*
 * Runs argv with stdout and stderr to `log`, in its own process under
 * LIMIT_SECONDS (CPU and wall clock) and LIMIT_BYTES of address space.
 * Returns the exit status (0..255), or -signal if it was killed.
 */
static int run_limited(char *const argv[], const char *log)
{
    pid_t pid = fork();
    if (pid < 0)
        return -SIGABRT;
    if (pid == 0) {
        int fd = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0) {
            dup2(fd, 1);
            dup2(fd, 2);
            close(fd);
        }
        struct rlimit cpu = {LIMIT_SECONDS, LIMIT_SECONDS};
        struct rlimit as = {LIMIT_BYTES, LIMIT_BYTES};
        setrlimit(RLIMIT_CPU, &cpu);
        setrlimit(RLIMIT_AS, &as);
        alarm(2 * LIMIT_SECONDS); /* kept across exec: a stall ends too */
        execv(argv[0], argv);
        _exit(127);
    }
    int status;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return -SIGABRT;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

/* Appends sep and s to the string in dst (cap bytes), cut with "..." if it is full. */
static void append(char *dst, size_t cap, const char *sep, const char *s)
{
    size_t used = strlen(dst);
    if (!dst[0])
        sep = "";
    size_t need = strlen(sep) + strlen(s);
    if (used + need < cap) {
        strcat(strcat(dst, sep), s);
        return;
    }
    if (cap < used + 4)
        return;
    size_t room = cap - used - 4;
    snprintf(dst + used, room + 1, "%s%s", sep, s);
    strcat(dst, "...");
}

/*
 * What the importer said, from its log: the first line of an error, or its
 * warnings joined by "; " with the file name and the "warning: " prefix
 * left out, cut to fit.
 */
static void summarise_log(const char *log, bool warnings_only, char *out, size_t cap)
{
    out[0] = 0;
    FILE *f = fopen(log, "r");
    if (!f)
        return;
    char line[1024];
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = 0;
        const char *w = strstr(line, "warning: ");
        if (warnings_only && !w)
            continue;
        const char *text = w ? w + 9 : line;
        if (!w) {
            /* an error names the file first: drop the suite's path */
            const char *svg = strstr(line, ".svg: ");
            text = svg ? svg + 6 : line;
        }
        append(out, cap, "; ", text);
        if (!warnings_only)
            break;
    }
    fclose(f);
}

/* PSNR of our RGB render against the reference's RGBA over white. */
static double psnr_over_white(const uint8_t *ours, const uint8_t *ref, int n)
{
    double se = 0;
    for (int i = 0; i < n; i++) {
        int a = ref[4 * i + 3];
        for (int k = 0; k < 3; k++) {
            /* straight alpha over white in 8-bit sRGB, rounded as resvg's PNG would be */
            double c = (ref[4 * i + k] * a + 255.0 * (255 - a)) / 255.0;
            double d = floor(c + 0.5) - ours[4 * i + k];
            se += d * d;
        }
    }
    double mse = se / (3.0 * n);
    return mse > 0 ? 10 * log10(255.0 * 255.0 / mse) : 99;
}

static void run_test(const char *svg, const char *suite, const char *celc, const char *celsim,
                     const char *work, result *r)
{
    size_t sl = strlen(suite);
    r->rel = strndup(svg + sl + (svg[sl] == '/'), strlen(svg) - sl - (svg[sl] == '/') - 4);
    r->psnr = 0;
    r->why[0] = 0;
    char refpng[4096], json[4096], png[4096], log[4096];
    snprintf(refpng, sizeof refpng, "%.*s.png", (int)(strlen(svg) - 4), svg);
    snprintf(json, sizeof json, "%s/t.json", work);
    snprintf(png, sizeof png, "%s/t.png", work);
    snprintf(log, sizeof log, "%s/t.log", work);
    uint8_t *ref = NULL, *ours = NULL;
    int w, h, ow, oh;
    if (sv_png_read_rgba(refpng, &ref, &w, &h) < 0) {
        r->what = ERROR;
        snprintf(r->why, sizeof r->why, "no reference PNG %.500s", refpng);
        return;
    }
    char size[64], nominal[32];
    snprintf(size, sizeof size, "%dx%d", w, h);
    snprintf(nominal, sizeof nominal, "%d", w > h ? w : h);
    remove(json);
    remove(png);
    char *imp[] = {(char *)celc, "import", (char *)svg, "-o", json, "--background", "#ffffff",
                   "--nominal", nominal, NULL};
    int rc = run_limited(imp, log);
    char warnings[sizeof r->why];
    summarise_log(log, true, warnings, sizeof warnings);
    if (rc != 0) {
        r->what = rc < 0 ? CRASH : ERROR;
        char err[sizeof r->why];
        summarise_log(log, false, err, sizeof err);
        if (rc < 0)
            snprintf(r->why, sizeof r->why, "celc import killed by signal %d (%s)", -rc,
                     strsignal(-rc));
        else
            append(strcpy(r->why, "celc import:"), sizeof r->why, " ", err);
        free(ref);
        return;
    }
    char *ren[] = {(char *)celsim, "render", json, "--size", size, "-o", png, NULL};
    rc = run_limited(ren, log);
    if (rc != 0) {
        /* 3: written, but the renderer ran out of capacity; still compared */
        char err[sizeof r->why];
        summarise_log(log, false, err, sizeof err);
        if (rc < 0 || rc != 3) {
            r->what = rc < 0 ? CRASH : ERROR;
            strcpy(r->why, rc < 0 ? "celsim render killed:" : "celsim render failed:");
            append(r->why, sizeof r->why, " ", err);
            free(ref);
            return;
        }
        append(warnings, sizeof warnings, "; ", "celsim:");
        append(warnings, sizeof warnings, " ", err);
    }
    if (sv_png_read_rgba(png, &ours, &ow, &oh) < 0 || ow != w || oh != h) {
        r->what = ERROR;
        snprintf(r->why, sizeof r->why, "celsim wrote no %s image", size);
    } else {
        r->psnr = psnr_over_white(ours, ref, w * h);
        r->what = r->psnr >= PASS_DB ? PASS : FAIL;
        strcpy(r->why, warnings);
    }
    free(ref);
    free(ours);
}

/* A hand-written reason for rel from the notes file ("category/name: reason"), or NULL. */
static const char *note_for(char **notes, int nnotes, const char *rel)
{
    size_t n = strlen(rel);
    for (int i = 0; i < nnotes; i++)
        if (!strncmp(notes[i], rel, n) && notes[i][n] == ':')
            return notes[i] + n + 1 + (notes[i][n + 1] == ' ');
    return NULL;
}

static int read_notes(const char *path, char ***notes)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    int n = 0, cap = 0;
    char line[2048];
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = 0;
        if (!line[0] || line[0] == '#')
            continue;
        if (n == cap) {
            cap = cap ? 2 * cap : 64;
            *notes = realloc(*notes, (size_t)cap * sizeof **notes);
        }
        (*notes)[n++] = strdup(line);
    }
    fclose(f);
    return n;
}

typedef struct category {
    char name[128];
    int total, pass;
} category;

static void category_of(const char *rel, char *out, size_t cap)
{
    const char *slash = strrchr(rel, '/');
    snprintf(out, cap, "%.*s", slash ? (int)(slash - rel) : 0, rel);
}

static const char *what_str(outcome o)
{
    return o == PASS ? "pass" : o == FAIL ? "FAIL" : o == ERROR ? "ERROR" : "CRASH";
}

/* Markdown cells must not break the table. */
static void md_cell(FILE *f, const char *s)
{
    for (; *s; s++)
        fputs(*s == '|' ? "\\|" : (char[2]){*s, 0}, f);
}

static void write_report(const char *path, const result *res, int n, const category *cat,
                         int ncat, int passed, char **notes, int nnotes, int every)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        return;
    }
    fprintf(f, "# SVG conformance: the importer on resvg's test suite\n\n"
               "Generated by `make svg-conformance-doc` (tests/svg_conformance.c); do not edit by "
               "hand.\nReasons for failures come from tests/svg_conformance_notes.txt where "
               "written there,\nelse from the importer's own warnings.\n\n"
               "Each test of `../shared/conformance/resvg/` (resvg's suite, its static-vector "
               "categories) is\nimported with `celc import --background '#ffffff'`, rendered by "
               "`celsim render` at the\nreference's size, and compared with resvg's PNG composited "
               "over white: PSNR over the 8-bit\nsRGB channels, pass at %.0f dB.%s\n\n",
            PASS_DB, every > 1 ? " (This run took every Nth test only.)" : "");
    fprintf(f, "**%d of %d pass (%.1f%%).**\n\n| category | pass | tests |\n|---|---:|---:|\n",
            passed, n, n ? 100.0 * passed / n : 0);
    for (int c = 0; c < ncat; c++)
        fprintf(f, "| %s | %d | %d |\n", cat[c].name, cat[c].pass, cat[c].total);
    fprintf(f, "| **total** | **%d** | **%d** |\n\n## Tests that fail\n\n"
               "| test | result | reason |\n|---|---|---|\n", passed, n);
    for (int i = 0; i < n; i++) {
        if (res[i].what == PASS)
            continue;
        const char *note = note_for(notes, nnotes, res[i].rel);
        fprintf(f, "| %s | ", res[i].rel);
        if (res[i].what == FAIL)
            fprintf(f, "%.1f dB", res[i].psnr);
        else
            fputs(what_str(res[i].what), f);
        fputs(" | ", f);
        md_cell(f, note ? note : res[i].why[0] ? res[i].why : "(no warning)");
        fputs(" |\n", f);
    }
    fclose(f);
}

static int usage(void)
{
    fprintf(stderr, "usage: svg_conformance SUITE --celc PATH --celsim PATH [--outdir DIR]\n"
                    "       [--every K] [--floor N] [--report FILE.md] [--notes FILE] [-v]\n");
    return 2;
}

int main(int argc, char **argv)
{
    const char *suite = NULL, *celc = NULL, *celsim = NULL, *outdir = "build/svg-conformance",
               *report = NULL, *notes_path = NULL;
    long every = 1, floor_n = -1;
    bool verbose = false;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        bool more = i + 1 < argc;
        if (!strcmp(a, "--celc") && more)
            celc = argv[++i];
        else if (!strcmp(a, "--celsim") && more)
            celsim = argv[++i];
        else if (!strcmp(a, "--outdir") && more)
            outdir = argv[++i];
        else if (!strcmp(a, "--report") && more)
            report = argv[++i];
        else if (!strcmp(a, "--notes") && more)
            notes_path = argv[++i];
        else if (!strcmp(a, "--every") && more) {
            if (!cli_int(argv[++i], 10, 0, 1, 1000, &every))
                return usage();
        } else if (!strcmp(a, "--floor") && more) {
            if (!cli_int(argv[++i], 10, 0, 0, 100000, &floor_n))
                return usage();
        } else if (!strcmp(a, "-v"))
            verbose = true;
        else if (a[0] != '-' && !suite)
            suite = a;
        else
            return usage();
    }
    if (!suite || !celc || !celsim)
        return usage();
    struct stat st;
    if (stat(suite, &st) != 0 || !S_ISDIR(st.st_mode)) {
        /* the suite lives beside the project; a checkout without it skips */
        printf("svg-conformance: suite not found at %s: skipped\n", suite);
        return tl_summary("svg-conformance");
    }
    char **notes = NULL;
    int nnotes = 0;
    if (notes_path && (nnotes = read_notes(notes_path, &notes)) < 0) {
        perror(notes_path);
        return 1;
    }
    mkdir(outdir, 0777);
    nftw(suite, visit, 16, FTW_PHYS);
    qsort(files, (size_t)nfiles, sizeof *files, cmp_str);
    size_t slen = strlen(suite);
    while (slen > 1 && suite[slen - 1] == '/')
        slen--;
    char base[4096];
    snprintf(base, sizeof base, "%.*s", (int)slen, suite);
    int n = (nfiles + (int)every - 1) / (int)every;
    result *res = calloc((size_t)(n ? n : 1), sizeof *res);
    category cat[64];
    int ncat = 0, passed = 0, broken = 0;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (int i = 0; i < n; i++) {
        result *r = &res[i];
        run_test(files[(long)i * every], base, celc, celsim, outdir, r);
        char cname[128];
        category_of(r->rel, cname, sizeof cname);
        int c = 0;
        while (c < ncat && strcmp(cat[c].name, cname))
            c++;
        if (c == ncat && ncat < 64) {
            snprintf(cat[ncat].name, sizeof cat[ncat].name, "%s", cname);
            cat[ncat].total = cat[ncat].pass = 0;
            ncat++;
        }
        if (c < ncat) {
            cat[c].total++;
            cat[c].pass += r->what == PASS;
        }
        passed += r->what == PASS;
        broken += r->what == CRASH;
        if (r->what != PASS || verbose) {
            const char *note = note_for(notes, nnotes, r->rel);
            printf("  %-5s %s", what_str(r->what), r->rel);
            if (r->what == PASS || r->what == FAIL)
                printf(": %.1f dB", r->psnr);
            if (note || r->why[0])
                printf(" - %s", note ? note : r->why);
            printf("\n");
        }
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    printf("svg-conformance: by category (pass / tests):\n");
    for (int c = 0; c < ncat; c++)
        printf("  %-32s %4d / %4d\n", cat[c].name, cat[c].pass, cat[c].total);
    double secs = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    printf("svg-conformance: %d of %d tests pass (%.1f%%) at %.0f dB%s, %d crashed or over "
           "limits, %.1f s\n", passed, n, n ? 100.0 * passed / n : 0, PASS_DB,
           every > 1 ? " (every Nth test)" : "", broken, secs);
    if (report)
        write_report(report, res, n, cat, ncat, passed, notes, nnotes, (int)every);
    CHECK(broken == 0, "%d tests crashed or ran over %d s / %ld MB", broken, LIMIT_SECONDS,
          LIMIT_BYTES >> 20);
    if (floor_n >= 0)
        CHECK(passed >= floor_n, "%d tests pass, below the floor of %ld", passed, floor_n);
    for (int i = 0; i < nfiles; i++)
        free(files[i]);
    for (int i = 0; i < n; i++)
        free(res[i].rel);
    for (int i = 0; i < nnotes; i++)
        free(notes[i]);
    free(notes);
    free(files);
    free(res);
    return tl_summary("svg-conformance");
}
