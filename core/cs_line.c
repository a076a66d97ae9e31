/*
 * cs_line.c - one display line: crossings, spans, coverage, compositing.
 *
 * For each line the active monotone pieces (those whose y range meets the
 * pixel row) are intersected afresh with each sample scanline: nothing is
 * carried from line to line but the list of which pieces are active, so
 * errors cannot accumulate and rows off screen cost nothing.
 *
 * Pieces are kept in scene order, which groups them by region and regions
 * by cel, front-most first. For one region the crossings of a scanline,
 * sorted by x, become spans under its fill rule, and each span adds its
 * exact horizontal coverage to two per-pixel accumulators in the manner of
 * FreeType's cells: `area` holds the partial coverage of the pixels where a
 * span starts or ends, `cover` holds +w/-w deltas whose running sum is the
 * coverage of the pixels fully inside. A span costs O(1) however long it
 * is, and the region costs one pass over the pixels it touched.
 *
 * Coverage c turns a region's paint map (E, T) into (c E, 1 - c (1 - T)).
 * Within a cel the regions' maps are summed, so two regions sharing an
 * edge leave no seam; each region may only claim the coverage the regions
 * in front of it left (`used`), so a region hidden behind another in the
 * same cel stays hidden. The cel then joins the stack front to back:
 * E += T_stack E_cel, T_stack *= T_cel, and the pixel is E + T_stack L.
 */
#include "cs_internal.h"

/* Adds span [xa, xb) with weight w to the accumulators (xa, xb in [0, W]). */
static void add_span(float *area, float *cover, float xa, float xb, float w)
{
    int32_t ia = cs__floori(xa), ib = cs__floori(xb);
    if (ia == ib) {
        area[ia] += w * (xb - xa);
        return;
    }
    area[ia] += w * ((float)(ia + 1) - xa);
    cover[ia + 1] += w;
    cover[ib] -= w;
    area[ib] += w * (xb - (float)ib);
}

/* Pixel-centre sampling: pixels i with xa <= i + 0.5 < xb. */
static void add_span_centres(float *cover, float xa, float xb)
{
    int32_t i0 = cs__floori(xa - 0.5f);
    if ((float)i0 + 0.5f < xa)
        i0++;
    int32_t i1 = cs__floori(xb - 0.5f);
    if ((float)i1 + 0.5f < xb)
        i1++;
    if (i1 > i0) {
        cover[i0] += 1.0f;
        cover[i1] -= 1.0f;
    }
}

