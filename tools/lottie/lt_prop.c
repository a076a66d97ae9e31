/*
 * lt_prop.c - Lottie animated properties: parsing and evaluation.
 *
 * A property is {"a": 0, "k": value} or {"a": 1, "k": [keyframe, ...]}
 * (older files leave "a" out). A keyframe holds its frame "t", its value
 * "s" (and, in files before Bodymovin 5.5, the segment's end value "e"),
 * the easing of the segment to the next keyframe as the cubic Bezier
 * through (o.x, o.y) and (i.x, i.y) (per dimension when given as arrays),
 * "h": 1 for a hold, and for positions the spatial tangents "to" and "ti"
 * that bend the motion into a cubic curve travelled by arc length. This is
 * what rlottie evaluates, so frames agree with the reference player.
 * Values are checked as they are read: numbers finite and within 1e7,
 * keyframe counts and path sizes within the limits of lt_internal.h.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lt_internal.h"

#define LT_BIG 1e7

/* Reads n numbers (an array, or one number when n is 1) into out. */
static int read_vals(lt_ctx *c, const cJSON *j, int n, double *out, const char *what)
{
    if (cJSON_IsNumber(j) && n >= 1) {
        for (int k = 0; k < n; k++)
            out[k] = j->valuedouble; /* a scalar for a vector: every component (rlottie) */
    } else if (cJSON_IsArray(j)) {
        int m = cJSON_GetArraySize(j);
        if (m < 1)
            return lt_fail(c, "%s: empty value", what);
        for (int k = 0; k < n; k++) {
            const cJSON *e = cJSON_GetArrayItem(j, k < m ? k : m - 1);
            if (!cJSON_IsNumber(e))
                return lt_fail(c, "%s: expected numbers", what);
            out[k] = e->valuedouble;
        }
    } else {
        return lt_fail(c, "%s: expected a number or an array of numbers", what);
    }
    for (int k = 0; k < n; k++)
        if (!isfinite(out[k]) || fabs(out[k]) > LT_BIG)
            return lt_fail(c, "%s: value %g not finite or beyond 1e7", what, out[k]);
    return 0;
}

/* An easing handle {"x": n or [..], "y": n or [..]} into x[dims], y[dims]. */
static int read_handle(lt_ctx *c, const cJSON *h, int dims, double *x, double *y, double dx,
                       double dy, const char *what)
{
    for (int k = 0; k < dims; k++) {
        x[k] = dx;
        y[k] = dy;
    }
    if (!cJSON_IsObject(h))
        return 0;
    const cJSON *jx = cJSON_GetObjectItemCaseSensitive(h, "x");
    const cJSON *jy = cJSON_GetObjectItemCaseSensitive(h, "y");
    if (jx && read_vals(c, jx, dims, x, what) != 0)
        return -1;
    if (jy && read_vals(c, jy, dims, y, what) != 0)
        return -1;
    for (int k = 0; k < dims; k++) {
        /* rlottie clamps x into 0..1; y may overshoot. */
        x[k] = x[k] < 0 ? 0 : x[k] > 1 ? 1 : x[k];
        if (fabs(y[k]) > 100)
            return lt_fail(c, "%s: easing y %g beyond +-100", what, y[k]);
    }
    return 0;
}

/* The value of a path keyframe or static path: {"c", "v", "i", "o"} (or [that]). */
static int read_path(lt_ctx *c, const cJSON *j, double **out, int *n, const char *what)
{
    if (cJSON_IsArray(j))
        j = cJSON_GetArrayItem(j, 0);
    if (!cJSON_IsObject(j))
        return lt_fail(c, "%s: expected a path {\"c\", \"v\", \"i\", \"o\"}", what);
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(j, "v");
    const cJSON *in = cJSON_GetObjectItemCaseSensitive(j, "i");
    const cJSON *o = cJSON_GetObjectItemCaseSensitive(j, "o");
    if (!cJSON_IsArray(v))
        return lt_fail(c, "%s: a path needs \"v\"", what);
    int m = cJSON_GetArraySize(v);
    if (m > LT_MAX_VERTICES)
        return lt_fail(c, "%s: %d vertices, more than %d", what, m, LT_MAX_VERTICES);
    if (*n >= 0 && m != *n)
        return lt_fail(c, "%s: keyframes of a path differ in vertex count (%d, %d)", what, *n, m);
    *n = m;
    double *buf = calloc((size_t)(1 + 6 * m), sizeof *buf);
    if (!buf)
        return lt_fail(c, "out of memory");
    *out = buf;
    const cJSON *cl = cJSON_GetObjectItemCaseSensitive(j, "c");
    buf[0] = cJSON_IsTrue(cl) || (cJSON_IsNumber(cl) && cl->valuedouble != 0) ? 1 : 0;
    const cJSON *arrs[3] = {v, in, o};
    for (int a = 0; a < 3; a++)
        for (int k = 0; k < m; k++) {
            const cJSON *p = cJSON_IsArray(arrs[a]) ? cJSON_GetArrayItem(arrs[a], k) : NULL;
            double xy[2] = {0, 0};
            if (p && read_vals(c, p, 2, xy, what) != 0)
                return -1;
            buf[1 + a * 2 * m + 2 * k] = xy[0];
            buf[1 + a * 2 * m + 2 * k + 1] = xy[1];
        }
    return 0;
}

