/*
 * cs_composite.c - compositing: a line's regions, cel by cel, front to
 *
 * back into the line's runs (cs__line_stack, also the cache builder's
 * line). Stage 5 of a frame; the line's output (cs_line.c) turns the
 * runs into pixels.
 *
 * Everything after that is per run of pixels, not per pixel (cs_runs.h):
 * the line is a list of runs that share one stack and one cel state. The
 * marked entries are visited in x order; pixel x gets clamp(area + running
 * cover), and the pixels up to the next marked entry share clamp(running
 * cover), so a region's coverage is a handful of runs however wide it is.
 * Coverage c turns a region's paint map (E, T) into (c E, 1 - c (1 - T)).
 * Within a cel the regions' maps are summed, so two regions sharing an
 * edge leave no seam; each region may only claim the coverage the regions
 * in front of it left (`used`), so a region hidden behind another in the
 * same cel stays hidden. The cel then joins the stack front to back:
 * E += T_stack E_cel, T_stack *= T_cel, and the pixel is E + T_stack L.
 * The finished runs become pixels once per run, in the display's format
 * (cs_line_pixels) or as floats (cs_render_line).
 *
 * Front to back pays off where the stack turns opaque. Where T_stack is 0
 * on every channel, E += 0 * E_cel and T_stack *= T_cel leave the pixel
 * exactly as it is, so later cels may be skipped there without changing a
 * bit: opaque runs are passed over, a region whose whole x range is opaque
 * is not intersected at all, and the line stops when every pixel is
 * opaque. A pre-combined cel range (the cache) is composited from its runs
 * at its place in the stack.
 */
#include "cs_runs.h"

/*
 * A region's paint at one pixel when any of its fields is a function:
 * the same E, T as the frame's region_map, with the fields evaluated at the
 * pixel centre. Its cel's lights are looked up here, not by fold_region_as
 * for every region-row whether functional or not.
 */
static void paint_at(const cs_renderer *r, const cs_region *region, float px, float py, float *E,
                     float *A)
{
    const cs_scene *scene = r->scene;
    uint32_t cel = r->ws->region_cel[region - scene->regions];
    const float *front = scene->cels[cel].has_front ? scene->cels[cel].front : scene->stack_front;
    const float *back = scene->cels[cel].back;
    bool srgb = r->opts.blend == CS_BLEND_SRGB;
    float pig[3], med[3], beta;
    const cs_paint *p = &region->paint;
    if (region->func[CS_FIELD_PIGMENT]) {
        uint32_t f = region->func[CS_FIELD_PIGMENT] - 1u;
        cs__func_eval(&scene->funcs[f], r->ws->func_xf[f], px, py, srgb, pig);
    } else {
        for (int ch = 0; ch < 3; ch++)
            pig[ch] = srgb ? cs__encode(p->pigment[ch]) : p->pigment[ch];
    }
    if (region->func[CS_FIELD_MEDIUM]) {
        uint32_t f = region->func[CS_FIELD_MEDIUM] - 1u;
        cs__func_eval(&scene->funcs[f], r->ws->func_xf[f], px, py, srgb, med);
    } else {
        for (int ch = 0; ch < 3; ch++)
            med[ch] = srgb ? cs__encode(p->medium[ch]) : p->medium[ch];
    }
    if (region->func[CS_FIELD_BETA]) {
        float v[3];
        uint32_t f = region->func[CS_FIELD_BETA] - 1u;
        cs__func_eval(&scene->funcs[f], r->ws->func_xf[f], px, py, false, v); /* a proportion */
        beta = v[0];
    } else {
        beta = p->beta;
    }
    beta *= r->ws->cel_opacity[cel];
    for (int ch = 0; ch < 3; ch++) {
        float clear = (1.0f - beta) * med[ch];
        E[ch] = beta * pig[ch] * front[ch] + clear * back[ch];
        A[ch] = 1.0f - clear;
    }
}

/*
 * Whether the region can make a pixel of its cel opaque on its own: T = 0
 * on every channel (or a functional medium or beta that may reach it).
 * The cel's T at a pixel is 1 - sum c_i (1 - T_i) with sum c_i <= 1, so it
 * can only vanish where such regions cover it. Only such cels snap T to 0
 * (below CS__T_ZERO), so that a stack covered by them turns opaque.
 */
