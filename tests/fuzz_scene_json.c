/*
 * fuzz_scene_json.c - libFuzzer target for the scene JSON loader
 * (host-sim/scene_json.c and paint_json.c), which celsim, celc and the
 * Linux firmware run on files people write by hand.
 *
 * The loader's own part is what the core cannot check: JSON types, field
 * names, array lengths, colour strings, and the JSON path it puts in every
 * message. Seeds are the committed scenes (every .json in scenes/), so mutations
 * start from real documents and reach deep paths; tests/fuzz_scene_json.dict
 * holds the field names. Beyond "no crash, no sanitizer report, no hang",
 * every execution checks:
 *   - the message buffer is NUL-terminated, and a failure has a message;
 *   - a scene that loads either renders, sub-scanlines at t = 0 and exact
 *     area at t = 1.7 s on a small frame, with every line CS_OK and every
 *     value in [0, 1], or is refused by cs_frame_begin with an error the
 *     loader can describe (a JSON path and the problem);
 *   - a frame that renders comes out the same bits with the grey path
 *     refused (cs_render_opts.no_grey): whichever path the paints allow,
 *     the pixels are the three-channel ones.
 * A violated check aborts, which libFuzzer reports as a crash.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celscan_private.h"
#include "scene_json.h"

#define FUZZ_NAME "fuzz_scene_json"
#include "fuzz_check.h"

static cs_scene scene;
static cs_workspace ws;

enum { FW = 16, FH = 12 };

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char msg[SCENE_JSON_ERRLEN];
    memset(msg, 'x', sizeof msg); /* so that a missing terminator shows */
    int rc = scene_json_load_string((const char *)data, size, "fuzz.json", &scene, msg, sizeof msg);
    REQUIRE(memchr(msg, 0, sizeof msg) != NULL);
    if (rc != 0) {
        REQUIRE(msg[0] != 0);
        return 0;
    }
    static float frame[FW * FH * 3], colour[FW * FH * 3];
    cs_render_opts o = cs_render_defaults(FW, FH);
    o.subscanlines = 3;
    for (int pass = 0; pass < 2; pass++) {
        o.aa = pass ? CS_AA_EXACT : CS_AA_SUBSCAN;
        o.time = pass ? 1.7f : 0.0f;
        cs_renderer r;
        cs_error err;
        if (fuzz_render(&r, &ws, &scene, &o, frame, &err) != CS_OK) {
            char where[512];
            where[0] = 0;
            scene_json_describe_error(&err, where, sizeof where);
            REQUIRE(where[0] != 0);
            continue;
        }
        cs_render_opts three = o;
        three.no_grey = true;
        REQUIRE(fuzz_render(&r, &ws, &scene, &three, colour, &err) == CS_OK);
        REQUIRE(memcmp(frame, colour, sizeof frame) == 0);
    }
    return 0;
}
