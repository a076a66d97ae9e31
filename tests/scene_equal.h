/*
 * scene_equal.h - compares two scene stores field by field, bit for bit.
 *
 * Shared by the stream tests (test_stream.c: encoder and decoder give the
 * very store they were given) and the scene tests (test_scenes.c: a scene
 * JSON and its compiled stream give the same store). Only the used part of
 * each array is compared, as cs_scene_copy copies it, and every field the
 * renderer reads is in: geometry, paints, paint functions (all stops, also
 * the padding copies beyond stop_count), CSG programs, contour operands,
 * tracks and their key pools. Header-only: static functions.
 */
#ifndef TESTS_SCENE_EQUAL_H
#define TESTS_SCENE_EQUAL_H

#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "celscan_private.h"

static bool scene_eq_bits(const void *a, const void *b, size_t n)
{
    return memcmp(a, b, n) == 0;
}

#define SCENE_EQ_F(a, b) scene_eq_bits(&(a), &(b), sizeof(a))

static bool scene_eq_func(const cs_paint_func *x, const cs_paint_func *y)
{
    if (x->kind != y->kind || x->spread != y->spread || x->stop_count != y->stop_count ||
        x->map_cols != y->map_cols || !SCENE_EQ_F(x->geom, y->geom))
        return false;
    for (int i = 0; i < CS_CFG_MAX_STOPS; i++)
        if (!SCENE_EQ_F(x->stops[i].offset, y->stops[i].offset) ||
            !SCENE_EQ_F(x->stops[i].value, y->stops[i].value))
            return false;
    return true;
}

/* Every used field of two stores, bit for bit; `why` names the first difference. */
static __attribute__((unused)) bool scene_equal(const cs_scene *a, const cs_scene *b, char *why,
                                                size_t whylen)
{
#define DIFF(...)                                                                                 \
    do {                                                                                          \
        snprintf(why, whylen, __VA_ARGS__);                                                       \
        return false;                                                                             \
    } while (0)
    if (!SCENE_EQ_F(a->canvas_w, b->canvas_w) || !SCENE_EQ_F(a->canvas_h, b->canvas_h))
        DIFF("canvas");
    if (a->has_background != b->has_background || !SCENE_EQ_F(a->background, b->background))
        DIFF("background");
    if (a->blend != b->blend)
        DIFF("blend");
    if (a->epoch_ns != b->epoch_ns)
        DIFF("epoch");
    if (!SCENE_EQ_F(a->stack_front, b->stack_front) || !SCENE_EQ_F(a->stack_back, b->stack_back))
        DIFF("stack lights");
    if (a->cel_count != b->cel_count || a->region_count != b->region_count ||
        a->contour_count != b->contour_count || a->point_count != b->point_count)
        DIFF("counts %u/%u %u/%u %u/%u %u/%u", a->cel_count, b->cel_count, a->region_count,
             b->region_count, a->contour_count, b->contour_count, a->point_count, b->point_count);
    if (a->func_count != b->func_count)
        DIFF("function counts %u/%u", a->func_count, b->func_count);
    if (a->track_count != b->track_count || a->key_count != b->key_count ||
        a->value_count != b->value_count)
        DIFF("track counts %u/%u %u/%u %u/%u", a->track_count, b->track_count, a->key_count,
             b->key_count, a->value_count, b->value_count);
    for (uint32_t i = 0; i < a->cel_count; i++) {
        const cs_cel *x = &a->cels[i], *y = &b->cels[i];
        if (x->first_region != y->first_region || x->region_count != y->region_count ||
            x->has_front != y->has_front || !SCENE_EQ_F(x->transform, y->transform) ||
            !SCENE_EQ_F(x->front, y->front) || !SCENE_EQ_F(x->back, y->back) ||
            x->parent != y->parent)
            DIFF("cel %u", i);
    }
    for (uint32_t i = 0; i < a->region_count; i++) {
        const cs_region *x = &a->regions[i], *y = &b->regions[i];
        if (x->first_contour != y->first_contour || x->contour_count != y->contour_count ||
            x->fill_rule != y->fill_rule || !SCENE_EQ_F(x->paint, y->paint))
            DIFF("region %u", i);
        if (!SCENE_EQ_F(x->func, y->func))
            DIFF("region %u: paint functions %u %u %u / %u %u %u", i, x->func[0], x->func[1],
                 x->func[2], y->func[0], y->func[1], y->func[2]);
        if (x->csg_len != y->csg_len || !scene_eq_bits(x->csg, y->csg, x->csg_len))
            DIFF("region %u: CSG program", i);
    }
    for (uint32_t i = 0; i < a->func_count; i++)
        if (!scene_eq_func(&a->funcs[i], &b->funcs[i]))
            DIFF("paint function %u", i);
    for (uint32_t i = 0; i < a->contour_count; i++) {
        const cs_contour *x = &a->contours[i], *y = &b->contours[i];
        if (x->first_point != y->first_point || x->point_count != y->point_count ||
            x->degree != y->degree)
            DIFF("contour %u", i);
        if (x->operand != y->operand)
            DIFF("contour %u: operand %u/%u", i, x->operand, y->operand);
    }
    if (!scene_eq_bits(a->points, b->points, a->point_count * sizeof(cs_point)))
        DIFF("points");
    if (!scene_eq_bits(a->intervals, b->intervals, a->point_count * sizeof(float)))
        DIFF("intervals");
    for (uint32_t i = 0; i < a->track_count; i++) {
        const cs_track *x = &a->tracks[i], *y = &b->tracks[i];
        if (x->target != y->target || x->first_key != y->first_key ||
            x->first_value != y->first_value || x->width != y->width ||
            x->key_count != y->key_count || x->kind != y->kind || x->ease != y->ease)
            DIFF("track %u", i);
    }
    if (!scene_eq_bits(a->key_times, b->key_times, a->key_count * sizeof(float)))
        DIFF("key times");
    if (!scene_eq_bits(a->key_values, b->key_values, a->value_count * sizeof(float)))
        DIFF("key values");
    return true;
#undef DIFF
}

#endif /* TESTS_SCENE_EQUAL_H */
