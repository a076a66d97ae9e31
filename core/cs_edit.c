/*
 * cs_edit.c - changing a built scene store: what cel stream patches do.
 *
 * The store keeps each cel's regions, each region's contours and each
 * contour's points contiguous, in creation order, and the builder only ever
 * appends. Editing keeps those invariants:
 *   - setters overwrite values in place (transform, lights, paint, points of
 *     the same count) after checking them exactly as the builder does;
 *   - removing a cel closes the gaps its regions, contours and points leave,
 *     renumbers what follows, and drops the tracks that animated them and
 *     the paint functions its regions owned (each function slot belongs to
 *     one field of one region, so the slots close up and the regions'
 *     references to later slots move down);
 *   - moving a cel permutes only the cels array (a cel finds its regions
 *     through first_region), so regions need not follow stack order;
 *     cel-targeted tracks are renumbered and re-sorted. CSG programs live in
 *     their regions and operands in their contours, so they move with them.
 * All of it is loops over the used part of the store, with no scratch
 * memory, so the stream decoder can apply a patch to its back store.
 */
#include "cs_internal.h"

cs_status cs_scene_set_canvas(cs_scene *scene, float canvas_w, float canvas_h)
{
    if (!scene)
        return CS_ERR_ARG;
    cs_status st = cs__check_canvas(canvas_w, canvas_h);
    if (st != CS_OK)
        return st;
    scene->canvas_w = canvas_w;
    scene->canvas_h = canvas_h;
    return CS_OK;
}

cs_status cs_scene_clear_background(cs_scene *scene)
{
    if (!scene)
        return CS_ERR_ARG;
    scene->has_background = false;
    scene->background[0] = scene->background[1] = scene->background[2] = 0.0f;
    return CS_OK;
}

cs_status cs_scene_set_transform(cs_scene *scene, uint32_t cel, const cs_affine *transform,
                                 cs_error *err)
{
    if (!scene || !transform) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    if (cel >= scene->cel_count) {
        cs__error(err, CS_ERR_INDEX, -1, -1, -1, -1);
        return CS_ERR_INDEX;
    }
    int32_t item;
    cs_status st = cs__check_affine(transform, &item);
    cs__error(err, st, st == CS_OK ? -1 : (int32_t)cel, -1, -1, item);
    if (st == CS_OK)
        CS__COPY(&scene->cels[cel].transform, transform);
    return st;
}

cs_status cs_scene_set_cel_lights(cs_scene *scene, uint32_t cel, const float front[3],
                                  const float back[3], cs_error *err)
{
    if (!scene) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    if (cel >= scene->cel_count) {
        cs__error(err, CS_ERR_INDEX, -1, -1, -1, -1);
        return CS_ERR_INDEX;
    }
    cs_status st = cs__check_lights(front, back);
    cs__error(err, st, st == CS_OK ? -1 : (int32_t)cel, -1, -1, -1);
    if (st != CS_OK)
        return st;
    static const float black[3] = {0.0f, 0.0f, 0.0f};
    cs_cel *c = &scene->cels[cel];
    c->has_front = front != 0;
    cs__copy3(c->front, front ? front : scene->stack_front);
    cs__copy3(c->back, back ? back : black);
    return CS_OK;
}

/* The cel and in-cel index of a region, for error locations. */
static void region_owner(const cs_scene *scene, uint32_t region, int32_t *cel, int32_t *rin)
{
    *cel = *rin = -1;
    for (uint32_t c = 0; c < scene->cel_count; c++)
        if (region >= scene->cels[c].first_region &&
            region - scene->cels[c].first_region < scene->cels[c].region_count) {
            *cel = (int32_t)c;
            *rin = (int32_t)(region - scene->cels[c].first_region);
        }
}

