/*
 * test_paint_json.c - the scene JSON syntax of paints, functions and CSG.
 *
 * Parses documents written as docs/SCENE.md shows them, builds regions
 * through host-sim/paint_json.c, and checks what lands in the scene store
 * (values converted from sRGB by the standard formula, computed here) and
 * that malformed input is refused with a message naming its JSON path.
 * Last line: `test_paint_json: N passed, M failed`.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "celscan_private.h"
#include "paint_json.h"

#include "testlib.h"

static cs_scene scene;

static double lin(double e)
{
    return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4);
}

/* Builds one region from `json` (a region object); 0 on success, else the message. */
static int build(const char *json, char *err, size_t errlen)
{
    cs_scene_init(&scene, 100, 100);
    cs_affine m = {1, 0, 0, 1, 0, 0};
    cs_error e;
    cs_scene_add_cel(&scene, &m, NULL, NULL, &e);
    cJSON *region = cJSON_Parse(json);
    if (!region) {
        snprintf(err, errlen, "bad JSON in test");
        return -1;
    }
    paint_json pj;
    paint_json_csg csg;
    int rc = paint_json_parse(cJSON_GetObjectItemCaseSensitive(region, "paint"), "r", &pj, err,
                              errlen);
    if (!rc)
        rc = paint_json_parse_csg(region, "r", &csg, err, errlen);
    if (!rc)
        rc = paint_json_add_region(&scene, CS_FILL_NONZERO, &pj, &csg, "r", err, errlen);
    const cJSON *contours = cJSON_GetObjectItemCaseSensitive(region, "contours");
    for (int i = 0; !rc && i < cJSON_GetArraySize(contours); i++) {
        cs_point p[3] = {{0, 0, 1}, {10, 0, 1}, {0, 10, 1}};
        cs_scene_add_contour(&scene, 1, 3, p, NULL, &e);
        rc = paint_json_set_operand(&scene, &csg, i, "r", err, errlen);
    }
    cJSON_Delete(region);
    return rc;
}

static void expect_error(const char *json, const char *needle)
{
    char err[256] = "";
    int rc = build(json, err, sizeof err);
    CHECK(rc != 0 && strstr(err, needle), "expected error with '%s' for %s, got '%s'", needle,
          json, err);
}

