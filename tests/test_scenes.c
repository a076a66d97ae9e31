/*
 * test_scenes.c - scene JSON, its "animate" tracks, and the same scene as a
 * compiled cel stream.
 *
 *   test_scenes DIR     DIR holds the scenes to check (scenes/)
 *
 * What is checked, and against what:
 *   - every .json file of DIR, loaded by the JSON loader and encoded as `celc
 *     compile` encodes it, decodes (byte by byte and whole) to the same
 *     store, every used field bit for bit (tests/scene_equal.h), and renders
 *     the same panel bytes and the same linear floats at nine instants and
 *     two sizes; an animated scene's frames differ between instants;
 *   - "animate" becomes exactly the tracks and key values the JSON states:
 *     colours through the sRGB formula computed here, missing members of
 *     lights and paint keys holding the static values;
 *   - a keyframed translation written in JSON puts the rendered centroid of
 *     a disc where the closed form says, within 0.01 px, at any time, from
 *     the JSON and from its stream;
 *   - malformed "animate" input is refused with the JSON path of the culprit
 *     and a message that says what was wrong.
 * The last line is `test_scenes: N passed, M failed`.
 */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cels_read.h"
#include "cels_write.h"
#include "celscan.h"
#include "scene_equal.h"
#include "scene_json.h"
#include "testlib.h"

static cs_scene *sa, *sb, *sc; /* loaded, decoder store a, decoder store b */
static const double PI = 3.14159265358979323846;
static cs_workspace *ws;

static double srgb_lin(double e)
{
    return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4);
}

/* ------------------------------------------------------------ rendering */

/* One frame as linear floats (w*h*3) and panel bytes (RGB565, w*h*2). */
static cs_status render(const cs_scene *s, int w, int h, float t, int sub, float *lin,
                        uint8_t *panel)
{
    cs_renderer r;
    cs_render_opts o = cs_render_defaults(w, h);
    o.subscanlines = sub;
    o.time = t;
    cs_error e;
    cs_status st = cs_frame_begin(&r, ws, s, &o, &e);
    if (st != CS_OK)
        return st;
    for (int y = 0; y < h; y++) {
        float *line = lin + (size_t)y * (size_t)w * 3;
        if ((st = cs_render_line(&r, y, line)) != CS_OK)
            return st;
        if (panel)
            cs_pixfmt_convert(CS_PANEL_PIXFMT, line, w, panel + (size_t)y * (size_t)w * 2);
    }
    return r.sticky.status;
}

/* --------------------------------------------------------------- streams */

/* The stream `celc compile` writes for `s`. */
static void compile(const cs_scene *s, cels_buf *b)
{
    cels_buf_init(b);
    cels_stream_header(b);
    if (cels_encode_scene(b, s) != 0) {
        printf("encode: out of memory\n");
        exit(2);
    }
}

/* Decodes byte by byte with the core's decoder; the committed scene or NULL. */
static const cs_scene *decode_bytewise(const cels_buf *b, int *commits, int *errors)
{
    cs_stream st;
    cs_stream_init(&st, sb, false, sc);
    *commits = *errors = 0;
    for (size_t i = 0; i < b->len; i++) {
        size_t off = 0;
        while (off < 1) {
            size_t used;
            cs_stream_event ev = cs_stream_feed(&st, b->data + i + off, 1 - off, &used);
            off += used;
            if (ev == CS_STREAM_COMMIT) {
                cs_stream_swap(&st);
                ++*commits;
            } else if (ev == CS_STREAM_ERROR) {
                ++*errors;
            }
        }
    }
    while (cs_stream_finish(&st) != CS_STREAM_MORE)
        ++*errors;
    return cs_stream_scene(&st);
}

/* ---------------------------------------------------------- every scene */

static const float instants[] = {-1.0f, 0.0f, 0.25f, 0.5f, 1.0f, 1.37f, 2.0f, 3.75f, 60.0f};
#define NINSTANTS (sizeof instants / sizeof instants[0])

