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
 * + - * / are used, so the result is the same on every IEEE-754 target.
 */
#include "cs_internal.h"

int cs__track_family(int kind)
{
    switch (kind) {
    case CS_TRACK_TRANSFORM:
    case CS_TRACK_CEL_LIGHTS:
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
        cs__copy_track(&scene->tracks[j], &scene->tracks[j + 1]);
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
        (unsigned)ease >= (unsigned)CS_EASE_COUNT_) {
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
        cs__copy_track(&scene->tracks[j], &scene->tracks[j - 1]);
    cs_track *t = &scene->tracks[i];
    t->kind = (uint8_t)kind;
    t->ease = (uint8_t)ease;
    t->target = target;
    t->width = width;
    t->key_count = 0;
    t->first_key = scene->key_count;
    t->first_value = scene->value_count;
    scene->track_count++;
    scene->open_track = i;
    cs__error(err, CS_OK, -1, -1, -1, -1);
    return CS_OK;
}

/* Checks one key's values as the static value of the same kind is checked. */
static cs_status check_values(int kind, const float *v, uint32_t width, int32_t *point)
{
    *point = -1;
    switch (kind) {
    case CS_TRACK_TRANSFORM: {
        cs_affine m = {v[0], v[1], v[2], v[3], v[4], v[5]};
        return cs__check_affine(&m, point);
    }
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
    int32_t key = t->key_count, point;
    cs_status st = CS_OK;
    if (!cs__finite(time))
        st = CS_ERR_NONFINITE;
    else if (t->key_count > 0 && !(time > scene->key_times[t->first_key + t->key_count - 1u]))
        st = CS_ERR_KEY_ORDER;
    else
        st = check_values(t->kind, values, t->width, &point);
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
        cs__copy_track(&t, &scene->tracks[i]);
        uint32_t j = i;
        while (j > 0 && track_cmp(&scene->tracks[j - 1], t.kind, t.target) > 0) {
            cs__copy_track(&scene->tracks[j], &scene->tracks[j - 1]);
            j--;
        }
        cs__copy_track(&scene->tracks[j], &t);
    }
    scene->open_track = UINT32_MAX;
}

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
    *i0 = lo;
    *i1 = hi;
    *s = u;
}
