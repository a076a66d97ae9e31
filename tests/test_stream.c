/*
 * test_stream.c - the cel stream, end to end: encoder, decoder, animation.
 *
 * What is checked, and against what:
 *   - round trip: a scene built with the cs_scene_* calls, encoded by
 *     cels_write and decoded by cs_stream, gives the same store (every used
 *     field compared bit for bit) and the same rendered lines, at several
 *     times, whatever the chunking of the input;
 *   - hostility: truncation at every offset, every single-bit flip, absurd
 *     lengths and counts, NaN/Inf in CRC-valid transactions, random bytes;
 *     each ends in the committed scene being exactly the last good one
 *     (compared with the scene the test built) and an error whose offset
 *     is the damaged transaction's, never a different picture;
 *   - resynchronisation after garbage and after a transaction cut short;
 *   - link gaps (cs_stream_gap): at every offset, with 0, 1 or 7 bytes lost;
 *   - patches: a patch transaction equals the same edits made with the
 *     scene calls directly, and cel removal / moves equal scenes built
 *     from scratch in the resulting order;
 *   - animation: the centroid of a disc under a keyframed translation,
 *     measured from rendered coverage, against the closed-form position.
 * The last line is `test_stream: N passed, M failed`.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cels_read.h"
#include "cels_write.h"
#include "celscan.h"
#include "cs_wire.h"
#include "scene_equal.h"
#include "shapes.h"
#include "testlib.h"

static const double PI = 3.14159265358979323846;

/* A check that runs thousands of times counts once, and reports its first failure. */
typedef struct {
    int fails;
    char first[256];
} bulk;

static void bulk_fail(bulk *b, const char *msg)
{
    if (b->fails++ == 0)
        snprintf(b->first, sizeof b->first, "%s", msg);
}

static void bulk_done(bulk *b, const char *name, int runs)
{
    CHECK(b->fails == 0, "%s: %d of %d runs failed; first: %s", name, b->fails, runs, b->first);
}

static uint32_t rng_state = 12345u;
static uint32_t rnd(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return rng_state;
}

static cs_scene *new_scene(void) { return tl_calloc(1, sizeof(cs_scene)); }

/* ------------------------------------------------------------ comparison */

/* scene_equal(): every used field of two stores, bit for bit (tests/scene_equal.h). */

/* ------------------------------------------------------------- rendering */

static cs_workspace *ws;

/* Renders a frame into out (w*h*3 floats); returns the status of frame or lines. */
static cs_status render(const cs_scene *s, int w, int h, float t, cs_aa_mode aa, int sub,
                        float *out)
{
    cs_renderer r;
    cs_render_opts o = {.width = w, .height = h, .aa = aa, .subscanlines = sub, .time = t,
                        .blend = CS_BLEND_LINEAR};
    cs_error err;
    cs_status st = cs_frame_begin(&r, ws, s, &o, &err);
    if (st != CS_OK)
        return st;
    for (int y = 0; y < h; y++)
        if ((st = cs_render_line(&r, y, out + (size_t)y * (size_t)w * 3)) != CS_OK)
            return st;
    return r.sticky.status;
}

enum { RW = 48, RH = 32 };
static const float frame_times[] = {-1.0f, 0.0f, 0.37f, 1.0f, 1.5f, 2.75f, 10.0f};
#define NTIMES (sizeof frame_times / sizeof frame_times[0])

/* Same pixels, bit for bit, at every test time? */
static bool renders_equal(const cs_scene *a, const cs_scene *b)
{
    static float fa[RW * RH * 3], fb[RW * RH * 3];
    for (size_t i = 0; i < NTIMES; i++) {
        cs_status sa = render(a, RW, RH, frame_times[i], CS_AA_SUBSCAN, 4, fa);
        cs_status sb = render(b, RW, RH, frame_times[i], CS_AA_SUBSCAN, 4, fb);
        if (sa != sb || sa != CS_OK || memcmp(fa, fb, sizeof fa) != 0)
            return false;
    }
    return true;
}

/* ---------------------------------------------------------------- scenes */

static cs_paint paint_of(float r, float g, float b, float beta)
{
    cs_paint p = {{r, g, b}, {1, 1, 1}, beta};
    return p;
}

/*
 * A scene with something of everything: three cels (own and default front
 * lights, back lights), degree 1, 2 and 3 contours, non-uniform intervals,
 * both fill rules, a background, stack lights, and one track of every kind.
 */
static void build_demo(cs_scene *s)
{
    cs_error e;
    cs_scene_init(s, 96, 64);
    const float front[3] = {1.0f, 0.9f, 0.8f}, back[3] = {0.1f, 0.2f, 0.3f};
    const float sback[3] = {0.05f, 0.05f, 0.1f}, bg[3] = {0.02f, 0.03f, 0.05f};
    cs_scene_set_lights(s, front, sback);
    cs_scene_set_background(s, bg);

    cs_affine id = {1, 0, 0, 1, 0, 0};
    cs_scene_add_cel(s, &id, NULL, NULL, &e); /* cel 0: a disc, animated transform */
    cs_paint red = paint_of(0.9f, 0.2f, 0.2f, 1.0f);
    cs_scene_add_region(s, CS_FILL_NONZERO, &red, &e);
    TL_MUST(ts_add_circle(s, 20, 20, 12));

    cs_affine rot = {0.8f, 0.6f, -0.6f, 0.8f, 50, 8};
    const float cel_front[3] = {0.9f, 0.95f, 1.0f};
    cs_scene_add_cel(s, &rot, cel_front, back, &e); /* cel 1: cubic blob + square */
    cs_paint gel = {{0.2f, 0.8f, 0.3f}, {0.6f, 0.9f, 0.7f}, 0.5f};
    cs_scene_add_region(s, CS_FILL_EVENODD, &gel, &e);
    cs_point blob[6] = {{0, 0, 1},   {10, -5, 1}, {20, 0, 1.5f},
                        {25, 15, 1}, {10, 25, 1}, {-5, 15, 0.8f}};
    float blob_iv[6] = {1, 0, 0, 2, 0, 0};
    cs_scene_add_contour(s, 3, 6, blob, blob_iv, &e);
    cs_point sq[4] = {{5, 5, 1}, {15, 5, 1}, {15, 15, 1}, {5, 15, 1}};
    cs_scene_add_contour(s, 1, 4, sq, NULL, &e);
    cs_paint blue = paint_of(0.1f, 0.2f, 0.9f, 0.8f);
    cs_scene_add_region(s, CS_FILL_NONZERO, &blue, &e);
    cs_point tri[3] = {{-10, 30, 1}, {30, 30, 1}, {10, 45, 1}};
    cs_scene_add_contour(s, 1, 3, tri, NULL, &e);

    cs_scene_add_cel(s, &id, NULL, back, &e); /* cel 2: a big backdrop quad */
    cs_paint grey = paint_of(0.5f, 0.5f, 0.5f, 1.0f);
    cs_scene_add_region(s, CS_FILL_NONZERO, &grey, &e);
    cs_point quad[4] = {{4, 40, 1}, {92, 36, 1}, {90, 60, 1}, {6, 62, 1}};
    cs_scene_add_contour(s, 1, 4, quad, NULL, &e);

    /* Tracks, in an order that is not (kind, target) order. */
    cs_scene_add_track(s, CS_TRACK_POINTS, 2, CS_EASE_SMOOTH, &e); /* the square */
    float k0[12] = {5, 5, 1, 15, 5, 1, 15, 15, 1, 5, 15, 1};
    float k1[12] = {0, 0, 1, 20, 3, 1, 18, 18, 2, 2, 20, 1};
    cs_scene_add_key(s, 0.5f, k0, &e);
    cs_scene_add_key(s, 2.0f, k1, &e);
    cs_scene_add_track(s, CS_TRACK_TRANSFORM, 0, CS_EASE_LINEAR, &e);
    float t0[6] = {1, 0, 0, 1, 0, 0}, t1[6] = {1, 0, 0, 1, 40, 10}, t2[6] = {0.5f, 0, 0, 0.5f, 60, 30};
    cs_scene_add_key(s, 0.0f, t0, &e);
    cs_scene_add_key(s, 1.0f, t1, &e);
    cs_scene_add_key(s, 2.5f, t2, &e);
    cs_scene_add_track(s, CS_TRACK_PAINT, 1, CS_EASE_LINEAR, &e);
    float p0[7] = {0.2f, 0.8f, 0.3f, 0.6f, 0.9f, 0.7f, 0.5f};
    float p1[7] = {1.0f, 1.0f, 0.0f, 0.2f, 0.2f, 0.2f, 0.9f};
    cs_scene_add_key(s, 0.25f, p0, &e);
    cs_scene_add_key(s, 1.75f, p1, &e);
    cs_scene_add_track(s, CS_TRACK_CEL_LIGHTS, 2, CS_EASE_SMOOTH, &e);
    float l0[6] = {1, 1, 1, 0, 0, 0}, l1[6] = {0.2f, 0.2f, 0.5f, 0.3f, 0.1f, 0};
    cs_scene_add_key(s, 0.0f, l0, &e);
    cs_scene_add_key(s, 4.0f, l1, &e);
    cs_scene_add_track(s, CS_TRACK_STACK_LIGHTS, 0, CS_EASE_LINEAR, &e);
    float s0[6] = {1, 0.9f, 0.8f, 0.05f, 0.05f, 0.1f}, s1[6] = {0.5f, 0.5f, 0.6f, 0, 0, 0};
    cs_scene_add_key(s, 1.0f, s0, &e);
    cs_scene_add_key(s, 3.0f, s1, &e);
    cs_scene_add_track(s, CS_TRACK_BACKGROUND, 0, CS_EASE_SMOOTH, &e);
    float b0[3] = {0.02f, 0.03f, 0.05f}, b1[3] = {0.3f, 0.1f, 0.1f};
    cs_scene_add_key(s, 0.0f, b0, &e);
    cs_scene_add_key(s, 2.0f, b1, &e);
}

/* A paint function from its parts; stops[i] = {offset, r, g, b}. */
static cs_paint_func make_func(int kind, int spread, const float *geom, int nstops, int cols,
                               const float (*stops)[4])
{
    cs_paint_func f;
    memset(&f, 0, sizeof f);
    f.kind = (uint8_t)kind;
    f.spread = (uint8_t)spread;
    f.stop_count = (uint8_t)nstops;
    f.map_cols = (uint8_t)cols;
    for (int i = 0; i < 6; i++)
        f.geom[i] = geom[i];
    for (int i = 0; i < nstops; i++) {
        f.stops[i].offset = stops[i][0];
        for (int k = 0; k < 3; k++)
            f.stops[i].value[k] = stops[i][1 + k];
    }
    return f;
}

/*
 * What the beta model added to a scene, for the class 5 records: a linear
 * gradient pigment, a radial beta (a feathered matte), a 3x2 colour map
 * medium, a CSG region (a ring minus a bar, plus a disc) with operands, a
 * region with a function in every field, and a paint track on a region
 * whose pigment is a function (it animates the constant fields only).
 */
static void build_beta(cs_scene *s)
{
    cs_error e;
    cs_scene_init(s, 96, 64);
    const float bg[3] = {0.1f, 0.1f, 0.12f};
    cs_scene_set_background(s, bg);
    cs_scene_set_blend(s, CS_BLEND_SRGB); /* the BLEND record travels too */
    cs_affine id = {1, 0, 0, 1, 0, 0};
    cs_affine tilt = {0.9f, 0.3f, -0.3f, 0.9f, 10, -4};

    cs_scene_add_cel(s, &tilt, NULL, NULL, &e); /* cel 0: gradients */
    cs_paint p = paint_of(0.5f, 0.5f, 0.5f, 1.0f);
    cs_scene_add_region(s, CS_FILL_NONZERO, &p, &e);
    const float lin_g[6] = {10, 10, 50, 30, 0, 0};
    const float lin_s[3][4] = {{0, 1, 0, 0}, {0.5f, 0, 1, 0}, {1, 0, 0, 1}};
    cs_paint_func f = make_func(CS_FUNC_LINEAR, CS_SPREAD_REFLECT, lin_g, 3, 1, lin_s);
    cs_scene_set_region_func(s, CS_FIELD_PIGMENT, &f, &e);
    const float rad_g[6] = {30, 20, 18, 26, 22, 0};
    const float rad_s[2][4] = {{0, 1, 1, 1}, {1, 0.2f, 0.2f, 0.2f}};
    f = make_func(CS_FUNC_RADIAL, CS_SPREAD_PAD, rad_g, 2, 1, rad_s);
    cs_scene_set_region_func(s, CS_FIELD_BETA, &f, &e);
    TL_MUST(ts_add_circle(s, 30, 20, 18));

    cs_paint gel = {{0.2f, 0.2f, 0.2f}, {0.8f, 0.8f, 0.8f}, 0.3f};
    cs_scene_add_region(s, CS_FILL_EVENODD, &gel, &e);
    const float map_g[6] = {50, 30, 30, 0, 0, 20};
    const float map_s[6][4] = {{0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1},
                               {0, 1, 1, 0}, {0, 0, 1, 1}, {0, 1, 0, 1}};
    f = make_func(CS_FUNC_MAP, CS_SPREAD_REPEAT, map_g, 6, 3, map_s);
    cs_scene_set_region_func(s, CS_FIELD_MEDIUM, &f, &e);
    cs_point box[4] = {{50, 30, 1}, {80, 30, 1}, {80, 50, 1}, {50, 50, 1}};
    cs_scene_add_contour(s, 1, 4, box, NULL, &e);

    cs_scene_add_cel(s, &id, NULL, NULL, &e); /* cel 1: CSG */
    cs_paint ink = paint_of(0.9f, 0.8f, 0.1f, 1.0f);
    cs_scene_add_region(s, CS_FILL_EVENODD, &ink, &e);
    const int rpn[5] = {0, 1, CS_CSG_DIFFERENCE, 2, CS_CSG_UNION};
    cs_scene_set_region_csg(s, rpn, 5, &e);
    TL_MUST(ts_add_circle(s, 60, 20, 14)); /* operand 0: a ring of two circles */
    cs_scene_set_contour_operand(s, 0, &e);
    TL_MUST(ts_add_circle(s, 60, 20, 8));
    cs_scene_set_contour_operand(s, 0, &e);
    cs_point bar[4] = {{40, 17, 1}, {80, 17, 1}, {80, 23, 1}, {40, 23, 1}};
    cs_scene_add_contour(s, 1, 4, bar, NULL, &e); /* operand 1: the bar */
    cs_scene_set_contour_operand(s, 1, &e);
    TL_MUST(ts_add_circle(s, 15, 50, 9)); /* operand 2: a disc */
    cs_scene_set_contour_operand(s, 2, &e);
    /* every field a function, on a region with no CSG */
    cs_paint any = paint_of(0, 0, 0, 0.5f);
    cs_scene_add_region(s, CS_FILL_NONZERO, &any, &e);
    const float lin2[6] = {0, 0, 96, 64, 0, 0};
    const float two[2][4] = {{0, 0.2f, 0.4f, 0.6f}, {1, 0.9f, 0.7f, 0.5f}};
    f = make_func(CS_FUNC_LINEAR, CS_SPREAD_PAD, lin2, 2, 1, two);
    cs_scene_set_region_func(s, CS_FIELD_PIGMENT, &f, &e);
    cs_scene_set_region_func(s, CS_FIELD_MEDIUM, &f, &e);
    cs_scene_set_region_func(s, CS_FIELD_BETA, &f, &e);
    cs_point tri[3] = {{70, 40, 1}, {94, 62, 1}, {60, 62, 1}};
    cs_scene_add_contour(s, 1, 3, tri, NULL, &e);

    /* Tracks: move the CSG cel, animate the gradient region's constants. */
    cs_scene_add_track(s, CS_TRACK_TRANSFORM, 1, CS_EASE_SMOOTH, &e);
    cs_scene_add_key(s, 0, (float[6]){1, 0, 0, 1, 0, 0}, &e);
    cs_scene_add_key(s, 2, (float[6]){1, 0, 0, 1, -20, 8}, &e);
    cs_scene_add_track(s, CS_TRACK_PAINT, 0, CS_EASE_LINEAR, &e);
    cs_scene_add_key(s, 0, (float[7]){0.5f, 0.5f, 0.5f, 1, 1, 1, 1}, &e);
    cs_scene_add_key(s, 1.5f, (float[7]){0.5f, 0.5f, 0.5f, 0.2f, 0.3f, 1, 0.4f}, &e);
}

