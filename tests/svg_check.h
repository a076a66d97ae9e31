/*
 * svg_check.h - the small check harness of test_svg (the importer's tests).
 *
 * Each check counts once; a failing check prints where and why. main()
 * prints the final `test_svg: N passed, M failed` line that tests/run.sh sums.
 */
#ifndef SVG_CHECK_H
#define SVG_CHECK_H

#include <stdbool.h>
#include <stdio.h>

extern int svc_pass, svc_fail;

#define SVC_CHECK(cond, ...)                                                                     \
    do {                                                                                         \
        if (cond) {                                                                              \
            svc_pass++;                                                                          \
        } else {                                                                                 \
            svc_fail++;                                                                          \
            printf("FAIL %s:%d: ", __FILE__, __LINE__);                                          \
            printf(__VA_ARGS__);                                                                 \
            printf("\n");                                                                        \
        }                                                                                        \
    } while (0)

#define SVC_NEAR(a, b, tol, what)                                                                \
    SVC_CHECK(fabs((double)(a) - (double)(b)) <= (tol), "%s: %.12g vs %.12g (tol %g)", what,      \
              (double)(a), (double)(b), (double)(tol))

typedef struct svg_test_opts {
    const char *outdir; /* images of failures go here (created) */
    bool all;           /* every installed icon, not the CI subset */
    int limit;          /* CI subset size */
    bool verbose;
    bool one_cel;       /* import with one cel per shape (SVG's per-shape "over") */
} svg_test_opts;

void test_svg_unit(const svg_test_opts *o);
void test_svg_cov(const svg_test_opts *o);
void test_svg_beta(const svg_test_opts *o);
void test_svg_rsvg(const svg_test_opts *o);
void test_svg_hostile(const svg_test_opts *o);

#endif /* SVG_CHECK_H */
