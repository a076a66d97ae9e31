/*
 * cs_internal.h - helpers shared by the core's files, not part of the API.
 *
 * The core may not call libm, so the handful of float operations it needs
 * live here as inline functions whose results are the same on every IEEE-754
 * target (no contraction, no library calls). Private names use the cs__
 * prefix, public ones cs_.
 */
#ifndef CS_INTERNAL_H
#define CS_INTERNAL_H

#include <float.h>

#include "celscan_private.h"

/* Identical bytes on every target need every float operation rounded to
 * float as it happens: x87 code (i386 without SSE) keeps excess precision
 * in registers, so results would depend on register allocation. */
#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD != 0 && FLT_EVAL_METHOD != -1
#error "celscan core needs FLT_EVAL_METHOD == 0 (SSE, VFP, RISC-V F; not x87)"
#endif

static inline float cs__absf(float v) { return v < 0.0f ? -v : v; }
/*
 * min and max as `a < b ? a : b` and `a > b ? a : b`: on every target the
 * same result for NaN and for -0 against +0 (the second operand). On
 * x86-64 the instructions minss/maxss compute exactly these, but GCC
 * compiles the conditional as a compare and a branch where it expects the
 * branch to go one way (the profile-guided build does so in most clamps),
 * and in a line the clamps bite or not by the data: ~140 k mispredicted
 * branches of a Many-blobs exact frame were these. So x86-64 states the
 * instruction (VEX-encoded where the build has AVX, so as not to mix
 * encodings).
 */
#if defined(__GNUC__) && defined(__x86_64__)
#if defined(__AVX__)
#define CS__MINMAX_X86(op, r, a, b) \
    __asm__("v" op " %2, %1, %0" : "=x"(r) : "x"(a), "xm"(b))
#else
#define CS__MINMAX_X86(op, r, a, b) \
    __asm__(op " %2, %0" : "=x"(r) : "0"(a), "xm"(b))
#endif
static inline float cs__minf(float a, float b)
{
    float r;
    CS__MINMAX_X86("minss", r, a, b);
    return r;
}
static inline float cs__maxf(float a, float b)
{
    float r;
    CS__MINMAX_X86("maxss", r, a, b);
    return r;
}
#else
static inline float cs__minf(float a, float b) { return a < b ? a : b; }
static inline float cs__maxf(float a, float b) { return a > b ? a : b; }
#endif
/*
 * Copies: a struct assignment may become a memcpy call, which the
 * freestanding core must not make (tools/check_core_symbols.sh), so a copy of
 * the store's structs is this one byte loop. It runs forward, so it also
 * shifts an array down over itself (dst before src). CS__COPY_N copies n
 * elements of one type (the unevaluated comparison makes a mix of types a
 * compile-time warning); CS__COPY one.
 */
void cs__copy_bytes(void *dst, const void *src, size_t bytes);
#define CS__COPY_N(dst, src, n) \
    cs__copy_bytes((dst), (src), (size_t)(n) * sizeof *(dst) + 0u * sizeof((dst) == (src)))
#define CS__COPY(dst, src) CS__COPY_N(dst, src, 1u)

static inline void cs__copy3(float *dst, const float *src)
{
    dst[0] = src[0];
    dst[1] = src[1];
    dst[2] = src[2];
}

/* For a function written once for two cases told apart by a constant
 * argument (a grey or a coloured frame, cs_renderer.grey): forced inline
 * into one wrapper per case, each case is compiled without the test.
 * Without the grey path there is one case, and the compiler may choose. */
#if defined(__GNUC__) && CS_CFG_GREY
#define CS__SPECIALISE inline __attribute__((always_inline))
#else
#define CS__SPECIALISE inline
#endif

/* For a hot function written into its hottest caller, where the compiler
 * would call it (the call and the registers it saves measured). */
#if defined(__GNUC__)
#define CS__HOT_INLINE inline __attribute__((always_inline))
#else
#define CS__HOT_INLINE inline
#endif