/* ---------------------------------------------------------------- decoding */

static cs_scene *store_a, *store_b;
static cs_stream st;

typedef struct {
    int commits, errors;
    cs_stream_error err[8];
    const cs_scene *scene; /* committed scene after the input, or NULL */
    uint32_t dropped;
    uint64_t skipped;
} result;

static void handle(cs_stream_event ev, result *r)
{
    if (ev == CS_STREAM_COMMIT) {
        cs_stream_swap(&st);
        r->commits++;
    } else if (ev == CS_STREAM_ERROR) {
        if (r->errors < 8)
            r->err[r->errors] = *cs_stream_last_error(&st);
        r->errors++;
    }
}

/* Chunking: 0 all at once, 1 byte by byte, 2 random chunks of 1..64, 3 random 1..4096. */
static void decode(const uint8_t *d, size_t n, int chunking, const cs_scene *initial, result *r)
{
    memset(r, 0, sizeof *r);
    if (initial)
        cs_scene_copy(store_a, initial);
    cs_stream_init(&st, store_a, initial != NULL, store_b);
    size_t off = 0;
    while (off < n) {
        size_t want = n - off;
        if (chunking == 1)
            want = 1;
        else if (chunking == 2)
            want = 1 + rnd() % 64;
        else if (chunking == 3)
            want = 1 + rnd() % 4096;
        if (want > n - off)
            want = n - off;
        size_t used;
        cs_stream_event ev = cs_stream_feed(&st, d + off, want, &used);
        off += used;
        handle(ev, r);
    }
    cs_stream_event ev;
    size_t used;
    while ((ev = cs_stream_feed(&st, NULL, 0, &used)) != CS_STREAM_MORE)
        handle(ev, r);
    while ((ev = cs_stream_finish(&st)) != CS_STREAM_MORE)
        handle(ev, r);
    r->scene = cs_stream_scene(&st);
    r->dropped = st.dropped;
    r->skipped = st.skipped;
}

static void encode(const cs_scene *s, cels_buf *b, bool stream_header)
{
    cels_buf_init(b);
    if (stream_header)
        cels_stream_header(b);
    if (cels_encode_scene(b, s) != 0) {
        fprintf(stderr, "encode failed\n");
        exit(2);
    }
}

/* Re-seals the transaction starting at `txn` after its bytes were edited. */
static void reseal(uint8_t *d, size_t txn)
{
    uint32_t body = (uint32_t)d[txn + 8] | (uint32_t)d[txn + 9] << 8 |
                    (uint32_t)d[txn + 10] << 16 | (uint32_t)d[txn + 11] << 24;
    uint32_t c = cs_crc32(0, d + txn, 12);
    memcpy(d + txn + 12, (uint8_t[]){(uint8_t)c, (uint8_t)(c >> 8), (uint8_t)(c >> 16),
                                      (uint8_t)(c >> 24)},
           4);
    c = cs_crc32(0, d + txn, 16 + (size_t)body);
    memcpy(d + txn + 16 + body,
           (uint8_t[]){(uint8_t)c, (uint8_t)(c >> 8), (uint8_t)(c >> 16), (uint8_t)(c >> 24)}, 4);
}

static const char *status_name(cs_status s)
{
    return cs_status_str(s);
}

/* ------------------------------------------------------------------ tests */

static void test_roundtrip(void)
{
    cs_scene *s = new_scene();
    build_demo(s);
    CHECK(s->cel_count == 3 && s->region_count == 4 && s->contour_count == 5 &&
              s->track_count == 6,
          "demo scene built: %u cels %u regions %u contours %u tracks", s->cel_count,
          s->region_count, s->contour_count, s->track_count);
    cels_buf b;
    encode(s, &b, true);
    printf("  demo scene: %zu bytes of stream\n", b.len);
    for (int chunking = 0; chunking < 4; chunking++) {
        result r;
        decode(b.data, b.len, chunking, NULL, &r);
        char why[128] = "";
        CHECK(r.commits == 1 && r.errors == 0 && r.scene, "chunking %d: %d commits %d errors (%s)",
              chunking, r.commits, r.errors,
              r.errors ? r.err[0].what : "-");
        CHECK(r.scene && scene_equal(s, r.scene, why, sizeof why),
              "chunking %d: decoded store differs: %s", chunking, why);
        CHECK(r.scene && renders_equal(s, r.scene), "chunking %d: renders differ", chunking);
    }
    /* Many random chunkings. */
    bulk bk = {0};
    for (int i = 0; i < 200; i++) {
        result r;
        decode(b.data, b.len, 2 + (i & 1), NULL, &r);
        char why[128] = "";
        if (!(r.commits == 1 && r.errors == 0 && r.scene && scene_equal(s, r.scene, why, sizeof why)))
            bulk_fail(&bk, why);
    }
    bulk_done(&bk, "random chunkings", 200);
    /* A stream without its optional stream header decodes the same. */
    result r;
    decode(b.data + 16, b.len - 16, 0, NULL, &r);
    char why[128] = "";
    CHECK(r.commits == 1 && r.errors == 0 && r.scene && scene_equal(s, r.scene, why, sizeof why),
          "headerless stream: %d commits %d errors %s", r.commits, r.errors, why);
    /* The renders actually change over time (the tracks do something). */
    static float f0[RW * RH * 3], f1[RW * RH * 3];
    render(s, RW, RH, 0.0f, CS_AA_SUBSCAN, 4, f0);
    render(s, RW, RH, 1.5f, CS_AA_SUBSCAN, 4, f1);
    CHECK(memcmp(f0, f1, sizeof f0) != 0, "animated demo renders the same at t=0 and t=1.5");
    cels_buf_free(&b);
    free(s);
}

/* Cel groups (class 6), TRS tracks and cubic / hold easing survive the trip. */
static void test_roundtrip_groups(void)
{
    cs_scene *s = new_scene();
    build_demo(s);
    cs_error e;
    static const cs_affine id = {1, 0, 0, 1, 0, 0};
    CHECK(cs_scene_add_cel(s, &id, NULL, NULL, &e) == CS_OK, "group cel");
    uint32_t g = s->cel_count - 1;
    CHECK(cs_scene_set_cel_parent(s, 0, g, &e) == CS_OK &&
              cs_scene_set_cel_parent(s, 1, g, &e) == CS_OK,
          "cels 0 and 1 in the group");
    CHECK(cs_scene_add_track(s, CS_TRACK_TRS, g, CS_EASE_CUBIC, &e) == CS_OK, "TRS track");
    float k0[14] = {0.42f, 0, 0.58f, 1, 10, 5, 0, 0, 1, 1, 0, 0, 0, 1};
    float k1[14] = {-1, 0, 0, 0, 12, 6, 0, 0, 1.2f, 0.9f, 120, 10, 30, 0.6f};
    float k2[14] = {0, 0, 1, 1, 12, 6, 0, 0, 1, 1, 200, 0, 0, 0.9f};
    CHECK(cs_scene_add_key(s, 0, k0, &e) == CS_OK && cs_scene_add_key(s, 1, k1, &e) == CS_OK &&
              cs_scene_add_key(s, 2, k2, &e) == CS_OK,
          "TRS keys");
    cels_buf b;
    encode(s, &b, true);
    result r;
    decode(b.data, b.len, 1, NULL, &r);
    char why[128] = "";
    CHECK(r.commits == 1 && r.errors == 0 && r.scene && scene_equal(s, r.scene, why, sizeof why),
          "groups round trip: %d commits %d errors %s", r.commits, r.errors, why);
    CHECK(r.scene && renders_equal(s, r.scene), "groups round trip renders the same");
    /* A 1.2 or 1.3 decoder refuses class 6 rather than drawing the children ungrouped. */
    CHECK(b.len > 21 && b.data[5] == 4 && b.data[21] == 4, "written as version 1.4");
    cels_buf_free(&b);
    free(s);
}

/* The class 5 records: functions, CSG and operands survive the trip. */
static void test_roundtrip_beta(void)
{
    cs_scene *s = new_scene();
    build_beta(s);
    CHECK(s->func_count == 6 && s->regions[2].csg_len == 5 && s->contours[4].operand == 1 &&
              s->contours[5].operand == 2,
          "beta scene built: %u functions, csg %u, operands %u %u", s->func_count,
          s->regions[2].csg_len, s->contours[4].operand, s->contours[5].operand);
    cels_buf b;
    encode(s, &b, true);
    printf("  beta scene: %zu bytes of stream\n", b.len);
    CHECK(b.len > 21 && b.data[5] == CS_WIRE_MINOR && b.data[21] == CS_WIRE_MINOR &&
              CS_WIRE_MINOR == 4,
          "stream and transaction headers say version 1.%d", CS_WIRE_MINOR);
    for (int chunking = 0; chunking < 4; chunking++) {
        result r;
        decode(b.data, b.len, chunking, NULL, &r);
        char why[128] = "";
        CHECK(r.commits == 1 && r.errors == 0 && r.scene, "beta chunking %d: %d commits %d errors (%s)",
              chunking, r.commits, r.errors, r.errors ? r.err[0].what : "-");
        CHECK(r.scene && scene_equal(s, r.scene, why, sizeof why),
              "beta chunking %d: decoded store differs: %s", chunking, why);
        CHECK(r.scene && renders_equal(s, r.scene), "beta chunking %d: renders differ", chunking);
    }
    /* The functions and CSG do something: without them the picture differs. */
    cs_scene *plain = new_scene();
    cs_scene_copy(plain, s);
    for (uint32_t i = 0; i < plain->region_count; i++) {
        plain->regions[i].func[0] = plain->regions[i].func[1] = plain->regions[i].func[2] = 0;
        plain->regions[i].csg_len = 0;
    }
    plain->func_count = 0;
    CHECK(!renders_equal(s, plain), "functions and CSG change the picture");
    cels_buf_free(&b);
    free(plain);
    free(s);
}

static void test_crc_and_lights_order(void)
{
    CHECK(cs_crc32(0, "123456789", 9) == 0xCBF43926u, "CRC-32 check value");
    /* Lights set before or after the cels give the same store. */
    cs_scene *a = new_scene(), *b = new_scene();
    cs_error e;
    const float f[3] = {0.5f, 0.6f, 0.7f}, k[3] = {0.1f, 0, 0};
    cs_affine id = {1, 0, 0, 1, 0, 0};
    cs_scene_init(a, 10, 10);
    cs_scene_set_lights(a, f, k);
    cs_scene_add_cel(a, &id, NULL, NULL, &e);
    cs_scene_init(b, 10, 10);
    cs_scene_add_cel(b, &id, NULL, NULL, &e);
    cs_scene_set_lights(b, f, k);
    char why[128] = "";
    CHECK(scene_equal(a, b, why, sizeof why), "lights before or after cels: %s", why);
    free(a);
    free(b);
}

static void test_copy(void)
{
    cs_scene *s = new_scene(), *c = new_scene();
    build_demo(s);
    memset(c, 0x5a, sizeof *c); /* dirty destination: copy must not depend on it */
    cs_scene_copy(c, s);
    char why[128] = "";
    CHECK(scene_equal(s, c, why, sizeof why), "cs_scene_copy: %s", why);
    build_beta(s);
    memset(c, 0xa5, sizeof *c);
    cs_scene_copy(c, s);
    CHECK(scene_equal(s, c, why, sizeof why) && renders_equal(s, c),
          "cs_scene_copy with functions and CSG: %s", why);
    free(s);
    free(c);
}

/* Truncation at every offset: nothing is committed, and the error is reported. */
static void truncation(void (*build)(cs_scene *), const char *name)
{
    cs_scene *s = new_scene();
    build(s);
    cels_buf b;
    encode(s, &b, true);
    bulk bk = {0};
    char msg[256];
    for (size_t k = 0; k < b.len; k++) {
        result r;
        decode(b.data, k, 0, NULL, &r);
        /* Cut inside the stream or transaction header: those bytes are no
         * header, so they are reported as skipped; later, as truncated. */
        cs_status want = k < 32 ? CS_ERR_STREAM_SYNC : CS_ERR_STREAM_TRUNCATED;
        uint64_t want_off = k < 16 ? 0 : 16;
        if (k == 0 || k == 16)
            want = CS_OK; /* nothing, or exactly the stream header: no error */
        bool ok = r.commits == 0 && r.scene == NULL &&
                  (want == CS_OK ? r.errors == 0
                                 : r.errors == 1 && r.err[0].status == want &&
                                       r.err[0].offset == want_off);
        if (!ok) {
            snprintf(msg, sizeof msg, "cut at %zu: %d commits, %d errors, first %s at %llu", k,
                     r.commits, r.errors, r.errors ? status_name(r.err[0].status) : "-",
                     r.errors ? (unsigned long long)r.err[0].offset : 0ull);
            bulk_fail(&bk, msg);
        }
    }
    snprintf(msg, sizeof msg, "%s: truncation at every offset", name);
    bulk_done(&bk, msg, (int)b.len);

    /* The same after a good transaction: the good scene stays. */
    cs_scene *first = new_scene();
    cs_scene_init(first, 96, 64);
    cs_affine id = {1, 0, 0, 1, 0, 0};
    cs_error e;
    cs_scene_add_cel(first, &id, NULL, NULL, &e);
    cs_paint p = paint_of(1, 1, 1, 1);
    cs_scene_add_region(first, CS_FILL_NONZERO, &p, &e);
    TL_MUST(ts_add_circle(first, 30, 30, 10));
    cels_buf g;
    encode(first, &g, true);
    size_t second = g.len;
    cels_encode_scene(&g, s);
    bulk bk2 = {0};
    for (size_t k = second; k < g.len; k++) {
        result r;
        decode(g.data, k, 1, NULL, &r);
        char why[128] = "";
        bool ok = r.commits == 1 && r.scene && scene_equal(first, r.scene, why, sizeof why) &&
                  (k == second ? r.errors == 0
                               : r.errors == 1 && r.err[0].offset == second);
        if (!ok) {
            snprintf(msg, sizeof msg, "cut at %zu: %d commits, %d errors (%s at %llu) %s", k,
                     r.commits, r.errors, r.errors ? status_name(r.err[0].status) : "-",
                     r.errors ? (unsigned long long)r.err[0].offset : 0ull, why);
            bulk_fail(&bk2, msg);
        }
    }
    snprintf(msg, sizeof msg, "%s: truncation of a second transaction keeps the first", name);
    bulk_done(&bk2, msg, (int)(g.len - second));
    cels_buf_free(&b);
    cels_buf_free(&g);
    free(s);
    free(first);
}

/*
 * Every single-bit flip of a second transaction: the first scene stays, one
 * error names the second transaction's offset. Flips in the stream header
 * only cost the header (it is optional).
 */
