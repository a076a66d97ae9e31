/*
 * svgimport_main.c - build/host/svgimport: the importer on its own, for
 * tests and debugging. `svgimport import ...` and `svgimport text ...` are
 * exactly `celc import` / `celc text`; `svgimport render` renders an SVG
 * straight through the IR's cs_scene back end with the core:
 *
 *   svgimport render icon.svg -o out.png [--size WxH] [--aa none|N|exact]
 *             [--blend srgb|linear] [--background C|none] [--one-cel-per-shape]
 */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../celc_import.h"
#include "../cli.h"
#include "../cli_num.h"
#include "celscan_private.h"
#include "sv.h"
#include "sv_import.h"
#include "sv_render.h"

static const char usage_text[] =
    "usage: svgimport import|text|render ... (see celc import/text; render:\n"
    "  svgimport render IN.svg -o OUT.png [--size WxH] [--aa none|N|exact]\n"
    "            [--blend srgb|linear] [--background C|none] [-q])\n";

/* A bad render command line: the help, exit 2. */
static int usage(void)
{
    fputs(usage_text, stderr);
    return CLI_EXIT_USAGE;
}

static int render_main(int argc, char **argv)
{
    const char *in = NULL, *out = NULL;
    int w = 128, h = 128, sub = 16;
    cs_aa_mode aa = CS_AA_SUBSCAN;
    sv_import_opts io;
    memset(&io, 0, sizeof io);
    sv_scene_opts so = {.has_background = true, .background = {1, 1, 1}};
    cs_blend blend = CS_BLEND_SRGB;
    bool quiet = false;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-o") && i + 1 < argc) {
            out = argv[++i];
        } else if (!strcmp(a, "--size") && i + 1 < argc) {
            /* the core refuses sizes it cannot render; this only reads them */
            if (!cli_size(argv[++i], 65535, 65535, &w, &h))
                return usage();
        } else if (!strcmp(a, "--aa") && i + 1 < argc) {
            if (!cli_aa(argv[++i], &aa, &sub))
                return usage();
        } else if (!strcmp(a, "--blend") && i + 1 < argc) {
            blend = strcmp(argv[++i], "linear") != 0 ? CS_BLEND_SRGB : CS_BLEND_LINEAR;
        } else if (!strcmp(a, "--background") && i + 1 < argc) {
            double al;
            const char *v = argv[++i];
            so.has_background = strcmp(v, "none") != 0;
            if (so.has_background && sv_parse_color(v, so.background, &al) != SV_COLOR_RGB)
                return usage();
        } else if (!strcmp(a, "--one-cel-per-shape")) {
            io.one_cel_per_shape = true;
        } else if (!strcmp(a, "-q")) {
            quiet = true;
        } else if (!in) {
            in = a;
        } else {
            return usage();
        }
    }
    if (!in || !out)
        return usage();
    io.nominal_px = w > h ? w : h;
    sv_doc doc;
    char err[512];
    if (sv_import_file(in, &io, &doc, err, sizeof err) < 0) {
        fprintf(stderr, "svgimport: %s\n", err);
        return 1;
    }
    if (!quiet)
        for (int i = 0; i < doc.nwarnings; i++)
            fprintf(stderr, "%s: warning: %s\n", in, doc.warnings[i]);
    cs_scene *scene = malloc(sizeof *scene);
    uint8_t *rgb = malloc((size_t)3 * w * h);
    int rc = 0;
    if (sv_doc_to_scene(&doc, &so, scene, err, sizeof err) < 0) {
        fprintf(stderr, "svgimport: %s: %s\n", in, err);
        rc = 1;
    } else {
        cs_status st = sv_render_rgb8(scene, w, h, aa, sub, blend, rgb);
        if (st != CS_OK) {
            fprintf(stderr, "svgimport: %s: render: %s\n", in, cs_status_str(st));
            rc = 1;
        } else if (sv_png_write_rgb(out, rgb, w, h) < 0) {
            fprintf(stderr, "svgimport: %s: cannot write\n", out);
            rc = 1;
        }
    }
    if (!quiet)
        fprintf(stderr, "%s: %d cels, %zu regions, %zu points\n", in, doc.ncels,
                sv_doc_region_count(&doc), sv_doc_point_count(&doc));
    free(scene);
    free(rgb);
    sv_doc_free(&doc);
    return rc;
}

int main(int argc, char **argv)
{
    static const cli_command commands[] = {
        {"import", celc_import_main}, {"text", celc_text_main}, {"render", render_main}};
    static const cli_program svgimport = {"svgimport", usage_text,
                                          "import, text or render; see svgimport --help", commands,
                                          3};
    return cli_main(&svgimport, argc, argv);
}
