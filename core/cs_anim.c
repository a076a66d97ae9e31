/*
 * cs_anim.c - keyframe tracks in the scene store.
 *
 * A track animates one value of the scene (a cel's transform or lights, a
 * region's paint, a contour's control points, the stack lights, the
 * background) over continuous time. Its keys live in two pools of the store,
 * key_times and key_values; a track owns a contiguous run of each, and only
 * the track added last (scene->open_track) grows, at the end of the pools,
 * so adding keys never moves anything.
 *
 * The tracks array is kept sorted by (kind, target) with at most one track
 * per pair: the renderer looks a track up by binary search for each cel,
 * region and contour of a frame, which costs nothing when there are no
 * tracks and O(log tracks) when there are, with no per-item index stored in
 * the scene and no lookup table in the workspace.
 *
 * Sampling (cs__track_locate) holds the first value before the first key
 * and the last after the last key, and between keys blends with
 * (1-s) a + s b, which gives every key's value exactly at its time. Only
 * + - * / are used, so the result is the same on every IEEE-754 target:
 * the cubic Bezier easing is solved for its x by a fixed number of
 * bisection steps, and the TRS track's sine and cosine are polynomials on
 * a range reduced in degrees, not libm calls.
 */
#include "cs_internal.h"

int cs__track_family(int kind)
{
    switch (kind) {
    case CS_TRACK_TRANSFORM:
    case CS_TRACK_CEL_LIGHTS:
    case CS_TRACK_TRS:
        return CS__FAM_CEL;
    case CS_TRACK_PAINT:
        return CS__FAM_REGION;
    case CS_TRACK_POINTS:
        return CS__FAM_CONTOUR;
    default:
        return CS__FAM_STACK;
    }
}

uint32_t cs_scene_track_width(const cs_scene *scene, cs_track_kind kind, uint32_t target)
{
    if (!scene)
        return 0;
    switch (kind) {
    case CS_TRACK_TRANSFORM:
    case CS_TRACK_CEL_LIGHTS:
        return target < scene->cel_count ? 6u : 0u;
    case CS_TRACK_TRS:
        return target < scene->cel_count ? 10u : 0u;
    case CS_TRACK_PAINT:
        return target < scene->region_count ? 7u : 0u;
    case CS_TRACK_POINTS:
        return target < scene->contour_count ? 3u * scene->contours[target].point_count : 0u;
    case CS_TRACK_STACK_LIGHTS:
        return target == 0 ? 6u : 0u;
    case CS_TRACK_BACKGROUND:
        return target == 0 ? 3u : 0u;
    default:
        return 0;
    }
}

/* Orders tracks by kind, then target. */
static int track_cmp(const cs_track *t, int kind, uint32_t target)
{
    if (t->kind != kind)
        return t->kind < kind ? -1 : 1;
    if (t->target != target)
        return t->target < target ? -1 : 1;
    return 0;
}