int main(void)
{
    char err[256];
    /* Constants and defaults. */
    int rc = build("{\"paint\": {\"pigment\": \"#e03030\"}}", err, sizeof err);
    CHECK(rc == 0, "constant paint: %s", err);
    const cs_region *r = &scene.regions[0];
    CHECK(fabs(r->paint.pigment[0] - lin(0xe0 / 255.0)) < 1e-6 &&
              fabs(r->paint.pigment[1] - lin(0x30 / 255.0)) < 1e-6,
          "pigment from sRGB hex");
    CHECK(r->paint.medium[0] == 1 && r->paint.beta == 1 && r->func[0] == 0,
          "defaults: medium 1, beta 1, no functions");
    rc = build("{\"paint\": {\"pigment\": [0.5, 0.25, 1], \"medium\": \"#fff\", \"beta\": 0.25}}",
               err, sizeof err);
    CHECK(rc == 0 && fabs(scene.regions[0].paint.pigment[0] - lin(0.5)) < 1e-6 &&
              scene.regions[0].paint.beta == 0.25f && scene.regions[0].paint.medium[2] == 1.0f,
          "array colour, #rgb, beta: %s", err);

    /* A linear gradient pigment, a radial beta, a map medium. */
    rc = build("{\"paint\": {"
               "\"pigment\": {\"linear\": [0, 0, 100, 0], \"spread\": \"reflect\","
               "              \"stops\": [[0, \"#ff0000\"], [0.5, [0, 1, 0]], [1, \"#0000ff\"]]},"
               "\"beta\": {\"radial\": [50, 50, 40, 60, 50], \"stops\": [[0, 1], [1, 0.2]]},"
               "\"medium\": {\"map\": [0, 0, 100, 0, 0, 100], \"cols\": 2,"
               "             \"values\": [\"#ffffff\", \"#000000\", \"#ff0000\", \"#00ff00\"]}}}",
               err, sizeof err);
    CHECK(rc == 0, "functions: %s", err);
    r = &scene.regions[0];
    CHECK(r->func[0] && r->func[1] && r->func[2] && scene.func_count == 3, "three functions");
    const cs_paint_func *f = &scene.funcs[r->func[CS_FIELD_PIGMENT] - 1];
    CHECK(f->kind == CS_FUNC_LINEAR && f->spread == CS_SPREAD_REFLECT && f->stop_count == 3 &&
              f->geom[2] == 100 && f->stops[1].offset == 0.5f && f->stops[1].value[1] == 1.0f &&
              f->stops[2].value[2] == 1.0f,
          "linear gradient stored");
    f = &scene.funcs[r->func[CS_FIELD_BETA] - 1];
    CHECK(f->kind == CS_FUNC_RADIAL && f->geom[3] == 60 && f->stops[1].value[0] == 0.2f,
          "radial beta stored");
    f = &scene.funcs[r->func[CS_FIELD_MEDIUM] - 1];
    CHECK(f->kind == CS_FUNC_MAP && f->map_cols == 2 && f->stop_count == 4 &&
              f->stops[2].value[0] == 1.0f && f->stops[3].value[1] == 1.0f,
          "map stored");
    rc = build("{\"paint\": {\"pigment\": {\"radial\": [5, 5, 3], \"stops\": [[0, \"#000\"]]}}}",
               err, sizeof err);
    f = &scene.funcs[0];
    CHECK(rc == 0 && f->geom[3] == 5 && f->geom[4] == 5, "radial without focal: %s", err);

    /* CSG. */
    rc = build("{\"paint\": {}, \"csg\": [0, 1, \"difference\", 2, \"union\"],"
               " \"contours\": [{}, {}, {}]}",
               err, sizeof err);
    r = &scene.regions[0];
    CHECK(rc == 0 && r->csg_len == 5 && scene.contours[2].operand == 2, "csg default operands: %s",
          err);
    rc = build("{\"paint\": {}, \"csg\": [0, 1, \"xor\"], \"operands\": [0, 0, 1],"
               " \"contours\": [{}, {}, {}]}",
               err, sizeof err);
    CHECK(rc == 0 && scene.contours[1].operand == 0 && scene.contours[2].operand == 1,
          "csg grouped operands: %s", err);

    /* Errors, each naming where. */
    expect_error("{\"paint\": {\"pigment\": \"red\"}}", "r.paint.pigment");
    expect_error("{\"paint\": {\"beta\": \"half\"}}", "r.paint.beta");
    expect_error("{\"paint\": {\"beta\": 1.5}}", "paint components must lie in 0..1");
    expect_error("{\"paint\": {\"pigment\": {\"linear\": [0, 0, 1]}}}", "r.paint.pigment.linear");
    expect_error("{\"paint\": {\"pigment\": {\"conic\": [0, 0, 1]}}}", "\"radial\"");
    expect_error("{\"paint\": {\"pigment\": {\"linear\": [0,0,1,0], \"stops\": [[0, 0.5]]}}}",
                 "r.paint.pigment.stops[0][1]");
    expect_error("{\"paint\": {\"pigment\": {\"linear\": [0,0,1,0], \"stops\": "
                 "[[0.6, \"#fff\"], [0.2, \"#000\"]]}}}",
                 "r.paint.pigment: paint function malformed");
    expect_error("{\"paint\": {\"pigment\": {\"linear\": [0,0,0,0], \"stops\": [[0, \"#fff\"]]}}}",
                 "paint function malformed");
    expect_error("{\"paint\": {\"pigment\": {\"linear\": [0,0,1,0], \"spread\": \"mirror\","
                 " \"stops\": [[0, \"#fff\"]]}}}",
                 "r.paint.pigment.spread");
    expect_error("{\"paint\": {\"medium\": {\"map\": [0,0,1,0,0,1], \"cols\": 3,"
                 " \"values\": [\"#fff\", \"#000\"]}}}",
                 "r.paint.medium.cols");
    expect_error("{\"paint\": {}, \"csg\": [0, \"minus\", 1]}", "r.csg[1]");
    expect_error("{\"paint\": {}, \"csg\": [0, \"union\"]}", "r.csg: CSG program malformed");
    expect_error("{\"paint\": {}, \"operands\": [0]}", "only meaningful with \"csg\"");
    expect_error("{\"paint\": {}, \"csg\": [0], \"operands\": [0, 1], \"contours\": [{}]}",
                 "one operand per contour");
    expect_error("{\"paint\": {}, \"csg\": [0], \"contours\": [{},{},{},{},{},{},{},{},{}]}",
                 "group them");
    expect_error("{}", "r.paint: expected an object");
    return tl_summary("test_paint_json");
}
