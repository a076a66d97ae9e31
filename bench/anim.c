/*
 * anim.c - plays the "animate" transform tracks of a scene file.
 *
 * The JSON loader (host-sim/scene_json.c) checks the shape of a cel's
 * "animate" object but does not apply it: animation belongs to the cel
 * stream, which is not written yet. The Animation benchmark needs time to
 * move, so this file reads the transform tracks itself and sets the cels'
 * transforms in the loaded cs_scene before each frame, as DESIGN.md
 * describes them: keys [t, [a,b,c,d,e,f]], values held before the first and
 * after the last key, interpolated component-wise in between, "linear" or
 * "smooth" (smoothstep, 3s^2 - 2s^3) easing. Lights tracks are not played
 * (the benchmark scenes have none).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "bench.h"

typedef struct track {
    uint32_t cel;
    bool smooth;
    int count;
    double *t;      /* count key times */
    double (*m)[6]; /* count transforms */
} track;

struct anim {
    track *tracks;
    int count;
};

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) {
        free(buf);
        buf = NULL;
    }
    fclose(f);
    if (buf) {
        buf[n] = '\0';
        *len = (size_t)n;
    }
    return buf;
}

anim *anim_load(const char *path, const cs_scene *scene)
{
    size_t len;
    char *text = slurp(path, &len);
    if (!text)
        return NULL;
    cJSON *root = cJSON_ParseWithLength(text, len);
    free(text);
    const cJSON *cels = cJSON_GetObjectItemCaseSensitive(root, "cels");
    anim *a = calloc(1, sizeof *a);
    int n = cJSON_GetArraySize(cels);
    a->tracks = calloc((size_t)n + 1, sizeof *a->tracks);
    for (int ci = 0; ci < n && (uint32_t)ci < scene->cel_count; ci++) {
        const cJSON *cel = cJSON_GetArrayItem(cels, ci);
        const cJSON *tr = cJSON_GetObjectItemCaseSensitive(
            cJSON_GetObjectItemCaseSensitive(cel, "animate"), "transform");
        const cJSON *keys = cJSON_GetObjectItemCaseSensitive(tr, "keys");
        int nk = cJSON_GetArraySize(keys);
        if (nk == 0)
            continue;
        track *t = &a->tracks[a->count++];
        t->cel = (uint32_t)ci;
        const cJSON *ease = cJSON_GetObjectItemCaseSensitive(tr, "ease");
        t->smooth = cJSON_IsString(ease) && strcmp(ease->valuestring, "smooth") == 0;
        t->count = nk;
        t->t = calloc((size_t)nk, sizeof *t->t);
        t->m = calloc((size_t)nk, sizeof *t->m);
        for (int k = 0; k < nk; k++) {
            const cJSON *key = cJSON_GetArrayItem(keys, k);
            t->t[k] = cJSON_GetNumberValue(cJSON_GetArrayItem(key, 0));
            const cJSON *m = cJSON_GetArrayItem(key, 1);
            for (int q = 0; q < 6; q++)
                t->m[k][q] = cJSON_GetNumberValue(cJSON_GetArrayItem(m, q));
        }
    }
    cJSON_Delete(root);
    if (a->count == 0) {
        anim_free(a);
        return NULL;
    }
    return a;
}

void anim_free(anim *a)
{
    if (!a)
        return;
    for (int i = 0; i < a->count; i++) {
        free(a->tracks[i].t);
        free(a->tracks[i].m);
    }
    free(a->tracks);
    free(a);
}

void anim_apply(const anim *a, cs_scene *scene, double time)
{
    for (int i = 0; a && i < a->count; i++) {
        const track *t = &a->tracks[i];
        double m[6];
        int k = 0;
        while (k + 1 < t->count && t->t[k + 1] <= time)
            k++;
        if (k + 1 >= t->count || time <= t->t[0]) {
            int at = time <= t->t[0] ? 0 : t->count - 1;
            memcpy(m, t->m[at], sizeof m);
        } else {
            double s = (time - t->t[k]) / (t->t[k + 1] - t->t[k]);
            if (t->smooth)
                s = s * s * (3.0 - 2.0 * s);
            for (int q = 0; q < 6; q++)
                m[q] = t->m[k][q] + s * (t->m[k + 1][q] - t->m[k][q]);
        }
        cs_affine *dst = &scene->cels[t->cel].transform;
        dst->a = (float)m[0];
        dst->b = (float)m[1];
        dst->c = (float)m[2];
        dst->d = (float)m[3];
        dst->e = (float)m[4];
        dst->f = (float)m[5];
    }
}

uint32_t anim_static_from(const anim *a, const cs_scene *scene)
{
    /* The static run is everything behind the back-most animated cel. */
    uint32_t from = 0;
    for (int i = 0; a && i < a->count; i++)
        if (a->tracks[i].cel + 1 > from)
            from = a->tracks[i].cel + 1;
    return from < scene->cel_count ? from : scene->cel_count;
}
