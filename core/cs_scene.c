/*
 * cs_scene.c - building the scene store, with complete validation.
 *
 * The scene store is what the renderer trusts, so everything that enters it
 * is checked here: finite numbers, coordinates within CS_CFG_COORD_LIMIT,
 * positive weights, legal knot intervals, paints in range, capacity. Each
 * add call checks its whole input before it writes anything, so a rejected
 * call leaves the store unchanged; the JSON loader and the stream decoder
 * both build scenes through these calls and get identical results.
 */
#include "cs_internal.h"

static bool rgb_finite(const float *v)
{
    return cs__finite(v[0]) && cs__finite(v[1]) && cs__finite(v[2]);
}

static bool rgb_unit(const float *v)
{
    for (int i = 0; i < 3; i++)
        if (!(v[i] >= 0.0f && v[i] <= 1.0f))
            return false;
    return true;
}

/* Light levels are multipliers: finite and not negative, but may exceed 1. */
static bool light_ok(const float *v)
{
    return rgb_finite(v) && v[0] >= 0.0f && v[1] >= 0.0f && v[2] >= 0.0f;
}

cs_status cs__check_lights(const float *front, const float *back)
{
    if ((front && !light_ok(front)) || (back && !light_ok(back)))
        return (front && !rgb_finite(front)) || (back && !rgb_finite(back)) ? CS_ERR_NONFINITE
                                                                            : CS_ERR_PAINT;
    return CS_OK;
}

cs_status cs__check_colour(const float *rgb)
{
    if (!rgb_finite(rgb))
        return CS_ERR_NONFINITE;
    return rgb_unit(rgb) ? CS_OK : CS_ERR_PAINT;
}

cs_status cs__check_affine(const cs_affine *m, int32_t *item)
{
    const float *v = &m->a;
    for (int i = 0; i < 6; i++) {
        *item = i;
        if (!cs__finite(v[i]))
            return CS_ERR_NONFINITE;
        if (cs__absf(v[i]) > CS_CFG_COORD_LIMIT)
            return CS_ERR_RANGE;
    }
    *item = -1;
    return CS_OK;
}

cs_status cs__check_point(const cs_point *p)
{
    if (!cs__finite(p->x) || !cs__finite(p->y) || !cs__finite(p->w))
        return CS_ERR_NONFINITE;
    if (cs__absf(p->x) > CS_CFG_COORD_LIMIT || cs__absf(p->y) > CS_CFG_COORD_LIMIT)
        return CS_ERR_RANGE;
    /* Weights far from 1 make the rational form ill-conditioned in float. */
    if (!(p->w > 0.0f) || p->w > CS_CFG_COORD_LIMIT || p->w < 1.0f / CS_CFG_COORD_LIMIT)
        return CS_ERR_WEIGHT;
    return CS_OK;
}

static void copy3(float *dst, const float *src)
{
    dst[0] = src[0];
    dst[1] = src[1];
    dst[2] = src[2];
}

cs_status cs__check_canvas(float canvas_w, float canvas_h)
{
    if (!cs__finite(canvas_w) || !cs__finite(canvas_h))
        return CS_ERR_NONFINITE;
    if (!(canvas_w > 0.0f && canvas_h > 0.0f))
        return CS_ERR_DEGENERATE;
    if (canvas_w > CS_CFG_COORD_LIMIT || canvas_h > CS_CFG_COORD_LIMIT)
        return CS_ERR_RANGE;
    return CS_OK;
}

cs_status cs_scene_init(cs_scene *scene, float canvas_w, float canvas_h)
{
    if (!scene)
        return CS_ERR_ARG;
    cs_status st = cs__check_canvas(canvas_w, canvas_h);
    if (st != CS_OK)
        return st;
    scene->canvas_w = canvas_w;
    scene->canvas_h = canvas_h;
    scene->has_background = false;
    for (int i = 0; i < 3; i++) {
        scene->background[i] = 0.0f;
        scene->stack_front[i] = 1.0f;
        scene->stack_back[i] = 0.0f;
    }
    scene->cel_count = scene->region_count = scene->contour_count = scene->point_count = 0;
    scene->track_count = scene->key_count = scene->value_count = 0;
    scene->open_track = UINT32_MAX;
    return CS_OK;
}

