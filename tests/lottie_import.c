/*
 * lottie_import.c - the Lottie importer (tools/lottie) on small made-up files.
 *
 * What a file's keys become: a rotation keyed with a Lottie easing comes
 * back as the same two keys with that easing (not a key per frame), a hold
 * as a hold, parenting as a cel group whose opacity the child does not
 * inherit, in/out points as opacity holds; the imported scene renders a
 * rectangle where the closed form puts it. Hostile files (not Lottie, NaN
 * and huge numbers, groups nested too deep, huge keyframe counts, cycles of
 * parents and of precomps, endless frame ranges, too much work) end in an
 * error naming the cause, each within a time bound; unsupported features
 * give one warning each per file.
 */
#include <math.h>
#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../host-sim/scene_json.h"
#include "../tools/lottie/lt.h"
#include "celscan_private.h"
#include "testlib.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* Imports text; returns the scene (or NULL) with err and the warnings. */
static cJSON *import(const char *text, lt_warnings *w, char *err, size_t errlen, double *secs)
{
    double t0 = now();
    cJSON *root = cJSON_Parse(text);
    cJSON *scene = NULL;
    if (!root)
        snprintf(err, errlen, "(JSON parse error)");
    else
        scene = lt_import(root, NULL, w, err, errlen);
    cJSON_Delete(root);
    if (secs)
        *secs = now() - t0;
    return scene;
}

#define HEAD "{\"v\":\"5.5.2\",\"fr\":30,\"ip\":0,\"op\":60,\"w\":100,\"h\":100,"
#define RECT_SHAPES                                                                               \
    "\"shapes\":[{\"ty\":\"gr\",\"it\":[{\"ty\":\"rc\",\"p\":{\"a\":0,\"k\":[0,0]},"              \
    "\"s\":{\"a\":0,\"k\":[40,20]},\"r\":{\"a\":0,\"k\":0}},"                                    \
    "{\"ty\":\"fl\",\"c\":{\"a\":0,\"k\":[1,0,0,1]},\"o\":{\"a\":0,\"k\":100}},"                  \
    "{\"ty\":\"tr\",\"p\":{\"a\":0,\"k\":[0,0]}}]}]"

static const cJSON *path(const cJSON *j, const char *p)
{
    char key[64];
    while (j && *p) {
        const char *dot = strchr(p, '.');
        size_t n = dot ? (size_t)(dot - p) : strlen(p);
        snprintf(key, sizeof key, "%.*s", (int)n, p);
        j = (key[0] >= '0' && key[0] <= '9') ? cJSON_GetArrayItem(j, atoi(key))
                                             : cJSON_GetObjectItemCaseSensitive(j, key);
        p += n + (dot ? 1 : 0);
    }
    return j;
}

/* The red a 100 x 100 scene paints at time t, in pixels: the coverage of a
 * pure red fill (sRGB blending: coverage is the encoded value over black);
 * -1 if it does not load. */
static double red_area(const cJSON *scene, float t)
{
    cs_scene *sc = calloc(1, sizeof *sc);
    cs_workspace *ws = calloc(1, sizeof *ws);
    uint8_t *line = calloc(3 * 100, 1);
    char lerr[SCENE_JSON_ERRLEN];
    double area = -1;
    cs_renderer r;
    cs_render_opts o = cs_render_defaults(100, 100);
    o.time = t;
    cs_error ce;
    if (CHECK(scene_json_load_tree(scene, "t", sc, lerr, sizeof lerr) == 0, "loads: %s", lerr) &&
        cs_frame_begin(&r, ws, sc, &o, &ce) == CS_OK) {
        area = 0;
        for (int y = 0; y < 100; y++) {
            cs_render_line_px(&r, y, CS_PIX_RGB888_SRGB, line);
            for (int x = 0; x < 100; x++)
                area += line[3 * x] / 255.0;
        }
    }
    free(line);
    free(ws);
    free(sc);
    return area;
}

