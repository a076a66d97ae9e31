/*
 * scene_json.c - authoring JSON to cs_scene (see scene_json.h).
 *
 * The loader walks the cJSON tree once, front to back, and feeds the core's
 * cs_scene_* calls in the same order the scene store keeps (front-most cel
 * first, front-most region first). It checks what only it can see (JSON
 * types, required fields, array lengths, colours in 0..1, numbers that do
 * not fit a float) and leaves every geometric rule (degree, weights, knot
 * intervals, coordinate range, capacity) to the core, so the rules live in
 * one place and the board enforces the same ones. Core errors come back as a
 * cs_error whose item index is turned into the JSON path of the culprit.
 *
 * Defaults, where DESIGN.md leaves them to the loader:
 *   canvas.background   absent: no card; the stack back light shines through
 *   lights.front/back   [1,1,1] / [0,0,0]      (linear multipliers)
 *   cel transform       [1,0,0,1,0,0]
 *   cel lights.front    the stack front light  (cel lights.back: black)
 *   region fill_rule    "nonzero"
 *   paint pigment       black  [0,0,0]
 *   paint medium        white  [1,1,1]  (a clear vehicle: β = 1 - alpha)
 *   paint beta          1.0    (opaque)
 *   contour w           1 per point;  intervals: all 1
 * Required: canvas.width, canvas.height, cels, and per cel regions, per region
 * paint and contours, per contour degree and points.
 *
 * Unknown keys are ignored, so scenes may carry extensions (names, notes).
 * "animate" objects are the exception: they become keyframe tracks (see the
 * animate section below), and an unknown track name in one is an error,
 * because a misspelt track would otherwise silently not move.
 */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celscan_private.h"
#include "scene_json.h"
#include "paint_json.h"

/* Deep enough for cels[N].regions[N].contours[N].intervals[N] with room to spare. */
#define PATH_CAP 256

typedef struct loader {
    const char *name;
    char *err;
    size_t errlen;
    char path[PATH_CAP];
    size_t plen;
    cs_scene *scene;
    cs_point *pts; /* scratch for one contour, grown as needed */
    float *ivs;
    size_t cap;
} loader;

/* ------------------------------------------------------------ messages */

static void set_path(char *path, size_t *plen, size_t at)
{
    *plen = at;
    path[at] = '\0';
}

/* Path components are pushed before a value is read and popped after, so a
 * failure anywhere below names its own location without passing it around. */
static size_t push_key(loader *L, const char *key)
{
    size_t old = L->plen;
    int n = snprintf(L->path + old, PATH_CAP - old, "%s%s", old ? "." : "", key);
    if (n > 0)
        L->plen = old + (size_t)n < PATH_CAP ? old + (size_t)n : PATH_CAP - 1;
    return old;
}

static size_t push_index(loader *L, int i)
{
    size_t old = L->plen;
    int n = snprintf(L->path + old, PATH_CAP - old, "[%d]", i);
    if (n > 0)
        L->plen = old + (size_t)n < PATH_CAP ? old + (size_t)n : PATH_CAP - 1;
    return old;
}

static void pop(loader *L, size_t old) { set_path(L->path, &L->plen, old); }

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static int fail(loader *L, const char *fmt, ...)
{
    if (L->errlen == 0)
        return -1;
    int n = snprintf(L->err, L->errlen, "%s: %s: ", L->name, L->plen ? L->path : "top level");
    if (n >= 0 && (size_t)n < L->errlen) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(L->err + n, L->errlen - (size_t)n, fmt, ap);
        va_end(ap);
    }
    return -1;
}

static const char *kind(const cJSON *j)
{
    if (j == NULL)
        return "nothing";
    if (cJSON_IsNumber(j))
        return "a number";
    if (cJSON_IsString(j))
        return "a string";
    if (cJSON_IsArray(j))
        return "an array";
    if (cJSON_IsObject(j))
        return "an object";
    if (cJSON_IsBool(j))
        return "a boolean";
    if (cJSON_IsNull(j))
        return "null";
    return "an invalid value";
}

/* ------------------------------------------------------------- values */

static const cJSON *member(const cJSON *obj, const char *key)
{
    return cJSON_GetObjectItemCaseSensitive(obj, key);
}

/* Reads a number into a float. JSON has no NaN, but 1e300 or 1e999 parse to
 * huge doubles or infinity, which must not silently become inf in the scene. */
static int get_float(loader *L, const cJSON *j, float *out)
{
    if (!cJSON_IsNumber(j))
        return fail(L, "expected a number, got %s", kind(j));
    double v = j->valuedouble;
    if (!(v >= -(double)FLT_MAX && v <= (double)FLT_MAX)) {
        if (isinf(v))
            return fail(L, "number out of range (overflows to infinity)");
        return fail(L, "number out of range (%g does not fit single precision)", v);
    }
    *out = (float)v;
    return 0;
}

/* A required or optional member number; absent optional members keep *out. */
static int member_float(loader *L, const cJSON *obj, const char *key, bool required, float *out)
{
    const cJSON *j = member(obj, key);
    size_t at = push_key(L, key);
    int rc = 0;
    if (j == NULL)
        rc = required ? fail(L, "missing (required number)") : 0;
    else
        rc = get_float(L, j, out);
    if (rc == 0)
        pop(L, at);
    return rc;
}

/* Exactly n numbers: `what` says the expected shape, e.g. "[a,b,c,d,e,f]". */
static int get_floats(loader *L, const cJSON *j, float *out, int n, const char *what)
{
    if (!cJSON_IsArray(j) || cJSON_GetArraySize(j) != n) {
        if (cJSON_IsArray(j))
            return fail(L, "expected %s (%d numbers), got %d", what, n, cJSON_GetArraySize(j));
        return fail(L, "expected %s, got %s", what, kind(j));
    }
    int i = 0;
    const cJSON *e;
    cJSON_ArrayForEach(e, j)
    {
        size_t at = push_index(L, i);
        if (get_float(L, e, &out[i]) != 0)
            return -1;
        pop(L, at);
        i++;
    }
    return 0;
}

