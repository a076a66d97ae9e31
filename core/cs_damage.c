/*
 * cs_damage.c - the window of a frame that can differ from the last one.
 *
 * A board's panel keeps its picture, so a frame need only redraw what
 * changed: a small cel that moves over a still background changes the
 * pixels it left and the ones it reaches, nothing else. Compositing is per
 * pixel, so a pixel can change only if a cel that covers it (before or
 * after) changed, or the card and lights behind every cel did. Each cel is
 * therefore summed up by a signature of everything of it that reaches the
 * render at the frame's time - its stored data (regions, paints, paint
 * functions, contours, control points, knot intervals, lights) and what its
 * tracks give at that time (world transform and opacity with its groups',
 * lights, paints, the keys its points are sampled from) - and by the pixels
 * its contours' control points reach through that transform: with positive
 * weights a NURBS curve stays inside their convex hull, and one pixel of
 * margin on each side takes the anti-aliased edge pixels and rounding. The
 * damage is the union of the old and the new extents of every cel whose
 * signature changed, with the cel at each stack position compared to the
 * one there before (a cel that moved in the stack, came or went changes
 * the positions' signatures, so their extents are redrawn). The frame's
 * own state (size, AA, blending, card, stack lights) changing damages
 * everything.
 *
 * The window is then rendered as a viewport, which gives the whole
 * render's bits for rows and for columns from 0 (cs_frame.c, cs_coverage.c);
 * a window that starts right of column 0 is exact only where coverage sums
 * are exact in any order (centre sampling, or 2^k sub-scanlines), so with
 * other AA it is widened to start at column 0.
 */
#include "cs_internal.h"

/* The extent being built: device coordinates, or "everything" on a number
 * that is not finite. */
typedef struct box {
    float x0, y0, x1, y1;
    bool all;
} box;

static void box_add(box *b, const float *dev, float x, float y)
{
    float dx = dev[0] * x + dev[2] * y + dev[4], dy = dev[1] * x + dev[3] * y + dev[5];
    if (!(cs__finite(dx) && cs__finite(dy))) {
        b->all = true;
        return;
    }
    b->x0 = dx < b->x0 ? dx : b->x0;
    b->x1 = dx > b->x1 ? dx : b->x1;
    b->y0 = dy < b->y0 ? dy : b->y0;
    b->y1 = dy > b->y1 ? dy : b->y1;
}

/* A device coordinate as a pixel edge in 0..limit, `pad` pixels outward. */
static int32_t edge(float v, int32_t pad, int32_t limit)
{
    if (!(v > -1e6f))
        return 0;
    if (!(v < 1e6f))
        return limit;
    int32_t i = cs__floori(v) + pad;
    return i < 0 ? 0 : i > limit ? limit : i;
}

/* Contour ki's control points (as sampled at t, when a points track moves
 * them: then those of the keys either side, whose blend lies between them)
 * into the extent and the signature. */
static uint32_t contour_state(const cs_scene *scene, uint32_t ki, float t, const float *dev,
                              box *b, uint32_t sig)
{
    const cs_contour *c = &scene->contours[ki];
    sig = cs_crc32(sig, c, sizeof *c);
    sig = cs_crc32(sig, &scene->intervals[c->first_point], c->point_count * sizeof(float));
    const cs_track *tr = cs__track_find(scene, CS_TRACK_POINTS, ki);
    if (tr != 0 && tr->key_count && tr->width - cs__track_lead(tr) == 3u * c->point_count &&
        c->point_count <= CS_CFG_MAX_ANIM_POINTS) {
        uint32_t i0, i1;
        float s;
        cs__track_locate(scene, tr, t, &i0, &i1, &s);
        if (i0 == i1)
            s = 0.0f;
        uint32_t lead = cs__track_lead(tr);
        for (uint32_t key = i0;; key = i1) {
            const float *v = &scene->key_values[tr->first_value + key * tr->width + lead];
            sig = cs_crc32(sig, v, 3u * c->point_count * sizeof(float));
            for (uint32_t k = 0; k < c->point_count; k++)
                box_add(b, dev, v[3 * k], v[3 * k + 1]);
            if (key == i1)
                break;
        }
        sig = cs_crc32(sig, &i0, sizeof i0);
        sig = cs_crc32(sig, &i1, sizeof i1);
        return cs_crc32(sig, &s, sizeof s);
    }
    const cs_point *p = &scene->points[c->first_point];
    sig = cs_crc32(sig, p, c->point_count * sizeof *p);
    for (uint32_t k = 0; k < c->point_count; k++)
        box_add(b, dev, p[k].x, p[k].y);
    return sig;
}

