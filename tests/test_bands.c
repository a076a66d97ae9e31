/*
 * test_bands.c - a frame's lines on several threads give one thread's bytes.
 *
 *   test_bands SCENE_DIR     SCENE_DIR holds scenes/ (demo, beta-csg, motion, bench/blobs)
 *
 * The truth is the core's single-renderer path, which every other test
 * checks against its references: cs_frame_begin, then cs_render_line on
 * every line. Against it, for each scene, in every AA mode (none, 1, 5 and
 * 16 sub-scanlines, exact area) and both blends, the same frame prepared
 * once and rendered by the thread pool of host-sim/bands.c (cs_frame_share
 * into a workspace per thread) with 1, 2, 3 and 4 threads must give the
 * same linear floats, bit for bit, on every line, also with the caller
 * rendering bands in the prepared renderer (bands_help); so must small bands,
 * bands of one line, a ring of a few lines that the consumer releases as it
 * goes, and a frame with a pre-combined cache. celfw's source
 * (hal/linux/lx_scene_source.c) with a pool must hand out the same lines,
 * also after a frame abandoned half way. A scene that
 * overflows the crossings on some lines must report the capacity error one
 * renderer reports (the first in line order), whichever thread met it.
 * cs_frame_share's refusals are checked too.
 *
 * A frame prepared in parts (cs_frame_begin_part, cs_frame_join) must be the
 * one cs_frame_begin prepares, field by field: every scene, cut into two
 * parts at every cel (every fourth, and the last, of a scene of many), into
 * three and four at several, with and without a
 * viewport, in every AA mode and both blends; so must bands_prepare's on 1..4
 * threads (its frames then rendered as above), and its errors must be
 * cs_frame_begin's, location included. The last line is
 * `test_bands: N passed, M failed`.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bands.h"
#include "celscan_private.h"
#include "lx_scene_source.h"
#include "scene_json.h"
#include "testlib.h"

static cs_scene *scene;
static cs_workspace *ws_ref, *ws_prep;
static cs_workspace *ws_part[3]; /* parts 1..3 of a frame prepared in parts */
static float *want, *got; /* whole frames of linear floats */
static const char *dir;

/* The pool's emit: line y's runs, expanded, into its slot of `got`. */
typedef struct sink {
    float *frame;
    int width;
    int slots; /* lines the frame holds: line y goes to slot y % slots */
} sink;

static void emit_floats(void *user, const cs_renderer *r, int y)
{
    const sink *k = user;
    bands_floats(r, k->frame + (size_t)(y % k->slots) * 3u * (size_t)k->width);
}

/* The pool's render (bands_start_render): line y rendered as floats into its slot. */
static void render_floats(void *user, cs_renderer *r, int row, int y)
{
    const sink *k = user;
    (void)cs_render_line(r, row, k->frame + (size_t)(y % k->slots) * 3u * (size_t)k->width);
}

/* One renderer, every line: the truth. Returns its sticky error. */
static cs_error render_one(const cs_render_opts *o, const cs_cache *cache)
{
    cs_renderer r;
    cs_error e;
    cs_status st = cache ? cs_frame_begin_cached(&r, ws_ref, scene, o, cache, &e)
                         : cs_frame_begin(&r, ws_ref, scene, o, &e);
    CHECK_STATUS(st, CS_OK, "cs_frame_begin (one thread)");
    for (int y = 0; y < o->height; y++)
        cs_render_line(&r, y, want + (size_t)y * 3u * (size_t)o->width);
    return cs_frame_error(&r);
}

/*
 * The frame on `pool` in bands of `chunk` (0: the default) with a window of
 * `window` lines (0: the whole frame), the caller rendering bands too when
 * `help` (bands_help), the lines rendered by the pool's callback when
 * `render` (bands_start_render) or else emitted after it rendered them;
 * compares each line with `want` as the consumer receives it. Returns the
 * number of lines that differ.
 */