static void test_easing_round_trip(void)
{
    const char *text = HEAD "\"layers\":[{\"ty\":4,\"ind\":1,\"ip\":0,\"op\":60,\"st\":0,"
                            "\"ks\":{\"p\":{\"a\":0,\"k\":[50,50]},\"r\":{\"a\":1,\"k\":["
                            "{\"t\":6,\"s\":[0],\"o\":{\"x\":[0.42],\"y\":[0]},\"i\":{\"x\":[0.58],\"y\":[1]}},"
                            "{\"t\":36,\"s\":[180],\"h\":1},{\"t\":48,\"s\":[90]}]}},"
        RECT_SHAPES "}]}";
    lt_warnings w = {0, NULL};
    char err[256];
    cJSON *scene = import(text, &w, err, sizeof err, NULL);
    if (!CHECK(scene != NULL, "import: %s", err))
        return;
    const cJSON *keys = path(scene, "cels.0.animate.trs.keys");
    CHECK(cJSON_GetArraySize(keys) == 4, "four keys (frames 0, 6, 36, 48: no key per frame), got %d",
          cJSON_GetArraySize(keys));
    const cJSON *k1 = cJSON_GetArrayItem(keys, 1), *k2 = cJSON_GetArrayItem(keys, 2);
    const cJSON *e = cJSON_GetArrayItem(k1, 2);
    CHECK(fabs(cJSON_GetArrayItem(k1, 0)->valuedouble - 0.2) < 1e-9 && cJSON_IsArray(e) &&
              cJSON_GetArrayItem(e, 0)->valuedouble == 0.42 &&
              cJSON_GetArrayItem(e, 2)->valuedouble == 0.58,
          "the turn is one key at 0.2 s with the file's easing (0.42 0 0.58 1)");
    CHECK(cJSON_IsString(cJSON_GetArrayItem(k2, 2)) &&
              !strcmp(cJSON_GetArrayItem(k2, 2)->valuestring, "hold"),
          "the hold keyframe is a hold key");
    CHECK(!strcmp(path(scene, "cels.0.animate.trs.ease")->valuestring, "cubic"), "cubic track");
    /* It loads, and renders the 40 x 20 rectangle at (50,50): area 800 px at t 0
     * and turned at 1 s. The scene blends in sRGB, so coverage is the encoded
     * value of red over black. */
    double area[2] = {red_area(scene, 0), red_area(scene, 1)}; /* frame 30: 180 deg turned */
    CHECK(fabs(area[0] - 800) < 1 && fabs(area[1] - 800) < 2,
          "the rectangle covers 800 px at t 0 and 1 s (%.2f, %.2f)", area[0], area[1]);
    cJSON_Delete(scene);
    lt_warnings_free(&w);
}

static void expect_refused(const char *what, const char *text, const char *msg);

/* A keyframe at the out point (frame 60 of 0..59 shown): the last stretch is
 * still one cubic key, ending at 2 s on the keyframe's value. */
static void test_tail_key(void)
{
    const char *text = HEAD "\"layers\":[{\"ty\":4,\"ind\":1,\"ip\":0,\"op\":60,\"st\":0,"
                            "\"ks\":{\"p\":{\"a\":0,\"k\":[50,50]},\"r\":{\"a\":1,\"k\":["
                            "{\"t\":20,\"s\":[0],\"o\":{\"x\":[0.33],\"y\":[0]},\"i\":{\"x\":[0.67],\"y\":[1]}},"
                            "{\"t\":60,\"s\":[90]}]}},"
        RECT_SHAPES "}]}";
    lt_warnings w = {0, NULL};
    char err[256];
    cJSON *scene = import(text, &w, err, sizeof err, NULL);
    if (!CHECK(scene != NULL, "import: %s", err))
        return;
    const cJSON *keys = path(scene, "cels.0.animate.trs.keys");
    const cJSON *last = cJSON_GetArrayItem(keys, cJSON_GetArraySize(keys) - 1);
    const cJSON *rot = path(cJSON_GetArrayItem(last, 1), "rotation");
    CHECK(cJSON_GetArraySize(keys) == 3, "three keys (frames 0, 20 and 60), got %d",
          cJSON_GetArraySize(keys));
    CHECK(fabs(cJSON_GetArrayItem(last, 0)->valuedouble - 2.0) < 1e-9 && rot &&
              fabs(rot->valuedouble - 90) < 0.05,
          "the last key is the keyframe past the end: 2 s, 90 degrees (%g)",
          rot ? rot->valuedouble : -1);
    cJSON_Delete(scene);
    lt_warnings_free(&w);
}

/* A repeater of three copies, each 20 px right of the one before, fading
 * from 100 % to 50 % over copy / copies: three regions, front to back copy
 * 2, 1, 0, each moved and faded as rlottie draws them. */
