/*
 * lt_track.c - sampled values back into keyframe tracks.
 *
 * The importer samples every value it maps (a cel's TRS, a region's paint,
 * a contour's control points) at every frame, because a value may depend
 * on several Lottie properties keyed at different frames with different
 * easings. This file turns the samples back into few keys:
 *
 *   - between two breaks (frames where a Lottie property has a keyframe),
 *     samples that stay put and then jump are a hold key;
 *   - samples that one of the Lottie easings seen on the value's properties
 *     reproduces, v(n) = v(a) + E((n - a) / (b - a)) (v(b) - v(a)) within
 *     the tolerance at every frame, are one cubic key with that easing:
 *     the common case of one animated property gives back its own keys;
 *   - anything else is cut into linear keys, each as long as every sample
 *     in between lies within the tolerance of the line.
 *
 * Every check is against the samples, so a key is never trusted to
 * reproduce what it was not seen to reproduce, and every frame the player
 * shows is within the tolerance.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lt_internal.h"

void lt_signal_init(lt_signal *s, int nframes, int width, double tol)
{
    memset(s, 0, sizeof *s);
    s->nframes = nframes;
    s->width = width;
    s->tol = tol;
    s->v = calloc((size_t)nframes * (size_t)(width ? width : 1), sizeof *s->v);
}

void lt_signal_free(lt_signal *s)
{
    free(s->v);
    free(s->breaks);
    free(s->eases);
    memset(s, 0, sizeof *s);
}

void lt_signal_break(lt_signal *s, double n)
{
    if (n > s->nframes - 1 && (s->tail == 0 || n < s->tail))
        s->tail = n;
    if (!(n > 0 && n < s->nframes - 1))
        return;
    for (int i = 0; i < s->nbreaks; i++)
        if (s->breaks[i] == n)
            return;
    double *b = realloc(s->breaks, (size_t)(s->nbreaks + 1) * sizeof *b);
    if (!b)
        return; /* a missing break only costs keys */
    s->breaks = b;
    int i = s->nbreaks++;
    while (i > 0 && s->breaks[i - 1] > n) {
        s->breaks[i] = s->breaks[i - 1];
        i--;
    }
    s->breaks[i] = n;
}

static void add_ease(lt_signal *s, const double *e)
{
    if (e[1] < -2 || e[1] > 3 || e[3] < -2 || e[3] > 3)
        return; /* beyond what a core key holds: linear keys instead */
    for (int i = 0; i < s->neases; i++)
        if (memcmp(s->eases[i], e, sizeof s->eases[i]) == 0)
            return;
    if (s->neases >= 64)
        return;
    double (*q)[4] = realloc(s->eases, (size_t)(s->neases + 1) * sizeof *q);
    if (!q)
        return;
    s->eases = q;
    memcpy(s->eases[s->neases++], e, sizeof *q);
}

void lt_signal_note_prop(lt_signal *s, const lt_prop *p, double f0, double fscale)
{
    if (p->split) {
        lt_signal_note_prop(s, p->sx, f0, fscale);
        lt_signal_note_prop(s, p->sy, f0, fscale);
        return;
    }
    if (p->nkeys < 2 || fscale == 0)
        return;
    for (int k = 0; k < p->nkeys && s->nbreaks < 4096; k++) {
        const lt_key *q = &p->keys[k];
        lt_signal_break(s, (q->t - f0) / fscale);
        if (k + 1 < p->nkeys && !q->hold) {
            double e[4] = {q->ox[0], q->oy[0], q->ix[0], q->iy[0]};
            add_ease(s, e);
        }
    }
}

static const double *frame(const lt_signal *s, int n) { return s->v + (size_t)n * s->width; }

static bool same(const lt_signal *s, const double *a, const double *b)
{
    for (int k = 0; k < s->width; k++)
        if (fabs(a[k] - b[k]) > s->tol)
            return false;
    return true;
}

bool lt_signal_static(const lt_signal *s)
{
    for (int n = 1; n < s->nframes; n++)
        if (!same(s, frame(s, 0), frame(s, n)))
            return false;
    return true;
}

/* Whether easing e (NULL: linear) carries the samples from a to b. */
static bool eases_through(const lt_signal *s, int a, int b, const double *e)
{
    const double *va = frame(s, a), *vb = frame(s, b);
    for (int n = a + 1; n < b; n++) {
        double u = (double)(n - a) / (b - a), w = e ? lt_ease(e, u) : u;
        const double *v = frame(s, n);
        for (int k = 0; k < s->width; k++)
            if (fabs(va[k] + w * (vb[k] - va[k]) - v[k]) > s->tol)
                return false;
    }
    return true;
}

/* Whether the samples hold v(a) from a to b - 1. */
static bool holds(const lt_signal *s, int a, int b)
{
    for (int n = a + 1; n < b; n++)
        if (!same(s, frame(s, a), frame(s, n)))
            return false;
    return !same(s, frame(s, a), frame(s, b));
}

/*
 * The last stretch, from a to the end of the samples, when its keyframe
 * lies beyond them (a composition whose last keyframe is at its out point
 * shows frames up to op - 1 only): easing e from a to s->tail, with the
 * end value that the last sample implies, carries every sample from a.
 * The end value goes into vt. A key past the last frame is never shown;
 * it only lets one cubic key stand for the stretch.
 */