static void check_scene_file(const char *path)
{
    char err[SCENE_JSON_ERRLEN];
    int rc = scene_json_load(path, sa, err, sizeof err);
    CHECK(rc == 0, "%s loads: %s", path, err);
    if (rc != 0)
        return;
    cels_buf b;
    compile(sa, &b);
    int commits, errors;
    const cs_scene *d = decode_bytewise(&b, &commits, &errors);
    char why[160] = "";
    CHECK(d && commits == 1 && errors == 0, "%s: stream of %zu bytes decodes byte by byte: %d "
          "commits, %d errors", path, b.len, commits, errors);
    CHECK(d && scene_equal(sa, d, why, sizeof why), "%s: store from the stream differs: %s", path,
          why);
    cels_read_stats stats;
    const cs_scene *d2 = cels_decode_buffer(b.data, b.len, path, sb, sc, stdout, &stats);
    CHECK(d2 && stats.commits == 1 && stats.errors == 0 && scene_equal(sa, d2, why, sizeof why),
          "%s: whole-buffer decode: %u commits %u errors %s", path, stats.commits, stats.errors,
          why);
    if (!d2)
        d2 = sa;
    /* Frames: the canvas size and a small panel; 16 and 5 sub-scanlines. */
    int sizes[2][3] = {{(int)(sa->canvas_w + 0.5f), (int)(sa->canvas_h + 0.5f), 16}, {96, 60, 5}};
    int differ = 0, frames = 0, moving = 0;
    uint32_t last_crc = 0;
    for (int k = 0; k < 2; k++) {
        int w = sizes[k][0], h = sizes[k][1];
        if (w < 1 || h < 1 || w > CS_CFG_MAX_WIDTH || h > 2048)
            continue;
        float *la = malloc((size_t)w * (size_t)h * 3 * sizeof(float));
        float *lb = malloc((size_t)w * (size_t)h * 3 * sizeof(float));
        uint8_t *pa = malloc((size_t)w * (size_t)h * 2), *pb = malloc((size_t)w * (size_t)h * 2);
        for (size_t i = 0; i < NINSTANTS; i++) {
            cs_status s1 = render(sa, w, h, instants[i], sizes[k][2], la, pa);
            cs_status s2 = render(d2, w, h, instants[i], sizes[k][2], lb, pb);
            frames++;
            uint32_t crc = cs_crc32(0, pa, (size_t)w * (size_t)h * 2);
            if (i > 0 && crc != last_crc)
                moving++;
            last_crc = crc;
            if (s1 != CS_OK || s2 != CS_OK ||
                memcmp(la, lb, (size_t)w * (size_t)h * 3 * sizeof(float)) != 0 ||
                memcmp(pa, pb, (size_t)w * (size_t)h * 2) != 0) {
                if (differ++ == 0)
                    CHECK(0, "%s: %dx%d at t=%g: JSON and stream frames differ (status %d/%d)",
                          path, w, h, (double)instants[i], (int)s1, (int)s2);
            }
        }
        free(la);
        free(lb);
        free(pa);
        free(pb);
    }
    CHECK(differ == 0 && frames > 0, "%s: %d of %d frames identical from JSON and stream", path,
          frames - differ, frames);
    if (sa->track_count > 0)
        CHECK(moving > 0, "%s: animated (%u tracks) but every instant renders the same", path,
              sa->track_count);
    tl_note("%s: %zu bytes of stream, %u cels, %u functions, %u tracks; %d frames identical",
            path, b.len, sa->cel_count, sa->func_count, sa->track_count, frames - differ);
    cels_buf_free(&b);
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static void test_scene_dir(const char *dir)
{
    DIR *d = opendir(dir);
    CHECK(d != NULL, "scene directory %s opens", dir);
    if (!d)
        return;
    char *names[256];
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL && n < 256) {
        size_t len = strlen(e->d_name);
        if (len > 5 && strcmp(e->d_name + len - 5, ".json") == 0) {
            size_t plen = strlen(dir) + len + 2;
            names[n] = malloc(plen);
            snprintf(names[n], plen, "%s/%s", dir, e->d_name);
            n++;
        }
    }
    closedir(d);
    qsort(names, (size_t)n, sizeof names[0], cmp_str);
    CHECK(n >= 2, "%s holds scenes (%d)", dir, n);
    for (int i = 0; i < n; i++) {
        check_scene_file(names[i]);
        free(names[i]);
    }
}