static int render_pool(bands *pool, const cs_render_opts *o, const cs_cache *cache, int chunk,
                       int window, bool help, bool render, cs_error *err)
{
    cs_renderer prep;
    cs_error e;
    /* A helping caller prepares the frame on the pool too, as celsim does. */
    cs_status st = cache  ? cs_frame_begin_cached(&prep, ws_prep, scene, o, cache, &e)
                   : help ? bands_prepare(pool, &prep, ws_prep, scene, o, &e)
                          : cs_frame_begin(&prep, ws_prep, scene, o, &e);
    if (st != CS_OK)
        return o->height;
    int slots = window > 0 ? window : o->height;
    sink k = {got, o->width, slots};
    size_t line_floats = 3u * (size_t)o->width;
    if ((render ? bands_start_render(pool, &prep, chunk, slots, render_floats, &k)
                        : bands_start(pool, &prep, chunk, slots, emit_floats, &k)) != CS_OK)
        return o->height;
    int bad = 0;
    for (int y = 0; y < o->height; y++) {
        if (help)
            bands_help(pool, &prep, y);
        else
            bands_wait(pool, y);
        const float *line = got + (size_t)(y % slots) * line_floats;
        if (memcmp(line, want + (size_t)y * line_floats, line_floats * sizeof(float)) != 0) {
            if (bad == 0)
                tl_note("first differing line %d", y);
            bad++;
        }
        bands_release(pool, y + 1);
    }
    *err = bands_finish(pool);
    return bad;
}

typedef struct scene_case {
    const char *file;
    int width, height;
    float time;
} scene_case;

static const scene_case scenes[] = {
    {"bench/blobs.json", 384, 216, 0.0f},
    {"demo.json", 320, 180, 0.0f},
    {"beta-csg.json", 256, 192, 0.0f},
    {"motion.json", 240, 160, 1.25f},
};

static void load(const char *file)
{
    char path[512], msg[512];
    snprintf(path, sizeof path, "%s/%s", dir, file);
    int rc = scene_json_load(path, scene, msg, sizeof msg);
    if (!CHECK(rc == 0, "load %s: %s", path, msg))
        exit(tl_summary("test_bands"));
}

/* Every scene, every AA mode, both blends, 1..4 threads, default bands. */
static void test_threads_match_one(void)
{
    static const struct {
        cs_aa_mode aa;
        int n;
    } modes[] = {{CS_AA_NONE, 1}, {CS_AA_SUBSCAN, 1}, {CS_AA_SUBSCAN, 5},
                 {CS_AA_SUBSCAN, 16}, {CS_AA_EXACT, 1}};
    bands *pool[4];
    for (int t = 0; t < 4; t++)
        pool[t] = bands_new(t + 1);
    CHECK(pool[0] && pool[1] && pool[2] && pool[3], "bands_new(1..4)");
    for (size_t s = 0; s < sizeof scenes / sizeof scenes[0]; s++) {
        load(scenes[s].file);
        for (size_t m = 0; m < sizeof modes / sizeof modes[0]; m++) {
            for (int blend = CS_BLEND_LINEAR; blend <= CS_BLEND_SRGB; blend++) {
                cs_render_opts o = cs_render_defaults(scenes[s].width, scenes[s].height);
                o.aa = modes[m].aa;
                o.subscanlines = modes[m].n;
                o.time = scenes[s].time;
                o.blend = (cs_blend)blend;
                cs_error e1 = render_one(&o, NULL);
                for (int t = 0; t < 8; t++) {
                    bool help = t >= 4; /* the caller a thread too */
                    if (!pool[t % 4])
                        continue;
                    cs_error et;
                    int bad = render_pool(pool[t % 4], &o, NULL, 0, 0, help, false, &et);
                    CHECK(bad == 0 && et.status == e1.status,
                          "%s aa %d/%d blend %d, %d threads%s: %d lines differ from one thread "
                          "(errors %d, %d)",
                          scenes[s].file, (int)o.aa, o.subscanlines, blend, t % 4 + 1,
                          help ? " and the caller" : "", bad, (int)et.status, (int)e1.status);
                }
            }
        }
    }
    for (int t = 0; t < 4; t++)
        bands_free(pool[t]);
}

