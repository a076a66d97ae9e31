/*
 * test_overflow.c - more crossings on one sub-scanline than the workspace
 * holds (CS_CFG_MAX_CROSSINGS, per region) is reported, not survived by luck.
 *
 * The library is built once, so the capacity is reached with geometry: a comb
 * (degree 1) with T teeth puts 2T crossings on every line through the teeth
 * (the pitch shrinks to fit CS_CFG_MAX_WIDTH). T = CS_CFG_MAX_CROSSINGS/2 fits exactly and must render right;
 * one tooth more must give CS_ERR_CAP_CROSSINGS from cs_render_frame (and from
 * cs_frame_error), still produce every line, leave the lines without overflow
 * right, and put no coverage outside the comb (the overflowing region is
 * left out of the sub-scanline, never half-paired into a streak).
 * cs_frame_error says which cel, region and line overflowed first. Under
 * `make test-asan` this also shows that nothing is written out of bounds.
 */
#include "common.h"

#define LEFT 4
#define TOP 5
#define GAP_BOTTOM 30
#define BOTTOM 40
#define H 48

/* Tooth pitch in px: a power of two (exact coordinates) small enough to fit the widest line. */
static double comb_pitch(int teeth)
{
    double pitch = 2;
    while (pitch * teeth + LEFT + 8 > CS_CFG_MAX_WIDTH && pitch > 1.0 / 64)
        pitch /= 2;
    return pitch;
}

/* Comb: teeth [x0 + t*pitch, x0 + (t+1/2)*pitch] x [TOP, BOTTOM], joined below GAP_BOTTOM. */
static void add_comb(tc_shape *s, int teeth, double x0, double pitch)
{
    int n = 0;
    double half = pitch / 2;
    double *xy = tl_calloc((size_t)(4 * teeth + 4), 2 * sizeof(double));
    xy[n++] = x0;
    xy[n++] = BOTTOM;
    for (int t = 0; t < teeth; t++) {
        xy[n++] = x0 + pitch * t;
        xy[n++] = TOP;
        xy[n++] = x0 + pitch * t + half;
        xy[n++] = TOP;
        if (t + 1 < teeth) {
            xy[n++] = x0 + pitch * t + half;
            xy[n++] = GAP_BOTTOM;
            xy[n++] = x0 + pitch * (t + 1);
            xy[n++] = GAP_BOTTOM;
        }
    }
    xy[n++] = x0 + pitch * (teeth - 1) + half;
    xy[n++] = BOTTOM;
    tc_add_xy(s, 1, n / 2, xy, NULL);
    free(xy);
}

typedef struct collect {
    double *cov;
    int width;
} collect;

static cs_status collect_line(void *user, int y, const float *rgb, int width)
{
    collect *c = user;
    for (int x = 0; x < width; x++)
        c->cov[(size_t)y * c->width + x] = rgb[3 * x];
    return CS_OK;
}

static void comb_case(int teeth, cs_fill_rule rule, cs_aa_mode aa, int nsub)
{
    const double pitch = comb_pitch(teeth);
    const double right = LEFT + pitch * (teeth - 1) + pitch / 2; /* right edge of the comb */
    const int W = (int)ceil(right) + 6;
    tc_shape *s = tc_shape_new(rule == CS_FILL_EVENODD);
    add_comb(s, teeth, LEFT, pitch);
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    double *cov = tl_calloc((size_t)W * H, sizeof *cov);
    float *line = tl_calloc((size_t)3 * W, sizeof *line);
    char what[120];
    snprintf(what, sizeof what, "comb of %d teeth at pitch %g px (%d crossings), %s, aa %d/%d",
             teeth, pitch, 2 * teeth, rule ? "evenodd" : "nonzero", (int)aa, nsub);
    if (tc_scene_one(sc, (float)W, H, NULL, s) != CS_OK)
        goto out;
    cs_renderer r;
    cs_render_opts o = {.width = W, .height = H, .aa = aa, .subscanlines = nsub};
    cs_error err;
    cs_status st = cs_frame_begin(&r, tc_workspace(), sc, &o, &err);
    if (!CHECK(st == CS_OK, "%s: cs_frame_begin gave %s", what, tl_status_name(st)))
        goto out;
    collect c = {cov, W};
    st = cs_render_frame(&r, line, collect_line, &c);
    int overflow = 2 * teeth > CS_CFG_MAX_CROSSINGS;
    CHECK(st == (overflow ? CS_ERR_CAP_CROSSINGS : CS_OK), "%s: cs_render_frame gave %s, expected %s",
          what, tl_status_name(st), overflow ? "CS_ERR_CAP_CROSSINGS" : "CS_OK");
    cs_error fe = cs_frame_error(&r);
    CHECK(fe.status == (overflow ? CS_ERR_CAP_CROSSINGS : CS_OK), "%s: cs_frame_error status is %s",
          what, tl_status_name(fe.status));
    if (overflow)
        CHECK(fe.cel == 0 && fe.region == 0 && fe.item == TOP,
              "%s: cs_frame_error location cel %d region %d line %d, expected cel 0 region 0 "
              "line %d (the first line through the teeth)",
              what, (int)fe.cel, (int)fe.region, (int)fe.item, TOP);

    ref_region *ref = tc_ref(s, NULL, 1, 1);
    double *area = tl_calloc((size_t)W * H, sizeof *area);
    ref_coverage_area(ref, W, H, area);
    if (!overflow && aa == CS_AA_NONE) {
        unsigned char *in = tl_calloc((size_t)W * H, 1), *amb = tl_calloc((size_t)W * H, 1);
        ref_coverage_centre(ref, W, H, 1e-3, in, amb);
        tc_expect_centre(what, cov, in, amb, W, H);
        free(in);
        free(amb);
    } else if (!overflow) {
        /* Horizontal edges lie on pixel boundaries, so sub-scanlines are exact here. */
        tc_expect_close(what, cov, area, W, H, 1e-4, 1e-6);
    } else {
        /* Lines outside the teeth band have no overflow and must be exact; no line may carry
         * coverage outside the comb's bounding box. */
        int bad = 0, outside = 0;
        unsigned char *in = tl_calloc((size_t)W * H, 1), *amb = tl_calloc((size_t)W * H, 1);
        ref_coverage_centre(ref, W, H, 1e-3, in, amb);
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                size_t k = (size_t)y * W + x;
                int band = y >= TOP && y < GAP_BOTTOM;
                if (aa == CS_AA_NONE) { /* one sample per pixel: the centre truth */
                    if (amb[k])
                        area[k] = cov[k];
                    else
                        area[k] = in[k] ? 1.0 : 0.0;
                }
                if (!band && fabs(cov[k] - area[k]) > 1e-4 && bad++ < 4)
                    tl_note("%s: pixel (%d,%d) outside the overflow band: expected %.4f got %.4f",
                            what, x, y, area[k], cov[k]);
                if ((x < LEFT || x >= (int)ceil(right)) && cov[k] != 0 && outside++ < 4)
                    tl_note("%s: pixel (%d,%d) outside the comb has coverage %.4f", what, x, y,
                            cov[k]);
                if (!(cov[k] >= 0 && cov[k] <= 1))
                    outside++;
            }
        free(in);
        free(amb);
        CHECK(bad == 0, "%s: %d pixels wrong on lines without overflow", what, bad);
        CHECK(outside == 0, "%s: %d pixels covered outside the comb (streaks) or out of 0..1",
              what, outside);
    }
    free(area);
    ref_region_free(ref);
