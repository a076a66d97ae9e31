/*
 * test_validate.c - bad input is refused with the documented status, says
 * where, and leaves the scene exactly as it was; capacities are enforced
 * without writing past any buffer.
 *
 * "Exactly as it was" is checked byte for byte: the whole cs_scene is
 * compared with a copy taken before the rejected call (celscan.h: "each call
 * validates its input completely before it changes the store"). Error
 * locations are local indices, as in the header's example ("cel 2, region 0,
 * contour 1, point 4"): the region within its cel, the contour within its
 * region, the point or interval within its contour. The scenes are built so
 * that local and global indices differ.
 */
#include <float.h>

#include "common.h"

/* The scene lives between two guard areas filled with 0xA5 (Zephyr-style). */
#define GUARD 4096
typedef struct guarded {
    unsigned char *block;
    cs_scene *scene;
} guarded;

static guarded guarded_new(void)
{
    guarded g;
    g.block = tl_calloc(1, sizeof(cs_scene) + 2 * GUARD);
    memset(g.block, 0xA5, GUARD);
    memset(g.block + GUARD + sizeof(cs_scene), 0xA5, GUARD);
    g.scene = (cs_scene *)(void *)(g.block + GUARD);
    return g;
}

static int guards_intact(const guarded *g)
{
    for (size_t i = 0; i < GUARD; i++)
        if (g->block[i] != 0xA5 || g->block[GUARD + sizeof(cs_scene) + i] != 0xA5)
            return 0;
    return 1;
}

/*
 * A scene whose last cel is cel 1 with regions (global 2, 3) and whose last
 * region holds one contour (global contour 3): the next contour is local
 * (cel 1, region 1, contour 1).
 */
static void build_base(cs_scene *sc)
{
    cs_error err;
    cs_paint paint = tc_white_paint();
    cs_point tri[3] = {{10, 10, 1}, {40, 10, 1}, {20, 40, 1}};
    cs_scene_init(sc, 100, 100);
    cs_scene_add_cel(sc, &tc_identity, NULL, NULL, &err);
    cs_scene_add_region(sc, CS_FILL_NONZERO, &paint, &err);
    cs_scene_add_contour(sc, 1, 3, tri, NULL, &err);
    cs_scene_add_region(sc, CS_FILL_NONZERO, &paint, &err);
    cs_scene_add_contour(sc, 1, 3, tri, NULL, &err);
    cs_scene_add_cel(sc, &tc_identity, NULL, NULL, &err);
    cs_scene_add_region(sc, CS_FILL_NONZERO, &paint, &err);
    cs_scene_add_contour(sc, 1, 3, tri, NULL, &err);
    cs_scene_add_region(sc, CS_FILL_EVENODD, &paint, &err);
    cs_status st = cs_scene_add_contour(sc, 2, 3, tri, NULL, &err);
    CHECK_STATUS(st, CS_OK, "building the base scene");
    CHECK(sc->cel_count == 2 && sc->region_count == 4 && sc->contour_count == 4 &&
              sc->point_count == 12,
          "base scene counts: expected 2/4/4/12, got %u/%u/%u/%u", (unsigned)sc->cel_count,
          (unsigned)sc->region_count, (unsigned)sc->contour_count, (unsigned)sc->point_count);
}

#define ANY_ITEM (-99)
#define ITEM_IN_SET (-98) /* item must be one of set[] */

typedef struct contour_bad {
    const char *what;
    int degree, count;
    cs_point pts[8];
    float iv[8];
    int has_iv;
    cs_status want;
    int item;     /* expected err.item, ANY_ITEM, or ITEM_IN_SET */
    int set[4];   /* for ITEM_IN_SET, terminated by -1 */
} contour_bad;

static void expect_rejected_contour(const contour_bad *c)
{
    guarded g = guarded_new();
    build_base(g.scene);
    cs_scene *before = tl_calloc(1, sizeof *before);
    memcpy(before, g.scene, sizeof *before);
    cs_error err = {CS_OK, -7, -7, -7, -7};
    cs_status st = cs_scene_add_contour(g.scene, c->degree, c->count, c->pts,
                                        c->has_iv ? c->iv : NULL, &err);
    CHECK_STATUS(st, c->want, c->what);
    CHECK_STATUS(err.status, c->want, c->what);
    CHECK(err.cel == 1 && err.region == 1 && err.contour == 1,
          "%s: error location: expected cel 1 region 1 contour 1 (local indices), got cel %d "
          "region %d contour %d",
          c->what, (int)err.cel, (int)err.region, (int)err.contour);
    if (c->item == ITEM_IN_SET) {
        int ok = 0;
        for (int k = 0; k < 4 && c->set[k] >= 0; k++)
            ok |= err.item == c->set[k];
        CHECK(ok, "%s: err.item %d is not one of the intervals of the offending run (%d %d %d)",
              c->what, (int)err.item, c->set[0], c->set[1], c->set[2]);
    } else if (c->item != ANY_ITEM) {
        CHECK(err.item == c->item, "%s: err.item: expected %d, got %d", c->what, c->item,
              (int)err.item);
    }
    CHECK(memcmp(before, g.scene, sizeof *before) == 0,
          "%s: the rejected call changed the scene store", c->what);
    CHECK(guards_intact(&g), "%s: guard bytes around the scene were overwritten", c->what);
    free(before);
    free(g.block);
}