static bool region_may_hide(const cs_renderer *r, uint32_t reg)
{
    const cs_region *region = &r->scene->regions[reg];
    const float *T = r->ws->region_T[reg];
    return (T[0] < CS__T_ZERO && T[1] < CS__T_ZERO && T[2] < CS__T_ZERO) ||
           region->func[CS_FIELD_MEDIUM] || region->func[CS_FIELD_BETA];
}

/* Whether any field of the region's paint is a function of the pixel. */
static inline bool region_functional(const cs_region *region)
{
    return (region->func[0] | region->func[1] | region->func[2]) != 0;
}

/* What a region adds to the runs: its paint, or how to evaluate it. */
typedef struct fold_paint {
    cs_renderer *r; /* the direct path counts opaque pixels in it */
    const cs_region *region;
    float E[4], A[3]; /* the constant map (c = 1) when not functional; E[3] 0 */
    int y;            /* the line, for functional paints */
    bool functional;
    bool direct;      /* the cel's only region on this line: straight into the stack */
    bool bare;        /* the first of its cel to fold on this line: no run holds the cel */
    bool snap;        /* with direct: the cel may hide (see region_may_hide) */
} fold_paint;

/* Adds coverage c (0 < c <= 1: the folds' clamp and test) of paint
 * (E, A) to the cel at the run starting at s, within what the regions in
 * front of it left (`used`). A grey frame keeps A in channel 0 alone. A
 * run the cel has not reached (used 0) has room for all of c, and what it
 * stores is stale: c E and c A are stored without the room's tests. With
 * `bare` (the cel's first region on the line, which meets each run once)
 * used is 0 without a read. */
static CS__SPECIALISE void accumulate(cs_workspace *ws, bool grey, bool bare, uint32_t s, float c,
                                      const float *E, const float *A)
{
    float used = bare ? 0.0f : ws->used[s];
    float *ce = &ws->cel_E[3 * s], *ca = &ws->cel_A[3 * s];
    if (used == 0.0f) {
        for (int ch = 0; ch < 3; ch++)
            ce[ch] = c * E[ch];
        ca[0] = c * A[0];
        if (!grey) {
            ca[1] = c * A[1];
            ca[2] = c * A[2];
        }
        ws->used[s] = c; /* 0 + c */
#if CS_CFG_CEL_LIST
        ws->cel_runs[ws->cel_run_count++] = (uint16_t)s;
#endif
        return;
    }
    float room = 1.0f - used;
    if (c > room)
        c = room;
    if (!(c > 0.0f))
        return;
    for (int ch = 0; ch < 3; ch++)
        ce[ch] += c * E[ch];
    ca[0] += c * A[0];
    if (!grey) {
        ca[1] += c * A[1];
        ca[2] += c * A[2];
    }
    ws->used[s] = used + c;
}

/* t = 1 - c A, snapped to 0 below CS__T_ZERO if the cel may hide; channel
 * 0 alone in a grey frame (the others are left unset). */
static CS__SPECIALISE void transmittance(float t[3], const float *A, float c, bool snap, bool grey)
{
    for (int ch = 0; ch < (grey ? 1 : 3); ch++) {
#if CS_CFG_SNAP_SELECT
        float v = 1.0f - c * A[ch];
        t[ch] = (snap & (v < CS__T_ZERO)) ? 0.0f : v;
#else
        t[ch] = 1.0f - c * A[ch];
        if (snap && t[ch] < CS__T_ZERO)
            t[ch] = 0.0f;
#endif
    }
}

/*
 * The region alone in its cel on this line: its cel map at the run is just
 * (c E, 1 - c A), so it joins the stack at once. These are the operations
 * accumulate and composite_cel would do on a cel with one region (room is
 * 1, 0 + v is v), so the bits are the same, without the round trip through
 * the cel's share of the runs.
 */
