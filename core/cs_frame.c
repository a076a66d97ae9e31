/*
 * cs_frame.c - per-frame preparation: scene at time t to monotone pieces.
 *
 * Once per frame the scene's contours are transformed to device space,
 * converted to rational polynomial segments, and every segment is split
 * where its y(u) = Y(u)/W(u) turns, giving y-monotone pieces. A monotone
 * piece meets a scanline at most once, so a line needs one bracketed solve
 * per active piece and never a search for several roots.
 *
 * Parity is made exact here, not in the solver: consecutive pieces of a
 * contour share their end y values bit for bit (the end of a segment takes
 * the start value of the next one), and a piece counts a scanline y when
 * y_top <= y < y_bot. The chain of end values of a closed contour is closed,
 * so every scanline meets it an even number of times with net winding zero,
 * through vertices, tangents and cusps alike, whatever rounding the solver
 * does in between.
 *
 * With a viewport, pieces wholly above or below its rows are left out, and
 * so are the segments left without a piece and the contours that lie
 * wholly outside: no line would read them, and the arena holds only what
 * the rows need (one segment more while a contour is converted). Without
 * one, every segment and piece is kept, as the tests of the conversion
 * expect (a horizontal edge is a segment without pieces). A board renders a scene larger than its
 * arena in bands of rows, each prepared as a viewport (firmware/fw_render.c).
 *
 * Pieces are then ordered by where they start (y_top, or its line: see
 * goes_before) so that each line can pick up the newly active ones with a
 * moving index instead of scanning them all.
 *
 * The frame also fixes what the lines need besides geometry: each region's
 * (E, T) map under its cel's lights (or, for functional paints, each
 * function compiled to device space), the pixels every segment can touch (so a
 * line can skip a region lying wholly where the stack is already opaque),
 * and, for CSG regions, which operand's winding each piece moves. Cels
 * held in a pre-combination cache are not converted at all.
 * Animation is evaluated here too, at opts->time, and nowhere else: each
 * cel, region and contour looks up its track (cs_anim.c) and uses the
 * sampled value in place of the stored one. An animated contour's points
 * are sampled into ws->anim_points, one contour at a time, so the workspace
 * grows by one contour, not by a copy of the scene.
 *
 * A host with threads prepares a frame in parts, ranges of cels, each in a
 * workspace of its own (cs_frame_begin_part: the same preparation, limited
 * to the range), and joins them (cs_frame_join): the parts' arrays follow
 * one another in cel order, as one preparation fills them, and their
 * sorted orders are merged stably, which gives the order one stable sort of
 * the whole gives. The core knows nothing of threads: a part is a call.
 */
#include "cs_internal.h"

/*
 * The pixels a segment can touch, from its Bezier form: with positive
 * homogeneous weights the curve lies in the hull of its control points.
 * Power to Bernstein: b_i = sum_{j<=i} C(i,j)/C(p,j) a_j. The hull's x
 * range is widened by half a pixel, so that a crossing rounded just past
 * it still counts, and kept within the line.
 */
static void segment_xbounds(cs_segment *s, float x0, float width)
{
    static const float ratio[4][4][4] = {
        /* [p][i][j] = C(i,j) / C(p,j) */
        {{1}},
        {{1, 0}, {1, 1}},
        {{1, 0, 0}, {1, 0.5f, 0}, {1, 1, 1}},
        {{1, 0, 0, 0}, {1, 1.0f / 3.0f, 0, 0}, {1, 2.0f / 3.0f, 1.0f / 3.0f, 0}, {1, 1, 1, 1}},
    };
    int p = s->degree;
    float lo = x0 + width, hi = x0;
    for (int i = 0; i <= p; i++) {
        float bx = 0.0f, bw = 0.0f;
        for (int j = 0; j <= i; j++) {
            bx += ratio[p][i][j] * s->x[j];
            bw += ratio[p][i][j] * s->w[j];
        }
        if (!(bw > 0.0f)) { /* not expected; then claim the whole line */
            lo = x0;
            hi = x0 + width;
            break;
        }
        float x = (float)s->ox + bx / bw;
        lo = cs__minf(lo, x);
        hi = cs__maxf(hi, x);
    }
    lo = cs__clampf(lo, x0, x0 + width) - x0;
    hi = cs__clampf(hi, x0, x0 + width) - x0;
    int32_t a = cs__floori(lo - 0.5f), b = cs__floori(hi + 0.5f) + 1;
    s->px_lo = (uint16_t)(a < 0 ? 0 : a);
    s->px_hi = (uint16_t)(b > (int32_t)width ? (int32_t)width : b);
}

/*
 * Appends the monotone pieces of segment `si`, whose end y is `y_end`; with
 * a viewport only those that can meet a row of it, [vy, vy + vh): a piece is active on row y
 * when y_top < y + 1 and y_bot > y (cs_cross.c: cs__line_active), so one wholly
 * above or below the window is never read, and leaving it out changes no
 * pixel. It leaves the arena to what the window needs, which is what lets a
 * small board render a scene larger than its arena in bands of rows.
 */
