/*
 * cs_stream_apply.c - applying a cel stream's records: once a record's
 * fields are all in (its fixed part in the decoder's buffer, its points,
 * keys or function already read into the back store), it becomes the
 * cs_scene_* call that the JSON loader makes for the same thing, so a
 * stream and its JSON give identical stores. The decoder (cs_stream.c)
 * frames, checks and reads the records; this file only applies them.
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

/* Records that build a scene: the scene, its canvas and lights, cels,
 * regions and contours. Returns false for any other type. */
static bool apply_build(cs_stream *s, cs_error *where, cs_status *out)
{
    cs_scene *sc = s->back;
    const uint8_t *b = s->buf;
    cs_status st = CS_OK;
    float f[6];
    cs_affine m;
    cs_paint paint;
    switch (s->rec_type) {
    case CS_REC_COMMIT:
        s->seen_commit = true;
        break;
    case CS_REC_SCENE:
        st = cs_scene_init(sc, cs__rd_f32(b), cs__rd_f32(b + 4));
        break;
    case CS_REC_CANVAS:
        st = cs_scene_set_canvas(sc, cs__rd_f32(b), cs__rd_f32(b + 4));
        break;
    case CS_REC_LIGHTS:
        cs__rd_f32s(b, f, 6);
        st = cs_scene_set_lights(sc, f, f + 3);
        break;
    case CS_REC_BACKGROUND:
        cs__rd_f32s(b, f, 3);
        st = cs_scene_set_background(sc, f);
        break;
    case CS_REC_NO_BACKGROUND:
        st = cs_scene_clear_background(sc);
        break;
    case CS_REC_BLEND:
        st = cs__rd_u32(b) > 1u ? CS_ERR_STREAM_RECORD : cs_scene_set_blend(sc, (cs_blend)cs__rd_u32(b));
        break;
    case CS_REC_EPOCH:
        st = cs_scene_set_epoch(sc, (uint64_t)cs__rd_u32(b) | (uint64_t)cs__rd_u32(b + 4) << 32);
        break;
    case CS_REC_CEL:
        wire_affine(b + 4, &m);
        cs__rd_f32s(b + 28, f, 6);
        st = cs_scene_add_cel(sc, &m, (s->rec_flags & CS_WIRE_CEL_HAS_FRONT) ? f : 0, f + 3,
                              where);
        break;
    case CS_REC_REGION:
        wire_paint(b + 4, &paint);
        st = cs_scene_add_region(sc, wire_rule(cs__rd_u32(b)), &paint, where);
        break;
    case CS_REC_CONTOUR: {
        uint32_t degree = cs__rd_u32(b);
        st = cs_scene_add_contour(sc, degree > 3 ? 4 : (int)degree, (int)s->count,
                                  &sc->points[s->base],
                                  (s->rec_flags & CS_WIRE_CONTOUR_INTERVALS) ? &sc->intervals[s->base]
                                                                           : 0,
                                  where);
        break;
    }
    default:
        return false;
    }
    *out = st;
    return true;
}

/* Records that change a scene in place: removals, moves, transforms,
 * lights, paints, points, tracks, functions and CSG. Returns false for any
 * other type. */
static bool apply_edit(cs_stream *s, cs_error *where, cs_status *out)
{
    cs_scene *sc = s->back;
    const uint8_t *b = s->buf;
    cs_status st = CS_OK;
    float f[6];
    cs_affine m;
    cs_paint paint;
    switch (s->rec_type) {
    case CS_REC_CEL_REMOVE:
        st = cs_scene_remove_cel(sc, cs__rd_u32(b), where);
        break;
    case CS_REC_CEL_MOVE:
        st = cs_scene_move_cel(sc, cs__rd_u32(b), cs__rd_u32(b + 4), where);
        break;
    case CS_REC_CEL_PARENT:
        st = cs_scene_set_cel_parent(sc, cs__rd_u32(b), cs__rd_u32(b + 4), where);
        break;
    case CS_REC_CEL_TRANSFORM:
        wire_affine(b + 4, &m);
        st = cs_scene_set_transform(sc, cs__rd_u32(b), &m, where);
        break;
    case CS_REC_CEL_LIGHTS:
        cs__rd_f32s(b + 8, f, 6);
        st = cs_scene_set_cel_lights(sc, cs__rd_u32(b), (s->rec_flags & CS_WIRE_CEL_HAS_FRONT) ? f : 0,
                                     f + 3, where);
        break;
    case CS_REC_REGION_PAINT:
        wire_paint(b + 8, &paint);
        st = cs_scene_set_paint(sc, cs__rd_u32(b), wire_rule(cs__rd_u32(b + 4)), &paint, where);
        break;
    case CS_REC_CONTOUR_POINTS:
        st = cs_scene_set_points(sc, cs__rd_u32(b), (int)s->count, &sc->points[s->base],
                                 (s->rec_flags & CS_WIRE_CONTOUR_INTERVALS) ? &sc->intervals[s->base]
                                                                          : 0,
                                 where);
        break;
    case CS_REC_TRACK:
        break; /* every key was added as it arrived */
    case CS_REC_REGION_FUNC:
        /* The function was read into its slot; the call checks it there. */
        st = cs_scene_set_region_func(sc, (cs_paint_field)cs__rd_u32(b), &sc->funcs[s->base], where);
        break;
    case CS_REC_REGION_CSG: {
        int rpn[CS_CFG_MAX_CSG];
        for (uint32_t i = 0; i < s->count; i++) {
            uint8_t t = b[4 + i];
            rpn[i] = (t & 0x80u) ? -(int)(t & 0x7Fu) : (int)t;
        }
        st = cs_scene_set_region_csg(sc, rpn, (int)s->count, where);
        break;
    }
    case CS_REC_CONTOUR_OPERAND: {
        uint32_t op = cs__rd_u32(b);
        st = cs_scene_set_contour_operand(sc, op > CS_CFG_MAX_OPERANDS ? -1 : (int)op, where);
        break;
    }
    case CS_REC_TRACK_REMOVE: {
        uint32_t kind = cs__rd_u32(b);
        st = cs_scene_remove_track(
            sc, kind < CS_TRACK_KIND_COUNT_ ? (cs_track_kind)kind : CS_TRACK_KIND_COUNT_,
            cs__rd_u32(b + 4), where);
        break;
    }
    default:
        return false;
    }
    *out = st;
    return true;
}

cs_status cs__stream_apply(cs_stream *s, cs_error *where)
{
    cs_status st = CS_OK;
    if (!apply_build(s, where, &st))
        apply_edit(s, where, &st);
    return st;
}