float scene_json_srgb_to_linear(double c)
{
    double v = c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
    return (float)v;
}

static int hexval(char ch)
{
    if (ch >= '0' && ch <= '9')
        return ch - '0';
    if (ch >= 'a' && ch <= 'f')
        return ch - 'a' + 10;
    if (ch >= 'A' && ch <= 'F')
        return ch - 'A' + 10;
    return -1;
}

/* "#rrggbb" or [r,g,b], sRGB-encoded in 0..1, returned in linear light. */
static int get_colour(loader *L, const cJSON *j, float out[3])
{
    double enc[3];
    if (cJSON_IsString(j)) {
        const char *s = j->valuestring;
        bool ok = strlen(s) == 7 && s[0] == '#';
        for (int i = 1; ok && i < 7; i++)
            ok = hexval(s[i]) >= 0;
        if (!ok)
            return fail(L, "expected a colour \"#rrggbb\", got \"%.40s\"", s);
        for (int i = 0; i < 3; i++)
            enc[i] = (hexval(s[1 + 2 * i]) * 16 + hexval(s[2 + 2 * i])) / 255.0;
    } else if (cJSON_IsArray(j)) {
        float v[3];
        if (get_floats(L, j, v, 3, "a colour [r,g,b]") != 0)
            return -1;
        for (int i = 0; i < 3; i++) {
            if (!(v[i] >= 0.0f && v[i] <= 1.0f)) {
                push_index(L, i);
                return fail(L, "colour component must be in 0..1 (sRGB-encoded), got %g",
                            (double)v[i]);
            }
            enc[i] = (double)v[i];
        }
    } else {
        return fail(L, "expected a colour \"#rrggbb\" or [r,g,b], got %s", kind(j));
    }
    for (int i = 0; i < 3; i++)
        out[i] = scene_json_srgb_to_linear(enc[i]);
    return 0;
}

static int member_colour(loader *L, const cJSON *obj, const char *key, float out[3])
{
    const cJSON *j = member(obj, key);
    if (j == NULL)
        return 0;
    size_t at = push_key(L, key);
    if (get_colour(L, j, out) != 0)
        return -1;
    pop(L, at);
    return 0;
}

/* A light level: three linear multipliers, >= 0, possibly above 1. Not a
 * "#rrggbb" string, because light is not an sRGB-encoded colour. */
static int get_light(loader *L, const cJSON *j, float out[3])
{
    if (get_floats(L, j, out, 3, "a light level [r,g,b] (linear multipliers)") != 0)
        return -1;
    for (int i = 0; i < 3; i++) {
        if (!(out[i] >= 0.0f)) {
            push_index(L, i);
            return fail(L, "light level must be >= 0, got %g", (double)out[i]);
        }
    }
    return 0;
}

/* A lights object {"front": [...], "back": [...]} whose path is already
 * pushed; *has_x says which of the two were given. */
static int get_lights_obj(loader *L, const cJSON *lights, float front[3], bool *has_front,
                          float back[3], bool *has_back)
{
    *has_front = *has_back = false;
    if (!cJSON_IsObject(lights))
        return fail(L, "expected an object {\"front\": [r,g,b], \"back\": [r,g,b]}, got %s",
                    kind(lights));
    const char *keys[2] = {"front", "back"};
    float *dst[2] = {front, back};
    bool *has[2] = {has_front, has_back};
    for (int i = 0; i < 2; i++) {
        const cJSON *j = member(lights, keys[i]);
        if (j == NULL)
            continue;
        size_t at = push_key(L, keys[i]);
        if (get_light(L, j, dst[i]) != 0)
            return -1;
        pop(L, at);
        *has[i] = true;
    }
    return 0;
}

/* The optional "lights" member of a scene or cel. */
static int get_lights(loader *L, const cJSON *obj, float front[3], bool *has_front, float back[3],
                      bool *has_back)
{
    const cJSON *lights = member(obj, "lights");
    *has_front = *has_back = false;
    if (lights == NULL)
        return 0;
    size_t at = push_key(L, "lights");
    if (get_lights_obj(L, lights, front, has_front, back, has_back) != 0)
        return -1;
    pop(L, at);
    return 0;
}

static int require_array(loader *L, const cJSON *obj, const char *key, const cJSON **out)
{
    const cJSON *j = member(obj, key);
    size_t at = push_key(L, key);
    if (j == NULL)
        return fail(L, "missing (required array)");
    if (!cJSON_IsArray(j))
        return fail(L, "expected an array, got %s", kind(j));
    pop(L, at);
    *out = j;
    return 0;
}

/* ------------------------------------------------------------- animate */

/*
 * "animate" objects become keyframe tracks in the store (cs_scene_add_track
 * and cs_scene_add_key), so the core checks the values exactly as it checks
 * the static ones and a compiled stream carries the same tracks. Where they
 * live and what a key's value is:
 *
 *   scene   "animate": {"lights": {front, back}, "background": colour}
 *   cel     "animate": {"transform": [a,b,c,d,e,f], "lights": {front, back},
 *                       "trs": {position, anchor, scale, rotation, skew, skew_axis, opacity}}
 *   region  "animate": {"paint": {pigment, medium, beta}}
 *   contour "animate": {"points": [[x,y] or [x,y,w], ...]}
 *
 * Each track is {"keys": [[t, value], ...], "ease": "linear"|"smooth"|"hold"|"cubic"};
 * a cubic track's key may add its segment's easing, [t, value, [x1,y1,x2,y2]]
 * or [t, value, "hold"] (left out: linear).
 * Object values may leave members out; those hold the item's static value
 * (its lights, its constant paint). Colours are sRGB and become linear
 * light, as everywhere in the scene. A paint key may not name a field the
 * region paints with a function of position: a paint track animates
 * constants only (docs/SCENE.md).
 */