/* ---------------------------------------------------------------- animate */

/* A one-cel scene with `cel_extra` inside the cel object, `region_extra`
 * inside its region, `contour_extra` inside its contour and `top_extra` at
 * the top level. Returns the loader's status; err holds its message. */
static int load_with(const char *top_extra, const char *cel_extra, const char *region_extra,
                     const char *contour_extra, char *err, size_t errlen)
{
    char json[8192];
    snprintf(json, sizeof json,
             "{\"canvas\": {\"width\": 100, \"height\": 80, \"background\": \"#102030\"},"
             " \"lights\": {\"front\": [0.9, 0.8, 0.7], \"back\": [0.1, 0.2, 0.3]}%s"
             " \"cels\": [{\"transform\": [1,0,0,1,10,20], \"lights\": {\"back\": [0.5, 0.4, 0.3]}%s"
             "  \"regions\": [{\"paint\": {\"pigment\": \"#804020\", \"medium\": [0.5, 0.6, 0.7],"
             "     \"beta\": 0.75}%s"
             "    \"contours\": [{\"degree\": 1, \"points\": [[0,0],[30,0],[30,20,2],[0,20]]%s}]}]}]}",
             top_extra, cel_extra, region_extra, contour_extra);
    return scene_json_load_string(json, strlen(json), "t.json", sa, err, errlen);
}

static const float *track_values(const cs_scene *s, cs_track_kind kind, uint32_t target,
                                 uint32_t *keys, uint8_t *ease)
{
    for (uint32_t i = 0; i < s->track_count; i++) {
        const cs_track *t = &s->tracks[i];
        if (t->kind == kind && t->target == target) {
            *keys = t->key_count;
            *ease = t->ease;
            return &s->key_values[t->first_value];
        }
    }
    *keys = 0;
    return NULL;
}

static const float *track_times(const cs_scene *s, cs_track_kind kind, uint32_t target)
{
    for (uint32_t i = 0; i < s->track_count; i++)
        if (s->tracks[i].kind == kind && s->tracks[i].target == target)
            return &s->key_times[s->tracks[i].first_key];
    return NULL;
}

static bool near(float a, double b)
{
    return fabs((double)a - b) <= 1e-6 * (1 + fabs(b));
}