/* First index whose (kind, target) is not below the pair. */
static uint32_t lower_bound(const cs_scene *scene, int kind, uint32_t target)
{
    uint32_t lo = 0, hi = scene->track_count;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (track_cmp(&scene->tracks[mid], kind, target) < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

const cs_track *cs__track_find(const cs_scene *scene, int kind, uint32_t target)
{
    if (scene->track_count == 0)
        return 0;
    uint32_t i = lower_bound(scene, kind, target);
    if (i < scene->track_count && track_cmp(&scene->tracks[i], kind, target) == 0)
        return &scene->tracks[i];
    return 0;
}

/* Removes track i and closes the gap its keys leave in the pools. */
static void remove_track_at(cs_scene *scene, uint32_t i)
{
    const cs_track *t = &scene->tracks[i];
    uint32_t k0 = t->first_key, nk = t->key_count;
    uint32_t v0 = t->first_value, nv = t->key_count * t->width;
    for (uint32_t k = k0; k + nk < scene->key_count; k++)
        scene->key_times[k] = scene->key_times[k + nk];
    for (uint32_t v = v0; v + nv < scene->value_count; v++)
        scene->key_values[v] = scene->key_values[v + nv];
    scene->key_count -= nk;
    scene->value_count -= nv;
    for (uint32_t j = i; j + 1 < scene->track_count; j++)
        CS__COPY(&scene->tracks[j], &scene->tracks[j + 1]);
    scene->track_count--;
    for (uint32_t j = 0; j < scene->track_count; j++) {
        cs_track *u = &scene->tracks[j];
        if (u->first_key > k0)
            u->first_key -= nk;
        if (u->first_value > v0)
            u->first_value -= nv;
    }
    /* The open track's keys may no longer end the pools. */
    scene->open_track = UINT32_MAX;
}

static void track_location(const cs_scene *scene, int kind, uint32_t target, cs_error *err,
                           cs_status st)
{
    switch (cs__track_family(kind)) {
    case CS__FAM_CEL:
        cs__error(err, st, (int32_t)target, -1, -1, -1);
        break;
    case CS__FAM_REGION:
    case CS__FAM_CONTOUR: {
        /* Name the cel and the region within it, as the builder's errors do. */
        uint32_t region = target, contour = UINT32_MAX;
        if (kind == CS_TRACK_POINTS) {
            contour = target;
            region = UINT32_MAX;
            for (uint32_t r = 0; r < scene->region_count; r++)
                if (target >= scene->regions[r].first_contour &&
                    target - scene->regions[r].first_contour < scene->regions[r].contour_count)
                    region = r;
        }
        int32_t cel = -1, rin = -1, cin = -1;
        for (uint32_t c = 0; c < scene->cel_count && region != UINT32_MAX; c++)
            if (region >= scene->cels[c].first_region &&
                region - scene->cels[c].first_region < scene->cels[c].region_count) {
                cel = (int32_t)c;
                rin = (int32_t)(region - scene->cels[c].first_region);
            }
        if (contour != UINT32_MAX && region != UINT32_MAX)
            cin = (int32_t)(contour - scene->regions[region].first_contour);
        cs__error(err, st, cel, rin, cin, -1);
        break;
    }
    default:
        cs__error(err, st, -1, -1, -1, -1);
        break;
    }
}

cs_status cs_scene_add_track(cs_scene *scene, cs_track_kind kind, uint32_t target, cs_ease ease,
                             cs_error *err)
{
    if (!scene) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    if ((unsigned)kind >= (unsigned)CS_TRACK_KIND_COUNT_ ||
        (unsigned)ease >= (unsigned)CS_EASE_COUNT_ ||
        (!CS_CFG_ANIM_PARTS && (kind == CS_TRACK_TRS || ease == CS_EASE_CUBIC))) {
        cs__error(err, CS_ERR_TRACK, -1, -1, -1, -1);
        return CS_ERR_TRACK;
    }
    uint32_t width = cs_scene_track_width(scene, kind, target);
    if (width == 0) {
        cs__error(err, CS_ERR_INDEX, -1, -1, -1, -1);
        return CS_ERR_INDEX;
    }
    if (kind == CS_TRACK_POINTS && width > 3u * CS_CFG_MAX_ANIM_POINTS) {
        track_location(scene, kind, target, err, CS_ERR_CAP_ANIM);
        return CS_ERR_CAP_ANIM;
    }
    uint32_t i = lower_bound(scene, kind, target);
    bool replace = i < scene->track_count && track_cmp(&scene->tracks[i], kind, target) == 0;
    if (!replace && scene->track_count >= CS_CFG_MAX_TRACKS) {
        track_location(scene, kind, target, err, CS_ERR_CAP_TRACKS);
        return CS_ERR_CAP_TRACKS;
    }
    if (replace)
        remove_track_at(scene, i);
    for (uint32_t j = scene->track_count; j > i; j--)
        CS__COPY(&scene->tracks[j], &scene->tracks[j - 1]);
    cs_track *t = &scene->tracks[i];
    t->kind = (uint8_t)kind;
    t->ease = (uint8_t)ease;
    t->target = target;
    t->width = width + (ease == CS_EASE_CUBIC ? CS_EASE_CUBIC_FLOATS : 0u);
    t->key_count = 0;
    t->first_key = scene->key_count;
    t->first_value = scene->value_count;
    scene->track_count++;
    scene->open_track = i;
    cs__error(err, CS_OK, -1, -1, -1, -1);
    return CS_OK;
}

#if CS_CFG_ANIM_PARTS
/* A cubic key's easing: a hold, or x1, x2 in 0..1 and y1, y2 in -2..3 (the
 * bound keeps an overshooting value within a few times its keys' span). */
static cs_status check_ease(const float *e)
{
    for (int i = 0; i < 4; i++)
        if (!cs__finite(e[i]))
            return CS_ERR_NONFINITE;
    if (e[0] == -1.0f)
        return e[1] == 0.0f && e[2] == 0.0f && e[3] == 0.0f ? CS_OK : CS_ERR_RANGE;
    if (!(e[0] >= 0.0f && e[0] <= 1.0f && e[2] >= 0.0f && e[2] <= 1.0f))
        return CS_ERR_RANGE;
    if (!(e[1] >= -2.0f && e[1] <= 3.0f && e[3] >= -2.0f && e[3] <= 3.0f))
        return CS_ERR_RANGE;
    return CS_OK;
}

/* A TRS key: finite, positions and anchors within the coordinate limit,
 * scales within +-10^4, skew within +-85 degrees (its tangent stays below
 * 12), turns within +-10^6 degrees, opacity in 0..1. */
static cs_status check_trs(const float *v)
{
    for (int i = 0; i < 10; i++)
        if (!cs__finite(v[i]))
            return CS_ERR_NONFINITE;
    for (int i = 0; i < 4; i++)
        if (cs__absf(v[i]) > CS_CFG_COORD_LIMIT)
            return CS_ERR_RANGE;
    if (cs__absf(v[4]) > 1e4f || cs__absf(v[5]) > 1e4f || cs__absf(v[6]) > 1e6f ||
        cs__absf(v[7]) > 85.0f || cs__absf(v[8]) > 1e6f)
        return CS_ERR_RANGE;
    return v[9] >= 0.0f && v[9] <= 1.0f ? CS_OK : CS_ERR_PAINT;
}

#endif

/* Checks one key's values as the static value of the same kind is checked. */
static cs_status check_values(int kind, const float *v, uint32_t width, int32_t *point)
{
    *point = -1;
    switch (kind) {
    case CS_TRACK_TRANSFORM: {
        cs_affine m = {v[0], v[1], v[2], v[3], v[4], v[5]};
        return cs__check_affine(&m, point);
    }
#if CS_CFG_ANIM_PARTS
    case CS_TRACK_TRS:
        return check_trs(v);
#endif
    case CS_TRACK_CEL_LIGHTS:
    case CS_TRACK_STACK_LIGHTS:
        return cs__check_lights(v, v + 3);
    case CS_TRACK_PAINT: {
        cs_paint p = {{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, v[6]};
        return cs__check_paint(&p);
    }
    case CS_TRACK_POINTS:
        for (uint32_t i = 0; i < width / 3; i++) {
            cs_point p = {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
            cs_status st = cs__check_point(&p);
            if (st != CS_OK) {
                *point = (int32_t)i;
                return st;
            }
        }
        return CS_OK;
    default:
        return cs__check_colour(v);
    }
}

cs_status cs_scene_add_key(cs_scene *scene, float time, const float *values, cs_error *err)
{
    if (!scene || !values) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    if (scene->open_track >= scene->track_count) {
        cs__error(err, CS_ERR_STATE, -1, -1, -1, -1);
        return CS_ERR_STATE;
    }
    cs_track *t = &scene->tracks[scene->open_track];
    int32_t key = t->key_count, point = -1;
    cs_status st = CS_OK;
    if (!cs__finite(time))
        st = CS_ERR_NONFINITE;
    else if (t->key_count > 0 && !(time > scene->key_times[t->first_key + t->key_count - 1u]))
        st = CS_ERR_KEY_ORDER;
    else {
        uint32_t lead = cs__track_lead(t);
#if CS_CFG_ANIM_PARTS
        st = lead ? check_ease(values) : CS_OK;
#endif
        if (st == CS_OK)
            st = check_values(t->kind, values + lead, t->width - lead, &point);
    }
    if (st == CS_OK && (scene->key_count >= CS_CFG_MAX_KEYS || t->key_count >= UINT16_MAX ||
                        t->width > CS_CFG_MAX_KEY_VALUES - scene->value_count))
        st = CS_ERR_CAP_KEYS;
    if (st != CS_OK) {
        track_location(scene, t->kind, t->target, err, st);
        if (err)
            err->item = key;
        return st;
    }
    scene->key_times[scene->key_count++] = time;
    /* `values` may already sit at the end of the pool (the stream decoder
     * reads keys there); the copy is then onto itself, index for index. */
    for (uint32_t i = 0; i < t->width; i++)
        scene->key_values[scene->value_count + i] = values[i];
    scene->value_count += t->width;
    t->key_count++;
    cs__error(err, CS_OK, -1, -1, -1, -1);
    return CS_OK;
}

cs_status cs_scene_remove_track(cs_scene *scene, cs_track_kind kind, uint32_t target,
                                cs_error *err)
{
    if (!scene) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    if ((unsigned)kind >= (unsigned)CS_TRACK_KIND_COUNT_) {
        cs__error(err, CS_ERR_TRACK, -1, -1, -1, -1);
        return CS_ERR_TRACK;
    }
    uint32_t i = lower_bound(scene, kind, target);
    if (i < scene->track_count && track_cmp(&scene->tracks[i], kind, target) == 0)
        remove_track_at(scene, i);
    cs__error(err, CS_OK, -1, -1, -1, -1);
    return CS_OK;
}

void cs__tracks_remove_range(cs_scene *scene, int family, uint32_t first, uint32_t count)
{
    uint32_t i = 0;
    while (i < scene->track_count) {
        cs_track *t = &scene->tracks[i];
        if (cs__track_family(t->kind) == family && t->target >= first &&
            t->target - first < count) {
            remove_track_at(scene, i);
            continue;
        }
        if (cs__track_family(t->kind) == family && t->target >= first + count)
            t->target -= count;
        i++;
    }
}

void cs__tracks_sort(cs_scene *scene)
{
    /* Insertion sort: few tracks, usually already in order, and stable. */
    for (uint32_t i = 1; i < scene->track_count; i++) {
        cs_track t;
        CS__COPY(&t, &scene->tracks[i]);
        uint32_t j = i;
        while (j > 0 && track_cmp(&scene->tracks[j - 1], t.kind, t.target) > 0) {
            CS__COPY(&scene->tracks[j], &scene->tracks[j - 1]);
            j--;
        }
        CS__COPY(&scene->tracks[j], &t);
    }
    scene->open_track = UINT32_MAX;
}

#if CS_CFG_ANIM_PARTS
/*
 * The cubic Bezier easing e = (x1, y1, x2, y2) at u: the curve's y where its
 * x is u. x(v) = 3(1-v)^2 v x1 + 3(1-v) v^2 x2 + v^3 rises on 0..1 (x1, x2
 * in 0..1), so 24 bisection steps find v to within 2^-24 whatever the
 * curve, in the same steps on every target. A segment whose control points
 * lie on the diagonal is linear and returns u itself; a hold returns 0.
 */
static float cubic_ease(const float *e, float u)
{
    if (e[0] < 0.0f)
        return 0.0f;
    if (e[0] == e[1] && e[2] == e[3])
        return u;
    float lo = 0.0f, hi = 1.0f;
    for (int i = 0; i < 24; i++) {
        float v = 0.5f * (lo + hi), w = 1.0f - v;
        float x = 3.0f * w * w * v * e[0] + 3.0f * w * v * v * e[2] + v * v * v;
        if (x < u)
            lo = v;
        else
            hi = v;
    }
    float v = 0.5f * (lo + hi), w = 1.0f - v;
    return 3.0f * w * w * v * e[1] + 3.0f * w * v * v * e[3] + v * v * v;
}

/*
 * sin and cos of `deg` degrees (|deg| <= 10^6): reduced exactly to
 * r = deg - 90 n in -45..45 (n * 90 and the difference are exact in float
 * at these magnitudes), then Taylor polynomials of r in radians, whose
 * truncation error below pi/4 is under 2e-9, far below float rounding.
 * Exact at multiples of 90 degrees.
 */
static void sincos_deg(float deg, float *sn, float *cs)
{
    int32_t n = cs__floori(deg / 90.0f + 0.5f);
    float r = (deg - (float)n * 90.0f) * 0.017453292519943295f, r2 = r * r;
    float s = r * (1.0f - r2 / 6.0f * (1.0f - r2 / 20.0f * (1.0f - r2 / 42.0f * (1.0f - r2 / 72.0f))));
    float c = 1.0f - r2 / 2.0f * (1.0f - r2 / 12.0f * (1.0f - r2 / 30.0f * (1.0f - r2 / 56.0f *
                                                                            (1.0f - r2 / 90.0f))));
    switch (n & 3) {
    case 0:
        *sn = s, *cs = c;
        break;
    case 1:
        *sn = c, *cs = -s;
        break;
    case 2:
        *sn = -s, *cs = -c;
        break;
    default:
        *sn = -c, *cs = s;
        break;
    }
}

/* m = a * b for affine maps in cs_affine's order (a b c d e f). */
static void affine_mul(const float *a, const float *b, float *m)
{
    float r[6] = {a[0] * b[0] + a[2] * b[1], a[1] * b[0] + a[3] * b[1],
                  a[0] * b[2] + a[2] * b[3], a[1] * b[2] + a[3] * b[3],
                  a[0] * b[4] + a[2] * b[5] + a[4], a[1] * b[4] + a[3] * b[5] + a[5]};
    for (int i = 0; i < 6; i++)
        m[i] = r[i];
}

void cs__trs_affine(const float *v, float m[6])
{
    float s, c, sa, ca, sk, ck;
    /* S(sx, sy) T(-a) */
    float acc[6] = {v[4], 0.0f, 0.0f, v[5], -v[4] * v[2], -v[5] * v[3]};
    if (v[7] != 0.0f) {
        /* K = R(axis) [1 tan(skew); 0 1] R(-axis) */
        sincos_deg(v[8], &sa, &ca);
        sincos_deg(v[7], &sk, &ck);
        float k = sk / ck;
        float rn[6] = {ca, -sa, sa, ca, 0.0f, 0.0f}, sh[6] = {1.0f, 0.0f, k, 1.0f, 0.0f, 0.0f};
        float rp[6] = {ca, sa, -sa, ca, 0.0f, 0.0f};
        affine_mul(rn, acc, acc);
        affine_mul(sh, acc, acc);
        affine_mul(rp, acc, acc);
    }
    sincos_deg(v[6], &s, &c);
    float rot[6] = {c, s, -s, c, v[0], v[1]};
    affine_mul(rot, acc, m);
}

#endif

void cs__track_locate(const cs_scene *scene, const cs_track *tr, float t, uint32_t *i0,
                      uint32_t *i1, float *s)
{
    const float *times = &scene->key_times[tr->first_key];
    uint32_t n = tr->key_count;
    *s = 0.0f;
    if (n <= 1 || !(t > times[0])) {
        *i0 = *i1 = 0;
        return;
    }
    if (!(t < times[n - 1])) {
        *i0 = *i1 = n - 1;
        return;
    }
    /* times[lo] <= t < times[hi] */
    uint32_t lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (times[mid] <= t)
            lo = mid;
        else
            hi = mid;
    }
    float u = (t - times[lo]) / (times[hi] - times[lo]);
    /* t - t0 <= t1 - t0 holds after rounding too; the clamp only guards a
     * key spacing that flushes to zero on a target without subnormals. */
    if (!(u >= 0.0f))
        u = 0.0f;
    if (u > 1.0f)
        u = 1.0f;
    if (tr->ease == CS_EASE_SMOOTH)
        u = u * u * (3.0f - 2.0f * u);
    else if (tr->ease == CS_EASE_HOLD)
        u = 0.0f;
#if CS_CFG_ANIM_PARTS
    else if (tr->ease == CS_EASE_CUBIC) {
        u = cubic_ease(&scene->key_values[tr->first_value + lo * tr->width], u);
        if (tr->kind != CS_TRACK_TRANSFORM && tr->kind != CS_TRACK_TRS &&
            tr->kind != CS_TRACK_POINTS)
            u = cs__clampf(u, 0.0f, 1.0f);
    }
#endif
    *i0 = lo;
    *i1 = hi;
    *s = u;
}
