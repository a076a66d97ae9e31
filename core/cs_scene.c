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

cs_status cs__check_canvas(float canvas_w, float canvas_h)
{
    if (!cs__finite(canvas_w) || !cs__finite(canvas_h))
        return CS_ERR_NONFINITE;
    if (!(canvas_w > 0.0f && canvas_h > 0.0f))
        return CS_ERR_SIZE;
    if (canvas_w > CS_CFG_COORD_LIMIT || canvas_h > CS_CFG_COORD_LIMIT)
        return CS_ERR_RANGE;
    return CS_OK;
}

cs_status cs_scene_init(cs_scene *scene, float canvas_w, float canvas_h)
{
    cs_status st = cs_scene_set_canvas(scene, canvas_w, canvas_h);
    if (st != CS_OK)
        return st;
    scene->has_background = false;
    scene->blend = CS_BLEND_LINEAR;
    scene->epoch_ns = 0;
    for (int i = 0; i < 3; i++) {
        scene->background[i] = 0.0f;
        scene->stack_front[i] = 1.0f;
        scene->stack_back[i] = 0.0f;
    }
    scene->cel_count = scene->region_count = scene->contour_count = scene->point_count = 0;
    scene->func_count = 0;
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
    cs__copy3(scene->background, rgb_linear);
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
    cs__copy3(scene->stack_front, front);
    cs__copy3(scene->stack_back, back);
    /* A cel without its own front light stores the stack's: keep it current,
     * so the store does not depend on whether lights or cels came first. */
    for (uint32_t i = 0; i < scene->cel_count; i++)
        if (!scene->cels[i].has_front)
            cs__copy3(scene->cels[i].front, front);
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
    c->parent = CS_NO_PARENT;
    static const float black[3] = {0.0f, 0.0f, 0.0f};
    cs__copy3(c->front, front ? front : scene->stack_front);
    cs__copy3(c->back, back ? back : black);
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

void cs__copy_bytes(void *dst, const void *src, size_t bytes)
{
    unsigned char *d = dst;
    const unsigned char *s = src;
    for (size_t i = 0; i < bytes; i++)
        d[i] = s[i];
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
    CS__COPY(&r->paint, paint);
    r->csg_len = 0;
    for (int k = 0; k < 3; k++)
        r->func[k] = 0;
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
        if (!cs__finite(intervals[i]) || intervals[i] < 0.0f || intervals[i] > CS_CFG_COORD_LIMIT)
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
    c->operand = 0;
    for (int i = 0; i < count; i++) {
        scene->points[scene->point_count + (uint32_t)i] = points[i];
        scene->intervals[scene->point_count + (uint32_t)i] = intervals ? intervals[i] : 1.0f;
    }
    scene->point_count += (uint32_t)count;
    return CS_OK;
}

/* ------------------------------------------------------ functional paints */

/*
 * The last region, or NULL (with err set) when there is none. As for
 * cs_scene_add_region, the last cel must own the end of the region array:
 * after cs_scene_move_cel the array's last region may belong to another cel,
 * and a stream patch must not reach into it.
 */
static cs_region *last_region(cs_scene *scene, cs_error *err, int32_t *cel, int32_t *region)
{
    if (scene->cel_count == 0 || scene->cels[scene->cel_count - 1].region_count == 0) {
        cs__error(err, CS_ERR_STATE, -1, -1, -1, -1);
        return 0;
    }
    const cs_cel *c = &scene->cels[scene->cel_count - 1];
    *cel = (int32_t)scene->cel_count - 1;
    *region = c->region_count - 1;
    if (c->first_region + c->region_count != scene->region_count) {
        cs__error(err, CS_ERR_STATE, *cel, -1, -1, -1);
        return 0;
    }
    return &scene->regions[scene->region_count - 1];
}

static bool coord_ok(float v)
{
    return cs__finite(v) && cs__absf(v) <= CS_CFG_COORD_LIMIT;
}

/*
 * Checks a paint function; *item is the offending stop (or -1 for the
 * header and geometry). Degenerate geometry is refused here so that the
 * per-pixel evaluation never divides by zero.
 */
static cs_status check_func(const cs_paint_func *fn, int32_t *item)
{
    *item = -1;
    if (fn->kind < CS_FUNC_LINEAR || fn->kind > CS_FUNC_MAP || fn->spread > CS_SPREAD_REPEAT)
        return CS_ERR_FUNC;
    if (fn->stop_count < 1 || fn->stop_count > CS_CFG_MAX_STOPS)
        return CS_ERR_FUNC;
    int ngeom = fn->kind == CS_FUNC_LINEAR ? 4 : fn->kind == CS_FUNC_RADIAL ? 5 : 6;
    for (int i = 0; i < ngeom; i++)
        if (!coord_ok(fn->geom[i]))
            return cs__finite(fn->geom[i]) ? CS_ERR_RANGE : CS_ERR_NONFINITE;
    const float *g = fn->geom;
    if (fn->kind == CS_FUNC_LINEAR) {
        float dx = g[2] - g[0], dy = g[3] - g[1];
        if (!(dx * dx + dy * dy > 1e-12f))
            return CS_ERR_FUNC;
    } else if (fn->kind == CS_FUNC_RADIAL) {
        float dx = g[3] - g[0], dy = g[4] - g[1];
        /* The focal point must lie strictly inside: on the circle the
         * gradient's t is unbounded (SVG importers pull it in to 0.99 r). */
        if (!(g[2] > 1e-6f) || !(dx * dx + dy * dy < 0.9999f * g[2] * g[2]))
            return CS_ERR_FUNC;
    } else {
        float det = g[2] * g[5] - g[4] * g[3];
        if (fn->map_cols < 1 || fn->stop_count % fn->map_cols != 0 || !(cs__absf(det) > 1e-12f))
            return CS_ERR_FUNC;
    }
    for (int i = 0; i < fn->stop_count; i++) {
        const cs_stop *st = &fn->stops[i];
        *item = i;
        if (!cs__finite(st->offset) || !rgb_finite(st->value))
            return CS_ERR_NONFINITE;
        if (!rgb_unit(st->value))
            return CS_ERR_PAINT;
        if (fn->kind == CS_FUNC_MAP)
            continue;
        if (!(st->offset >= 0.0f && st->offset <= 1.0f) ||
            (i > 0 && st->offset < fn->stops[i - 1].offset))
            return CS_ERR_FUNC;
    }
    *item = -1;
    return CS_OK;
}

cs_status cs_scene_set_region_func(cs_scene *scene, cs_paint_field field, const cs_paint_func *fn,
                                   cs_error *err)
{
    if (!scene || !fn || (unsigned)field > (unsigned)CS_FIELD_BETA) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    int32_t cel, region, item;
    cs_region *r = last_region(scene, err, &cel, &region);
    if (!r)
        return CS_ERR_STATE;
    cs_status st = check_func(fn, &item);
    if (st != CS_OK) {
        cs__error(err, st, cel, region, -1, item);
        return st;
    }
    uint32_t slot;
    if (r->func[field] != 0) {
        slot = r->func[field] - 1u;
    } else {
        if (scene->func_count >= CS_CFG_MAX_FUNCS) {
            cs__error(err, CS_ERR_CAP_FUNCS, cel, region, -1, -1);
            return CS_ERR_CAP_FUNCS;
        }
        slot = scene->func_count++;
        r->func[field] = (uint16_t)(slot + 1u);
    }
    /* Field by field: a struct copy this large may become a memcpy call. */
    cs_paint_func *d = &scene->funcs[slot];
    d->kind = fn->kind;
    d->spread = fn->spread;
    d->stop_count = fn->stop_count;
    d->map_cols = fn->kind == CS_FUNC_MAP ? fn->map_cols : 1;
    for (int i = 0; i < 6; i++)
        d->geom[i] = fn->geom[i];
    if (fn->kind == CS_FUNC_LINEAR)
        d->geom[4] = d->geom[5] = 0.0f;
    else if (fn->kind == CS_FUNC_RADIAL)
        d->geom[5] = 0.0f;
    for (int i = 0; i < CS_CFG_MAX_STOPS; i++) {
        const cs_stop *s = &fn->stops[i < fn->stop_count ? i : fn->stop_count - 1];
        d->stops[i].offset = s->offset;
        cs__copy3(d->stops[i].value, s->value);
    }
    return CS_OK;
}

/* ------------------------------------------------------------------- CSG */

cs_status cs_scene_set_region_csg(cs_scene *scene, const int *rpn, int len, cs_error *err)
{
    if (!scene || !rpn) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    int32_t cel, region;
    cs_region *r = last_region(scene, err, &cel, &region);
    if (!r)
        return CS_ERR_STATE;
    if (len < 1 || len > CS_CFG_MAX_CSG) {
        cs__error(err, CS_ERR_CSG, cel, region, -1, -1);
        return CS_ERR_CSG;
    }
    /* Run the program on its depth alone: every token must find its inputs,
     * and exactly one value must remain. */
    int depth = 0;
    for (int i = 0; i < len; i++) {
        int t = rpn[i];
        bool ok;
        if (t >= 0) {
            ok = t < CS_CFG_MAX_OPERANDS && depth < 32;
            depth++;
        } else {
            ok = t >= CS_CSG_XOR && depth >= 2;
            depth--;
        }
        if (!ok) {
            cs__error(err, CS_ERR_CSG, cel, region, -1, i);
            return CS_ERR_CSG;
        }
    }
    if (depth != 1) {
        cs__error(err, CS_ERR_CSG, cel, region, -1, len);
        return CS_ERR_CSG;
    }
    for (int i = 0; i < len; i++)
        r->csg[i] = (uint8_t)(rpn[i] >= 0 ? (unsigned)rpn[i] : (CS__CSG_OP | (unsigned)-rpn[i]));
    r->csg_len = (uint8_t)len;
    return CS_OK;
}

cs_status cs_scene_set_contour_operand(cs_scene *scene, int operand, cs_error *err)
{
    if (!scene) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    int32_t cel, region;
    cs_region *r = last_region(scene, err, &cel, &region);
    if (!r)
        return CS_ERR_STATE;
    if (r->contour_count == 0 || r->first_contour + r->contour_count != scene->contour_count) {
        cs__error(err, CS_ERR_STATE, cel, region, -1, -1);
        return CS_ERR_STATE;
    }
    int32_t contour = r->contour_count - 1;
    if (operand < 0 || operand >= CS_CFG_MAX_OPERANDS) {
        cs__error(err, CS_ERR_CSG, cel, region, contour, -1);
        return CS_ERR_CSG;
    }
    scene->contours[scene->contour_count - 1].operand = (uint8_t)operand;
    return CS_OK;
}

cs_status cs_scene_set_epoch(cs_scene *scene, uint64_t epoch_ns)
{
    if (!scene)
        return CS_ERR_ARG;
    scene->epoch_ns = epoch_ns;
    return CS_OK;
}

cs_status cs_scene_set_blend(cs_scene *scene, cs_blend blend)
{
    if (!scene)
        return CS_ERR_ARG;
    if (blend != CS_BLEND_LINEAR && blend != CS_BLEND_SRGB)
        return CS_ERR_ARG;
    scene->blend = (uint8_t)blend;
    return CS_OK;
}