static void test_repeater(void)
{
    const char *text =
        HEAD "\"layers\":[{\"ty\":4,\"ind\":1,\"ip\":0,\"op\":60,\"st\":0,\"ks\":{},"
             "\"shapes\":[{\"ty\":\"gr\",\"it\":[{\"ty\":\"rc\",\"p\":{\"a\":0,\"k\":[10,10]},"
             "\"s\":{\"a\":0,\"k\":[10,10]},\"r\":{\"a\":0,\"k\":0}},"
             "{\"ty\":\"fl\",\"c\":{\"a\":0,\"k\":[1,0,0,1]},\"o\":{\"a\":0,\"k\":100}},"
             "{\"ty\":\"tr\"}]},"
             "{\"ty\":\"rp\",\"c\":{\"a\":0,\"k\":3},\"o\":{\"a\":0,\"k\":0},\"m\":1,"
             "\"tr\":{\"p\":{\"a\":0,\"k\":[20,0]},\"so\":{\"a\":0,\"k\":100},"
             "\"eo\":{\"a\":0,\"k\":50}}}]}]}";
    lt_warnings w = {0, NULL};
    char err[256];
    cJSON *scene = import(text, &w, err, sizeof err, NULL);
    if (!CHECK(scene != NULL, "import: %s", err))
        return;
    CHECK(w.n == 0, "no warning (%d)", w.n);
    const cJSON *regs = path(scene, "cels.0.regions");
    if (!CHECK(cJSON_GetArraySize(regs) == 3, "three regions, one per copy (got %d)",
               cJSON_GetArraySize(regs)))
        goto out;
    for (int k = 0; k < 3; k++) {
        int copy = 2 - k;
        const cJSON *reg = cJSON_GetArrayItem(regs, k);
        double beta = path(reg, "paint.beta")->valuedouble, x0 = 1e9;
        const cJSON *pt;
        cJSON_ArrayForEach(pt, path(reg, "contours.0.points"))
            x0 = fmin(x0, cJSON_GetArrayItem(pt, 0)->valuedouble);
        CHECK(fabs(beta - (1 - 0.5 * copy / 3.0)) < 1e-9 && fabs(x0 - (5 + 20 * copy)) < 1e-9,
              "copy %d: left edge %g (want %d), beta %g (want %g)", copy, x0, 5 + 20 * copy, beta,
              1 - 0.5 * copy / 3.0);
    }
out:
    cJSON_Delete(scene);
    lt_warnings_free(&w);
    expect_refused("repeater flood",
                   HEAD "\"layers\":[{\"ty\":4,\"ind\":1,\"ks\":{},\"shapes\":["
                        "{\"ty\":\"rc\",\"s\":{\"a\":0,\"k\":[1,1]}},{\"ty\":\"fl\"},"
                        "{\"ty\":\"rp\",\"c\":{\"a\":0,\"k\":1e6}}]}]}",
                   "copies, more than");
    expect_refused("nested repeaters",
                   HEAD "\"layers\":[{\"ty\":4,\"ind\":1,\"ks\":{},\"shapes\":["
                        "{\"ty\":\"rc\",\"s\":{\"a\":0,\"k\":[1,1]}},{\"ty\":\"fl\"},"
                        "{\"ty\":\"rp\",\"c\":{\"a\":0,\"k\":1000}},"
                        "{\"ty\":\"rp\",\"c\":{\"a\":0,\"k\":1000}}]}]}",
                   "shape items");
}

/* A 40 x 20 red rectangle (x 30..70) matted by a 10 x 20 white one (x 30..40)
 * in the layer listed before it, which moves by its own transform: alpha
 * shows 200 px, inverted 600 px, luma (white source) as alpha; a source at
 * 50 % shows the 200 px at half strength, and inverted it cannot be CSG and
 * is warned (drawn unmatted). */
static void test_track_matte(void)
{
    static const int tts[5] = {1, 2, 3, 1, 2}, opacity[5] = {100, 100, 100, 50, 50};
    static const int warns[5] = {0, 0, 0, 0, 1};
    static const double want[5] = {200, 600, 200, 100, 800};
    for (int k = 0; k < 5; k++) {
        char text[2048];
        snprintf(text, sizeof text,
                 HEAD "\"layers\":[{\"ty\":4,\"ind\":1,\"td\":1,\"ip\":0,\"op\":60,"
                      "\"ks\":{\"p\":{\"a\":0,\"k\":[10,0]}},\"shapes\":[{\"ty\":\"rc\","
                      "\"p\":{\"a\":0,\"k\":[25,50]},\"s\":{\"a\":0,\"k\":[10,20]},"
                      "\"r\":{\"a\":0,\"k\":0}},{\"ty\":\"fl\",\"c\":{\"a\":0,\"k\":[1,1,1,1]},"
                      "\"o\":{\"a\":0,\"k\":%d}}]},"
                      "{\"ty\":4,\"ind\":2,\"tt\":%d,\"ip\":0,\"op\":60,\"ks\":{\"p\":{\"a\":0,"
                      "\"k\":[50,50]}}," RECT_SHAPES "}]}",
                 opacity[k], tts[k]);
        lt_warnings w = {0, NULL};
        char err[256];
        cJSON *scene = import(text, &w, err, sizeof err, NULL);
        if (!CHECK(scene != NULL, "import: %s", err))
            return;
        double a = red_area(scene, 0);
        CHECK(fabs(a - want[k]) < 1 && w.n == warns[k],
              "matte type %d, source at %d %%: %.2f px shown (want %.0f), %d warnings", tts[k],
              opacity[k], a, want[k], w.n);
        cJSON_Delete(scene);
        lt_warnings_free(&w);
    }
    /* The same rectangle inside a precomp, shifted 10 px left by the precomp layer
     * and back by its own position: the matte reaches the precomp's layers. */
    const char *pre =
        HEAD "\"assets\":[{\"id\":\"a\",\"layers\":[{\"ty\":4,\"ind\":1,\"ip\":0,\"op\":60,"
             "\"ks\":{\"p\":{\"a\":0,\"k\":[60,50]}}," RECT_SHAPES "}]}],"
             "\"layers\":[{\"ty\":4,\"ind\":1,\"td\":1,\"ip\":0,\"op\":60,\"ks\":{},"
             "\"shapes\":[{\"ty\":\"rc\",\"p\":{\"a\":0,\"k\":[35,50]},"
             "\"s\":{\"a\":0,\"k\":[10,20]},\"r\":{\"a\":0,\"k\":0}},{\"ty\":\"fl\"}]},"
             "{\"ty\":0,\"ind\":2,\"tt\":1,\"refId\":\"a\",\"ip\":0,\"op\":60,"
             "\"ks\":{\"p\":{\"a\":0,\"k\":[-10,0]}}}]}";
    lt_warnings w = {0, NULL};
    char err[256];
    cJSON *scene = import(pre, &w, err, sizeof err, NULL);
    if (!CHECK(scene != NULL, "import: %s", err))
        return;
    double a = red_area(scene, 0);
    CHECK(fabs(a - 200) < 1 && w.n == 0, "alpha matte over a precomp: %.2f px (want 200), %d warnings",
          a, w.n);
    cJSON_Delete(scene);
    lt_warnings_free(&w);
}