static cs_status split_segment(cs_renderer *r, uint32_t si, float y_end, uint8_t operand)
{
    const float row_lo = r->rows_only ? (float)r->vy : -CS_CFG_COORD_LIMIT;
    const float row_hi = r->rows_only ? (float)(r->vy + r->vh) : CS_CFG_COORD_LIMIT;
    cs_frame_data *fd = &r->ws->frame;
    const cs_segment *s = &fd->segments[si];
    float cut[6];
    int n = 0;
    cut[n++] = 0.0f;
    n += cs__turns(s->y, s->w, s->degree, 0.0f, 1.0f, &cut[1]);
    cut[n++] = 1.0f;
    float ya = cs__segment_y(s, 0.0f);
    for (int k = 0; k + 1 < n; k++) {
        float yb = (k + 2 == n) ? y_end : cs__segment_y(s, cut[k + 1]);
        float top = yb > ya ? ya : yb, bot = yb > ya ? yb : ya;
        if (ya != yb && bot > row_lo && top < row_hi) {
            if (r->piece_count >= CS_CFG_MAX_PIECES)
                return CS_ERR_CAP_PIECES;
            cs_piece *pc = &fd->pieces[r->piece_count++];
            pc->u0 = cut[k];
            pc->u1 = cut[k + 1];
            pc->dir = yb > ya ? 1 : -1;
            pc->y_top = top;
            pc->y_bot = bot;
            pc->segment = (cs_index)si;
            pc->region = s->region;
            pc->operand = operand;
        }
        ya = yb;
    }
    return CS_OK;
}

/* *d = *s field by field: a struct copy of this size would be a memcpy
 * call, which the freestanding core does not have. */
static void copy_segment(cs_segment *d, const cs_segment *s)
{
    for (int k = 0; k < 4; k++) {
        d->x[k] = s->x[k];
        d->y[k] = s->y[k];
        d->w[k] = s->w[k];
    }
    d->ox = s->ox;
    d->oy = s->oy;
    d->px_lo = s->px_lo;
    d->px_hi = s->px_hi;
    d->region = s->region;
    d->degree = s->degree;
    d->rational = s->rational;
}

/*
 * The segments of one contour that the rows need, and their pieces. The
 * segment in hand sits in the arena's next free slot and, with a viewport,
 * keeps it only if split_segment kept a piece of it, so the arena holds
 * what the window needs plus one segment, never a whole contour it would
 * mostly drop. A segment's last piece ends at the next segment's start
 * (exact parity: the chain of end values closes), so the next segment is
 * made first, in the slot after it, and the last one ends at the first
 * one's start.
 */
static cs_status contour_pieces(cs_renderer *r, cs__contour_iter *it, uint8_t operand)
{
    cs_frame_data *fd = &r->ws->frame;
    /* A contour whose control points all lie a pixel or more above or below
     * the rows (and more: a 256th of its height, for the rounding of values
     * computed on the curve) has no piece there: it is not converted, so a
     * band costs about what its own contours cost. */
    float margin = 1.0f + (it->ymax - it->ymin) * (1.0f / 256.0f);
    if (r->rows_only &&
        (it->ymax + margin < (float)r->vy || it->ymin - margin > (float)(r->vy + r->vh)))
        return CS_OK;
    if (r->segment_count >= CS_CFG_MAX_SEGMENTS)
        return CS_ERR_CAP_SEGMENTS;
    if (!cs__contour_next(it, &fd->segments[r->segment_count]))
        return CS_OK;
    const float first_y = cs__segment_y(&fd->segments[r->segment_count], 0.0f);
    for (;;) {
        uint32_t si = r->segment_count, pieces = r->piece_count;
        bool more = cs__contour_more(it);
        if (more && si + 1 >= CS_CFG_MAX_SEGMENTS)
            return CS_ERR_CAP_SEGMENTS;
        cs_segment *next = &fd->segments[si + 1];
        if (more)
            cs__contour_next(it, next);
        segment_xbounds(&fd->segments[si], (float)r->vx, (float)r->vw);
        cs_status st = split_segment(r, si, more ? cs__segment_y(next, 0.0f) : first_y, operand);
        bool keep = r->piece_count > pieces || !r->rows_only;
        if (st != CS_OK || !more) {
            if (st == CS_OK && keep)
                r->segment_count++;
            return st;
        }
        if (keep)
            r->segment_count++; /* the next one is in place already */
        else
            copy_segment(&fd->segments[si], next);
    }
}

/*
 * The pieces are ordered so that the ones a line takes come first:
 * cs__line_active takes a piece at line y once y_top < y + 1, and keeps the
 * newly active pieces of a line in piece order whatever their order here.
 * So the key can be y_top, or the line of the window on which a piece is
 * first taken, floor(y_top) counted from the window's top (vh: none of
 * its lines), with ties in piece order. Lines are few, so where the
 * workspace has room for a count a line (LINE_COUNTS, the hosts) the
 * pieces are sorted by that line, by counting, in time linear in the
 * pieces (a merge sort by y_top was ~0.8 M instructions of a Many-blobs
 * frame); the boards, with a few dozen pieces and no such room, keep a
 * stable merge sort by y_top.
 */
#define LINE_COUNTS (CS_CFG_MAX_HEIGHT + 1 <= CS_CFG_MAX_PIECES)