/* Bands of one line, odd bands, a ring of a few lines, and a cached frame;
 * lines emitted after the pool rendered them, or rendered by the callback
 * (bands_start_render). */
static void test_band_shapes(void)
{
    load("bench/blobs.json");
    bands *pool = bands_new(3);
    if (!CHECK(pool != NULL, "bands_new(3)"))
        return;
    cs_render_opts o = cs_render_defaults(384, 216);
    o.aa = CS_AA_EXACT;
    static const int shapes[][2] = {{1, 0}, {7, 0}, {500, 0}, {4, 12}, {8, 8}};
    for (int aa = 0; aa < 2; aa++) {
        o.aa = aa ? CS_AA_EXACT : CS_AA_SUBSCAN;
        render_one(&o, NULL);
        for (size_t k = 0; k < sizeof shapes / sizeof shapes[0]; k++) {
            cs_error e;
            for (int mode = 0; mode < 4; mode++) { /* helped or not, emit or render */
                bool help = mode & 1, render = mode >> 1;
                int bad =
                    render_pool(pool, &o, NULL, shapes[k][0], shapes[k][1], help, render, &e);
                CHECK(bad == 0,
                      "aa %d, bands of %d lines, window %d, help %d, render %d: %d lines differ",
                      (int)o.aa, shapes[k][0], shapes[k][1], help, render, bad);
            }
        }
    }
    /* A window smaller than a band could never start one. */
    cs_renderer prep;
    cs_error e;
    CHECK_STATUS(cs_frame_begin(&prep, ws_prep, scene, &o, &e), CS_OK, "frame");
    sink k = {got, o.width, 4};
    CHECK_STATUS(bands_start(pool, &prep, 8, 4, emit_floats, &k), CS_ERR_ARG, "window < band");
    CHECK_STATUS(bands_start(pool, &prep, -1, 4, emit_floats, &k), CS_ERR_ARG, "negative band");
    CHECK_EQ_INT(bands_finish(pool).status, CS_OK, "finish with no frame running");

    /* The back cels pre-combined into a cache, shared by every thread read-only. */
    static unsigned char buf[8u << 20];
    cs_cache cache;
    o.aa = CS_AA_SUBSCAN;
    uint32_t first = scene->cel_count / 2;
    cs_status st = cs_cache_build(&cache, buf, sizeof buf, ws_ref, scene, &o, first,
                                  scene->cel_count - first, &e);
    if (CHECK(st == CS_OK, "cs_cache_build: %s (%zu bytes needed)", cs_status_str(st),
              cache.bytes_needed)) {
        render_one(&o, &cache);
        int bad = render_pool(pool, &o, &cache, 0, 0, true, false, &e);
        CHECK(bad == 0, "cached frame on 3 threads: %d lines differ", bad);
    }
    bands_free(pool);
}