typedef struct track_ctx {
    cs_track_kind kind;
    uint32_t target;
    float defaults[7];    /* static values for members a key leaves out */
    const bool *func;     /* paint: which fields are functions; else NULL */
    uint32_t points;      /* points: the contour's count */
} track_ctx;

/* Reads a {"front", "back"} key into v[0..5], missing members from defaults. */
static int key_lights(loader *L, const cJSON *j, const track_ctx *c, float *v)
{
    float f[3], b[3];
    bool hf, hb;
    if (get_lights_obj(L, j, f, &hf, b, &hb) != 0)
        return -1;
    for (int k = 0; k < 3; k++) {
        v[k] = hf ? f[k] : c->defaults[k];
        v[3 + k] = hb ? b[k] : c->defaults[3 + k];
    }
    return 0;
}

/* Reads a {"pigment", "medium", "beta"} key of constants into v[0..6]. */
static int key_paint(loader *L, const cJSON *j, const track_ctx *c, float *v)
{
    if (!cJSON_IsObject(j))
        return fail(L, "expected a paint {\"pigment\", \"medium\", \"beta\"}, got %s", kind(j));
    for (int k = 0; k < 7; k++)
        v[k] = c->defaults[k];
    static const char *const names[3] = {"pigment", "medium", "beta"};
    for (int field = 0; field < 3; field++) {
        const cJSON *m = member(j, names[field]);
        if (m == NULL)
            continue;
        size_t at = push_key(L, names[field]);
        if (c->func[field])
            return fail(L, "this region's %s is a function of position; a paint track animates "
                           "constant paint fields only",
                        names[field]);
        if (field == CS_FIELD_BETA) {
            if (get_float(L, m, &v[6]) != 0)
                return -1;
        } else if (paint_json_colour(m, v + 3 * field) != 0) {
            return fail(L, "expected a colour \"#rrggbb\", \"#rgb\" or [r,g,b] in 0..1, got %s",
                        kind(m));
        }
        pop(L, at);
    }
    return 0;
}

/* Reads a key of c->points control points into v (x y w each). */
static int key_points(loader *L, const cJSON *j, const track_ctx *c, float *v)
{
    if (!cJSON_IsArray(j))
        return fail(L, "expected an array of %u points [x,y] or [x,y,w], got %s", c->points,
                    kind(j));
    if ((uint32_t)cJSON_GetArraySize(j) != c->points)
        return fail(L, "expected %u points (the contour's point count), got %d", c->points,
                    cJSON_GetArraySize(j));
    int i = 0;
    const cJSON *p;
    cJSON_ArrayForEach(p, j)
    {
        size_t at = push_index(L, i);
        int n = cJSON_IsArray(p) ? cJSON_GetArraySize(p) : 0;
        if (n != 2 && n != 3)
            return fail(L, "expected a point [x,y] or [x,y,w], got %s", kind(p));
        float *q = v + 3 * i;
        q[2] = 1.0f;
        if (get_floats(L, p, q, n, n == 2 ? "[x,y]" : "[x,y,w]") != 0)
            return -1;
        pop(L, at);
        i++;
    }
    return 0;
}

/* A TRS key {"position", "anchor", "scale", "rotation", "skew", "skew_axis",
 * "opacity"} into v[0..9]; members left out are the identity's. */
static int key_trs(loader *L, const cJSON *j, float *v)
{
    if (!cJSON_IsObject(j))
        return fail(L, "expected a TRS key {\"position\", \"anchor\", \"scale\", \"rotation\", "
                       "\"skew\", \"skew_axis\", \"opacity\"}, got %s",
                    kind(j));
    static const float identity[10] = {0, 0, 0, 0, 1, 1, 0, 0, 0, 1};
    for (int k = 0; k < 10; k++)
        v[k] = identity[k];
    static const char *const pairs[3] = {"position", "anchor", "scale"};
    for (int k = 0; k < 3; k++) {
        const cJSON *m = member(j, pairs[k]);
        if (m == NULL)
            continue;
        size_t at = push_key(L, pairs[k]);
        if (get_floats(L, m, v + 2 * k, 2, "a pair [x,y]") != 0)
            return -1;
        pop(L, at);
    }
    static const char *const singles[4] = {"rotation", "skew", "skew_axis", "opacity"};
    for (int k = 0; k < 4; k++)
        if (member(j, singles[k]) != NULL && member_float(L, j, singles[k], false, &v[6 + k]) != 0)
            return -1;
    const cJSON *m;
    cJSON_ArrayForEach(m, j)
    {
        bool known = false;
        for (int k = 0; k < 3; k++)
            known = known || strcmp(m->string, pairs[k]) == 0;
        for (int k = 0; k < 4; k++)
            known = known || strcmp(m->string, singles[k]) == 0;
        if (!known) {
            push_key(L, m->string);
            return fail(L, "unknown TRS member (position, anchor, scale, rotation, skew, "
                           "skew_axis, opacity)");
        }
    }
    return 0;
}

/* A cubic track key's easing (third element): [x1,y1,x2,y2] or "hold". */
static int key_ease(loader *L, const cJSON *j, float *e)
{
    if (cJSON_IsString(j) && strcmp(j->valuestring, "hold") == 0) {
        e[0] = -1.0f;
        e[1] = e[2] = e[3] = 0.0f;
        return 0;
    }
    return get_floats(L, j, e, 4, "an easing [x1,y1,x2,y2] or \"hold\"");
}

