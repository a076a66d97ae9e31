/*
 * test_csg.c - CSG programs over a region's contours
 * (cs_scene_set_region_csg, cs_scene_set_contour_operand).
 *
 * Each operand is a circle or a polygon; the reference knows its exact
 * membership, combines the operands with the same RPN program and
 * integrates the coverage of every pixel on 512 rows per pixel with exact
 * horizontal intervals, in long double. The core's coverage (white on
 * nothing, so the output is the coverage) must match it; programs and
 * operands that cannot run are refused with CS_ERR_CSG.
 *
 * On tests/testlib.h; the last line is `test_csg: N passed, M failed`.
 */
#include "beta_common.h"

/* ------------------------------------------------------------- 7. CSG */

/* The reference: shapes with exact membership, combined by the same RPN. */
typedef struct shape {
    int kind; /* 0 circle, 1 polygon */
    double cx, cy, r;
    const double *xy;
    int n;
    int operand;
} shape;

/* x positions where row y crosses the shape's boundary. */
static int shape_breaks(const shape *s, long double y, long double *out)
{
    if (s->kind == 0) {
        long double dy = y - s->cy, q = (long double)s->r * s->r - dy * dy;
        if (q <= 0)
            return 0;
        long double h = sqrtl(q);
        out[0] = s->cx - h;
        out[1] = s->cx + h;
        return 2;
    }
    int k = 0;
    for (int i = 0; i < s->n; i++) {
        long double x0 = s->xy[2 * i], y0 = s->xy[2 * i + 1];
        long double x1 = s->xy[2 * ((i + 1) % s->n)], y1 = s->xy[2 * ((i + 1) % s->n) + 1];
        if ((y0 <= y && y < y1) || (y1 <= y && y < y0))
            out[k++] = x0 + (y - y0) * (x1 - x0) / (y1 - y0);
    }
    return k;
}

static int shape_inside(const shape *s, long double x, long double y)
{
    if (s->kind == 0)
        return (x - s->cx) * (x - s->cx) + (y - s->cy) * (y - s->cy) < (long double)s->r * s->r;
    int in = 0;
    for (int i = 0; i < s->n; i++) {
        long double x0 = s->xy[2 * i], y0 = s->xy[2 * i + 1];
        long double x1 = s->xy[2 * ((i + 1) % s->n)], y1 = s->xy[2 * ((i + 1) % s->n) + 1];
        if ((y0 <= y && y < y1) || (y1 <= y && y < y0))
            if (x < x0 + (y - y0) * (x1 - x0) / (y1 - y0))
                in ^= 1;
    }
    return in;
}

/* Evaluates the RPN over operand memberships (operand = evenodd of its shapes). */
static int rpn_eval(const int *rpn, int len, const int *in_operand)
{
    int st[32], sp = 0;
    for (int i = 0; i < len; i++) {
        if (rpn[i] >= 0) {
            st[sp++] = in_operand[rpn[i]];
            continue;
        }
        int b = st[--sp], a = st[--sp];
        st[sp++] = rpn[i] == CS_CSG_UNION       ? (a || b)
                   : rpn[i] == CS_CSG_INTERSECT ? (a && b)
                   : rpn[i] == CS_CSG_DIFFERENCE ? (a && !b)
                                                 : (a != b);
    }
    return st[0];
}

static void reference_coverage(const shape *sh, int ns, const int *rpn, int len, int w, int h,
                               double *cov)
{
    const int rows = 512;
    for (int i = 0; i < w * h; i++)
        cov[i] = 0;
    long double brk[64];
    for (int y = 0; y < h; y++)
        for (int k = 0; k < rows; k++) {
            long double ys = y + (k + 0.5L) / rows;
            int nb = 0;
            for (int s = 0; s < ns; s++)
                nb += shape_breaks(&sh[s], ys, brk + nb);
            brk[nb++] = 0;
            brk[nb++] = w;
            for (int i = 1; i < nb; i++) /* insertion sort */
                for (int j = i; j > 0 && brk[j - 1] > brk[j]; j--) {
                    long double t = brk[j];
                    brk[j] = brk[j - 1];
                    brk[j - 1] = t;
                }
            for (int i = 0; i + 1 < nb; i++) {
                long double a = brk[i] < 0 ? 0 : brk[i], b = brk[i + 1] > w ? w : brk[i + 1];
                if (!(b > a))
                    continue;
                long double mid = 0.5L * (a + b);
                int in_op[8] = {0};
                for (int s = 0; s < ns; s++)
                    in_op[sh[s].operand] ^= shape_inside(&sh[s], mid, ys);
                if (!rpn_eval(rpn, len, in_op))
                    continue;
                for (int px = (int)a; px < w && px < b; px++)
                    cov[y * w + px] += (double)(overlap((double)a, (double)b, px) / rows);
            }
        }
}