/* A comb of 2100 teeth: 4200 crossings on lines 40..59, beyond CS_CFG_MAX_CROSSINGS. */
static void build_comb(void)
{
    static cs_point pts[2 * 2100 + 3];
    int n = 0;
    const int teeth = 2100;
    const float d = 300.0f / (float)teeth;
    for (int i = 0; i < teeth; i++) {
        pts[n++] = (cs_point){10.0f + (float)i * d, 60.0f, 1.0f};
        pts[n++] = (cs_point){10.0f + ((float)i + 0.5f) * d, 40.0f, 1.0f};
    }
    pts[n++] = (cs_point){10.0f + (float)teeth * d, 60.0f, 1.0f};
    pts[n++] = (cs_point){10.0f + (float)teeth * d, 80.0f, 1.0f};
    pts[n++] = (cs_point){10.0f, 80.0f, 1.0f};
    cs_error e;
    const cs_affine id = {1, 0, 0, 1, 0, 0};
    const cs_paint paint = {{0.8f, 0.2f, 0.1f}, {0.0f, 0.0f, 0.0f}, 1.0f};
    const cs_paint glass = {{0.1f, 0.5f, 0.9f}, {0.5f, 0.5f, 0.5f}, 0.5f};
    const cs_point sq[4] = {{20, 5, 1}, {300, 5, 1}, {300, 95, 1}, {20, 95, 1}};
    cs_scene_init(scene, 320.0f, 100.0f);
    CHECK_STATUS(cs_scene_add_cel(scene, &id, NULL, NULL, &e), CS_OK, "cel");
    CHECK_STATUS(cs_scene_add_region(scene, CS_FILL_NONZERO, &glass, &e), CS_OK, "region");
    CHECK_STATUS(cs_scene_add_contour(scene, 1, 4, sq, NULL, &e), CS_OK, "square");
    CHECK_STATUS(cs_scene_add_cel(scene, &id, NULL, NULL, &e), CS_OK, "cel");
    CHECK_STATUS(cs_scene_add_region(scene, CS_FILL_NONZERO, &paint, &e), CS_OK, "region");
    CHECK_STATUS(cs_scene_add_contour(scene, 1, n, pts, NULL, &e), CS_OK, "comb");
}

static void test_capacity_error_in_line_order(void)
{
    build_comb();
    bands *pool = bands_new(4);
    if (!CHECK(pool != NULL, "bands_new(4)"))
        return;
    for (int aa = 0; aa < 3; aa++) {
        cs_render_opts o = cs_render_defaults(320, 100);
        o.aa = (cs_aa_mode)aa;
        o.subscanlines = 4;
        cs_error e1 = render_one(&o, NULL);
        CHECK_STATUS(e1.status, CS_ERR_CAP_CROSSINGS, "the comb overflows (one thread)");
        /* Bands of 3 lines: several threads meet the overflow, the lowest line wins. */
        for (int help = 0; help < 2; help++) {
            cs_error e4;
            int bad = render_pool(pool, &o, NULL, 3, 0, help, false, &e4);
            CHECK(bad == 0, "aa %d, help %d: %d lines differ", aa, help, bad);
            CHECK(e4.status == e1.status && e4.cel == e1.cel && e4.region == e1.region &&
                      e4.item == e1.item,
                  "aa %d, help %d: 4 threads report %s at cel %d region %d line %d; one thread "
                  "%s at cel %d region %d line %d",
                  aa, help, cs_status_str(e4.status), e4.cel, e4.region, e4.item,
                  cs_status_str(e1.status), e1.cel, e1.region, e1.item);
        }
    }
    bands_free(pool);
}

/* celfw's line source with 1 and 3 threads, as a one-lane backend pulls it. */
static void test_celfw_source(void)
{
    load("demo.json");
    const int w = 320, h = 180;
    cs_render_opts o = cs_render_defaults(w, h);
    o.aa = CS_AA_SUBSCAN;
    o.subscanlines = 4;
    render_one(&o, NULL);
    for (int threads = 1; threads <= 3; threads += 2) {
        lx_scene_source src;
        if (!CHECK(lx_scene_source_init(&src, w, h, CS_AA_SUBSCAN, 4) == HAL_OK &&
                       lx_scene_source_threads(&src, threads) == HAL_OK,
                   "source with %d threads", threads))
            continue;
        lx_scene_source_set(&src, scene, 0.0f);
        float *line = tl_calloc(3u * (size_t)w, sizeof(float));
        for (int round = 0; round < 2; round++) {
            /* Round 0 gives up after 40 lines, as a backend that lost its device does. */
            int bad = 0, last = round == 0 ? 40 : h;
            CHECK(src.src.begin(src.src.user, 1) == HAL_OK, "begin");
            for (int y = 0; y < last; y++) {
                if (src.src.line(src.src.user, 0, y, line) != HAL_OK ||
                    memcmp(line, want + (size_t)y * 3u * (size_t)w, 3u * (size_t)w * sizeof(float)))
                    bad++;
            }
            CHECK(bad == 0, "%d threads, round %d: %d of %d lines differ", threads, round, bad, last);
            if (round == 1 && threads > 1)
                CHECK(src.src.line(src.src.user, 0, 5, line) == HAL_ERR_RENDER,
                      "a line behind the ring is refused");
        }
        lx_scene_source_end(&src);
        CHECK_EQ_INT(src.err.status, CS_OK, "no capacity error");
        free(line);
        lx_scene_source_free(&src);
    }
}