#if LINE_COUNTS
static uint32_t due_line(const cs_renderer *r, float y_top)
{
    float y = cs__clampf(y_top, (float)r->vy, (float)(r->vy + r->vh));
    return (uint32_t)(int32_t)y - (uint32_t)r->vy; /* y >= vy >= 0: the cast is floor */
}
#endif

/* Whether piece a goes before piece b in the order. */
static bool goes_before(const cs_renderer *r, const cs_piece *a, const cs_piece *b)
{
#if LINE_COUNTS
    return due_line(r, a->y_top) < due_line(r, b->y_top);
#else
    (void)r;
    return a->y_top < b->y_top;
#endif
}

/* The sorted runs a[lo, mid) and a[mid, hi) of piece indices, merged into
 * b[lo, hi); on a tie the left run's piece first (stable). */
static void merge_by_top(const cs_renderer *r, const cs_index *a, cs_index *b, uint32_t lo,
                         uint32_t mid, uint32_t hi)
{
    const cs_piece *pieces = r->ws->frame.pieces;
    uint32_t i = lo, j = mid, k = lo;
    while (i < mid && j < hi)
        b[k++] = goes_before(r, &pieces[a[j]], &pieces[a[i]]) ? a[j++] : a[i++];
    while (i < mid)
        b[k++] = a[i++];
    while (j < hi)
        b[k++] = a[j++];
}

/* The frame's pieces in order (above): by counting, with a count a line
 * in ws->active (idle until the first line), or by a stable merge sort
 * using ws->scratch. */
static void sort_by_top(cs_renderer *r)
{
    cs_workspace *ws = r->ws;
    cs_frame_data *fd = &ws->frame;
    uint32_t n = r->piece_count;
#if LINE_COUNTS
    cs_index *at = ws->active; /* per line: its count, then where its next piece goes */
    uint32_t lines = (uint32_t)r->vh + 1u;
    for (uint32_t b = 0; b < lines; b++)
        at[b] = 0;
    for (uint32_t p = 0; p < n; p++)
        at[due_line(r, fd->pieces[p].y_top)]++;
    for (uint32_t b = 0, sum = 0; b < lines; b++) {
        uint32_t c = at[b];
        at[b] = (cs_index)sum;
        sum += c;
    }
    for (uint32_t p = 0; p < n; p++)
        fd->order[at[due_line(r, fd->pieces[p].y_top)]++] = (cs_index)p;
#else
    cs_index *a = fd->order, *b = ws->scratch;
    for (uint32_t i = 0; i < n; i++)
        a[i] = (cs_index)i;
    for (uint32_t width = 1; width < n; width *= 2) {
        for (uint32_t lo = 0; lo < n; lo += 2 * width) {
            uint32_t mid = lo + width < n ? lo + width : n;
            uint32_t hi = lo + 2 * width < n ? lo + 2 * width : n;
            merge_by_top(r, a, b, lo, mid, hi);
        }
        cs_index *t = a;
        a = b;
        b = t;
    }
    if (a != fd->order)
        for (uint32_t i = 0; i < n; i++)
            fd->order[i] = a[i];
#endif
}

cs_render_opts cs_render_defaults(int width, int height)
{
    cs_render_opts o;
    o.width = width;
    o.height = height;
    o.aa = CS_AA_SUBSCAN;
    o.subscanlines = 16;
    o.time = 0.0f;
    o.blend = CS_BLEND_SCENE;
    o.no_early_out = false;
    o.no_grey = false;
    o.view_x = o.view_y = o.view_w = o.view_h = 0;
    return o;
}

/* Whether the options ask for a viewport rather than the whole output. */
static bool windowed(const cs_render_opts *o)
{
    return o->view_w != 0 || o->view_h != 0;
}

static cs_status check_opts(const cs_render_opts *o)
{
    if (!windowed(o)) {
        if (o->width < 1 || o->width > CS_CFG_MAX_WIDTH || o->height < 1 ||
            o->height > CS_CFG_MAX_HEIGHT)
            return CS_ERR_SIZE;
    } else if (o->width < 1 || o->width > CS_CFG_MAX_WALL || o->height < 1 ||
               o->height > CS_CFG_MAX_WALL || o->view_w < 1 || o->view_w > CS_CFG_MAX_WIDTH ||
               o->view_h < 1 || o->view_h > CS_CFG_MAX_HEIGHT || o->view_x < 0 ||
               o->view_y < 0 || o->view_x > o->width - o->view_w ||
               o->view_y > o->height - o->view_h) {
        return CS_ERR_SIZE;
    }
    if (o->aa != CS_AA_NONE && o->aa != CS_AA_SUBSCAN && (o->aa != CS_AA_EXACT || !CS_CFG_EXACT))
        return CS_ERR_ARG;
    if (o->aa == CS_AA_SUBSCAN && (o->subscanlines < 1 || o->subscanlines > CS_CFG_MAX_SUBSCANLINES))
        return CS_ERR_ARG;
    if (o->blend != CS_BLEND_LINEAR && o->blend != CS_BLEND_SRGB && o->blend != CS_BLEND_SCENE)
        return CS_ERR_ARG;
    if (!cs__finite(o->time))
        return CS_ERR_NONFINITE;
    return CS_OK;
}

