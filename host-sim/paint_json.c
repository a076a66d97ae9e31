/*
 * paint_json.c - paints, gradients, colour maps and CSG from scene JSON.
 *
 * The syntax is documented in docs/SCENE.md. This file reads shapes and
 * types (is it a number, an array of four, a known spread name) and
 * converts sRGB colours to linear light; whether the numbers make sense is
 * for the core to say when the region is built, so the JSON loader and the
 * cel-stream decoder reject exactly the same scenes. Messages name the JSON
 * path of the offending value.
 */
#include "paint_json.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static int fail(char *err, size_t errlen, const char *fmt, ...)
{
    if (err && errlen) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err, errlen, fmt, ap);
        va_end(ap);
    }
    return -1;
}

static float srgb_to_linear(double e)
{
    return (float)(e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4));
}

static int hex_digit(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    return -1;
}

int paint_json_colour(const cJSON *node, float out[3])
{
    if (cJSON_IsString(node)) {
        const char *s = node->valuestring;
        size_t n = strlen(s);
        if (s[0] != '#' || (n != 7 && n != 4))
            return -1;
        for (int k = 0; k < 3; k++) {
            int v;
            if (n == 7) {
                int hi = hex_digit(s[1 + 2 * k]), lo = hex_digit(s[2 + 2 * k]);
                if (hi < 0 || lo < 0)
                    return -1;
                v = hi * 16 + lo;
            } else {
                int d = hex_digit(s[1 + k]);
                if (d < 0)
                    return -1;
                v = d * 17;
            }
            out[k] = srgb_to_linear(v / 255.0);
        }
        return 0;
    }
    if (cJSON_IsArray(node) && cJSON_GetArraySize(node) == 3) {
        for (int k = 0; k < 3; k++) {
            const cJSON *c = cJSON_GetArrayItem(node, k);
            if (!cJSON_IsNumber(c) || !(c->valuedouble >= 0.0 && c->valuedouble <= 1.0))
                return -1;
            out[k] = srgb_to_linear(c->valuedouble);
        }
        return 0;
    }
    return -1;
}

/* A stop or map value: a colour, or for beta a number in 0..1. */
static int field_value(const cJSON *node, bool scalar, float out[3])
{
    if (scalar) {
        if (!cJSON_IsNumber(node) || !isfinite(node->valuedouble))
            return -1;
        out[0] = out[1] = out[2] = (float)node->valuedouble;
        return 0;
    }
    return paint_json_colour(node, out);
}

static int number_array(const cJSON *node, float *out, int min, int max)
{
    int n = cJSON_GetArraySize(node);
    if (!cJSON_IsArray(node) || n < min || n > max)
        return -1;
    for (int i = 0; i < n; i++) {
        const cJSON *c = cJSON_GetArrayItem(node, i);
        if (!cJSON_IsNumber(c))
            return -1;
        out[i] = (float)c->valuedouble;
    }
    return n;
}