static CS__SPECIALISE void composite_direct(cs_renderer *r, bool grey, uint32_t s, uint32_t e,
                                            float c, const float *E, const float *A, bool snap)
{
    float t[3];
#if CS__VEC3
    /* cE's lanes as cs__add_scaled3 reads them (E[3] is read too, and
     * its lane discarded there). */
    cs__v4 v = c * *(const cs__v4 *)E;
    const float *cE = (const float *)&v;
#else
    float cE[3];
    for (int ch = 0; ch < 3; ch++)
        cE[ch] = c * E[ch];
#endif
    transmittance(t, A, c, snap, grey);
    cs__run_join(r, grey, s, e, cE, t);
}

/*
 * Folds coverage c over pixels [a, b) into the runs, splitting them at a
 * and b; opaque runs are passed over whole. `s` is a run start at or left
 * of a; returns the start of the last run visited (at or left of b - 1),
 * from which the region's next coverage run, further right, is sought.
 */
static CS__SPECIALISE uint32_t fold_run_as(cs_workspace *ws, const fold_paint *fp, uint32_t s,
                                           uint32_t a, uint32_t b, float c, bool grey)
{
    s = cs__run_seek(ws, s, a);
    for (;;) {
        uint32_t e = ws->run_end[s];
        if (!cs__run_start_opaque(fp->r, s)) {
            /* A bare cel holds nothing (cs__run_split_as); the boards' one
             * copy for all cases keeps the test. */
            e = cs__run_clip_as(ws, grey, CS_CFG_GREY && fp->bare, &s, a, b);
            if (!fp->functional) {
                if (fp->direct)
                    composite_direct(fp->r, grey, s, e, c, fp->E, fp->A, fp->snap);
                else
                    accumulate(ws, grey, CS_CFG_GREY && fp->bare, s, c, fp->E, fp->A);
            } else {
                /* The paint varies along x: a run per pixel. */
                for (uint32_t x = s;; x++) {
                    if (x + 1u < e)
                        cs__run_split_as(ws, grey, CS_CFG_GREY && fp->bare, x, x + 1u);
                    float E[4], A[3]; /* E[3]: see composite_direct */
                    E[3] = 0.0f;
                    paint_at(fp->r, fp->region, (float)((int32_t)x + fp->r->vx) + 0.5f,
                             (float)fp->y + 0.5f, E, A);
                    if (fp->direct)
                        composite_direct(fp->r, grey, x, x + 1u, c, E, A, fp->snap);
                    else
                        accumulate(ws, grey, CS_CFG_GREY && fp->bare, x, c, E, A);
                    if (x + 1u >= e)
                        break;
                }
            }
        }
        if (e >= b)
            return s;
        s = e;
    }
}

/*
 * Coverage waiting to be folded: pixels [a, b) at c. It waits until a
 * different value comes, so that a pixel with the coverage of the pixels
 * after it (an entry that only holds a cover delta, as at the inner side
 * of an edge) joins them: fewer, longer runs, and every pixel gets the
 * value it would alone. `cursor` is where fold_run_as seeks from.
 */
typedef struct pending {
    uint32_t a, b, cursor;
    float c;
} pending;

/* Pixels [p->b, b) at coverage c. */
static CS__SPECIALISE void pending_extend(cs_workspace *ws, const fold_paint *fp, pending *p,
                                          uint32_t b, float c, bool grey)
{
    if (c != p->c) {
        if (p->c > 0.0f)
            p->cursor = fold_run_as(ws, fp, p->cursor, p->a, p->b, p->c, grey);
        p->a = p->b;
        p->c = c;
    }
    p->b = b;
}

/*
 * Folds the region's coverage into the cel's share of the runs and clears
 * the coverage accumulators behind it. Only the accumulator entries the
 * region wrote (ws->touched) are visited, in x order: pixel x gets
 * clamp(area[x] + running cover), and the pixels up to the next entry
 * share clamp(running cover), so they are folded as one run. The sums are
 * those a pass over every pixel of [lo, hi) makes, in the same order.
 * Returns whether the region may hide (region_may_hide), which each copy
 * tests in its own case: the caller's test of every field per region-row
 * was ~0.2 M instructions of a Many-blobs exact frame.
 */