static void test_animate_values(void)
{
    char err[SCENE_JSON_ERRLEN] = "";
    int rc = load_with(
        ", \"animate\": {\"lights\": {\"keys\": [[0, {\"front\": [1, 1, 1]}], [2, {\"back\": [0, 0, 0.5]}]],"
        " \"ease\": \"smooth\"}, \"background\": {\"keys\": [[1, \"#ff8000\"], [3, [0, 0.5, 1]]]}},",
        ", \"animate\": {\"transform\": {\"keys\": [[0, [1,0,0,1,10,20]], [1.5, [0,1,-1,0,50,40]]]},"
        " \"lights\": {\"keys\": [[0, {\"front\": [2, 2, 2]}], [1, {\"back\": [0, 1, 0]}]]}},",
        ", \"animate\": {\"paint\": {\"keys\": [[0.5, {\"pigment\": \"#ffffff\"}],"
        " [1.5, {\"beta\": 0.25, \"medium\": \"#000\"}]], \"ease\": \"linear\"}},",
        ", \"animate\": {\"points\": {\"keys\": [[0, [[0,0],[30,0],[30,20,2],[0,20]]],"
        " [2, [[5,5,1],[40,0],[40,30],[0,25,0.5]]]], \"ease\": \"smooth\"}}",
        err, sizeof err);
    CHECK(rc == 0, "scene with every kind of track loads: %s", err);
    if (rc != 0)
        return;
    CHECK_EQ_INT(sa->track_count, 6, "tracks");
    uint32_t n;
    uint8_t ease;
    const float *v = track_values(sa, CS_TRACK_TRANSFORM, 0, &n, &ease);
    const float *t = track_times(sa, CS_TRACK_TRANSFORM, 0);
    CHECK(v && n == 2 && ease == CS_EASE_LINEAR && t[0] == 0.0f && t[1] == 1.5f &&
              v[6] == 0 && v[7] == 1 && v[8] == -1 && v[9] == 0 && v[10] == 50 && v[11] == 40,
          "transform track: %u keys, default ease linear, values as written", n);
    /* Cel lights: the cel has no front light of its own (stack front holds),
     * back [0.5,0.4,0.3]; each key fills what it leaves out. */
    v = track_values(sa, CS_TRACK_CEL_LIGHTS, 0, &n, &ease);
    CHECK(v && n == 2 && v[0] == 2 && v[3] == 0.5f && v[4] == 0.4f && v[5] == 0.3f &&
              near(v[6], 0.9) && near(v[7], 0.8) && near(v[8], 0.7) && v[9] == 0 && v[10] == 1 &&
              v[11] == 0,
          "cel lights track: missing front holds the stack's, missing back the cel's");
    /* Paint: pigment #ffffff then the static #804020; medium static then #000. */
    v = track_values(sa, CS_TRACK_PAINT, 0, &n, &ease);
    CHECK(v && n == 2 && v[0] == 1.0f && near(v[3], srgb_lin(0.5)) &&
              near(v[6], 0.75) && near(v[7], srgb_lin(0x80 / 255.0)) &&
              near(v[8], srgb_lin(0x40 / 255.0)) && near(v[9], srgb_lin(0x20 / 255.0)) &&
              v[10] == 0 && v[11] == 0 && v[12] == 0 && v[13] == 0.25f,
          "paint track: sRGB colours in linear light, missing fields hold the static paint");
    v = track_values(sa, CS_TRACK_POINTS, 0, &n, &ease);
    CHECK(v && n == 2 && ease == CS_EASE_SMOOTH && v[8] == 2 && v[12] == 5 && v[13] == 5 &&
              v[14] == 1 && v[17] == 1 && v[23] == 0.5f,
          "points track: [x,y] gets w = 1, [x,y,w] keeps w");
    v = track_values(sa, CS_TRACK_STACK_LIGHTS, 0, &n, &ease);
    CHECK(v && n == 2 && ease == CS_EASE_SMOOTH && v[0] == 1 && near(v[3], 0.1) &&
              near(v[6], 0.9) && v[11] == 0.5f,
          "stack lights track: missing members hold the stack's static lights");
    v = track_values(sa, CS_TRACK_BACKGROUND, 0, &n, &ease);
    CHECK(v && n == 2 && v[0] == 1.0f && near(v[1], srgb_lin(128 / 255.0)) && v[2] == 0 &&
              v[3] == 0 && near(v[4], srgb_lin(0.5)) && v[5] == 1,
          "background track: colours in linear light");
    /* And through a stream, the same tracks. */
    cels_buf b;
    compile(sa, &b);
    cels_read_stats stats;
    const cs_scene *d = cels_decode_buffer(b.data, b.len, "t", sb, sc, stdout, &stats);
    char why[160] = "";
    CHECK(d && scene_equal(sa, d, why, sizeof why), "animated scene through a stream: %s", why);
    cels_buf_free(&b);

    /* A region whose pigment is a function: a paint track may animate its
     * other fields, not the pigment. */
    rc = load_with(",", ",", ", \"animate\": {\"paint\": {\"keys\": [[0, {\"beta\": 1}], [1, {\"beta\": 0.5,"
                   " \"medium\": [1, 1, 1]}]]}}, \"dummy\": 0,", "", err, sizeof err);
    CHECK(rc == 0, "paint track on a constant region: %s", err);
    const char *grad = "{\"canvas\": {\"width\": 10, \"height\": 10}, \"cels\": [{\"regions\": [{"
                       "\"paint\": {\"pigment\": {\"linear\": [0,0,10,0], \"stops\": [[0, \"#000\"], [1, \"#fff\"]]}},"
                       "\"animate\": {\"paint\": {\"keys\": [[0, {\"beta\": 1}], [1, {\"beta\": 0.2}]]}},"
                       "\"contours\": [{\"degree\": 1, \"points\": [[0,0],[10,0],[10,10],[0,10]]}]}]}]}";
    rc = scene_json_load_string(grad, strlen(grad), "g.json", sa, err, sizeof err);
    CHECK(rc == 0 && sa->func_count == 1 && sa->track_count == 1,
          "paint track animating beta under a gradient pigment: %s", err);
}

