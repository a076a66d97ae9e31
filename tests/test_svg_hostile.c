/*
 * test_svg_hostile.c - the importer on files made to exhaust it.
 *
 * Each case is generated here (none is in any suite): 200,000 nested <g>,
 * a dash pattern of 0.001 on a long path, <use> fan-out (a billion laughs,
 * with and without anything drawn), 100,000 shapes, a curvy stroke too
 * wide for any outline budget, a chain of <use> deeper than the nesting
 * limit, a large clip path applied a thousand times, clip paths and
 * markers nested in themselves six deep, half a million characters of
 * text, a million empty elements. Each is imported in a child process under 512 MB of address
 * space and 5 s of CPU (and a 10 s alarm), and must end in an error that
 * names its limit within those bounds, measured from outside: the child's
 * wall time and peak resident size (wait4's rusage). The large benign file
 * also checks the stated memory bound, 64 x file size + 64 MB.
 *
 * Where the file is valid but odd (viewBox 0 0 0 0, stroke-width 1e30,
 * 1e8, a gradient of 100,000 stops, more warnings than are kept) the import succeeds and the checks are
 * on its warnings and output.
 */
#define _GNU_SOURCE
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "../tools/svg/sv.h"
#include "svg_test.h"

#define LIMIT_MB 512
#define LIMIT_S 5

/* A growable string for building the files. */
typedef struct buf {
    char *s;
    size_t n, cap;
} buf;

static void put(buf *b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    char tmp[512];
    int k = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (b->n + (size_t)k + 1 > b->cap) {
        b->cap = 2 * (b->n + (size_t)k + 1);
        b->s = realloc(b->s, b->cap);
    }
    memcpy(b->s + b->n, tmp, (size_t)k + 1);
    b->n += (size_t)k;
}

static void put_n(buf *b, const char *s, long times)
{
    for (long i = 0; i < times; i++)
        put(b, "%s", s);
}

typedef struct outcome {
    bool exited;   /* normally, not killed */
    int rc;        /* 0: imported, 1: import error */
    char msg[600]; /* the error, or the warnings joined */
    int nwarnings;
    long regions;
    double secs;
    long rss_mb;
} outcome;

/*
 * Imports `svg` in a child under the limits; the child sends its result
 * through a pipe. The wall time and peak RSS are the parent's view.
 */
static outcome import_limited(const buf *svg)
{
    outcome o;
    memset(&o, 0, sizeof o);
    int fd[2];
    if (pipe(fd) < 0)
        return o;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    pid_t pid = fork();
    if (pid == 0) {
        close(fd[0]);
        struct rlimit as = {(rlim_t)LIMIT_MB << 20, (rlim_t)LIMIT_MB << 20};
        struct rlimit cpu = {LIMIT_S, LIMIT_S};
        setrlimit(RLIMIT_AS, &as);
        setrlimit(RLIMIT_CPU, &cpu);
        alarm(2 * LIMIT_S);
        sv_doc doc;
        char err[600];
        sv_import_opts io;
        memset(&io, 0, sizeof io);
        io.nominal_px = 256;
        int rc = sv_import_buffer(svg->s, svg->n, &io, &doc, err, sizeof err) < 0;
        outcome r;
        memset(&r, 0, sizeof r);
        r.exited = true;
        r.rc = rc;
        if (rc) {
            snprintf(r.msg, sizeof r.msg, "%s", err);
        } else {
            r.nwarnings = doc.nwarnings;
            r.regions = (long)sv_doc_region_count(&doc);
            for (int i = 0; i < doc.nwarnings; i++) {
                size_t used = strlen(r.msg);
                snprintf(r.msg + used, sizeof r.msg - used, "%s%s", i ? "; " : "",
                         doc.warnings[i]);
            }
            sv_doc_free(&doc);
        }
        if (write(fd[1], &r, sizeof r) != (ssize_t)sizeof r)
            _exit(3);
        _exit(0);
    }
    close(fd[1]);
    outcome got;
    ssize_t n = pid > 0 ? read(fd[0], &got, sizeof got) : -1;
    close(fd[0]);
    int status = 0;
    struct rusage ru;
    memset(&ru, 0, sizeof ru);
    if (pid > 0)
        wait4(pid, &status, 0, &ru);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    if (n == (ssize_t)sizeof got && WIFEXITED(status) && WEXITSTATUS(status) == 0)
        o = got;
    else if (WIFSIGNALED(status))
        snprintf(o.msg, sizeof o.msg, "child killed by signal %d (%s)", WTERMSIG(status),
                 strsignal(WTERMSIG(status)));
    o.secs = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    o.rss_mb = ru.ru_maxrss / 1024;
    return o;
}

/* The case ends in an error naming `limit`, within the time and memory bounds. */
static void expect_error(const char *name, const buf *svg, const char *limit)
{
    outcome o = import_limited(svg);
    printf("  hostile %-22s %8zu bytes: %.2f s, %4ld MB: %s\n", name, svg->n, o.secs, o.rss_mb,
           o.exited ? (o.rc ? o.msg : "imported") : o.msg);
    CHECK(o.exited && o.rc == 1 && strstr(o.msg, limit), "%s: error naming %s (got: %s)",
              name, limit, o.msg);
    CHECK(o.secs < LIMIT_S, "%s: %.2f s, not under %d s", name, o.secs, LIMIT_S);
    CHECK(o.rss_mb < LIMIT_MB, "%s: %ld MB, not under %d MB", name, o.rss_mb, LIMIT_MB);
}