static bool is_keyframed(const cJSON *k)
{
    const cJSON *first = cJSON_IsArray(k) ? cJSON_GetArrayItem(k, 0) : NULL;
    return cJSON_IsObject(first) && cJSON_GetObjectItemCaseSensitive(first, "t") != NULL;
}

/* Parses the keyframes of k (dims values each, or a path when path_n). */
static int parse_keys(lt_ctx *c, const cJSON *k, int dims, bool is_path, int *path_n,
                      const char *what, lt_prop *p)
{
    int n = cJSON_GetArraySize(k);
    if (n > LT_MAX_KEYFRAMES)
        return lt_fail(c, "%s: %d keyframes, more than %d", what, n, LT_MAX_KEYFRAMES);
    if (!lt_charge(c, (double)n * dims))
        return -1;
    p->keys = calloc((size_t)n, sizeof *p->keys);
    if (!p->keys)
        return lt_fail(c, "out of memory");
    const cJSON *kf;
    double prev = -INFINITY;
    cJSON_ArrayForEach(kf, k)
    {
        if (!cJSON_IsObject(kf))
            return lt_fail(c, "%s: a keyframe is not an object", what);
        lt_key *q = &p->keys[p->nkeys];
        if (lt_num(c, kf, "t", -LT_BIG, LT_BIG, NAN, &q->t) != 0)
            return -1;
        if (isnan(q->t))
            return lt_fail(c, "%s: keyframe %d has no time \"t\"", what, p->nkeys);
        if (q->t < prev)
            return lt_fail(c, "%s: keyframe times go back (%g after %g)", what, q->t, prev);
        prev = q->t;
        const cJSON *s = cJSON_GetObjectItemCaseSensitive(kf, "s");
        const cJSON *e = cJSON_GetObjectItemCaseSensitive(kf, "e");
        p->nkeys++;
        if (!s) {
            if (p->nkeys == n && p->nkeys > 1)
                continue; /* old format: the last keyframe is only a time */
            return lt_fail(c, "%s: keyframe %d has no value \"s\"", what, p->nkeys - 1);
        }
        if (is_path) {
            if (read_path(c, s, &q->s, path_n, what) != 0)
                return -1;
            if (e && read_path(c, e, &q->e, path_n, what) != 0)
                return -1;
        } else {
            q->s = calloc((size_t)dims, sizeof *q->s);
            if (!q->s || read_vals(c, s, dims, q->s, what) != 0)
                return q->s ? -1 : lt_fail(c, "out of memory");
            if (e) {
                q->e = calloc((size_t)dims, sizeof *q->e);
                if (!q->e || read_vals(c, e, dims, q->e, what) != 0)
                    return q->e ? -1 : lt_fail(c, "out of memory");
            }
        }
        const cJSON *h = cJSON_GetObjectItemCaseSensitive(kf, "h");
        q->hold = (cJSON_IsNumber(h) && h->valuedouble != 0) || cJSON_IsTrue(h);
        int ed = 1; /* rlottie reads the first dimension's easing only */
        if (read_handle(c, cJSON_GetObjectItemCaseSensitive(kf, "o"), ed, q->ox, q->oy, 0, 0,
                        what) != 0 ||
            read_handle(c, cJSON_GetObjectItemCaseSensitive(kf, "i"), ed, q->ix, q->iy, 1, 1,
                        what) != 0)
            return -1;
        for (int d = ed; d < LT_MAX_DIMS; d++) {
            q->ox[d] = q->ox[0];
            q->oy[d] = q->oy[0];
            q->ix[d] = q->ix[0];
            q->iy[d] = q->iy[0];
        }
        const cJSON *to = cJSON_GetObjectItemCaseSensitive(kf, "to");
        const cJSON *ti = cJSON_GetObjectItemCaseSensitive(kf, "ti");
        if (!is_path && dims >= 2 && cJSON_IsArray(to) && cJSON_IsArray(ti)) {
            if (read_vals(c, to, 2, q->to, what) != 0 || read_vals(c, ti, 2, q->ti, what) != 0)
                return -1;
            q->spatial = q->to[0] != 0 || q->to[1] != 0 || q->ti[0] != 0 || q->ti[1] != 0;
        }
    }
    /* Old-format last keyframe without "s": it takes the previous "e". */
    lt_key *last = &p->keys[p->nkeys - 1];
    if (!last->s) {
        const lt_key *before = &p->keys[p->nkeys - 2];
        const double *src = before->e ? before->e : before->s;
        size_t cnt = is_path ? (size_t)(1 + 6 * *path_n) : (size_t)dims;
        last->s = malloc(cnt * sizeof *last->s);
        if (!last->s)
            return lt_fail(c, "out of memory");
        memcpy(last->s, src, cnt * sizeof *last->s);
    }
    return 0;
}