/* A contour's degree must be a whole number 1..3; one far beyond int's range
 * (found by fuzz_scene_json) is refused like any other, not converted. */
static void test_degree_errors(void)
{
    static const char *const bad[] = {"9999999999999999992", "1e300", "-1e300", "2.5", "-1", "4"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char json[512], err[SCENE_JSON_ERRLEN] = "";
        snprintf(json, sizeof json,
                 "{\"canvas\": {\"width\": 10, \"height\": 10}, \"cels\": [{\"regions\": [{"
                 "\"paint\": {\"pigment\": \"#fff\"}, \"contours\": [{\"degree\": %s, "
                 "\"points\": [[0,0],[10,0],[10,10],[0,10]]}]}]}]}",
                 bad[i]);
        int rc = scene_json_load_string(json, strlen(json), "d.json", sa, err, sizeof err);
        CHECK(rc != 0 && strstr(err, "d.json: cels[0].regions[0].contours[0].degree: ") == err,
              "degree %s: refused with its path, got \"%s\"", bad[i], err);
    }
}

/* Loads and expects failure with `path` and `what` in the message. */
static void expect_fail(const char *name, const char *top, const char *cel, const char *region,
                        const char *contour, const char *path, const char *what)
{
    char err[SCENE_JSON_ERRLEN] = "";
    int rc = load_with(top, cel, region, contour, err, sizeof err);
    char want[300];
    snprintf(want, sizeof want, "t.json: %s: ", path);
    CHECK(rc != 0 && strstr(err, want) == err && strstr(err, what) != NULL,
          "%s: expected \"%s...%s\", got \"%s\"", name, want, what, err);
}

#define T(keys) ", \"animate\": {\"transform\": " keys "},"