/*
 * Region paint under the cel's lights: E = b p F + (1-b) m B, T = (1-b) m.
 * Under sRGB blending the colours are encoded first; lights stay
 * multipliers.
 */
static void region_map(const cs_paint *p, const float *front, const float *back, bool srgb,
                       float *E, float *T)
{
    for (int k = 0; k < 3; k++) {
        float pig = srgb ? cs__encode(p->pigment[k]) : p->pigment[k];
        float med = srgb ? cs__encode(p->medium[k]) : p->medium[k];
        float clear = (1.0f - p->beta) * med;
        E[k] = p->beta * pig * front[k] + clear * back[k];
        T[k] = clear;
    }
}

/*
 * Whether a region's T = (1 - beta) m is grey at every pixel, so that the
 * frame may keep one channel of it (cs_renderer.grey). A functional medium
 * is grey where all its stops are: values between them are the same
 * arithmetic on each channel. A functional beta scales the constant medium.
 * Otherwise T is the constant the frame computed: an opaque paint's is 0 on
 * every channel whatever its medium.
 */
static bool region_grey(const cs_scene *scene, const cs_region *reg, const cs_paint *paint,
                        const float *T)
{
    if (reg->func[CS_FIELD_MEDIUM]) {
        const cs_paint_func *fn = &scene->funcs[reg->func[CS_FIELD_MEDIUM] - 1u];
        for (uint32_t k = 0; k < fn->stop_count; k++)
            if (!cs__grey3(fn->stops[k].value))
                return false;
        return true;
    }
    if (reg->func[CS_FIELD_BETA])
        return cs__grey3(paint->medium);
    return cs__grey3(T);
}

/* Inverse of an affine map; all zeros when it is singular (its cel then
 * has no area, so no pixel ever asks for a function value). */
static cs_affine affine_inverse(const cs_affine *m)
{
    cs_affine inv = {0, 0, 0, 0, 0, 0};
    float det = m->a * m->d - m->b * m->c;
    if (!(det != 0.0f) || !cs__finite(1.0f / det))
        return inv;
    float k = 1.0f / det;
    inv.a = m->d * k;
    inv.b = -m->b * k;
    inv.c = -m->c * k;
    inv.d = m->a * k;
    inv.e = -(inv.a * m->e + inv.c * m->f);
    inv.f = -(inv.b * m->e + inv.d * m->f);
    return inv;
}

/* Samples track `tr` at time t into out[0 .. width). */
void cs__track_sample(const cs_scene *scene, const cs_track *tr, float t, float *out)
{
    uint32_t i0, i1;
    float s;
    cs__track_locate(scene, tr, t, &i0, &i1, &s);
    uint32_t lead = cs__track_lead(tr);
    const float *a = &scene->key_values[tr->first_value + i0 * tr->width + lead];
    const float *b = &scene->key_values[tr->first_value + i1 * tr->width + lead];
    for (uint32_t k = 0; k < tr->width - lead; k++)
        out[k] = i0 == i1 ? a[k] : cs__lerp(a[k], b[k], s);
}

/* Cel ci's own transform and opacity at time t: a TRS track's, else a
 * transform track's or the stored one (opacity 1). */
static float cel_local(const cs_scene *scene, uint32_t ci, float t, float *m)
{
    const cs_cel *cel = &scene->cels[ci];
    const cs_track *tr;
#if CS_CFG_ANIM_PARTS
    if ((tr = cs__track_find(scene, CS_TRACK_TRS, ci)) != 0 && tr->key_count) {
        float v[10];
        cs__track_sample(scene, tr, t, v);
        cs__trs_affine(v, m);
        return cs__clampf(v[9], 0.0f, 1.0f);
    }
#endif
    m[0] = cel->transform.a;
    m[1] = cel->transform.b;
    m[2] = cel->transform.c;
    m[3] = cel->transform.d;
    m[4] = cel->transform.e;
    m[5] = cel->transform.f;
    if ((tr = cs__track_find(scene, CS_TRACK_TRANSFORM, ci)) != 0 && tr->key_count)
        cs__track_sample(scene, tr, t, m);
    return 1.0f;
}

/* Cel ci's transform and opacity with its groups': parent after child, up
 * the chain (at most CS_CFG_MAX_GROUP_DEPTH long, cs_scene_set_cel_parent). */
float cs__cel_world(const cs_scene *scene, uint32_t ci, float t, float *m)
{
    float opacity = cel_local(scene, ci, t, m);
    uint32_t p = scene->cels[ci].parent;
    for (int depth = 1; p < scene->cel_count && depth < CS_CFG_MAX_GROUP_DEPTH; depth++) {
        float pm[6];
        opacity *= cel_local(scene, p, t, pm);
        float r[6] = {pm[0] * m[0] + pm[2] * m[1], pm[1] * m[0] + pm[3] * m[1],
                      pm[0] * m[2] + pm[2] * m[3], pm[1] * m[2] + pm[3] * m[3],
                      pm[0] * m[4] + pm[2] * m[5] + pm[4], pm[1] * m[4] + pm[3] * m[5] + pm[5]};
        for (int i = 0; i < 6; i++)
            m[i] = r[i];
        p = scene->cels[p].parent;
    }
    return opacity;
}