/* Masks over the 40 x 20 rectangle (layer space x -20..20): A (x -20..0) then
 * B (x -10..10) in difference mode show A xor B, 400 px; A alone at 50 %
 * opacity shows its 400 px at half strength. */
#define MASK(mode, x0, x1, o)                                                                      \
    "{\"mode\":\"" mode "\",\"o\":{\"a\":0,\"k\":" #o "},\"pt\":{\"a\":0,\"k\":{\"c\":true,"         \
    "\"v\":[[" #x0 ",-10],[" #x1 ",-10],[" #x1 ",10],[" #x0 ",10]],"                                \
    "\"i\":[[0,0],[0,0],[0,0],[0,0]],\"o\":[[0,0],[0,0],[0,0],[0,0]]}}}"

static void test_mask_modes(void)
{
    const char *texts[2] = {
        HEAD "\"layers\":[{\"ty\":4,\"ind\":1,\"ip\":0,\"op\":60,\"ks\":{\"p\":{\"a\":0,"
             "\"k\":[50,50]}},\"masksProperties\":[" MASK("a", -20, 0, 100) ","
             MASK("f", -10, 10, 100) "]," RECT_SHAPES "}]}",
        HEAD "\"layers\":[{\"ty\":4,\"ind\":1,\"ip\":0,\"op\":60,\"ks\":{\"p\":{\"a\":0,"
             "\"k\":[50,50]}},\"masksProperties\":[" MASK("a", -20, 0, 50) "]," RECT_SHAPES "}]}"};
    const char *what[2] = {"difference mask", "mask at 50 % opacity"};
    for (int k = 0; k < 2; k++) {
        lt_warnings w = {0, NULL};
        char err[256];
        cJSON *scene = import(texts[k], &w, err, sizeof err, NULL);
        if (!CHECK(scene != NULL, "import: %s", err))
            return;
        double a = red_area(scene, 0), want = k == 0 ? 400 : 200;
        CHECK(fabs(a - want) < 1 && w.n == 0, "%s: %.2f px (want %.0f), %d warnings", what[k], a,
              want, w.n);
        cJSON_Delete(scene);
        lt_warnings_free(&w);
    }
}

static void test_parent_and_inout(void)
{
    const char *text = HEAD "\"layers\":["
        "{\"ty\":4,\"ind\":1,\"parent\":2,\"ip\":10,\"op\":40,\"st\":0,\"ks\":{}," RECT_SHAPES "},"
        "{\"ty\":3,\"ind\":2,\"ip\":0,\"op\":60,\"st\":0,\"ks\":{\"o\":{\"a\":0,\"k\":0},"
        "\"p\":{\"a\":1,\"k\":[{\"t\":0,\"s\":[0,0]},{\"t\":60,\"s\":[60,0]}]}}}]}";
    lt_warnings w = {0, NULL};
    char err[256];
    cJSON *scene = import(text, &w, err, sizeof err, NULL);
    if (!CHECK(scene != NULL, "import: %s", err))
        return;
    const cJSON *cels = path(scene, "cels");
    CHECK(cJSON_GetArraySize(cels) == 2, "a group cel for the null and a cel for the shape");
    const cJSON *child = NULL, *group = NULL;
    int gi = -1;
    for (int i = 0; i < cJSON_GetArraySize(cels); i++) {
        const cJSON *c = cJSON_GetArrayItem(cels, i);
        if (cJSON_GetArraySize(path(c, "regions")) > 0)
            child = c;
        else
            group = c, gi = i;
    }
    if (!CHECK(child && group, "one content cel, one group"))
        return;
    CHECK(path(child, "parent") && path(child, "parent")->valueint == gi, "the child is in the group");
    /* The null's opacity 0 does not reach the child: the group carries no opacity. */
    const cJSON *gk = path(group, "animate.trs.keys");
    bool faded = false;
    const cJSON *k;
    cJSON_ArrayForEach(k, gk)
    {
        faded = faded || path(cJSON_GetArrayItem(k, 1), "opacity") != NULL;
    }
    CHECK(gk && !faded, "the parent's group moves (%d keys) but does not fade",
          cJSON_GetArraySize(gk));
    /* In/out points 10..40: opacity 0, then 1 from frame 10, 0 from frame 40. */
    const cJSON *ck = path(child, "animate.trs.keys");
    int n = cJSON_GetArraySize(ck);
    const cJSON *first = cJSON_GetArrayItem(ck, 0);
    CHECK(n >= 3 && path(cJSON_GetArrayItem(first, 1), "opacity")->valuedouble == 0 &&
              !strcmp(cJSON_GetArrayItem(first, 2)->valuestring, "hold"),
          "hidden before its in point by a hold key (%d keys)", n);
    cJSON_Delete(scene);
    lt_warnings_free(&w);
}