static bool same_segment(const cs_segment *s, const cs_segment *t)
{
    bool same = s->ox == t->ox && s->oy == t->oy && s->px_lo == t->px_lo && s->px_hi == t->px_hi &&
                s->region == t->region && s->degree == t->degree && s->rational == t->rational;
    for (int k = 0; k < 4; k++)
        same = same && tl_bits_of(s->x[k]) == tl_bits_of(t->x[k]) &&
               tl_bits_of(s->y[k]) == tl_bits_of(t->y[k]) && tl_bits_of(s->w[k]) == tl_bits_of(t->w[k]);
    return same;
}

static bool same_piece(const cs_piece *p, const cs_piece *q)
{
    return tl_bits_of(p->u0) == tl_bits_of(q->u0) && tl_bits_of(p->u1) == tl_bits_of(q->u1) &&
           tl_bits_of(p->y_top) == tl_bits_of(q->y_top) &&
           tl_bits_of(p->y_bot) == tl_bits_of(q->y_bot) && p->segment == q->segment &&
           p->region == q->region && p->operand == q->operand && p->dir == q->dir;
}

/* Cel ci's opacity, its regions' paints and their functions' maps alike in fa and fb. */
static bool same_cel(const cs_frame_data *fa, const cs_frame_data *fb, uint32_t ci)
{
    const cs_cel *cel = &scene->cels[ci];
    bool same = tl_bits_of(fa->cel_opacity[ci]) == tl_bits_of(fb->cel_opacity[ci]);
    for (uint32_t ri = cel->first_region; ri < cel->first_region + cel->region_count; ri++) {
        same = same && fa->region_cel[ri] == fb->region_cel[ri];
        for (int k = 0; k < 3; k++)
            same = same && tl_bits_of(fa->region_E[ri][k]) == tl_bits_of(fb->region_E[ri][k]) &&
                   tl_bits_of(fa->region_T[ri][k]) == tl_bits_of(fb->region_T[ri][k]);
        for (int f = 0; f < 3; f++)
            for (int k = 0; k < 6 && scene->regions[ri].func[f]; k++) {
                uint32_t fi = scene->regions[ri].func[f] - 1u;
                same = same && tl_bits_of(fa->func_xf[fi][k]) == tl_bits_of(fb->func_xf[fi][k]);
            }
    }
    return same;
}

/* Whether the frames a and b hold are the same, field by field: one check, saying where not. */
static void same_frame(const cs_renderer *a, const cs_renderer *b, const char *what)
{
    const cs_frame_data *fa = &a->ws->frame, *fb = &b->ws->frame;
    if (!CHECK(a->segment_count == b->segment_count && a->piece_count == b->piece_count &&
                   a->grey == b->grey && a->cel_begin == b->cel_begin && a->cel_end == b->cel_end,
               "%s: %u/%u segments, %u/%u pieces, grey %d/%d, cels to %u/%u", what,
               a->segment_count, b->segment_count, a->piece_count, b->piece_count, a->grey,
               b->grey, a->cel_end, b->cel_end))
        return;
    uint32_t seg = 0, piece = 0, cel = 0;
    while (seg < a->segment_count && same_segment(&fa->segments[seg], &fb->segments[seg]))
        seg++;
    while (piece < a->piece_count && same_piece(&fa->pieces[piece], &fb->pieces[piece]) &&
           fa->order[piece] == fb->order[piece])
        piece++;
    while (cel < scene->cel_count && same_cel(fa, fb, cel))
        cel++;
    CHECK(seg == a->segment_count && piece == a->piece_count && cel == scene->cel_count,
          "%s: first differing segment %u, piece or place in the order %u, cel's paints %u "
          "(of %u, %u, %u)",
          what, seg, piece, cel, a->segment_count, a->piece_count, scene->cel_count);
}