cs_status cs_scene_set_paint(cs_scene *scene, uint32_t region, cs_fill_rule rule,
                             const cs_paint *paint, cs_error *err)
{
    if (!scene || !paint) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    if (region >= scene->region_count) {
        cs__error(err, CS_ERR_INDEX, -1, -1, -1, -1);
        return CS_ERR_INDEX;
    }
    cs_status st = (rule != CS_FILL_NONZERO && rule != CS_FILL_EVENODD) ? CS_ERR_FILL_RULE
                                                                       : cs__check_paint(paint);
    if (st != CS_OK) {
        int32_t cel, rin;
        region_owner(scene, region, &cel, &rin);
        cs__error(err, st, cel, rin, -1, -1);
        return st;
    }
    cs_region *r = &scene->regions[region];
    r->fill_rule = (uint8_t)rule;
    CS__COPY(&r->paint, paint);
    cs__error(err, CS_OK, -1, -1, -1, -1);
    return CS_OK;
}

cs_status cs_scene_set_points(cs_scene *scene, uint32_t contour, int count,
                              const cs_point *points, const float *intervals, cs_error *err)
{
    if (!scene || !points) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    if (contour >= scene->contour_count) {
        cs__error(err, CS_ERR_INDEX, -1, -1, -1, -1);
        return CS_ERR_INDEX;
    }
    cs_contour *c = &scene->contours[contour];
    int32_t item = -1;
    cs_status st = CS_OK;
    if (count != (int)c->point_count)
        st = CS_ERR_COUNT;
    else
        st = cs__check_contour(c->degree, count, points,
                               intervals ? intervals : &scene->intervals[c->first_point], &item);
    if (st != CS_OK) {
        int32_t cel = -1, rin = -1, cin = -1;
        for (uint32_t r = 0; r < scene->region_count; r++)
            if (contour >= scene->regions[r].first_contour &&
                contour - scene->regions[r].first_contour < scene->regions[r].contour_count) {
                region_owner(scene, r, &cel, &rin);
                cin = (int32_t)(contour - scene->regions[r].first_contour);
            }
        cs__error(err, st, cel, rin, cin, item);
        return st;
    }
    /* In place when the caller passed the store's own arrays: same index. */
    for (int i = 0; i < count; i++) {
        CS__COPY(&scene->points[c->first_point + (uint32_t)i], &points[i]);
        if (intervals)
            scene->intervals[c->first_point + (uint32_t)i] = intervals[i];
    }
    cs__error(err, CS_OK, -1, -1, -1, -1);
    return CS_OK;
}

/*
 * Start indices of the items after a removed run [first, first+n) move down
 * by n; an empty owner whose start lies inside the run (possible only for
 * owners with no items) moves to `first`.
 */
static uint32_t shift_start(uint32_t start, uint32_t first, uint32_t n)
{
    if (start >= first + n)
        return start - n;
    return start > first ? first : start;
}

/*
 * Removes function slot k: later slots move down one, and every reference
 * to them (1 + slot in a region's func[]) with them. Removed regions that
 * still wait for their own slots to go are renumbered too, so their
 * references stay right until they are reached.
 */
static void remove_func_slot(cs_scene *scene, uint32_t k)
{
    CS__COPY_N(&scene->funcs[k], &scene->funcs[k + 1], scene->func_count - k - 1u);
    scene->func_count--;
    for (uint32_t r = 0; r < scene->region_count; r++)
        for (int f = 0; f < 3; f++)
            if (scene->regions[r].func[f] > k + 1u)
                scene->regions[r].func[f]--;
}