cs_status cs_scene_set_background(cs_scene *scene, const float rgb_linear[3])
{
    if (!scene || !rgb_linear)
        return CS_ERR_ARG;
    cs_status st = cs__check_colour(rgb_linear);
    if (st != CS_OK)
        return st;
    copy3(scene->background, rgb_linear);
    scene->has_background = true;
    return CS_OK;
}

cs_status cs_scene_set_lights(cs_scene *scene, const float front[3], const float back[3])
{
    if (!scene || !front || !back)
        return CS_ERR_ARG;
    cs_status st = cs__check_lights(front, back);
    if (st != CS_OK)
        return st;
    copy3(scene->stack_front, front);
    copy3(scene->stack_back, back);
    /* A cel without its own front light stores the stack's: keep it current,
     * so the store does not depend on whether lights or cels came first. */
    for (uint32_t i = 0; i < scene->cel_count; i++)
        if (!scene->cels[i].has_front)
            copy3(scene->cels[i].front, front);
    return CS_OK;
}

cs_status cs_scene_add_cel(cs_scene *scene, const cs_affine *transform, const float front[3],
                           const float back[3], cs_error *err)
{
    if (!scene || !transform) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    int32_t cel = (int32_t)scene->cel_count, item;
    cs_status st = cs__check_affine(transform, &item);
    if (st != CS_OK) {
        cs__error(err, st, cel, -1, -1, item);
        return st;
    }
    st = cs__check_lights(front, back);
    if (st != CS_OK) {
        cs__error(err, st, cel, -1, -1, -1);
        return st;
    }
    if (scene->cel_count >= CS_CFG_MAX_CELS) {
        cs__error(err, CS_ERR_CAP_CELS, cel, -1, -1, -1);
        return CS_ERR_CAP_CELS;
    }
    cs_cel *c = &scene->cels[scene->cel_count++];
    c->first_region = scene->region_count;
    c->region_count = 0;
    c->transform.a = transform->a;
    c->transform.b = transform->b;
    c->transform.c = transform->c;
    c->transform.d = transform->d;
    c->transform.e = transform->e;
    c->transform.f = transform->f;
    c->has_front = front != 0;
    static const float black[3] = {0.0f, 0.0f, 0.0f};
    copy3(c->front, front ? front : scene->stack_front);
    copy3(c->back, back ? back : black);
    return CS_OK;
}

cs_status cs__check_paint(const cs_paint *p)
{
    if (!rgb_finite(p->pigment) || !rgb_finite(p->medium) || !cs__finite(p->beta))
        return CS_ERR_NONFINITE;
    if (!rgb_unit(p->pigment) || !rgb_unit(p->medium) || !(p->beta >= 0.0f && p->beta <= 1.0f))
        return CS_ERR_PAINT;
    return CS_OK;
}

void cs__copy_paint(cs_paint *dst, const cs_paint *src)
{
    copy3(dst->pigment, src->pigment);
    copy3(dst->medium, src->medium);
    dst->beta = src->beta;
}

cs_status cs_scene_add_region(cs_scene *scene, cs_fill_rule rule, const cs_paint *paint,
                              cs_error *err)
{
    if (!scene || !paint) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    int32_t cel = (int32_t)scene->cel_count - 1;
    if (scene->cel_count == 0) {
        cs__error(err, CS_ERR_STATE, -1, -1, -1, -1);
        return CS_ERR_STATE;
    }
    cs_cel *c = &scene->cels[cel];
    int32_t region = c->region_count;
    /* Regions of a cel are contiguous: only a cel owning the end of the
     * region array can grow (after cs_scene_move_cel it may not). */
    if (c->first_region + c->region_count != scene->region_count) {
        cs__error(err, CS_ERR_STATE, cel, region, -1, -1);
        return CS_ERR_STATE;
    }
    if (rule != CS_FILL_NONZERO && rule != CS_FILL_EVENODD) {
        cs__error(err, CS_ERR_FILL_RULE, cel, region, -1, -1);
        return CS_ERR_FILL_RULE;
    }
    cs_status st = cs__check_paint(paint);
    if (st != CS_OK) {
        cs__error(err, st, cel, region, -1, -1);
        return st;
    }
    if (scene->region_count >= CS_CFG_MAX_REGIONS || c->region_count >= UINT16_MAX) {
        cs__error(err, CS_ERR_CAP_REGIONS, cel, region, -1, -1);
        return CS_ERR_CAP_REGIONS;
    }
    cs_region *r = &scene->regions[scene->region_count++];
    c->region_count++;
    r->first_contour = scene->contour_count;
    r->contour_count = 0;
    r->fill_rule = (uint8_t)rule;
    cs__copy_paint(&r->paint, paint);
    return CS_OK;
}