static void test_contour_rejections(void)
{
    static const contour_bad cases[] = {
        {"degree 0", 0, 4, {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, 1}}, {0}, 0, CS_ERR_DEGREE, -1, {-1}},
        {"degree 4", 4, 6, {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, 1}, {2, 2, 1}, {3, 3, 1}}, {0}, 0,
         CS_ERR_DEGREE, -1, {-1}},
        {"degree -1", -1, 4, {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, 1}}, {0}, 0, CS_ERR_DEGREE, -1, {-1}},
        {"degree 1, 1 point", 1, 1, {{1, 1, 1}}, {0}, 0, CS_ERR_TOO_FEW_POINTS, -1, {-1}},
        {"degree 2, 2 points", 2, 2, {{1, 1, 1}, {5, 1, 1}}, {0}, 0, CS_ERR_TOO_FEW_POINTS, -1, {-1}},
        {"degree 3, 3 points", 3, 3, {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}}, {0}, 0, CS_ERR_TOO_FEW_POINTS, -1,
         {-1}},
        {"degree 2, 0 points", 2, 0, {{0, 0, 0}}, {0}, 0, CS_ERR_TOO_FEW_POINTS, -1, {-1}},
        {"weight 0 at point 2", 2, 4, {{1, 1, 1}, {5, 1, 1}, {5, 5, 0}, {1, 5, 1}}, {0}, 0, CS_ERR_WEIGHT,
         2, {-1}},
        {"weight -1 at point 3", 3, 5, {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, -1}, {0, 3, 1}}, {0}, 0,
         CS_ERR_WEIGHT, 3, {-1}},
        {"weight -0 at point 0", 1, 3, {{1, 1, -0.0f}, {5, 1, 1}, {5, 5, 1}}, {0}, 0, CS_ERR_WEIGHT, 0, {-1}},
        {"weight -FLT_MIN at point 1", 1, 3,
         {{1, 1, 1}, {5, 1, -FLT_MIN}, {5, 5, 1}}, {0}, 0, CS_ERR_WEIGHT, 1, {-1}},
        {"NaN x at point 3", 2, 4, {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {NAN, 5, 1}}, {0}, 0, CS_ERR_NONFINITE,
         3, {-1}},
        {"NaN y at point 1", 2, 4, {{1, 1, 1}, {5, NAN, 1}, {5, 5, 1}, {1, 5, 1}}, {0}, 0, CS_ERR_NONFINITE,
         1, {-1}},
        {"NaN w at point 2", 2, 4, {{1, 1, 1}, {5, 1, 1}, {5, 5, NAN}, {1, 5, 1}}, {0}, 0, CS_ERR_NONFINITE,
         2, {-1}},
        {"+inf x at point 0", 1, 3, {{INFINITY, 1, 1}, {5, 1, 1}, {5, 5, 1}}, {0}, 0, CS_ERR_NONFINITE, 0,
         {-1}},
        {"-inf y at point 2", 1, 3, {{1, 1, 1}, {5, 1, 1}, {5, -INFINITY, 1}}, {0}, 0, CS_ERR_NONFINITE, 2,
         {-1}},
        {"+inf w at point 1", 1, 3, {{1, 1, 1}, {5, 1, INFINITY}, {5, 5, 1}}, {0}, 0, CS_ERR_NONFINITE, 1,
         {-1}},
        {"x = 1.5e6 at point 1", 1, 3, {{1, 1, 1}, {1.5e6f, 1, 1}, {5, 5, 1}}, {0}, 0, CS_ERR_RANGE, 1,
         {-1}},
        {"y = -2e6 at point 2", 2, 3, {{1, 1, 1}, {5, 1, 1}, {5, -2e6f, 1}}, {0}, 0, CS_ERR_RANGE, 2, {-1}},
        {"x = 3e38 at point 0", 3, 4, {{3e38f, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, 1}}, {0}, 0, CS_ERR_RANGE,
         0, {-1}},
        {"interval -1 at 2", 2, 4, {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, 1}}, {1, 1, -1, 1}, 1,
         CS_ERR_INTERVAL, 2, {-1}},
        {"interval -1e-30 at 0", 3, 4, {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, 1}}, {-1e-30f, 1, 1, 1}, 1,
         CS_ERR_INTERVAL, 0, {-1}},
        {"interval NaN at 1", 2, 4, {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, 1}}, {1, NAN, 1, 1}, 1,
         CS_ERR_INTERVAL, 1, {-1}},
        {"interval inf at 3", 2, 4, {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, 1}}, {1, 1, 1, INFINITY}, 1,
         CS_ERR_INTERVAL, 3, {-1}},
        {"degree 1 with a zero interval at 1", 1, 4, {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, 1}},
         {1, 0, 1, 1}, 1, CS_ERR_ZERO_RUN, ITEM_IN_SET, {1, -1}},
        {"degree 2 with zeros at 2,3", 2, 5, {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, 1}, {0, 3, 1}},
         {1, 1, 0, 0, 1}, 1, CS_ERR_ZERO_RUN, ITEM_IN_SET, {2, 3, -1}},
        {"degree 3 with zeros at 1,2,3", 3, 6,
         {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, 1}, {0, 3, 1}, {2, 2, 1}}, {1, 0, 0, 0, 1, 1}, 1,
         CS_ERR_ZERO_RUN, ITEM_IN_SET, {1, 2, 3, -1}},
        {"degree 2 zero run across the wrap (4, 0)", 2, 5,
         {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, 1}, {0, 3, 1}}, {0, 1, 1, 1, 0}, 1, CS_ERR_ZERO_RUN,
         ITEM_IN_SET, {4, 0, -1}},
        {"degree 3 zero run across the wrap (4, 5, 0)", 3, 6,
         {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, 1}, {0, 3, 1}, {2, 2, 1}}, {0, 1, 1, 1, 0, 0}, 1,
         CS_ERR_ZERO_RUN, ITEM_IN_SET, {4, 5, 0, -1}},
        {"degree 3 zero run across the wrap (5, 0, 1)", 3, 6,
         {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, 1}, {0, 3, 1}, {2, 2, 1}}, {0, 0, 1, 1, 1, 0}, 1,
         CS_ERR_ZERO_RUN, ITEM_IN_SET, {5, 0, 1, -1}},
        {"degree 1 all intervals zero", 1, 3, {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}}, {0, 0, 0}, 1,
         CS_ERR_DEGENERATE, ANY_ITEM, {-1}},
        {"degree 2 all intervals zero", 2, 4, {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, 1}}, {0, 0, 0, 0},
         1, CS_ERR_DEGENERATE, ANY_ITEM, {-1}},
        {"degree 3 all intervals zero", 3, 4, {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, 1}}, {0, 0, 0, 0},
         1, CS_ERR_DEGENERATE, ANY_ITEM, {-1}},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        expect_rejected_contour(&cases[i]);
}

