/*
 * cs_stream_apply.c - the record types of the cel stream, one table row
 * each: the size of its fixed part, the layout of what follows (how the
 * decoder reads it) and the function that applies it. Once a record's
 * fields are all in (its fixed part in the decoder's buffer, its points,
 * keys or function already read into the back store), it becomes the
 * cs_scene_* call that the JSON loader makes for the same thing, so a
 * stream and its JSON give identical stores. The decoder (cs_stream.c)
 * frames, checks and reads the records by their row; adding a record type
 * is a row here and, if it needs one, an apply function.
 */
#include "cs_stream_internal.h"

void cs__rd_f32s(const uint8_t *p, float *out, int n)
{
    for (int i = 0; i < n; i++)
        out[i] = cs__rd_f32(p + 4 * i);
}

/* Fill rule from the wire: anything but 0 or 1 becomes an invalid value the
 * scene call rejects with its location. */
static cs_fill_rule wire_rule(uint32_t v)
{
    return v <= 1 ? (cs_fill_rule)v : (cs_fill_rule)2;
}

static void wire_paint(const uint8_t *p, cs_paint *paint)
{
    cs__rd_f32s(p, paint->pigment, 3);
    cs__rd_f32s(p + 12, paint->medium, 3);
    paint->beta = cs__rd_f32(p + 24);
}

static void wire_affine(const uint8_t *p, cs_affine *m)
{
    m->a = cs__rd_f32(p);
    m->b = cs__rd_f32(p + 4);
    m->c = cs__rd_f32(p + 8);
    m->d = cs__rd_f32(p + 12);
    m->e = cs__rd_f32(p + 16);
    m->f = cs__rd_f32(p + 20);
}

static cs_status apply_commit(cs_stream *s, cs_error *where)
{
    (void)where;
    s->seen_commit = true;
    return CS_OK;
}

static cs_status apply_scene(cs_stream *s, cs_error *where)
{
    (void)where;
    return cs_scene_init(s->back, cs__rd_f32(s->buf), cs__rd_f32(s->buf + 4));
}

static cs_status apply_canvas(cs_stream *s, cs_error *where)
{
    (void)where;
    return cs_scene_set_canvas(s->back, cs__rd_f32(s->buf), cs__rd_f32(s->buf + 4));
}

static cs_status apply_lights(cs_stream *s, cs_error *where)
{
    float f[6];
    (void)where;
    cs__rd_f32s(s->buf, f, 6);
    return cs_scene_set_lights(s->back, f, f + 3);
}

static cs_status apply_background(cs_stream *s, cs_error *where)
{
    float f[3];
    (void)where;
    cs__rd_f32s(s->buf, f, 3);
    return cs_scene_set_background(s->back, f);
}

static cs_status apply_no_background(cs_stream *s, cs_error *where)
{
    (void)where;
    return cs_scene_clear_background(s->back);
}

static cs_status apply_blend(cs_stream *s, cs_error *where)
{
    uint32_t blend = cs__rd_u32(s->buf);
    (void)where;
    return blend > 1u ? CS_ERR_STREAM_RECORD : cs_scene_set_blend(s->back, (cs_blend)blend);
}

static cs_status apply_epoch(cs_stream *s, cs_error *where)
{
    (void)where;
    return cs_scene_set_epoch(s->back, (uint64_t)cs__rd_u32(s->buf) |
                                           (uint64_t)cs__rd_u32(s->buf + 4) << 32);
}

static cs_status apply_cel(cs_stream *s, cs_error *where)
{
    float f[6];
    cs_affine m;
    wire_affine(s->buf + 4, &m);
    cs__rd_f32s(s->buf + 28, f, 6);
    return cs_scene_add_cel(s->back, &m, (s->rec_flags & CS_WIRE_CEL_HAS_FRONT) ? f : 0, f + 3,
                            where);
}

static cs_status apply_region(cs_stream *s, cs_error *where)
{
    cs_paint paint;
    wire_paint(s->buf + 4, &paint);
    return cs_scene_add_region(s->back, wire_rule(cs__rd_u32(s->buf)), &paint, where);
}

/* The knot intervals read with a CONTOUR or CONTOUR_POINTS record, if it has them. */
static const float *wire_intervals(const cs_stream *s)
{
    return (s->rec_flags & CS_WIRE_CONTOUR_INTERVALS) ? &s->back->intervals[s->base] : 0;
}

static cs_status apply_contour(cs_stream *s, cs_error *where)
{
    uint32_t degree = cs__rd_u32(s->buf);
    return cs_scene_add_contour(s->back, degree > 3 ? 4 : (int)degree, (int)s->count,
                                &s->back->points[s->base], wire_intervals(s), where);
}

static cs_status apply_cel_remove(cs_stream *s, cs_error *where)
{
    return cs_scene_remove_cel(s->back, cs__rd_u32(s->buf), where);
}

static cs_status apply_cel_move(cs_stream *s, cs_error *where)
{
    return cs_scene_move_cel(s->back, cs__rd_u32(s->buf), cs__rd_u32(s->buf + 4), where);
}

static cs_status apply_cel_parent(cs_stream *s, cs_error *where)
{
    return cs_scene_set_cel_parent(s->back, cs__rd_u32(s->buf), cs__rd_u32(s->buf + 4), where);
}

