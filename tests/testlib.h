/*
 * testlib.h - the in-house test harness of celscan's test programs.
 *
 * Deliberately tiny: one header, no registration, no fixtures. A test program
 * calls its test functions from main() through TL_RUN, uses CHECK* for every
 * expectation and returns tl_summary(argv[0]). Each failed expectation prints
 *   file:line: FAIL [test] message
 * and the program ends with the line
 *   <binary>: N passed, M failed
 * which tests/run.sh sums over all binaries. The exit status is non-zero if
 * anything failed.
 *
 * An expectation over a whole image is one CHECK (say "worst pixel within
 * 12/255") whose message names the worst pixel, what was expected and what
 * came out; tl_note() adds context lines (the first few offending pixels)
 * without counting anything.
 *
 * It is the one harness of every C test program (tests/, tests/linuxhal/):
 * tests/README.md says how to use it and where a new test goes.
 *
 * Everything is static: a test program in one file includes this once. A
 * program whose checks are spread over several files (test_svg) defines
 * TL_SHARED before including it in each of them, and TL_MAIN as well in the
 * file with main(): they then count into one pair of counters.
 */
#ifndef CELSCAN_TESTLIB_H
#define CELSCAN_TESTLIB_H

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celscan.h" /* cs_status, for the names of CHECK_STATUS and TL_MUST */

#if defined(TL_SHARED)
extern int tl_passed, tl_failed;
extern const char *tl_current;
#if defined(TL_MAIN)
int tl_passed, tl_failed;
const char *tl_current = "";
#endif
#else
static int tl_passed, tl_failed;
static const char *tl_current = "";
#endif

#if defined(__GNUC__)
#define TL_PRINTF(a, b) __attribute__((format(printf, a, b)))
#define TL_UNUSED __attribute__((unused))
#else
#define TL_PRINTF(a, b)
#define TL_UNUSED
#endif

static TL_PRINTF(4, 5) TL_UNUSED int tl_check(int ok, const char *file, int line, const char *fmt,
                                               ...)
{
    if (ok) {
        tl_passed++;
        return 1;
    }
    tl_failed++;
    if (tl_current[0])
        printf("%s:%d: FAIL [%s] ", file, line, tl_current);
    else
        printf("%s:%d: FAIL ", file, line);
    va_list ap;
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    printf("\n");
    fflush(stdout);
    return 0;
}

/* Context for the last failure (or any information worth a line): not counted. */
static TL_PRINTF(1, 2) TL_UNUSED void tl_note(const char *fmt, ...)
{
    printf("    ");
    va_list ap;
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    printf("\n");
}

/* CHECK(cond, "format", ...): the message says what was expected and what came. */
#define CHECK(cond, ...) tl_check(!!(cond), __FILE__, __LINE__, __VA_ARGS__)

#define CHECK_EQ_INT(got, want, what)                                                             \
    do {                                                                                          \
        long long tl_g_ = (long long)(got), tl_w_ = (long long)(want);                            \
        CHECK(tl_g_ == tl_w_, "%s: expected %lld, got %lld", (what), tl_w_, tl_g_);               \
    } while (0)

#define CHECK_NEAR(got, want, tol, what)                                                          \
    do {                                                                                          \
        double tl_g_ = (double)(got), tl_w_ = (double)(want), tl_t_ = (double)(tol);               \
        CHECK(tl_g_ - tl_w_ <= tl_t_ && tl_w_ - tl_g_ <= tl_t_,                                   \
              "%s: expected %.9g (+-%.3g), got %.9g (off by %.3g)", (what), tl_w_, tl_t_, tl_g_,  \
              tl_g_ - tl_w_);                                                                     \
    } while (0)

/* Status codes print with their names so a failure reads "CS_ERR_WEIGHT". */
#define CHECK_STATUS(got, want, what)                                                             \
    do {                                                                                          \
        int tl_g_ = (int)(got), tl_w_ = (int)(want);                                              \
        CHECK(tl_g_ == tl_w_, "%s: expected status %s (%d), got %s (%d)", (what),                 \
              tl_status_name(tl_w_), tl_w_, tl_status_name(tl_g_), tl_g_);                        \
    } while (0)

/* The name of a status (designated, so the order of cs_status does not
 * matter); one added to the core but not here prints as unnamed. */
/* A float's bits and the float of some bits, for tests that compare floats
 * bit for bit or walk every float of a range. */
static TL_UNUSED uint32_t tl_bits_of(float f)
{
    uint32_t b;
    memcpy(&b, &f, sizeof b);
    return b;
}