/* Valid edge cases must be accepted (and appended). */
static void test_contour_accepted(void)
{
    static const struct {
        const char *what;
        int degree, count;
        cs_point pts[6];
        float iv[6];
        int has_iv;
    } ok[] = {
        {"degree 1, 2 points (p+1)", 1, 2, {{1, 1, 1}, {5, 5, 1}}, {0}, 0},
        {"degree 3, 4 points (p+1)", 3, 4, {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, 1}}, {0}, 0},
        {"degree 2, one zero", 2, 4, {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, 1}}, {1, 0, 1, 1}, 1},
        {"degree 3, two zeros across the wrap", 3, 4, {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}, {1, 5, 1}},
         {0, 1, 1, 0}, 1},
        {"degree 2, 3 points, intervals [1,0,1]", 2, 3, {{1, 1, 1}, {5, 1, 1}, {5, 5, 1}}, {1, 0, 1}, 1},
        {"coordinate 9.9e5 and tiny weight", 1, 3, {{9.9e5f, 1, 1}, {5, -9.9e5f, 1e-6f}, {5, 5, 1}},
         {0}, 0},
        {"duplicate points", 2, 4, {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}, {5, 5, 1}}, {0}, 0},
    };
    for (size_t i = 0; i < sizeof ok / sizeof ok[0]; i++) {
        cs_scene *sc = tl_calloc(1, sizeof *sc);
        build_base(sc);
        cs_error err;
        cs_status st = cs_scene_add_contour(sc, ok[i].degree, ok[i].count, ok[i].pts,
                                            ok[i].has_iv ? ok[i].iv : NULL, &err);
        CHECK_STATUS(st, CS_OK, ok[i].what);
        CHECK(sc->contour_count == 5 && sc->point_count == 12u + (unsigned)ok[i].count,
              "%s: counts after append: contours %u points %u", ok[i].what,
              (unsigned)sc->contour_count, (unsigned)sc->point_count);
        free(sc);
    }
    /* A contour whose one segment is all one point, or of zero length, must still render. */
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    cs_error err;
    cs_scene_init(sc, 16, 16);
    cs_scene_add_cel(sc, &tc_identity, NULL, NULL, &err);
    cs_paint paint = tc_white_paint();
    cs_scene_add_region(sc, CS_FILL_NONZERO, &paint, &err);
    cs_point dup[4] = {{4, 4, 1}, {4, 4, 1}, {4, 4, 1}, {12, 12, 1}};
    cs_scene_add_contour(sc, 3, 4, dup, NULL, &err);
    cs_point dot[3] = {{8, 8, 1}, {8, 8, 1}, {8, 8, 1}};
    cs_scene_add_contour(sc, 2, 3, dot, NULL, &err);
    double cov[256];
    cs_status st = tc_render(sc, 16, 16, CS_AA_SUBSCAN, 16, cov);
    CHECK_STATUS(st, CS_OK, "rendering degenerate (point-like) contours");
    int finite = 1;
    for (int k = 0; k < 256; k++)
        finite &= cov[k] >= 0 && cov[k] <= 1;
    CHECK(finite, "degenerate contours gave coverage outside 0..1");
    free(sc);
}