static CS__SPECIALISE bool fold_region_as(cs_renderer *r, uint32_t reg, int y, int32_t lo,
                                           int32_t hi, bool direct, bool bare, bool grey,
                                           bool functional)
{
    cs_workspace *ws = r->ws;
    fold_paint fp;
    fp.r = r;
    fp.region = &r->scene->regions[reg];
    fp.functional = functional;
    /* Written out: as a loop GCC vectorised the six floats behind a
     * run-time test of the arrays' overlap, ~30 instructions a region-row. */
    const float *E = ws->region_E[reg], *T = ws->region_T[reg];
    fp.E[0] = E[0];
    fp.E[1] = E[1];
    fp.E[2] = E[2];
    fp.E[3] = 0.0f;
    fp.A[0] = 1.0f - T[0];
    fp.A[1] = 1.0f - T[1];
    fp.A[2] = 1.0f - T[2];
    fp.y = y;
    fp.direct = direct;
    fp.bare = bare;
    /* region_may_hide, where a region with no function has its T alone to
     * test, and a grey frame's T is one number on every channel. */
    bool hides = functional ? region_may_hide(r, reg)
                 : grey     ? T[0] < CS__T_ZERO
                            : T[0] < CS__T_ZERO && T[1] < CS__T_ZERO && T[2] < CS__T_ZERO;
    fp.snap = direct && hides;
    uint32_t width = (uint32_t)r->vw;
    uint32_t end = (uint32_t)hi; /* hi <= width: coverage ends there */
    float run = 0.0f;
    /* Nothing waits, at coverage 0 from lo, the first entry (lo is at or
     * left of every entry written), so that entry needs no test of its own:
     * the gap before it has the running cover 0 and leaves nothing to fold. */
    pending p;
    p.a = p.b = (uint32_t)lo;
    p.cursor = cs__run_start(ws, (uint32_t)lo);
    p.c = 0.0f;
    /* The last word to visit, found once: the loop's one bound test per
     * word is most of its cost where a wide region's interior words are 0. */
    uint32_t w_last = (end + 1u) >> 5 < width >> 5 ? (end + 1u) >> 5 : width >> 5;
    for (uint32_t w = (uint32_t)lo >> 5; w <= w_last; w++) {
        uint32_t bits = ws->touched[w];
        ws->touched[w] = 0u;
        while (bits) {
            uint32_t x = (w << 5) + cs__low_bit(bits);
            bits &= bits - 1u;
            float cv = ws->cover[x], ar = ws->area[x];
            ws->cover[x] = ws->area[x] = 0.0f;
            if (x >= end)
                continue; /* deltas past the right end sum to zero */
            if (p.b < x) /* the gap up to x has the running cover */
                pending_extend(ws, &fp, &p, x, cs__clampf(run, 0.0f, 1.0f), grey);
            run += cv;
            pending_extend(ws, &fp, &p, x + 1u, cs__clampf(ar + run, 0.0f, 1.0f), grey);
        }
    }
    /* Rounding may leave the running cover a hair from zero up to hi. */
    if (p.b < end)
        pending_extend(ws, &fp, &p, end, cs__clampf(run, 0.0f, 1.0f), grey);
    if (p.c > 0.0f)
        fold_run_as(ws, &fp, p.cursor, p.a, p.b, p.c, grey);
    return hides;
}

/*
 * fold_region_as once per case, a grey frame and a coloured one, with the
 * run code inlined at each of its four places: 2 % fewer instructions in a
 * Many-blobs frame than calling one copy of it per case (the call, and the
 * registers it saves, were ~25 instructions of each of ~100 k folded runs),
 * for ~14 KB more Cortex-M4 code, which CS_CFG_GREY 0 leaves out. Where
 * CS_CFG_GREY is on (the hosts) a region folded straight into the stack
 * (`direct`) has copies of its own as well: the test per folded run was
 * mispredicted ~28 k times a Many-blobs exact frame (cachegrind
 * --branch-sim), as lone and summed regions alternate along a line
 * (another ~10 KB of Cortex-M4 code, again none with CS_CFG_GREY 0).
 * The four copies are inlined into cs__line_stack, fold_region's one
 * caller, too: its call saved and restored six registers and set up a
 * 424-byte frame for every region-row (-0.5 M instructions a Many-blobs
 * exact frame). A functional paint (a gradient: rare, and per pixel
 * anyway) takes a fifth copy for all cases, so that the four test no
 * run for it (-0.3 M). A grey frame's summed region that is the first of
 * its cel to fold on the line (`bare`: no run holds the cel yet) takes a
 * sixth, whose splits and accumulation read and test no run's `used`
 * (-0.3 M, -0.56 M without the v3 build's profile).
 */
