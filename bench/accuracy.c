/*
 * accuracy.c - how close each renderer's coverage is to the exact area.
 *
 * Speed only counts at equal or better quality, so every speed figure comes
 * with this one. The truth is the test suite's independent reference
 * (tests/ref: long double NURBS evaluation from the knot vector, dense
 * flattening to 2e-6 px, exact polygon area per pixel), which is far too
 * slow for whole 1080p scenes of hundreds of curved shapes but fine for
 * single shapes. So the measure is per shape: an even sample of the scene's
 * contours, each drawn alone in opaque white on black, in its own cel
 * transform at the benchmark's output size, over its bounding box (one pixel
 * of margin). Every renderer draws exactly that:
 *
 *   celscan   a one-cel, one-region scene through cs_render_line; the linear
 *             output of a white opaque paint over black is the coverage, as
 *             a float (celscan composites in float; it never quantizes
 *             coverage to 8 bits);
 *   cairo     an A8 surface, default antialias, tolerance 0.1 (default) and
 *             0.01 ("fine");
 *   FreeType  the smooth rasterizer's spans (8-bit coverage);
 *   AGG       its scanline rasterizer into an 8-bit grey buffer, with its
 *             default curve flattening (8-bit coverage).
 *
 * Errors are in 1/255 of full coverage: the largest over every pixel of the
 * box, and the mean over edge pixels (exact coverage strictly between 0 and
 * 1; interior and exterior pixels are right for every renderer).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "ref/ref.h"

const char *const acc_names[ACC_COUNT] = {
    "celscan --aa none", "celscan --aa 16", "celscan --aa exact",
    "cairo (tolerance 0.1, default)", "cairo (tolerance 0.01)", "FreeType smooth",
    "AGG (defaults)"};

static void add_stats(acc_stats *s, const double *cov, const double *exact, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        double e = fabs(cov[i] - exact[i]) * 255.0;
        if (e > s->max_err)
            s->max_err = e;
        if (exact[i] > 1e-9 && exact[i] < 1.0 - 1e-9) {
            s->sum_err += e;
            s->edge_pixels++;
            if (e > 1.0)
                s->over_1++;
        }
    }
    s->shapes++;
}

/* celscan's coverage of contour `ci` alone, rows [y0, y0+h), columns [x0, x0+w). */
static int celscan_coverage(const cs_scene *scene, cs_scene *one, cs_workspace *ws, float *line,
                            int width, int height, uint32_t cel, uint32_t reg, uint32_t ci,
                            cs_aa_mode aa, int x0, int y0, int w, int h, double *out)
{
    const cs_region *region = &scene->regions[reg];
    const cs_contour *c = &scene->contours[ci];
    cs_error e;
    cs_paint white = {{1, 1, 1}, {1, 1, 1}, 1.0f};
    if (cs_scene_init(one, scene->canvas_w, scene->canvas_h) ||
        cs_scene_add_cel(one, &scene->cels[cel].transform, NULL, NULL, &e) ||
        cs_scene_add_region(one, (cs_fill_rule)region->fill_rule, &white, &e) ||
        cs_scene_add_contour(one, c->degree, c->point_count, &scene->points[c->first_point],
                             &scene->intervals[c->first_point], &e))
        return -1;
    cs_render_opts o = cs_render_defaults(width, height);
    o.aa = aa;
    cs_renderer r;
    if (cs_frame_begin(&r, ws, one, &o, &e) != CS_OK)
        return -1;
    for (int y = 0; y < h; y++) {
        if (cs_render_line(&r, y0 + y, line) != CS_OK)
            return -1;
        for (int x = 0; x < w; x++)
            out[(size_t)y * w + x] = line[3 * (x0 + x)];
    }
    return 0;
}