static void test_call_order_and_args(void)
{
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    cs_scene *before = tl_calloc(1, sizeof *before);
    cs_error err;
    cs_paint paint = tc_white_paint();
    cs_point tri[3] = {{10, 10, 1}, {40, 10, 1}, {20, 40, 1}};

    CHECK_STATUS(cs_scene_init(sc, 0, 100), CS_ERR_SIZE, "canvas width 0");
    CHECK_STATUS(cs_scene_init(sc, 100, 0), CS_ERR_SIZE, "canvas height 0");
    CHECK(cs_scene_init(sc, NAN, 100) != CS_OK, "canvas width NaN must be refused");
    CHECK(cs_scene_init(sc, -5, 100) != CS_OK, "canvas width -5 must be refused");
    CHECK(cs_scene_init(sc, INFINITY, 100) != CS_OK, "canvas width inf must be refused");
    CHECK_STATUS(cs_scene_init(NULL, 10, 10), CS_ERR_ARG, "cs_scene_init(NULL)");

    CHECK_STATUS(cs_scene_init(sc, 100, 100), CS_OK, "cs_scene_init");
    memcpy(before, sc, sizeof *before);
    CHECK_STATUS(cs_scene_add_region(sc, CS_FILL_NONZERO, &paint, &err), CS_ERR_STATE,
                 "region before any cel");
    CHECK_STATUS(cs_scene_add_contour(sc, 1, 3, tri, NULL, &err), CS_ERR_STATE,
                 "contour before any cel");
    CHECK(memcmp(before, sc, sizeof *before) == 0, "out-of-order calls changed the scene");

    CHECK_STATUS(cs_scene_add_cel(sc, &tc_identity, NULL, NULL, &err), CS_OK, "add cel");
    memcpy(before, sc, sizeof *before);
    CHECK_STATUS(cs_scene_add_contour(sc, 1, 3, tri, NULL, &err), CS_ERR_STATE,
                 "contour before any region of the cel");
    CHECK_STATUS(cs_scene_add_region(sc, (cs_fill_rule)2, &paint, &err), CS_ERR_FILL_RULE,
                 "fill rule 2");
    CHECK_EQ_INT(err.cel, 0, "fill rule error: err.cel");
    CHECK_STATUS(cs_scene_add_region(sc, (cs_fill_rule)-1, &paint, &err), CS_ERR_FILL_RULE,
                 "fill rule -1");
    CHECK_STATUS(cs_scene_add_region(sc, CS_FILL_NONZERO, NULL, &err), CS_ERR_ARG, "NULL paint");
    cs_paint bad = paint;
    bad.pigment[1] = 1.5f;
    CHECK_STATUS(cs_scene_add_region(sc, CS_FILL_NONZERO, &bad, &err), CS_ERR_PAINT,
                 "pigment 1.5");
    bad = paint;
    bad.medium[2] = -0.25f;
    CHECK_STATUS(cs_scene_add_region(sc, CS_FILL_NONZERO, &bad, &err), CS_ERR_PAINT,
                 "medium -0.25");
    bad = paint;
    bad.beta = 1.0001f;
    CHECK_STATUS(cs_scene_add_region(sc, CS_FILL_NONZERO, &bad, &err), CS_ERR_PAINT,
                 "beta 1.0001");
    bad = paint;
    bad.beta = NAN;
    CHECK_STATUS(cs_scene_add_region(sc, CS_FILL_NONZERO, &bad, &err), CS_ERR_NONFINITE,
                 "beta NaN");
    bad = paint;
    bad.pigment[0] = INFINITY;
    CHECK_STATUS(cs_scene_add_region(sc, CS_FILL_NONZERO, &bad, &err), CS_ERR_NONFINITE,
                 "pigment inf");
    CHECK(memcmp(before, sc, sizeof *before) == 0, "rejected regions changed the scene");

    cs_affine t = tc_identity;
    t.e = NAN;
    CHECK_STATUS(cs_scene_add_cel(sc, &t, NULL, NULL, &err), CS_ERR_NONFINITE,
                 "cel transform with NaN");
    t = tc_identity;
    t.a = INFINITY;
    CHECK_STATUS(cs_scene_add_cel(sc, &t, NULL, NULL, &err), CS_ERR_NONFINITE,
                 "cel transform with inf");
    CHECK_STATUS(cs_scene_add_cel(sc, NULL, NULL, NULL, &err), CS_ERR_ARG, "NULL cel transform");
    float light_nan[3] = {1, NAN, 1};
    CHECK_STATUS(cs_scene_add_cel(sc, &tc_identity, light_nan, NULL, &err), CS_ERR_NONFINITE,
                 "cel front light NaN");
    CHECK_STATUS(cs_scene_add_cel(sc, &tc_identity, NULL, light_nan, &err), CS_ERR_NONFINITE,
                 "cel back light NaN");
    CHECK_STATUS(cs_scene_set_background(sc, light_nan), CS_ERR_NONFINITE, "background NaN");
    CHECK_STATUS(cs_scene_set_background(sc, NULL), CS_ERR_ARG, "background NULL");
    CHECK_STATUS(cs_scene_set_lights(sc, light_nan, NULL), CS_ERR_ARG,
                 "set_lights with NULL back");
    float one[3] = {1, 1, 1};
    CHECK_STATUS(cs_scene_set_lights(sc, light_nan, one), CS_ERR_NONFINITE, "stack light NaN");
    CHECK(memcmp(before, sc, sizeof *before) == 0, "rejected cels/lights changed the scene");

    CHECK_STATUS(cs_scene_add_region(sc, CS_FILL_NONZERO, &paint, &err), CS_OK, "region");
    memcpy(before, sc, sizeof *before);
    CHECK_STATUS(cs_scene_add_contour(sc, 1, 3, NULL, NULL, &err), CS_ERR_ARG, "NULL points");
    CHECK(cs_scene_add_contour(sc, 1, -3, tri, NULL, &err) != CS_OK, "count -3 must be refused");
    CHECK(memcmp(before, sc, sizeof *before) == 0, "rejected contours changed the scene");
    CHECK_STATUS(cs_scene_add_contour(sc, 1, 3, tri, NULL, NULL), CS_OK,
                 "err may be NULL on success");
    CHECK_STATUS(cs_scene_add_contour(sc, 0, 3, tri, NULL, NULL), CS_ERR_DEGREE,
                 "err may be NULL on failure");
    free(sc);
    free(before);
}

