/*
 * fuzz_svg.c - libFuzzer target for the SVG importer (tools/svg), which
 * `celc import` runs on artwork people bring: XML through expat, CSS,
 * path data, transforms, strokes and dashes, gradients, clips and text.
 *
 * Seeds are scenes/svg/sign.svg and a fixed sample of the icon themes the
 * SVG tests install (see mk/svg.mk); tests/fuzz_svg.dict holds the element,
 * attribute, property and keyword names the importer looks for. Beyond "no
 * crash, no sanitizer report, no hang", every execution checks:
 *   - a refused document comes with a NUL-terminated message;
 *   - an imported document that builds a scene (sv_doc_to_scene) renders
 *     on a small frame with every line CS_OK and every value in [0, 1];
 *   - for such a document the scene JSON written for it (sv_doc_to_json),
 *     the path `celc import` takes, loads with celsim's loader too;
 *   - an imported document's exact geometry fits the scene store (the
 *     importer's output cap: regions, contours, points) and its warnings
 *     stay within SV_MAX_WARNINGS + 1.
 * The fuzzer's -rss_limit_mb and -timeout hold the importer's limits on
 * nesting, <use>, dashes, stops and text to their bounds.
 * A violated check aborts, which libFuzzer reports as a crash.
 */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celscan_private.h"
#include "scene_json.h"
#include "sv.h"

#define FUZZ_NAME "fuzz_svg"
#include "fuzz_check.h"

static cs_scene scene;
static cs_workspace ws;

enum { FW = 32, FH = 24 };

/* A frame the core refuses as a whole (a capacity, say) draws nothing. */
static void render_small(const cs_scene *s)
{
    static float frame[FW * FH * 3];
    cs_render_opts o = cs_render_defaults(FW, FH);
    o.subscanlines = 3;
    o.blend = CS_BLEND_SRGB;
    cs_renderer r;
    cs_error err;
    (void)fuzz_render(&r, &ws, s, &o, frame, &err);
}

/*
 * fontconfig 2.14 loses one 288-byte block while it parses its configuration
 * (once per process, at the first font lookup of <text>); it is not the
 * importer's, so the leak check at exit leaves that library out.
 */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void)
{
    return "leak:libfontconfig.so\n";
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    sv_import_opts io;
    memset(&io, 0, sizeof io);
    io.nominal_px = 64;
    sv_doc doc;
    char msg[512];
    memset(msg, 'x', sizeof msg); /* so that a missing terminator shows */
    if (sv_import_buffer((const char *)data, size, &io, &doc, msg, sizeof msg) < 0) {
        REQUIRE(memchr(msg, 0, sizeof msg) != NULL && msg[0] != 0);
        return 0;
    }
    size_t contours = 0;
    for (int c = 0; c < doc.ncels; c++)
        for (int r = 0; r < doc.cels[c].nregions; r++)
            contours += (size_t)doc.cels[c].regions[r].ncontours;
    REQUIRE(sv_doc_region_count(&doc) <= CS_CFG_MAX_REGIONS && contours <= CS_CFG_MAX_CONTOURS &&
            sv_doc_point_count(&doc) <= CS_CFG_MAX_POINTS);
    REQUIRE(doc.nwarnings <= SV_MAX_WARNINGS + 1);
    sv_scene_opts so;
    memset(&so, 0, sizeof so);
    so.has_background = true;
    so.background[0] = so.background[1] = so.background[2] = 1.0;
    bool built = sv_doc_to_scene(&doc, &so, &scene, msg, sizeof msg) == 0;
    if (built)
        render_small(&scene);
    else
        REQUIRE(memchr(msg, 0, sizeof msg) != NULL && msg[0] != 0);
    char *json = sv_doc_to_json(&doc, NULL);
    if (json) {
        char jmsg[SCENE_JSON_ERRLEN];
        int loaded = scene_json_load_string(json, strlen(json), "import.json", &scene, jmsg,
                                            sizeof jmsg);
        if (built && loaded != 0) { /* the same document, the other back end */
            fprintf(stderr, "fuzz_svg: the imported JSON does not load: %s\n", jmsg);
            abort();
        }
        free(json);
    }
    sv_doc_free(&doc);
    return 0;
}