static CS__SPECIALISE bool fold_region(cs_renderer *r, uint32_t reg, int y, int32_t lo, int32_t hi,
                                        bool direct, bool bare)
{
    bool functional = region_functional(&r->scene->regions[reg]);
#if CS_CFG_GREY
    if (functional) {
        return fold_region_as(r, reg, y, lo, hi, direct, direct, r->grey, true);
    } else if (r->grey) {
        if (direct)
            return fold_region_as(r, reg, y, lo, hi, true, true, true, false);
        else if (bare)
            return fold_region_as(r, reg, y, lo, hi, false, true, true, false);
        else
            return fold_region_as(r, reg, y, lo, hi, false, false, true, false);
    } else if (direct) {
        return fold_region_as(r, reg, y, lo, hi, true, true, false, false);
    } else {
        return fold_region_as(r, reg, y, lo, hi, false, false, false, false);
    }
#else
    (void)bare;
    return fold_region_as(r, reg, y, lo, hi, direct, false, false, functional);
#endif
}

/*
 * Whether every pixel the region's pieces could touch on this line (their
 * segments' hulls, cs_segment.px_lo/px_hi) is already opaque: a skipped
 * region then provably changes no pixel.
 */
static bool region_hidden(cs_renderer *r, const cs_index *act, uint32_t n)
{
    if (r->opaque_px == 0u) /* always so with the early-out off (cs__run_join) */
        return false;
    cs_workspace *ws = r->ws;
    /* Most regions show, and a pixel of their first piece's hull (within
     * the region's) tells so without the hull of all their pieces: that
     * hull is tested first, the whole one only if it shows nothing. One
     * call of cs__span_opaque, so that a board inlines it once. */
    const cs_segment *s = &ws->segments[ws->pieces[act[0]].segment];
    uint32_t a = s->px_lo, b = s->px_hi, i = 1; /* px_lo < r->vw (cs_frame.c) */
    for (;;) {
        if (a < b && !cs__span_opaque(r, a, b))
            return false;
        if (i >= n)
            return true;
        for (; i < n; i++) {
            s = &ws->segments[ws->pieces[act[i]].segment];
            a = s->px_lo < a ? s->px_lo : a;
            b = s->px_hi > b ? s->px_hi : b;
        }
    }
}

/*
 * The region's coverage on line y in the accumulators, over [*lo, *hi):
 * exact area straight from cs_exact.c, the sampled modes through
 * cs__region_coverage (one call instead of two: the sampled modes' body
 * saved and restored its registers around the exact call too, ~60
 * instructions of each of a Many-blobs exact frame's 26 k region-rows).
 */
static void region_coverage(cs_renderer *r, uint32_t reg, const cs_index *act, uint32_t n, int y,
                            int32_t *lo, int32_t *hi)
{
#if CS_CFG_EXACT
    if (r->opts.aa == CS_AA_EXACT) {
        *lo = INT32_MAX;
        *hi = INT32_MIN;
        cs_status st = cs__exact_region(r, &r->scene->regions[reg], act, n, y, lo, hi);
        if (CS__UNLIKELY(st != CS_OK) && r->sticky.status == CS_OK) {
            uint32_t cel = r->ws->region_cel[reg];
            cs__error(&r->sticky, st, cel, (int32_t)(reg - r->scene->cels[cel].first_region), -1,
                      y);
        }
        if (*hi > r->vw)
            *hi = r->vw;
        return;
    }
#endif
    cs__region_coverage(r, reg, act, n, y, lo, hi);
}