/* Shell sort by x: no scratch memory, fast on the short lists lines give. */
static void sort_crossings(cs_crossing *c, uint32_t n)
{
    static const uint32_t gaps[] = {701, 301, 132, 57, 23, 10, 4, 1};
    for (unsigned g = 0; g < sizeof gaps / sizeof gaps[0]; g++) {
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

/*
 * Crossings of the active pieces act[0..n) with scanline ys, sorted by x
 * and clamped to [0, width]. Returns the count, or -1 if they do not fit.
 */
static int32_t crossings_at(cs_renderer *r, const uint32_t *act, uint32_t n, float ys)
{
    cs_workspace *ws = r->ws;
    float width = (float)r->opts.width;
    uint32_t count = 0;
    for (uint32_t i = 0; i < n; i++) {
        const cs_piece *pc = &ws->pieces[act[i]];
        if (!(pc->y_top <= ys && ys < pc->y_bot))
            continue;
        if (count >= CS_CFG_MAX_CROSSINGS)
            return -1;
        const cs_segment *s = &ws->segments[pc->segment];
        float u = cs__solve_level(s->y, s->w, s->degree, ys, pc->u0, pc->u1);
        float x = cs__poly_eval(s->x, s->degree, u) / cs__poly_eval(s->w, s->degree, u);
        ws->crossings[count].x = cs__clampf(x, 0.0f, width);
        ws->crossings[count].dir = pc->dir;
        ws->crossings[count].operand = pc->operand;
        count++;
    }
    sort_crossings(ws->crossings, count);
    return (int32_t)count;
}

/* Turns sorted crossings into spans under the fill rule and accumulates. */
static void accumulate_spans(cs_renderer *r, uint32_t count, const cs_region *region, float weight,
                             bool centres, int32_t *lo, int32_t *hi)
{
    cs_workspace *ws = r->ws;
    int32_t winding[CS_CFG_MAX_OPERANDS];
    for (int k = 0; k < CS_CFG_MAX_OPERANDS; k++) /* a loop: `= {0}` may call memset */
        winding[k] = 0;
    for (uint32_t i = 0; i + 1 < count; i++) {
        winding[ws->crossings[i].operand] += ws->crossings[i].dir;
        bool inside = cs__region_inside(region, winding);
        float xa = ws->crossings[i].x, xb = ws->crossings[i + 1].x;
        if (!inside || !(xb > xa))
            continue;
        if (centres)
            add_span_centres(ws->cover, xa, xb);
        else
            add_span(ws->area, ws->cover, xa, xb, weight);
        int32_t a = cs__floori(xa), b = cs__floori(xb) + 1;
        if (a < *lo)
            *lo = a;
        if (b > *hi)
            *hi = b;
    }
}

/*
 * Coverage of region `reg` on line y from its active pieces, folded into the
 * cel accumulators. [*cel_lo, *cel_hi) grows to what the cel touched.
 */
static void render_region(cs_renderer *r, uint32_t reg, const uint32_t *act, uint32_t n, int y,
                          int32_t *cel_lo, int32_t *cel_hi)
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
    if (r->opts.aa == CS_AA_EXACT) {
        cs_status st = cs__exact_region(r, region, act, n, y, &lo, &hi);
        if (st != CS_OK && r->sticky.status == CS_OK) {
            const cs_cel *cel = &r->scene->cels[ws->region_cel[reg]];
            cs__error(&r->sticky, st, ws->region_cel[reg],
                      (int32_t)(reg - cel->first_region), -1, y);
        }
    }
    for (int k = 0; k < samples; k++) {
        float ys = (float)y + ((float)k + 0.5f) * weight;
        int32_t count = crossings_at(r, act, n, ys);
        if (count < 0) {
            if (r->sticky.status == CS_OK) {
                const cs_cel *cel = &r->scene->cels[ws->region_cel[reg]];
                cs__error(&r->sticky, CS_ERR_CAP_CROSSINGS, ws->region_cel[reg],
                          (int32_t)(reg - cel->first_region), -1, y);
            }
            continue; /* the region is left out of this sample: visible, never unsafe */
        }
        accumulate_spans(r, (uint32_t)count, region, weight, centres, &lo, &hi);
    }
    if (lo >= hi)
        return;
    if (hi > r->opts.width)
        hi = r->opts.width;
    const float *E = ws->region_E[reg], *T = ws->region_T[reg];
    float A[3] = {1.0f - T[0], 1.0f - T[1], 1.0f - T[2]};
    float run = 0.0f;
    for (int32_t x = lo; x < hi; x++) {
        run += ws->cover[x];
        float c = cs__clampf(ws->area[x] + run, 0.0f, 1.0f);
        ws->area[x] = 0.0f;
        ws->cover[x] = 0.0f;
        float room = 1.0f - ws->used[x];
        if (c > room)
            c = room;
        if (!(c > 0.0f))
            continue;
        ws->used[x] += c;
        float *ce = &ws->cel_E[3 * x], *ca = &ws->cel_A[3 * x];
        for (int ch = 0; ch < 3; ch++) {
            ce[ch] += c * E[ch];
            ca[ch] += c * A[ch];
        }
    }
    /* Deltas at and just past the right end may remain; they sum to zero. */
    ws->area[hi] = ws->cover[hi] = 0.0f;
    ws->area[hi + 1] = ws->cover[hi + 1] = 0.0f;
    if (lo < *cel_lo)
        *cel_lo = lo;
    if (hi > *cel_hi)
        *cel_hi = hi;
}

/* Composites the accumulated cel behind the stack and clears it. */
static void composite_cel(cs_workspace *ws, int32_t lo, int32_t hi)
{
    for (int32_t x = lo; x < hi; x++) {
        float *ce = &ws->cel_E[3 * x], *ca = &ws->cel_A[3 * x];
        float *se = &ws->stack_E[3 * x], *st = &ws->stack_T[3 * x];
        for (int ch = 0; ch < 3; ch++) {
            se[ch] += st[ch] * ce[ch];
            st[ch] *= 1.0f - ca[ch];
            ce[ch] = 0.0f;
            ca[ch] = 0.0f;
        }
        ws->used[x] = 0.0f;
    }
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
    uint32_t *fresh = ws->scratch;
    for (uint32_t i = first_new; i < r->next_order; i++) {
        uint32_t p = ws->order[i];
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

cs_status cs_render_line(cs_renderer *r, int y, float *rgb_linear)
{
    if (!r || !r->ws || !rgb_linear || y < 0 || y >= r->opts.height)
        return CS_ERR_ARG;
    cs_workspace *ws = r->ws;
    int width = r->opts.width;
    update_active(r, y);
    for (int i = 0; i < 3 * width; i++) {
        ws->stack_E[i] = 0.0f;
        ws->stack_T[i] = 1.0f;
    }
    uint32_t i = 0;
    int32_t cel_lo = INT32_MAX, cel_hi = INT32_MIN;
    uint32_t current_cel = UINT32_MAX;
    while (i < r->active_count) {
        uint32_t reg = ws->pieces[ws->active[i]].region;
        uint32_t j = i + 1;
        while (j < r->active_count && ws->pieces[ws->active[j]].region == reg)
            j++;
        uint32_t cel = ws->region_cel[reg];
        if (cel != current_cel && cel_lo < cel_hi) {
            composite_cel(ws, cel_lo, cel_hi);
            cel_lo = INT32_MAX;
            cel_hi = INT32_MIN;
        }
        current_cel = cel;
        render_region(r, reg, &ws->active[i], j - i, y, &cel_lo, &cel_hi);
        i = j;
    }
    if (cel_lo < cel_hi)
        composite_cel(ws, cel_lo, cel_hi);
    for (int x = 0; x < 3 * width; x++) {
        float v = ws->stack_E[x] + ws->stack_T[x] * r->behind[x % 3];
        rgb_linear[x] = cs__clampf(v, 0.0f, 1.0f);
    }
    return CS_OK;
}

cs_status cs_render_frame(cs_renderer *r, float *line, cs_line_sink sink, void *user)
{
    if (!r || !line || !sink)
        return CS_ERR_ARG;
    for (int y = 0; y < r->opts.height; y++) {
        cs_status st = cs_render_line(r, y, line);
        if (st == CS_OK)
            st = sink(user, y, line, r->opts.width);
        if (st != CS_OK)
            return st;
    }
    return r->sticky.status;
}
