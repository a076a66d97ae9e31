/*
 * lt_import.c - the Lottie importer's entry: recognition, the composition's
 * frames, errors, warnings and the work budget (lt.h).
 *
 * The scene's time t shows Lottie frame ip + t fr of the main composition,
 * as rlottie's frame index n = t fr does; the importer samples frames ip ..
 * op - 1 (what rlottie offers) and writes the canvas at the file's w x h,
 * with sRGB blending ("canvas": {"blend": "srgb"}) since Lottie players
 * composite encoded values. The canvas has no background: Lottie frames are
 * transparent where nothing is drawn.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lt_internal.h"

int lt_fail(lt_ctx *c, const char *fmt, ...)
{
    if (!c->failed) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(c->err, c->errlen, fmt, ap);
        va_end(ap);
        c->failed = true;
    }
    return -1;
}

static const char *const feature_names[LT_F_COUNT_] = {
    "expressions", "effects", "text", "images", "merge paths", "3D layers", "repeaters",
    "round corners", "track mattes", "masks", "auto-orient", "polystar points",
    "animated outlines", "gradients", "blend modes", "other"};

void lt_warn(lt_ctx *c, lt_feature f, const char *fmt, ...)
{
    if ((c->warned >> f) & 1u || !c->warnings)
        return;
    c->warned |= 1u << f;
    char buf[300];
    int k = snprintf(buf, sizeof buf, "%s: ", feature_names[f]);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf + k, sizeof buf - (size_t)k, fmt, ap);
    va_end(ap);
    char **t = realloc(c->warnings->text, (size_t)(c->warnings->n + 1) * sizeof *t);
    if (!t)
        return;
    c->warnings->text = t;
    t[c->warnings->n] = strdup(buf);
    if (t[c->warnings->n])
        c->warnings->n++;
}

void lt_warnings_free(lt_warnings *w)
{
    for (int i = 0; i < w->n; i++)
        free(w->text[i]);
    free(w->text);
    w->n = 0;
    w->text = NULL;
}

bool lt_charge(lt_ctx *c, double n)
{
    c->work += n;
    if (c->work > c->max_work) {
        lt_fail(c, "the animation needs more than %.0f sampled values (frames x shapes): refused",
                c->max_work);
        return false;
    }
    return true;
}

int lt_num(lt_ctx *c, const cJSON *obj, const char *key, double lo, double hi, double dflt,
           double *out)
{
    const cJSON *j = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (j == NULL) {
        *out = dflt;
        return 0;
    }
    if (cJSON_IsBool(j)) {
        *out = cJSON_IsTrue(j) ? 1 : 0;
        return 0;
    }
    if (!cJSON_IsNumber(j) || !isfinite(j->valuedouble) || j->valuedouble < lo ||
        j->valuedouble > hi)
        return lt_fail(c, "\"%s\" must be a number in %g..%g", key, lo, hi);
    *out = j->valuedouble;
    return 0;
}

bool lt_is_lottie(const cJSON *root)
{
    static const char *const keys[] = {"v", "fr", "ip", "op", "layers"};
    if (!cJSON_IsObject(root))
        return false;
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
        if (!cJSON_GetObjectItemCaseSensitive(root, keys[i]))
            return false;
    return true;
}

cJSON *lt_import(const cJSON *root, const lt_opts *opts, lt_warnings *warnings, char *err,
                 size_t errlen)
{
    lt_ctx c;
    memset(&c, 0, sizeof c);
    c.root = root;
    c.err = err;
    c.errlen = errlen;
    c.warnings = warnings;
    if (errlen)
        err[0] = '\0';
    if (!lt_is_lottie(root)) {
        lt_fail(&c, "not a Lottie file (needs \"v\", \"fr\", \"ip\", \"op\" and \"layers\")");
        return NULL;
    }
    if (lt_num(&c, root, "fr", 0.01, 1000, 30, &c.fr) || lt_num(&c, root, "ip", -1e6, 1e6, 0, &c.ip) ||
        lt_num(&c, root, "op", -1e6, 1e6, 0, &c.op) || lt_num(&c, root, "w", 1, 1e5, 512, &c.w) ||
        lt_num(&c, root, "h", 1, 1e5, 512, &c.h))
        return NULL;
    /* rlottie rounds ip and op to whole frames and shows ip .. op - 1. */
    double ip = round(c.ip), op = round(c.op);
    if (!(op > ip)) {
        lt_fail(&c, "out point %g is not after in point %g", c.op, c.ip);
        return NULL;
    }
    int max_frames = opts && opts->max_frames > 0 ? opts->max_frames : LT_MAX_FRAMES;
    c.max_work = opts && opts->max_work > 0 ? opts->max_work : LT_MAX_WORK;
    if (op - ip > max_frames) {
        lt_fail(&c, "%g frames, more than %d", op - ip, max_frames);
        return NULL;
    }
    c.nframes = (int)(op - ip);
    double diag = fmax(c.w, c.h);
    c.tolerance = opts && opts->tolerance > 0 ? opts->tolerance : 0.01 * diag / 1024;
    c.assets = cJSON_GetObjectItemCaseSensitive(root, "assets");
    const cJSON *chars = cJSON_GetObjectItemCaseSensitive(root, "chars");
    if (cJSON_IsArray(chars) && cJSON_GetArraySize(chars) > 0)
        lt_warn(&c, LT_F_TEXT, "glyphs (\"chars\") are not read: text layers are not drawn");
    double *frames = malloc((size_t)c.nframes * sizeof *frames);
    if (!frames) {
        lt_fail(&c, "out of memory");
        return NULL;
    }
    for (int n = 0; n < c.nframes; n++)
        frames[n] = ip + n;
    cJSON *scene = cJSON_CreateObject();
    cJSON *canvas = cJSON_AddObjectToObject(scene, "canvas");
    cJSON_AddNumberToObject(canvas, "width", c.w);
    cJSON_AddNumberToObject(canvas, "height", c.h);
    cJSON_AddStringToObject(canvas, "blend", "srgb");
    c.cels = cJSON_AddArrayToObject(scene, "cels");
    lt_time tm = {c.nframes, frames, ip, 1, NULL};
    int rc = lt_layers(&c, cJSON_GetObjectItemCaseSensitive(root, "layers"), &tm, -1);
    free(frames);
    if (rc != 0 || c.failed) {
        if (!c.failed)
            lt_fail(&c, "import failed");
        cJSON_Delete(scene);
        return NULL;
    }
    return scene;
}