static int prop_parse(lt_ctx *c, const cJSON *j, int dims, const double *dflt, const char *what,
                      lt_prop *p)
{
    memset(p, 0, sizeof *p);
    p->dims = dims;
    p->value = calloc((size_t)dims, sizeof *p->value);
    if (!p->value)
        return lt_fail(c, "out of memory");
    for (int k = 0; k < dims; k++)
        p->value[k] = dflt ? dflt[k] : 0;
    if (j == NULL)
        return 0;
    if (!cJSON_IsObject(j))
        return lt_fail(c, "%s: expected a property object", what);
    if (cJSON_GetObjectItemCaseSensitive(j, "x") && cJSON_IsString(cJSON_GetObjectItemCaseSensitive(j, "x")))
        lt_warn(c, LT_F_EXPRESSION, "expressions are not evaluated (%s and others keep their keyframes)",
                what);
    const cJSON *sep = cJSON_GetObjectItemCaseSensitive(j, "s");
    if (dims == 2 && cJSON_IsTrue(sep)) {
        /* Separate dimensions: "x" and "y" are properties of their own. */
        p->split = true;
        p->sx = calloc(1, sizeof *p->sx);
        p->sy = calloc(1, sizeof *p->sy);
        if (!p->sx || !p->sy)
            return lt_fail(c, "out of memory");
        if (prop_parse(c, cJSON_GetObjectItemCaseSensitive(j, "x"), 1, dflt, what, p->sx) != 0 ||
            prop_parse(c, cJSON_GetObjectItemCaseSensitive(j, "y"), 1, dflt ? dflt + 1 : NULL,
                       what, p->sy) != 0)
            return -1;
        return 0;
    }
    const cJSON *k = cJSON_GetObjectItemCaseSensitive(j, "k");
    if (k == NULL)
        return 0;
    if (is_keyframed(k))
        return parse_keys(c, k, dims, false, NULL, what, p);
    return read_vals(c, k, dims, p->value, what);
}

/*
 * A property that failed to parse holds nothing: what was read before the
 * fault is freed here, so no caller has to know how far it got.
 */
int lt_prop_parse(lt_ctx *c, const cJSON *j, int dims, const double *dflt, const char *what,
                  lt_prop *p)
{
    int rc = prop_parse(c, j, dims, dflt, what, p);
    if (rc != 0)
        lt_prop_free(p);
    return rc;
}

static int prop_parse_path(lt_ctx *c, const cJSON *j, const char *what, lt_prop *p, int *nverts)
{
    memset(p, 0, sizeof *p);
    *nverts = -1;
    if (!cJSON_IsObject(j))
        return lt_fail(c, "%s: expected a path property", what);
    const cJSON *k = cJSON_GetObjectItemCaseSensitive(j, "k");
    if (is_keyframed(k)) {
        if (parse_keys(c, k, 0, true, nverts, what, p) != 0)
            return -1;
        if (*nverts < 0)
            *nverts = 0;
    } else if (read_path(c, k, &p->value, nverts, what) != 0) {
        return -1;
    }
    p->dims = 1 + 6 * *nverts;
    if (!p->value) {
        p->value = calloc((size_t)p->dims, sizeof *p->value);
        if (!p->value)
            return lt_fail(c, "out of memory");
    }
    return 0;
}

void lt_prop_free(lt_prop *p)
{
    if (!p)
        return;
    for (int k = 0; k < p->nkeys; k++) {
        free(p->keys[k].s);
        free(p->keys[k].e);
    }
    free(p->keys);
    free(p->value);
    if (p->split) {
        lt_prop_free(p->sx);
        lt_prop_free(p->sy);
        free(p->sx);
        free(p->sy);
    }
    memset(p, 0, sizeof *p);
}

bool lt_prop_animated(const lt_prop *p)
{
    if (p->split)
        return lt_prop_animated(p->sx) || lt_prop_animated(p->sy);
    return p->nkeys > 1;
}