/* A precomp layer over a composition of one layer folds into that layer's TRS track (no
 * group cel) where its scale is uniform; a non-uniform one keeps the group. Either way the
 * 40 x 20 rectangle shows at the precomp's scale, whatever the precomp's turn. */
static void test_precomp_fold(void)
{
    const char *fmt = "{\"v\":\"5.5.2\",\"fr\":30,\"ip\":0,\"op\":60,\"w\":100,\"h\":100,"
        "\"assets\":[{\"id\":\"c\",\"layers\":[{\"ty\":4,\"ind\":1,\"ip\":0,\"op\":60,\"st\":0,"
        "\"ks\":{\"p\":{\"a\":0,\"k\":[50,50]}}," RECT_SHAPES "}]}],"
        "\"layers\":[{\"ty\":0,\"refId\":\"c\",\"ind\":1,\"ip\":0,\"op\":60,\"st\":0,\"w\":100,"
        "\"h\":100,\"ks\":{\"a\":{\"a\":0,\"k\":[50,50]},\"p\":{\"a\":0,\"k\":[50,50]},"
        "\"s\":{\"a\":0,\"k\":[50,%d]},\"o\":{\"a\":0,\"k\":100},"
        "\"r\":{\"a\":1,\"k\":[{\"t\":0,\"s\":[0],\"o\":{\"x\":[0.4],\"y\":[0]},"
        "\"i\":{\"x\":[0.6],\"y\":[1]}},{\"t\":60,\"s\":[90]}]}}}]}";
    for (int uniform = 1; uniform >= 0; uniform--) {
        char text[2048], err[256];
        snprintf(text, sizeof text, fmt, uniform ? 50 : 100);
        lt_warnings w = {0, NULL};
        cJSON *scene = import(text, &w, err, sizeof err, NULL);
        if (!CHECK(scene != NULL, "import: %s", err))
            return;
        int cels = cJSON_GetArraySize(path(scene, "cels"));
        CHECK(cels == (uniform ? 1 : 2), "%s scale: %d cels", uniform ? "uniform" : "non-uniform",
              cels);
        double want = uniform ? 20 * 10 : 20 * 20;
        for (float t = 0; t < 2; t += 0.5f) {
            double a = red_area(scene, t);
            CHECK(fabs(a - want) < 1.5, "%s scale, t = %.1f: red area %.2f, want %.0f",
                  uniform ? "uniform" : "non-uniform", t, a, want);
        }
        if (uniform) {
            /* The precomp's eased turn is the cel's, on the cel's own cubic keys. */
            const cJSON *keys = path(scene, "cels.0.animate.trs.keys");
            CHECK(cJSON_GetArraySize(keys) == 2, "the turn is 2 keys (%d)",
                  cJSON_GetArraySize(keys));
        }
        cJSON_Delete(scene);
        lt_warnings_free(&w);
    }
}

/* A mask on a precomp layer (one add or subtract mask at full opacity) mattes the
 * composition's layers: the 40 x 20 rectangle (x 30..70) under a mask over x 0..40 shows
 * 10 x 20 of it, or 30 x 20 subtracted; two masks stay warned and drawn unmasked. */
static void test_precomp_mask(void)
{
    const char *fmt = "{\"v\":\"5.5.2\",\"fr\":30,\"ip\":0,\"op\":60,\"w\":100,\"h\":100,"
        "\"assets\":[{\"id\":\"c\",\"layers\":[{\"ty\":4,\"ind\":1,\"ip\":0,\"op\":60,\"st\":0,"
        "\"ks\":{\"p\":{\"a\":0,\"k\":[50,50]}}," RECT_SHAPES "}]}],"
        "\"layers\":[{\"ty\":0,\"refId\":\"c\",\"ind\":1,\"ip\":0,\"op\":60,\"st\":0,\"w\":100,"
        "\"h\":100,\"ks\":{},\"masksProperties\":[%s]}]}";
    const char *mask = "{\"mode\":\"%s\",\"inv\":false,\"o\":{\"a\":0,\"k\":100},"
        "\"pt\":{\"a\":0,\"k\":{\"c\":true,\"v\":[[0,0],[40,0],[40,100],[0,100]],"
        "\"i\":[[0,0],[0,0],[0,0],[0,0]],\"o\":[[0,0],[0,0],[0,0],[0,0]]}}}";
    struct {
        const char *modes;
        double area;
        int warnings;
    } cases[] = {{"a", 200, 0}, {"s", 600, 0}, {"aa", 800, 1}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char masks[1024] = "", one[512], text[4096], err[256];
        for (const char *m = cases[i].modes; *m; m++) {
            snprintf(one, sizeof one, mask, (char[]){*m, 0});
            snprintf(masks + strlen(masks), sizeof masks - strlen(masks), "%s%s",
                     m == cases[i].modes ? "" : ",", one);
        }
        snprintf(text, sizeof text, fmt, masks);
        lt_warnings w = {0, NULL};
        cJSON *scene = import(text, &w, err, sizeof err, NULL);
        if (!CHECK(scene != NULL, "import: %s", err))
            continue;
        double a = red_area(scene, 0.5f);
        CHECK(fabs(a - cases[i].area) < 1.5, "masks \"%s\": red area %.2f, want %.0f",
              cases[i].modes, a, cases[i].area);
        CHECK(w.n == cases[i].warnings, "masks \"%s\": %d warnings (%d)", cases[i].modes,
              cases[i].warnings, w.n);
        cJSON_Delete(scene);
        lt_warnings_free(&w);
    }
}