static bool eases_to_tail(const lt_signal *s, int a, const double *e, double *vt)
{
    int last = s->nframes - 1;
    double span = s->tail - a, wl = lt_ease(e, (last - a) / span);
    if (s->tail != floor(s->tail) || last - a < 2 || !(fabs(wl) > 0.05))
        return false;
    const double *va = frame(s, a), *vl = frame(s, last);
    for (int k = 0; k < s->width; k++)
        vt[k] = va[k] + (vl[k] - va[k]) / wl;
    for (int n = a + 1; n <= last; n++) {
        double w = lt_ease(e, (n - a) / span);
        const double *v = frame(s, n);
        for (int k = 0; k < s->width; k++)
            if (fabs(va[k] + w * (vt[k] - va[k]) - v[k]) > s->tol)
                return false;
    }
    return true;
}

typedef struct key_out {
    int frame;
    int kind; /* 0 linear, 1 cubic (ease), 2 hold */
    double ease[4];
} key_out;

cJSON *lt_signal_track(const lt_signal *s, double fr,
                       cJSON *(*value_fn)(const double *v, int width))
{
    if (s->nframes < 1 || lt_signal_static(s))
        return NULL;
    key_out *keys = calloc((size_t)s->nframes + 1, sizeof *keys);
    if (!keys)
        return NULL;
    double *vt = malloc((size_t)(s->width ? s->width : 1) * sizeof *vt);
    if (!vt) {
        free(keys);
        return NULL;
    }
    bool to_tail = false;
    int nk = 0;
    /* Stretches between breaks on whole frames; others are cut linearly. */
    int a = 0;
    int bi = 0;
    bool rest_still = false;
    while (a < s->nframes - 1) {
        /* Nothing moves from here on: the last key holds it. */
        rest_still = true;
        for (int n = a + 1; n < s->nframes && rest_still; n++)
            rest_still = same(s, frame(s, a), frame(s, n));
        if (rest_still)
            break;
        while (bi < s->nbreaks && s->breaks[bi] <= a)
            bi++;
        int b = s->nframes - 1;
        bool whole = true;
        if (bi < s->nbreaks) {
            double nb = s->breaks[bi];
            whole = nb == floor(nb);
            b = whole ? (int)nb : (int)ceil(nb);
        }
        key_out *k = &keys[nk];
        k->frame = a;
        if (whole && holds(s, a, b)) {
            k->kind = 2;
            nk++;
            a = b;
            continue;
        }
        bool done = false;
        if (bi >= s->nbreaks && s->tail > 0)
            for (int e = 0; e < s->neases && !to_tail; e++)
                if (eases_to_tail(s, a, s->eases[e], vt)) {
                    k->kind = 1;
                    memcpy(k->ease, s->eases[e], sizeof k->ease);
                    to_tail = true;
                }
        if (to_tail) {
            nk++;
            a = s->nframes - 1;
            break;
        }
        if (whole && b - a > 1) {
            if (eases_through(s, a, b, NULL)) {
                k->kind = 0;
                done = true;
            }
            for (int e = 0; e < s->neases && !done; e++)
                if (eases_through(s, a, b, s->eases[e])) {
                    k->kind = 1;
                    memcpy(k->ease, s->eases[e], sizeof k->ease);
                    done = true;
                }
        } else if (b - a == 1) {
            done = true;
            k->kind = 0;
        }
        if (done) {
            nk++;
            a = b;
            continue;
        }
        /* Linear pieces, each as long as the samples allow, up to b. */
        int end = a + 1;
        while (end < b && eases_through(s, a, end + 1, NULL))
            end++;
        k->kind = 0;
        nk++;
        a = end;
    }
    keys[nk].frame = rest_still ? a : s->nframes - 1;
    keys[nk].kind = 0;
    nk++;
    /* Keys that repeat their neighbours' value with linear segments are dropped. */
    bool cubic = false;
    for (int i = 0; i < nk; i++)
        cubic = cubic || keys[i].kind != 0;
    cJSON *track = cJSON_CreateObject(), *arr = cJSON_AddArrayToObject(track, "keys");
    for (int i = 0; i < nk; i++) {
        const key_out *k = &keys[i];
        cJSON *key = cJSON_CreateArray();
        bool tail_key = to_tail && i + 1 == nk;
        cJSON_AddItemToArray(key, cJSON_CreateNumber((tail_key ? s->tail : k->frame) / fr));
        cJSON_AddItemToArray(key, value_fn(tail_key ? vt : frame(s, k->frame), s->width));
        if (i + 1 < nk && k->kind == 1)
            cJSON_AddItemToArray(key, lt_num_array(k->ease, 4));
        else if (i + 1 < nk && k->kind == 2)
            cJSON_AddItemToArray(key, cJSON_CreateString("hold"));
        cJSON_AddItemToArray(arr, key);
    }
    if (cubic)
        cJSON_AddStringToObject(track, "ease", "cubic");
    free(keys);
    free(vt);
    return track;
}