/* The value of one key, its path already pushed. */
static int key_value(loader *L, const cJSON *j, const track_ctx *c, float *v)
{
    switch (c->kind) {
    case CS_TRACK_TRANSFORM:
        return get_floats(L, j, v, 6, "a transform [a,b,c,d,e,f]");
    case CS_TRACK_CEL_LIGHTS:
    case CS_TRACK_STACK_LIGHTS:
        return key_lights(L, j, c, v);
    case CS_TRACK_PAINT:
        return key_paint(L, j, c, v);
    case CS_TRACK_POINTS:
        return key_points(L, j, c, v);
    case CS_TRACK_TRS:
        return key_trs(L, j, v);
    default:
        return get_colour(L, j, v);
    }
}

/* A core error on key i, with the JSON path of its time or value. */
static int key_core_error(loader *L, const cs_error *e, float t, float prev)
{
    switch (e->status) {
    case CS_ERR_KEY_ORDER:
        push_index(L, 0);
        return fail(L, "key times must increase strictly (%g after %g)", (double)t, (double)prev);
    case CS_ERR_NONFINITE:
        if (!isfinite(t)) {
            push_index(L, 0);
            return fail(L, "%s", cs_status_str(e->status));
        }
        break;
    case CS_ERR_CAP_KEYS:
        return fail(L, "%s", cs_status_str(e->status));
    default:
        break;
    }
    /* A value the core refused (range, weight, paint, light): the key's value. */
    push_index(L, 1);
    return fail(L, "%s", cs_status_str(e->status));
}

/* One track object {"keys": [...], "ease": ...} whose path is pushed. */
static int load_track(loader *L, const cJSON *track, const track_ctx *c)
{
    if (!cJSON_IsObject(track))
        return fail(L, "expected a track {\"keys\": [[t, value], ...], \"ease\": ...}, got %s",
                    kind(track));
    cs_ease ease = CS_EASE_LINEAR;
    const cJSON *ej = member(track, "ease");
    if (ej != NULL) {
        size_t at = push_key(L, "ease");
        static const char *const eases[CS_EASE_COUNT_] = {"linear", "smooth", "hold", "cubic"};
        int k = 0;
        while (k < CS_EASE_COUNT_ && !(cJSON_IsString(ej) && strcmp(ej->valuestring, eases[k]) == 0))
            k++;
        if (k == CS_EASE_COUNT_ && cJSON_IsString(ej))
            return fail(L, "ease must be \"linear\", \"smooth\", \"hold\" or \"cubic\", got \"%.40s\"",
                        ej->valuestring);
        if (k == CS_EASE_COUNT_)
            return fail(L, "ease must be \"linear\", \"smooth\", \"hold\" or \"cubic\", got %s", kind(ej));
        ease = (cs_ease)k;
        pop(L, at);
    }
    const cJSON *keys = member(track, "keys");
    size_t at = push_key(L, "keys");
    if (keys == NULL)
        return fail(L, "missing (required array of keys [t, value])");
    if (!cJSON_IsArray(keys) || cJSON_GetArraySize(keys) == 0)
        return fail(L, "expected a non-empty array of keys [t, value], got %s%s", kind(keys),
                    cJSON_IsArray(keys) ? " with no keys" : "");
    pop(L, at);
    cs_error e;
    if (cs_scene_add_track(L->scene, c->kind, c->target, ease, &e) != CS_OK) {
        if (e.status == CS_ERR_CAP_ANIM)
            return fail(L, "%s (the contour has %u points, at most %d animate)",
                        cs_status_str(e.status), c->points, CS_CFG_MAX_ANIM_POINTS);
        return fail(L, "%s", cs_status_str(e.status));
    }
    uint32_t lead = ease == CS_EASE_CUBIC ? CS_EASE_CUBIC_FLOATS : 0u;
    uint32_t width = cs_scene_track_width(L->scene, c->kind, c->target) + lead;
    float *v = calloc(width ? width : 1, sizeof *v);
    if (v == NULL)
        return fail(L, "out of memory for a key of %u values", width);
    at = push_key(L, "keys");
    int i = 0, rc = 0;
    float prev = 0.0f;
    const cJSON *key;
    cJSON_ArrayForEach(key, keys)
    {
        size_t at2 = push_index(L, i);
        float t = 0.0f;
        int n = cJSON_IsArray(key) ? cJSON_GetArraySize(key) : 0;
        if (n != 2 && !(n == 3 && lead)) {
            rc = fail(L, "expected a key [t, value]%s, got %s",
                      lead ? " or [t, value, easing]" : "", kind(key));
            break;
        }
        size_t at3 = push_index(L, 0);
        if (get_float(L, cJSON_GetArrayItem(key, 0), &t) != 0) {
            rc = -1;
            break;
        }
        set_path(L->path, &L->plen, at3);
        static const float linear[4] = {0.0f, 0.0f, 1.0f, 1.0f};
        for (uint32_t k = 0; k < lead; k++)
            v[k] = linear[k];
        if (n == 3) {
            push_index(L, 2);
            if (key_ease(L, cJSON_GetArrayItem(key, 2), v) != 0) {
                rc = -1;
                break;
            }
            set_path(L->path, &L->plen, at3);
        }
        push_index(L, 1);
        if (key_value(L, cJSON_GetArrayItem(key, 1), c, v + lead) != 0) {
            rc = -1;
            break;
        }
        set_path(L->path, &L->plen, at3);
        if (cs_scene_add_key(L->scene, t, v, &e) != CS_OK) {
            rc = key_core_error(L, &e, t, prev);
            break;
        }
        prev = t;
        pop(L, at2);
        i++;
    }
    free(v);
    if (rc != 0)
        return rc;
    pop(L, at);
    return 0;
}