/* Polystars as Debian's librlottie draws them (checked against it with stars turned 30
 * degrees and 0..184, rounded, with 5.5 points, and a rounded hexagon: all above 36 dB):
 * turned by twice their rotation, starting from the top outer vertex; roundness makes the
 * sides cubics through the same vertices; an animated point count is drawn in whole points
 * with sharp corners, warned. */
static void test_polystar(void)
{
    const char *fmt = HEAD "\"layers\":[{\"ty\":4,\"ind\":1,\"ip\":0,\"op\":60,\"st\":0,"
        "\"ks\":{},\"shapes\":[{\"ty\":\"gr\",\"it\":[{\"ty\":\"sr\",\"sy\":1,\"d\":1,"
        "\"pt\":%s,\"p\":{\"a\":0,\"k\":[50,50]},\"r\":{\"a\":0,\"k\":30},"
        "\"ir\":{\"a\":0,\"k\":20},\"or\":{\"a\":0,\"k\":40},\"is\":{\"a\":0,\"k\":%d},"
        "\"os\":{\"a\":0,\"k\":%d}},{\"ty\":\"fl\",\"c\":{\"a\":0,\"k\":[1,0,0,1]},"
        "\"o\":{\"a\":0,\"k\":100}},{\"ty\":\"tr\"}]}]}]}";
    const char *five = "{\"a\":0,\"k\":5}";
    const char *grows = "{\"a\":1,\"k\":[{\"t\":0,\"s\":[5]},{\"t\":60,\"s\":[8]}]}";
    struct {
        const char *pt;
        int is, os, degree, warnings;
    } cases[] = {{five, 0, 0, 1, 0}, {five, 30, 70, 3, 0}, {grows, 30, 70, 1, 1}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char text[2048], err[256];
        snprintf(text, sizeof text, fmt, cases[i].pt, cases[i].is, cases[i].os);
        lt_warnings w = {0, NULL};
        cJSON *scene = import(text, &w, err, sizeof err, NULL);
        const cJSON *ct = path(scene, "cels.0.regions.0.contours.0");
        const cJSON *p0 = path(ct, "points.0"), *deg = path(ct, "degree");
        /* The first vertex: the outer radius at 2 x 30 degrees from the top, clockwise. */
        double want_x = 50 + 40 * cos((60 - 90) * M_PI / 180);
        double want_y = 50 + 40 * sin((60 - 90) * M_PI / 180);
        CHECK(p0 && fabs(cJSON_GetArrayItem(p0, 0)->valuedouble - want_x) < 1e-3 &&
                  fabs(cJSON_GetArrayItem(p0, 1)->valuedouble - want_y) < 1e-3,
              "case %zu: starts at (%.3f, %.3f)", i, want_x, want_y);
        CHECK(deg && deg->valueint == cases[i].degree, "case %zu: sides of degree %d (%d)", i,
              cases[i].degree, deg ? deg->valueint : -1);
        CHECK(w.n == cases[i].warnings, "case %zu: %d warnings (%d)", i, cases[i].warnings, w.n);
        cJSON_Delete(scene);
        lt_warnings_free(&w);
    }
}

/* In and out points are whole frames, rounded, as rlottie keeps them: a layer with ip 9.6
 * or 10.4 shows from frame 10 (not 9, and not only from 11), one with op 20.4 until 19. */
static void test_inout_rounded(void)
{
    const char *fmt = HEAD "\"layers\":[{\"ty\":4,\"ind\":1,\"ip\":%s,\"op\":20.4,\"st\":0,"
                           "\"ks\":{\"p\":{\"a\":0,\"k\":[50,50]}}," RECT_SHAPES "}]}";
    const char *ips[] = {"9.6", "10.4"};
    for (int i = 0; i < 2; i++) {
        char text[2048], err[256];
        snprintf(text, sizeof text, fmt, ips[i]);
        lt_warnings w = {0, NULL};
        cJSON *scene = import(text, &w, err, sizeof err, NULL);
        if (!CHECK(scene != NULL, "import: %s", err))
            continue;
        const int frames[] = {9, 10, 19, 20};
        const bool shown[] = {false, true, true, false};
        for (int k = 0; k < 4; k++) {
            double a = red_area(scene, frames[k] / 30.0f);
            CHECK(shown[k] ? fabs(a - 800) < 1.5 : a < 0.5, "ip %s: frame %d %s (red area %.1f)",
                  ips[i], frames[k], shown[k] ? "shown" : "hidden", a);
        }
        cJSON_Delete(scene);
        lt_warnings_free(&w);
    }
}