static TL_UNUSED float tl_float_of(uint32_t b)
{
    float f;
    memcpy(&f, &b, sizeof f);
    return f;
}

static TL_UNUSED const char *tl_status_name(int s)
{
#define TL_STATUS(name) [name] = #name
    static const char *const names[CS_ERR_COUNT_] = {
        TL_STATUS(CS_OK),
        TL_STATUS(CS_ERR_ARG),
        TL_STATUS(CS_ERR_STATE),
        TL_STATUS(CS_ERR_NONFINITE),
        TL_STATUS(CS_ERR_RANGE),
        TL_STATUS(CS_ERR_DEGREE),
        TL_STATUS(CS_ERR_TOO_FEW_POINTS),
        TL_STATUS(CS_ERR_WEIGHT),
        TL_STATUS(CS_ERR_INTERVAL),
        TL_STATUS(CS_ERR_ZERO_RUN),
        TL_STATUS(CS_ERR_DEGENERATE),
        TL_STATUS(CS_ERR_FILL_RULE),
        TL_STATUS(CS_ERR_PAINT),
        TL_STATUS(CS_ERR_SIZE),
        TL_STATUS(CS_ERR_CAP_CELS),
        TL_STATUS(CS_ERR_CAP_REGIONS),
        TL_STATUS(CS_ERR_CAP_CONTOURS),
        TL_STATUS(CS_ERR_CAP_POINTS),
        TL_STATUS(CS_ERR_CAP_SEGMENTS),
        TL_STATUS(CS_ERR_CAP_PIECES),
        TL_STATUS(CS_ERR_CAP_CROSSINGS),
        TL_STATUS(CS_ERR_IO),
        TL_STATUS(CS_ERR_CAP_FUNCS),
        TL_STATUS(CS_ERR_FUNC),
        TL_STATUS(CS_ERR_CSG),
        TL_STATUS(CS_ERR_CAP_CACHE),
        TL_STATUS(CS_ERR_INDEX),
        TL_STATUS(CS_ERR_COUNT),
        TL_STATUS(CS_ERR_TRACK),
        TL_STATUS(CS_ERR_KEY_ORDER),
        TL_STATUS(CS_ERR_CAP_TRACKS),
        TL_STATUS(CS_ERR_CAP_KEYS),
        TL_STATUS(CS_ERR_CAP_ANIM),
        TL_STATUS(CS_ERR_STREAM_SYNC),
        TL_STATUS(CS_ERR_STREAM_VERSION),
        TL_STATUS(CS_ERR_STREAM_CRC),
        TL_STATUS(CS_ERR_STREAM_TRUNCATED),
        TL_STATUS(CS_ERR_STREAM_TOO_BIG),
        TL_STATUS(CS_ERR_STREAM_RECORD),
        TL_STATUS(CS_ERR_GROUP),
        TL_STATUS(CS_ERR_STREAM_GAP),
    };
#undef TL_STATUS
    if (s >= 0 && s < (int)(sizeof names / sizeof names[0]) && names[s])
        return names[s];
    return "(unnamed status)";
}

/* A set-up call the test cannot go on without (status 0, CS_OK): on any
 * other status the program ends (exit 2, which tests/run.sh counts as a
 * failure) naming the call and the status. */
#define TL_MUST(call) tl_must((int)(call), #call, __FILE__, __LINE__)

static TL_UNUSED void tl_must(int status, const char *call, const char *file, int line)
{
    if (status == 0)
        return;
    printf("%s:%d: FAIL %s: status %s (%d)\n", file, line, call, tl_status_name(status), status);
    fflush(stdout);
    exit(2);
}

#define TL_RUN(fn)                                                                                \
    do {                                                                                          \
        tl_current = #fn;                                                                         \
        fn();                                                                                     \
        tl_current = "";                                                                          \
    } while (0)

/* Prints the summary line and gives main()'s exit status. */
static TL_UNUSED int tl_summary(const char *argv0)
{
    const char *name = strrchr(argv0, '/');
    name = name ? name + 1 : argv0;
    printf("%s: %d passed, %d failed\n", name, tl_passed, tl_failed);
    fflush(stdout);
    return tl_failed ? 1 : 0;
}

/* calloc that ends the program on failure: scene and workspace are MB-sized. */
static TL_UNUSED void *tl_calloc(size_t n, size_t size)
{
    void *p = calloc(n, size);
    if (!p) {
        printf("out of memory allocating %zu x %zu bytes\n", n, size);
        exit(2);
    }
    return p;
}

#endif /* CELSCAN_TESTLIB_H */
