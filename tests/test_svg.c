/*
 * test_svg.c - the importer's test program: unit checks of the SVG
 * grammars, transforms, colours, stroke outliner and glyph conversion;
 * coverage of stroked paths and text against an independent long-double
 * reference at 16, 128 and 512 px; gradients as paint functions, clip paths
 * as CSG and the scene JSON's round trip through celsim's loader; and the
 * comparison with librsvg's rsvg-convert on installed icon artwork (one
 * check: the pass rate); and files made to exhaust the importer, each of
 * which must end in an error naming its limit within 5 s and 512 MB.
 *
 *   test_svg [--only unit|cov|beta|rsvg|hostile] [--all] [--limit N] [--outdir DIR] [--one-cel] [-v]
 */
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define TL_MAIN
#include "svg_test.h"

int main(int argc, char **argv)
{
    svg_test_opts o = {"build/svg-test", false, 200, false, false};
    const char *only = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--only") && i + 1 < argc)
            only = argv[++i];
        else if (!strcmp(argv[i], "--outdir") && i + 1 < argc)
            o.outdir = argv[++i];
        else if (!strcmp(argv[i], "--limit") && i + 1 < argc)
            o.limit = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--all"))
            o.all = true;
        else if (!strcmp(argv[i], "-v"))
            o.verbose = true;
        else if (!strcmp(argv[i], "--one-cel"))
            o.one_cel = true;
        else {
            fprintf(stderr, "usage: test_svg [--only unit|cov|beta|rsvg|hostile] [--all] [--limit N] "
                            "[--outdir DIR] [-v]\n");
            return 2;
        }
    }
    mkdir(o.outdir, 0777);
    if (!only || !strcmp(only, "unit"))
        test_svg_unit(&o);
    if (!only || !strcmp(only, "cov"))
        test_svg_cov(&o);
    if (!only || !strcmp(only, "beta"))
        test_svg_beta(&o);
    if (!only || !strcmp(only, "rsvg"))
        test_svg_rsvg(&o);
    if (!only || !strcmp(only, "hostile"))
        test_svg_hostile(&o);
    return tl_summary("test_svg");
}