/* Samples a points track into the workspace's contour buffer. */
static const cs_point *sample_points(const cs_scene *scene, const cs_track *tr, float t,
                                     cs_point *out)
{
    uint32_t i0, i1;
    float s;
    cs__track_locate(scene, tr, t, &i0, &i1, &s);
    uint32_t lead = cs__track_lead(tr);
    const float *a = &scene->key_values[tr->first_value + i0 * tr->width + lead];
    const float *b = &scene->key_values[tr->first_value + i1 * tr->width + lead];
    for (uint32_t k = 0; k < (tr->width - lead) / 3; k++) {
        out[k].x = i0 == i1 ? a[3 * k] : cs__lerp(a[3 * k], b[3 * k], s);
        out[k].y = i0 == i1 ? a[3 * k + 1] : cs__lerp(a[3 * k + 1], b[3 * k + 1], s);
        out[k].w = i0 == i1 ? a[3 * k + 2] : cs__lerp(a[3 * k + 2], b[3 * k + 2], s);
    }
    return out;
}

/* The lines of ws read the frame fd (its own, while it is being prepared). */
static void read_frame(cs_workspace *ws, const cs_frame_data *fd)
{
    ws->segments = fd->segments;
    ws->pieces = fd->pieces;
    ws->order = fd->order;
    ws->region_cel = fd->region_cel;
    ws->region_E = fd->region_E;
    ws->region_T = fd->region_T;
    ws->func_xf = fd->func_xf;
    ws->cel_opacity = fd->cel_opacity;
}

/*
 * The state a renderer carries from line to line, set to the top of the
 * frame: the active list, the sticky error and, in r's workspace, the
 * accumulators and the exact-area row memo.
 */
static void clear_lines(cs_renderer *r)
{
    cs_workspace *ws = r->ws;
    r->active_count = r->next_order = 0;
    r->next_line = 0;
    cs__error(&r->sticky, CS_OK, -1, -1, -1, -1);
    /* The line code clears what it touches; start from a clean slate in case
     * an earlier frame was abandoned part way through a line. The runs are
     * set up afresh by every line. */
    for (int x = 0; x < r->vw + 2; x++)
        ws->area[x] = ws->cover[x] = 0.0f;
    for (uint32_t w = 0; w < sizeof ws->touched / sizeof ws->touched[0]; w++)
        ws->touched[w] = 0u;
#if CS_CFG_EXACT
    if (r->opts.aa == CS_AA_EXACT) /* no row placed yet: -1 lies below every key (cs_exact_place.c) */
        for (uint32_t i = 0; i < r->piece_count; i++)
            ws->level_memo[i].y = -1.0f;
#endif
}

cs_status cs_frame_begin(cs_renderer *r, cs_workspace *ws, const cs_scene *scene,
                         const cs_render_opts *opts, cs_error *err)
{
    return cs__frame_prepare(r, ws, scene, opts, 0, UINT32_MAX, 0, err);
}

cs_status cs_scene_check_render(cs_renderer *r, cs_workspace *ws, const cs_scene *scene,
                                const cs_render_opts *opts, cs_error *err)
{
    if (!r || !ws || !scene || !opts) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    float t[3] = {opts->time, opts->time, opts->time};
    if (scene->key_count > 0) {
        t[1] = t[2] = scene->key_times[0];
        for (uint32_t k = 1; k < scene->key_count && k < CS_CFG_MAX_KEYS; k++) {
            if (scene->key_times[k] < t[1])
                t[1] = scene->key_times[k];
            if (scene->key_times[k] > t[2])
                t[2] = scene->key_times[k];
        }
    }
    cs_render_opts o = *opts;
    for (int i = 0; i < 3; i++) {
        if (i > 0 && (t[i] == t[0] || t[i] == t[i - 1]))
            continue;
        o.time = t[i];
        cs_status st = cs_frame_begin(r, ws, scene, &o, err);
        if (st != CS_OK)
            return st;
    }
    return CS_OK;
}

cs_status cs_frame_begin_cached(cs_renderer *r, cs_workspace *ws, const cs_scene *scene,
                                const cs_render_opts *opts, const cs_cache *cache,
                                cs_error *err)
{
    if (cache && opts) { /* a build without CS_CFG_CACHE has none */
        const cs_render_opts *c = &cache->opts;
        cs_blend blend = opts->blend == CS_BLEND_SCENE && scene ? (cs_blend)scene->blend : opts->blend;
        if (!CS_CFG_CACHE || cache->status != CS_OK || windowed(opts) ||
            c->width != opts->width || c->height != opts->height ||
            c->aa != opts->aa || c->blend != blend ||
            (opts->aa == CS_AA_SUBSCAN && c->subscanlines != opts->subscanlines) || !scene ||
            cache->cel_first + cache->cel_count > scene->cel_count) {
            cs__error(err, CS_ERR_STATE, -1, -1, -1, -1);
            return CS_ERR_STATE;
        }
    }
    return cs__frame_prepare(r, ws, scene, opts, 0, UINT32_MAX, cache, err);
}

/* The lights of the stack (front, back: into stack[6]) at time t, and the
 * light behind every cel, r->behind. */