cs_status cs_scene_remove_cel(cs_scene *scene, uint32_t cel, cs_error *err)
{
    if (!scene) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    if (cel >= scene->cel_count) {
        cs__error(err, CS_ERR_INDEX, -1, -1, -1, -1);
        return CS_ERR_INDEX;
    }
    const cs_cel *victim = &scene->cels[cel];
    uint32_t fr = victim->first_region, nr = victim->region_count;
    uint32_t fc = 0, nc = 0, fp = 0, np = 0;
    if (nr > 0) {
        fc = scene->regions[fr].first_contour;
        for (uint32_t r = fr; r < fr + nr; r++)
            nc += scene->regions[r].contour_count;
    }
    if (nc > 0) {
        fp = scene->contours[fc].first_point;
        for (uint32_t k = fc; k < fc + nc; k++)
            np += scene->contours[k].point_count;
    }
    /* Paint functions of the cel's regions, while the regions are in place. */
    for (uint32_t r = fr; r < fr + nr; r++)
        for (int f = 0; f < 3; f++) {
            uint16_t ref = scene->regions[r].func[f];
            if (ref) {
                scene->regions[r].func[f] = 0;
                remove_func_slot(scene, ref - 1u);
            }
        }
    /* Tracks first, while their targets still mean the old indices. */
    cs__tracks_remove_range(scene, CS__FAM_CEL, cel, 1);
    cs__tracks_remove_range(scene, CS__FAM_REGION, fr, nr);
    cs__tracks_remove_range(scene, CS__FAM_CONTOUR, fc, nc);

    /* Each array closes up over the removed range, forward (cs__copy_bytes). */
    CS__COPY_N(&scene->cels[cel], &scene->cels[cel + 1], scene->cel_count - cel - 1u);
    scene->cel_count--;
    CS__COPY_N(&scene->regions[fr], &scene->regions[fr + nr], scene->region_count - fr - nr);
    scene->region_count -= nr;
    CS__COPY_N(&scene->contours[fc], &scene->contours[fc + nc], scene->contour_count - fc - nc);
    scene->contour_count -= nc;
    CS__COPY_N(&scene->points[fp], &scene->points[fp + np], scene->point_count - fp - np);
    CS__COPY_N(&scene->intervals[fp], &scene->intervals[fp + np], scene->point_count - fp - np);
    scene->point_count -= np;

    for (uint32_t i = 0; i < scene->cel_count; i++) {
        cs_cel *c = &scene->cels[i];
        c->first_region = shift_start(c->first_region, fr, nr);
        if (c->parent == cel)
            c->parent = CS_NO_PARENT;
        else if (c->parent != CS_NO_PARENT && c->parent > cel)
            c->parent--;
    }
    for (uint32_t i = 0; i < scene->region_count; i++)
        scene->regions[i].first_contour = shift_start(scene->regions[i].first_contour, fc, nc);
    for (uint32_t i = 0; i < scene->contour_count; i++)
        scene->contours[i].first_point = shift_start(scene->contours[i].first_point, fp, np);
    scene->open_track = UINT32_MAX;
    cs__error(err, CS_OK, -1, -1, -1, -1);
    return CS_OK;
}

/* Where cel index i goes when cel `from` moves to `to`. */
static uint32_t moved_index(uint32_t i, uint32_t from, uint32_t to)
{
    if (i == from)
        return to;
    if (from < to && i > from && i <= to)
        return i - 1;
    if (from > to && i >= to && i < from)
        return i + 1;
    return i;
}

#if CS_CFG_ANIM_PARTS
/* Length of cel c's group chain (1: no parent) if cel `cel` had parent
 * `parent`, or CS_CFG_MAX_GROUP_DEPTH + 1 once it is longer (or cycles). */
static int chain_length(const cs_scene *scene, uint32_t c, uint32_t cel, uint32_t parent)
{
    int n = 1;
    while (n <= CS_CFG_MAX_GROUP_DEPTH) {
        uint32_t p = c == cel ? parent : scene->cels[c].parent;
        if (p == CS_NO_PARENT)
            return n;
        c = p;
        n++;
    }
    return n;
}

#endif