out:
    free(line);
    free(cov);
    free(sc);
    free(s);
}

static void test_comb_at_capacity(void)
{
    int teeth = CS_CFG_MAX_CROSSINGS / 2;
    comb_case(teeth, CS_FILL_NONZERO, CS_AA_NONE, 1);
    comb_case(teeth, CS_FILL_NONZERO, CS_AA_SUBSCAN, 4);
    comb_case(teeth, CS_FILL_EVENODD, CS_AA_SUBSCAN, 16);
}

static void test_comb_over_capacity(void)
{
    int teeth = CS_CFG_MAX_CROSSINGS / 2 + 1;
    comb_case(teeth, CS_FILL_NONZERO, CS_AA_NONE, 1);
    comb_case(teeth, CS_FILL_NONZERO, CS_AA_SUBSCAN, 4);
    comb_case(teeth, CS_FILL_EVENODD, CS_AA_SUBSCAN, 16);
    comb_case(3 * CS_CFG_MAX_CROSSINGS / 4, CS_FILL_NONZERO, CS_AA_SUBSCAN, 2); /* 1.5x */
}

/* The capacity is per region: two regions with 3/4 of it each on the same lines are fine. */
static void test_two_regions_share_lines(void)
{
    int teeth = 3 * CS_CFG_MAX_CROSSINGS / 8;
    const double pitch = comb_pitch(2 * teeth + 2);
    const double x1 = LEFT + pitch * (teeth + 1);
    const int W = (int)ceil(x1 + pitch * teeth) + 6;
    cs_scene *sc = tl_calloc(1, sizeof *sc);
    tc_shape *a = tc_shape_new(0), *b = tc_shape_new(0);
    add_comb(a, teeth, LEFT, pitch);
    add_comb(b, teeth, x1, pitch);
    cs_error err;
    cs_paint paint = tc_white_paint();
    cs_scene_init(sc, (float)W, H);
    cs_scene_add_cel(sc, &tc_identity, NULL, NULL, &err);
    cs_scene_add_region(sc, CS_FILL_NONZERO, &paint, &err);
    tc_add_contours(sc, a);
    cs_scene_add_region(sc, CS_FILL_NONZERO, &paint, &err);
    cs_status st = tc_add_contours(sc, b);
    CHECK_STATUS(st, CS_OK, "two combs");
    double *cov = tl_calloc((size_t)W * H, sizeof *cov);
    st = tc_render(sc, W, H, CS_AA_SUBSCAN, 4, cov);
    CHECK_STATUS(st, CS_OK, "two regions of 3/4 capacity each on the same lines");
    tc_shape *both = tc_shape_new(0);
    add_comb(both, teeth, LEFT, pitch);
    add_comb(both, teeth, x1, pitch);
    ref_region *ref = tc_ref(both, NULL, 1, 1);
    double *area = tl_calloc((size_t)W * H, sizeof *area);
    ref_coverage_area(ref, W, H, area);
    tc_expect_close("two combs in two regions", cov, area, W, H, 1e-4, 1e-6);
    ref_region_free(ref);
    free(area);
    free(cov);
    free(both);
    free(a);
    free(b);
    free(sc);
}

int main(int argc, char **argv)
{
    (void)argc;
    TL_RUN(test_comb_at_capacity);
    TL_RUN(test_comb_over_capacity);
    TL_RUN(test_two_regions_share_lines);
    free(tc_ws_);
    return tl_summary(argv[0]);
}