/* Composites the cel's map at the run starting at s behind the stack and
 * clears the cel's share of it. If the cel may hide (`snap`), T is snapped
 * to 0 below CS__T_ZERO. Snapping depends on the cel alone, never on the
 * early-out, so turning the early-out off changes no bit. */
static CS__SPECIALISE void composite_run(cs_renderer *r, uint32_t s, bool snap, bool grey)
{
    cs_workspace *ws = r->ws;
    float t[3];
    ws->used[s] = 0.0f; /* before the join, which may mark the run opaque there */
    transmittance(t, &ws->cel_A[3 * s], 1.0f, snap, grey);
    cs__run_join(r, grey, s, ws->run_end[s], &ws->cel_E[3 * s], t);
}

#if CS_CFG_CEL_LIST
/*
 * Composites the runs the cel covers (used > 0), which are listed; the
 * cel's map is (0, 1) elsewhere, which leaves the stack as it is. Each
 * run's join reads and writes that run alone, so the list's order (that
 * of first coverage and splits) gives the bits of an x-order walk.
 */
static CS__SPECIALISE void composite_cel_as(cs_renderer *r, bool snap, bool grey)
{
    cs_workspace *ws = r->ws;
    for (uint32_t k = 0; k < ws->cel_run_count; k++)
        composite_run(r, ws->cel_runs[k], snap, grey);
    ws->cel_run_count = 0;
}

static void composite_cel(cs_renderer *r, bool snap)
{
    if (CS_CFG_GREY && r->grey)
        composite_cel_as(r, snap, true);
    else
        composite_cel_as(r, snap, false);
}
#else
/*
 * Composites the runs of [lo, hi) that the cel covers (used > 0); the
 * cel's map is (0, 1) elsewhere, which leaves the stack as it is.
 */
static CS__SPECIALISE void composite_cel_as(cs_renderer *r, uint32_t lo, uint32_t hi, bool snap,
                                            bool grey)
{
    cs_workspace *ws = r->ws;
    for (uint32_t s = cs__run_start(ws, lo); s < hi; s = ws->run_end[s])
        if (ws->used[s] > 0.0f) /* not 0, nor an opaque run's CS__USED_OPAQUE */
            composite_run(r, s, snap, grey);
}

static void composite_cel(cs_renderer *r, uint32_t lo, uint32_t hi, bool snap)
{
    if (CS_CFG_GREY && r->grey)
        composite_cel_as(r, lo, hi, snap, true);
    else
        composite_cel_as(r, lo, hi, snap, false);
}

/*
 * The pixel ranges a cel's regions touched on this line, sorted and
 * disjoint: composite_cel walks these rather than the hull from the
 * leftmost to the rightmost region, which for a cel of scattered shapes
 * is most of the line. A few ranges suffice; when an added range would
 * make one too many, the two closest ranges become one (covering the gap
 * costs a scan of pixels whose coverage is zero, never a wrong pixel).
 */
#define CEL_RANGES 8

typedef struct cel_ranges {
    int32_t lo[CEL_RANGES + 1], hi[CEL_RANGES + 1];
    uint32_t n;
} cel_ranges;

static void ranges_add(cel_ranges *s, int32_t lo, int32_t hi)
{
    int32_t tlo[CEL_RANGES + 1], thi[CEL_RANGES + 1];
    uint32_t n = 0;
    bool placed = false;
    for (uint32_t k = 0; k < s->n; k++) {
        if (s->hi[k] < lo) {
            tlo[n] = s->lo[k];
            thi[n++] = s->hi[k];
        } else if (s->lo[k] > hi) {
            if (!placed) {
                tlo[n] = lo;
                thi[n++] = hi;
                placed = true;
            }
            tlo[n] = s->lo[k];
            thi[n++] = s->hi[k];
        } else { /* overlapping or touching: absorb it */
            lo = s->lo[k] < lo ? s->lo[k] : lo;
            hi = s->hi[k] > hi ? s->hi[k] : hi;
        }
    }
    if (!placed) {
        tlo[n] = lo;
        thi[n++] = hi;
    }
    if (n > CEL_RANGES) { /* join the two ranges with the smallest gap */
        uint32_t best = 0;
        for (uint32_t k = 1; k + 1 < n; k++)
            if (tlo[k + 1] - thi[k] < tlo[best + 1] - thi[best])
                best = k;
        thi[best] = thi[best + 1];
        for (uint32_t k = best + 1; k + 1 < n; k++) {
            tlo[k] = tlo[k + 1];
            thi[k] = thi[k + 1];
        }
        n--;
    }
    for (uint32_t k = 0; k < n; k++) {
        s->lo[k] = tlo[k];
        s->hi[k] = thi[k];
    }
    s->n = n;
}