/* The "animate" member of obj: the track names allowed there and what each animates. */
typedef struct track_name {
    const char *name;
    track_ctx ctx;
} track_name;

static int load_animate(loader *L, const cJSON *obj, const track_name *names, int n,
                        const char *owner)
{
    const cJSON *anim = member(obj, "animate");
    if (anim == NULL)
        return 0;
    size_t at = push_key(L, "animate");
    if (!cJSON_IsObject(anim))
        return fail(L, "expected an object of tracks, got %s", kind(anim));
    const cJSON *t;
    cJSON_ArrayForEach(t, anim)
    {
        int k = 0;
        while (k < n && strcmp(t->string, names[k].name) != 0)
            k++;
        if (k == n) {
            char allowed[96] = "";
            for (int i = 0; i < n; i++)
                snprintf(allowed + strlen(allowed), sizeof allowed - strlen(allowed), "%s\"%s\"",
                         i == 0 ? "" : i == n - 1 ? " and " : ", ", names[i].name);
            push_key(L, t->string);
            return fail(L, "unknown track: %s animates %s", owner, allowed);
        }
        size_t at2 = push_key(L, t->string);
        if (load_track(L, t, &names[k].ctx) != 0)
            return -1;
        pop(L, at2);
    }
    pop(L, at);
    return 0;
}

/* A cel's tracks, after the cel (scene->cels[cel]) was added. */
static int cel_animate(loader *L, const cJSON *cel_json, uint32_t cel)
{
    const cs_cel *c = &L->scene->cels[cel];
    track_name names[3] = {{"transform", {CS_TRACK_TRANSFORM, cel, {0}, NULL, 0}},
                           {"lights", {CS_TRACK_CEL_LIGHTS, cel, {0}, NULL, 0}},
                           {"trs", {CS_TRACK_TRS, cel, {0}, NULL, 0}}};
    for (int k = 0; k < 3; k++) {
        names[1].ctx.defaults[k] = c->front[k]; /* the stack's if the cel has none */
        names[1].ctx.defaults[3 + k] = c->back[k];
    }
    return load_animate(L, cel_json, names, 3, "a cel");
}

/* A region's paint track, after the region (the last one) was added. */
static int region_animate(loader *L, const cJSON *region_json)
{
    uint32_t ri = L->scene->region_count - 1u;
    const cs_region *r = &L->scene->regions[ri];
    bool func[3] = {r->func[0] != 0, r->func[1] != 0, r->func[2] != 0};
    track_name names[1] = {{"paint", {CS_TRACK_PAINT, ri, {0}, func, 0}}};
    for (int k = 0; k < 3; k++) {
        names[0].ctx.defaults[k] = r->paint.pigment[k];
        names[0].ctx.defaults[3 + k] = r->paint.medium[k];
    }
    names[0].ctx.defaults[6] = r->paint.beta;
    return load_animate(L, region_json, names, 1, "a region");
}

/* A contour's points track, after the contour (the last one) was added. */
static int contour_animate(loader *L, const cJSON *contour_json)
{
    uint32_t ci = L->scene->contour_count - 1u;
    track_name names[1] = {
        {"points", {CS_TRACK_POINTS, ci, {0}, NULL, L->scene->contours[ci].point_count}}};
    return load_animate(L, contour_json, names, 1, "a contour");
}

/* The scene's own tracks: stack lights and the background card. */
static int scene_animate(loader *L, const cJSON *root)
{
    const cs_scene *s = L->scene;
    track_name names[2] = {{"lights", {CS_TRACK_STACK_LIGHTS, 0, {0}, NULL, 0}},
                           {"background", {CS_TRACK_BACKGROUND, 0, {0}, NULL, 0}}};
    for (int k = 0; k < 3; k++) {
        names[0].ctx.defaults[k] = s->stack_front[k];
        names[0].ctx.defaults[3 + k] = s->stack_back[k];
    }
    const cJSON *anim = member(root, "animate");
    if (cJSON_IsObject(anim) && member(anim, "background") != NULL && !s->has_background) {
        push_key(L, "animate");
        push_key(L, "background");
        return fail(L, "the canvas has no background to animate (give canvas.background)");
    }
    return load_animate(L, root, names, 2, "the scene");
}

/* ------------------------------------------------------------ structure */

static int grow_scratch(loader *L, size_t n)
{
    if (n <= L->cap)
        return 0;
    cs_point *p = realloc(L->pts, n * sizeof *p);
    if (p == NULL)
        return fail(L, "out of memory for %zu points", n);
    L->pts = p;
    float *f = realloc(L->ivs, n * sizeof *f);
    if (f == NULL)
        return fail(L, "out of memory for %zu points", n);
    L->ivs = f;
    L->cap = n;
    return 0;
}

/* Turns a core error on the contour being added into the path of its cause. */
static int contour_core_error(loader *L, const cs_error *e, int degree, int count)
{
    const char *msg = cs_status_str(e->status);
    switch (e->status) {
    case CS_ERR_DEGREE:
        push_key(L, "degree");
        return fail(L, "%s, got %d", msg, degree);
    case CS_ERR_TOO_FEW_POINTS:
        push_key(L, "points");
        return fail(L, "%s (degree %d needs %d, got %d)", msg, degree, degree + 1, count);
    case CS_ERR_INTERVAL:
    case CS_ERR_ZERO_RUN:
    case CS_ERR_DEGENERATE:
        push_key(L, "intervals");
        if (e->item >= 0 && e->status != CS_ERR_DEGENERATE)
            push_index(L, e->item);
        return fail(L, "%s", msg);
    case CS_ERR_NONFINITE:
    case CS_ERR_RANGE:
    case CS_ERR_WEIGHT:
        if (e->item >= 0 && e->item < count) {
            push_key(L, "points");
            push_index(L, e->item);
        }
        return fail(L, "%s", msg);
    default:
        return fail(L, "%s", msg);
    }
}

