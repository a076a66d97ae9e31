/*
 * cs_line.c - one display line: crossings, spans, coverage, compositing.
 *
 * For each line the active monotone pieces (those whose y range meets the
 * pixel row) are intersected afresh with each sample scanline: nothing is
 * carried from line to line but the list of which pieces are active (and,
 * in exact mode, each piece's end at the last row boundary, a pure
 * function of the piece and the height: see cs_exact.c), so errors cannot
 * accumulate, rows off screen cost nothing, and a line comes out the same
 * whichever lines were rendered before it. Within a line, a
 * piece's root on one sub-scanline starts the Newton solve on the next,
 * 1/N of a pixel lower, which converges in two or three steps where a solve
 * over the whole piece needs several more. The guess travels with the
 * crossing (cs_crossing.guess) to the next sub-scanline, whose crossings
 * are taken in the previous one's x order and so come nearly sorted; it is
 * a starting point only, the same on every target, and the result is the
 * solver's. With many sub-scanlines, most pieces cross all of them, and
 * over one pixel of height x(y) is nearly a cubic: such a piece is solved
 * on the first, middle and last sub-scanline only, and in between x is the
 * cubic through the ends with the curve's slope there, kept only if it
 * meets the middle root to 1/1024 px (interp_setup). A straight piece is
 * exactly linear in y and needs its two ends alone.
 *
 * Pieces are kept in scene order, which groups them by region and regions
 * by cel, front-most first. For one region the crossings of a scanline,
 * sorted by x, become spans under its fill rule, and each span adds its
 * exact horizontal coverage to two per-pixel accumulators in the manner of
 * FreeType's cells: `area` holds the partial coverage of the pixels where a
 * span starts or ends, `cover` holds +w/-w deltas whose running sum is the
 * coverage of the pixels fully inside. A span costs O(1) however long it
 * is, and the entries it wrote are marked (ws->touched).
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
 * Adds span [xa, xb) with weight w to the accumulators of the window that
 * starts at device column x0 (xa, xb in [r->clip_lo, r->clip_hi]). The
 * arithmetic is on device x, as the whole output's render does it; only
 * the accumulator index is shifted. A span entering from the left of the
 * window (from column x0 - 1, where crossings further left are clamped)
 * puts its +w on the window's first entry rather than on its own column:
 * the running cover is then the same sum of multiples of w (exact: w is
 * 1/2^k, or the window is the whole line), and no area lands on a pixel
 * of the window that the whole render would not give it.
 */
static void add_span(cs_workspace *ws, float xa, float xb, float w, int32_t x0)
{
    int32_t ia = cs__floori(xa), ib = cs__floori(xb);
    if (ia == ib) {
        if (ia >= x0)
            cs__acc_area(ws, ia - x0, w * (xb - xa));
        return;
    }
    if (ia >= x0)
        cs__acc_area(ws, ia - x0, w * ((float)(ia + 1) - xa));
    cs__acc_cover(ws, ia + 1 - x0, w);
    cs__acc_cover(ws, ib - x0, -w);
    cs__acc_area(ws, ib - x0, w * (xb - (float)ib));
}

/* Pixel-centre sampling: pixels i with xa <= i + 0.5 < xb, those left of
 * the window x0 counted from its first entry (integers: exact). */
static void add_span_centres(cs_workspace *ws, float xa, float xb, int32_t x0)
{
    int32_t i0 = cs__floori(xa - 0.5f);
    if ((float)i0 + 0.5f < xa)
        i0++;
    int32_t i1 = cs__floori(xb - 0.5f);
    if ((float)i1 + 0.5f < xb)
        i1++;
    if (i1 > i0 && i1 > x0) {
        cs__acc_cover(ws, (i0 > x0 ? i0 : x0) - x0, 1.0f);
        cs__acc_cover(ws, i1 - x0, -1.0f);
    }
}

/* Shell sort by x: no scratch memory, fast on the short lists lines give.
 * Most lists are one shape's two crossings, which need one comparison, not
 * eight passes. Gaps not below n would be empty passes. */
static void sort_crossings(cs_crossing *c, uint32_t n)
{
    static const uint32_t gaps[] = {701, 301, 132, 57, 23, 10, 4, 1};
    if (n <= 2u) {
        if (n == 2u && c[1].x < c[0].x) {
            cs_crossing t = c[0];
            c[0] = c[1];
            c[1] = t;
        }
        return;
    }
    unsigned g = 0;
    while (gaps[g] >= n)
        g++;
    for (; g < sizeof gaps / sizeof gaps[0]; g++) {
        uint32_t gap = gaps[g];
        for (uint32_t i = gap; i < n; i++) {
            cs_crossing t = c[i];
            uint32_t j = i;
            while (j >= gap && c[j - gap].x > t.x) {
                c[j] = c[j - gap];
                j -= gap;
            }
            c[j] = t;
        }
    }
}