int acc_measure(const cs_scene *scene, int width, int height, int max_shapes, peer_ft *ft,
                acc_stats out[ACC_COUNT], double *ref_s)
{
    memset(out, 0, ACC_COUNT * sizeof *out);
    *ref_s = 0.0;
    /* Every contour of a plain (non-CSG) region, with its region and cel. */
    uint32_t n = 0, *shape = malloc(3 * (scene->contour_count + 1) * sizeof *shape);
    for (uint32_t ci = 0; ci < scene->cel_count; ci++) {
        const cs_cel *cel = &scene->cels[ci];
        for (uint32_t ri = cel->first_region; ri < cel->first_region + cel->region_count; ri++) {
            const cs_region *reg = &scene->regions[ri];
            for (uint32_t k = 0; k < reg->contour_count && !reg->csg_len; k++) {
                shape[3 * n] = ci;
                shape[3 * n + 1] = ri;
                shape[3 * n + 2] = reg->first_contour + k;
                n++;
            }
        }
    }
    cs_scene *one = calloc(1, sizeof *one);
    cs_workspace *ws = calloc(1, sizeof *ws);
    float *line = malloc((size_t)width * 3 * sizeof *line);
    int rc = (one && ws && line && shape) ? 0 : -1;
    uint32_t take = (uint32_t)max_shapes < n ? (uint32_t)max_shapes : n;
    for (uint32_t s = 0; s < take && rc == 0; s++) {
        uint32_t pick = (uint32_t)(((double)s + 0.5) * n / take);
        uint32_t cel = shape[3 * pick], reg = shape[3 * pick + 1], ci = shape[3 * pick + 2];
        bool evenodd = scene->regions[reg].fill_rule == CS_FILL_EVENODD;
        double m[6];
        ol_cel_device_map(scene, (int)cel, width, height, m);
        ol_set tmp;
        memset(&tmp, 0, sizeof tmp);
        tmp.width = width;
        tmp.height = height;
        ol_contour oc;
        if (ol_add_contour(&tmp, scene, (int)ci, m, &oc) != 0) {
            rc = -1;
            break;
        }
        double bx0 = oc.x0, bx1 = oc.x0, by0 = oc.y0, by1 = oc.y0;
        for (int i = oc.first; i < oc.first + oc.count; i++)
            for (int q = 0; q < tmp.cmds[i].op; q++) {
                bx0 = fmin(bx0, tmp.cmds[i].p[2 * q]);
                bx1 = fmax(bx1, tmp.cmds[i].p[2 * q]);
                by0 = fmin(by0, tmp.cmds[i].p[2 * q + 1]);
                by1 = fmax(by1, tmp.cmds[i].p[2 * q + 1]);
            }
        int x0 = (int)fmax(0, floor(bx0) - 1), y0 = (int)fmax(0, floor(by0) - 1);
        int x1 = (int)fmin(width, ceil(bx1) + 1), y1 = (int)fmin(height, ceil(by1) + 1);
        if (x1 <= x0 || y1 <= y0) {
            ol_free(&tmp);
            continue;
        }
        int w = x1 - x0, h = y1 - y0;
        size_t np = (size_t)w * h;
        double *exact = malloc(np * sizeof *exact), *cov = malloc(np * sizeof *cov);

        /* The reference, from the scene's own floats. */
        double t0 = bench_now();
        const cs_contour *c = &scene->contours[ci];
        float *xyw = malloc((size_t)c->point_count * 3 * sizeof *xyw);
        for (int k = 0; k < c->point_count; k++) {
            const cs_point *p = &scene->points[c->first_point + k];
            xyw[3 * k] = p->x;
            xyw[3 * k + 1] = p->y;
            xyw[3 * k + 2] = p->w;
        }
        ref_region *rr = ref_region_new(evenodd);
        ref_region_add(rr, c->degree, c->point_count, xyw, &scene->intervals[c->first_point]);
        const cs_affine *t = &scene->cels[cel].transform;
        long double mt[6] = {t->a, t->b, t->c, t->d, t->e, t->f};
        long double shift[6] = {1, 0, 0, 1, -x0, -y0};
        ref_region_transform(rr, mt, (long double)width / scene->canvas_w,
                             (long double)height / scene->canvas_h);
        ref_region_transform(rr, shift, 1, 1);
        ref_coverage_area(rr, w, h, exact);
        ref_region_free(rr);
        free(xyw);
        *ref_s += bench_now() - t0;

        static const cs_aa_mode modes[3] = {CS_AA_NONE, CS_AA_SUBSCAN, CS_AA_EXACT};
        for (int k = 0; k < 3 && rc == 0; k++) {
            rc = celscan_coverage(scene, one, ws, line, width, height, cel, reg, ci, modes[k], x0,
                                  y0, w, h, cov);
            if (rc == 0)
                add_stats(&out[ACC_CS_NONE + k], cov, exact, np);
        }
        peer_cairo_coverage(&tmp, &oc, evenodd, 0.1, x0, y0, w, h, cov);
        add_stats(&out[ACC_CAIRO], cov, exact, np);
        peer_cairo_coverage(&tmp, &oc, evenodd, 0.01, x0, y0, w, h, cov);
        add_stats(&out[ACC_CAIRO_FINE], cov, exact, np);
        if (peer_ft_coverage(ft, &tmp, &oc, evenodd, x0, y0, w, h, cov) == 0)
            add_stats(&out[ACC_FT], cov, exact, np);
        else
            rc = -1;
        peer_agg_coverage(&tmp, &oc, evenodd, x0, y0, w, h, cov);
        add_stats(&out[ACC_AGG], cov, exact, np);
        free(exact);
        free(cov);
        ol_free(&tmp);
    }
    free(shape);
    free(one);
    free(ws);
    free(line);
    return rc;
}
