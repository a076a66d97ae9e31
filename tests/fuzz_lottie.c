/*
 * fuzz_lottie.c - libFuzzer target for the Lottie importer (tools/lottie),
 * which `celc import` runs on animation files people bring.
 *
 * Seeds are the small files of the conformance set (see mk/lottie.mk);
 * tests/fuzz_lottie.dict holds the keys the importer reads. Beyond "no
 * crash, no sanitizer report, no hang", every execution checks:
 *   - a refused file comes with a NUL-terminated message;
 *   - an imported file's scene JSON either loads with celsim's loader or is
 *     refused by it with a message (a store capacity, say), and a scene that
 *     loads renders a small frame at two times with every line CS_OK and
 *     every value in [0, 1].
 * A violated check aborts, which libFuzzer reports as a crash.
 */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celscan_private.h"
#include "lottie/lt.h"
#include "scene_json.h"

#define FUZZ_NAME "fuzz_lottie"
#include "fuzz_check.h"

static cs_scene scene;
static cs_workspace ws;

enum { FW = 32, FH = 24 };

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    cJSON *root = cJSON_ParseWithLength((const char *)data, size);
    if (!root)
        return 0;
    lt_warnings w = {0, NULL};
    char msg[512];
    memset(msg, 'x', sizeof msg); /* so that a missing terminator shows */
    /* Small budgets keep every execution well under a second under the sanitizers. */
    lt_opts opts = {0, 2e5, 24};
    cJSON *sc = lt_import(root, &opts, &w, msg, sizeof msg);
    cJSON_Delete(root);
    lt_warnings_free(&w);
    if (!sc) {
        REQUIRE(memchr(msg, 0, sizeof msg) != NULL && msg[0] != 0);
        return 0;
    }
    char err[SCENE_JSON_ERRLEN];
    err[0] = 'x';
    if (scene_json_load_tree(sc, "fuzz", &scene, err, sizeof err) != 0) {
        REQUIRE(memchr(err, 0, sizeof err) != NULL && err[0] != 0);
    } else {
        static float frame[FW * FH * 3];
        for (int k = 0; k < 2; k++) {
            cs_render_opts o = cs_render_defaults(FW, FH);
            o.subscanlines = 3;
            o.time = k ? 0.37f : 0.0f;
            cs_renderer r;
            cs_error e;
            (void)fuzz_render(&r, &ws, &scene, &o, frame, &e);
        }
    }
    cJSON_Delete(sc);
    return 0;
}