/* A solid layer whose colour is not #rrggbb ("" in starts_transparent.json) is white, as
 * rlottie draws it (checked against librlottie: an 800 x 800 "" solid renders ffffffff). */
static void test_solid_colour(void)
{
    const char *fmt = HEAD "\"layers\":[{\"ty\":1,\"ind\":1,\"ip\":0,\"op\":60,\"st\":0,"
                           "\"ks\":{},\"sw\":100,\"sh\":100,\"sc\":\"%s\"}]}";
    const char *cases[][2] = {{"", "white"}, {"#ff0000", "red"}, {"red", "white"}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char text[512], err[256];
        snprintf(text, sizeof text, fmt, cases[i][0]);
        lt_warnings w = {0, NULL};
        cJSON *scene = import(text, &w, err, sizeof err, NULL);
        const cJSON *pig = path(scene, "cels.0.regions.0.paint.pigment");
        bool white = !strcmp(cases[i][1], "white");
        CHECK(pig && cJSON_GetArraySize(pig) == 3 &&
                  cJSON_GetArrayItem(pig, 0)->valuedouble == 1 &&
                  cJSON_GetArrayItem(pig, 1)->valuedouble == (white ? 1 : 0) &&
                  cJSON_GetArrayItem(pig, 2)->valuedouble == (white ? 1 : 0),
              "solid \"%s\" is %s", cases[i][0], cases[i][1]);
        cJSON_Delete(scene);
        lt_warnings_free(&w);
    }
}

static void test_warnings_once(void)
{
    const char *text = HEAD "\"layers\":["
        "{\"ty\":5,\"ind\":1,\"ip\":0,\"op\":60,\"st\":0,\"ks\":{}},"
        "{\"ty\":5,\"ind\":2,\"ip\":0,\"op\":60,\"st\":0,\"ks\":{}},"
        "{\"ty\":2,\"ind\":3,\"ip\":0,\"op\":60,\"st\":0,\"ks\":{}},"
        "{\"ty\":4,\"ind\":4,\"ip\":0,\"op\":60,\"st\":0,\"ef\":[{}],\"ks\":{\"r\":{\"a\":0,\"k\":0,"
        "\"x\":\"time*2\"},\"p\":{\"a\":0,\"k\":[0,0],\"x\":\"wiggle(1,2)\"}}," RECT_SHAPES "}]}";
    lt_warnings w = {0, NULL};
    char err[256];
    cJSON *scene = import(text, &w, err, sizeof err, NULL);
    CHECK(scene != NULL, "import: %s", err);
    CHECK(w.n == 4, "one warning each for text, images, effects, expressions: got %d", w.n);
    for (int i = 0; i < w.n; i++)
        tl_note("  %s", w.text[i]);
    cJSON_Delete(scene);
    lt_warnings_free(&w);
}

/* A string of n copies of `unit` between `head` and `tail` (malloc'd). */
static char *repeat(const char *head, const char *unit, int n, const char *sep, const char *tail)
{
    size_t len = strlen(head) + (strlen(unit) + strlen(sep)) * (size_t)n + strlen(tail) + 1;
    char *s = malloc(len), *p = s;
    p += sprintf(p, "%s", head);
    for (int i = 0; i < n; i++)
        p += sprintf(p, "%s%s", i ? sep : "", unit);
    sprintf(p, "%s", tail);
    return s;
}

static void expect_refused(const char *what, const char *text, const char *msg)
{
    lt_warnings w = {0, NULL};
    char err[256] = "";
    double secs = 0;
    cJSON *scene = import(text, &w, err, sizeof err, &secs);
    CHECK(scene == NULL && strstr(err, msg) != NULL && secs < 5,
          "%s: refused with \"...%s...\" within 5 s (got \"%s\", %.2f s)", what, msg, err, secs);
    cJSON_Delete(scene);
    lt_warnings_free(&w);
}