double lt_ease(const double *e, double u)
{
    if (e[0] == e[1] && e[2] == e[3])
        return u;
    double lo = 0, hi = 1, v = u;
    for (int i = 0; i < 60; i++) {
        v = 0.5 * (lo + hi);
        double w = 1 - v, x = 3 * w * w * v * e[0] + 3 * w * v * v * e[2] + v * v * v;
        if (x < u)
            lo = v;
        else
            hi = v;
    }
    double w = 1 - v;
    return 3 * w * w * v * e[1] + 3 * w * v * v * e[3] + v * v * v;
}

/* A point at arc-length fraction s of the cubic p0 p1 p2 p3 (rlottie's tAtLength). */
static void spatial_point(const double *p0, const double *p1, const double *p2, const double *p3,
                          double s, double *out)
{
    enum { N = 64 };
    double len[N + 1], px = p0[0], py = p0[1];
    len[0] = 0;
    for (int i = 1; i <= N; i++) {
        double t = (double)i / N, w = 1 - t;
        double x = w * w * w * p0[0] + 3 * w * w * t * p1[0] + 3 * w * t * t * p2[0] + t * t * t * p3[0];
        double y = w * w * w * p0[1] + 3 * w * w * t * p1[1] + 3 * w * t * t * p2[1] + t * t * t * p3[1];
        len[i] = len[i - 1] + hypot(x - px, y - py);
        px = x;
        py = y;
    }
    double target = s * len[N], t = s;
    if (len[N] > 0) {
        int i = 1;
        while (i < N && len[i] < target)
            i++;
        double seg = len[i] - len[i - 1];
        t = ((double)(i - 1) + (seg > 0 ? (target - len[i - 1]) / seg : 0)) / N;
    }
    double w = 1 - t;
    out[0] = w * w * w * p0[0] + 3 * w * w * t * p1[0] + 3 * w * t * t * p2[0] + t * t * t * p3[0];
    out[1] = w * w * w * p0[1] + 3 * w * w * t * p1[1] + 3 * w * t * t * p2[1] + t * t * t * p3[1];
}

void lt_prop_eval(const lt_prop *p, double f, double *out)
{
    if (p->split) {
        lt_prop_eval(p->sx, f, out);
        lt_prop_eval(p->sy, f, out + 1);
        return;
    }
    int n = p->nkeys, dims = p->dims;
    if (n == 0) {
        memcpy(out, p->value, (size_t)dims * sizeof *out);
        return;
    }
    if (n == 1 || f <= p->keys[0].t) {
        memcpy(out, p->keys[0].s, (size_t)dims * sizeof *out);
        return;
    }
    if (f >= p->keys[n - 1].t) {
        /* After the last keyframe: its value (an old-format one took the "e"). */
        memcpy(out, p->keys[n - 1].s, (size_t)dims * sizeof *out);
        return;
    }
    int lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (p->keys[mid].t <= f)
            lo = mid;
        else
            hi = mid;
    }
    const lt_key *a = &p->keys[lo], *b = &p->keys[hi];
    const double *s0 = a->s, *s1 = a->e ? a->e : b->s;
    if (a->hold || b->t <= a->t) {
        memcpy(out, s0, (size_t)dims * sizeof *out);
        return;
    }
    double u = (f - a->t) / (b->t - a->t);
    if (a->spatial && dims >= 2) {
        double e[4] = {a->ox[0], a->oy[0], a->ix[0], a->iy[0]};
        double s = lt_ease(e, u);
        double c1[2] = {s0[0] + a->to[0], s0[1] + a->to[1]};
        double c2[2] = {s1[0] + a->ti[0], s1[1] + a->ti[1]};
        spatial_point(s0, c1, c2, s1, s, out);
        for (int d = 2; d < dims; d++)
            out[d] = s0[d] + s * (s1[d] - s0[d]);
        return;
    }
    /* One easing for every dimension: the first one's, as rlottie reads it. */
    double e[4] = {a->ox[0], a->oy[0], a->ix[0], a->iy[0]};
    double s = lt_ease(e, u);
    for (int d = 0; d < dims; d++)
        out[d] = s0[d] + s * (s1[d] - s0[d]);
}

void lt_path_from_values(const double *vals, int n, lt_path *out)
{
    out->n = n;
    out->closed = vals[0] != 0;
    out->v = (double *)vals + 1;
    out->in = (double *)vals + 1 + 2 * n;
    out->out = (double *)vals + 1 + 4 * n;
}

int lt_prop_parse_path(lt_ctx *c, const cJSON *j, const char *what, lt_prop *p, int *nverts)
{
    int rc = prop_parse_path(c, j, what, p, nverts);
    if (rc != 0)
        lt_prop_free(p);
    return rc;
}