/* Coverage as celscan renders it: white paint, black surround. */
static void celscan_coverage(const shape *sh, int ns, const int *rpn, int len, int w, int h,
                             int aa, double *cov)
{
    cs_scene *s = &g_scene;
    cs_scene_init(s, (float)w, (float)h);
    add_cel(s, NULL, NULL, NULL);
    cs_paint p = paint(1, 1, 1, 0, 0, 0, 1);
    cs_error e;
    cs_scene_add_region(s, CS_FILL_EVENODD, &p, &e);
    if (len > 0) {
        cs_status st = cs_scene_set_region_csg(s, rpn, len, &e);
        CHECK(st == CS_OK, "set csg: %s", cs_status_str(st));
    }
    for (int i = 0; i < ns; i++) {
        if (sh[i].kind == 0)
            TL_MUST(ts_add_circle(s, sh[i].cx, sh[i].cy, sh[i].r));
        else
            TL_MUST(ts_add_polygon(s, sh[i].xy, sh[i].n));
        cs_scene_set_contour_operand(s, sh[i].operand, &e);
    }
    cs_render_opts o = opts_n(w, h, 64);
    o.aa = aa ? CS_AA_EXACT : CS_AA_SUBSCAN;
    CHECK(render(s, &o, NULL, img_c) == CS_OK, "render csg");
    for (int i = 0; i < w * h; i++)
        cov[i] = img_c[3 * i];
}

static double cov_ref[64 * 64], cov_got[64 * 64], cov_a[64 * 64], cov_b[64 * 64],
    cov_ab[64 * 64];

static void test_csg(void)
{
    static const double tri[6] = {6, 58, 60, 50.5, 30.3, 6.2};
    static const double square[8] = {20.5, 20.5, 44.25, 20.5, 44.25, 44.75, 20.5, 44.75};
    /* Operands: 0 = circle A, 1 = circle B, 2 = triangle, 3 = ring (two
     * circles in one operand: evenodd makes it a ring), 4 = square. */
    const shape sh[] = {
        {0, 24, 28, 15.5, NULL, 0, 0}, {0, 38.3, 31.7, 13.2, NULL, 0, 1},
        {1, 0, 0, 0, tri, 3, 2},       {0, 32, 32, 27, NULL, 0, 3},
        {0, 32, 32, 22.5, NULL, 0, 3}, {1, 0, 0, 0, square, 4, 4},
    };
    const int ns = 6;
    struct {
        const char *name;
        int rpn[8];
        int len;
    } progs[] = {
        {"A union B", {0, 1, CS_CSG_UNION}, 3},
        {"A intersect B", {0, 1, CS_CSG_INTERSECT}, 3},
        {"A - B", {0, 1, CS_CSG_DIFFERENCE}, 3},
        {"A xor B", {0, 1, CS_CSG_XOR}, 3},
        {"(A - B) u tri", {0, 1, CS_CSG_DIFFERENCE, 2, CS_CSG_UNION}, 5},
        {"tri n (A u B)", {2, 0, 1, CS_CSG_UNION, CS_CSG_INTERSECT}, 5},
        {"ring - square", {3, 4, CS_CSG_DIFFERENCE}, 3},
        {"ring xor tri", {3, 2, CS_CSG_XOR}, 3},
    };
    const int W = 64, H = 64;
    for (unsigned p = 0; p < sizeof progs / sizeof progs[0]; p++) {
        reference_coverage(sh, ns, progs[p].rpn, progs[p].len, W, H, cov_ref);
        for (int aa = 0; aa < 2; aa++) {
            celscan_coverage(sh, ns, progs[p].rpn, progs[p].len, W, H, aa, cov_got);
            double worst = 0, sum = 0, area_ref = 0, area_got = 0;
            for (int i = 0; i < W * H; i++) {
                double d = fabs(cov_got[i] - cov_ref[i]);
                worst = d > worst ? d : worst;
                sum += d;
                area_ref += cov_ref[i];
                area_got += cov_got[i];
            }
            /* 64 sub-scanlines: per pixel the midpoint rule errs by at most
             * half a sub-scanline's height across the pixel (1/128). */
            CHECK(worst <= 1.0 / 128 + 1e-4 && sum / (W * H) < 1e-3,
                  "csg %s (aa %d): worst %.4f mean %.2e", progs[p].name, aa, worst,
                  sum / (W * H));
            CHECK(fabs(area_got - area_ref) < 0.05, "csg %s area %.3f vs %.3f", progs[p].name,
                  area_got, area_ref);
            if (aa == 0)
                printf("  csg %-14s area %8.3f ref %8.3f  worst %.4f  mean %.1e\n",
                       progs[p].name, area_got, area_ref, worst, sum / (W * H));
        }
    }
    /* Identities on the renderer's own coverage (same samples, so tight):
     * |A u B| + |A n B| = |A| + |B|, |A - B| = |A| - |A n B|,
     * |A xor B| = |A u B| - |A n B|. */
    int ra[] = {0}, rb[] = {1}, run[] = {0, 1, CS_CSG_UNION}, rin[] = {0, 1, CS_CSG_INTERSECT};
    int rdf[] = {0, 1, CS_CSG_DIFFERENCE}, rx[] = {0, 1, CS_CSG_XOR};
    celscan_coverage(sh, ns, ra, 1, W, H, 0, cov_a);
    celscan_coverage(sh, ns, rb, 1, W, H, 0, cov_b);
    celscan_coverage(sh, ns, rin, 3, W, H, 0, cov_ab);
    double w1 = 0, w2 = 0, w3 = 0;
    celscan_coverage(sh, ns, run, 3, W, H, 0, cov_got);
    for (int i = 0; i < W * H; i++)
        w1 = fmax(w1, fabs(cov_got[i] + cov_ab[i] - cov_a[i] - cov_b[i]));
    celscan_coverage(sh, ns, rdf, 3, W, H, 0, cov_got);
    for (int i = 0; i < W * H; i++)
        w2 = fmax(w2, fabs(cov_got[i] - (cov_a[i] - cov_ab[i])));
    celscan_coverage(sh, ns, rx, 3, W, H, 0, cov_ref);
    celscan_coverage(sh, ns, run, 3, W, H, 0, cov_got);
    for (int i = 0; i < W * H; i++)
        w3 = fmax(w3, fabs(cov_ref[i] - (cov_got[i] - cov_ab[i])));
    CHECK(w1 < 1e-4 && w2 < 1e-4 && w3 < 1e-4, "csg identities: %.2e %.2e %.2e", w1, w2, w3);
    /* A region without CSG ignores operands: contours wind together. */
    cs_scene *s = &g_scene;
    cs_scene_init(s, 64, 64);
    add_cel(s, NULL, NULL, NULL);
    add_region(s, paint(1, 1, 1, 0, 0, 0, 1));
    cs_error e;
    TL_MUST(ts_add_circle(s, 24, 28, 15.5));
    cs_scene_set_contour_operand(s, 3, &e);
    cs_render_opts o = opts_n(64, 64, 64);
    render(s, &o, NULL, img_c);
    int rq[] = {0};
    shape one = sh[0];
    reference_coverage(&one, 1, rq, 1, W, H, cov_ref);
    double worst = 0;
    for (int i = 0; i < W * H; i++)
        worst = fmax(worst, fabs(img_c[3 * i] - cov_ref[i]));
    CHECK(worst <= 1.0 / 128 + 1e-4, "no-csg region with an operand set: %.4f", worst);
}