/* Insertion sort by x, for crossings listed in the previous sub-scanline's
 * x order: 1/N of a pixel lower few have changed places, so this is one
 * comparison per crossing plus one move per swap. */
static void sort_nearly_sorted(cs_crossing *c, uint32_t n)
{
    for (uint32_t i = 1; i < n; i++) {
        if (!(c[i - 1].x > c[i].x))
            continue;
        cs_crossing t = c[i];
        uint32_t j = i;
        do {
            c[j] = c[j - 1];
            j--;
        } while (j > 0 && c[j - 1].x > t.x);
        c[j] = t;
    }
}

/* The level of sub-scanline k of line y, of N = 1 / step. */
static inline float sample_y(int y, int k, float step)
{
    return (float)y + ((float)k + 0.5f) * step;
}

/* u where a straight piece (degree 1) meets level ys: the closed form of
 * cs__solve_level, g = Y - ys W being linear, without its bracket checks
 * (an active piece meets the level inside [u0, u1] up to rounding, and the
 * clamp keeps it there). */
static inline float straight_root(const cs_segment *s, const cs_piece *pc, float ys)
{
    ys -= (float)s->oy;
    float g0 = s->y[0] - ys * s->w[0], g1 = s->y[1] - ys * s->w[1];
    if (g1 == 0.0f) /* level along the piece: the solver picks the end */
        return cs__solve_level(s->y, s->w, 1, ys, pc->u0, pc->u1);
    return cs__clampf(-g0 / g1, pc->u0, pc->u1);
}

/*
 * The crossing of piece pc with scanline ys, which it spans: x clamped to
 * [lo, hi] (r->clip_lo, r->clip_hi), and the guess for the next sub-scanline's root. A curved
 * piece's root is sought by Newton's iteration from `guess` when `warm`,
 * by the full bracketed solve on its first sub-scanline of the line.
 */
static inline void piece_crossing(const cs_workspace *ws, const cs_piece *pc, float ys,
                                  float step, float lo, float hi, bool warm, float guess,
                                  cs_crossing *c)
{
    const cs_segment *s = &ws->segments[pc->segment];
    float u, w, slope = 0.0f;
    if (s->degree == 1) { /* closed form: no guess needed */
        u = straight_root(s, pc, ys);
        w = cs__horner(s->w, 1, u);
        c->guess = u;
    } else {
        float level = ys - (float)s->oy;
        if (warm)
            u = cs__solve_level_from(s->y, s->w, s->degree, level, pc->u0, pc->u1, guess,
                                     pc->dir > 0, &slope);
        else
            u = cs__solve_level(s->y, s->w, s->degree, level, pc->u0, pc->u1);
        w = cs__horner(s->w, s->degree, u);
        /* This root moved along the level by one step (du/dlevel = W / g'),
         * or the root itself. */
        c->guess = slope != 0.0f ? cs__clampf(u + step * w / slope, pc->u0, pc->u1) : u;
    }
    float x = (float)s->ox + cs__horner(s->x, s->degree, u) / w;
    c->x = cs__clampf(x, lo, hi);
    c->dir = pc->dir;
    c->operand = pc->operand;
}

/* Segment s at parameter u, where it meets level ys: x, dx/dy, W, and
 * g' = Y' - ys W' (the level polynomial's derivative, so du/dy = W / g'). */
typedef struct level_point {
    float x, dxdy, w, g1;
} level_point;

static inline level_point level_point_at(const cs_segment *s, float u, float ys)
{
    float dX, dY, dW;
    float X = cs__horner_d(s->x, s->degree, u, &dX);
    float W = cs__horner_d(s->w, s->degree, u, &dW);
    (void)cs__horner_d(s->y, s->degree, u, &dY);
    level_point p;
    float x = X / W; /* from the segment's origin, as X is */
    p.x = (float)s->ox + x;
    p.w = W;
    p.g1 = dY - (ys - (float)s->oy) * dW;
    p.dxdy = (dX - x * dW) / p.g1;
    return p;
}

/* How far (px) the cubic may miss the middle root: below 1/4 of 1/255 of
 * coverage, where --aa 16's own sampling error reaches ~8/255. */
#define CS__INTERP_TOL (1.0f / 1024.0f)

/*
 * Sets crossing c, just solved on the line's first sub-scanline ys0 (its
 * root in c->guess), to follow x through the remaining ones by a formula,
 * if piece pc reaches below the last, ys_last. A straight piece is linear
 * in y. A curved one gets the cubic Hermite interpolant of x(y) from x and
 * dx/dy at ys0 and ys_last, kept only if it meets the root on sub-scanline
 * `mid` (at ys_mid) within CS__INTERP_TOL: a cubic's error over an interval
 * is largest near its middle, so the check catches the curves too bent
 * for it (they stay with Newton), though it is a check, not a bound.
 */