static int load_contour(loader *L, const cJSON *c)
{
    if (!cJSON_IsObject(c))
        return fail(L, "expected a contour {\"degree\", \"points\", \"intervals\"}, got %s",
                    kind(c));
    float degf = 0.0f;
    if (member_float(L, c, "degree", true, &degf) != 0)
        return -1;
    /* The range first: converting a float beyond int's range is undefined. */
    if (!(degf >= 0.0f && degf <= 64.0f) || degf != (float)(int)degf) {
        push_key(L, "degree");
        return fail(L, "degree must be an integer 1, 2 or 3, got %g", (double)degf);
    }
    int degree = (int)degf;

    const cJSON *points;
    if (require_array(L, c, "points", &points) != 0)
        return -1;
    int count = cJSON_GetArraySize(points);
    if (grow_scratch(L, count > 0 ? (size_t)count : 1) != 0)
        return -1;
    size_t at = push_key(L, "points");
    int i = 0;
    const cJSON *p;
    cJSON_ArrayForEach(p, points)
    {
        size_t at2 = push_index(L, i);
        int n = cJSON_IsArray(p) ? cJSON_GetArraySize(p) : 0;
        if (n != 2 && n != 3) {
            if (cJSON_IsArray(p))
                return fail(L, "expected a point [x,y] or [x,y,w], got %d numbers", n);
            return fail(L, "expected a point [x,y] or [x,y,w], got %s", kind(p));
        }
        float v[3] = {0.0f, 0.0f, 1.0f};
        if (get_floats(L, p, v, n, n == 2 ? "[x,y]" : "[x,y,w]") != 0)
            return -1;
        L->pts[i] = (cs_point){v[0], v[1], v[2]};
        pop(L, at2);
        i++;
    }
    pop(L, at);

    const cJSON *ivs = member(c, "intervals");
    if (ivs != NULL) {
        at = push_key(L, "intervals");
        if (!cJSON_IsArray(ivs))
            return fail(L, "expected an array of knot intervals, got %s", kind(ivs));
        if (cJSON_GetArraySize(ivs) != count)
            return fail(L, "expected %d knot intervals (one per point), got %d", count,
                        cJSON_GetArraySize(ivs));
        i = 0;
        const cJSON *v;
        cJSON_ArrayForEach(v, ivs)
        {
            size_t at2 = push_index(L, i);
            if (get_float(L, v, &L->ivs[i]) != 0)
                return -1;
            pop(L, at2);
            i++;
        }
        pop(L, at);
    }

    cs_error e;
    if (cs_scene_add_contour(L->scene, degree, count, L->pts, ivs ? L->ivs : NULL, &e) != CS_OK)
        return contour_core_error(L, &e, degree, count);
    return 0;
}

/* Passes on a message from paint_json, which already names the JSON path. */
static int fail_with(loader *L, const char *msg)
{
    if (L->errlen > 0)
        snprintf(L->err, L->errlen, "%s: %s", L->name, msg);
    return -1;
}

static int load_region(loader *L, const cJSON *r)
{
    if (!cJSON_IsObject(r))
        return fail(L, "expected a region object, got %s", kind(r));
    cs_fill_rule rule = CS_FILL_NONZERO;
    const cJSON *fr = member(r, "fill_rule");
    if (fr != NULL) {
        size_t at = push_key(L, "fill_rule");
        if (!cJSON_IsString(fr))
            return fail(L, "expected \"nonzero\" or \"evenodd\", got %s", kind(fr));
        if (strcmp(fr->valuestring, "nonzero") == 0)
            rule = CS_FILL_NONZERO;
        else if (strcmp(fr->valuestring, "evenodd") == 0)
            rule = CS_FILL_EVENODD;
        else
            return fail(L, "fill rule must be \"nonzero\" or \"evenodd\", got \"%.40s\"",
                        fr->valuestring);
        pop(L, at);
    }
    /* Paints (constants or functions of position) and CSG: paint_json.c. */
    const cJSON *pn = member(r, "paint");
    if (pn == NULL) {
        push_key(L, "paint");
        return fail(L, "missing (required object {\"pigment\", \"medium\", \"beta\"})");
    }
    paint_json paint;
    paint_json_csg csg;
    char msg[512];
    if (paint_json_parse(pn, L->path, &paint, msg, sizeof msg) != 0 ||
        paint_json_parse_csg(r, L->path, &csg, msg, sizeof msg) != 0)
        return fail_with(L, msg);
    const cJSON *contours;
    if (require_array(L, r, "contours", &contours) != 0)
        return -1;
    if (paint_json_add_region(L->scene, rule, &paint, &csg, L->path, msg, sizeof msg) != 0)
        return fail_with(L, msg);
    size_t at = push_key(L, "contours");
    int i = 0;
    const cJSON *c;
    cJSON_ArrayForEach(c, contours)
    {
        size_t at2 = push_index(L, i);
        if (load_contour(L, c) != 0)
            return -1;
        pop(L, at2);
        if (paint_json_set_operand(L->scene, &csg, i, L->path, msg, sizeof msg) != 0)
            return fail_with(L, msg);
        size_t at3 = push_index(L, i);
        if (contour_animate(L, c) != 0)
            return -1;
        pop(L, at3);
        i++;
    }
    pop(L, at);
    return region_animate(L, r);
}