/* A functional field: {"linear"|"radial"|"map": [...], "stops"|"values": [...], ...}. */
static int parse_func(const cJSON *node, bool scalar, const char *path, cs_paint_func *f,
                      char *err, size_t errlen)
{
    memset(f, 0, sizeof *f);
    const char *what = scalar ? "a number" : "a colour (\"#rrggbb\" or [r,g,b] in 0..1)";
    const cJSON *g;
    int n;
    if ((g = cJSON_GetObjectItemCaseSensitive(node, "linear"))) {
        f->kind = CS_FUNC_LINEAR;
        if (number_array(g, f->geom, 4, 4) != 4)
            return fail(err, errlen, "%s.linear: expected [x0, y0, x1, y1]", path);
    } else if ((g = cJSON_GetObjectItemCaseSensitive(node, "radial"))) {
        f->kind = CS_FUNC_RADIAL;
        n = number_array(g, f->geom, 3, 5);
        if (n != 3 && n != 5)
            return fail(err, errlen, "%s.radial: expected [cx, cy, r] or [cx, cy, r, fx, fy]",
                        path);
        if (n == 3) { /* focal point at the centre */
            f->geom[3] = f->geom[0];
            f->geom[4] = f->geom[1];
        }
    } else if ((g = cJSON_GetObjectItemCaseSensitive(node, "map"))) {
        f->kind = CS_FUNC_MAP;
        if (number_array(g, f->geom, 6, 6) != 6)
            return fail(err, errlen, "%s.map: expected [ox, oy, ux, uy, vx, vy]", path);
    } else {
        return fail(err, errlen, "%s: expected %s, or an object with \"linear\", \"radial\" "
                                 "or \"map\"",
                    path, what);
    }
    const cJSON *sp = cJSON_GetObjectItemCaseSensitive(node, "spread");
    if (sp) {
        const char *s = cJSON_IsString(sp) ? sp->valuestring : "";
        if (!strcmp(s, "pad"))
            f->spread = CS_SPREAD_PAD;
        else if (!strcmp(s, "reflect"))
            f->spread = CS_SPREAD_REFLECT;
        else if (!strcmp(s, "repeat"))
            f->spread = CS_SPREAD_REPEAT;
        else
            return fail(err, errlen, "%s.spread: expected \"pad\", \"reflect\" or \"repeat\"",
                        path);
    }
    if (f->kind == CS_FUNC_MAP) {
        const cJSON *vals = cJSON_GetObjectItemCaseSensitive(node, "values");
        const cJSON *cols = cJSON_GetObjectItemCaseSensitive(node, "cols");
        n = cJSON_GetArraySize(vals);
        if (!cJSON_IsArray(vals) || n < 1 || n > CS_CFG_MAX_STOPS)
            return fail(err, errlen, "%s.values: expected 1..%d values, row by row", path,
                        CS_CFG_MAX_STOPS);
        if (!cJSON_IsNumber(cols) || cols->valuedouble < 1 || cols->valuedouble > n ||
            n % (int)cols->valuedouble != 0 || cols->valuedouble != (int)cols->valuedouble)
            return fail(err, errlen, "%s.cols: expected a whole number of columns dividing the "
                                     "%d values",
                        path, n);
        f->map_cols = (uint8_t)cols->valuedouble;
        f->stop_count = (uint8_t)n;
        for (int i = 0; i < n; i++)
            if (field_value(cJSON_GetArrayItem(vals, i), scalar, f->stops[i].value))
                return fail(err, errlen, "%s.values[%d]: expected %s", path, i, what);
        return 0;
    }
    const cJSON *stops = cJSON_GetObjectItemCaseSensitive(node, "stops");
    n = cJSON_GetArraySize(stops);
    if (!cJSON_IsArray(stops) || n < 1 || n > CS_CFG_MAX_STOPS)
        return fail(err, errlen, "%s.stops: expected 1..%d stops [offset, value]", path,
                    CS_CFG_MAX_STOPS);
    f->stop_count = (uint8_t)n;
    for (int i = 0; i < n; i++) {
        const cJSON *st = cJSON_GetArrayItem(stops, i);
        const cJSON *off = cJSON_GetArrayItem(st, 0);
        if (!cJSON_IsArray(st) || cJSON_GetArraySize(st) != 2 || !cJSON_IsNumber(off))
            return fail(err, errlen, "%s.stops[%d]: expected [offset, value]", path, i);
        f->stops[i].offset = (float)off->valuedouble;
        if (field_value(cJSON_GetArrayItem(st, 1), scalar, f->stops[i].value))
            return fail(err, errlen, "%s.stops[%d][1]: expected %s", path, i, what);
    }
    return 0;
}

int paint_json_parse(const cJSON *paint, const char *path, paint_json *out, char *err,
                     size_t errlen)
{
    memset(out, 0, sizeof *out);
    for (int k = 0; k < 3; k++) {
        out->paint.pigment[k] = 0.0f;
        out->paint.medium[k] = 1.0f;
    }
    out->paint.beta = 1.0f;
    if (!cJSON_IsObject(paint))
        return fail(err, errlen, "%s.paint: expected an object", path);
    static const char *const names[3] = {"pigment", "medium", "beta"};
    char sub[512];
    for (int field = 0; field < 3; field++) {
        const cJSON *v = cJSON_GetObjectItemCaseSensitive(paint, names[field]);
        if (!v)
            continue;
        snprintf(sub, sizeof sub, "%s.paint.%s", path, names[field]);
        bool scalar = field == CS_FIELD_BETA;
        float *dst = field == CS_FIELD_PIGMENT ? out->paint.pigment : out->paint.medium;
        if (cJSON_IsObject(v)) {
            if (parse_func(v, scalar, sub, &out->func[field], err, errlen))
                return -1;
            out->has_func[field] = true;
            /* The constant is unused; keep it valid for the core's check. */
            const float *first = out->func[field].stops[0].value;
            float c = fminf(fmaxf(first[0], 0.0f), 1.0f);
            if (scalar)
                out->paint.beta = c;
            else
                for (int k = 0; k < 3; k++)
                    dst[k] = fminf(fmaxf(first[k], 0.0f), 1.0f);
            continue;
        }
        if (scalar) {
            if (!cJSON_IsNumber(v))
                return fail(err, errlen, "%s: expected a number in 0..1 or a function", sub);
            out->paint.beta = (float)v->valuedouble;
        } else if (paint_json_colour(v, dst)) {
            return fail(err, errlen, "%s: expected \"#rrggbb\", [r,g,b] in 0..1 or a function",
                        sub);
        }
    }
    return 0;
}