/*
 * The frame prepared in n parts cut at cels cut[1 .. n) (cut[0] = 0, the
 * last part to the scene's end) is cs_frame_begin's (in ws_ref).
 */
static void check_parts(const cs_render_opts *o, const cs_renderer *whole, const uint32_t *cut,
                        int n, const char *what)
{
    cs_renderer r, part[3];
    const cs_renderer *rest[3];
    cs_error e;
    char name[256];
    snprintf(name, sizeof name, "%s, %d parts from cels %u %u %u", what, n, cut[1],
             n > 2 ? cut[2] : 0u, n > 3 ? cut[3] : 0u);
    CHECK_STATUS(cs_frame_begin_part(&r, ws_prep, scene, o, 0, n > 1 ? cut[1] : UINT32_MAX, &e),
                 CS_OK, "part 0");
    for (int k = 1; k < n; k++) {
        uint32_t end = k + 1 < n ? cut[k + 1] : scene->cel_count;
        CHECK_STATUS(cs_frame_begin_part(&part[k - 1], ws_part[k - 1], scene, o, cut[k], end, &e),
                     CS_OK, "part k");
        rest[k - 1] = &part[k - 1];
    }
    cs_status st = cs_frame_join(&r, rest, n - 1);
    if (CHECK(st == CS_OK, "%s: join: %s", name, cs_status_str(st)))
        same_frame(whole, &r, name);
}

/* Every scene, options and cuts: the parts joined are the whole. */
static void test_parts_are_the_whole(void)
{
    static const struct {
        cs_aa_mode aa;
        int blend;
        bool view;
    } modes[] = {{CS_AA_EXACT, CS_BLEND_LINEAR, false}, {CS_AA_SUBSCAN, CS_BLEND_SRGB, false},
                 {CS_AA_NONE, CS_BLEND_LINEAR, true}, {CS_AA_EXACT, CS_BLEND_SRGB, true}};
    for (size_t s = 0; s < sizeof scenes / sizeof scenes[0]; s++) {
        load(scenes[s].file);
        for (size_t m = 0; m < sizeof modes / sizeof modes[0]; m++) {
            cs_render_opts o = cs_render_defaults(scenes[s].width, scenes[s].height);
            o.aa = modes[m].aa;
            o.subscanlines = 5;
            o.time = scenes[s].time;
            o.blend = (cs_blend)modes[m].blend;
            if (modes[m].view) { /* a band of rows in the middle, as a board or a wall tile */
                o.view_x = o.width / 4;
                o.view_y = o.height / 3;
                o.view_w = o.width / 2;
                o.view_h = o.height / 4;
            }
            char what[128];
            snprintf(what, sizeof what, "%s aa %d blend %d%s", scenes[s].file, (int)o.aa,
                     modes[m].blend, modes[m].view ? " viewport" : "");
            cs_renderer whole;
            cs_error e;
            CHECK_STATUS(cs_frame_begin(&whole, ws_ref, scene, &o, &e), CS_OK, what);
            /* Two parts cut at every cel (every fourth of Many-blobs' 56, for the sanitizers' time). */
            uint32_t n = scene->cel_count, step = n > 16 ? 4 : 1;
            for (uint32_t c = 0; c <= n; c += c + step > n && c < n ? n - c : step)
                check_parts(&o, &whole, (uint32_t[]){0, c}, 2, what);
            check_parts(&o, &whole, (uint32_t[]){0, n / 3, 2 * n / 3}, 3, what);
            check_parts(&o, &whole, (uint32_t[]){0, 1, 1, n - 1}, 4, what);
            check_parts(&o, &whole, (uint32_t[]){0, n / 4, n / 2, 3 * n / 4}, 4, what);
            /* The pool's own cuts, on 1..4 threads and a caller. */
            for (int t = 1; t <= 4; t++) {
                bands *pool = bands_new(t);
                cs_renderer r;
                cs_status st = pool ? bands_prepare(pool, &r, ws_prep, scene, &o, &e) : CS_ERR_ARG;
                if (CHECK(st == CS_OK, "%s: bands_prepare on %d threads: %s", what, t + 1,
                          cs_status_str(st)))
                    same_frame(&whole, &r, what);
                bands_free(pool);
            }
        }
    }
}