static void test_csg_validation(void)
{
    cs_scene *s = &g_scene;
    cs_scene_init(s, 10, 10);
    cs_error e;
    int bad_under[] = {0, CS_CSG_UNION};
    int bad_left[] = {0, 1};
    int bad_op[] = {0, 1, -9};
    int bad_operand[] = {CS_CFG_MAX_OPERANDS};
    int good[] = {0, 1, CS_CSG_XOR};
    CHECK(cs_scene_set_region_csg(s, good, 3, &e) == CS_ERR_STATE, "csg before any region");
    add_cel(s, NULL, NULL, NULL);
    add_region(s, paint(1, 1, 1, 0, 0, 0, 1));
    CHECK(cs_scene_set_region_csg(s, bad_under, 2, &e) == CS_ERR_CSG && e.item == 1,
          "operator without two inputs (item %d)", e.item);
    CHECK(cs_scene_set_region_csg(s, bad_left, 2, &e) == CS_ERR_CSG, "two results left");
    CHECK(cs_scene_set_region_csg(s, bad_op, 3, &e) == CS_ERR_CSG && e.item == 2, "bad operator");
    CHECK(cs_scene_set_region_csg(s, bad_operand, 1, &e) == CS_ERR_CSG, "operand out of range");
    CHECK(cs_scene_set_region_csg(s, good, 0, &e) == CS_ERR_CSG, "empty program");
    CHECK(cs_scene_set_region_csg(s, good, CS_CFG_MAX_CSG + 1, &e) == CS_ERR_CSG, "too long");
    CHECK(s->regions[0].csg_len == 0, "rejected programs leave the region unchanged");
    CHECK(cs_scene_set_region_csg(s, good, 3, &e) == CS_OK, "good program");
    CHECK(cs_scene_set_contour_operand(s, 1, &e) == CS_ERR_STATE, "operand before a contour");
    TL_MUST(ts_add_rect(s, 1, 1, 5, 5));
    CHECK(cs_scene_set_contour_operand(s, -1, &e) == CS_ERR_CSG, "negative operand");
    CHECK(cs_scene_set_contour_operand(s, CS_CFG_MAX_OPERANDS, &e) == CS_ERR_CSG,
          "operand too large");
    CHECK(cs_scene_set_contour_operand(s, 1, &e) == CS_OK && s->contours[0].operand == 1,
          "operand set");
}


int main(void)
{
    TL_RUN(test_csg);
    TL_RUN(test_csg_validation);
    return tl_summary("test_csg");
}