static void frame_lights(cs_renderer *r, const cs_scene *scene, float t, float stack[6])
{
    float bg[3];
    cs__copy3(stack, scene->stack_front);
    cs__copy3(stack + 3, scene->stack_back);
    cs__copy3(bg, scene->background);
    const cs_track *tr = cs__track_find(scene, CS_TRACK_STACK_LIGHTS, 0);
    if (tr && tr->key_count)
        cs__track_sample(scene, tr, t, stack);
    tr = cs__track_find(scene, CS_TRACK_BACKGROUND, 0);
    if (tr && tr->key_count)
        cs__track_sample(scene, tr, t, bg);
    bool srgb = r->opts.blend == CS_BLEND_SRGB;
    for (int k = 0; k < 3; k++) {
        float card = srgb ? cs__encode(bg[k]) : bg[k];
        r->behind[k] = scene->has_background ? card * stack[k] : stack[3 + k];
    }
}

/* Region ri's paint at time t under its cel's opacity: its own, or one
 * made in *animated when a track or the opacity changes it. */
const cs_paint *cs__region_paint(const cs_scene *scene, uint32_t ri, float t, float opacity,
                                    cs_paint *animated)
{
    const cs_paint *paint = &scene->regions[ri].paint;
    const cs_track *tr = cs__track_find(scene, CS_TRACK_PAINT, ri);
    if (tr != 0 && tr->key_count) {
        float v[7];
        cs__track_sample(scene, tr, t, v);
        for (int k = 0; k < 3; k++) {
            animated->pigment[k] = cs__clampf(v[k], 0.0f, 1.0f);
            animated->medium[k] = cs__clampf(v[3 + k], 0.0f, 1.0f);
        }
        animated->beta = cs__clampf(v[6], 0.0f, 1.0f);
        paint = animated;
    }
    if (opacity < 1.0f) {
        if (paint != animated) {
            cs__copy3(animated->pigment, paint->pigment);
            cs__copy3(animated->medium, paint->medium);
            animated->beta = paint->beta;
            paint = animated;
        }
        animated->beta *= opacity;
    }
    return paint;
}

/* The monotone pieces of region ri's contours (of cel ci) at time t, in
 * device coordinates (dev). */
static cs_status region_pieces(cs_renderer *r, uint32_t ci, uint32_t ri, const cs_affine *dev,
                               float t, cs_error *err)
{
    const cs_scene *scene = r->scene;
    cs_workspace *ws = r->ws;
    cs_frame_data *fd = &ws->frame;
    const cs_region *reg = &scene->regions[ri];
    const cs_cel *cel = &scene->cels[ci];
    for (uint32_t k = 0; k < reg->contour_count; k++) {
        uint32_t ki = reg->first_contour + k;
        const cs_contour *c = &scene->contours[ki];
        const cs_point *pts = &scene->points[c->first_point];
        const cs_track *tr = cs__track_find(scene, CS_TRACK_POINTS, ki);
        if (tr != 0 && tr->key_count && tr->width - cs__track_lead(tr) == 3u * c->point_count &&
            c->point_count <= CS_CFG_MAX_ANIM_POINTS)
            pts = sample_points(scene, tr, t, ws->anim_points);
        int32_t bad;
        cs_status st = cs__contour_begin(&fd->contour, pts, &scene->intervals[c->first_point],
                                         c->point_count, c->degree, dev, (uint16_t)ri, &bad);
        /* Without CSG every contour winds together in operand 0. */
        if (st == CS_OK)
            st = contour_pieces(r, &fd->contour, reg->csg_len ? c->operand : 0);
        if (st != CS_OK) {
            cs__error(err, st, (int32_t)ci, (int32_t)(ri - cel->first_region), (int32_t)k, bad);
            return st;
        }
    }
    return CS_OK;
}