/* Joins that cannot make a frame, and a part's error reported as one call reports it. */
static void test_parts_refused(void)
{
    load("demo.json");
    cs_render_opts o = cs_render_defaults(64, 36);
    uint32_t n = scene->cel_count;
    cs_renderer r, a, b;
    const cs_renderer *parts[2] = {&a, &b};
    cs_error e;
    CHECK_STATUS(cs_frame_begin_part(&r, ws_prep, scene, &o, 0, 2, &e), CS_OK, "part 0");
    CHECK_STATUS(cs_frame_begin_part(&a, ws_part[0], scene, &o, 3, n, &e), CS_OK, "part 1");
    CHECK_STATUS(cs_frame_join(&r, parts, 1), CS_ERR_ARG, "a cel left out");
    CHECK_STATUS(cs_frame_begin_part(&a, ws_part[0], scene, &o, 2, n - 1, &e), CS_OK, "part 1");
    CHECK_STATUS(cs_frame_join(&r, parts, 1), CS_ERR_ARG, "the last cel left out");
    CHECK_STATUS(cs_frame_join(&r, parts, -1), CS_ERR_ARG, "a negative count");
    CHECK_STATUS(cs_frame_join(NULL, parts, 1), CS_ERR_ARG, "no renderer");
    cs_render_opts other = o;
    other.time = 0.5f;
    CHECK_STATUS(cs_frame_begin_part(&a, ws_part[0], scene, &other, 2, n, &e), CS_OK, "part 1");
    CHECK_STATUS(cs_frame_join(&r, parts, 1), CS_ERR_ARG, "another time");
    CHECK_STATUS(cs_frame_begin_part(&a, ws_prep, scene, &o, 2, n, &e), CS_OK, "part 1");
    CHECK_STATUS(cs_frame_join(&a, parts, 1), CS_ERR_ARG, "the first part does not start at cel 0");
    CHECK_STATUS(cs_frame_begin_part(&r, ws_prep, scene, &o, 0, 2, &e), CS_OK, "part 0");
    CHECK_STATUS(cs_frame_begin_part(&a, ws_prep, scene, &o, 2, n, &e), CS_OK, "part 1");
    CHECK_STATUS(cs_frame_join(&r, parts, 1), CS_ERR_ARG, "both parts in one workspace");
    CHECK_STATUS(cs_frame_begin_part(&r, ws_prep, scene, &o, 0, 2, &e), CS_OK, "part 0");
    CHECK_STATUS(cs_frame_begin_part(&a, ws_part[0], scene, &o, 2, 3, &e), CS_OK, "part 1");
    CHECK_STATUS(cs_frame_begin_part(&b, ws_part[1], scene, &o, 3, n, &e), CS_OK, "part 2");
    CHECK_STATUS(cs_frame_join(&r, parts, 2), CS_OK, "three parts");

    /* Four cels; the third's points land beyond CS_CFG_COORD_LIMIT. */
    const cs_affine id = {1, 0, 0, 1, 0, 0}, huge = {1.0e5f, 0, 0, 1.0e5f, 0, 0};
    const cs_paint paint = {{0.8f, 0.2f, 0.1f}, {0.0f, 0.0f, 0.0f}, 1.0f};
    const cs_point sq[4] = {{20, 5, 1}, {60, 5, 1}, {60, 30, 1}, {20, 30, 1}};
    cs_scene_init(scene, 64.0f, 36.0f);
    for (int c = 0; c < 4; c++) {
        CHECK_STATUS(cs_scene_add_cel(scene, c == 2 ? &huge : &id, NULL, NULL, &e), CS_OK, "cel");
        CHECK_STATUS(cs_scene_add_region(scene, CS_FILL_NONZERO, &paint, &e), CS_OK, "region");
        CHECK_STATUS(cs_scene_add_contour(scene, 1, 4, sq, NULL, &e), CS_OK, "contour");
    }
    cs_error want_e, got_e;
    cs_renderer whole;
    cs_status st1 = cs_frame_begin(&whole, ws_ref, scene, &o, &want_e);
    CHECK_STATUS(st1, CS_ERR_RANGE, "one call: the third cel is out of range");
    for (int t = 1; t <= 3; t++) {
        bands *pool = bands_new(t);
        if (!CHECK(pool != NULL, "bands_new(%d)", t))
            continue;
        cs_status st = bands_prepare(pool, &r, ws_prep, scene, &o, &got_e);
        CHECK(st == st1 && got_e.status == want_e.status && got_e.cel == want_e.cel &&
                  got_e.region == want_e.region && got_e.contour == want_e.contour &&
                  got_e.item == want_e.item,
              "%d threads: %s at cel %d region %d contour %d point %d; one call %s at cel %d "
              "region %d contour %d point %d",
              t + 1, cs_status_str(got_e.status), got_e.cel, got_e.region, got_e.contour,
              got_e.item, cs_status_str(want_e.status), want_e.cel, want_e.region,
              want_e.contour, want_e.item);
        bands_free(pool);
    }
}

