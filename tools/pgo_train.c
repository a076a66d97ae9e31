/*
 * pgo_train.c - the training run of the x86-64-v3 build of the core
 * (mk/variant.mk): renders each scene given, at 1920x1080, in exact area
 * and with 5 and 16 sub-scanlines, into 8-bit sRGB and RGB565 lines, with
 * the core's objects built by -fprofile-generate. GCC then builds the core
 * again from the counts (-fprofile-use): the same arithmetic, so the same
 * bytes, laid out and inlined for the branches that are taken. The scenes
 * are chosen by the Makefile, not here; nothing is checked or printed but
 * a failure to load or render, which stops the build.
 *
 *   pgo_train SCENE.json...
 */
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "celscan_private.h"
#include "scene_json.h"

enum { TRAIN_W = 1920, TRAIN_H = 1080 };

static int train(cs_scene *scene, cs_workspace *ws, cs_aa_mode aa, int subscanlines,
                 uint8_t *line)
{
    cs_render_opts o = cs_render_defaults(TRAIN_W, TRAIN_H);
    o.aa = aa;
    o.subscanlines = subscanlines;
    cs_renderer r;
    cs_error e;
    if (cs_frame_begin(&r, ws, scene, &o, &e) != CS_OK)
        return -1;
    for (int y = 0; y < TRAIN_H; y++) {
        if (cs_render_line_runs(&r, y) != CS_OK)
            return -1;
        cs_line_pixels(&r, y & 1 ? CS_PIX_RGB565_SRGB : CS_PIX_RGB888_SRGB, line);
    }
    return 0;
}

int main(int argc, char **argv)
{
    /* The objects trained are the x86-64-v3 build: on an x86-64 CPU without
     * it they would stop at their first AVX2 instruction and the build with
     * them. Nothing runs, no count is written, and the build proper is
     * compiled as without a profile (-Wno-missing-profile), as V3_PGO=0
     * builds it; the host programs will choose the baseline build there. */
    __builtin_cpu_init();
    if (!__builtin_cpu_supports("x86-64-v3")) {
        fprintf(stderr, "pgo_train: this CPU has no x86-64-v3: the v3 build goes without a profile\n");
        _exit(0); /* not exit: that would write the (empty) counts */
    }
    cs_scene *scene = calloc(1, sizeof *scene);
    cs_workspace *ws = calloc(1, sizeof *ws);
    uint8_t *line = calloc(TRAIN_W, 3);
    if (!scene || !ws || !line) {
        fprintf(stderr, "pgo_train: out of memory\n");
        return 1;
    }
    for (int i = 1; i < argc; i++) {
        char err[SCENE_JSON_ERRLEN];
        if (scene_json_load(argv[i], scene, err, sizeof err) != 0) {
            fprintf(stderr, "pgo_train: %s\n", err);
            return 1;
        }
        if (train(scene, ws, CS_AA_EXACT, 0, line) || train(scene, ws, CS_AA_SUBSCAN, 5, line) ||
            train(scene, ws, CS_AA_SUBSCAN, 16, line)) {
            fprintf(stderr, "pgo_train: %s did not render\n", argv[i]);
            return 1;
        }
    }
    free(line);
    free(ws);
    free(scene);
    return 0;
}