/* Validates a contour's numbers; on failure reports the offending item. */
cs_status cs__check_contour(int degree, int count, const cs_point *pts, const float *intervals,
                               int32_t *item)
{
    *item = -1;
    if (degree < 1 || degree > 3)
        return CS_ERR_DEGREE;
    if (count < degree + 1)
        return CS_ERR_TOO_FEW_POINTS;
    for (int i = 0; i < count; i++) {
        *item = i;
        cs_status st = cs__check_point(&pts[i]);
        if (st != CS_OK)
            return st;
    }
    *item = -1;
    if (!intervals)
        return CS_OK;
    int nonzero = 0;
    for (int i = 0; i < count; i++) {
        *item = i;
        if (!cs__finite(intervals[i]))
            return CS_ERR_NONFINITE;
        if (intervals[i] < 0.0f || intervals[i] > CS_CFG_COORD_LIMIT)
            return CS_ERR_INTERVAL;
        if (intervals[i] > 0.0f)
            nonzero++;
    }
    *item = -1;
    if (nonzero == 0)
        return CS_ERR_DEGENERATE;
    /* Longest cyclic run of zeros; start just after a non-zero interval. */
    int start = 0;
    while (intervals[start] == 0.0f)
        start++;
    int run = 0;
    for (int k = 1; k <= count; k++) {
        int i = (start + k) % count;
        if (intervals[i] == 0.0f) {
            if (++run > degree - 1) {
                *item = i;
                return CS_ERR_ZERO_RUN;
            }
        } else {
            run = 0;
        }
    }
    return CS_OK;
}

cs_status cs_scene_add_contour(cs_scene *scene, int degree, int count, const cs_point *points,
                               const float *intervals, cs_error *err)
{
    if (!scene || !points || count < 0) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    if (scene->cel_count == 0 || scene->cels[scene->cel_count - 1].region_count == 0) {
        cs__error(err, CS_ERR_STATE, -1, -1, -1, -1);
        return CS_ERR_STATE;
    }
    const cs_cel *last = &scene->cels[scene->cel_count - 1];
    if (last->first_region + last->region_count != scene->region_count) {
        cs__error(err, CS_ERR_STATE, (int32_t)scene->cel_count - 1, -1, -1, -1);
        return CS_ERR_STATE;
    }
    int32_t cel = (int32_t)scene->cel_count - 1;
    int32_t region = scene->cels[cel].region_count - 1;
    cs_region *r = &scene->regions[scene->region_count - 1];
    int32_t contour = r->contour_count;
    if (r->first_contour + r->contour_count != scene->contour_count) {
        cs__error(err, CS_ERR_STATE, cel, region, contour, -1);
        return CS_ERR_STATE;
    }
    int32_t item;
    cs_status st = cs__check_contour(degree, count, points, intervals, &item);
    if (st != CS_OK) {
        cs__error(err, st, cel, region, contour, item);
        return st;
    }
    if (scene->contour_count >= CS_CFG_MAX_CONTOURS || r->contour_count >= UINT16_MAX) {
        cs__error(err, CS_ERR_CAP_CONTOURS, cel, region, contour, -1);
        return CS_ERR_CAP_CONTOURS;
    }
    if ((uint32_t)count > CS_CFG_MAX_POINTS - scene->point_count || count > UINT16_MAX) {
        cs__error(err, CS_ERR_CAP_POINTS, cel, region, contour, -1);
        return CS_ERR_CAP_POINTS;
    }
    cs_contour *c = &scene->contours[scene->contour_count++];
    r->contour_count++;
    c->first_point = scene->point_count;
    c->point_count = (uint16_t)count;
    c->degree = (uint8_t)degree;
    for (int i = 0; i < count; i++) {
        scene->points[scene->point_count + (uint32_t)i] = points[i];
        scene->intervals[scene->point_count + (uint32_t)i] = intervals ? intervals[i] : 1.0f;
    }
    scene->point_count += (uint32_t)count;
    return CS_OK;
}