cs_status cs__frame_prepare(cs_renderer *r, cs_workspace *ws, const cs_scene *scene,
                            const cs_render_opts *opts, uint32_t cel_begin, uint32_t cel_end,
                            const cs_cache *cache, cs_error *err)
{
    cs__error(err, CS_OK, -1, -1, -1, -1);
    if (!r || !ws || !scene || !opts) {
        cs__error(err, CS_ERR_ARG, -1, -1, -1, -1);
        return CS_ERR_ARG;
    }
    cs_status st = check_opts(opts);
    if (st != CS_OK) {
        cs__error(err, st, -1, -1, -1, -1);
        return st;
    }
    r->scene = scene;
    r->ws = ws;
    r->opts = *opts;
    if (r->opts.blend == CS_BLEND_SCENE)
        r->opts.blend = (cs_blend)scene->blend;
    r->segment_count = r->piece_count = r->active_count = r->next_order = 0;
    r->next_line = 0;
    r->cache = cache;
    r->grey = false;
    r->cel_begin = cel_begin;
    r->cel_end = cel_end < scene->cel_count ? cel_end : scene->cel_count;
    cs__error(&r->sticky, CS_OK, -1, -1, -1, -1);
    bool win = windowed(opts);
    r->rows_only = win;
    r->vx = win ? opts->view_x : 0;
    r->vy = win ? opts->view_y : 0;
    r->vw = win ? opts->view_w : opts->width;
    r->vh = win ? opts->view_h : opts->height;
    /* One column left of the window stands for everything left of it (the
     * whole output clamps at its own left edge, column 0): see cs_coverage.c. */
    r->clip_lo = (float)(r->vx > 0 ? r->vx - 1 : 0);
    r->clip_hi = (float)(r->vx + r->vw);
    r->sx = (float)opts->width / scene->canvas_w;
    r->sy = (float)opts->height / scene->canvas_h;
    if (!(r->sx <= CS_CFG_COORD_LIMIT && r->sy <= CS_CFG_COORD_LIMIT)) {
        cs__error(err, CS_ERR_RANGE, -1, -1, -1, -1);
        return CS_ERR_RANGE;
    }
    cs_frame_data *fd = &ws->frame;
    read_frame(ws, fd);
    const float t = opts->time;
    float stack[6];
    frame_lights(r, scene, t, stack);
    bool srgb = r->opts.blend == CS_BLEND_SRGB;
    const cs_track *tr;

    bool grey = !opts->no_grey && (!cache || cache->grey);
    for (uint32_t ci = r->cel_begin; ci < r->cel_end; ci++) {
        if (cache && ci >= cache->cel_first && ci - cache->cel_first < cache->cel_count)
            continue; /* composited from the cache's runs instead */
        const cs_cel *cel = &scene->cels[ci];
        float m[6];
        float opacity = cs__cel_world(scene, ci, t, m);
        fd->cel_opacity[ci] = opacity;
        float lights[6];
        cs__copy3(lights, cel->has_front ? cel->front : stack);
        cs__copy3(lights + 3, cel->back);
        if ((tr = cs__track_find(scene, CS_TRACK_CEL_LIGHTS, ci)) != 0 && tr->key_count)
            cs__track_sample(scene, tr, t, lights);
        cs_affine dev = {m[0] * r->sx, m[1] * r->sy, m[2] * r->sx,
                         m[3] * r->sy, m[4] * r->sx, m[5] * r->sy};
        cs_affine inv = affine_inverse(&dev);
        for (uint32_t ri = cel->first_region; ri < cel->first_region + cel->region_count; ri++) {
            const cs_region *reg = &scene->regions[ri];
            fd->region_cel[ri] = (uint16_t)ci;
            cs_paint animated;
            const cs_paint *paint = cs__region_paint(scene, ri, t, opacity, &animated);
            region_map(paint, lights, lights + 3, srgb, fd->region_E[ri], fd->region_T[ri]);
            grey = grey && region_grey(scene, reg, paint, fd->region_T[ri]);
            for (int f = 0; f < 3; f++)
                if (reg->func[f])
                    cs__func_compile(&scene->funcs[reg->func[f] - 1u], &inv,
                                     fd->func_xf[reg->func[f] - 1u]);
            st = region_pieces(r, ci, ri, &dev, t, err);
            if (st != CS_OK)
                return st;
        }
    }
    r->grey = CS_CFG_GREY && grey;
    sort_by_top(r);
    clear_lines(r);
    return CS_OK;
}

cs_status cs_frame_share(cs_renderer *r, cs_workspace *ws, const cs_renderer *prepared)
{
    if (!r || !ws || !prepared || !prepared->ws || r == prepared || ws == prepared->ws)
        return CS_ERR_ARG;
    const cs_workspace *src = prepared->ws;
    if (src->segments != src->frame.segments)
        return CS_ERR_STATE; /* itself a share: share the renderer that prepared the frame */
    /* Field by field: a struct copy of this size is a memcpy call, which
     * the freestanding core does not have. The line state follows. */
    r->scene = prepared->scene;
    r->ws = ws;
    r->opts = prepared->opts;
    r->segment_count = prepared->segment_count;
    r->piece_count = prepared->piece_count;
    cs__copy3(r->behind, prepared->behind);
    r->sx = prepared->sx;
    r->sy = prepared->sy;
    r->cel_begin = prepared->cel_begin;
    r->cel_end = prepared->cel_end;
    r->cache = prepared->cache;
    r->grey = prepared->grey;
    r->vx = prepared->vx;
    r->vy = prepared->vy;
    r->vw = prepared->vw;
    r->vh = prepared->vh;
    r->rows_only = prepared->rows_only;
    r->clip_lo = prepared->clip_lo;
    r->clip_hi = prepared->clip_hi;
    read_frame(ws, &src->frame);
    clear_lines(r);
    return CS_OK;
}

cs_status cs_frame_begin_part(cs_renderer *r, cs_workspace *ws, const cs_scene *scene,
                              const cs_render_opts *opts, uint32_t cel_begin, uint32_t cel_end,
                              cs_error *err)
{
    return cs__frame_prepare(r, ws, scene, opts, cel_begin, cel_end, 0, err);
}

/* *d = *s field by field, as copy_segment does, with the segment index moved by `base`. */
static void copy_piece(cs_piece *d, const cs_piece *s, uint32_t base)
{
    d->u0 = s->u0;
    d->u1 = s->u1;
    d->y_top = s->y_top;
    d->y_bot = s->y_bot;
    d->segment = (cs_index)(s->segment + base);
    d->region = s->region;
    d->operand = s->operand;
    d->dir = s->dir;
}

/* Whether part p continues the frame r holds: the same scene and options,
 * prepared in its own workspace, from the cel where r's part ends. */