static void interp_setup(const cs_workspace *ws, const cs_piece *pc, float ys0, float ys_last,
                         float ys_mid, int samples, int mid, cs_crossing *c)
{
    const cs_segment *s = &ws->segments[pc->segment];
    float u0 = c->guess, n1 = (float)(samples - 1);
    if (s->degree == 1) { /* exact, so no check */
        float u1 = straight_root(s, pc, ys_last);
        float x1 = cs__segment_x(s, u1), x0 = cs__segment_x(s, u0);
        c->guess = x0;
        c->a1 = (x1 - x0) / n1;
        c->a2 = 0.0f;
        c->a3 = 0.0f;
        return;
    }
    float slope;
    level_point p0 = level_point_at(s, u0, ys0);
    float x0 = p0.x;
    /* Newton's start on ys_last: du/dy = W / g' at u0. */
    float guess = cs__clampf(u0 + (ys_last - ys0) * p0.w / p0.g1, pc->u0, pc->u1);
    bool rising = pc->dir > 0;
    float oy = (float)s->oy;
    float u1 = cs__solve_level_from(s->y, s->w, s->degree, ys_last - oy, pc->u0, pc->u1, guess,
                                    rising, &slope);
    level_point p1 = level_point_at(s, u1, ys_last);
    float x1 = p1.x;
    /* Hermite over t = k / n1 in [0, 1]: end slopes in x per unit t. */
    float h = ys_last - ys0, m0 = p0.dxdy * h, m1 = p1.dxdy * h;
    float c2 = 3.0f * (x1 - x0) - 2.0f * m0 - m1, c3 = 2.0f * (x0 - x1) + m0 + m1;
    float t = (float)mid / n1;
    float um = cs__solve_level_from(s->y, s->w, s->degree, ys_mid - oy, pc->u0, pc->u1,
                                    u0 + (u1 - u0) * t, rising, &slope);
    float xm = cs__segment_x(s, um);
    /* NaN or infinite slopes fail this test too. */
    if (!(cs__absf(x0 + t * (m0 + t * (c2 + t * c3)) - xm) <= CS__INTERP_TOL))
        return;
    c->guess = x0;
    c->a1 = m0 / n1;
    c->a2 = c2 / (n1 * n1);
    c->a3 = c3 / (n1 * n1 * n1); /* a finite number, as the test above passed */
}

/*
 * The crossings of a region's active pieces act[] with sub-scanline `sub`
 * (of `samples`) of line y, sorted by x. Returns their count, or -1 if they do not
 * fit in ws->crossings.
 *
 * The previous sub-scanline's `live` crossings, still in ws->crossings in
 * x order, say which pieces crossed it and where to seek their roots now:
 * they are redone in that order (those that end above ys dropped), so they
 * come nearly sorted. Pieces that did not cross it yet wait in
 * ord[0..*idle) (indices into act); those reaching ys join at the end with
 * a full solve; an interpolated one (interp_setup) is only evaluated.
 * Nothing of this outlives the line: its first sub-scanline starts with
 * every piece waiting.
 */
static int32_t crossings_at(cs_renderer *r, const cs_index *act, cs_index *ord, uint32_t *idle,
                            uint32_t live, int y, int sub, int samples)
{
    cs_workspace *ws = r->ws;
    float lo = r->clip_lo, hi = r->clip_hi;
    float step = 1.0f / (float)samples, ys = sample_y(y, sub, step);
    /* Pieces that cross every sub-scanline of the line are interpolated
     * (interp_setup); the first sub-scanline sets them up. */
    float at = (float)sub;
    bool setup = sub == 0 && samples >= CS__INTERP_MIN_SAMPLES;
    int mid = samples / 2;
    float ys_last = sample_y(y, samples - 1, step), ys_mid = sample_y(y, mid, step);
    uint32_t count = 0, kept = 0, waiting = 0, total = live + *idle;
    /* One loop over both lists, so that piece_crossing is made once. */
    for (uint32_t j = 0; j < total; j++) {
        bool warm = j < live;
        float guess = 0.0f;
        cs_index k;
        const cs_piece *pc;
        if (warm) { /* count <= j: rewritten in place */
            if (ws->crossings[j].a3 == ws->crossings[j].a3) { /* interpolated */
                cs_crossing *c = &ws->crossings[count++];
                *c = ws->crossings[j];
                float x = c->guess + at * (c->a1 + at * (c->a2 + at * c->a3));
                c->x = cs__clampf(x, lo, hi);
                continue;
            }
            guess = ws->crossings[j].guess;
            k = ws->crossings[j].piece;
            pc = &ws->pieces[act[k]];
        } else {
            if (j == live)
                kept = count;
            k = ord[j - live];
            pc = &ws->pieces[act[k]];
            if (ys < pc->y_top) {
                ord[waiting++] = k; /* waiting <= j - live: only entries already read */
                continue;
            }
            if (count >= CS_CFG_MAX_CROSSINGS)
                return -1;
        }
        if (!(ys < pc->y_bot))
            continue; /* ended, or passed between two sub-scanlines */
        cs_crossing *c = &ws->crossings[count++];
        piece_crossing(ws, pc, ys, step, lo, hi, warm, guess, c);
        c->piece = (uint16_t)k;
        c->a3 = CS__NAN; /* not interpolated, unless: */
        if (setup && ys_last < pc->y_bot)
            interp_setup(ws, pc, ys, ys_last, ys_mid, samples, mid, c);
    }
    if (live == total)
        kept = count;
    *idle = waiting;
    /* Many newcomers (the line's first sub-scanline) come in piece order. */
    if (count - kept > 4u)
        sort_crossings(ws->crossings, count);
    else
        sort_nearly_sorted(ws->crossings, count);
    return (int32_t)count;
}