static int load_cel(loader *L, const cJSON *cel)
{
    if (!cJSON_IsObject(cel))
        return fail(L, "expected a cel object, got %s", kind(cel));
    const cJSON *name = member(cel, "name");
    if (name != NULL && !cJSON_IsString(name)) {
        push_key(L, "name");
        return fail(L, "expected a string, got %s", kind(name));
    }
    cs_affine m = {1.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f};
    const cJSON *tr = member(cel, "transform");
    if (tr != NULL) {
        size_t at = push_key(L, "transform");
        float v[6];
        if (get_floats(L, tr, v, 6, "a transform [a,b,c,d,e,f]") != 0)
            return -1;
        m = (cs_affine){v[0], v[1], v[2], v[3], v[4], v[5]};
        pop(L, at);
    }
    float front[3], back[3];
    bool has_front, has_back;
    if (get_lights(L, cel, front, &has_front, back, &has_back) != 0)
        return -1;
    const cJSON *regions;
    if (require_array(L, cel, "regions", &regions) != 0)
        return -1;

    cs_error e;
    if (cs_scene_add_cel(L->scene, &m, has_front ? front : NULL, has_back ? back : NULL, &e) !=
        CS_OK) {
        if (e.item >= 0) {
            push_key(L, "transform");
            push_index(L, e.item);
        } else if (e.status == CS_ERR_NONFINITE || e.status == CS_ERR_PAINT) {
            push_key(L, "lights");
        }
        return fail(L, "%s", cs_status_str(e.status));
    }

    size_t at = push_key(L, "regions");
    int i = 0;
    const cJSON *r;
    cJSON_ArrayForEach(r, regions)
    {
        size_t at2 = push_index(L, i);
        if (load_region(L, r) != 0)
            return -1;
        pop(L, at2);
        i++;
    }
    pop(L, at);
    return cel_animate(L, cel, L->scene->cel_count - 1u);
}

static int load_root(loader *L, const cJSON *root)
{
    if (!cJSON_IsObject(root))
        return fail(L, "expected a JSON object with \"canvas\" and \"cels\", got %s", kind(root));

    const cJSON *canvas = member(root, "canvas");
    size_t at = push_key(L, "canvas");
    if (canvas == NULL)
        return fail(L, "missing (required object {\"width\", \"height\"})");
    if (!cJSON_IsObject(canvas))
        return fail(L, "expected an object {\"width\", \"height\", \"background\"}, got %s",
                    kind(canvas));
    float w = 0.0f, h = 0.0f;
    if (member_float(L, canvas, "width", true, &w) != 0 ||
        member_float(L, canvas, "height", true, &h) != 0)
        return -1;
    if (!(w > 0.0f)) {
        push_key(L, "width");
        return fail(L, "width must be > 0, got %g", (double)w);
    }
    if (!(h > 0.0f)) {
        push_key(L, "height");
        return fail(L, "height must be > 0, got %g", (double)h);
    }
    cs_status st = cs_scene_init(L->scene, w, h);
    if (st != CS_OK)
        return fail(L, "%s", cs_status_str(st));
    float bg[3];
    if (member(canvas, "background") != NULL) {
        if (member_colour(L, canvas, "background", bg) != 0)
            return -1;
        st = cs_scene_set_background(L->scene, bg);
        if (st != CS_OK) {
            push_key(L, "background");
            return fail(L, "%s", cs_status_str(st));
        }
    }
    /* "blend": "srgb" asks for SVG-like blending (imported artwork does). */
    const cJSON *blend = member(canvas, "blend");
    if (blend != NULL) {
        size_t at_blend = push_key(L, "blend");
        if (!cJSON_IsString(blend) ||
            (strcmp(blend->valuestring, "linear") != 0 && strcmp(blend->valuestring, "srgb") != 0))
            return fail(L, "expected \"linear\" or \"srgb\", got %s",
                        cJSON_IsString(blend) ? blend->valuestring : kind(blend));
        cs_scene_set_blend(L->scene, strcmp(blend->valuestring, "srgb") == 0 ? CS_BLEND_SRGB
                                                                           : CS_BLEND_LINEAR);
        pop(L, at_blend);
    }
    /* "epoch": seconds since 1970 UTC at animation time 0, for boards on the wall clock */
    const cJSON *epoch = member(canvas, "epoch");
    if (epoch != NULL) {
        size_t at_epoch = push_key(L, "epoch");
        /* up to 2262 (ns since 1970 in 63 bits); double keeps the ns to ~0.3 us */
        if (!cJSON_IsNumber(epoch) || !(epoch->valuedouble > 0.0 && epoch->valuedouble < 9.2e9))
            return fail(L, "expected seconds since 1970 UTC in (0, 9.2e9), got %s",
                        cJSON_IsNumber(epoch) ? "a number out of range" : kind(epoch));
        cs_scene_set_epoch(L->scene, (uint64_t)(epoch->valuedouble * 1e9));
        pop(L, at_epoch);
    }
    pop(L, at);

    float front[3] = {1.0f, 1.0f, 1.0f}, back[3] = {0.0f, 0.0f, 0.0f};
    bool has_front, has_back;
    if (get_lights(L, root, front, &has_front, back, &has_back) != 0)
        return -1;
    st = cs_scene_set_lights(L->scene, front, back);
    if (st != CS_OK) {
        push_key(L, "lights");
        return fail(L, "%s", cs_status_str(st));
    }

    const cJSON *cels;
    if (require_array(L, root, "cels", &cels) != 0)
        return -1;
    at = push_key(L, "cels");
    int i = 0;
    const cJSON *cel;
    cJSON_ArrayForEach(cel, cels)
    {
        size_t at2 = push_index(L, i);
        if (load_cel(L, cel) != 0)
            return -1;
        pop(L, at2);
        i++;
    }
    /* Groups once every cel exists: a parent may come after its child. */
    i = 0;
    cJSON_ArrayForEach(cel, cels)
    {
        const cJSON *parent = member(cel, "parent");
        if (parent != NULL) {
            size_t at2 = push_index(L, i);
            push_key(L, "parent");
            if (!cJSON_IsNumber(parent) || parent->valuedouble != (double)(int)parent->valuedouble ||
                parent->valuedouble < 0 || parent->valuedouble >= (double)L->scene->cel_count)
                return fail(L, "expected the index of another cel (0..%u)",
                            L->scene->cel_count - 1u);
            cs_error e;
            if (cs_scene_set_cel_parent(L->scene, (uint32_t)i, (uint32_t)parent->valueint, &e) !=
                CS_OK)
                return fail(L, "%s", cs_status_str(e.status));
            pop(L, at2);
        }
        i++;
    }
    pop(L, at);
    return scene_animate(L, root);
}

