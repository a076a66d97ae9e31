/*
 * cs_coverage.c - spans and coverage: one region's crossings become spans
 *
 * and the spans its per-pixel coverage. Stage 4 of a frame, for the
 * sampled AA modes (exact area comes from cs_exact.c into the same
 * accumulators); compositing (cs_composite.c) folds what is left here.
 *
 * Pieces are kept in scene order, which groups them by region and regions
 * by cel, front-most first. For one region the crossings of a scanline,
 * sorted by x, become spans under its fill rule, and each span adds its
 * exact horizontal coverage to two per-pixel accumulators in the manner of
 * FreeType's cells: `area` holds the partial coverage of the pixels where a
 * span starts or ends, `cover` holds +w/-w deltas whose running sum is the
 * coverage of the pixels fully inside. A span costs O(1) however long it
 * is, and the entries it wrote are marked (ws->touched).
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
 * area/cover accumulators over [*lo, *hi), in the sampled modes (exact
 * area is cs__exact_region's, which cs__line_stack calls itself; here,
 * in a build without it, exact mode has no samples and covers nothing).
 * Every anti-aliasing mode fills the same accumulators, so everything
 * after this step is mode-blind.
 */
void cs__region_coverage(cs_renderer *r, uint32_t reg, const cs_index *act, uint32_t n, int y,
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
    /* Every piece waits for its first crossing: no root carries over from
     * another line. ws->scratch is free once cs__line_active is done. */
    cs_index *ord = ws->scratch;
    uint32_t idle = 0, live = 0;
    for (int k = 0; k < samples; k++) {
        if (k == 0)
            for (idle = 0; idle < n; idle++)
                ord[idle] = (cs_index)idle;
        int32_t count = cs__crossings_at(r, act, ord, &idle, live, y, k, samples);
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