static void test_animate_errors(void)
{
    expect_fail("animate not an object", ",", ", \"animate\": [1],", ",", "", "cels[0].animate",
                "expected an object of tracks, got an array");
    expect_fail("unknown cel track", ",", ", \"animate\": {\"translate\": {}},", ",", "",
                "cels[0].animate.translate",
                "unknown track: a cel animates \"transform\", \"lights\" and \"trs\"");
    expect_fail("unknown region track", ",", ",", ", \"animate\": {\"pigment\": {}},", "",
                "cels[0].regions[0].animate.pigment",
                "unknown track: a region animates \"paint\"");
    expect_fail("unknown scene track", ", \"animate\": {\"canvas\": 1},", ",", ",", "",
                "animate.canvas", "the scene animates \"lights\" and \"background\"");
    expect_fail("track not an object", ",", T("[]"), ",", "", "cels[0].animate.transform",
                "expected a track");
    expect_fail("no keys", ",", T("{\"ease\": \"linear\"}"), ",", "",
                "cels[0].animate.transform.keys", "missing (required array of keys");
    expect_fail("empty keys", ",", T("{\"keys\": []}"), ",", "", "cels[0].animate.transform.keys",
                "expected a non-empty array of keys");
    expect_fail("bad ease", ",", T("{\"keys\": [[0, [1,0,0,1,0,0]]], \"ease\": \"bounce\"}"), ",",
                "", "cels[0].animate.transform.ease",
                "ease must be \"linear\", \"smooth\", \"hold\" or \"cubic\", got \"bounce\"");
    expect_fail("easing on a linear track", ",",
                T("{\"keys\": [[0, [1,0,0,1,0,0], [0,0,1,1]]]}"), ",", "",
                "cels[0].animate.transform.keys[0]", "expected a key [t, value], got an array");
    expect_fail("easing not four numbers", ",",
                T("{\"ease\": \"cubic\", \"keys\": [[0, [1,0,0,1,0,0], [0,0,1]]]}"), ",", "",
                "cels[0].animate.transform.keys[0][2]", "an easing [x1,y1,x2,y2]");
    expect_fail("easing x out of 0..1", ",",
                T("{\"ease\": \"cubic\", \"keys\": [[0, [1,0,0,1,0,0], [1.5,0,1,1]]]}"), ",",
                "", "cels[0].animate.transform.keys[0][1]", "coordinate");
    expect_fail("TRS member unknown", ",",
                ", \"animate\": {\"trs\": {\"keys\": [[0, {\"rotate\": 5}]]}},", ",", "",
                "cels[0].animate.trs.keys[0][1].rotate", "unknown TRS member");
    expect_fail("TRS opacity above 1", ",",
                ", \"animate\": {\"trs\": {\"keys\": [[0, {\"opacity\": 2}]]}},", ",", "",
                "cels[0].animate.trs.keys[0][1]", "must lie in 0..1");
    expect_fail("parent is itself", ",", ", \"parent\": 0,", ",", "", "cels[0].parent",
                "cel parent would make a cycle");
    expect_fail("parent missing", ",", ", \"parent\": 3,", ",", "", "cels[0].parent",
                "expected the index of another cel");
    expect_fail("key not a pair", ",", T("{\"keys\": [[0, [1,0,0,1,0,0]], [1]]}"), ",", "",
                "cels[0].animate.transform.keys[1]", "expected a key [t, value]");
    expect_fail("time not a number", ",", T("{\"keys\": [[\"0s\", [1,0,0,1,0,0]]]}"), ",", "",
                "cels[0].animate.transform.keys[0][0]", "expected a number, got a string");
    expect_fail("time overflows", ",", T("{\"keys\": [[1e999, [1,0,0,1,0,0]]]}"), ",", "",
                "cels[0].animate.transform.keys[0][0]", "out of range");
    expect_fail("times equal", ",", T("{\"keys\": [[1, [1,0,0,1,0,0]], [1, [1,0,0,1,5,0]]]}"),
                ",", "", "cels[0].animate.transform.keys[1][0]",
                "key times must increase strictly (1 after 1)");
    expect_fail("times decrease", ",",
                T("{\"keys\": [[0, [1,0,0,1,0,0]], [2, [1,0,0,1,5,0]], [1.5, [1,0,0,1,0,0]]]}"),
                ",", "", "cels[0].animate.transform.keys[2][0]",
                "key times must increase strictly (1.5 after 2)");
    expect_fail("transform of five", ",", T("{\"keys\": [[0, [1,0,0,1,0]]]}"), ",", "",
                "cels[0].animate.transform.keys[0][1]", "expected a transform [a,b,c,d,e,f]");
    expect_fail("transform entry a string", ",", T("{\"keys\": [[0, [1,0,0,1,\"x\",0]]]}"), ",",
                "", "cels[0].animate.transform.keys[0][1][4]", "expected a number");
    expect_fail("transform out of range", ",", T("{\"keys\": [[0, [1,0,0,1,2e7,0]]]}"), ",", "",
                "cels[0].animate.transform.keys[0][1]", "coordinate magnitude");
    expect_fail("negative light", ",",
                ", \"animate\": {\"lights\": {\"keys\": [[0, {\"front\": [1, -0.5, 1]}]]}},", ",",
                "", "cels[0].animate.lights.keys[0][1].front[1]", "light level must be >= 0");
    expect_fail("lights not an object", ",", ", \"animate\": {\"lights\": {\"keys\": [[0, [1,1,1]]]}},",
                ",", "", "cels[0].animate.lights.keys[0][1]", "expected an object");
    expect_fail("paint colour", ",", ",",
                ", \"animate\": {\"paint\": {\"keys\": [[0, {\"pigment\": \"red\"}]]}},", "",
                "cels[0].regions[0].animate.paint.keys[0][1].pigment", "expected a colour");
    expect_fail("paint beta out of range", ",", ",",
                ", \"animate\": {\"paint\": {\"keys\": [[0, {\"beta\": 1.5}]]}},", "",
                "cels[0].regions[0].animate.paint.keys[0][1]", "paint components must lie in 0..1");
    expect_fail("points count", ",", ",", ",",
                ", \"animate\": {\"points\": {\"keys\": [[0, [[0,0],[1,0],[1,1]]]]}}",
                "cels[0].regions[0].contours[0].animate.points.keys[0][1]",
                "expected 4 points (the contour's point count), got 3");
    expect_fail("point shape", ",", ",", ",",
                ", \"animate\": {\"points\": {\"keys\": [[0, [[0,0],[1,0],[1],[0,1]]]]}}",
                "cels[0].regions[0].contours[0].animate.points.keys[0][1][2]",
                "expected a point [x,y] or [x,y,w]");
    expect_fail("point weight", ",", ",", ",",
                ", \"animate\": {\"points\": {\"keys\": [[0, [[0,0],[1,0],[1,1,0],[0,1]]]]}}",
                "cels[0].regions[0].contours[0].animate.points.keys[0][1]", "weight must be > 0");
    expect_fail("background colour", ", \"animate\": {\"background\": {\"keys\": [[0, [2, 0, 0]]]}},",
                ",", ",", "", "animate.background.keys[0][1][0]",
                "colour component must be in 0..1");
    expect_fail("stack light", ", \"animate\": {\"lights\": {\"keys\": [[0, {\"back\": \"#fff\"}]]}},",
                ",", ",", "", "animate.lights.keys[0][1].back", "expected a light level");

    /* Paint track naming a functional field; background without a card. */
    char err[SCENE_JSON_ERRLEN] = "";
    const char *grad = "{\"canvas\": {\"width\": 10, \"height\": 10}, \"cels\": [{\"regions\": [{"
                       "\"paint\": {\"beta\": {\"radial\": [5,5,5], \"stops\": [[0, 1], [1, 0]]}},"
                       "\"animate\": {\"paint\": {\"keys\": [[0, {\"pigment\": \"#fff\"}], [1, {\"beta\": 0.2}]]}},"
                       "\"contours\": [{\"degree\": 1, \"points\": [[0,0],[10,0],[10,10],[0,10]]}]}]}]}";
    int rc = scene_json_load_string(grad, strlen(grad), "g.json", sa, err, sizeof err);
    CHECK(rc != 0 && strstr(err, "g.json: cels[0].regions[0].animate.paint.keys[1][1].beta: "
                                 "this region's beta is a function of position; a paint track "
                                 "animates constant paint fields only") == err,
          "paint track on a functional beta refused: %s", err);
    const char *nobg = "{\"canvas\": {\"width\": 10, \"height\": 10}, \"cels\": [],"
                       "\"animate\": {\"background\": {\"keys\": [[0, \"#fff\"]]}}}";
    rc = scene_json_load_string(nobg, strlen(nobg), "n.json", sa, err, sizeof err);
    CHECK(rc != 0 && strstr(err, "n.json: animate.background: the canvas has no background") == err,
          "background track without a background refused: %s", err);
    /* A points track on a contour too big to animate. */
    char *big = malloc(200000);
    int n = snprintf(big, 200000, "{\"canvas\": {\"width\": 10, \"height\": 10}, \"cels\": [{\"regions\":"
                                  " [{\"paint\": {}, \"contours\": [{\"degree\": 1, \"points\": [");
    int count = CS_CFG_MAX_ANIM_POINTS + 1;
    for (int i = 0; i < count; i++)
        n += snprintf(big + n, 200000 - (size_t)n, "%s[%d,%d]", i ? "," : "", i % 7, i % 5);
    n += snprintf(big + n, 200000 - (size_t)n,
                  "], \"animate\": {\"points\": {\"keys\": [[0, []]]}}}]}]}]}");
    rc = scene_json_load_string(big, (size_t)n, "big.json", sa, err, sizeof err);
    CHECK(rc != 0 && strstr(err, "big.json: cels[0].regions[0].contours[0].animate.points: ") == err &&
              strstr(err, "at most 1024 animate") != NULL,
          "points track on %d points refused: %s", count, err);
    free(big);
}

