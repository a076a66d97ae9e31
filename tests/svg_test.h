/*
 * svg_test.h - what the files of test_svg (the importer's tests) share: the
 * options of the run and the entry point of each part. The parts check on
 * tests/testlib.h and count into main()'s counters (TL_SHARED), so the
 * program ends with one `test_svg: N passed, M failed` line.
 */
#ifndef SVG_TEST_H
#define SVG_TEST_H

#include <stdbool.h>

#include "celscan_private.h" /* the tests place and read scene stores */
#define TL_SHARED
#include "testlib.h"

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

#endif /* SVG_TEST_H */