/* A branch that is rarely taken (a mode few frames use), for the code layout. */
#if defined(__GNUC__)
#define CS__UNLIKELY(c) __builtin_expect(!!(c), 0)
#else
#define CS__UNLIKELY(c) (c)
#endif

/* For a small helper that the line code calls per crossing or per Newton
 * step: forced inline where the file is compiled for speed, left to the
 * compiler where it is compiled for size (-Os, __OPTIMIZE_SIZE__: the
 * boards' frame preparation and stream code). On a board the line code's
 * inline limit (mk/firmware.mk) kept cs__horner and cs__horner_d out of
 * line: inlined, the board demo frame takes 0.32 M fewer instructions for
 * 0.7 KB of flash (firmware/README.md). The same operations either way. */
#if defined(__GNUC__) && !defined(__OPTIMIZE_SIZE__)
#define CS__LINE_INLINE inline __attribute__((always_inline))
#else
#define CS__LINE_INLINE inline
#endif

/* Whether the three channels of v hold the same number: a grey
 * transmittance, which a frame may keep in one channel (cs_renderer.grey). */
static inline bool cs__grey3(const float *v)
{
    return v[0] == v[1] && v[1] == v[2];
}

/* A quiet NaN, as a constant (no libm). */
#define CS__NAN (__builtin_nanf(""))

/* Clamps v to [lo, hi] (lo <= hi); NaN becomes lo, so no NaN reaches an
 * integer cast. Written as max then min, each the `a > b ? a : b` that
 * SSE's maxss/minss compute, so that it compiles without branches: clamps
 * sit in the inner loops, and whether they bite is data, not a pattern. */
static inline float cs__clampf(float v, float lo, float hi)
{
    return cs__minf(cs__maxf(v, lo), hi);
}

/* True for every float that is neither NaN nor infinite. */
static inline bool cs__finite(float v)
{
    return v == v && v - v == 0.0f;
}

/* floor() for |v| < 2^31; the core only asks it of device coordinates. */
static inline int32_t cs__floori(float v)
{
    int32_t i = (int32_t)v;
    return ((float)i > v) ? i - 1 : i;
}

/* Correctly rounded square root: one instruction with -fno-math-errno on
 * SSE, VFP and RISC-V F, so the result is identical on every target. */
static inline float cs__sqrtf(float v) { return __builtin_sqrtf(v); }

static inline void cs__error(cs_error *err, cs_status st, int32_t cel, int32_t region,
                             int32_t contour, int32_t item)
{
    if (err) {
        err->status = st;
        err->cel = cel;
        err->region = region;
        err->contour = contour;
        err->item = item;
    }
}

/* Validation shared by the builder (cs_scene.c), editing (cs_edit.c) and
 * animation keys (cs_anim.c), so every path into the store checks alike. */
cs_status cs__check_canvas(float canvas_w, float canvas_h);
cs_status cs__check_lights(const float *front, const float *back); /* either may be NULL */
cs_status cs__check_colour(const float *rgb);                    /* finite, in 0..1 */
cs_status cs__check_affine(const cs_affine *m, int32_t *item);
cs_status cs__check_paint(const cs_paint *p);
cs_status cs__check_point(const cs_point *p);
cs_status cs__check_contour(int degree, int count, const cs_point *pts, const float *intervals,
                            int32_t *item);

/* Removes the tracks whose target of `kind`'s family lies in [first, first+count)
 * and renumbers the later targets down by `count` (cs_anim.c). */
void cs__tracks_remove_range(cs_scene *scene, int family, uint32_t first, uint32_t count);
/* Track families: what a target index counts. */
enum { CS__FAM_CEL = 0, CS__FAM_REGION = 1, CS__FAM_CONTOUR = 2, CS__FAM_STACK = 3 };
int cs__track_family(int kind);
/* Re-sorts the tracks by (kind, target) after targets were renumbered. */
void cs__tracks_sort(cs_scene *scene);