/* ----------------------------------------------------------------- API */

int scene_json_load_tree(const cJSON *root, const char *name, cs_scene *out, char *errbuf,
                         size_t errlen)
{
    loader L = {.name = name ? name : "scene", .err = errbuf, .errlen = errlen, .scene = out};
    if (errlen > 0)
        errbuf[0] = '\0';
    int rc = load_root(&L, root);
    free(L.pts);
    free(L.ivs);
    return rc;
}

/* Line and column (1-based) of byte offset `off`, for syntax errors. */
static void line_col(const char *text, size_t off, int *line, int *col)
{
    *line = 1;
    *col = 1;
    for (size_t i = 0; i < off && text[i]; i++) {
        if (text[i] == '\n') {
            (*line)++;
            *col = 1;
        } else {
            (*col)++;
        }
    }
}

int scene_json_load_string(const char *text, size_t len, const char *name, cs_scene *out,
                           char *errbuf, size_t errlen)
{
    if (name == NULL)
        name = "scene";
    if (errlen > 0)
        errbuf[0] = '\0';
    /* cJSON wants the terminating NUL inside the length to reject trailing
     * garbage, and `text` need not be terminated: parse a terminated copy. */
    char *buf = malloc(len + 1);
    if (buf == NULL) {
        snprintf(errbuf, errlen, "%s: out of memory", name);
        return -1;
    }
    memcpy(buf, text, len);
    buf[len] = '\0';
    size_t nul = strlen(buf);
    if (nul != len) {
        int line, col;
        line_col(buf, nul, &line, &col);
        snprintf(errbuf, errlen, "%s:%d:%d: NUL byte in JSON text (offset %zu)", name, line, col,
                 nul);
        free(buf);
        return -1;
    }
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithLengthOpts(buf, len + 1, &end, 1);
    if (root == NULL) {
        size_t off = end && end >= buf && end <= buf + len ? (size_t)(end - buf) : 0;
        int line, col;
        line_col(buf, off, &line, &col);
        /* Show a little of the text where parsing stopped, on one line. */
        char near[24];
        size_t k = 0;
        for (size_t i = off; i < len && k + 1 < sizeof near && buf[i] != '\n'; i++)
            near[k++] = buf[i];
        near[k] = '\0';
        if (off >= len)
            snprintf(errbuf, errlen, "%s:%d:%d: JSON syntax error: unexpected end of input",
                     name, line, col);
        else
            snprintf(errbuf, errlen, "%s:%d:%d: JSON syntax error near '%s'", name, line, col,
                     near);
        free(buf);
        return -1;
    }
    int rc = scene_json_load_tree(root, name, out, errbuf, errlen);
    cJSON_Delete(root);
    free(buf);
    return rc;
}

int scene_json_load(const char *path, cs_scene *out, char *errbuf, size_t errlen)
{
    if (errlen > 0)
        errbuf[0] = '\0';
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        snprintf(errbuf, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    char *text = NULL;
    size_t len = 0, cap = 0;
    for (;;) {
        if (len == cap) {
            cap = cap ? cap * 2 : 65536;
            char *t = realloc(text, cap);
            if (t == NULL) {
                snprintf(errbuf, errlen, "%s: out of memory reading the file", path);
                free(text);
                fclose(f);
                return -1;
            }
            text = t;
        }
        size_t n = fread(text + len, 1, cap - len, f);
        len += n;
        if (n == 0)
            break;
    }
    int bad = ferror(f);
    int saved = errno;
    fclose(f);
    if (bad) {
        snprintf(errbuf, errlen, "%s: cannot read: %s", path, strerror(saved));
        free(text);
        return -1;
    }
    int rc = scene_json_load_string(text, len, path, out, errbuf, errlen);
    free(text);
    return rc;
}

void scene_json_describe_error(const cs_error *e, char *buf, size_t len)
{
    char path[PATH_CAP];
    size_t plen = 0;
    path[0] = '\0';
#define APPEND(...)                                                                                \
    do {                                                                                           \
        int n_ = snprintf(path + plen, sizeof path - plen, __VA_ARGS__);                           \
        if (n_ > 0 && plen + (size_t)n_ < sizeof path)                                             \
            plen += (size_t)n_;                                                                    \
    } while (0)
    if (e->cel >= 0) {
        APPEND("cels[%d]", (int)e->cel);
        if (e->region >= 0) {
            APPEND(".regions[%d]", (int)e->region);
            if (e->contour >= 0) {
                APPEND(".contours[%d]", (int)e->contour);
                if (e->item >= 0) {
                    bool iv = e->status == CS_ERR_INTERVAL || e->status == CS_ERR_ZERO_RUN;
                    APPEND(".%s[%d]", iv ? "intervals" : "points", (int)e->item);
                }
            }
        } else if (e->item >= 0) {
            APPEND(".transform[%d]", (int)e->item);
        }
    }
#undef APPEND
    if (plen > 0)
        snprintf(buf, len, "%s: %s", path, cs_status_str(e->status));
    else
        snprintf(buf, len, "%s", cs_status_str(e->status));
}