static bool part_follows(const cs_renderer *r, const cs_renderer *p)
{
    const cs_render_opts *a = &r->opts, *b = &p->opts;
    return p->ws && p->ws != r->ws && p->ws->segments == p->ws->frame.segments &&
           p->scene == r->scene && !p->cache && p->cel_begin == r->cel_end &&
           a->width == b->width && a->height == b->height && a->aa == b->aa &&
           a->subscanlines == b->subscanlines && a->time == b->time && a->blend == b->blend &&
           a->no_early_out == b->no_early_out && a->no_grey == b->no_grey &&
           a->view_x == b->view_x && a->view_y == b->view_y && a->view_w == b->view_w &&
           a->view_h == b->view_h;
}

/* Part p's cels' paints, opacities and function maps into fd, region by
 * region as cs__frame_prepare writes them (a function two regions share
 * keeps the later one's map, as there). */
static void join_paints(cs_frame_data *fd, const cs_renderer *p)
{
    const cs_scene *scene = p->scene;
    const cs_frame_data *src = &p->ws->frame;
    for (uint32_t ci = p->cel_begin; ci < p->cel_end; ci++) {
        const cs_cel *cel = &scene->cels[ci];
        fd->cel_opacity[ci] = src->cel_opacity[ci];
        for (uint32_t ri = cel->first_region; ri < cel->first_region + cel->region_count; ri++) {
            const cs_region *reg = &scene->regions[ri];
            fd->region_cel[ri] = src->region_cel[ri];
            cs__copy3(fd->region_E[ri], src->region_E[ri]);
            cs__copy3(fd->region_T[ri], src->region_T[ri]);
            for (int f = 0; f < 3; f++)
                if (reg->func[f])
                    for (int k = 0; k < 6; k++)
                        fd->func_xf[reg->func[f] - 1u][k] = src->func_xf[reg->func[f] - 1u][k];
        }
    }
}

/*
 * The parts' pieces were each sorted (goes_before) on their own: the order is
 * runs[0] sorted runs, run k from bound[k] to bound[k + 1]. Adjacent runs
 * are merged pairwise until one is left, the left run first on a tie, so
 * the order is the one sort_by_top gives the whole (a stable sort: ties
 * in piece order, and a part's pieces follow the earlier parts').
 */
static void merge_runs(const cs_renderer *r, uint32_t *bound, int runs)
{
    cs_workspace *ws = r->ws;
    cs_frame_data *fd = &ws->frame;
    cs_index *a = fd->order, *b = ws->scratch;
    while (runs > 1) {
        int out = 0;
        for (int k = 0; k < runs; k += 2) {
            uint32_t lo = bound[k], mid = bound[k + 1];
            uint32_t hi = k + 1 < runs ? bound[k + 2] : mid;
            merge_by_top(r, a, b, lo, mid, hi);
            bound[out++] = lo;
        }
        bound[out] = bound[runs];
        runs = out;
        cs_index *t = a;
        a = b;
        b = t;
    }
    if (a != fd->order)
        for (uint32_t i = 0; i < bound[1]; i++)
            fd->order[i] = a[i];
}

cs_status cs_frame_join(cs_renderer *r, const cs_renderer *const *parts, int n)
{
    if (!r || !r->ws || r->ws->segments != r->ws->frame.segments || r->cel_begin != 0 ||
        r->cache || n < 0 || n > CS_FRAME_MAX_PARTS - 1 || (n > 0 && !parts))
        return CS_ERR_ARG;
    uint32_t segments = r->segment_count, pieces = r->piece_count;
    for (int k = 0; k < n; k++) {
        const cs_renderer *p = parts[k];
        if (!p || !part_follows(k ? parts[k - 1] : r, p))
            return CS_ERR_ARG;
        segments += p->segment_count;
        pieces += p->piece_count;
    }
    if ((n ? parts[n - 1] : r)->cel_end != r->scene->cel_count)
        return CS_ERR_ARG;
    if (segments > CS_CFG_MAX_SEGMENTS)
        return CS_ERR_CAP_SEGMENTS;
    if (pieces > CS_CFG_MAX_PIECES)
        return CS_ERR_CAP_PIECES;

    cs_frame_data *fd = &r->ws->frame;
    uint32_t bound[CS_FRAME_MAX_PARTS + 1];
    bound[0] = 0;
    bound[1] = r->piece_count;
    for (int k = 0; k < n; k++) {
        const cs_renderer *p = parts[k];
        const cs_frame_data *src = &p->ws->frame;
        uint32_t s0 = r->segment_count, p0 = r->piece_count;
        for (uint32_t i = 0; i < p->segment_count; i++)
            copy_segment(&fd->segments[s0 + i], &src->segments[i]);
        for (uint32_t i = 0; i < p->piece_count; i++) {
            copy_piece(&fd->pieces[p0 + i], &src->pieces[i], s0);
            fd->order[p0 + i] = (cs_index)(src->order[i] + p0);
        }
        join_paints(fd, p);
        r->segment_count += p->segment_count;
        r->piece_count += p->piece_count;
        r->grey = r->grey && p->grey;
        r->cel_end = p->cel_end;
        bound[k + 2] = r->piece_count;
    }
    merge_runs(r, bound, n + 1);
    clear_lines(r);
    return CS_OK;
}