static void head(buf *b, const char *viewbox)
{
    put(b, "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" "
           "viewBox=\"%s\">", viewbox);
}

/* Ten <use> of the level below at each of `levels` levels: 10^levels copies. */
static void laughs(buf *b, const char *leaf, int levels)
{
    head(b, "0 0 10 10");
    put(b, "<defs>%s", leaf);
    for (int i = 1; i <= levels; i++) {
        put(b, "<g id=\"a%d\">", i);
        for (int k = 0; k < 10; k++)
            put(b, "<use xlink:href=\"#a%d\"/>", i - 1);
        put(b, "</g>");
    }
    put(b, "</defs><use xlink:href=\"#a%d\"/></svg>", levels);
}

static void test_errors(void)
{
    buf b = {0};
    head(&b, "0 0 10 10");
    put_n(&b, "<g>", 200000);
    put(&b, "<rect width=\"5\" height=\"5\"/>");
    put_n(&b, "</g>", 200000);
    put(&b, "</svg>");
    expect_error("200000 nested <g>", &b, "SV_MAX_DEPTH");

    b.n = 0;
    head(&b, "0 0 1000 1000");
    put(&b, "<path d=\"M0 0 L1000 1000 L0 1000 Z\" stroke=\"black\" "
            "stroke-dasharray=\"0.001\"/></svg>");
    expect_error("dasharray 0.001", &b, "SV_MAX_DASHES");

    b.n = 0;
    laughs(&b, "<g id=\"a0\"/>", 19);
    expect_error("<use> fan-out, empty", &b, "SV_MAX_USE_COPIES");

    b.n = 0;
    laughs(&b, "<rect id=\"a0\" width=\"1\" height=\"1\"/>", 19);
    expect_error("<use> fan-out, rects", &b, "CS_CFG_MAX_REGIONS");

    b.n = 0;
    head(&b, "0 0 10 10");
    put(&b, "<defs><g id=\"a300\"/>");
    for (int i = 299; i >= 0; i--)
        put(&b, "<g id=\"a%d\"><use xlink:href=\"#a%d\"/></g>", i, i + 1);
    put(&b, "</defs><use xlink:href=\"#a0\"/></svg>");
    expect_error("<use> chain of 300", &b, "SV_MAX_DEPTH");

    b.n = 0;
    head(&b, "0 0 1000 1000");
    for (int i = 0; i < 100000; i++)
        put(&b, "<rect x=\"%d\" y=\"%d\" width=\"3\" height=\"3\" fill=\"#%06x\"/>", i % 1000,
            i / 1000, (i * 37) % 0xffffff);
    put(&b, "</svg>");
    expect_error("100000 rects", &b, "CS_CFG_MAX_REGIONS");

    b.n = 0;
    head(&b, "0 0 1000 1000");
    put(&b, "<path d=\"M0 0");
    for (int i = 0; i < 300; i++)
        put(&b, " c 5 -10 10 10 15 0");
    put(&b, "\" fill=\"none\" stroke=\"black\" stroke-width=\"1e4\"/></svg>");
    expect_error("curvy stroke-width 1e4", &b, "CS_CFG_MAX_POINTS");

    b.n = 0;
    head(&b, "0 0 1000 1000");
    put(&b, "<clipPath id=\"c\"><path d=\"M0 0");
    for (int i = 0; i < 2000; i++)
        put(&b, " L%d %d", i % 1000, (i * 7) % 1000);
    put(&b, "\"/></clipPath>");
    put_n(&b, "<g clip-path=\"url(#c)\"/>", 1000);
    put(&b, "</svg>");
    expect_error("clip path x 1000", &b, "SV_MAX_CLIP_POINTS");

    /* markers whose content has markers: 300 vertices each, 6 deep (300^7 instances) */
    b.n = 0;
    head(&b, "0 0 100 100");
    for (int level = -1; level < 6; level++) {
        if (level >= 0)
            put(&b, "<marker id=\"m%d\">", level);
        put(&b, "<path d=\"M0 0");
        for (int i = 0; i < 300; i++)
            put(&b, " L%d %d", i % 100, (i * 7) % 100);
        put(&b, "\" fill=\"none\" stroke=\"none\" marker-mid=\"url(#m%d)\"/>", level + 1);
        if (level >= 0)
            put(&b, "</marker>");
    }
    put(&b, "</svg>");
    expect_error("marker fan-out", &b, "SV_MAX_USE_COPIES");

    /* clip paths whose children are clipped by the next: 50^6 applications */
    b.n = 0;
    head(&b, "0 0 100 100");
    for (int level = 0; level < 6; level++) {
        put(&b, "<clipPath id=\"k%d\">", level);
        for (int i = 0; i < 50; i++)
            put(&b, level < 5 ? "<rect width=\"%d\" height=\"9\" clip-path=\"url(#k%d)\"/>"
                              : "<rect width=\"%d\" height=\"9\"/>", i + 1, level + 1);
        put(&b, "</clipPath>");
    }
    put(&b, "<rect width=\"100\" height=\"100\" clip-path=\"url(#k0)\"/></svg>");
    expect_error("clip children fan-out", &b, "SV_MAX_CLIP_POINTS");

    b.n = 0;
    head(&b, "0 0 1000 1000");
    put(&b, "<text x=\"0\" y=\"20\" font-size=\"20\">");
    put_n(&b, "WMB@&amp;", 100000);
    put(&b, "</text></svg>");
    expect_error("500000 characters", &b, "SV_MAX_TEXT_BYTES");
    free(b.s);
}