static void bitflips(void (*build)(cs_scene *), const char *name)
{
    cs_scene *first = new_scene(), *s = new_scene();
    build(s);
    cs_scene_init(first, 96, 64);
    cs_affine id = {1, 0, 0, 1, 0, 0};
    cs_error e;
    cs_scene_add_cel(first, &id, NULL, NULL, &e);
    cs_paint p = paint_of(1, 0.5f, 0.25f, 1);
    cs_scene_add_region(first, CS_FILL_NONZERO, &p, &e);
    TL_MUST(ts_add_circle(first, 30, 30, 10));
    cels_buf g;
    encode(first, &g, true);
    size_t second = g.len;
    cels_encode_scene(&g, s);
    uint8_t *d = malloc(g.len);
    bulk bk = {0};
    char msg[256];
    int runs = 0;
    for (size_t k = 0; k < g.len; k++)
        for (int bit = 0; bit < 8; bit++) {
            memcpy(d, g.data, g.len);
            d[k] ^= (uint8_t)(1u << bit);
            result r;
            decode(d, g.len, 0, NULL, &r);
            runs++;
            char why[128] = "";
            bool ok;
            if (k < 16) /* stream header damaged: skipped, both transactions commit */
                ok = r.commits == 2 && r.errors == 1 && r.err[0].status == CS_ERR_STREAM_SYNC &&
                     r.err[0].offset == 0 && r.scene && scene_equal(s, r.scene, why, sizeof why);
            else if (k < second) /* first transaction damaged: dropped, the second commits */
                ok = r.commits == 1 && r.errors == 1 && r.err[0].offset == 16 && r.scene &&
                     scene_equal(s, r.scene, why, sizeof why);
            else
                ok = r.commits == 1 && r.errors == 1 && r.err[0].offset == second && r.scene &&
                     scene_equal(first, r.scene, why, sizeof why);
            if (!ok) {
                snprintf(msg, sizeof msg, "flip byte %zu bit %d: %d commits, %d errors (%s at %llu) %s",
                         k, bit, r.commits, r.errors, r.errors ? status_name(r.err[0].status) : "-",
                         r.errors ? (unsigned long long)r.err[0].offset : 0ull, why);
                bulk_fail(&bk, msg);
            }
        }
    snprintf(msg, sizeof msg, "%s: every bit flip", name);
    bulk_done(&bk, msg, runs);
    printf("  bit flips, %s: %d streams\n", name, runs);
    free(d);
    cels_buf_free(&g);
    free(first);
    free(s);
}

static void test_truncation(void)
{
    truncation(build_demo, "demo");
    truncation(build_beta, "beta");
}

static void test_bitflips(void)
{
    bitflips(build_demo, "demo");
    bitflips(build_beta, "beta");
}

/* A one-transaction stream around records written by `fill`, resealed. */
static void one_txn(cels_buf *b, void (*fill)(cels_buf *))
{
    cels_buf_init(b);
    cels_txn_begin(b);
    fill(b);
    cels_txn_end(b);
}

static void rec_scene(cels_buf *b)
{
    cels_rec_begin(b, CS_REC_SCENE);
    cels_put_f32(b, 100);
    cels_put_f32(b, 100);
    cels_rec_end(b);
}

static void rec_cel_region(cels_buf *b)
{
    cels_rec_begin(b, CS_REC_CEL);
    cels_put_u32(b, 0);
    float m[12] = {1, 0, 0, 1, 0, 0, 1, 1, 1, 0, 0, 0};
    cels_put_f32s(b, m, 12);
    cels_rec_end(b);
    cels_rec_begin(b, CS_REC_REGION);
    cels_put_u32(b, 0);
    float p[7] = {1, 1, 1, 1, 1, 1, 1};
    cels_put_f32s(b, p, 7);
    cels_rec_end(b);
}

static void rec_square(cels_buf *b, float x)
{
    cels_rec_begin(b, CS_REC_CONTOUR);
    cels_put_u32(b, 1);
    cels_put_u32(b, 4);
    cels_put_u32(b, 0);
    float pts[12] = {x, 10, 1, x + 20, 10, 1, x + 20, 30, 1, x, 30, 1};
    cels_put_f32s(b, pts, 12);
    cels_rec_end(b);
}

static void good_body(cels_buf *b)
{
    rec_scene(b);
    rec_cel_region(b);
    rec_square(b, 10);
    cels_rec_commit(b);
}

/* Decodes one crafted transaction and expects one error of `want`. */
static void expect_error(const char *name, void (*fill)(cels_buf *), cs_status want)
{
    cels_buf b;
    one_txn(&b, fill);
    result r;
    decode(b.data, b.len, 0, NULL, &r);
    CHECK(r.commits == 0 && r.errors == 1 && r.err[0].status == want && r.err[0].offset == 0,
          "%s: %d commits %d errors, first %s (want %s)", name, r.commits, r.errors,
          r.errors ? status_name(r.err[0].status) : "-", status_name(want));
    /* Followed by a good transaction, the decoder recovers. */
    cels_buf g;
    one_txn(&g, good_body);
    cels_put_bytes(&b, g.data, g.len);
    decode(b.data, b.len, 1, NULL, &r);
    CHECK(r.commits == 1 && r.errors == 1 && r.scene && r.scene->contour_count == 1,
          "%s then a good transaction: %d commits %d errors", name, r.commits, r.errors);
    cels_buf_free(&b);
    cels_buf_free(&g);
}