static cs_status apply_cel_transform(cs_stream *s, cs_error *where)
{
    cs_affine m;
    wire_affine(s->buf + 4, &m);
    return cs_scene_set_transform(s->back, cs__rd_u32(s->buf), &m, where);
}

static cs_status apply_cel_lights(cs_stream *s, cs_error *where)
{
    float f[6];
    cs__rd_f32s(s->buf + 8, f, 6);
    return cs_scene_set_cel_lights(s->back, cs__rd_u32(s->buf),
                                   (s->rec_flags & CS_WIRE_CEL_HAS_FRONT) ? f : 0, f + 3, where);
}

static cs_status apply_region_paint(cs_stream *s, cs_error *where)
{
    cs_paint paint;
    wire_paint(s->buf + 8, &paint);
    return cs_scene_set_paint(s->back, cs__rd_u32(s->buf), wire_rule(cs__rd_u32(s->buf + 4)),
                              &paint, where);
}

static cs_status apply_contour_points(cs_stream *s, cs_error *where)
{
    return cs_scene_set_points(s->back, cs__rd_u32(s->buf), (int)s->count,
                               &s->back->points[s->base], wire_intervals(s), where);
}

static cs_status apply_track_remove(cs_stream *s, cs_error *where)
{
    uint32_t kind = cs__rd_u32(s->buf);
    return cs_scene_remove_track(
        s->back, kind < CS_TRACK_KIND_COUNT_ ? (cs_track_kind)kind : CS_TRACK_KIND_COUNT_,
        cs__rd_u32(s->buf + 4), where);
}

/* The function was read into its slot; the call checks it there. */
static cs_status apply_region_func(cs_stream *s, cs_error *where)
{
    return cs_scene_set_region_func(s->back, (cs_paint_field)cs__rd_u32(s->buf),
                                    &s->back->funcs[s->base], where);
}

static cs_status apply_region_csg(cs_stream *s, cs_error *where)
{
    int rpn[CS_CFG_MAX_CSG];
    for (uint32_t i = 0; i < s->count; i++) {
        uint8_t t = s->buf[4 + i];
        rpn[i] = (t & 0x80u) ? -(int)(t & 0x7Fu) : (int)t;
    }
    return cs_scene_set_region_csg(s->back, rpn, (int)s->count, where);
}

static cs_status apply_contour_operand(cs_stream *s, cs_error *where)
{
    uint32_t op = cs__rd_u32(s->buf);
    return cs_scene_set_contour_operand(s->back, op > CS_CFG_MAX_OPERANDS ? -1 : (int)op, where);
}

/*
 * Every record type this version applies, in wire order (cs_wire.h has
 * their fields). PAD and types of a known class that are not here (a newer
 * minor version's) are skipped. TRACK needs no apply function: each key was
 * added as it arrived.
 */
const cs__rec_kind cs__rec_kinds[] = {
    {CS_REC_COMMIT, 0, L_FIXED, apply_commit},
    {CS_REC_SCENE, 8, L_FIXED, apply_scene},
    {CS_REC_CANVAS, 8, L_FIXED, apply_canvas},
    {CS_REC_LIGHTS, 24, L_FIXED, apply_lights},
    {CS_REC_BACKGROUND, 12, L_FIXED, apply_background},
    {CS_REC_NO_BACKGROUND, 0, L_FIXED, apply_no_background},
    {CS_REC_BLEND, 4, L_FIXED, apply_blend},
    {CS_REC_EPOCH, 8, L_FIXED, apply_epoch},
    {CS_REC_CEL, 52, L_FLAGS_AT0, apply_cel},
    {CS_REC_REGION, 32, L_FIXED, apply_region},
    {CS_REC_CONTOUR, 12, L_POINTS_NEW, apply_contour},
    {CS_REC_CEL_REMOVE, 4, L_FIXED, apply_cel_remove},
    {CS_REC_CEL_MOVE, 8, L_FIXED, apply_cel_move},
    {CS_REC_CEL_TRANSFORM, 28, L_FIXED, apply_cel_transform},
    {CS_REC_CEL_LIGHTS, 32, L_FLAGS_AT4, apply_cel_lights},
    {CS_REC_REGION_PAINT, 36, L_FIXED, apply_region_paint},
    {CS_REC_CONTOUR_POINTS, 12, L_POINTS_AT, apply_contour_points},
    {CS_REC_TRACK, 16, L_KEYS, 0},
    {CS_REC_TRACK_REMOVE, 8, L_FIXED, apply_track_remove},
    {CS_REC_REGION_FUNC, 44, L_STOPS, apply_region_func},
    {CS_REC_REGION_CSG, 4, L_TOKENS, apply_region_csg},
    {CS_REC_CONTOUR_OPERAND, 4, L_FIXED, apply_contour_operand},
    {CS_REC_CEL_PARENT, 8, L_FIXED, apply_cel_parent},
};

int cs__rec_kind_find(uint32_t type)
{
    for (int i = 0; i < (int)(sizeof cs__rec_kinds / sizeof cs__rec_kinds[0]); i++)
        if (cs__rec_kinds[i].type == type)
            return i;
    return -1;
}