/*
 * A million empty elements (5 MB): nothing to draw, within the stated
 * bound on memory, 64 x file size + 64 MB.
 */
static void test_memory_bound(void)
{
    buf b = {0};
    head(&b, "0 0 10 10");
    put_n(&b, "<g/> ", 1000000);
    put(&b, "</svg>");
    outcome o = import_limited(&b);
    long bound = (long)(64 * b.n >> 20) + 64;
    printf("  hostile %-22s %8zu bytes: %.2f s, %4ld MB (bound %ld MB)\n", "1000000 <g/>", b.n,
           o.secs, o.rss_mb, bound);
    CHECK(o.exited && o.rc == 0, "1000000 <g/>: imported (%s)", o.msg);
    CHECK(o.rss_mb <= bound, "1000000 <g/>: %ld MB over the bound of %ld MB", o.rss_mb, bound);
    CHECK(o.secs < LIMIT_S, "1000000 <g/>: %.2f s", o.secs);
    free(b.s);
}

static outcome import_text(const char *svg)
{
    buf b = {0};
    put(&b, "%s", svg);
    outcome o = import_limited(&b);
    free(b.s);
    return o;
}

/* Valid but odd: drawn as far as it can be, and every loss warned. */
static void test_warned(void)
{
    outcome o = import_text("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 0 0\">"
                            "<rect width=\"5\" height=\"5\"/></svg>");
    CHECK(o.exited && o.rc == 0 && o.regions == 0 && strstr(o.msg, "zero width"),
              "viewBox 0 0 0 0: nothing drawn, warned (%s)", o.msg);

    o = import_text("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 10 10\">"
                    "<rect width=\"5\" height=\"5\" stroke=\"red\" stroke-width=\"1e30\"/></svg>");
    CHECK(o.exited && o.rc == 0 && o.regions == 1 && strstr(o.msg, "not drawn") &&
                  strstr(o.msg, "stroke"),
              "stroke-width 1e30: the stroke left out, warned (%ld regions: %s)", o.regions,
              o.msg);

    o = import_text("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 10 10\">"
                    "<rect width=\"5\" height=\"5\" stroke=\"red\" stroke-width=\"1e8\"/></svg>");
    CHECK(o.exited && o.rc == 0 && o.regions == 2 && strstr(o.msg, "cut to the canvas"),
              "stroke-width 1e8: cut to the canvas, warned (%ld regions: %s)", o.regions, o.msg);

    /* 100,000 stops painting 1000 shapes: SV_MAX_STOPS of them, warned, in bounded time */
    buf b = {0};
    head(&b, "0 0 1000 1000");
    put(&b, "<linearGradient id=\"g\">");
    for (int i = 0; i < 100000; i++)
        put(&b, "<stop offset=\"%g\" stop-color=\"#%06x\"/>", i / 1e5, (i * 7919) % 0xffffff);
    put(&b, "</linearGradient>");
    for (int i = 0; i < 1000; i++)
        put(&b, "<rect x=\"%d\" width=\"1\" height=\"9\" fill=\"url(#g)\"/>", i);
    put(&b, "</svg>");
    o = import_limited(&b);
    printf("  hostile %-22s %8zu bytes: %.2f s, %4ld MB\n", "100000 stops x 1000", b.n, o.secs,
           o.rss_mb);
    CHECK(o.exited && o.rc == 0 && o.regions == 1000 && strstr(o.msg, "SV_MAX_STOPS"),
              "100000 stops: drawn with the first SV_MAX_STOPS, warned (%s)", o.msg);
    CHECK(o.secs < LIMIT_S && o.rss_mb < LIMIT_MB, "100000 stops: %.2f s, %ld MB", o.secs,
              o.rss_mb);

    b.n = 0;
    head(&b, "0 0 10 10");
    for (int i = 0; i < 5000; i++)
        put(&b, "<blink id=\"b%d\"/>", i);
    put(&b, "</svg>");
    o = import_limited(&b);
    CHECK(o.exited && o.rc == 0 && o.nwarnings == SV_MAX_WARNINGS + 1,
              "5000 unsupported elements: %d warnings kept, not %d", o.nwarnings,
              SV_MAX_WARNINGS + 1);
    free(b.s);
}

void test_svg_hostile(const svg_test_opts *o)
{
    (void)o;
    test_errors();
    test_memory_bound();
    test_warned();
}
