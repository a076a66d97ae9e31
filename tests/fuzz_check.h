/*
 * fuzz_check.h - the checks of the libFuzzer targets (tests/fuzz_*.c).
 *
 * A target defines FUZZ_NAME (its name in messages) before including this.
 * A violated check prints what failed and where, then aborts, which
 * libFuzzer reports as a crash and saves the input that caused it.
 */
#ifndef TESTS_FUZZ_CHECK_H
#define TESTS_FUZZ_CHECK_H

#include <stdio.h>
#include <stdlib.h>

#define REQUIRE(cond)                                                                             \
    do {                                                                                          \
        if (!(cond)) {                                                                            \
            fprintf(stderr, FUZZ_NAME ": check failed: %s (line %d)\n", #cond, __LINE__);       \
            abort();                                                                              \
        }                                                                                         \
    } while (0)

#endif /* TESTS_FUZZ_CHECK_H */