/* Turns sorted crossings into spans under the fill rule and accumulates.
 * The spans come in x order, so the first and the last set the pixel
 * range. A region without CSG keeps one winding count and no stack. */
static void accumulate_spans(cs_renderer *r, uint32_t count, const cs_region *region, float weight,
                             bool centres, int32_t *lo, int32_t *hi)
{
    cs_workspace *ws = r->ws;
    const cs_crossing *c = ws->crossings;
    int32_t winding[CS_CFG_MAX_OPERANDS];
    for (int k = 0; k < CS_CFG_MAX_OPERANDS; k++) /* a loop: `= {0}` may call memset */
        winding[k] = 0;
    bool csg = region->csg_len != 0;
    uint8_t rule = region->fill_rule; /* a local: a byte read may alias the float stores */
    int32_t wind = 0;
    float first = 0.0f, last = 0.0f;
    bool any = false;
    for (uint32_t i = 0; i + 1 < count; i++) {
        bool inside;
        if (csg) {
            winding[c[i].operand] += c[i].dir;
            inside = cs__region_inside(region, winding);
        } else {
            wind += c[i].dir;
            inside = cs__fill(rule, wind);
        }
        float xa = c[i].x, xb = c[i + 1].x;
        if (!inside || !(xb > xa))
            continue;
        if (centres)
            add_span_centres(ws, xa, xb, r->vx);
        else
            add_span(ws, xa, xb, weight, r->vx);
        if (!any)
            first = xa;
        any = true;
        last = xb;
    }
    if (any) {
        int32_t a = cs__floori(first) - r->vx, b = cs__floori(last) + 1 - r->vx;
        if (a < 0) /* entered from the left of the window */
            a = 0;
        if (a < *lo)
            *lo = a;
        if (b > *hi)
            *hi = b;
    }
}

/*
 * Coverage of region `reg` on line y from its active pieces, left in the
 * area/cover accumulators over [*lo, *hi). Every anti-aliasing mode fills
 * the same accumulators, so everything after this step is mode-blind.
 */
static void region_coverage(cs_renderer *r, uint32_t reg, const cs_index *act, uint32_t n, int y,
                            int32_t *lo_out, int32_t *hi_out)
{
    cs_workspace *ws = r->ws;
    const cs_region *region = &r->scene->regions[reg];
    int samples = 1;
    bool centres = false;
    switch (r->opts.aa) {
    case CS_AA_NONE:
        centres = true;
        break;
    case CS_AA_SUBSCAN:
        samples = r->opts.subscanlines;
        break;
    case CS_AA_EXACT:
        samples = 0; /* no samples: cs_exact.c finds the area itself */
        break;
    }
    float weight = samples > 0 ? 1.0f / (float)samples : 0.0f;
    int32_t lo = INT32_MAX, hi = INT32_MIN;
#if CS_CFG_EXACT
    if (r->opts.aa == CS_AA_EXACT) {
        cs_status st = cs__exact_region(r, region, act, n, y, &lo, &hi);
        if (st != CS_OK && r->sticky.status == CS_OK) {
            const cs_cel *cel = &r->scene->cels[ws->region_cel[reg]];
            cs__error(&r->sticky, st, ws->region_cel[reg],
                      (int32_t)(reg - cel->first_region), -1, y);
        }
    }
#endif
    /* Every piece waits for its first crossing: no root carries over from
     * another line. ws->scratch is free once update_active is done. */
    cs_index *ord = ws->scratch;
    uint32_t idle = 0, live = 0;
    for (int k = 0; k < samples; k++) {
        if (k == 0)
            for (idle = 0; idle < n; idle++)
                ord[idle] = (cs_index)idle;
        int32_t count = crossings_at(r, act, ord, &idle, live, y, k, samples);
        if (count < 0) {
            if (r->sticky.status == CS_OK) {
                const cs_cel *cel = &r->scene->cels[ws->region_cel[reg]];
                cs__error(&r->sticky, CS_ERR_CAP_CROSSINGS, ws->region_cel[reg],
                          (int32_t)(reg - cel->first_region), -1, y);
            }
            /* The region is left out of this sample (visible, never
             * unsafe); the next one starts afresh. */
            for (idle = 0; idle < n; idle++)
                ord[idle] = (cs_index)idle;
            live = 0;
            continue;
        }
        live = (uint32_t)count;
        accumulate_spans(r, live, region, weight, centres, &lo, &hi);
    }
    if (hi > r->vw)
        hi = r->vw;
    *lo_out = lo;
    *hi_out = hi;
}