static void test_frame_opts(void)
{
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    tc_shape *s = tc_shape_new(0);
    tc_add_circle(s, 50, 50, 20, 1);
    tc_scene_one(sc, 100, 100, NULL, s);
    cs_renderer r;
    cs_error err;
    cs_workspace *ws = tc_workspace();
    static const struct {
        const char *what;
        cs_render_opts o;
        cs_status want;
    } cases[] = {
        {"width 0", {0, 10, CS_AA_NONE, 1, 0, CS_BLEND_LINEAR, false, false, 0, 0, 0, 0}, CS_ERR_SIZE},
        {"height 0", {10, 0, CS_AA_NONE, 1, 0, CS_BLEND_LINEAR, false, false, 0, 0, 0, 0}, CS_ERR_SIZE},
        {"width -1", {-1, 10, CS_AA_NONE, 1, 0, CS_BLEND_LINEAR, false, false, 0, 0, 0, 0}, CS_ERR_SIZE},
        {"width beyond CS_CFG_MAX_WIDTH", {CS_CFG_MAX_WIDTH + 1, 10, CS_AA_NONE, 1, 0, CS_BLEND_LINEAR, false, false, 0, 0, 0, 0}, CS_ERR_SIZE},
        {"height beyond CS_CFG_MAX_HEIGHT", {10, CS_CFG_MAX_HEIGHT + 1, CS_AA_NONE, 1, 0, CS_BLEND_LINEAR, false, false, 0, 0, 0, 0}, CS_ERR_SIZE},
        {"width exactly CS_CFG_MAX_WIDTH", {CS_CFG_MAX_WIDTH, 4, CS_AA_NONE, 1, 0, CS_BLEND_LINEAR, false, false, 0, 0, 0, 0}, CS_OK},
        {"subscanlines 0", {10, 10, CS_AA_SUBSCAN, 0, 0, CS_BLEND_LINEAR, false, false, 0, 0, 0, 0}, CS_ERR_ARG},
        {"subscanlines beyond max", {10, 10, CS_AA_SUBSCAN, CS_CFG_MAX_SUBSCANLINES + 1, 0, CS_BLEND_LINEAR, false, false, 0, 0, 0, 0},
         CS_ERR_ARG},
        {"subscanlines exactly max", {10, 10, CS_AA_SUBSCAN, CS_CFG_MAX_SUBSCANLINES, 0, CS_BLEND_LINEAR, false, false, 0, 0, 0, 0}, CS_OK},
        {"aa mode 7", {10, 10, (cs_aa_mode)7, 1, 0, CS_BLEND_LINEAR, false, false, 0, 0, 0, 0}, CS_ERR_ARG},
        {"time NaN", {10, 10, CS_AA_NONE, 1, NAN, CS_BLEND_LINEAR, false, false, 0, 0, 0, 0}, CS_ERR_NONFINITE},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        cs_status st = cs_frame_begin(&r, ws, sc, &cases[i].o, &err);
        CHECK_STATUS(st, cases[i].want, cases[i].what);
    }
    cs_render_opts o = {10, 10, CS_AA_NONE, 1, 0, CS_BLEND_LINEAR, false, false, 0, 0, 0, 0};
    CHECK_STATUS(cs_frame_begin(&r, ws, NULL, &o, &err), CS_ERR_ARG, "NULL scene");
    CHECK_STATUS(cs_frame_begin(&r, NULL, sc, &o, &err), CS_ERR_ARG, "NULL workspace");
    CHECK_STATUS(cs_frame_begin(&r, ws, sc, NULL, &err), CS_ERR_ARG, "NULL opts");
    CHECK_STATUS(cs_frame_begin(NULL, ws, sc, &o, &err), CS_ERR_ARG, "NULL renderer");

    /* Lines out of range or out of order are refused, not rendered out of bounds. */
    float line[3 * 10];
    CHECK_STATUS(cs_frame_begin(&r, ws, sc, &o, &err), CS_OK, "frame_begin 10x10");
    CHECK(cs_render_line(&r, 10, line) != CS_OK, "render_line(y = height) must be refused");
    CHECK(cs_render_line(&r, -1, line) != CS_OK, "render_line(y = -1) must be refused");
    /* Going backwards is either refused or gives the same line as in order. */
    float line4[3 * 10], again[3 * 10];
    CHECK_STATUS(cs_render_line(&r, 4, line4), CS_OK, "render_line 4");
    CHECK_STATUS(cs_render_line(&r, 5, line), CS_OK, "render_line 5");
    cs_status back = cs_render_line(&r, 4, again);
    CHECK(back != CS_OK || memcmp(line4, again, sizeof line4) == 0,
          "render_line(4) after line 5 was accepted but differs from line 4 rendered in order");
    CHECK_STATUS(cs_render_line(&r, 6, line), CS_OK, "render_line 6 after going backwards");
    CHECK_STATUS(cs_render_line(&r, 7, NULL), CS_ERR_ARG, "render_line with NULL buffer");

    /* A cel transform that takes the contour beyond the coordinate limit in device space. */
    cs_affine big = {3e4f, 0, 0, 3e4f, 0, 0};
    cs_scene *sc2 = tl_calloc(1, sizeof *sc2);
    cs_scene_init(sc2, 100, 100);
    cs_paint paint = tc_white_paint();
    cs_scene_add_cel(sc2, &tc_identity, NULL, NULL, &err);
    cs_scene_add_region(sc2, CS_FILL_NONZERO, &paint, &err);
    cs_point tri[3] = {{10, 10, 1}, {40, 10, 1}, {20, 40, 1}};
    cs_scene_add_contour(sc2, 1, 3, tri, NULL, &err);
    cs_scene_add_cel(sc2, &big, NULL, NULL, &err);
    cs_scene_add_region(sc2, CS_FILL_NONZERO, &paint, &err);
    cs_scene_add_region(sc2, CS_FILL_NONZERO, &paint, &err);
    cs_scene_add_contour(sc2, 1, 3, tri, NULL, &err);
    cs_scene_add_contour(sc2, 1, 3, tri, NULL, &err);
    err = (cs_error){CS_OK, -7, -7, -7, -7};
    cs_render_opts o100 = {100, 100, CS_AA_NONE, 1, 0, CS_BLEND_LINEAR, false, false, 0, 0, 0, 0}; /* canvas units = device pixels */
    cs_status st = cs_frame_begin(&r, ws, sc2, &o100, &err);
    CHECK_STATUS(st, CS_ERR_RANGE, "cel transform scaling points to 1.2e6 device px");
    CHECK(err.cel == 1 && err.region == 1 && err.contour == 0,
          "device range error location: expected cel 1 region 1 contour 0, got cel %d region %d "
          "contour %d",
          (int)err.cel, (int)err.region, (int)err.contour);
    free(sc2);
    free(sc);
    free(s);
}