/* The track of (kind, target), or NULL (binary search; the tracks are sorted). */
const cs_track *cs__track_find(const cs_scene *scene, int kind, uint32_t target);
/*
 * Where time t falls among a track's keys: the value is
 * (1-s) * key[i0] + s * key[i1], with i0 == i1 (and s = 0) outside the keys.
 */
void cs__track_locate(const cs_scene *scene, const cs_track *tr, float t, uint32_t *i0,
                      uint32_t *i1, float *s);
/* Floats of easing before each key's values on track `tr` (0 or CS_EASE_CUBIC_FLOATS). */
static inline uint32_t cs__track_lead(const cs_track *tr)
{
    return tr->ease == CS_EASE_CUBIC ? CS_EASE_CUBIC_FLOATS : 0u;
}
/* A TRS key (CS_TRACK_TRS) as the affine map it stands for (cs_anim.c). */
void cs__trs_affine(const float *v, float m[6]);
/* Track `tr` sampled at time t into out[0 .. width - lead) (cs_frame.c). */
void cs__track_sample(const cs_scene *scene, const cs_track *tr, float t, float *out);
/* Cel ci's world transform (into m) and opacity at time t, its groups' included. */
float cs__cel_world(const cs_scene *scene, uint32_t ci, float t, float *m);
/* Region ri's paint at time t under opacity: its own, or one made in *animated. */
const cs_paint *cs__region_paint(const cs_scene *scene, uint32_t ri, float t, float opacity,
                                 cs_paint *animated);
/* (1-s) a + s b: exactly a at s = 0 and b at s = 1, between them (to rounding) otherwise. */
static inline float cs__lerp(float a, float b, float s) { return (1.0f - s) * a + s * b; }

/* Polynomials of degree <= 4 in power basis, c[0] + c[1] u + ... */
float cs__poly_eval(const float *c, int degree, float u);

/*
 * The same Horner evaluation unrolled per degree, for the inner loops: the
 * loop form spends as many instructions on its counter as on arithmetic.
 * The operations and their order are those of cs__poly_eval, so the result
 * is the same float.
 */
static CS__LINE_INLINE float cs__horner(const float *c, int degree, float u)
{
    switch (degree) {
    case 1:
        return c[1] * u + c[0];
    case 2:
        return (c[2] * u + c[1]) * u + c[0];
    case 3:
        return ((c[3] * u + c[2]) * u + c[1]) * u + c[0];
    default:
        return cs__poly_eval(c, degree, u);
    }
}

/* The point of segment s at u: its origin plus X/W and Y/W (cs_segment). */
static inline float cs__segment_x(const cs_segment *s, float u)
{
    return (float)s->ox + cs__horner(s->x, s->degree, u) / cs__horner(s->w, s->degree, u);
}

static inline float cs__segment_y(const cs_segment *s, float u)
{
    return (float)s->oy + cs__horner(s->y, s->degree, u) / cs__horner(s->w, s->degree, u);
}

/* Value of c at u, and its derivative in *d, by Horner's scheme (unrolled). */
static CS__LINE_INLINE float cs__horner_d(const float *c, int degree, float u, float *d)
{
    switch (degree) {
    case 1:
        *d = c[1];
        return c[1] * u + c[0];
    case 2:
        *d = c[2] * u + (c[2] * u + c[1]);
        return (c[2] * u + c[1]) * u + c[0];
    case 3: {
        float v2 = c[3] * u + c[2];
        float v1 = v2 * u + c[1];
        *d = (c[3] * u + v2) * u + v1;
        return v1 * u + c[0];
    }
    default: {
        float v = c[degree], dv = 0.0f;
        for (int i = degree - 1; i >= 0; i--) {
            dv = dv * u + v;
            v = v * u + c[i];
        }
        *d = dv;
        return v;
    }
    }
}