static void test_hostile(void)
{
    expect_refused("not Lottie", "{\"canvas\":{}}", "not a Lottie file");
    expect_refused("op before ip",
                   "{\"v\":\"5\",\"fr\":30,\"ip\":10,\"op\":5,\"w\":10,\"h\":10,\"layers\":[]}",
                   "not after in point");
    expect_refused("endless", "{\"v\":\"5\",\"fr\":30,\"ip\":0,\"op\":1e6,\"w\":10,\"h\":10,\"layers\":[]}",
                   "frames, more than");
    expect_refused("frame rate NaN-like",
                   "{\"v\":\"5\",\"fr\":1e999,\"ip\":0,\"op\":5,\"w\":10,\"h\":10,\"layers\":[]}",
                   "\"fr\" must be a number");
    expect_refused("huge coordinate",
                   HEAD "\"layers\":[{\"ty\":4,\"ind\":1,\"ip\":0,\"op\":60,\"ks\":{\"p\":{\"a\":0,"
                        "\"k\":[1e300,0]}}," RECT_SHAPES "}]}",
                   "beyond 1e7");
    expect_refused("infinite coordinate",
                   HEAD "\"layers\":[{\"ty\":4,\"ind\":1,\"ip\":0,\"op\":60,\"ks\":{\"p\":{\"a\":0,"
                        "\"k\":[1e999,0]}}," RECT_SHAPES "}]}",
                   "not finite");
    expect_refused("parent cycle",
                   HEAD "\"layers\":[{\"ty\":3,\"ind\":1,\"parent\":2,\"ks\":{}},"
                        "{\"ty\":3,\"ind\":2,\"parent\":1,\"ks\":{}}]}",
                   "cycle of parents");
    expect_refused("precomp cycle",
                   HEAD "\"assets\":[{\"id\":\"a\",\"layers\":[{\"ty\":0,\"refId\":\"a\",\"ks\":{}}]}],"
                        "\"layers\":[{\"ty\":0,\"refId\":\"a\",\"ks\":{}}]}",
                   "precomps nested deeper");
    /* Groups nested 200 deep (cJSON itself stops at 1000). */
    char *open = repeat("", "{\"ty\":\"gr\",\"it\":[", 200, "", "");
    char *close = repeat("", "]}", 200, "", "");
    size_t len = strlen(open) + strlen(close) + 256;
    char *deep = malloc(len);
    snprintf(deep, len, HEAD "\"layers\":[{\"ty\":4,\"ind\":1,\"ks\":{},\"shapes\":[%s%s]}]}", open,
             close);
    expect_refused("deep groups", deep, "nested deeper than");
    free(open), free(close), free(deep);
    /* 200000 keyframes of one property. */
    char *many = repeat(HEAD "\"layers\":[{\"ty\":4,\"ind\":1,\"ks\":{\"r\":{\"a\":1,\"k\":[",
                        "{\"t\":1,\"s\":[0]}", 200000, ",", "]}}," RECT_SHAPES "}]}");
    expect_refused("huge keyframe count", many, "keyframes, more than");
    free(many);
    /* A 0.001 dash on a 40x20 rectangle: 120,000 dashes, beyond what the store holds. */
    expect_refused("dash flood",
                   HEAD "\"layers\":[{\"ty\":4,\"ind\":1,\"ks\":{},\"shapes\":[{\"ty\":\"rc\","
                        "\"p\":{\"a\":0,\"k\":[50,50]},\"s\":{\"a\":0,\"k\":[40,20]},"
                        "\"r\":{\"a\":0,\"k\":0}},{\"ty\":\"st\",\"c\":{\"a\":0,\"k\":[0,0,0,1]},"
                        "\"o\":{\"a\":0,\"k\":100},\"w\":{\"a\":0,\"k\":1},\"d\":["
                        "{\"n\":\"d\",\"v\":{\"a\":0,\"k\":0.001}},"
                        "{\"n\":\"g\",\"v\":{\"a\":0,\"k\":0.001}}]}]}]}",
                   "SV_MAX_DASHES");
    /* Keyframe times going back. */
    expect_refused("keys back",
                   HEAD "\"layers\":[{\"ty\":4,\"ind\":1,\"ks\":{\"r\":{\"a\":1,\"k\":["
                        "{\"t\":5,\"s\":[0]},{\"t\":2,\"s\":[9]}]}}," RECT_SHAPES "}]}",
                   "keyframe times go back");
    /* Too much work: 20000 frames of 40 layers, each a 2000-vertex path. */
    char *verts = repeat("", "[1,2]", 2000, ",", "");
    size_t vl = strlen(verts) * 3 + 512;
    char *shape = malloc(vl);
    snprintf(shape, vl,
             "{\"ty\":4,\"ks\":{},\"shapes\":[{\"ty\":\"sh\",\"ks\":{\"a\":0,\"k\":{\"c\":true,"
             "\"v\":[%s],\"i\":[%s],\"o\":[%s]}}},{\"ty\":\"fl\"}]}",
             verts, verts, verts);
    char *heavy = repeat("{\"v\":\"5\",\"fr\":30,\"ip\":0,\"op\":20000,\"w\":10,\"h\":10,\"layers\":[",
                         shape, 40, ",", "]}");
    expect_refused("work budget", heavy, "sampled values");
    free(verts), free(shape), free(heavy);
}

int main(int argc, char **argv)
{
    (void)argc;
    TL_RUN(test_easing_round_trip);
    TL_RUN(test_tail_key);
    TL_RUN(test_repeater);
    TL_RUN(test_track_matte);
    TL_RUN(test_mask_modes);
    TL_RUN(test_parent_and_inout);
    TL_RUN(test_solid_colour);
    TL_RUN(test_inout_rounded);
    TL_RUN(test_precomp_fold);
    TL_RUN(test_polystar);
    TL_RUN(test_precomp_mask);
    TL_RUN(test_warnings_once);
    TL_RUN(test_hostile);
    return tl_summary(argv[0]);
}
