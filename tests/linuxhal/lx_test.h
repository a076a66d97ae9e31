/*
 * lx_test.h - a tiny check harness for the Linux-board tests.
 *
 * Each test binary ends with one line "<name>: N passed, M failed", the
 * contract tests/run.sh sums over. CHECK records a failure with its location
 * and carries on, so one run shows every broken expectation. (The shared
 * tests/testlib.h is being written at the same time; these tests can move to
 * it when it lands.)
 */
#ifndef LX_TEST_H
#define LX_TEST_H

#include <stdio.h>

static int lx_test_passed, lx_test_failed;

#define CHECK(cond, ...)                                                                 \
    do {                                                                                 \
        if (cond) {                                                                      \
            lx_test_passed++;                                                            \
        } else {                                                                         \
            lx_test_failed++;                                                            \
            fprintf(stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);              \
            fprintf(stderr, __VA_ARGS__);                                                \
            fputc('\n', stderr);                                                         \
        }                                                                                \
    } while (0)

static inline int lx_test_report(const char *name)
{
    printf("%s: %d passed, %d failed\n", name, lx_test_passed, lx_test_failed);
    fflush(stdout);
    return lx_test_failed ? 1 : 0;
}

#endif /* LX_TEST_H */