/*
 * Real roots of the polynomial c (degree <= 4) strictly inside (lo, hi), in
 * increasing order, written to roots[]; returns how many (at most degree).
 * Roots are isolated between the roots of the derivative and refined by a
 * bounded bracketed solve, so the cost is fixed and no recursion follows
 * the input.
 */
int cs__poly_roots(const float *c, int degree, float lo, float hi, float *roots);

/*
 * Parameters in (lo, hi) where the rational coordinate c(u)/w(u) turns
 * (c and w of `degree`): roots of c'w - cw', whose u^(2p-1) coefficient
 * cancels analytically and is dropped rather than left to rounding. At most
 * 2*degree - 2 of them, in increasing order.
 */
int cs__turns(const float *c, const float *w, int degree, float lo, float hi, float *roots);

/*
 * Solves f(u) = 0 for u in [lo, hi] where f(lo) and f(hi) have opposite
 * signs (or one is zero), f given as num(u) - level*den(u) with num, den
 * polynomials of degree `degree`. Bounded Illinois iteration; returns the
 * end point with the smaller |f| if the signs do not bracket.
 */
float cs__solve_level(const float *num, const float *den, int degree, float level, float lo,
                      float hi);

/*
 * The same root on a monotone piece of y = num/den (`rising`: y grows with
 * u), found by Newton's iteration from `guess`, the root for a nearby level
 * (the previous sub-scanline of the same line). The result is
 * deterministic for given arguments; it may differ from cs__solve_level's
 * in the last bits. *slope receives d(num - level den)/du near the root
 * (0 when unknown), from which the caller can predict the next root:
 * du/dlevel = den(u) / slope. Inline, with cs__level_poly: it runs for
 * every crossing of every sub-scanline, where the call cost as much as a
 * Newton step.
 */
#define CS__NEWTON_MAX_ITER 8
#define CS__WARM_STEP_TOL 1.0e-5f

/* g = num - level den. */
static inline void cs__level_poly(const float *num, const float *den, int degree, float level,
                                  float *g)
{
    g[0] = num[0] - level * den[0];
    g[1] = num[1] - level * den[1];
    g[2] = degree >= 2 ? num[2] - level * den[2] : 0.0f;
    g[3] = degree >= 3 ? num[3] - level * den[3] : 0.0f;
}

/*
 * With W > 0, g(u) = W(u) (y(u) - level) has the sign of y(u) - level, so
 * on a monotone piece the side of the root is known from the sign of g at
 * any u, without evaluating the ends: for a rising piece g < 0 before the
 * root. Newton from the nearby root then needs no set-up at all; when it
 * does not settle inside the piece, the full bracketed solve decides.
 */
static inline float cs__solve_level_from(const float *num, const float *den, int degree,
                                         float level, float lo, float hi, float guess,
                                         bool rising, float *slope)
{
    float g[4];
    *slope = 0.0f;
    cs__level_poly(num, den, degree, level, g);
    if (degree == 1 || !(guess > lo && guess < hi))
        return cs__solve_level(num, den, degree, level, lo, hi);
    float a = lo, b = hi, u = guess;
    for (int it = 0; it < CS__NEWTON_MAX_ITER; it++) {
        float d, f = cs__horner_d(g, degree, u, &d);
        if (f == 0.0f) {
            *slope = d;
            return u;
        }
        if ((f < 0.0f) == rising)
            a = u;
        else
            b = u;
        float next = u - f / d;
        /* A step below u's last bit: converged. u may have just become an
         * end of the bracket, which the test below would take for a step
         * out of it, and hand a found root to the full solve. */
        if (next == u) {
            *slope = d;
            return u;
        }
        if (!(next > a && next < b))
            break;
        /* Newton leaves an error of about K s^2 after a step s (K = g''/2g'),
         * so a step of 1e-5 already lands within ~1e-10 K of the root. */
        if (cs__absf(next - u) <= CS__WARM_STEP_TOL) {
            *slope = d;
            return next;
        }
        u = next;
    }
    return cs__solve_level(num, den, degree, level, lo, hi);
}