cs_status cs_scene_set_cel_parent(cs_scene *scene, uint32_t cel, uint32_t parent, cs_error *err)
{
    if (!scene) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    if (parent == UINT32_MAX)
        parent = CS_NO_PARENT;
    if (cel >= scene->cel_count || (parent != CS_NO_PARENT && parent >= scene->cel_count)) {
        cs__error(err, CS_ERR_INDEX, (int32_t)cel, -1, -1, -1);
        return CS_ERR_INDEX;
    }
#if CS_CFG_ANIM_PARTS
    /* Every chain through `cel` must stay short and acyclic; the frame
     * follows chains without checking them again. */
    for (uint32_t c = 0; c < scene->cel_count; c++)
        if (chain_length(scene, c, cel, parent) > CS_CFG_MAX_GROUP_DEPTH) {
            cs__error(err, CS_ERR_GROUP, (int32_t)cel, -1, -1, -1);
            return CS_ERR_GROUP;
        }
#else
    if (parent != CS_NO_PARENT) { /* groups are left out of this build */
        cs__error(err, CS_ERR_GROUP, (int32_t)cel, -1, -1, -1);
        return CS_ERR_GROUP;
    }
#endif
    scene->cels[cel].parent = (uint8_t)parent;
    cs__error(err, CS_OK, -1, -1, -1, -1);
    return CS_OK;
}

cs_status cs_scene_move_cel(cs_scene *scene, uint32_t from, uint32_t to, cs_error *err)
{
    if (!scene) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    if (from >= scene->cel_count || to >= scene->cel_count) {
        cs__error(err, CS_ERR_INDEX, -1, -1, -1, -1);
        return CS_ERR_INDEX;
    }
    cs_cel moving;
    CS__COPY(&moving, &scene->cels[from]);
    if (from < to)
        CS__COPY_N(&scene->cels[from], &scene->cels[from + 1], to - from);
    else
        for (uint32_t i = from; i > to; i--) /* upwards: a backward loop */
            CS__COPY(&scene->cels[i], &scene->cels[i - 1]);
    CS__COPY(&scene->cels[to], &moving);
    for (uint32_t i = 0; i < scene->cel_count; i++)
        if (scene->cels[i].parent != CS_NO_PARENT)
            scene->cels[i].parent = (uint8_t)moved_index(scene->cels[i].parent, from, to);
    for (uint32_t i = 0; i < scene->track_count; i++) {
        cs_track *t = &scene->tracks[i];
        if (cs__track_family(t->kind) == CS__FAM_CEL)
            t->target = moved_index(t->target, from, to);
    }
    cs__tracks_sort(scene);
    cs__error(err, CS_OK, -1, -1, -1, -1);
    return CS_OK;
}

void cs_scene_copy(cs_scene *dst, const cs_scene *src)
{
    if (!dst || !src || dst == src)
        return;
    dst->canvas_w = src->canvas_w;
    dst->canvas_h = src->canvas_h;
    dst->has_background = src->has_background;
    dst->blend = src->blend;
    dst->epoch_ns = src->epoch_ns;
    cs__copy3(dst->background, src->background);
    cs__copy3(dst->stack_front, src->stack_front);
    cs__copy3(dst->stack_back, src->stack_back);
    dst->cel_count = src->cel_count;
    dst->region_count = src->region_count;
    dst->contour_count = src->contour_count;
    dst->point_count = src->point_count;
    dst->func_count = src->func_count;
    dst->track_count = src->track_count;
    dst->key_count = src->key_count;
    dst->value_count = src->value_count;
    dst->open_track = src->open_track;
    CS__COPY_N(dst->funcs, src->funcs, src->func_count);
    CS__COPY_N(dst->cels, src->cels, src->cel_count);
    CS__COPY_N(dst->regions, src->regions, src->region_count);
    CS__COPY_N(dst->contours, src->contours, src->contour_count);
    CS__COPY_N(dst->points, src->points, src->point_count);
    CS__COPY_N(dst->intervals, src->intervals, src->point_count);
    CS__COPY_N(dst->tracks, src->tracks, src->track_count);
    CS__COPY_N(dst->key_times, src->key_times, src->key_count);
    CS__COPY_N(dst->key_values, src->key_values, src->value_count);
}