static int csg_token(const cJSON *t)
{
    if (cJSON_IsNumber(t)) {
        double v = t->valuedouble;
        return v >= 0 && v < CS_CFG_MAX_OPERANDS && v == (int)v ? (int)v : -100;
    }
    if (!cJSON_IsString(t))
        return -100;
    const char *s = t->valuestring;
    if (!strcmp(s, "union"))
        return CS_CSG_UNION;
    if (!strcmp(s, "intersect") || !strcmp(s, "intersection"))
        return CS_CSG_INTERSECT;
    if (!strcmp(s, "difference"))
        return CS_CSG_DIFFERENCE;
    if (!strcmp(s, "xor"))
        return CS_CSG_XOR;
    return -100;
}

int paint_json_parse_csg(const cJSON *region, const char *path, paint_json_csg *out, char *err,
                         size_t errlen)
{
    memset(out, 0, sizeof *out);
    const cJSON *csg = cJSON_GetObjectItemCaseSensitive(region, "csg");
    const cJSON *ops = cJSON_GetObjectItemCaseSensitive(region, "operands");
    if (!csg) {
        if (ops)
            return fail(err, errlen, "%s.operands: only meaningful with \"csg\"", path);
        return 0;
    }
    int n = cJSON_GetArraySize(csg);
    if (!cJSON_IsArray(csg) || n < 1 || n > CS_CFG_MAX_CSG)
        return fail(err, errlen, "%s.csg: expected 1..%d RPN tokens", path, CS_CFG_MAX_CSG);
    for (int i = 0; i < n; i++) {
        int t = csg_token(cJSON_GetArrayItem(csg, i));
        if (t == -100)
            return fail(err, errlen,
                        "%s.csg[%d]: expected an operand 0..%d or \"union\", \"intersect\", "
                        "\"difference\", \"xor\"",
                        path, i, CS_CFG_MAX_OPERANDS - 1);
        out->rpn[i] = t;
    }
    out->len = n;
    const cJSON *contours = cJSON_GetObjectItemCaseSensitive(region, "contours");
    int nc = cJSON_GetArraySize(contours);
    if (ops) {
        if (!cJSON_IsArray(ops) || cJSON_GetArraySize(ops) != nc)
            return fail(err, errlen, "%s.operands: expected one operand per contour (%d)", path,
                        nc);
        for (int i = 0; i < nc; i++) {
            const cJSON *o = cJSON_GetArrayItem(ops, i);
            if (!cJSON_IsNumber(o) || o->valuedouble < 0 ||
                o->valuedouble >= CS_CFG_MAX_OPERANDS || o->valuedouble != (int)o->valuedouble)
                return fail(err, errlen, "%s.operands[%d]: expected an operand 0..%d", path, i,
                            CS_CFG_MAX_OPERANDS - 1);
        }
        out->operands = ops;
    } else if (nc > CS_CFG_MAX_OPERANDS) {
        return fail(err, errlen,
                    "%s: %d contours but at most %d operands; group them with \"operands\"",
                    path, nc, CS_CFG_MAX_OPERANDS);
    }
    return 0;
}

static int core_fail(char *err, size_t errlen, const char *path, const char *what,
                     const cs_error *e)
{
    if (e->item >= 0)
        return fail(err, errlen, "%s.%s: %s (item %d)", path, what, cs_status_str(e->status),
                    e->item);
    return fail(err, errlen, "%s.%s: %s", path, what, cs_status_str(e->status));
}

int paint_json_add_region(cs_scene *scene, cs_fill_rule rule, const paint_json *p,
                          const paint_json_csg *csg, const char *path, char *err, size_t errlen)
{
    cs_error e;
    static const char *const names[3] = {"paint.pigment", "paint.medium", "paint.beta"};
    if (cs_scene_add_region(scene, rule, &p->paint, &e) != CS_OK)
        return core_fail(err, errlen, path, "paint", &e);
    for (int field = 0; field < 3; field++)
        if (p->has_func[field] &&
            cs_scene_set_region_func(scene, (cs_paint_field)field, &p->func[field], &e) != CS_OK)
            return core_fail(err, errlen, path, names[field], &e);
    if (csg && csg->len && cs_scene_set_region_csg(scene, csg->rpn, csg->len, &e) != CS_OK)
        return core_fail(err, errlen, path, "csg", &e);
    return 0;
}

int paint_json_set_operand(cs_scene *scene, const paint_json_csg *csg, int index,
                           const char *path, char *err, size_t errlen)
{
    if (!csg || !csg->len)
        return 0;
    int op = csg->operands ? (int)cJSON_GetArrayItem(csg->operands, index)->valuedouble : index;
    cs_error e;
    if (cs_scene_set_contour_operand(scene, op, &e) != CS_OK)
        return core_fail(err, errlen, path, "operands", &e);
    return 0;
}