/*
 * Converts one closed periodic NURBS contour to rational polynomial segments
 * in device space, each relative to its own origin (cs_segment; cs_nurbs.c),
 * one knot span at a time. Control points go through `to_device` first; a
 * transformed NURBS is still a NURBS with the same weights.
 * cs__contour_begin fails with CS_ERR_RANGE (and *bad_point set) if a
 * transformed point leaves the coordinate limit, and otherwise sets the
 * control points' device y range, which holds the whole curve (positive
 * weights: the convex hull property); then cs__contour_next
 * writes the next segment to *out, or returns false after the last. The
 * arrays and the map must outlive the iteration.
 */
/* cs__contour_iter is in celscan_private.h: the frame keeps it in the workspace
 * (cs_frame_data), off the stack. */
cs_status cs__contour_begin(cs__contour_iter *it, const cs_point *points, const float *intervals,
                            int count, int degree, const cs_affine *to_device, uint16_t region,
                            int32_t *bad_point);
bool cs__contour_next(cs__contour_iter *it, cs_segment *out);
/* Whether cs__contour_next has a segment left to give. */
bool cs__contour_more(const cs__contour_iter *it);

/* Fewest sub-scanlines for which crossings are interpolated (cs_cross.c):
 * below it the extra solves and slopes cost about what they save. */
#define CS__INTERP_MIN_SAMPLES 8

/* Capacities the storage formats rely on. */
_Static_assert(CS_CFG_MAX_CSG >= 1 && CS_CFG_MAX_CSG <= 32, "CSG bit stack holds 32 values");
_Static_assert(CS_CFG_MAX_OPERANDS >= 1 && CS_CFG_MAX_OPERANDS <= 127,
               "operand tokens are stored below 0x80");
_Static_assert(CS_CFG_MAX_STOPS >= 2 && CS_CFG_MAX_STOPS <= 255, "stop_count is a uint8_t");
_Static_assert(CS_CFG_MAX_FUNCS <= 65535, "regions refer to functions by uint16_t");
_Static_assert(CS_CFG_MAX_WIDTH <= 65535, "cache runs store x and length as uint16_t");

/* CSG operator tokens as stored in cs_region.csg. */
#define CS__CSG_OP 0x80u

static inline bool cs__fill(uint8_t rule, int32_t winding)
{
    return rule == CS_FILL_EVENODD ? (winding & 1) != 0 : winding != 0;
}

/*
 * Whether a point is inside `region`, given the winding number of each of
 * its operands (winding[0] only, unless the region combines operands). Every
 * coverage method asks this one question, so fill rules and CSG mean the
 * same thing in every anti-aliasing mode.
 *
 * A CSG region runs its RPN program on a stack of single bits kept in one
 * register (bit 0 is the top). cs_scene_set_region_csg proved the program
 * well formed (depth <= 32, one result, operands in range), so no check is
 * needed here. Every operator yields "outside" when both inputs are
 * outside, so a CSG region is never inside where none of its contours are:
 * its bounds are those of its contours.
 */
static inline bool cs__region_inside(const cs_region *region, const int32_t *winding)
{
    if (region->csg_len == 0)
        return cs__fill(region->fill_rule, winding[0]);
    uint32_t stack = 0;
    for (uint32_t i = 0; i < region->csg_len; i++) {
        uint32_t t = region->csg[i];
        if (t < CS__CSG_OP) {
            stack = (stack << 1) | (cs__fill(region->fill_rule, winding[t]) ? 1u : 0u);
            continue;
        }
        uint32_t b = stack & 1u, a = (stack >> 1) & 1u, v;
        switch (t & 0x7Fu) {
        case 1: v = a | b; break;          /* CS_CSG_UNION */
        case 2: v = a & b; break;          /* CS_CSG_INTERSECT */
        case 3: v = a & (b ^ 1u); break;   /* CS_CSG_DIFFERENCE */
        default: v = a ^ b; break;         /* CS_CSG_XOR */
        }
        stack = ((stack >> 2) << 1) | v;
    }
    return (stack & 1u) != 0;
}