static void test_status_strings(void)
{
    int bad = 0, dup = 0;
    for (int s = -3; s < CS_ERR_COUNT_ + 5; s++) {
        const char *str = cs_status_str((cs_status)s);
        if (!str || !str[0]) {
            tl_note("cs_status_str(%d) is %s", s, str ? "empty" : "NULL");
            bad++;
            continue;
        }
        for (int t = 0; t < s && s < CS_ERR_COUNT_; t++)
            if (t >= 0 && strcmp(cs_status_str((cs_status)t), str) == 0) {
                tl_note("cs_status_str(%d) == cs_status_str(%d) = \"%s\"", s, t, str);
                dup++;
            }
    }
    CHECK(bad == 0, "%d statuses without a description", bad);
    CHECK(dup == 0, "%d statuses share a description with another", dup);
    CHECK(strstr(cs_status_str(CS_ERR_WEIGHT), "weight") != NULL,
          "CS_ERR_WEIGHT described as \"%s\"", cs_status_str(CS_ERR_WEIGHT));
}

static void test_capacity(void)
{
    cs_error err;
    cs_paint paint = tc_white_paint();
    cs_point tri[3] = {{10, 10, 1}, {40, 10, 1}, {20, 40, 1}};
    cs_scene *before = tl_calloc(1, sizeof *before);

    /* Cels. */
    guarded g = guarded_new();
    cs_scene_init(g.scene, 100, 100);
    int okc = 0;
    for (int i = 0; i < CS_CFG_MAX_CELS; i++)
        okc += cs_scene_add_cel(g.scene, &tc_identity, NULL, NULL, &err) == CS_OK;
    CHECK_EQ_INT(okc, CS_CFG_MAX_CELS, "cels accepted up to capacity");
    memcpy(before, g.scene, sizeof *before);
    CHECK_STATUS(cs_scene_add_cel(g.scene, &tc_identity, NULL, NULL, &err), CS_ERR_CAP_CELS,
                 "one cel beyond capacity");
    CHECK(memcmp(before, g.scene, sizeof *before) == 0, "CAP_CELS changed the scene");
    CHECK(guards_intact(&g), "cel overflow wrote outside the scene");
    free(g.block);

    /* Regions. */
    g = guarded_new();
    cs_scene_init(g.scene, 100, 100);
    cs_scene_add_cel(g.scene, &tc_identity, NULL, NULL, &err);
    int okr = 0;
    for (int i = 0; i < CS_CFG_MAX_REGIONS; i++)
        okr += cs_scene_add_region(g.scene, CS_FILL_NONZERO, &paint, &err) == CS_OK;
    CHECK_EQ_INT(okr, CS_CFG_MAX_REGIONS, "regions accepted up to capacity");
    memcpy(before, g.scene, sizeof *before);
    CHECK_STATUS(cs_scene_add_region(g.scene, CS_FILL_NONZERO, &paint, &err), CS_ERR_CAP_REGIONS,
                 "one region beyond capacity");
    CHECK(memcmp(before, g.scene, sizeof *before) == 0, "CAP_REGIONS changed the scene");
    CHECK(guards_intact(&g), "region overflow wrote outside the scene");
    free(g.block);

    /* Contours. */
    g = guarded_new();
    cs_scene_init(g.scene, 100, 100);
    cs_scene_add_cel(g.scene, &tc_identity, NULL, NULL, &err);
    cs_scene_add_region(g.scene, CS_FILL_NONZERO, &paint, &err);
    int okk = 0;
    for (int i = 0; i < CS_CFG_MAX_CONTOURS; i++)
        okk += cs_scene_add_contour(g.scene, 1, 3, tri, NULL, &err) == CS_OK;
    CHECK_EQ_INT(okk, CS_CFG_MAX_CONTOURS, "contours accepted up to capacity");
    memcpy(before, g.scene, sizeof *before);
    CHECK_STATUS(cs_scene_add_contour(g.scene, 1, 3, tri, NULL, &err), CS_ERR_CAP_CONTOURS,
                 "one contour beyond capacity");
    CHECK(memcmp(before, g.scene, sizeof *before) == 0, "CAP_CONTOURS changed the scene");
    CHECK(guards_intact(&g), "contour overflow wrote outside the scene");
    /* The full scene still renders (3 * CS_CFG_MAX_CONTOURS segments). */
    double *cov = tl_calloc(64 * 64, sizeof *cov);
    CHECK_STATUS(tc_render(g.scene, 64, 64, CS_AA_SUBSCAN, 4, cov), CS_OK,
                 "rendering a scene full of contours");
    free(cov);
    free(g.block);

    /* Points: one huge contour, then one point too many. */
    g = guarded_new();
    cs_scene_init(g.scene, 100, 100);
    cs_scene_add_cel(g.scene, &tc_identity, NULL, NULL, &err);
    cs_scene_add_region(g.scene, CS_FILL_NONZERO, &paint, &err);
    int n = CS_CFG_MAX_POINTS + 1;
    cs_point *many = tl_calloc((size_t)n, sizeof *many);
    for (int k = 0; k < n; k++) {
        double a = 6.283185307179586 * k / n;
        many[k] = (cs_point){(float)(50 + 40 * cos(a)), (float)(50 + 40 * sin(a)), 1};
    }
    memcpy(before, g.scene, sizeof *before);
    CHECK_STATUS(cs_scene_add_contour(g.scene, 1, n, many, NULL, &err), CS_ERR_CAP_POINTS,
                 "a contour of CS_CFG_MAX_POINTS + 1 points");
    CHECK(memcmp(before, g.scene, sizeof *before) == 0, "CAP_POINTS changed the scene");
    CHECK_STATUS(cs_scene_add_contour(g.scene, 1, n - 4, many, NULL, &err), CS_OK,
                 "a contour of CS_CFG_MAX_POINTS - 3 points");
    memcpy(before, g.scene, sizeof *before);
    CHECK_STATUS(cs_scene_add_contour(g.scene, 3, 4, many, NULL, &err), CS_ERR_CAP_POINTS,
                 "4 points when 3 are left");
    CHECK(memcmp(before, g.scene, sizeof *before) == 0, "CAP_POINTS changed the scene");
    CHECK_STATUS(cs_scene_add_contour(g.scene, 2, 3, many, NULL, &err), CS_OK,
                 "3 points when 3 are left");
    CHECK_EQ_INT(g.scene->point_count, CS_CFG_MAX_POINTS, "point_count at capacity");
    CHECK_STATUS(cs_scene_add_contour(g.scene, 1, 2, many, NULL, &err), CS_ERR_CAP_POINTS,
                 "2 points when none are left");
    CHECK(guards_intact(&g), "point overflow wrote outside the scene");
    /* A scene holding CS_CFG_MAX_POINTS points has as many segments: it must render. */
    cov = tl_calloc(64 * 64, sizeof *cov);
    CHECK_STATUS(tc_render(g.scene, 64, 64, CS_AA_SUBSCAN, 2, cov), CS_OK,
                 "rendering a scene full of points");
    free(cov);
    free(many);
    free(g.block);
    free(before);
}

int main(int argc, char **argv)
{
    (void)argc;
    TL_RUN(test_contour_rejections);
    TL_RUN(test_contour_accepted);
    TL_RUN(test_call_order_and_args);
    TL_RUN(test_frame_opts);
    TL_RUN(test_status_strings);
    TL_RUN(test_capacity);
    free(tc_ws_);
    return tl_summary(argv[0]);
}
