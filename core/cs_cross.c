/*
 * cs_cross.c - the crossings of one line: which pieces are active, and where
 *
 * they meet each sample scanline. Stage 3 of a frame; spans and coverage
 * (cs_coverage.c) take the sorted crossings from here.
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
 */
#include "cs_runs.h"

#if defined(__AVX2__) && defined(__BMI2__) && defined(__GNUC__) && defined(__x86_64__)
typedef int32_t v8i __attribute__((vector_size(32)));
typedef float v8f __attribute__((vector_size(32)));
typedef int32_t v8i_u __attribute__((vector_size(32), aligned(4), may_alias));

/*
 * The active pieces that still reach below `top`, kept in order at the
 * list's start, eight at a time (the x86-64-v3 build, 4-byte indices):
 * the eight pieces' y_bot by one gather, the compare as a mask, and the
 * kept indices packed left by one permute whose lane order pdep and pext
 * make from the mask. Each store of eight lanes lies at or before the
 * entries not yet read. ~2.5 instructions a piece where the scalar loop
 * (below) takes ~9, ~90 k pieces a Many-blobs frame. Returns how many of
 * the first n8 (a multiple of 8) are kept.
 */
static uint32_t keep_active8(cs_workspace *ws, float top, uint32_t n8)
{
    cs_index *a = ws->active;
    const float *y_bot = &ws->pieces[0].y_bot;
    const v8i stride = {6, 6, 6, 6, 6, 6, 6, 6}; /* sizeof (cs_piece) / 4, checked below */
    const v8f tops = {top, top, top, top, top, top, top, top};
    uint32_t kept = 0;
    for (uint32_t i = 0; i < n8; i += 8) {
        v8i p = *(const v8i_u *)&a[i];
        v8i at = p * stride;
        v8f yb, m;
        __asm__("vpcmpeqd %1, %1, %1\n\tvgatherdps %1, (%2, %3, 4), %0"
                : "=&x"(yb), "=&x"(m)
                : "r"(y_bot), "x"(at));
        uint32_t mask = (uint32_t)__builtin_ia32_movmskps256((v8f)(yb > tops));
        uint64_t bytes = __builtin_ia32_pdep_di(mask, 0x0101010101010101ull) * 0xFFu;
        uint64_t lanes = __builtin_ia32_pext_di(0x0706050403020100ull, bytes);
        v8i order; /* the bytes of `lanes` widened to lanes (GCC builds it byte by byte) */
        __asm__("vmovq %1, %x0\n\tvpmovzxbd %x0, %0" : "=x"(order) : "r"(lanes));
        *(v8i_u *)&a[kept] = __builtin_ia32_permvarsi256(p, order);
        kept += (uint32_t)__builtin_popcount(mask);
    }
    return kept;
}

/*
 * The merge of newly active pieces (cs__line_active) moves the kept
 * entries above the next new one up by `gap` places; here eight at a time
 * while all eight lie above it (the list is in order, so the lowest of
 * them tells), one load and one store of eight lanes, which read the
 * eight before writing any, then the rest by one blend. The kept list's
 * tail above the first new piece moves, ~150 entries a line of a
 * Many-blobs frame that adds any. Returns where the entries still to move
 * end: with eight or more below, at the last entry not above f.
 */
static uint32_t shift_active8(cs_index *a, uint32_t i, uint32_t gap, cs_index f)
{
    while (i >= 8u && a[i - 8u] > f) {
        *(v8i_u *)&a[i - 8u + gap] = *(const v8i_u *)&a[i - 8u];
        i -= 8u;
    }
    /* Then those of the eight below i that lie above f, blended into what
     * their places hold (the places of the others keep it), with no branch
     * per entry: their number went by the data. Indices are below 2^31, so
     * a signed compare orders them. */
    if (i >= 8u) {
        v8i v = *(const v8i_u *)&a[i - 8u], d = *(const v8i_u *)&a[i - 8u + gap];
        v8i fs = {(int32_t)f, (int32_t)f, (int32_t)f, (int32_t)f,
                  (int32_t)f, (int32_t)f, (int32_t)f, (int32_t)f};
        v8i m = v > fs;
        *(v8i_u *)&a[i - 8u + gap] = (v & m) | (d & ~m);
        i -= (uint32_t)__builtin_popcount((uint32_t)__builtin_ia32_movmskps256((v8f)m));
    }
    return i;
}
#define KEEP8 (sizeof(cs_index) == 4 && sizeof(cs_piece) == 24)
#else
#define KEEP8 0
#define keep_active8(ws, top, n8) 0u
#define shift_active8(a, i, gap, f) (i)
#endif

/* Moves the active list to line y: adds pieces starting above y+1, drops
 * those ending at or above y. The list stays in piece (scene) order. */
void cs__line_active(cs_renderer *r, int y)
{
    cs_workspace *ws = r->ws;
    if (y < r->next_line) { /* lines asked out of order: start over */
        r->active_count = 0;
        r->next_order = 0;
    }
    float top = (float)y, bottom = (float)(y + 1);
    /* Written whether kept or not, counted if kept: whether a piece ends
     * goes by the data, and as a branch it was mispredicted ~20 k times a
     * Many-blobs frame. */
    uint32_t n8 = KEEP8 ? r->active_count & ~7u : 0u;
    uint32_t kept = n8 ? keep_active8(ws, top, n8) : 0u;
    for (uint32_t i = n8; i < r->active_count; i++) {
        cs_index p = ws->active[i];
        ws->active[kept] = p;
        kept += ws->pieces[p].y_bot > top;
    }
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
            if (KEEP8) {
                i = shift_active8(ws->active, i, j, fresh[j - 1]);
                k = i + j;
            }
            if (i > 0 && ws->active[i - 1] > fresh[j - 1])
                ws->active[--k] = ws->active[--i];
            else
                ws->active[--k] = fresh[--j];
        }
    }
    r->active_count = kept + added;
    r->next_line = y + 1;
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
int32_t cs__crossings_at(cs_renderer *r, const cs_index *act, cs_index *ord, uint32_t *idle,
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
