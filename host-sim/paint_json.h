/*
 * paint_json.h - scene JSON for paints (constant and functional) and CSG.
 *
 * A small helper the scene loader (host-sim/scene_json.c) calls per region,
 * so that the syntax of docs/SCENE.md for "paint", "csg" and "operands"
 * lives in one place. It only reads the cJSON tree and fills plain structs;
 * the numeric validation (ranges, stop order, degenerate geometry, RPN
 * depth) is the core's (cs_scene_set_region_func, cs_scene_set_region_csg),
 * and the apply calls turn its cs_error into a message naming the JSON path.
 *
 * Use, per region (path like "cels[0].regions[2]"):
 *
 *   paint_json pj;  paint_json_csg csg;
 *   if (paint_json_parse(cJSON_GetObjectItemCaseSensitive(region, "paint"), path, &pj, err, n)
 *       || paint_json_parse_csg(region, path, &csg, err, n)
 *       || paint_json_add_region(scene, rule, &pj, &csg, path, err, n))
 *       fail;
 *   for each contour i:
 *       cs_scene_add_contour(...);
 *       if (paint_json_set_operand(scene, &csg, i, path, err, n)) fail;
 *
 * All functions return 0 on success, -1 with a message in err otherwise.
 */
#ifndef PAINT_JSON_H
#define PAINT_JSON_H

#include <stdbool.h>
#include <stddef.h>

#include <cjson/cJSON.h>

#include "celscan.h"

typedef struct paint_json {
    cs_paint paint;          /* constants; a functional field holds its first value */
    bool has_func[3];        /* per cs_paint_field */
    cs_paint_func func[3];
} paint_json;

typedef struct paint_json_csg {
    int len;                 /* 0: no "csg" */
    int rpn[CS_CFG_MAX_CSG];
    const cJSON *operands;   /* the "operands" array, or NULL: contour i -> operand i */
} paint_json_csg;

/*
 * Parses a "paint" object. Missing fields default to pigment #000000,
 * medium [1,1,1] (a clear vehicle) and beta 1. Colours are sRGB ("#rrggbb",
 * "#rgb" or [r,g,b] in 0..1) and come out in linear light.
 */
int paint_json_parse(const cJSON *paint, const char *path, paint_json *out, char *err,
                     size_t errlen);

/* Parses a region's "csg" and "operands" (both optional). */
int paint_json_parse_csg(const cJSON *region, const char *path, paint_json_csg *out, char *err,
                         size_t errlen);

/* Appends the region to the last cel: paint, functions and CSG program. */
int paint_json_add_region(cs_scene *scene, cs_fill_rule rule, const paint_json *paint,
                          const paint_json_csg *csg, const char *path, char *err, size_t errlen);

/* After contour `index` of the region was added: puts it in its operand. */
int paint_json_set_operand(cs_scene *scene, const paint_json_csg *csg, int index,
                           const char *path, char *err, size_t errlen);

/* sRGB colour ("#rrggbb", "#rgb" or [r,g,b]) to linear light; 0 or -1. */
int paint_json_colour(const cJSON *node, float out[3]);

#endif /* PAINT_JSON_H */