/* sRGB encoding (0..1) of linear (i/1024)^2 (cs_srgb_table.c). */
extern const float cs__srgb_by_sqrt[1025];

/* Its entry i, and sRGB decoding (cs_srgb_decode): from the table, or on a
 * board short of flash from its compact form (CS_CFG_SRGB_COMPACT,
 * cs_srgb_compact.c), the same floats. */
float cs__srgb_compact_at(uint32_t i);
float cs__srgb_decode_compact(float encoded);
#if CS_CFG_SRGB_COMPACT
static inline float cs__srgb_at(uint32_t i) { return cs__srgb_compact_at(i); }
static inline float cs__srgb_decode(float encoded) { return cs__srgb_decode_compact(encoded); }
#else
static inline float cs__srgb_at(uint32_t i) { return cs__srgb_by_sqrt[i]; }
static inline float cs__srgb_decode(float encoded) { return cs_srgb_decode(encoded); }
#endif

/* The cell of a strictly rising table, read through `at`, that holds v:
 * the i in [lo, hi) with at(i) <= v < at(i + 1), given at(lo) <= v < at(hi). */
static inline uint32_t cs__srgb_cell(float (*at)(uint32_t), uint32_t lo, uint32_t hi, float v)
{
    while (hi - lo > 1u) {
        uint32_t mid = (lo + hi) / 2u;
        if (at(mid) <= v)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/*
 * sRGB decoding within entries lo..hi of the encoding table, read through
 * `at` (entry lo <= encoded < entry hi): the cell holding the value, then
 * the inverse of its linear interpolation, so decode(encode(v)) returns v to
 * float precision. cs_srgb_decode searches the whole table; the compact
 * form's decoder (cs_srgb_compact.c) first finds the anchors around the
 * value. The table rises strictly, so both find the same cell and float.
 */
static inline float cs__srgb_decode_in(float (*at)(uint32_t), uint32_t lo, uint32_t hi, float encoded)
{
    lo = cs__srgb_cell(at, lo, hi, encoded);
    float a = at(lo), b = at(lo + 1u);
    float s = ((float)lo + (encoded - a) / (b - a)) * (1.0f / 1024.0f);
    return s * s;
}

/* sRGB encoding of linear light in 0..1 (clamped), as 0..1. */
static inline float cs__srgb_encode(float linear)
{
    if (!(linear > 0.0f))
        return 0.0f;
    if (linear >= 1.0f)
        return 1.0f;
    float pos = cs__sqrtf(linear) * 1024.0f;
    int32_t i = (int32_t)pos;
    if (i >= 1024)
        return 1.0f;
    float a = cs__srgb_at((uint32_t)i), b = cs__srgb_at((uint32_t)i + 1u);
    return a + (b - a) * (pos - (float)i);
}
/* The 8-bit code of the encoding, round(255 * cs__srgb_encode(v)), from
 * two tables in which the core's own arithmetic was run on every float
 * (tools/gen_srgb8_table.c): a comparison instead of an interpolation. The
 * cells are cut by the square root of v, or, with CS_CFG_SRGB8_BITS, by the
 * top bits of v's float (128 cells per power of two from the first whose
 * code is not 0), which needs no square root, multiply or conversion. */
#define CS__SRGB8_BITS_FIRST 0x391Eu /* bits >> 16 of the first cell */
#define CS__SRGB8_BITS_CELLS 1634u   /* up to 1.0 */
#define CS__SRGB8_BITS_PAD 3u        /* zero bytes after the base table, for dword gathers */
/* The bits tables have one cell more, 1.0's (cs__srgb8_px). */
extern const uint8_t cs__srgb8_base[1024],
    cs__srgb8_bits_base[CS__SRGB8_BITS_CELLS + 1 + CS__SRGB8_BITS_PAD];
extern const float cs__srgb8_step[1024], cs__srgb8_bits_step[CS__SRGB8_BITS_CELLS + 1];
static inline uint32_t cs__srgb8(float linear)
{
#if CS_CFG_SRGB8_BITS
    union {
        float f;
        uint32_t u;
    } v = {linear};
    uint32_t i = (v.u >> 16) - CS__SRGB8_BITS_FIRST; /* negative v: the sign bit, far out */
    if (i < CS__SRGB8_BITS_CELLS)
        return cs__srgb8_bits_base[i] + (linear >= cs__srgb8_bits_step[i] ? 1u : 0u);
    return linear >= 1.0f ? 255u : 0u; /* below the cells (0 too) and NaN: 0 */
#elif CS_CFG_SRGB8_TABLE
    if (!(linear > 0.0f))
        return 0u;
    if (linear >= 1.0f)
        return 255u;
    int32_t i = (int32_t)(cs__sqrtf(linear) * 1024.0f);
    if (i >= 1024)
        return 255u;
    return cs__srgb8_base[i] + (linear >= cs__srgb8_step[i] ? 1u : 0u);
#else
    uint32_t c = (uint32_t)(cs__srgb_encode(linear) * 255.0f + 0.5f);
    return c > 255u ? 255u : c;
#endif
}

/* The RGB565 channel codes min(M, (uint32)(cs__srgb_encode(v) * M + 0.5)),
 * M = 31 or 63, from the thresholds where the code changes: a cell of the
 * square root gives the code of its first float, and the code rises by at
 * most two within a cell (tables made by tools/gen_rgb565_table.c running
 * that arithmetic on every float; tests/test_pixfmt.c checks every float). */
#define CS_RGB5_CELLS 32u
#define CS_RGB6_CELLS 64u
extern const uint8_t cs__rgb5_cell[CS_RGB5_CELLS + 1u], cs__rgb6_cell[CS_RGB6_CELLS + 1u];
extern const float cs__rgb5_step[32], cs__rgb6_step[64];
static inline uint32_t cs__code_by_step(float linear, uint32_t max, float cells,
                                        const uint8_t *cell, const float *step)
{
    if (!(linear > 0.0f))
        return 0u;
    if (linear >= 1.0f)
        return max;
    uint32_t c = cell[(int32_t)(cs__sqrtf(linear) * cells)];
    c += linear >= step[c] ? 1u : 0u;
    return c + (linear >= step[c] ? 1u : 0u);
}
static inline uint32_t cs__rgb5(float linear)
{
    return cs__code_by_step(linear, 31u, (float)CS_RGB5_CELLS, cs__rgb5_cell, cs__rgb5_step);
}
static inline uint32_t cs__rgb6(float linear)
{
    return cs__code_by_step(linear, 63u, (float)CS_RGB6_CELLS, cs__rgb6_cell, cs__rgb6_step);
}

/*
 * Stack transmittance below this counts as zero. Summed coverages of a
 * pixel fully inside land within a few ulps of 1, not on it; calling
 * T < 2^-20 (1/16 of a 16-bit output step) zero lets such pixels become
 * exactly opaque, which is what makes skipping the cels behind them exact.
 */
#define CS__T_ZERO (1.0f / 1048576.0f)

/* ---- functional paints (cs_paint.c) */

/*
 * Compiles `fn` for a frame: xf maps a device pixel position to function
 * space (LINEAR: row 0 gives t; RADIAL: the unit-circle frame; MAP: the
 * unit-square frame), given `inv`, the cel's device-to-canvas affine.
 */
void cs__func_compile(const cs_paint_func *fn, const cs_affine *inv, float xf[6]);

/* Value of `fn` at device position (px, py); sRGB-encoded if `srgb`. */
void cs__func_eval(const cs_paint_func *fn, const float xf[6], float px, float py, bool srgb,
                   float out[3]);

/* sRGB-encoded value of a linear one, as a float 0..1 (--blend srgb). */
static inline float cs__encode(float linear)
{
    return cs__srgb_encode(linear);
}

/* ---- coverage accumulators of the region being scan-converted
 *
 * Every write to ws->area / ws->cover goes through these two, which also
 * mark the pixel in ws->touched: the line code then visits only marked
 * pixels (in x order) instead of scanning the region's whole x range. */
static inline void cs__acc_area(cs_workspace *ws, int32_t x, float v)
{
    ws->area[x] += v;
    ws->touched[(uint32_t)x >> 5] |= 1u << ((uint32_t)x & 31u);
}

static inline void cs__acc_cover(cs_workspace *ws, int32_t x, float v)
{
    ws->cover[x] += v;
    ws->touched[(uint32_t)x >> 5] |= 1u << ((uint32_t)x & 31u);
}

/* ---- line pipeline (cs_cross.c, cs_coverage.c, cs_composite.c, cs_line.c) */

/* Composites line y of every live cel (and the cache) into the line's runs
 * (ws->stack_E, ws->stack_T at run starts; see cs_runs.h): cs_composite.c,
 * shared with the cache builder. */
void cs__line_stack(cs_renderer *r, int y);

/* Moves the active list (ws->active, in piece order) to line y
 * (cs_cross.c). */
void cs__line_active(cs_renderer *r, int y);

/* The crossings of a region's active pieces act[] with sub-scanline `sub`
 * (of `samples`) of line y, sorted by x into ws->crossings; -1 if they do
 * not fit (cs_cross.c). */
int32_t cs__crossings_at(cs_renderer *r, const cs_index *act, cs_index *ord, uint32_t *idle,
                         uint32_t live, int y, int sub, int samples);

/* Coverage of region `reg` on line y from its n active pieces act[], left
 * in the area/cover accumulators over [*lo, *hi), in the sampled modes
 * (cs_coverage.c; exact mode calls cs__exact_region). */
void cs__region_coverage(cs_renderer *r, uint32_t reg, const cs_index *act, uint32_t n, int y,
                         int32_t *lo, int32_t *hi);

/* Prepares the frame for cels [cel_begin, cel_end), skipping `cache`'s range. */
cs_status cs__frame_prepare(cs_renderer *r, cs_workspace *ws, const cs_scene *scene,
                            const cs_render_opts *opts, uint32_t cel_begin, uint32_t cel_end,
                            const cs_cache *cache, cs_error *err);

/* Composites the cached runs of line y into the stack (cs_cache.c). */
void cs__cache_composite(cs_renderer *r, int y);

/* Writes pixels [x0, x1) of `out`, all of linear colour rgb, in `fmt`: the
 * bytes cs_pixfmt_convert makes of them, converted once (cs_pixfmt.c). */
void cs__pixfmt_fill(cs_pixfmt fmt, const float rgb[3], uint32_t x0, uint32_t x1, uint8_t *out);
/* A line of runs [s, run_end[s]) from s = 0 to width, values at rgb[3 s]. */
void cs__pixfmt_runs(cs_pixfmt fmt, const float *rgb, const uint16_t *run_end, uint32_t width,
                     uint8_t *out);


/*
 * Exact-area coverage of `region` on pixel row y (cs_exact.c), from its
 * active pieces act[0..n): adds to ws->area / ws->cover what the
 * sub-scanline code adds for its spans, so fold_region folds both alike.
 * [*lo, *hi) grows to every accumulator entry written. Returns
 * CS_ERR_CAP_CROSSINGS, adding nothing, if n exceeds CS_CFG_MAX_CROSSINGS,
 * or, with the row still added, if it needed more than
 * CS_CFG_EXACT_MAX_BANDS bands to separate crossing curves.
 */
cs_status cs__exact_region(cs_renderer *r, const cs_region *region, const cs_index *act,
                           uint32_t n, int y, int32_t *lo, int32_t *hi);


#endif /* CS_INTERNAL_H */