/* Cel ci at time t: its signature, and its extent in output pixels. */
static uint32_t cel_state(const cs_scene *scene, uint32_t ci, float t, float sx, float sy,
                          int32_t width, int32_t height, int32_t ext[4])
{
    const cs_cel *cel = &scene->cels[ci];
    float m[7];
    m[6] = cs__cel_world(scene, ci, t, m);
    uint32_t sig = cs_crc32(0, cel, sizeof *cel);
    sig = cs_crc32(sig, m, sizeof m);
    const cs_track *tr = cs__track_find(scene, CS_TRACK_CEL_LIGHTS, ci);
    if (tr != 0 && tr->key_count) {
        float lights[6];
        cs__track_sample(scene, tr, t, lights);
        sig = cs_crc32(sig, lights, sizeof lights);
    }
    float dev[6] = {m[0] * sx, m[1] * sy, m[2] * sx, m[3] * sy, m[4] * sx, m[5] * sy};
    box b = {1e30f, 1e30f, -1e30f, -1e30f, false};
    for (uint32_t ri = cel->first_region; ri < cel->first_region + cel->region_count; ri++) {
        const cs_region *reg = &scene->regions[ri];
        cs_paint animated;
        const cs_paint *paint = cs__region_paint(scene, ri, t, m[6], &animated);
        sig = cs_crc32(sig, reg, sizeof *reg);
        sig = cs_crc32(sig, paint, sizeof *paint);
        for (int f = 0; f < 3; f++)
            if (reg->func[f])
                sig = cs_crc32(sig, &scene->funcs[reg->func[f] - 1u], sizeof(cs_paint_func));
        for (uint32_t k = 0; k < reg->contour_count; k++)
            sig = contour_state(scene, reg->first_contour + k, t, dev, &b, sig);
    }
    if (b.all) {
        ext[0] = ext[1] = 0;
        ext[2] = width;
        ext[3] = height;
    } else if (b.x0 > b.x1) {
        ext[0] = ext[1] = ext[2] = ext[3] = 0; /* no contours: no pixels */
    } else {
        ext[0] = edge(b.x0, -1, width);
        ext[1] = edge(b.y0, -1, height);
        ext[2] = edge(b.x1, 2, width);
        ext[3] = edge(b.y1, 2, height);
    }
    return sig;
}

/* The frame's own state: what, when it changes, changes every pixel. */
static uint32_t frame_state(const cs_scene *scene, const cs_render_opts *o)
{
    float v[12] = {(float)o->width, (float)o->height, (float)o->aa, (float)o->subscanlines,
                   (float)(o->blend == CS_BLEND_SCENE ? scene->blend : o->blend),
                   scene->canvas_w, scene->canvas_h, scene->has_background ? 1.0f : 0.0f};
    cs__copy3(v + 9, scene->background);
    const cs_track *tr = cs__track_find(scene, CS_TRACK_BACKGROUND, 0);
    if (tr && tr->key_count)
        cs__track_sample(scene, tr, o->time, v + 9);
    uint32_t sig = cs_crc32(0, v, 12 * sizeof(float));
    cs__copy3(v, scene->stack_front);
    cs__copy3(v + 3, scene->stack_back);
    tr = cs__track_find(scene, CS_TRACK_STACK_LIGHTS, 0);
    if (tr && tr->key_count)
        cs__track_sample(scene, tr, o->time, v);
    return cs_crc32(sig, v, 6 * sizeof(float));
}