/*
 * A disc moved by a keyframed translation written in JSON: the centroid of
 * its rendered coverage against the closed form, from the JSON and from its
 * stream. 16 sub-scanlines; the disc is a rational quadratic circle, exact.
 */
static void test_json_centroid(void)
{
    enum { W = 200, H = 100 };
    const double e0 = 30.3, f0 = 40.7, e1 = 161.9, f1 = 57.2, ta = 0.5, tb = 2.5;
    const double r = 12, s2 = 0.70710678118654752;
    static float img[W * H * 3];
    for (int ease = 0; ease < 2; ease++) {
        char json[2048];
        snprintf(json, sizeof json,
                 "{\"canvas\": {\"width\": %d, \"height\": %d}, \"cels\": [{"
                 " \"animate\": {\"transform\": {\"ease\": \"%s\", \"keys\": [[%g, [1,0,0,1,%.17g,%.17g]],"
                 "  [%g, [1,0,0,1,%.17g,%.17g]]]}},"
                 " \"regions\": [{\"paint\": {\"pigment\": \"#ffffff\"}, \"contours\": [{\"degree\": 2,"
                 "  \"points\": [[%g,0],[%g,%g,%.17g],[0,%g],[%g,%g,%.17g],[%g,0],[%g,%g,%.17g],[0,%g],"
                 "[%g,%g,%.17g]], \"intervals\": [1,0,1,0,1,0,1,0]}]}]}]}",
                 W, H, ease ? "smooth" : "linear", ta, e0, f0, tb, e1, f1, r, r, r, s2, r, -r, r, s2,
                 -r, -r, -r, s2, -r, r, -r, s2);
        char err[SCENE_JSON_ERRLEN];
        int rc = scene_json_load_string(json, strlen(json), "disc.json", sa, err, sizeof err);
        CHECK(rc == 0, "moving disc loads: %s", err);
        if (rc != 0)
            return;
        cels_buf b;
        compile(sa, &b);
        cels_read_stats stats;
        const cs_scene *d = cels_decode_buffer(b.data, b.len, "disc", sb, sc, stdout, &stats);
        cels_buf_free(&b);
        CHECK(d != NULL, "moving disc through a stream");
        const double times[] = {-3.0, 0.0, 0.5, 0.61, 1.0, 1.2345, 1.5, 2.0, 2.4999, 2.5, 7.0};
        double worst = 0;
        for (int src = 0; src < 2; src++) {
            const cs_scene *s = src == 0 ? sa : d;
            if (!s)
                continue;
            for (size_t i = 0; i < sizeof times / sizeof times[0]; i++) {
                double t = times[i];
                double u = t <= ta ? 0 : t >= tb ? 1 : (t - ta) / (tb - ta);
                if (ease)
                    u = u * u * (3 - 2 * u);
                double cx = e0 + (e1 - e0) * u, cy = f0 + (f1 - f0) * u;
                cs_status st = render(s, W, H, (float)t, 16, img, NULL);
                double m = 0, mx = 0, my = 0;
                for (int y = 0; y < H; y++)
                    for (int x = 0; x < W; x++) {
                        double c = img[(y * W + x) * 3 + 1];
                        m += c;
                        mx += c * (x + 0.5);
                        my += c * (y + 0.5);
                    }
                double dx = mx / m - cx, dy = my / m - cy, off = sqrt(dx * dx + dy * dy);
                if (off > worst)
                    worst = off;
                CHECK(st == CS_OK && off < 0.01 && fabs(m - PI * r * r) < 0.2,
                      "%s %s t=%g: centroid (%.5f, %.5f), want (%.5f, %.5f): off %.5f px",
                      src ? "stream" : "JSON", ease ? "smooth" : "linear", t, mx / m, my / m, cx,
                      cy, off);
            }
        }
        tl_note("centroid of a JSON-keyed disc, %s ease: worst %.5f px (JSON and stream, 11 "
                "instants)",
                ease ? "smooth" : "linear", worst);
    }
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "scenes";
    sa = tl_calloc(1, sizeof *sa);
    sb = tl_calloc(1, sizeof *sb);
    sc = tl_calloc(1, sizeof *sc);
    ws = tl_calloc(1, sizeof *ws);
    test_scene_dir(dir);
    TL_RUN(test_animate_values);
    TL_RUN(test_animate_errors);
    TL_RUN(test_degree_errors);
    TL_RUN(test_json_centroid);
    free(sa);
    free(sb);
    free(sc);
    free(ws);
    return tl_summary("test_scenes");
}