static void test_share_refusals(void)
{
    load("demo.json");
    cs_render_opts o = cs_render_defaults(64, 36);
    cs_renderer prep, a, b;
    cs_error e;
    CHECK_STATUS(cs_frame_begin(&prep, ws_prep, scene, &o, &e), CS_OK, "frame");
    CHECK_STATUS(cs_frame_share(NULL, ws_ref, &prep), CS_ERR_ARG, "no renderer");
    CHECK_STATUS(cs_frame_share(&a, NULL, &prep), CS_ERR_ARG, "no workspace");
    CHECK_STATUS(cs_frame_share(&a, ws_ref, NULL), CS_ERR_ARG, "nothing to share");
    CHECK_STATUS(cs_frame_share(&a, ws_prep, &prep), CS_ERR_ARG, "the prepared workspace itself");
    CHECK_STATUS(cs_frame_share(&a, ws_ref, &prep), CS_OK, "a share");
    static cs_workspace other;
    CHECK_STATUS(cs_frame_share(&b, &other, &a), CS_ERR_STATE, "a share of a share");
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: test_bands SCENE_DIR\n");
        return 2;
    }
    dir = argv[1];
    scene = tl_calloc(1, sizeof *scene);
    ws_ref = tl_calloc(1, sizeof *ws_ref);
    ws_prep = tl_calloc(1, sizeof *ws_prep);
    for (int k = 0; k < 3; k++)
        ws_part[k] = tl_calloc(1, sizeof *ws_part[k]);
    want = tl_calloc(3u * 384u * 216u, sizeof(float));
    got = tl_calloc(3u * 384u * 216u, sizeof(float));
    TL_RUN(test_threads_match_one);
    TL_RUN(test_band_shapes);
    TL_RUN(test_capacity_error_in_line_order);
    TL_RUN(test_celfw_source);
    TL_RUN(test_share_refusals);
    TL_RUN(test_parts_are_the_whole);
    TL_RUN(test_parts_refused);
    for (int k = 0; k < 3; k++)
        free(ws_part[k]);
    free(scene);
    free(ws_ref);
    free(ws_prep);
    free(want);
    free(got);
    return tl_summary(argv[0]);
}