static void composite_ranges(cs_renderer *r, cel_ranges *s, bool snap)
{
    for (uint32_t k = 0; k < s->n; k++)
        composite_cel(r, (uint32_t)s->lo[k], (uint32_t)s->hi[k], snap);
    s->n = 0;
}
#endif

void cs__line_stack(cs_renderer *r, int y)
{
    cs_workspace *ws = r->ws;
    uint32_t width = (uint32_t)r->vw;
    cs__line_active(r, y);
    /* One clear run: E = 0, T = 1, nothing of a cel. */
    for (uint32_t w = 0; w <= width >> 5; w++)
        ws->run_starts[w] = ws->opaque_bits[w] = 0u;
    ws->run_starts[0] = 1u;
    ws->run_end[0] = (uint16_t)width;
    ws->used[0] = 0.0f;
    for (int ch = 0; ch < 3; ch++) {
        ws->stack_E[ch] = 0.0f;
        ws->stack_T[ch] = 1.0f;
    }
    r->opaque_px = 0;
    /* Without the record nothing is ever opaque, so nothing is skipped. */
    r->record = !r->opts.no_early_out;
    uint32_t cache_end = r->cache ? r->cache->cel_first + r->cache->cel_count : 0;
    bool cache_pending = CS_CFG_CACHE && r->cache != 0; /* else its code is left out */
    uint32_t i = 0;
#if CS_CFG_CEL_LIST
    ws->cel_run_count = 0;
#else
    cel_ranges ranges;
    ranges.n = 0;
#endif
    uint32_t current_cel = UINT32_MAX;
    bool cel_hides = false;
    bool cel_folded = false; /* a region of the current cel was folded on this line */
    /* The active pieces come grouped by region; the scan for a group's end
     * reads the next group's region, which is kept (`next`), not read again. */
    uint32_t n = r->active_count;
    uint32_t next = n ? ws->pieces[ws->active[0]].region : 0u;
    while (i < n) {
        uint32_t reg = next;
        uint32_t j = i + 1;
        while (j < n && (next = ws->pieces[ws->active[j]].region) == reg)
            j++;
        uint32_t cel = ws->region_cel[reg];
        if (cel != current_cel) {
#if CS_CFG_CEL_LIST
            composite_cel(r, cel_hides);
#else
            composite_ranges(r, &ranges, cel_hides);
#endif
            cel_hides = false;
            cel_folded = false;
            if (cache_pending && cel >= cache_end) {
                cs__cache_composite(r, y);
                cache_pending = false;
            }
            current_cel = cel;
            /* Front to back: once the whole line is opaque nothing behind shows. */
            if (r->opaque_px >= width) /* never with the early-out off */
                break;
        }
        if (!region_hidden(r, &ws->active[i], j - i)) {
            int32_t lo, hi;
            region_coverage(r, reg, &ws->active[i], j - i, y, &lo, &hi);
            if (lo < hi) {
                /* A cel's only region on the line goes straight into the
                 * stack; otherwise the cel's regions are summed first. */
                bool alone = !cel_folded && (j == n || ws->region_cel[next] != cel);
                bool hides = fold_region(r, reg, y, lo, hi, alone, !cel_folded);
                if (!alone) {
#if !CS_CFG_CEL_LIST
                    ranges_add(&ranges, lo, hi);
#endif
                    cel_hides = cel_hides || hides;
                }
                cel_folded = true;
            }
        }
        i = j;
    }
#if CS_CFG_CEL_LIST
    composite_cel(r, cel_hides);
#else
    composite_ranges(r, &ranges, cel_hides);
#endif
    if (cache_pending)
        cs__cache_composite(r, y);
}