void cs_damage_reset(cs_damage *d)
{
    if (d)
        d->valid = 0;
}

static void grow(cs_rect *w, const int32_t *e)
{
    if (e[0] >= e[2] || e[1] >= e[3])
        return;
    if (w->x0 >= w->x1) {
        w->x0 = e[0], w->y0 = e[1], w->x1 = e[2], w->y1 = e[3];
        return;
    }
    w->x0 = e[0] < w->x0 ? e[0] : w->x0;
    w->y0 = e[1] < w->y0 ? e[1] : w->y0;
    w->x1 = e[2] > w->x1 ? e[2] : w->x1;
    w->y1 = e[3] > w->y1 ? e[3] : w->y1;
}

cs_status cs_frame_damage(cs_damage *d, const cs_scene *scene, const cs_render_opts *opts,
                          cs_rect *window)
{
    if (!d || !scene || !opts || !window || opts->width < 1 || opts->height < 1 ||
        opts->width > CS_CFG_MAX_WALL || opts->height > CS_CFG_MAX_WALL ||
        !(scene->canvas_w > 0.0f && scene->canvas_h > 0.0f) || scene->cel_count > CS_CFG_MAX_CELS)
        return CS_ERR_ARG;
    int32_t w = opts->width, h = opts->height;
    float sx = (float)w / scene->canvas_w, sy = (float)h / scene->canvas_h;
    uint32_t fsig = frame_state(scene, opts);
    bool all = !d->valid || fsig != d->frame_sig;
    window->x0 = window->y0 = window->x1 = window->y1 = 0;
    uint32_t old_count = all ? 0u : d->cel_count;
    /* Extents are kept in units of u pixels, rounded outward: a byte each. */
    int32_t u = ((w > h ? w : h) + 254) / 255;
    for (uint32_t ci = 0; ci < scene->cel_count || ci < old_count; ci++) {
        int32_t ext[4] = {0, 0, 0, 0};
        uint32_t sig = 0;
        if (ci < scene->cel_count) {
            sig = cel_state(scene, ci, opts->time, sx, sy, w, h, ext);
            ext[0] /= u, ext[1] /= u;
            ext[2] = (ext[2] + u - 1) / u, ext[3] = (ext[3] + u - 1) / u;
        }
        if (ci >= old_count || ci >= scene->cel_count || sig != d->cels[ci].sig) {
            if (ci < old_count) {
                int32_t was[4] = {d->cels[ci].x0, d->cels[ci].y0, d->cels[ci].x1, d->cels[ci].y1};
                grow(window, was);
            }
            grow(window, ext);
        }
        if (ci < scene->cel_count) {
            d->cels[ci].sig = sig;
            d->cels[ci].x0 = (uint8_t)ext[0];
            d->cels[ci].y0 = (uint8_t)ext[1];
            d->cels[ci].x1 = (uint8_t)ext[2];
            d->cels[ci].y1 = (uint8_t)ext[3];
        }
    }
    /* Back to pixels, within the output. */
    window->x0 *= u, window->y0 *= u;
    window->x1 = window->x1 * u < w ? window->x1 * u : w;
    window->y1 = window->y1 * u < h ? window->y1 * u : h;
    d->valid = 1;
    d->frame_sig = fsig;
    d->cel_count = scene->cel_count;
    if (all) {
        window->x0 = window->y0 = 0;
        window->x1 = w;
        window->y1 = h;
    }
    bool narrow = opts->aa == CS_AA_NONE ||
                  (opts->aa == CS_AA_SUBSCAN && (opts->subscanlines & (opts->subscanlines - 1)) == 0);
    if (!narrow && window->x0 < window->x1)
        window->x0 = 0;
    return CS_OK;
}