/*
 * A region's paint at one pixel when any of its fields is a function:
 * the same E, T as the frame's region_map, with the fields evaluated at the
 * pixel centre.
 */
static void paint_at(const cs_renderer *r, const cs_region *region, const float *front,
                     const float *back, float px, float py, float *E, float *A)
{
    const cs_scene *scene = r->scene;
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
    beta *= r->ws->cel_opacity[r->ws->region_cel[region - scene->regions]];
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

/* What a region adds to the runs: its paint, or how to evaluate it. */
typedef struct fold_paint {
    cs_renderer *r; /* the direct path counts opaque pixels in it */
    const cs_region *region;
    const cs_cel *cel;
    const float *front;
    float E[3], A[3]; /* the constant map (c = 1) when not functional */
    float py;         /* pixel-centre y, for functional paints */
    bool functional;
    bool direct;      /* the cel's only region on this line: straight into the stack */
    bool snap;        /* with direct: the cel may hide (see region_may_hide) */
} fold_paint;

/* Adds coverage c of paint (E, A) to the cel at the run starting at s,
 * within what the regions in front of it left (`used`). A grey frame keeps
 * A in channel 0 alone. */
static CS__SPECIALISE void accumulate(cs_workspace *ws, bool grey, uint32_t s, float c,
                                      const float *E, const float *A)
{
    float room = 1.0f - ws->used[s];
    if (c > room)
        c = room;
    if (!(c > 0.0f))
        return;
    float *ce = &ws->cel_E[3 * s], *ca = &ws->cel_A[3 * s];
    if (ws->used[s] == 0.0f) { /* the first region here: what is stored is stale */
        for (int ch = 0; ch < 3; ch++)
            ce[ch] = c * E[ch];
        ca[0] = c * A[0];
        if (!grey) {
            ca[1] = c * A[1];
            ca[2] = c * A[2];
        }
    } else {
        for (int ch = 0; ch < 3; ch++)
            ce[ch] += c * E[ch];
        ca[0] += c * A[0];
        if (!grey) {
            ca[1] += c * A[1];
            ca[2] += c * A[2];
        }
    }
    ws->used[s] += c;
}

/* t = 1 - c A, snapped to 0 below CS__T_ZERO if the cel may hide; channel
 * 0 alone in a grey frame (the others are left unset). */
static CS__SPECIALISE void transmittance(float t[3], const float *A, float c, bool snap, bool grey)
{
    for (int ch = 0; ch < (grey ? 1 : 3); ch++) {
        t[ch] = 1.0f - c * A[ch];
        if (snap && t[ch] < CS__T_ZERO)
            t[ch] = 0.0f;
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
    float cE[3], t[3];
    for (int ch = 0; ch < 3; ch++)
        cE[ch] = c * E[ch];
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
        if (!cs__run_opaque(fp->r, s)) {
            e = cs__run_clip(ws, grey, &s, a, b);
            if (!fp->functional) {
                if (fp->direct)
                    composite_direct(fp->r, grey, s, e, c, fp->E, fp->A, fp->snap);
                else
                    accumulate(ws, grey, s, c, fp->E, fp->A);
            } else {
                /* The paint varies along x: a run per pixel. */
                for (uint32_t x = s;; x++) {
                    if (x + 1u < e)
                        cs__run_split(ws, grey, x, x + 1u);
                    float E[3], A[3];
                    paint_at(fp->r, fp->region, fp->front, fp->cel->back,
                             (float)((int32_t)x + fp->r->vx) + 0.5f, fp->py, E, A);
                    if (fp->direct)
                        composite_direct(fp->r, grey, x, x + 1u, c, E, A, fp->snap);
                    else
                        accumulate(ws, grey, x, c, E, A);
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
 */
static CS__SPECIALISE void fold_region_as(cs_renderer *r, uint32_t reg, int y, int32_t lo,
                                           int32_t hi, bool direct, bool grey)
{
    cs_workspace *ws = r->ws;
    fold_paint fp;
    fp.r = r;
    fp.region = &r->scene->regions[reg];
    fp.cel = &r->scene->cels[ws->region_cel[reg]];
    fp.front = fp.cel->has_front ? fp.cel->front : r->scene->stack_front;
    fp.functional = (fp.region->func[0] | fp.region->func[1] | fp.region->func[2]) != 0;
    const float *E = ws->region_E[reg], *T = ws->region_T[reg];
    for (int ch = 0; ch < 3; ch++) {
        fp.E[ch] = E[ch];
        fp.A[ch] = 1.0f - T[ch];
    }
    fp.py = (float)y + 0.5f;
    fp.direct = direct;
    fp.snap = direct && region_may_hide(r, reg);
    uint32_t width = (uint32_t)r->vw;
    uint32_t end = (uint32_t)hi; /* hi <= width: coverage ends there */
    float run = 0.0f;
    pending p;
    p.a = p.b = p.cursor = 0;
    p.c = 0.0f;
    bool first = true;
    for (uint32_t w = (uint32_t)lo >> 5; w <= width >> 5 && w <= (end + 1u) >> 5; w++) {
        uint32_t bits = ws->touched[w];
        ws->touched[w] = 0u;
        while (bits) {
            uint32_t x = (w << 5) + cs__low_bit(bits);
            bits &= bits - 1u;
            float cv = ws->cover[x], ar = ws->area[x];
            ws->cover[x] = ws->area[x] = 0.0f;
            if (x >= end)
                continue; /* deltas past the right end sum to zero */
            if (first) {
                p.cursor = cs__run_start(ws, x);
                p.a = p.b = x;
                first = false;
            } else if (p.b < x) { /* the gap up to x has the running cover */
                pending_extend(ws, &fp, &p, x, cs__clampf(run, 0.0f, 1.0f), grey);
            }
            run += cv;
            pending_extend(ws, &fp, &p, x + 1u, cs__clampf(ar + run, 0.0f, 1.0f), grey);
        }
    }
    if (first)
        return;
    /* Rounding may leave the running cover a hair from zero up to hi. */
    if (p.b < end)
        pending_extend(ws, &fp, &p, end, cs__clampf(run, 0.0f, 1.0f), grey);
    if (p.c > 0.0f)
        fold_run_as(ws, &fp, p.cursor, p.a, p.b, p.c, grey);
}

/*
 * fold_region_as once per case, a grey frame and a coloured one, with the
 * run code inlined at each of its four places: 2 % fewer instructions in a
 * Many-blobs frame than calling one copy of it per case (the call, and the
 * registers it saves, were ~25 instructions of each of ~100 k folded runs),
 * for ~14 KB more Cortex-M4 code, which CS_CFG_GREY 0 leaves out.
 */
static void fold_region(cs_renderer *r, uint32_t reg, int y, int32_t lo, int32_t hi, bool direct)
{
    if (CS_CFG_GREY && r->grey)
        fold_region_as(r, reg, y, lo, hi, direct, true);
    else
        fold_region_as(r, reg, y, lo, hi, direct, false);
}

/*
 * Whether every pixel the region's pieces could touch on this line (their
 * segments' hulls, cs_segment.px_lo/px_hi) is already opaque: a skipped
 * region then provably changes no pixel.
 */
static bool region_hidden(cs_renderer *r, const cs_index *act, uint32_t n)
{
    if (!r->record || r->opaque_px == 0u)
        return false;
    cs_workspace *ws = r->ws;
    uint32_t a = (uint32_t)r->vw, b = 0u;
    for (uint32_t i = 0; i < n; i++) {
        const cs_segment *s = &ws->segments[ws->pieces[act[i]].segment];
        a = s->px_lo < a ? s->px_lo : a;
        b = s->px_hi > b ? s->px_hi : b;
    }
    return a >= b || cs__span_opaque(r, a, b);
}

/*
 * Composites the runs of [lo, hi) that the cel covers (used > 0) behind
 * the stack and clears the cel's share of them. Elsewhere the cel's map is
 * (0, 1), which leaves the stack as it is. If the cel may hide (`snap`), T
 * is snapped to 0 below CS__T_ZERO. Snapping depends on the cel alone,
 * never on the early-out, so turning the early-out off changes no bit.
 */
static CS__SPECIALISE void composite_cel_as(cs_renderer *r, uint32_t lo, uint32_t hi, bool snap,
                                            bool grey)
{
    cs_workspace *ws = r->ws;
    for (uint32_t s = cs__run_start(ws, lo); s < hi; s = ws->run_end[s]) {
        if (ws->used[s] == 0.0f)
            continue;
        float *ce = &ws->cel_E[3 * s], *ca = &ws->cel_A[3 * s];
        float t[3];
        transmittance(t, ca, 1.0f, snap, grey);
        cs__run_join(r, grey, s, ws->run_end[s], ce, t);
        ws->used[s] = 0.0f;
    }
}

static void composite_cel(cs_renderer *r, uint32_t lo, uint32_t hi, bool snap)
{
    if (CS_CFG_GREY && r->grey)
        composite_cel_as(r, lo, hi, snap, true);
    else
        composite_cel_as(r, lo, hi, snap, false);
}

/* Moves the active list to line y: adds pieces starting above y+1, drops
 * those ending at or above y. The list stays in piece (scene) order. */
static void update_active(cs_renderer *r, int y)
{
    cs_workspace *ws = r->ws;
    if (y < r->next_line) { /* lines asked out of order: start over */
        r->active_count = 0;
        r->next_order = 0;
    }
    float top = (float)y, bottom = (float)(y + 1);
    uint32_t kept = 0;
    for (uint32_t i = 0; i < r->active_count; i++)
        if (ws->pieces[ws->active[i]].y_bot > top)
            ws->active[kept++] = ws->active[i];
    uint32_t first_new = r->next_order, added = 0;
    while (r->next_order < r->piece_count && ws->pieces[ws->order[r->next_order]].y_top < bottom)
        r->next_order++;
    /* Newly active pieces, in piece order, merged into the kept list. */
    cs_index *fresh = ws->scratch;
    for (uint32_t i = first_new; i < r->next_order; i++) {
        cs_index p = ws->order[i];
        if (ws->pieces[p].y_bot > top) {
            uint32_t j = added++;
            while (j > 0 && fresh[j - 1] > p) {
                fresh[j] = fresh[j - 1];
                j--;
            }
            fresh[j] = p;
        }
    }
    if (added) {
        uint32_t i = kept, j = added, k = kept + added;
        while (j > 0) {
            if (i > 0 && ws->active[i - 1] > fresh[j - 1])
                ws->active[--k] = ws->active[--i];
            else
                ws->active[--k] = fresh[--j];
        }
    }
    r->active_count = kept + added;
    r->next_line = y + 1;
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

void cs__line_stack(cs_renderer *r, int y)
{
    cs_workspace *ws = r->ws;
    uint32_t width = (uint32_t)r->vw;
    update_active(r, y);
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
    cel_ranges ranges;
    ranges.n = 0;
    uint32_t current_cel = UINT32_MAX;
    bool cel_hides = false;
    bool cel_folded = false; /* a region of the current cel was folded on this line */
    while (i < r->active_count) {
        uint32_t reg = ws->pieces[ws->active[i]].region;
        uint32_t j = i + 1;
        while (j < r->active_count && ws->pieces[ws->active[j]].region == reg)
            j++;
        uint32_t cel = ws->region_cel[reg];
        if (cel != current_cel) {
            composite_ranges(r, &ranges, cel_hides);
            cel_hides = false;
            cel_folded = false;
            if (cache_pending && cel >= cache_end) {
                cs__cache_composite(r, y);
                cache_pending = false;
            }
            current_cel = cel;
            /* Front to back: once the whole line is opaque nothing behind shows. */
            if (r->record && r->opaque_px >= width)
                break;
        }
        if (!region_hidden(r, &ws->active[i], j - i)) {
            int32_t lo, hi;
            region_coverage(r, reg, &ws->active[i], j - i, y, &lo, &hi);
            if (lo < hi) {
                /* A cel's only region on the line goes straight into the
                 * stack; otherwise the cel's regions are summed first. */
                bool alone = ranges.n == 0 && !cel_folded &&
                             (j == r->active_count ||
                              ws->region_cel[ws->pieces[ws->active[j]].region] != cel);
                fold_region(r, reg, y, lo, hi, alone);
                if (!alone) {
                    ranges_add(&ranges, lo, hi);
                    cel_hides = cel_hides || region_may_hide(r, reg);
                }
                cel_folded = true;
            }
        }
        i = j;
    }
    composite_ranges(r, &ranges, cel_hides);
    if (cache_pending)
        cs__cache_composite(r, y);
}

/*
 * Turns the stack of each run into its pixel, E + T L clamped to [0, 1]
 * (decoded to linear light under sRGB blending), in place in stack_E, and
 * joins neighbouring runs whose pixels came out equal.
 */
static CS__SPECIALISE void finish_line_as(cs_renderer *r, bool grey)
{
    cs_workspace *ws = r->ws;
    uint32_t width = (uint32_t)r->vw;
    float L0 = r->behind[0], L1 = r->behind[1], L2 = r->behind[2];
    bool srgb = r->opts.blend == CS_BLEND_SRGB;
    uint32_t prev = UINT32_MAX;
    for (uint32_t s = 0; s < width;) {
        float *E = &ws->stack_E[3 * s], T[3];
        cs__run_T(ws, grey, s, T);
        E[0] = cs__clampf(E[0] + T[0] * L0, 0.0f, 1.0f);
        E[1] = cs__clampf(E[1] + T[1] * L1, 0.0f, 1.0f);
        E[2] = cs__clampf(E[2] + T[2] * L2, 0.0f, 1.0f);
        /* sRGB blending composited encoded values; hand back linear light. */
        if (srgb)
            for (int ch = 0; ch < 3; ch++)
                E[ch] = cs_srgb_decode(E[ch]);
        uint32_t e = ws->run_end[s];
        if (prev != UINT32_MAX) {
            const float *P = &ws->stack_E[3 * prev];
            if (P[0] == E[0] && P[1] == E[1] && P[2] == E[2]) {
                ws->run_end[prev] = (uint16_t)e; /* same pixels: one run */
                s = e;
                continue;
            }
        }
        prev = s;
        s = e;
    }
}

static void finish_line(cs_renderer *r)
{
    if (CS_CFG_GREY && r->grey)
        finish_line_as(r, true);
    else
        finish_line_as(r, false);
}

cs_status cs_render_line_runs(cs_renderer *r, int y)
{
    if (!r || !r->ws || y < r->vy || y - r->vy >= r->vh)
        return CS_ERR_ARG;
    cs__line_stack(r, y);
    finish_line(r);
    return CS_OK;
}

int cs_line_run(const cs_renderer *r, int x, float rgb_linear[3])
{
    const cs_workspace *ws = r->ws;
    for (int ch = 0; ch < 3; ch++)
        rgb_linear[ch] = ws->stack_E[3 * x + ch];
    return ws->run_end[x];
}

void cs_line_pixels(const cs_renderer *r, cs_pixfmt fmt, uint8_t *out)
{
    const cs_workspace *ws = r->ws;
    cs__pixfmt_runs(fmt, ws->stack_E, ws->run_end, (uint32_t)r->vw, out);
}

const uint8_t *cs_line_pixels_scratch(cs_renderer *r, cs_pixfmt fmt)
{
    /* A cel value is read only where the line has set `used`, after it
     * wrote the value: between lines the memory is free. 12 bytes a pixel
     * hold any format. */
    uint8_t *out = (uint8_t *)(void *)r->ws->cel_E;
    cs_line_pixels(r, fmt, out);
    return out;
}

cs_status cs_render_line(cs_renderer *r, int y, float *rgb_linear)
{
    if (!rgb_linear)
        return CS_ERR_ARG;
    cs_status st = cs_render_line_runs(r, y);
    if (st != CS_OK)
        return st;
    const cs_workspace *ws = r->ws;
    uint32_t width = (uint32_t)r->vw;
    for (uint32_t s = 0; s < width;) {
        uint32_t e = ws->run_end[s];
        float c0 = ws->stack_E[3 * s], c1 = ws->stack_E[3 * s + 1], c2 = ws->stack_E[3 * s + 2];
        for (uint32_t x = s; x < e; x++) {
            rgb_linear[3 * x] = c0;
            rgb_linear[3 * x + 1] = c1;
            rgb_linear[3 * x + 2] = c2;
        }
        s = e;
    }
    return CS_OK;
}

cs_status cs_render_line_px(cs_renderer *r, int y, cs_pixfmt fmt, uint8_t *out)
{
    if (!out)
        return CS_ERR_ARG;
    cs_status st = cs_render_line_runs(r, y);
    if (st == CS_OK)
        cs_line_pixels(r, fmt, out);
    return st;
}

cs_error cs_frame_error(const cs_renderer *r)
{
    return r->sticky;
}

cs_status cs_render_frame(cs_renderer *r, float *line, cs_line_sink sink, void *user)
{
    if (!r || !line || !sink)
        return CS_ERR_ARG;
    for (int y = r->vy; y < r->vy + r->vh; y++) {
        cs_status st = cs_render_line(r, y, line);
        if (st == CS_OK)
            st = sink(user, y - r->vy, line, r->vw);
        if (st != CS_OK)
            return st;
    }
    return r->sticky.status;
}