static void f_huge_record_len(cels_buf *b)
{
    rec_scene(b);
    cels_put_u16(b, CS_REC_CEL);
    cels_put_u32(b, 0xFFFFFFF0u);
    cels_put_u32(b, 0);
    cels_rec_commit(b);
}
static void f_huge_count(cels_buf *b)
{
    rec_scene(b);
    rec_cel_region(b);
    cels_rec_begin(b, CS_REC_CONTOUR);
    cels_put_u32(b, 1);
    cels_put_u32(b, 0xFFFFFFFFu);
    cels_put_u32(b, 0);
    float pts[12] = {0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
    cels_put_f32s(b, pts, 12);
    cels_rec_end(b);
    cels_rec_commit(b);
}
static void f_count_mismatch(cels_buf *b)
{
    rec_scene(b);
    rec_cel_region(b);
    cels_rec_begin(b, CS_REC_CONTOUR);
    cels_put_u32(b, 1);
    cels_put_u32(b, 5); /* says 5 points, carries 4 */
    cels_put_u32(b, 0);
    float pts[12] = {0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
    cels_put_f32s(b, pts, 12);
    cels_rec_end(b);
    cels_rec_commit(b);
}
static void f_huge_keys(cels_buf *b)
{
    good_body(b);
    b->len -= 6; /* drop the commit again */
    cels_rec_begin(b, CS_REC_TRACK);
    cels_put_u32(b, CS_TRACK_TRANSFORM);
    cels_put_u32(b, 0);
    cels_put_u32(b, 0);
    cels_put_u32(b, 0x40000000u);
    float k[7] = {0, 1, 0, 0, 1, 0, 0};
    cels_put_f32s(b, k, 7);
    cels_rec_end(b);
    cels_rec_commit(b);
}
static void f_huge_index(cels_buf *b)
{
    good_body(b);
    b->len -= 6;
    cels_rec_begin(b, CS_REC_CEL_TRANSFORM);
    cels_put_u32(b, 0xFFFFFFFFu);
    float m[6] = {1, 0, 0, 1, 0, 0};
    cels_put_f32s(b, m, 6);
    cels_rec_end(b);
    cels_rec_commit(b);
}
static void f_huge_degree(cels_buf *b)
{
    rec_scene(b);
    rec_cel_region(b);
    cels_rec_begin(b, CS_REC_CONTOUR);
    cels_put_u32(b, 0x80000001u);
    cels_put_u32(b, 4);
    cels_put_u32(b, 0);
    float pts[12] = {0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
    cels_put_f32s(b, pts, 12);
    cels_rec_end(b);
    cels_rec_commit(b);
}
static void f_nan_point(cels_buf *b)
{
    rec_scene(b);
    rec_cel_region(b);
    cels_rec_begin(b, CS_REC_CONTOUR);
    cels_put_u32(b, 1);
    cels_put_u32(b, 4);
    cels_put_u32(b, 0);
    float pts[12] = {0, 0, 1, 1, 0, 1, 1, NAN, 1, 0, 1, 1};
    cels_put_f32s(b, pts, 12);
    cels_rec_end(b);
    cels_rec_commit(b);
}
static void f_inf_transform(cels_buf *b)
{
    rec_scene(b);
    cels_rec_begin(b, CS_REC_CEL);
    cels_put_u32(b, 0);
    float m[12] = {1, 0, 0, 1, INFINITY, 0, 1, 1, 1, 0, 0, 0};
    cels_put_f32s(b, m, 12);
    cels_rec_end(b);
    cels_rec_commit(b);
}
static void f_nan_paint(cels_buf *b)
{
    rec_scene(b);
    rec_cel_region(b);
    b->len -= 4; /* beta */
    cels_put_f32(b, NAN);
    cels_rec_commit(b);
}
static void f_nan_canvas(cels_buf *b)
{
    cels_rec_begin(b, CS_REC_SCENE);
    cels_put_f32(b, NAN);
    cels_put_f32(b, 100);
    cels_rec_end(b);
    cels_rec_commit(b);
}
static void f_nan_key_time(cels_buf *b)
{
    good_body(b);
    b->len -= 6;
    cels_rec_begin(b, CS_REC_TRACK);
    cels_put_u32(b, CS_TRACK_TRANSFORM);
    cels_put_u32(b, 0);
    cels_put_u32(b, 0);
    cels_put_u32(b, 2);
    float k[14] = {0, 1, 0, 0, 1, 0, 0, NAN, 1, 0, 0, 1, 5, 0};
    cels_put_f32s(b, k, 14);
    cels_rec_end(b);
    cels_rec_commit(b);
}
static void f_inf_key_value(cels_buf *b)
{
    good_body(b);
    b->len -= 6;
    cels_rec_begin(b, CS_REC_TRACK);
    cels_put_u32(b, CS_TRACK_POINTS);
    cels_put_u32(b, 0);
    cels_put_u32(b, 1);
    cels_put_u32(b, 1);
    float k[13] = {0, 10, 10, 1, 30, 10, 1, 30, -INFINITY, 1, 10, 30, 1};
    cels_put_f32s(b, k, 13);
    cels_rec_end(b);
    cels_rec_commit(b);
}
static void f_key_order(cels_buf *b)
{
    good_body(b);
    b->len -= 6;
    cels_rec_begin(b, CS_REC_TRACK);
    cels_put_u32(b, CS_TRACK_TRANSFORM);
    cels_put_u32(b, 0);
    cels_put_u32(b, 0);
    cels_put_u32(b, 2);
    float k[14] = {1, 1, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 5, 0};
    cels_put_f32s(b, k, 14);
    cels_rec_end(b);
    cels_rec_commit(b);
}
static void f_range(cels_buf *b)
{
    rec_scene(b);
    rec_cel_region(b);
    rec_square(b, 2e7f);
    cels_rec_commit(b);
}
static void f_unknown_class(cels_buf *b)
{
    good_body(b);
    b->len -= 6;
    cels_rec_begin(b, 0x0700);
    cels_put_u32(b, 1);
    cels_rec_end(b);
    cels_rec_commit(b);
}
static void f_no_commit(cels_buf *b)
{
    rec_scene(b);
    rec_cel_region(b);
}
static void f_after_commit(cels_buf *b)
{
    good_body(b);
    rec_square(b, 40);
}
static void f_patch_first(cels_buf *b)
{
    rec_cel_region(b);
    cels_rec_commit(b);
}
static void f_scene_late(cels_buf *b)
{
    rec_scene(b);
    rec_scene(b);
    cels_rec_commit(b);
}
static void f_reserved_flags(cels_buf *b)
{
    rec_scene(b);
    cels_rec_begin(b, CS_REC_CEL);
    cels_put_u32(b, 0x80);
    float m[12] = {1, 0, 0, 1, 0, 0, 1, 1, 1, 0, 0, 0};
    cels_put_f32s(b, m, 12);
    cels_rec_end(b);
    cels_rec_commit(b);
}
static void f_short_record(cels_buf *b)
{
    rec_scene(b);
    cels_rec_begin(b, CS_REC_LIGHTS);
    cels_put_f32(b, 1);
    cels_rec_end(b);
    cels_rec_commit(b);
}
static void f_long_record(cels_buf *b)
{
    rec_scene(b);
    cels_rec_begin(b, CS_REC_CANVAS);
    float v[3] = {10, 10, 10};
    cels_put_f32s(b, v, 3);
    cels_rec_end(b);
    cels_rec_commit(b);
}
static void f_ends_in_header(cels_buf *b)
{
    good_body(b);
    cels_put_u16(b, CS_REC_PAD);
}
static void f_zero_keys(cels_buf *b)
{
    good_body(b);
    b->len -= 6;
    cels_rec_begin(b, CS_REC_TRACK);
    cels_put_u32(b, CS_TRACK_TRANSFORM);
    cels_put_u32(b, 0);
    cels_put_u32(b, 0);
    cels_put_u32(b, 0);
    cels_rec_end(b);
    cels_rec_commit(b);
}
static void f_bad_ease(cels_buf *b)
{
    good_body(b);
    b->len -= 6;
    cels_rec_begin(b, CS_REC_TRACK);
    cels_put_u32(b, CS_TRACK_TRANSFORM);
    cels_put_u32(b, 0);
    cels_put_u32(b, 7);
    cels_put_u32(b, 1);
    float k[7] = {0, 1, 0, 0, 1, 0, 0};
    cels_put_f32s(b, k, 7);
    cels_rec_end(b);
    cels_rec_commit(b);
}
/* A cel its own group. */
static void f_parent_self(cels_buf *b)
{
    good_body(b);
    b->len -= 6;
    cels_rec_begin(b, CS_REC_CEL_PARENT);
    cels_put_u32(b, 0);
    cels_put_u32(b, 0);
    cels_rec_end(b);
    cels_rec_commit(b);
}
/* A group that does not exist. */
static void f_parent_missing(cels_buf *b)
{
    good_body(b);
    b->len -= 6;
    cels_rec_begin(b, CS_REC_CEL_PARENT);
    cels_put_u32(b, 0);
    cels_put_u32(b, 3);
    cels_rec_end(b);
    cels_rec_commit(b);
}
/* A cubic key whose easing x1 leaves 0..1. */
static void f_bad_cubic(cels_buf *b)
{
    good_body(b);
    b->len -= 6;
    cels_rec_begin(b, CS_REC_TRACK);
    cels_put_u32(b, CS_TRACK_TRS);
    cels_put_u32(b, 0);
    cels_put_u32(b, CS_EASE_CUBIC);
    cels_put_u32(b, 1);
    float k[15] = {0, 1.5f, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 1};
    cels_put_f32s(b, k, 15);
    cels_rec_end(b);
    cels_rec_commit(b);
}
static void f_bad_target(cels_buf *b)
{
    good_body(b);
    b->len -= 6;
    cels_rec_begin(b, CS_REC_TRACK);
    cels_put_u32(b, CS_TRACK_PAINT);
    cels_put_u32(b, 3);
    cels_put_u32(b, 0);
    cels_put_u32(b, 1);
    float k[8] = {0, 1, 1, 1, 1, 1, 1, 1};
    cels_put_f32s(b, k, 8);
    cels_rec_end(b);
    cels_rec_commit(b);
}
static void f_bad_rule(cels_buf *b)
{
    rec_scene(b);
    rec_cel_region(b);
    b->data[b->len - 32] = 9; /* fill rule 9 */
    cels_rec_commit(b);
}

/* REGION_FUNC with raw fields: a two-stop linear gradient unless changed. */
typedef struct {
    uint32_t field, kind, spread, cols, stops;
    float geom[6];
    float stop[2][4];
} wire_func;

static wire_func good_func(void)
{
    wire_func f = {0, CS_FUNC_LINEAR, 0, 1, 2, {0, 0, 40, 0, 0, 0},
                   {{0, 1, 0, 0}, {1, 0, 0, 1}}};
    return f;
}

static void rec_func(cels_buf *b, const wire_func *f, uint32_t carried)
{
    cels_rec_begin(b, CS_REC_REGION_FUNC);
    cels_put_u32(b, f->field);
    cels_put_u32(b, f->kind);
    cels_put_u32(b, f->spread);
    cels_put_u32(b, f->cols);
    cels_put_u32(b, f->stops);
    cels_put_f32s(b, f->geom, 6);
    for (uint32_t i = 0; i < carried; i++)
        cels_put_f32s(b, f->stop[i < 2 ? i : 1], 4);
    cels_rec_end(b);
}

static void rec_csg(cels_buf *b, const int32_t *tok, uint32_t n, uint32_t len)
{
    cels_rec_begin(b, CS_REC_REGION_CSG);
    cels_put_u32(b, len);
    for (uint32_t i = 0; i < n; i++)
        cels_put_u32(b, (uint32_t)tok[i]);
    cels_rec_end(b);
}

static void rec_operand(cels_buf *b, uint32_t op)
{
    cels_rec_begin(b, CS_REC_CONTOUR_OPERAND);
    cels_put_u32(b, op);
    cels_rec_end(b);
}

/* SCENE, a cel with a region, `f` as the region's function, a square, COMMIT. */
static void func_body(cels_buf *b, const wire_func *f)
{
    rec_scene(b);
    rec_cel_region(b);
    rec_func(b, f, f->stops);
    rec_square(b, 10);
    cels_rec_commit(b);
}
static void f_func_field(cels_buf *b)
{
    wire_func f = good_func();
    f.field = 3;
    func_body(b, &f);
}
static void f_func_no_stops(cels_buf *b)
{
    wire_func f = good_func();
    f.stops = 0;
    func_body(b, &f);
}
static void f_func_many_stops(cels_buf *b)
{
    wire_func f = good_func();
    f.stops = CS_CFG_MAX_STOPS + 1;
    func_body(b, &f);
}
static void f_func_huge_stops(cels_buf *b)
{
    wire_func f = good_func();
    f.stops = 0xFFFFFFFFu;
    rec_scene(b);
    rec_cel_region(b);
    rec_func(b, &f, 2);
    cels_rec_commit(b);
}
static void f_func_kind(cels_buf *b)
{
    wire_func f = good_func();
    f.kind = 0x101; /* would be LINEAR if cut to a byte */
    func_body(b, &f);
}
static void f_func_spread(cels_buf *b)
{
    wire_func f = good_func();
    f.spread = 0x100;
    func_body(b, &f);
}
static void f_func_degenerate(cels_buf *b)
{
    wire_func f = good_func();
    f.geom[2] = 0; /* p1 == p0 */
    func_body(b, &f);
}
static void f_func_nan_geom(cels_buf *b)
{
    wire_func f = good_func();
    f.geom[1] = NAN;
    func_body(b, &f);
}
static void f_func_inf_stop(cels_buf *b)
{
    wire_func f = good_func();
    f.stop[1][2] = INFINITY;
    func_body(b, &f);
}
static void f_func_stop_range(cels_buf *b)
{
    wire_func f = good_func();
    f.stop[0][1] = 1.5f;
    func_body(b, &f);
}
static void f_func_stop_order(cels_buf *b)
{
    wire_func f = good_func();
    f.stop[0][0] = 0.8f;
    f.stop[1][0] = 0.2f;
    func_body(b, &f);
}
static void f_func_map_cols(cels_buf *b)
{
    wire_func f = good_func();
    f.kind = CS_FUNC_MAP;
    f.cols = 0x102; /* would be 2 if cut to a byte */
    f.geom[0] = 0, f.geom[1] = 0, f.geom[2] = 10, f.geom[3] = 0, f.geom[4] = 0, f.geom[5] = 10;
    func_body(b, &f);
}
static void f_func_short(cels_buf *b)
{
    wire_func f = good_func();
    rec_scene(b);
    rec_cel_region(b);
    rec_func(b, &f, 1); /* says 2 stops, carries 1 */
    cels_rec_commit(b);
}
static void f_func_no_region(cels_buf *b)
{
    wire_func f = good_func();
    rec_scene(b);
    rec_func(b, &f, 2);
    cels_rec_commit(b);
}
static void f_csg_empty(cels_buf *b)
{
    rec_scene(b);
    rec_cel_region(b);
    rec_csg(b, NULL, 0, 0);
    cels_rec_commit(b);
}
static void f_csg_long(cels_buf *b)
{
    int32_t t[17];
    for (int i = 0; i < 17; i++)
        t[i] = i % 2 ? CS_CSG_UNION : 0;
    rec_scene(b);
    rec_cel_region(b);
    rec_csg(b, t, 17, 17);
    cels_rec_commit(b);
}
static void f_csg_huge_len(cels_buf *b)
{
    int32_t t[1] = {0};
    rec_scene(b);
    rec_cel_region(b);
    rec_csg(b, t, 1, 0x80000001u);
    cels_rec_commit(b);
}
static void f_csg_operand(cels_buf *b)
{
    int32_t t[3] = {0, CS_CFG_MAX_OPERANDS, CS_CSG_UNION};
    rec_scene(b);
    rec_cel_region(b);
    rec_csg(b, t, 3, 3);
    cels_rec_commit(b);
}
static void f_csg_operator(cels_buf *b)
{
    int32_t t[3] = {0, 1, -5};
    rec_scene(b);
    rec_cel_region(b);
    rec_csg(b, t, 3, 3);
    cels_rec_commit(b);
}
static void f_csg_wrap(cels_buf *b)
{
    int32_t t[3] = {0, 1, (int32_t)0x80000001u};
    rec_scene(b);
    rec_cel_region(b);
    rec_csg(b, t, 3, 3);
    cels_rec_commit(b);
}
static void f_csg_leftover(cels_buf *b)
{
    int32_t t[2] = {0, 1};
    rec_scene(b);
    rec_cel_region(b);
    rec_csg(b, t, 2, 2);
    cels_rec_commit(b);
}
static void f_csg_underflow(cels_buf *b)
{
    int32_t t[2] = {0, CS_CSG_XOR};
    rec_scene(b);
    rec_cel_region(b);
    rec_csg(b, t, 2, 2);
    cels_rec_commit(b);
}
static void f_csg_no_region(cels_buf *b)
{
    int32_t t[1] = {0};
    rec_scene(b);
    rec_csg(b, t, 1, 1);
    cels_rec_commit(b);
}
static void f_operand_range(cels_buf *b)
{
    rec_scene(b);
    rec_cel_region(b);
    rec_square(b, 10);
    rec_operand(b, CS_CFG_MAX_OPERANDS);
    cels_rec_commit(b);
}
static void f_operand_huge(cels_buf *b)
{
    rec_scene(b);
    rec_cel_region(b);
    rec_square(b, 10);
    rec_operand(b, 0xFFFFFFFFu);
    cels_rec_commit(b);
}
static void f_operand_no_contour(cels_buf *b)
{
    rec_scene(b);
    rec_cel_region(b);
    rec_operand(b, 1);
    cels_rec_commit(b);
}
static void f_operand_long(cels_buf *b)
{
    rec_scene(b);
    rec_cel_region(b);
    rec_square(b, 10);
    cels_rec_begin(b, CS_REC_CONTOUR_OPERAND);
    cels_put_u32(b, 1);
    cels_put_u32(b, 1);
    cels_rec_end(b);
    cels_rec_commit(b);
}
/* A function on a region of a cel moved away from the end of the store. */
static void f_func_moved_cel(cels_buf *b)
{
    wire_func f = good_func();
    rec_scene(b);
    rec_cel_region(b);
    rec_square(b, 10);
    rec_cel_region(b);
    rec_square(b, 40);
    cels_rec_begin(b, CS_REC_CEL_MOVE);
    cels_put_u32(b, 1);
    cels_put_u32(b, 0);
    cels_rec_end(b);
    rec_func(b, &f, 2);
    cels_rec_commit(b);
}
/* One function more than the store holds. */
static void f_func_cap(cels_buf *b)
{
    wire_func f = good_func();
    rec_scene(b);
    cels_rec_begin(b, CS_REC_CEL);
    cels_put_u32(b, 0);
    float m[12] = {1, 0, 0, 1, 0, 0, 1, 1, 1, 0, 0, 0};
    cels_put_f32s(b, m, 12);
    cels_rec_end(b);
    for (int i = 0; i <= CS_CFG_MAX_FUNCS; i++) {
        if (i % 3 == 0) {
            cels_rec_begin(b, CS_REC_REGION);
            cels_put_u32(b, 0);
            float p[7] = {1, 1, 1, 1, 1, 1, 1};
            cels_put_f32s(b, p, 7);
            cels_rec_end(b);
        }
        f.field = (uint32_t)(i % 3);
        rec_func(b, &f, 2);
    }
    cels_rec_commit(b);
}

static void test_crafted_beta(void)
{
    expect_error("function field 3", f_func_field, CS_ERR_FUNC);
    expect_error("function without stops", f_func_no_stops, CS_ERR_FUNC);
    expect_error("function with 17 stops", f_func_many_stops, CS_ERR_FUNC);
    expect_error("function with 2^32-1 stops", f_func_huge_stops, CS_ERR_FUNC);
    expect_error("function kind 0x101", f_func_kind, CS_ERR_FUNC);
    expect_error("function spread 0x100", f_func_spread, CS_ERR_FUNC);
    expect_error("degenerate gradient", f_func_degenerate, CS_ERR_FUNC);
    expect_error("NaN gradient geometry", f_func_nan_geom, CS_ERR_NONFINITE);
    expect_error("Inf stop value", f_func_inf_stop, CS_ERR_NONFINITE);
    expect_error("stop value 1.5", f_func_stop_range, CS_ERR_PAINT);
    expect_error("stop offsets decreasing", f_func_stop_order, CS_ERR_FUNC);
    expect_error("map columns 0x102", f_func_map_cols, CS_ERR_FUNC);
    expect_error("function record short of its stops", f_func_short, CS_ERR_STREAM_RECORD);
    expect_error("function before any region", f_func_no_region, CS_ERR_STATE);
    expect_error("function on a moved-away cel", f_func_moved_cel, CS_ERR_STATE);
    expect_error("one function more than the store holds", f_func_cap, CS_ERR_CAP_FUNCS);
    expect_error("empty CSG program", f_csg_empty, CS_ERR_CSG);
    expect_error("CSG program of 17 tokens", f_csg_long, CS_ERR_CSG);
    expect_error("CSG length 0x80000001", f_csg_huge_len, CS_ERR_CSG);
    expect_error("CSG operand 8", f_csg_operand, CS_ERR_CSG);
    expect_error("CSG operator -5", f_csg_operator, CS_ERR_CSG);
    expect_error("CSG token 0x80000001", f_csg_wrap, CS_ERR_CSG);
    expect_error("CSG program leaves two values", f_csg_leftover, CS_ERR_CSG);
    expect_error("CSG operator without operands", f_csg_underflow, CS_ERR_CSG);
    expect_error("CSG before any region", f_csg_no_region, CS_ERR_STATE);
    expect_error("operand 8", f_operand_range, CS_ERR_CSG);
    expect_error("operand 0xFFFFFFFF", f_operand_huge, CS_ERR_CSG);
    expect_error("operand before any contour", f_operand_no_contour, CS_ERR_STATE);
    expect_error("operand record too long", f_operand_long, CS_ERR_STREAM_RECORD);

    /* The fault is located: a bad stop names its cel, region and stop. */
    cels_buf b;
    one_txn(&b, f_func_stop_range);
    result r;
    decode(b.data, b.len, 1, NULL, &r);
    size_t func_rec = 16 + (6 + 8) + (6 + 52) + (6 + 32);
    CHECK(r.errors == 1 && r.err[0].at == func_rec && r.err[0].where.cel == 0 &&
              r.err[0].where.region == 0 && r.err[0].where.item == 0,
          "bad stop located at record %llu cel %d region %d item %d (want %zu 0 0 0)",
          r.errors ? (unsigned long long)r.err[0].at : 0ull, r.err[0].where.cel,
          r.err[0].where.region, r.err[0].where.item, func_rec);
    cels_buf_free(&b);
    /* A bad token names its index. */
    one_txn(&b, f_csg_operator);
    decode(b.data, b.len, 0, NULL, &r);
    CHECK(r.errors == 1 && r.err[0].where.item == 2, "bad CSG token located: item %d (want 2)",
          r.err[0].where.item);
    cels_buf_free(&b);

    /* Setting a field twice replaces its function in place, as the call does. */
    cels_buf_init(&b);
    cels_txn_begin(&b);
    rec_scene(&b);
    rec_cel_region(&b);
    wire_func f = good_func();
    rec_func(&b, &f, 2);
    f.geom[2] = 80;
    rec_func(&b, &f, 2);
    rec_square(&b, 10);
    cels_rec_commit(&b);
    cels_txn_end(&b);
    decode(b.data, b.len, 1, NULL, &r);
    CHECK(r.commits == 1 && r.scene && r.scene->func_count == 1 &&
              r.scene->regions[0].func[0] == 1 && r.scene->funcs[0].geom[2] == 80,
          "a field set twice: %d commits, %u functions", r.commits,
          r.scene ? r.scene->func_count : 0);
    cels_buf_free(&b);
}

static void test_crafted(void)
{
    expect_error("record length 0xFFFFFFF0", f_huge_record_len, CS_ERR_STREAM_RECORD);
    expect_error("point count 0xFFFFFFFF", f_huge_count, CS_ERR_CAP_POINTS);
    expect_error("point count beyond the record", f_count_mismatch, CS_ERR_STREAM_RECORD);
    expect_error("key count 2^30", f_huge_keys, CS_ERR_CAP_KEYS);
    expect_error("cel index 0xFFFFFFFF", f_huge_index, CS_ERR_INDEX);
    expect_error("degree 0x80000001", f_huge_degree, CS_ERR_DEGREE);
    expect_error("NaN control point", f_nan_point, CS_ERR_NONFINITE);
    expect_error("Inf in a transform", f_inf_transform, CS_ERR_NONFINITE);
    expect_error("NaN beta", f_nan_paint, CS_ERR_NONFINITE);
    expect_error("NaN canvas", f_nan_canvas, CS_ERR_NONFINITE);
    expect_error("NaN key time", f_nan_key_time, CS_ERR_NONFINITE);
    expect_error("-Inf key value", f_inf_key_value, CS_ERR_NONFINITE);
    expect_error("keys out of order", f_key_order, CS_ERR_KEY_ORDER);
    expect_error("coordinate 2e7", f_range, CS_ERR_RANGE);
    expect_error("unknown record class", f_unknown_class, CS_ERR_STREAM_RECORD);
    expect_error("no COMMIT", f_no_commit, CS_ERR_STREAM_RECORD);
    expect_error("record after COMMIT", f_after_commit, CS_ERR_STREAM_RECORD);
    expect_error("patch before any scene", f_patch_first, CS_ERR_STATE);
    expect_error("SCENE not first", f_scene_late, CS_ERR_STREAM_RECORD);
    expect_error("reserved flag bits", f_reserved_flags, CS_ERR_STREAM_RECORD);
    expect_error("record shorter than its fields", f_short_record, CS_ERR_STREAM_RECORD);
    expect_error("record longer than its fields", f_long_record, CS_ERR_STREAM_RECORD);
    expect_error("body ends in a record header", f_ends_in_header, CS_ERR_STREAM_RECORD);
    expect_error("track without keys", f_zero_keys, CS_ERR_STREAM_RECORD);
    expect_error("ease 7", f_bad_ease, CS_ERR_TRACK);
    expect_error("cel its own parent", f_parent_self, CS_ERR_GROUP);
    expect_error("parent cel missing", f_parent_missing, CS_ERR_INDEX);
    expect_error("cubic easing x1 1.5", f_bad_cubic, CS_ERR_RANGE);
    expect_error("track on a missing region", f_bad_target, CS_ERR_INDEX);
    expect_error("fill rule 9", f_bad_rule, CS_ERR_FILL_RULE);

    /* An empty transaction has no COMMIT; the next one is not swallowed. */
    cels_buf b;
    cels_buf_init(&b);
    cels_txn_begin(&b);
    cels_txn_end(&b);
    size_t next = b.len;
    cels_buf g0;
    one_txn(&g0, good_body);
    cels_put_bytes(&b, g0.data, g0.len);
    result r;
    decode(b.data, b.len, 1, NULL, &r);
    CHECK(r.commits == 1 && r.errors == 1 && r.err[0].status == CS_ERR_STREAM_RECORD &&
              r.err[0].offset == 0 && r.err[0].at == 16 && next == 20,
          "empty transaction: %d commits %d errors (%s at %llu)", r.commits, r.errors,
          r.errors ? r.err[0].what : "-", r.errors ? (unsigned long long)r.err[0].at : 0ull);
    cels_buf_free(&b);
    cels_buf_free(&g0);

    /* The fault offset of a validation error is its record's. */
    one_txn(&b, f_nan_point);
    decode(b.data, b.len, 1, NULL, &r);
    size_t contour_rec = 16 + (6 + 8) + (6 + 52) + (6 + 32);
    CHECK(r.errors == 1 && r.err[0].at == contour_rec && r.err[0].where.cel == 0 &&
              r.err[0].where.region == 0 && r.err[0].where.contour == 0 &&
              r.err[0].where.item == 2,
          "NaN point located at record %llu cel %d region %d contour %d item %d (want %zu 0 0 0 2)",
          r.errors ? (unsigned long long)r.err[0].at : 0ull, r.err[0].where.cel,
          r.err[0].where.region, r.err[0].where.contour, r.err[0].where.item, contour_rec);
    cels_buf_free(&b);

    /* An oversized transaction (CRC-valid header) is skipped, the next one found. */
    cels_buf_init(&b);
    cels_txn_begin(&b);
    cels_put_u32(&b, 0);
    cels_txn_end(&b);
    uint8_t *h = b.data;
    uint32_t big = 0xFFFFFF00u;
    memcpy(h + 8, (uint8_t[]){(uint8_t)big, (uint8_t)(big >> 8), (uint8_t)(big >> 16),
                              (uint8_t)(big >> 24)},
           4);
    uint32_t c = cs_crc32(0, h, 12);
    memcpy(h + 12, (uint8_t[]){(uint8_t)c, (uint8_t)(c >> 8), (uint8_t)(c >> 16), (uint8_t)(c >> 24)},
           4);
    size_t good_at = b.len;
    cels_buf g;
    one_txn(&g, good_body);
    cels_put_bytes(&b, g.data, g.len);
    decode(b.data, b.len, 2, NULL, &r);
    CHECK(r.commits == 1 && r.errors == 1 && r.err[0].status == CS_ERR_STREAM_TOO_BIG &&
              r.err[0].offset == 0,
          "oversized transaction: %d commits %d errors (%s)", r.commits, r.errors,
          r.errors ? status_name(r.err[0].status) : "-");
    (void)good_at;
    cels_buf_free(&b);

    /* Unknown types of known classes are skipped: same scene as without them. */
    cels_buf_init(&b);
    cels_txn_begin(&b);
    rec_scene(&b);
    cels_rec_begin(&b, 0x01FE);
    cels_put_u32(&b, 0xdeadbeef);
    cels_rec_end(&b);
    rec_cel_region(&b);
    cels_rec_begin(&b, 0x04FF);
    cels_rec_end(&b);
    cels_rec_begin(&b, CS_REC_PAD);
    for (int i = 0; i < 100; i++)
        cels_put_u8(&b, (uint8_t)i);
    cels_rec_end(&b);
    rec_square(&b, 10);
    cels_rec_begin(&b, 0x0042);
    cels_put_u32(&b, 1);
    cels_rec_end(&b);
    cels_rec_commit(&b);
    cels_txn_end(&b);
    decode(b.data, b.len, 1, NULL, &r);
    result r2;
    cs_scene *plain = new_scene();
    decode(g.data, g.len, 0, NULL, &r2);
    cs_scene_copy(plain, r2.scene);
    decode(b.data, b.len, 1, NULL, &r);
    char why[128] = "";
    CHECK(r.commits == 1 && r.errors == 0 && r.scene && scene_equal(plain, r.scene, why, sizeof why),
          "unknown subtypes skipped: %d commits %d errors %s", r.commits, r.errors, why);
    cels_buf_free(&b);
    cels_buf_free(&g);
    free(plain);

    /* Versions: a newer major is refused (stream header and transaction). */
    cels_buf_init(&b);
    cels_stream_header(&b);
    b.data[4] = 2;
    uint32_t hc = cs_crc32(0, b.data, 12);
    memcpy(b.data + 12, (uint8_t[]){(uint8_t)hc, (uint8_t)(hc >> 8), (uint8_t)(hc >> 16),
                                     (uint8_t)(hc >> 24)},
           4);
    size_t txn2 = b.len;
    one_txn(&g, good_body);
    cels_put_bytes(&b, g.data, g.len);
    b.data[txn2 + 4] = 2;
    reseal(b.data, txn2);
    cels_put_bytes(&b, g.data, g.len);
    decode(b.data, b.len, 1, NULL, &r);
    CHECK(r.commits == 1 && r.errors == 2 && r.err[0].status == CS_ERR_STREAM_VERSION &&
              r.err[0].offset == 0 && r.err[1].status == CS_ERR_STREAM_VERSION &&
              r.err[1].offset == txn2,
          "major version 2: %d commits %d errors", r.commits, r.errors);
    /* A newer minor is accepted. */
    b.data[txn2 + 4] = 1;
    b.data[txn2 + 5] = 9;
    reseal(b.data, txn2);
    decode(b.data, b.len, 1, NULL, &r);
    CHECK(r.commits == 2 && r.errors == 1, "minor version 9 accepted: %d commits %d errors",
          r.commits, r.errors);
    cels_buf_free(&b);
    cels_buf_free(&g);
}

static void test_random_and_resync(void)
{
    cs_scene *s = new_scene();
    build_demo(s);
    cels_buf good;
    encode(s, &good, false);
    /* Pure random bytes: never a commit, never a crash; errors reported. */
    bulk bk = {0};
    int runs = 2000;
    uint8_t *d = malloc(8192 + good.len);
    for (int i = 0; i < runs; i++) {
        size_t n = 1 + rnd() % 8192;
        for (size_t k = 0; k < n; k++)
            d[k] = (uint8_t)rnd();
        result r;
        decode(d, n, 2, NULL, &r);
        if (r.commits != 0 || r.scene || (n >= 16 && r.errors == 0))
            bulk_fail(&bk, "random bytes committed or went unreported");
    }
    bulk_done(&bk, "random bytes", runs);
    /* Garbage, then a valid transaction: resync, one error at offset 0. */
    bulk bk2 = {0};
    char msg[200];
    for (int i = 0; i < 300; i++) {
        size_t n = 1 + rnd() % 4096;
        for (size_t k = 0; k < n; k++)
            d[k] = (uint8_t)rnd();
        memcpy(d + n, good.data, good.len);
        result r;
        decode(d, n + good.len, i % 4, NULL, &r);
        char why[128] = "";
        if (!(r.commits == 1 && r.errors == 1 && r.err[0].status == CS_ERR_STREAM_SYNC &&
              r.err[0].offset == 0 && r.skipped == n && r.scene &&
              scene_equal(s, r.scene, why, sizeof why))) {
            snprintf(msg, sizeof msg, "%zu garbage bytes: %d commits %d errors skipped %llu %s", n,
                     r.commits, r.errors, (unsigned long long)r.skipped, why);
            bulk_fail(&bk2, msg);
        }
    }
    bulk_done(&bk2, "resync after garbage", 300);
    /* A transaction cut short by a restarted sender: the new one still commits. */
    cels_buf b;
    cels_buf_init(&b);
    cels_put_bytes(&b, good.data, good.len / 2);
    size_t restart = b.len;
    cels_put_bytes(&b, good.data, good.len);
    result r;
    decode(b.data, b.len, 1, NULL, &r);
    char why[128] = "";
    CHECK(r.commits == 1 && r.errors == 1 && r.err[0].status == CS_ERR_STREAM_TRUNCATED &&
              r.err[0].offset == 0 && r.err[0].at == restart && r.scene &&
              scene_equal(s, r.scene, why, sizeof why),
          "cut short by a restart: %d commits %d errors (%s offset %llu at %llu) %s", r.commits,
          r.errors, r.errors ? status_name(r.err[0].status) : "-",
          r.errors ? (unsigned long long)r.err[0].offset : 0ull,
          r.errors ? (unsigned long long)r.err[0].at : 0ull, why);
    cels_buf_free(&b);
    cels_buf_free(&good);
    free(d);
    free(s);
}

/* A valid stream then a damaged transaction: the valid scene renders, damage reported. */
static void test_valid_then_damaged(void)
{
    cs_scene *s = new_scene(), *other = new_scene();
    build_demo(s);
    cs_scene_copy(other, s);
    cs_error e;
    cs_affine m = {1, 0, 0, 1, 5, 5};
    cs_scene_set_transform(other, 1, &m, &e);
    cels_buf b;
    encode(s, &b, true);
    size_t second = b.len;
    cels_encode_scene(&b, other);
    b.data[second + 40] ^= 0x10;
    result r;
    decode(b.data, b.len, 2, NULL, &r);
    char why[128] = "";
    CHECK(r.commits == 1 && r.errors == 1 && r.err[0].status == CS_ERR_STREAM_CRC &&
              r.err[0].offset == second && r.err[0].at == b.len - 4,
          "damaged second transaction: %d commits %d errors (%s at %llu, want %zu)", r.commits,
          r.errors, r.errors ? status_name(r.err[0].status) : "-",
          r.errors ? (unsigned long long)r.err[0].offset : 0ull, second);
    CHECK(r.scene && scene_equal(s, r.scene, why, sizeof why) && renders_equal(s, r.scene),
          "the valid scene stays on display: %s", why);
    /* Feeding pauses at a commit until the swap. */
    cs_scene_copy(store_a, s);
    cs_stream_init(&st, store_a, false, store_b);
    size_t used;
    cs_stream_event ev = cs_stream_feed(&st, b.data, b.len, &used);
    CHECK(ev == CS_STREAM_COMMIT && used == second, "commit after %zu of %zu bytes (want %zu)",
          used, b.len, second);
    CHECK(cs_stream_scene(&st) == NULL, "nothing on display before the swap");
    size_t used2;
    ev = cs_stream_feed(&st, b.data + used, b.len - used, &used2);
    CHECK(ev == CS_STREAM_COMMIT && used2 == 0, "no byte consumed until the swap");
    CHECK(cs_stream_swap(&st) == CS_OK && cs_stream_scene(&st) == store_b,
          "swap shows the new scene");
    CHECK(cs_stream_swap(&st) == CS_ERR_STATE, "second swap without a commit refused");
    cels_buf_free(&b);
    free(s);
    free(other);
}

/*
 * cs_stream_gap: a link that lost `lost` bytes at offset k of two
 * transactions. For every k: a transaction the gap or the lost bytes touch
 * never commits, the one on display before stays, the other commits intact;
 * a gap inside a transaction's body or trailer is reported as
 * CS_ERR_STREAM_GAP at k (the offset counts the bytes fed), for the
 * transaction's own offset; nothing is ever pieced together across it.
 */
static void gap_run(const uint8_t *d, size_t n, size_t k, size_t lost, result *r)
{
    memset(r, 0, sizeof *r);
    cs_stream_init(&st, store_a, false, store_b);
    size_t off = 0, used;
    cs_stream_event ev;
    while (off < k) {
        ev = cs_stream_feed(&st, d + off, k - off, &used);
        off += used;
        handle(ev, r);
    }
    while ((ev = cs_stream_gap(&st)) != CS_STREAM_MORE)
        handle(ev, r);
    for (off = k + lost; off < n; off += used) {
        ev = cs_stream_feed(&st, d + off, n - off, &used);
        handle(ev, r);
    }
    while ((ev = cs_stream_finish(&st)) != CS_STREAM_MORE)
        handle(ev, r);
    r->scene = cs_stream_scene(&st);
}

static void test_gap(void)
{
    cs_scene *s = new_scene(), *other = new_scene();
    build_demo(s);
    cs_scene_copy(other, s);
    cs_error e;
    cs_affine m = {1, 0, 0, 1, 5, 5};
    cs_scene_set_transform(other, 1, &m, &e);
    cels_buf b;
    encode(s, &b, true);
    size_t t[2] = {16, b.len}, end[2];
    end[0] = b.len;
    cels_encode_scene(&b, other);
    end[1] = b.len;
    const cs_scene *want_scene[2] = {s, other};
    static const size_t losses[3] = {0, 1, 7};
    for (int li = 0; li < 3; li++) {
        size_t lost = losses[li];
        bulk bk = {0, ""};
        int runs = 0;
        for (size_t k = 0; k + lost <= b.len; k += (k < 64 || b.len - k < 64) ? 1 : 13) {
            result r;
            gap_run(b.data, b.len, k, lost, &r);
            const cs_scene *want = NULL;
            int gap_errors = 0, want_gap = -1;
            for (int i = 0; i < 2; i++) {
                if (k + lost <= t[i] || k >= end[i])
                    want = want_scene[i];
                if (k >= t[i] + 16 && k < end[i])
                    want_gap = i;
            }
            for (int i = 0; i < r.errors && i < 8; i++)
                if (r.err[i].status == CS_ERR_STREAM_GAP) {
                    gap_errors++;
                    if (want_gap < 0 || r.err[i].offset != t[want_gap] || r.err[i].at != k)
                        gap_errors += 100;
                }
            char why[160] = "";
            if (!want ? r.scene != NULL
                      : !r.scene || !scene_equal(want, r.scene, why, sizeof why)) {
                char msg[256];
                snprintf(msg, sizeof msg, "gap at %zu, %zu lost: wrong scene on display %s", k,
                         lost, why);
                bulk_fail(&bk, msg);
            }
            if (gap_errors != (want_gap >= 0)) {
                char msg[256];
                snprintf(msg, sizeof msg, "gap at %zu, %zu lost: %d gap errors (want %d)", k, lost,
                         gap_errors, want_gap >= 0);
                bulk_fail(&bk, msg);
            }
            runs++;
        }
        char name[64];
        snprintf(name, sizeof name, "gap of %zu lost bytes at each offset", lost);
        bulk_done(&bk, name, runs);
    }
    /* A commit waiting for the swap is returned first; the gap follows. */
    cs_stream_init(&st, store_a, false, store_b);
    size_t used;
    cs_stream_event ev = cs_stream_feed(&st, b.data, end[0], &used);
    CHECK(ev == CS_STREAM_COMMIT && cs_stream_gap(&st) == CS_STREAM_COMMIT,
          "a waiting commit comes before the gap");
    cs_stream_swap(&st);
    CHECK(cs_stream_gap(&st) == CS_STREAM_MORE && !cs_stream_busy(&st),
          "a gap between transactions drops nothing");
    ev = cs_stream_feed(&st, b.data + end[0], 40, &used);
    CHECK(ev == CS_STREAM_MORE && cs_stream_busy(&st) && cs_stream_gap(&st) == CS_STREAM_ERROR &&
              cs_stream_last_error(&st)->status == CS_ERR_STREAM_GAP &&
              cs_stream_last_error(&st)->at == end[0] + 40 && !cs_stream_busy(&st),
          "a gap inside a transaction drops it at once and frees the back store");
    CHECK(strcmp(cs_status_str(CS_ERR_STREAM_GAP), "bytes lost on the link (receive overrun)") == 0,
          "the gap's status text");
    cels_buf_free(&b);
    free(s);
    free(other);
}

/*
 * cs_stream_busy: false exactly between transactions, and then the back
 * store really is scratch. The test scribbles over the back store at every
 * byte where the decoder is not busy (as the MCU firmware does when it
 * renders with the same RAM) and still gets the right scenes: a whole
 * scene, a patch (which copies the front), and a damaged patch dropped.
 */
static void test_busy(void)
{
    cs_scene *s = new_scene(), *other = new_scene();
    build_demo(s);
    cs_scene_copy(other, s);
    cs_error e;
    cs_affine m = {1, 0, 0, 1, 5, 5};
    cs_scene_set_transform(other, 1, &m, &e);
    cels_buf b;
    encode(s, &b, true);
    size_t first = b.len;
    /* a patch: the transform of cel 1 */
    cels_txn_begin(&b);
    cels_rec_begin(&b, CS_REC_CEL_TRANSFORM);
    cels_put_u32(&b, 1);
    cels_put_f32s(&b, &m.a, 6);
    cels_rec_end(&b);
    cels_rec_commit(&b);
    cels_txn_end(&b);
    size_t second = b.len;
    /* the same patch, damaged */
    cels_put_bytes(&b, b.data + first, second - first);
    b.data[second + 30] ^= 0x01;
    cs_stream_init(&st, store_a, false, store_b);
    int commits = 0, errors = 0, busy_wrong = 0, scribbles = 0;
    bool shown_ok[2] = {false, false};
    for (size_t i = 0; i < b.len; i++) {
        if (!cs_stream_busy(&st)) {
            memset(st.back, 0xA5, sizeof *st.back); /* lent out and used */
            scribbles++;
        }
        size_t used;
        cs_stream_event ev = cs_stream_feed(&st, b.data + i, 1, &used);
        bool in_txn = (i >= 16 && i + 1 < first) || (i >= first && i + 1 < second) ||
                      (i >= second && i + 1 < b.len);
        if (ev == CS_STREAM_COMMIT) {
            if (!cs_stream_busy(&st))
                busy_wrong++; /* the commit waits in the back store */
            cs_stream_swap(&st);
            char why[128] = "";
            const cs_scene *want = commits == 0 ? s : other;
            if (commits < 2)
                shown_ok[commits] = scene_equal(want, cs_stream_scene(&st), why, sizeof why);
            commits++;
        } else if (ev == CS_STREAM_ERROR) {
            errors++;
        }
        /* busy from the first byte after a transaction header to its commit */
        bool hdr_done = i >= 31 && (i < first || i >= first + 15) && (i < second || i >= second + 15);
        if (ev == CS_STREAM_MORE && cs_stream_busy(&st) != (in_txn && hdr_done))
            busy_wrong++;
    }
    CHECK(commits == 2 && errors == 1, "scribbled back store: %d commits, %d errors", commits,
          errors);
    CHECK(shown_ok[0] && shown_ok[1], "scribbled back store: whole scene %d, patch %d",
          shown_ok[0], shown_ok[1]);
    CHECK(busy_wrong == 0 && scribbles > 32, "cs_stream_busy wrong at %d bytes (%d scribbles)",
          busy_wrong, scribbles);
    char why[128] = "";
    CHECK(scene_equal(other, cs_stream_scene(&st), why, sizeof why),
          "the damaged patch left the patched scene on display: %s", why);
    CHECK(!cs_stream_busy(&st) && !cs_stream_busy(NULL), "idle at the end; NULL is not busy");
    cels_buf_free(&b);
    free(s);
    free(other);
}

/*
 * A scene that decodes and validates but cannot render at the board's size
 * (canvas 1e-6 scaled to 320x180: beyond the coordinate limit) is found by
 * cs_scene_check_render at its commit and dropped with cs_stream_refuse: the
 * error names the transaction, the scene on display stays, and the next
 * transaction decodes as usual.
 */
static void test_refuse(void)
{
    cs_scene *s = new_scene(), *tiny = new_scene();
    build_demo(s);
    cs_scene_copy(tiny, s);
    cs_error e;
    CHECK(cs_scene_set_canvas(tiny, 1e-6f, 1e-6f) == CS_OK, "a valid canvas of 1e-6");
    cels_buf b;
    encode(s, &b, true);
    size_t second = b.len;
    cels_encode_scene(&b, tiny);
    size_t third = b.len;
    cels_encode_scene(&b, s);
    cs_render_opts o = cs_render_defaults(320, 180);
    cs_renderer r;
    CHECK(cs_scene_check_render(&r, ws, s, &o, &e) == CS_OK, "the demo renders at 320x180");
    cs_stream_init(&st, store_a, false, store_b);
    size_t off = 0, used;
    int commits = 0, refused = 0;
    while (off < b.len || commits + refused < 3) {
        cs_stream_event ev = cs_stream_feed(&st, b.data + off, b.len - off, &used);
        off += used;
        if (ev == CS_STREAM_COMMIT) {
            cs_status c = cs_scene_check_render(&r, ws, st.back, &o, &e);
            if (c == CS_OK) {
                commits++;
                cs_stream_swap(&st);
                continue;
            }
            refused++;
            CHECK(c == CS_ERR_RANGE && e.cel == -1, "tiny canvas: %s (cel %d)", status_name(c), (int)e.cel);
            CHECK(cs_stream_refuse(&st, c, "cannot render", &e) == CS_OK, "refuse the commit");
            const cs_stream_error *le = cs_stream_last_error(&st);
            CHECK(le->status == CS_ERR_RANGE && le->offset == second && le->at == third &&
                      !strcmp(le->what, "cannot render"),
                  "refusal reported at %llu for the transaction at %llu (want %zu, %zu)",
                  (unsigned long long)le->at, (unsigned long long)le->offset, third, second);
            char why[128] = "";
            CHECK(cs_stream_scene(&st) && scene_equal(s, cs_stream_scene(&st), why, sizeof why),
                  "the demo stays on display: %s", why);
            CHECK(cs_stream_refuse(&st, c, "again", &e) == CS_ERR_STATE, "nothing left to refuse");
        } else if (ev == CS_STREAM_MORE && off >= b.len) {
            break;
        }
    }
    CHECK(commits == 2 && refused == 1 && st.commits == 2 && st.dropped == 1,
          "two commits and one refusal (%d, %d; decoder counts %u, %u)", commits, refused, st.commits,
          st.dropped);
    cels_buf_free(&b);
    free(s);
    free(tiny);
}

/*
 * EPOCH (1.3): the wall-clock instant of animation time 0 travels with the
 * scene, a patch may set it alone, and it changes no pixel.
 */
static void test_epoch(void)
{
    cs_scene *s = new_scene(), *t = new_scene();
    build_demo(s);
    cs_scene_copy(t, s);
    const uint64_t epoch = 1795000000123456789ull; /* 2026-11-18, to the ns; both halves non-zero */
    CHECK(cs_scene_set_epoch(t, epoch) == CS_OK && t->epoch_ns == epoch && s->epoch_ns == 0, "set the epoch");
    cels_buf b;
    encode(t, &b, true);
    result r;
    decode(b.data, b.len, 7, NULL, &r);
    char why[128] = "";
    CHECK(r.commits == 1 && r.errors == 0 && r.scene && r.scene->epoch_ns == epoch &&
              scene_equal(t, r.scene, why, sizeof why) && renders_equal(s, r.scene),
          "epoch round trip: %d commits, %d errors, %s", r.commits, r.errors, why);
    cels_buf_free(&b);
    /* a patch of the epoch alone */
    encode(s, &b, true);
    cels_txn_begin(&b);
    cels_rec_begin(&b, CS_REC_EPOCH);
    cels_put_u32(&b, (uint32_t)epoch);
    cels_put_u32(&b, (uint32_t)(epoch >> 32));
    cels_rec_end(&b);
    cels_rec_commit(&b);
    cels_txn_end(&b);
    decode(b.data, b.len, 1, NULL, &r);
    CHECK(r.commits == 2 && r.errors == 0 && r.scene && scene_equal(t, r.scene, why, sizeof why),
          "EPOCH patch: %d commits, %d errors, %s", r.commits, r.errors, why);
    cels_buf_free(&b);
    free(s);
    free(t);
}

/* cs_stream_error_text: the line every program prints, written out here by
 * hand; offsets beyond 32 bits; cut to the buffer, with the length needed. */
static void test_error_text(void)
{
    cs_stream_error e = {CS_ERR_WEIGHT, 40, 52, {CS_ERR_WEIGHT, 2, 0, 1, -1}, "weight must be > 0"};
    char buf[200];
    size_t n = cs_stream_error_text(&e, 1000, buf, sizeof buf);
    const char *want = "weight must be > 0 (cel 2, region 0, contour 1) (transaction at byte 1040 dropped)";
    CHECK(strcmp(buf, want) == 0 && n == strlen(want), "validation error: '%s' (%zu)", buf, n);
    cs_stream_error s = {CS_ERR_STREAM_SYNC, 18446744073709551610u, 7, {CS_OK, -1, -1, -1, -1},
                         "no transaction header here"};
    n = cs_stream_error_text(&s, 5, buf, sizeof buf);
    size_t whole = strlen(want);
    want = "bytes outside any transaction were skipped: no transaction header here (skipping from "
           "byte 18446744073709551615)";
    CHECK(strcmp(buf, want) == 0 && n == strlen(want), "skipped bytes: '%s' (%zu)", buf, n);
    char small[8];
    memset(small, 'x', sizeof small);
    n = cs_stream_error_text(&e, 0, small, sizeof small);
    CHECK(memcmp(small, "weight ", 8) == 0 && n > sizeof small, "cut to 8 bytes: '%.8s' (%zu)",
          small, n);
    n = cs_stream_error_text(&e, 1000, NULL, 0);
    CHECK(n == whole, "size query: %zu, want %zu", n, whole);
}

/* The host reader: a file with a good scene and a damaged patch. */
static void test_reader(void)
{
    cs_scene *s = new_scene(), *a = new_scene(), *b = new_scene();
    build_demo(s);
    cels_buf buf;
    encode(s, &buf, true);
    size_t second = buf.len;
    cels_txn_begin(&buf);
    cels_rec_begin(&buf, CS_REC_CEL_TRANSFORM);
    cels_put_u32(&buf, 0);
    cels_put_f32s(&buf, (float[6]){1, 0, 0, 1, NAN, 0}, 6);
    cels_rec_end(&buf);
    cels_rec_commit(&buf);
    cels_txn_end(&buf);
    char path[] = "/tmp/test_stream_XXXXXX";
    int fd = mkstemp(path);
    FILE *f = fd >= 0 ? fdopen(fd, "wb") : NULL;
    CHECK(f && fwrite(buf.data, 1, buf.len, f) == buf.len, "temporary file written");
    if (f)
        fclose(f);
    char *log = NULL;
    size_t loglen = 0;
    FILE *errf = open_memstream(&log, &loglen);
    cels_read_stats stats;
    const cs_scene *got = cels_read_file(path, a, b, errf, &stats);
    fclose(errf);
    char why[128] = "", want[256];
    snprintf(want, sizeof want,
             "%s: byte %zu: number is NaN or infinite (cel 0, item 4) (transaction at byte %zu "
             "dropped)\n",
             path, second + 16, second);
    CHECK(got && scene_equal(s, got, why, sizeof why) && stats.commits == 1 && stats.errors == 1,
          "reader keeps the good scene: %s, %u commits, %u errors", why, stats.commits,
          stats.errors);
    CHECK(log && strcmp(log, want) == 0, "reader message:\n  got  %s  want %s", log ? log : "",
          want);
    free(log);
    remove(path);
    CHECK(cels_read_file(path, a, b, NULL, &stats) == NULL, "missing file gives no scene");
    CHECK(cels_decode_buffer(buf.data, 20, "x", a, b, NULL, &stats) == NULL && stats.errors == 1,
          "truncated buffer gives no scene, one error");
    cels_buf_free(&buf);
    free(s);
    free(a);
    free(b);
}

/* Patches: the stream's edits equal the same scene calls made directly. */
static void test_patches(void)
{
    cs_scene *s = new_scene(), *want = new_scene();
    build_demo(s);
    cs_scene_copy(want, s);
    cs_error e;
    cels_buf b;
    cels_buf_init(&b);
    cels_txn_begin(&b);
    /* transform of cel 1 */
    cs_affine m = {0.9f, 0.1f, -0.1f, 0.9f, 40, 12};
    cels_rec_begin(&b, CS_REC_CEL_TRANSFORM);
    cels_put_u32(&b, 1);
    cels_put_f32s(&b, &m.a, 6);
    cels_rec_end(&b);
    cs_scene_set_transform(want, 1, &m, &e);
    /* lights of cel 2: stack default front */
    const float back[3] = {0.3f, 0.3f, 0.3f};
    cels_rec_begin(&b, CS_REC_CEL_LIGHTS);
    cels_put_u32(&b, 2);
    cels_put_u32(&b, 0);
    float zero3[3] = {0, 0, 0};
    cels_put_f32s(&b, zero3, 3);
    cels_put_f32s(&b, back, 3);
    cels_rec_end(&b);
    cs_scene_set_cel_lights(want, 2, NULL, back, &e);
    /* paint of region 3 */
    cs_paint p = {{0.3f, 0.4f, 0.5f}, {0.9f, 0.9f, 0.9f}, 0.7f};
    cels_rec_begin(&b, CS_REC_REGION_PAINT);
    cels_put_u32(&b, 3);
    cels_put_u32(&b, CS_FILL_EVENODD);
    cels_put_f32s(&b, p.pigment, 3);
    cels_put_f32s(&b, p.medium, 3);
    cels_put_f32(&b, p.beta);
    cels_rec_end(&b);
    cs_scene_set_paint(want, 3, CS_FILL_EVENODD, &p, &e);
    /* points of contour 4 (the quad), with intervals */
    cs_point q[4] = {{2, 38, 1}, {94, 34, 1}, {92, 62, 2}, {4, 60, 1}};
    float qiv[4] = {1, 2, 1, 2};
    cels_rec_begin(&b, CS_REC_CONTOUR_POINTS);
    cels_put_u32(&b, 4);
    cels_put_u32(&b, 4);
    cels_put_u32(&b, CS_WIRE_CONTOUR_INTERVALS);
    for (int i = 0; i < 4; i++) {
        cels_put_f32(&b, q[i].x);
        cels_put_f32(&b, q[i].y);
        cels_put_f32(&b, q[i].w);
    }
    cels_put_f32s(&b, qiv, 4);
    cels_rec_end(&b);
    cs_scene_set_points(want, 4, 4, q, qiv, &e);
    /* stack lights, background off, canvas */
    const float lf[3] = {0.8f, 0.8f, 0.8f}, lb[3] = {0, 0, 0.2f};
    cels_rec_begin(&b, CS_REC_LIGHTS);
    cels_put_f32s(&b, lf, 3);
    cels_put_f32s(&b, lb, 3);
    cels_rec_end(&b);
    cs_scene_set_lights(want, lf, lb);
    cels_rec_begin(&b, CS_REC_NO_BACKGROUND);
    cels_rec_end(&b);
    cs_scene_clear_background(want);
    cels_rec_begin(&b, CS_REC_CANVAS);
    cels_put_f32(&b, 100);
    cels_put_f32(&b, 70);
    cels_rec_end(&b);
    cs_scene_set_canvas(want, 100, 70);
    /* remove the transform track, replace the paint track */
    cels_rec_begin(&b, CS_REC_TRACK_REMOVE);
    cels_put_u32(&b, CS_TRACK_TRANSFORM);
    cels_put_u32(&b, 0);
    cels_rec_end(&b);
    cs_scene_remove_track(want, CS_TRACK_TRANSFORM, 0, &e);
    float pk[2][7] = {{1, 0, 0, 1, 1, 1, 1}, {0, 0, 1, 1, 1, 1, 0.5f}};
    cels_rec_begin(&b, CS_REC_TRACK);
    cels_put_u32(&b, CS_TRACK_PAINT);
    cels_put_u32(&b, 1);
    cels_put_u32(&b, CS_EASE_SMOOTH);
    cels_put_u32(&b, 2);
    cels_put_f32(&b, 0.0f);
    cels_put_f32s(&b, pk[0], 7);
    cels_put_f32(&b, 3.0f);
    cels_put_f32s(&b, pk[1], 7);
    cels_rec_end(&b);
    cs_scene_add_track(want, CS_TRACK_PAINT, 1, CS_EASE_SMOOTH, &e);
    cs_scene_add_key(want, 0.0f, pk[0], &e);
    cs_scene_add_key(want, 3.0f, pk[1], &e);
    /* remove cel 0 (and its tracks); add a new cel at the back and move it to the front */
    cels_rec_begin(&b, CS_REC_CEL_REMOVE);
    cels_put_u32(&b, 0);
    cels_rec_end(&b);
    cs_scene_remove_cel(want, 0, &e);
    rec_cel_region(&b);
    rec_square(&b, 60);
    /* rec_cel_region: identity, no own front light (flags 0), black back light */
    cs_affine id = {1, 0, 0, 1, 0, 0};
    cs_scene_add_cel(want, &id, NULL, zero3, &e);
    cs_paint wp = {{1, 1, 1}, {1, 1, 1}, 1};
    cs_scene_add_region(want, CS_FILL_NONZERO, &wp, &e);
    cs_point sq[4] = {{60, 10, 1}, {80, 10, 1}, {80, 30, 1}, {60, 30, 1}};
    cs_scene_add_contour(want, 1, 4, sq, NULL, &e);
    cels_rec_begin(&b, CS_REC_CEL_MOVE);
    cels_put_u32(&b, 2);
    cels_put_u32(&b, 0);
    cels_rec_end(&b);
    cs_scene_move_cel(want, 2, 0, &e);
    cels_rec_commit(&b);
    cels_txn_end(&b);

    result r;
    decode(b.data, b.len, 1, s, &r);
    char why[128] = "";
    CHECK(r.commits == 1 && r.errors == 0, "patch: %d commits %d errors (%s)", r.commits, r.errors,
          r.errors ? r.err[0].what : "-");
    CHECK(r.scene && scene_equal(want, r.scene, why, sizeof why), "patched store differs: %s", why);
    CHECK(r.scene && renders_equal(want, r.scene), "patched renders differ");
    CHECK(r.scene && r.scene->cel_count == 3 && r.scene->track_count == 5,
          "patched scene: %u cels %u tracks", r.scene ? r.scene->cel_count : 0,
          r.scene ? r.scene->track_count : 0);
    /* The same patch, damaged: the original scene stays, untouched. */
    b.data[b.len - 10] ^= 1;
    decode(b.data, b.len, 0, s, &r);
    CHECK(r.commits == 0 && r.errors == 1 && r.err[0].status == CS_ERR_STREAM_CRC && r.scene &&
              scene_equal(s, r.scene, why, sizeof why),
          "damaged patch leaves the scene: %d commits %d errors %s", r.commits, r.errors, why);
    cels_buf_free(&b);
    free(s);
    free(want);
}

/* Removing and moving cels against scenes built from scratch. */
static void build_three(cs_scene *s, const int *order, int n)
{
    cs_error e;
    cs_scene_init(s, 64, 64);
    for (int i = 0; i < n; i++) {
        int k = order[i];
        cs_affine m = {1, 0, 0, 1, (float)(8 * k), (float)(4 * k)};
        cs_scene_add_cel(s, &m, NULL, NULL, &e);
        cs_paint p = paint_of(0.3f * (float)k, 0.5f, 1.0f - 0.3f * (float)k, 0.5f + 0.2f * (float)k);
        cs_scene_add_region(s, CS_FILL_NONZERO, &p, &e);
        TL_MUST(ts_add_circle(s, 20, 20, 8 + 2 * (float)k));
        cs_scene_add_region(s, CS_FILL_EVENODD, &p, &e);
        TL_MUST(ts_add_circle(s, 30, 30, 5));
        TL_MUST(ts_add_circle(s, 30, 30, 3));
    }
    for (int i = 0; i < n; i++) {
        int k = order[i];
        cs_scene_add_track(s, CS_TRACK_TRANSFORM, (uint32_t)i, CS_EASE_LINEAR, &e);
        float a[6] = {1, 0, 0, 1, (float)(8 * k), (float)(4 * k)};
        float b[6] = {1, 0, 0, 1, (float)(8 * k + 10), (float)(4 * k)};
        cs_scene_add_key(s, 0, a, &e);
        cs_scene_add_key(s, 1 + (float)k, b, &e);
        cs_scene_add_track(s, CS_TRACK_POINTS, (uint32_t)(3 * i + 2), CS_EASE_SMOOTH, &e);
        float pk[24];
        for (int j = 0; j < 8; j++) {
            pk[3 * j] = 30 + (float)(j % 3);
            pk[3 * j + 1] = 30 + (float)(j % 2);
            pk[3 * j + 2] = 1;
        }
        cs_scene_add_key(s, (float)k, pk, &e);
    }
}

static void test_edit_ops(void)
{
    cs_scene *s = new_scene(), *want = new_scene();
    cs_error e;
    char why[128] = "";
    const int abc[3] = {0, 1, 2}, ac[2] = {0, 2}, bc[2] = {1, 2}, ab[2] = {0, 1};
    const int cab[3] = {2, 0, 1}, bca[3] = {1, 2, 0};
    build_three(s, abc, 3);
    CHECK(cs_scene_remove_cel(s, 1, &e) == CS_OK, "remove cel 1");
    build_three(want, ac, 2);
    /* Tracks of the survivors were added in a different order; compare pictures and structure. */
    CHECK(scene_equal(want, s, why, sizeof why), "remove middle cel: %s", why);
    CHECK(renders_equal(want, s), "remove middle cel: renders differ");
    CHECK(s->cel_count == 2 && s->region_count == 4 && s->contour_count == 6 &&
              s->point_count == 48 && s->track_count == 4 && s->key_count == 6 &&
              s->value_count == 2 * 12 + 2 * 24,
          "remove middle cel: counts");
    build_three(s, abc, 3);
    cs_scene_remove_cel(s, 0, &e);
    build_three(want, bc, 2);
    CHECK(scene_equal(want, s, why, sizeof why), "remove front cel: %s", why);
    CHECK(renders_equal(want, s), "remove front cel: renders differ");
    build_three(s, abc, 3);
    cs_scene_remove_cel(s, 2, &e);
    build_three(want, ab, 2);
    CHECK(scene_equal(want, s, why, sizeof why), "remove last cel: %s", why);
    build_three(s, abc, 3);
    CHECK(cs_scene_move_cel(s, 2, 0, &e) == CS_OK, "move cel 2 to 0");
    build_three(want, cab, 3);
    CHECK(renders_equal(want, s), "move back cel to front: renders differ");
    build_three(s, abc, 3);
    cs_scene_move_cel(s, 0, 2, &e);
    build_three(want, bca, 3);
    CHECK(renders_equal(want, s), "move front cel to back: renders differ");
    /* Encoding a moved store gives the same picture after decoding. */
    cels_buf b;
    encode(s, &b, true);
    result r;
    decode(b.data, b.len, 0, NULL, &r);
    CHECK(r.commits == 1 && r.scene && renders_equal(s, r.scene), "moved store round trip");
    cels_buf_free(&b);
    /* After a move, appending to a cel that does not own the end is refused. */
    build_three(s, abc, 3);
    cs_scene_move_cel(s, 2, 0, &e);
    cs_paint p = paint_of(1, 1, 1, 1);
    CHECK(cs_scene_add_region(s, CS_FILL_NONZERO, &p, &e) == CS_ERR_STATE,
          "region append to a moved-away cel refused");
    CHECK(cs_scene_remove_cel(s, 3, &e) == CS_ERR_INDEX && cs_scene_move_cel(s, 0, 3, &e) == CS_ERR_INDEX,
          "edit indices checked");
    free(s);
    free(want);
}

/* Three cels with paint functions, CSG and operands, in the given order. */
static void build_three_beta(cs_scene *s, const int *order, int n)
{
    cs_error e;
    cs_scene_init(s, 64, 64);
    for (int i = 0; i < n; i++) {
        int k = order[i];
        float fk = (float)k;
        cs_affine m = {1, 0, 0, 1, 6 * fk, 3 * fk};
        cs_scene_add_cel(s, &m, NULL, NULL, &e);
        cs_paint p = paint_of(0.2f, 0.4f, 0.6f, 1.0f);
        cs_scene_add_region(s, CS_FILL_NONZERO, &p, &e);
        const float lg[6] = {10 + fk, 10, 40, 20 + 5 * fk, 0, 0};
        const float ls[2][4] = {{0, 0.1f * fk, 0.5f, 1}, {1, 1, 0.3f * fk, 0}};
        cs_paint_func f = make_func(CS_FUNC_LINEAR, k % 3, lg, 2, 1, ls);
        cs_scene_set_region_func(s, CS_FIELD_PIGMENT, &f, &e);
        if (k != 1) { /* cel 1 has one function fewer: slots are not evenly spread */
            const float rg[6] = {20, 20, 12 + fk, 20, 22, 0};
            const float rs[2][4] = {{0, 1, 1, 1}, {1, 0.3f, 0.3f, 0.3f}};
            f = make_func(CS_FUNC_RADIAL, 0, rg, 2, 1, rs);
            cs_scene_set_region_func(s, CS_FIELD_BETA, &f, &e);
        }
        TL_MUST(ts_add_circle(s, 20, 20, 8 + 2 * fk));
        cs_scene_add_region(s, CS_FILL_EVENODD, &p, &e);
        const float mg[6] = {20, 20, 20, 0, 0, 20};
        const float ms[4][4] = {{0, 1, 0, 0}, {0, 0, fk / 2, 0}, {0, 0, 0, 1}, {0, 1, 1, 1}};
        f = make_func(CS_FUNC_MAP, 0, mg, 4, 2, ms);
        cs_scene_set_region_func(s, CS_FIELD_MEDIUM, &f, &e);
        const int rpn[3] = {0, 1, k == 2 ? CS_CSG_XOR : CS_CSG_DIFFERENCE};
        cs_scene_set_region_csg(s, rpn, 3, &e);
        TL_MUST(ts_add_circle(s, 30, 30, 9));
        cs_scene_set_contour_operand(s, 0, &e);
        TL_MUST(ts_add_circle(s, 34, 30, 5));
        cs_scene_set_contour_operand(s, 1, &e);
    }
    for (int i = 0; i < n; i++) {
        int k = order[i];
        cs_scene_add_track(s, CS_TRACK_TRANSFORM, (uint32_t)i, CS_EASE_LINEAR, &e);
        cs_scene_add_key(s, 0, (float[6]){1, 0, 0, 1, 6 * (float)k, 3 * (float)k}, &e);
        cs_scene_add_key(s, 1, (float[6]){1, 0, 0, 1, 6 * (float)k + 5, 3 * (float)k}, &e);
    }
}

/* Removing and moving cels that own paint functions, CSG programs and operands. */
static void test_edit_ops_beta(void)
{
    cs_scene *s = new_scene(), *want = new_scene();
    cs_error e;
    char why[128] = "";
    const int abc[3] = {0, 1, 2}, ac[2] = {0, 2}, bc[2] = {1, 2}, ab[2] = {0, 1};
    const int cab[3] = {2, 0, 1}, bca[3] = {1, 2, 0};
    build_three_beta(s, abc, 3);
    CHECK(s->func_count == 8, "three cels hold 8 functions: %u", s->func_count);
    const int *keep[3] = {bc, ac, ab};
    for (uint32_t victim = 0; victim < 3; victim++) {
        build_three_beta(s, abc, 3);
        CHECK(cs_scene_remove_cel(s, victim, &e) == CS_OK, "remove cel %u", victim);
        build_three_beta(want, keep[victim], 2);
        CHECK(scene_equal(want, s, why, sizeof why), "remove cel %u with functions: %s", victim,
              why);
        CHECK(renders_equal(want, s), "remove cel %u with functions: renders differ", victim);
    }
    /* Remove them all, one by one: no function slot is left behind. */
    build_three_beta(s, abc, 3);
    cs_scene_remove_cel(s, 1, &e);
    cs_scene_remove_cel(s, 0, &e);
    cs_scene_remove_cel(s, 0, &e);
    CHECK(s->cel_count == 0 && s->region_count == 0 && s->func_count == 0 && s->track_count == 0,
          "all removed: %u cels %u regions %u functions %u tracks", s->cel_count, s->region_count,
          s->func_count, s->track_count);
    /* Functions can be added again up to the capacity after removals. */
    build_three_beta(s, abc, 3);
    for (int round = 0; round < 3 * CS_CFG_MAX_FUNCS; round++) {
        cs_scene_remove_cel(s, 0, &e);
        const int one[1] = {round % 3};
        cs_scene *t = want;
        build_three_beta(t, one, 1);
        /* append the same cel by hand at the back */
        cs_affine m = {1, 0, 0, 1, 0, 0};
        cs_scene_add_cel(s, &m, NULL, NULL, &e);
        cs_paint p = paint_of(0.2f, 0.4f, 0.6f, 1.0f);
        cs_scene_add_region(s, CS_FILL_NONZERO, &p, &e);
        cs_status fs = cs_scene_set_region_func(s, CS_FIELD_PIGMENT, &t->funcs[0], &e);
        if (fs != CS_OK) {
            CHECK(fs == CS_OK, "round %d: function slot leaked (%s, %u in use)", round,
                  cs_status_str(fs), s->func_count);
            break;
        }
        TL_MUST(ts_add_circle(s, 20, 20, 8));
    }
    CHECK(s->func_count <= 8, "after %d remove/add rounds: %u functions in use",
          3 * CS_CFG_MAX_FUNCS, s->func_count);
    /* Moves keep functions and CSG with their cels. */
    build_three_beta(s, abc, 3);
    cs_scene_move_cel(s, 2, 0, &e);
    build_three_beta(want, cab, 3);
    CHECK(renders_equal(want, s), "move with functions: back cel to front: renders differ");
    build_three_beta(s, abc, 3);
    cs_scene_move_cel(s, 0, 2, &e);
    build_three_beta(want, bca, 3);
    CHECK(renders_equal(want, s), "move with functions: front cel to back: renders differ");
    /* Remove after a move, then a stream round trip of the result. */
    cs_scene_remove_cel(s, 1, &e);
    const int ba[2] = {1, 0};
    build_three_beta(want, ba, 2);
    CHECK(renders_equal(want, s), "move then remove with functions: renders differ");
    cels_buf b;
    encode(s, &b, true);
    result r;
    decode(b.data, b.len, 2, NULL, &r);
    CHECK(r.commits == 1 && r.errors == 0 && r.scene && renders_equal(s, r.scene) &&
              r.scene->func_count == s->func_count,
          "edited store with functions round trip: %d commits %d errors", r.commits, r.errors);
    cels_buf_free(&b);
    free(s);
    free(want);
}

/* A patch that replaces a cel with functions and CSG, as the stream carries it. */
static void test_patch_beta(void)
{
    cs_scene *s = new_scene(), *want = new_scene();
    const int abc[3] = {0, 1, 2}, acc[3] = {0, 2, 2};
    build_three_beta(s, abc, 3);
    /* Replace cel 1 (remove, append, move) by the cel built for index 2. */
    cs_scene *donor = new_scene();
    const int two[1] = {2};
    build_three_beta(donor, two, 1);
    cels_buf full;
    encode(donor, &full, false);
    /* The donor's transaction: its records between SCENE and the tracks. */
    cels_buf b;
    cels_buf_init(&b);
    cels_txn_begin(&b);
    cels_rec_begin(&b, CS_REC_CEL_REMOVE);
    cels_put_u32(&b, 1);
    cels_rec_end(&b);
    size_t pos = 16;
    while (pos + 6 <= full.len - 4) {
        uint32_t type = (uint32_t)full.data[pos] | (uint32_t)full.data[pos + 1] << 8;
        uint32_t len = (uint32_t)full.data[pos + 2] | (uint32_t)full.data[pos + 3] << 8 |
                       (uint32_t)full.data[pos + 4] << 16 | (uint32_t)full.data[pos + 5] << 24;
        if ((type >> 8) == 2 || (type >> 8) == 5)
            cels_put_bytes(&b, full.data + pos, 6 + (size_t)len);
        pos += 6 + (size_t)len;
    }
    cels_rec_begin(&b, CS_REC_CEL_MOVE);
    cels_put_u32(&b, 2);
    cels_put_u32(&b, 1);
    cels_rec_end(&b);
    cels_rec_commit(&b);
    cels_txn_end(&b);
    result r;
    decode(b.data, b.len, 1, s, &r);
    /* a, c', c: the old cel 1's track went with it, and the donor's was not sent. */
    build_three_beta(want, acc, 3);
    cs_error e;
    cs_scene_remove_track(want, CS_TRACK_TRANSFORM, 1, &e);
    CHECK(r.commits == 1 && r.errors == 0, "replace a cel with functions: %d commits %d errors (%s)",
          r.commits, r.errors, r.errors ? r.err[0].what : "-");
    CHECK(r.scene && r.scene->func_count == 9 && r.scene->cel_count == 3,
          "replaced: %u functions, %u cels", r.scene ? r.scene->func_count : 0,
          r.scene ? r.scene->cel_count : 0);
    CHECK(r.scene && renders_equal(want, r.scene), "replace a cel with functions: renders differ");
    cels_buf_free(&b);
    cels_buf_free(&full);
    free(donor);
    free(s);
    free(want);
}

static void test_track_validation(void)
{
    cs_scene *s = new_scene();
    cs_error e;
    cs_scene_init(s, 10, 10);
    cs_affine id = {1, 0, 0, 1, 0, 0};
    cs_scene_add_cel(s, &id, NULL, NULL, &e);
    cs_paint p = paint_of(1, 1, 1, 1);
    cs_scene_add_region(s, CS_FILL_NONZERO, &p, &e);
    TL_MUST(ts_add_circle(s, 5, 5, 2));
    CHECK(cs_scene_add_track(s, CS_TRACK_TRANSFORM, 1, CS_EASE_LINEAR, &e) == CS_ERR_INDEX,
          "track on a missing cel");
    CHECK(cs_scene_add_track(s, (cs_track_kind)9, 0, CS_EASE_LINEAR, &e) == CS_ERR_TRACK,
          "unknown track kind");
    CHECK(cs_scene_add_track(s, CS_TRACK_TRANSFORM, 0, (cs_ease)4, &e) == CS_ERR_TRACK,
          "unknown ease");
    CHECK(cs_scene_add_key(s, 0, (float[6]){1, 0, 0, 1, 0, 0}, &e) == CS_ERR_STATE,
          "key before any track");
    CHECK(cs_scene_track_width(s, CS_TRACK_POINTS, 0) == 24, "points width 3*8");
    CHECK(cs_scene_add_track(s, CS_TRACK_PAINT, 0, CS_EASE_LINEAR, &e) == CS_OK, "paint track");
    CHECK(cs_scene_add_key(s, 1, (float[7]){1, 1, 1, 1, 1, 1, 1.5f}, &e) == CS_ERR_PAINT &&
              e.cel == 0 && e.region == 0 && e.item == 0,
          "paint key out of range located");
    CHECK(cs_scene_add_key(s, 1, (float[7]){1, 1, 1, 1, 1, 1, 1}, &e) == CS_OK, "paint key");
    CHECK(cs_scene_add_key(s, 1, (float[7]){1, 1, 1, 1, 1, 1, 1}, &e) == CS_ERR_KEY_ORDER &&
              e.item == 1,
          "equal key time refused");
    CHECK(cs_scene_add_key(s, INFINITY, (float[7]){1, 1, 1, 1, 1, 1, 1}, &e) == CS_ERR_NONFINITE,
          "infinite key time refused");
    CHECK(cs_scene_add_track(s, CS_TRACK_CEL_LIGHTS, 0, CS_EASE_SMOOTH, &e) == CS_OK &&
              cs_scene_add_key(s, 0, (float[6]){2, 2, 2, -0.1f, 0, 0}, &e) == CS_ERR_PAINT,
          "negative light refused, lights above 1 allowed");
    CHECK(cs_scene_add_track(s, CS_TRACK_POINTS, 0, CS_EASE_SMOOTH, &e) == CS_OK, "points track");
    float pk[24];
    for (int i = 0; i < 24; i++)
        pk[i] = 1;
    pk[11] = 0; /* weight of point 3 */
    CHECK(cs_scene_add_key(s, 0, pk, &e) == CS_ERR_WEIGHT && e.contour == 0,
          "zero weight in a key refused");
    /* Replacing a track keeps one per (kind, target). */
    uint32_t before = s->track_count;
    cs_scene_add_track(s, CS_TRACK_PAINT, 0, CS_EASE_SMOOTH, &e);
    CHECK(s->track_count == before && s->key_count == 0,
          "replacing a track: %u tracks (want %u), %u keys", s->track_count, before, s->key_count);
    free(s);
}

/*
 * The centroid of a disc under a keyframed translation, measured from
 * rendered coverage (16 sub-scanlines), against the closed form.
 */
static void test_centroid(void)
{
    enum { W = 200, H = 100 };
    cs_scene *s = new_scene();
    cs_error e;
    cs_scene_init(s, W, H);
    cs_affine id = {1, 0, 0, 1, 0, 0};
    cs_scene_add_cel(s, &id, NULL, NULL, &e);
    cs_paint white = paint_of(1, 1, 1, 1);
    cs_scene_add_region(s, CS_FILL_NONZERO, &white, &e);
    TL_MUST(ts_add_circle(s, 0, 0, 12));
    const double e0 = 30.3, f0 = 40.7, e1 = 161.9, f1 = 57.2, ta = 0.5, tb = 2.5;
    for (int ease = 0; ease < 2; ease++) {
        cs_scene_add_track(s, CS_TRACK_TRANSFORM, 0, (cs_ease)ease, &e);
        cs_scene_add_key(s, (float)ta, (float[6]){1, 0, 0, 1, (float)e0, (float)f0}, &e);
        cs_scene_add_key(s, (float)tb, (float[6]){1, 0, 0, 1, (float)e1, (float)f1}, &e);
        /* Through the stream, as the board gets it. */
        cels_buf b;
        encode(s, &b, true);
        result r;
        decode(b.data, b.len, 0, NULL, &r);
        cels_buf_free(&b);
        static float img[W * H * 3];
        const double times[] = {0.0, 0.5, 0.77, 1.0, 1.2345, 1.5, 2.0, 2.4, 2.5, 3.0, 17.0};
        double worst = 0;
        for (size_t i = 0; i < sizeof times / sizeof times[0]; i++) {
            double t = times[i];
            double u = t <= ta ? 0 : t >= tb ? 1 : (t - ta) / (tb - ta);
            if (ease == 1)
                u = u * u * (3 - 2 * u);
            double cx = e0 + (e1 - e0) * u, cy = f0 + (f1 - f0) * u;
            cs_status rs = render(r.scene ? r.scene : s, W, H, (float)t, CS_AA_SUBSCAN, 16, img);
            double m = 0, mx = 0, my = 0;
            for (int y = 0; y < H; y++)
                for (int x = 0; x < W; x++) {
                    double c = img[(y * W + x) * 3];
                    m += c;
                    mx += c * (x + 0.5);
                    my += c * (y + 0.5);
                }
            double dx = mx / m - cx, dy = my / m - cy;
            double err = sqrt(dx * dx + dy * dy);
            if (err > worst)
                worst = err;
            CHECK(rs == CS_OK && err < 0.01 && fabs(m - PI * 144) < 0.2,
                  "%s t=%.4f: centroid (%.5f, %.5f) want (%.5f, %.5f), off %.5f px, area %.4f",
                  ease ? "smooth" : "linear", t, mx / m, my / m, cx, cy, err, m);
        }
        printf("  centroid, %s ease: worst error %.5f px over %zu instants\n",
               ease ? "smooth" : "linear", worst, sizeof times / sizeof times[0]);
    }
    free(s);
}

/* Animated points, lights and paints sample what the closed form says. */
static void test_sampling(void)
{
    cs_scene *s = new_scene();
    cs_error e;
    cs_scene_init(s, 4, 4);
    cs_affine id = {1, 0, 0, 1, 0, 0};
    const float black[3] = {0, 0, 0};
    cs_scene_add_cel(s, &id, NULL, black, &e);
    cs_paint p = paint_of(1, 1, 1, 1);
    cs_scene_add_region(s, CS_FILL_NONZERO, &p, &e);
    cs_point sq[4] = {{-1, -1, 1}, {5, -1, 1}, {5, 5, 1}, {-1, 5, 1}};
    cs_scene_add_contour(s, 1, 4, sq, NULL, &e);
    /* Paint red channel 0.2 -> 0.8 over [1, 3] (linear): pixel = pigment * front. */
    cs_scene_add_track(s, CS_TRACK_PAINT, 0, CS_EASE_LINEAR, &e);
    cs_scene_add_key(s, 1, (float[7]){0.2f, 0, 0, 1, 1, 1, 1}, &e);
    cs_scene_add_key(s, 3, (float[7]){0.8f, 0, 0, 1, 1, 1, 1}, &e);
    /* Stack front light green 1 -> 0 over [0, 2] (smooth). */
    cs_scene_add_track(s, CS_TRACK_STACK_LIGHTS, 0, CS_EASE_SMOOTH, &e);
    cs_scene_add_key(s, 0, (float[6]){1, 1, 1, 0, 0, 0}, &e);
    cs_scene_add_key(s, 2, (float[6]){1, 0, 1, 0, 0, 0}, &e);
    float img[4 * 4 * 3];
    const float ts[] = {0.0f, 0.5f, 1.5f, 2.0f, 2.5f, 5.0f};
    for (size_t i = 0; i < sizeof ts / sizeof ts[0]; i++) {
        double t = ts[i];
        double u = t < 1 ? 0 : t > 3 ? 1 : (t - 1) / 2;
        double want_r = 0.2 + 0.6 * u;
        render(s, 4, 4, (float)t, CS_AA_EXACT, 0, img);
        CHECK(fabs(img[5 * 3] - want_r) < 1e-6, "paint at t=%.2f: %.7f want %.7f", t, img[15],
              want_r);
    }
    /* The green pigment is 0, so light green changes nothing; check via background. */
    cs_scene_add_cel(s, &id, NULL, NULL, &e); /* empty, ignored */
    const float bg[3] = {1, 1, 1};
    cs_scene_set_background(s, bg);
    cs_scene_remove_cel(s, 0, &e); /* drops the paint track with it */
    CHECK(s->track_count == 1, "paint track removed with its cel: %u tracks", s->track_count);
    for (size_t i = 0; i < sizeof ts / sizeof ts[0]; i++) {
        double t = ts[i];
        double u = t < 0 ? 0 : t > 2 ? 1 : t / 2;
        u = u * u * (3 - 2 * u);
        render(s, 4, 4, (float)t, CS_AA_EXACT, 0, img);
        CHECK(fabs(img[1] - (1 - u)) < 1e-6, "background under stack light at t=%.2f: %.7f want %.7f",
              t, img[1], 1 - u);
    }
    /* Points: a square whose right edge moves 1 -> 3 over [0, 1]. */
    cs_scene_init(s, 4, 1);
    cs_scene_add_cel(s, &id, NULL, NULL, &e);
    cs_scene_add_region(s, CS_FILL_NONZERO, &p, &e);
    cs_point r4[4] = {{0, -1, 1}, {1, -1, 1}, {1, 2, 1}, {0, 2, 1}};
    cs_scene_add_contour(s, 1, 4, r4, NULL, &e);
    cs_scene_add_track(s, CS_TRACK_POINTS, 0, CS_EASE_LINEAR, &e);
    cs_scene_add_key(s, 0, (float[12]){0, -1, 1, 1, -1, 1, 1, 2, 1, 0, 2, 1}, &e);
    cs_scene_add_key(s, 1, (float[12]){0, -1, 1, 3, -1, 1, 3, 2, 1, 0, 2, 1}, &e);
    float line[4 * 3];
    render(s, 4, 1, 0.25f, CS_AA_EXACT, 0, line);
    /* right edge at 1.5: pixel 1 half covered */
    CHECK(fabs(line[0] - 1) < 1e-6 && fabs(line[3] - 0.5) < 1e-6 && line[6] == 0,
          "points at t=0.25: %.6f %.6f %.6f", line[0], line[3], line[6]);
    free(s);
}

/* Writes small seeds for the fuzz target (a mode byte, then a stream): a
 * whole scene, a simple scene, a scene then a patch with a points track and
 * an unknown record, a scene then an added, moved and removed cel, and a
 * scene with paint functions, CSG and operands (class 5). */
static int write_seeds(const char *dir)
{
    cs_scene *s = new_scene();
    build_demo(s);
    struct {
        const char *name;
        cels_buf b;
    } seeds[5];
    seeds[0].name = "demo.fuzz";
    encode(s, &seeds[0].b, true);
    seeds[1].name = "square.fuzz";
    one_txn(&seeds[1].b, good_body);
    seeds[2].name = "patch.fuzz";
    one_txn(&seeds[2].b, good_body);
    cels_txn_begin(&seeds[2].b);
    cels_rec_begin(&seeds[2].b, CS_REC_CEL_TRANSFORM);
    cels_put_u32(&seeds[2].b, 0);
    cels_put_f32s(&seeds[2].b, (float[6]){1, 0, 0, 1, 5, 5}, 6);
    cels_rec_end(&seeds[2].b);
    cels_rec_begin(&seeds[2].b, CS_REC_TRACK);
    cels_put_u32(&seeds[2].b, CS_TRACK_POINTS);
    cels_put_u32(&seeds[2].b, 0);
    cels_put_u32(&seeds[2].b, CS_EASE_SMOOTH);
    cels_put_u32(&seeds[2].b, 2);
    cels_put_f32(&seeds[2].b, 0);
    cels_put_f32s(&seeds[2].b, (float[12]){10, 10, 1, 30, 10, 1, 30, 30, 1, 10, 30, 1}, 12);
    cels_put_f32(&seeds[2].b, 1);
    cels_put_f32s(&seeds[2].b, (float[12]){0, 0, 1, 40, 10, 2, 30, 40, 1, 10, 30, 1}, 12);
    cels_rec_end(&seeds[2].b);
    cels_rec_begin(&seeds[2].b, 0x02FE);
    cels_put_u32(&seeds[2].b, 7);
    cels_rec_end(&seeds[2].b);
    cels_rec_commit(&seeds[2].b);
    cels_txn_end(&seeds[2].b);
    seeds[3].name = "edit.fuzz";
    one_txn(&seeds[3].b, good_body);
    cels_txn_begin(&seeds[3].b);
    rec_cel_region(&seeds[3].b);
    rec_square(&seeds[3].b, 50);
    cels_rec_begin(&seeds[3].b, CS_REC_CEL_MOVE);
    cels_put_u32(&seeds[3].b, 1);
    cels_put_u32(&seeds[3].b, 0);
    cels_rec_end(&seeds[3].b);
    cels_rec_begin(&seeds[3].b, CS_REC_CEL_REMOVE);
    cels_put_u32(&seeds[3].b, 1);
    cels_rec_end(&seeds[3].b);
    cels_rec_commit(&seeds[3].b);
    cels_txn_end(&seeds[3].b);
    seeds[4].name = "beta.fuzz";
    cs_scene *beta = new_scene();
    build_beta(beta);
    encode(beta, &seeds[4].b, false);
    free(beta);
    int rc = 0;
    for (int i = 0; i < 5; i++) {
        char path[512];
        snprintf(path, sizeof path, "%s/%s", dir, seeds[i].name);
        FILE *f = fopen(path, "wb");
        /* The fuzz target's first byte: chunking, built-in scene, CRC re-sealing. */
        static const uint8_t mode[5] = {0x40, 0x01, 0xC2, 0x83, 0x42};
        if (!f || fwrite(&mode[i], 1, 1, f) != 1 ||
            fwrite(seeds[i].b.data, 1, seeds[i].b.len, f) != seeds[i].b.len) {
            fprintf(stderr, "test_stream: cannot write %s\n", path);
            rc = 1;
        }
        if (f)
            fclose(f);
        cels_buf_free(&seeds[i].b);
    }
    free(s);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc == 3 && strcmp(argv[1], "--seeds") == 0)
        return write_seeds(argv[2]);
    store_a = new_scene();
    store_b = new_scene();
    ws = tl_calloc(1, sizeof *ws);
    printf("test_stream: sizeof(cs_stream) = %zu bytes (decoder state, apart from the two "
           "scene stores of %zu bytes each)\n",
           sizeof(cs_stream), sizeof(cs_scene));
    TL_RUN(test_crc_and_lights_order);
    TL_RUN(test_copy);
    TL_RUN(test_roundtrip);
    TL_RUN(test_roundtrip_beta);
    TL_RUN(test_roundtrip_groups);
    TL_RUN(test_truncation);
    TL_RUN(test_bitflips);
    TL_RUN(test_crafted);
    TL_RUN(test_crafted_beta);
    TL_RUN(test_random_and_resync);
    TL_RUN(test_valid_then_damaged);
    TL_RUN(test_busy);
    TL_RUN(test_gap);
    TL_RUN(test_refuse);
    TL_RUN(test_epoch);
    TL_RUN(test_patches);
    TL_RUN(test_error_text);
    TL_RUN(test_reader);
    TL_RUN(test_edit_ops);
    TL_RUN(test_edit_ops_beta);
    TL_RUN(test_patch_beta);
    TL_RUN(test_track_validation);
    TL_RUN(test_sampling);
    TL_RUN(test_centroid);
    free(store_a);
    free(store_b);
    free(ws);
    return tl_summary("test_stream");
}
