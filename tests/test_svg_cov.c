/*
 * test_svg_cov.c - coverage of stroked paths and text against independent
 * references, at 16, 128 and 512 pixels.
 *
 * Strokes. The reference builds SVG's definition of a stroke directly, in
 * long double: the body of every segment as thin pieces between its normals
 * at closely spaced parameters (each piece a convex quad, or where the
 * normals cross, its two lobes), the joins as polygons (bevel triangle,
 * miter quad within the limit, round sector) and the caps (square, round).
 * The union of these pieces under nonzero winding is scanned by the
 * reference scanner (svg_refscan.c, 256 sub-scanlines per row, exact spans).
 * It shares nothing with the outliner, which fits offset curves instead.
 * The importer's side goes the product's way: SVG text -> sv_import_buffer
 * (stroke tolerance 0.01 px at the output size) -> cs_scene -> core.
 *
 * Text. The reference decodes the font's TrueType points itself (on and off
 * points, implied midpoints) and flattens the quadratics finely; the product
 * goes through FT_Outline_Decompose, NURBS contours and the core. FreeType's
 * own anti-aliasing rasterizer is a second, coarser opinion.
 *
 * Bars (coverage, 0..1, per pixel): the core renders exact area
 * (CS_AA_EXACT, within 1/255 of the true coverage; the bar was set when it
 * was 64 sub-scanlines, where a horizontal edge may be off by 1/128); the
 * reference by 1/512; the stroke outline may
 * move an edge by 0.01 px, i.e. up to 0.014 of a pixel. The maximum bar is
 * their sum rounded up, 0.03; the mean over edge pixels must stay below
 * 0.004 and the total area within 0.1%.
 */
#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_OUTLINE_H
#include FT_BITMAP_H

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../tools/svg/sv.h"
#include "../tools/svg/sv_render.h"
#include "../tools/svg/sv_text.h"
#include "svg_test.h"
#include "svg_refscan.h"

#define PI_L 3.141592653589793238462643383279502884L
#define MAX_BAR 0.03
#define MEAN_BAR 0.004
#define AREA_BAR 1e-3

/* ------------------------------------------------------------- helpers */

typedef struct lpt {
    long double x, y;
} lpt;

static lpt L(long double x, long double y)
{
    lpt p = {x, y};
    return p;
}
static lpt ladd(lpt a, lpt b) { return L(a.x + b.x, a.y + b.y); }
static lpt lsub(lpt a, lpt b) { return L(a.x - b.x, a.y - b.y); }
static lpt lmul(lpt a, long double s) { return L(a.x * s, a.y * s); }
static long double lcross(lpt a, lpt b) { return a.x * b.y - a.y * b.x; }
static long double llen(lpt a) { return sqrtl(a.x * a.x + a.y * a.y); }
static lpt lunit(lpt a) { return lmul(a, 1 / llen(a)); }
static lpt lperp(lpt a) { return L(-a.y, a.x); }

/* A polygon in device pixels, oriented to wind +1 (counter-clockwise in y-up terms). */
static void add_pos(ref_raster *r, const lpt *v, int n)
{
    long double a = 0;
    for (int i = 0; i < n; i++)
        a += lcross(v[i], v[(i + 1) % n]);
    if (a == 0)
        return;
    long double *xy = malloc(sizeof(long double) * 2 * (size_t)n);
    for (int i = 0; i < n; i++) {
        int k = a > 0 ? i : n - 1 - i;
        xy[2 * i] = v[k].x;
        xy[2 * i + 1] = v[k].y;
    }
    ref_add_poly(r, xy, n);
    free(xy);
}

typedef struct cmp_result {
    double max, mean, area_ref, area;
} cmp_result;

static cmp_result compare_cov(const double *ref, const float *got, int n)
{
    cmp_result c = {0, 0, 0, 0};
    int edge = 0;
    for (int i = 0; i < n; i++) {
        double d = fabs(ref[i] - (double)got[i]);
        c.max = fmax(c.max, d);
        c.area_ref += ref[i];
        c.area += got[i];
        if ((ref[i] > 0 && ref[i] < 1) || (got[i] > 0 && got[i] < 1)) {
            c.mean += d;
            edge++;
        }
    }
    c.mean = edge ? c.mean / edge : 0;
    return c;
}

/* Renders the scene's coverage (white paint on black, linear light). */
static float *core_coverage(const cs_scene *scene, int w, int h)
{
    cs_workspace *ws = malloc(sizeof *ws);
    float *out = malloc(sizeof(float) * (size_t)w * h), *line = malloc(sizeof(float) * 3 * (size_t)w);
    cs_renderer r;
    cs_render_opts o = cs_render_defaults(w, h);
    o.aa = CS_AA_EXACT;
    cs_error e;
    cs_status st = cs_frame_begin(&r, ws, scene, &o, &e);
    for (int y = 0; y < h; y++) {
        if (st == CS_OK)
            st = cs_render_line(&r, y, line);
        for (int x = 0; x < w; x++)
            out[(size_t)y * w + x] = st == CS_OK ? line[3 * x] : -1;
    }
    free(ws);
    free(line);
    return out;
}

/* ------------------------------------------------------------- strokes */

typedef enum { RS_LINE, RS_CUBIC, RS_ARC } rs_kind;

typedef struct rseg {
    rs_kind kind;
    lpt p[4];                             /* line: p0 p1; cubic: p0..p3 */
    long double cx, cy, rx, ry, rot, a0, da; /* arc: centre parametrisation */
} rseg;

static lpt rs_eval(const rseg *s, long double t, lpt *d)
{
    if (s->kind == RS_LINE) {
        *d = lsub(s->p[1], s->p[0]);
        return ladd(s->p[0], lmul(*d, t));
    }
    if (s->kind == RS_CUBIC) {
        long double u = 1 - t;
        lpt q = ladd(ladd(lmul(s->p[0], u * u * u), lmul(s->p[1], 3 * u * u * t)),
                     ladd(lmul(s->p[2], 3 * u * t * t), lmul(s->p[3], t * t * t)));
        *d = ladd(ladd(lmul(lsub(s->p[1], s->p[0]), 3 * u * u), lmul(lsub(s->p[2], s->p[1]), 6 * u * t)),
                  lmul(lsub(s->p[3], s->p[2]), 3 * t * t));
        return q;
    }
    long double a = s->a0 + t * s->da, c = cosl(s->rot), sn = sinl(s->rot);
    long double ex = s->rx * cosl(a), ey = s->ry * sinl(a);
    long double dx = -s->rx * sinl(a) * s->da, dy = s->ry * cosl(a) * s->da;
    *d = L(c * dx - sn * dy, sn * dx + c * dy);
    return L(s->cx + c * ex - sn * ey, s->cy + sn * ex + c * ey);
}

static lpt rs_tangent(const rseg *s, long double t)
{
    lpt d;
    rs_eval(s, t, &d);
    if (llen(d) < 1e-15L) { /* a cubic with a zero leg: the limit direction */
        lpt a, b;
        rs_eval(s, fminl(t + 1e-7L, 1), &d);
        a = rs_eval(s, fminl(t + 1e-7L, 1), &d);
        b = rs_eval(s, fmaxl(t - 1e-7L, 0), &d);
        return lunit(lsub(a, b));
    }
    return lunit(d);
}

typedef struct rpath {
    const char *name;
    rseg seg[8];
    int n;
    bool closed;
    double width;
    sv_cap cap;
    sv_join join;
    double limit;
} rpath;

/* SVG path data for the same geometry. */
static void rpath_svg(const rpath *rp, char *buf, size_t len)
{
    size_t k = 0;
    lpt d;
    lpt start = rs_eval(&rp->seg[0], 0, &d);
    k += (size_t)snprintf(buf + k, len - k, "M%.17Lg %.17Lg", start.x, start.y);
    for (int i = 0; i < rp->n; i++) {
        const rseg *s = &rp->seg[i];
        if (s->kind == RS_LINE)
            k += (size_t)snprintf(buf + k, len - k, " L%.17Lg %.17Lg", s->p[1].x, s->p[1].y);
        else if (s->kind == RS_CUBIC)
            k += (size_t)snprintf(buf + k, len - k, " C%.17Lg %.17Lg %.17Lg %.17Lg %.17Lg %.17Lg",
                                  s->p[1].x, s->p[1].y, s->p[2].x, s->p[2].y, s->p[3].x, s->p[3].y);
        else {
            lpt e = rs_eval(s, 1, &d);
            k += (size_t)snprintf(buf + k, len - k, " A%.17Lg %.17Lg %.17Lg %d %d %.17Lg %.17Lg",
                                  s->rx, s->ry, s->rot * 180 / PI_L, fabsl(s->da) > PI_L,
                                  s->da > 0, e.x, e.y);
        }
    }
    if (rp->closed)
        snprintf(buf + k, len - k, " Z");
}

static void ref_join(ref_raster *r, const rpath *rp, lpt v, lpt ta, lpt tb, long double h)
{
    long double cr = lcross(ta, tb), ang = atan2l(cr, ta.x * tb.x + ta.y * tb.y);
    if (fabsl(ang) < 1e-12L)
        return;
    int out = cr > 0 ? -1 : 1;
    lpt na = lmul(lperp(ta), out * h), nb = lmul(lperp(tb), out * h);
    lpt pa = ladd(v, na), pb = ladd(v, nb);
    lpt poly[300];
    int n = 0;
    poly[n++] = v;
    poly[n++] = pa;
    if (rp->join == SV_JOIN_ROUND) {
        long double a0 = atan2l(na.y, na.x);
        for (int i = 1; i < 256; i++) {
            long double a = a0 + ang * i / 256;
            poly[n++] = ladd(v, L(h * cosl(a), h * sinl(a)));
        }
    } else if (rp->join == SV_JOIN_MITER) {
        /* the offset edges' lines meet at the tip; SVG's ratio is tip distance / h */
        long double den = lcross(ta, tb);
        long double lam = lcross(lsub(pb, pa), tb) / den;
        lpt tip = ladd(pa, lmul(ta, lam));
        if (llen(lsub(tip, v)) / h <= rp->limit)
            poly[n++] = tip;
    }
    poly[n++] = pb;
    add_pos(r, poly, n);
}

static void ref_cap(ref_raster *r, const rpath *rp, lpt p, lpt dir, long double h)
{
    lpt n = lmul(lperp(dir), h), e = lmul(dir, h);
    lpt poly[300];
    int k = 0;
    if (rp->cap == SV_CAP_SQUARE) {
        poly[k++] = ladd(p, n);
        poly[k++] = ladd(ladd(p, n), e);
        poly[k++] = ladd(lsub(p, n), e);
        poly[k++] = lsub(p, n);
    } else if (rp->cap == SV_CAP_ROUND) {
        long double a0 = atan2l(n.y, n.x), sweep = lcross(n, e) > 0 ? PI_L : -PI_L;
        for (int i = 0; i <= 256; i++)
            poly[k++] = ladd(p, L(h * cosl(a0 + sweep * i / 256), h * sinl(a0 + sweep * i / 256)));
    } else {
        return;
    }
    add_pos(r, poly, k);
}

/* SVG's stroke definition, scaled by `sc` to device pixels, into r. */
static void ref_stroke(ref_raster *r, const rpath *rp, long double sc)
{
    long double h = rp->width / 2 * sc;
    for (int i = 0; i < rp->n; i++) {
        rseg s = rp->seg[i];
        /* scale the segment to pixels */
        for (int k = 0; k < 4; k++)
            s.p[k] = lmul(s.p[k], sc);
        s.cx *= sc, s.cy *= sc, s.rx *= sc, s.ry *= sc;
        lpt d, prev = rs_eval(&s, 0, &d);
        long double len = 0;
        for (int k = 1; k <= 256; k++) {
            lpt q = rs_eval(&s, k / 256.0L, &d);
            len += llen(lsub(q, prev));
            prev = q;
        }
        int n = (int)fmaxl(256, 4 * len);
        lpt c0 = rs_eval(&s, 0, &d), t0 = rs_tangent(&s, 0);
        for (int k = 1; k <= n; k++) {
            long double t = (long double)k / n;
            lpt c1 = rs_eval(&s, t, &d), t1 = rs_tangent(&s, t);
            lpt a0 = ladd(c0, lmul(lperp(t0), h)), b0 = lsub(c0, lmul(lperp(t0), h));
            lpt a1 = ladd(c1, lmul(lperp(t1), h)), b1 = lsub(c1, lmul(lperp(t1), h));
            /* do the normals a0-b0 and a1-b1 cross inside both? then two lobes */
            lpt e0 = lsub(a0, b0), e1 = lsub(a1, b1);
            long double den = lcross(e0, e1);
            bool lobes = false;
            if (fabsl(den) > 1e-30L) {
                long double u = lcross(lsub(b1, b0), e1) / den, v = lcross(lsub(b1, b0), e0) / den;
                if (u > 0 && u < 1 && v > 0 && v < 1) {
                    lpt x = ladd(b0, lmul(e0, u));
                    add_pos(r, (lpt[]){a0, a1, x}, 3);
                    add_pos(r, (lpt[]){x, b1, b0}, 3);
                    lobes = true;
                }
            }
            if (!lobes)
                add_pos(r, (lpt[]){a0, a1, b1, b0}, 4);
            c0 = c1;
            t0 = t1;
        }
    }
    for (int i = 0; i + 1 < rp->n + (rp->closed ? 1 : 0); i++) {
        const rseg *a = &rp->seg[i], *b = &rp->seg[(i + 1) % rp->n];
        lpt d, v = rs_eval(a, 1, &d);
        ref_join(r, rp, lmul(v, sc), rs_tangent(a, 1), rs_tangent(b, 0), h);
    }
    if (!rp->closed) {
        lpt d, p0 = rs_eval(&rp->seg[0], 0, &d), p1 = rs_eval(&rp->seg[rp->n - 1], 1, &d);
        ref_cap(r, rp, lmul(p0, sc), lmul(rs_tangent(&rp->seg[0], 0), -1), h);
        ref_cap(r, rp, lmul(p1, sc), rs_tangent(&rp->seg[rp->n - 1], 1), h);
    }
}

static rseg line(long double x0, long double y0, long double x1, long double y1)
{
    rseg s = {RS_LINE, {{x0, y0}, {x1, y1}}, 0, 0, 0, 0, 0, 0, 0};
    return s;
}
static rseg cubic(long double x0, long double y0, long double x1, long double y1, long double x2,
                  long double y2, long double x3, long double y3)
{
    rseg s = {RS_CUBIC, {{x0, y0}, {x1, y1}, {x2, y2}, {x3, y3}}, 0, 0, 0, 0, 0, 0, 0};
    return s;
}
static rseg arc(long double cx, long double cy, long double rx, long double ry, long double rot_deg,
                long double a0_deg, long double da_deg)
{
    rseg s = {RS_ARC, {{0, 0}}, cx, cy, rx, ry, rot_deg * PI_L / 180, a0_deg * PI_L / 180,
              da_deg * PI_L / 180};
    return s;
}

static void stroke_case(const svg_test_opts *o, const rpath *rp)
{
    char d[2048], svg[4096], err[256];
    rpath_svg(rp, d, sizeof d);
    static const char *caps[] = {"butt", "round", "square"}, *joins[] = {"miter", "round", "bevel"};
    snprintf(svg, sizeof svg,
             "<svg xmlns='http://www.w3.org/2000/svg' width='64' height='64'>"
             "<path d='%s' fill='none' stroke='white' stroke-width='%.17g' stroke-linecap='%s'"
             " stroke-linejoin='%s' stroke-miterlimit='%.17g'/></svg>",
             d, rp->width, caps[rp->cap], joins[rp->join], rp->limit);
    static const int sizes[] = {16, 128, 512};
    for (int si = 0; si < 3; si++) {
        int px = sizes[si];
        clock_t t0 = clock();
        sv_import_opts io;
        memset(&io, 0, sizeof io);
        io.nominal_px = px; /* 0.01 px at this size */
        sv_doc doc;
        if (sv_import_buffer(svg, strlen(svg), &io, &doc, err, sizeof err) < 0) {
            CHECK(false, "%s: import: %s", rp->name, err);
            return;
        }
        CHECK(doc.nwarnings == 0, "%s: %d warnings (%s)", rp->name, doc.nwarnings,
                  doc.nwarnings ? doc.warnings[0] : "");
        cs_scene *scene = malloc(sizeof *scene);
        sv_scene_opts so = {0};
        CHECK(sv_doc_to_scene(&doc, &so, scene, err, sizeof err) == 0, "%s: scene: %s",
                  rp->name, err);
        float *got = core_coverage(scene, px, px);
        ref_raster rr;
        ref_init(&rr, px, px);
        ref_stroke(&rr, rp, px / 64.0L);
        double *ref = malloc(sizeof(double) * (size_t)px * px);
        ref_render(&rr, 256, ref);
        cmp_result c = compare_cov(ref, got, px * px);
        double area_err = fabs(c.area - c.area_ref) / fmax(c.area_ref, 1);
        printf("  stroke %-26s %3d px: max %.4f mean %.5f area %.5f%% (%zu points, %.1f s)\n",
               rp->name, px, c.max, c.mean, 100 * area_err, sv_doc_point_count(&doc),
               (double)(clock() - t0) / CLOCKS_PER_SEC);
        CHECK(c.max <= MAX_BAR && c.mean <= MEAN_BAR && area_err <= AREA_BAR,
                  "%s at %d px: max %.4f mean %.5f area %.4f%%", rp->name, px, c.max, c.mean,
                  100 * area_err);
        if (o->verbose || c.max > MAX_BAR) { /* the difference image, for a look */
            uint8_t *img = malloc((size_t)3 * px * px * 3);
            for (int y = 0; y < px; y++)
                for (int x = 0; x < px; x++) {
                    size_t i = (size_t)y * px + x, row = (size_t)y * 3 * px;
                    int a = (int)lround(255 * got[i]), b = (int)lround(255 * ref[i]);
                    int df = (int)lround(255 - 2550 * fabs(got[i] - ref[i]));
                    for (int k = 0; k < 3; k++) {
                        img[3 * (row + x) + k] = (uint8_t)a;
                        img[3 * (row + px + x) + k] = (uint8_t)b;
                        img[3 * (row + 2 * px + x) + k] = (uint8_t)(df < 0 ? 0 : df);
                    }
                }
            char path[512];
            snprintf(path, sizeof path, "%s/stroke-%s-%d.png", o->outdir, rp->name, px);
            sv_png_write_rgb(path, img, 3 * px, px);
            free(img);
        }
        free(ref);
        ref_free(&rr);
        free(got);
        free(scene);
        sv_doc_free(&doc);
    }
}

static void test_strokes(const svg_test_opts *o)
{
    rpath cases[5];
    memset(cases, 0, sizeof cases);
    cases[0] = (rpath){"cubic-butt", {cubic(8, 40, 20, 0, 44, 64, 56, 24)}, 1, false, 6,
                       SV_CAP_BUTT, SV_JOIN_MITER, 4};
    cases[1] = (rpath){"zigzag-square-miter",
                       {line(6, 12, 20, 30), line(20, 30, 28, 8), line(28, 8, 44, 30),
                        line(44, 30, 50, 10), line(50, 10, 58, 28)},
                       5, false, 4, SV_CAP_SQUARE, SV_JOIN_MITER, 4};
    cases[2] = (rpath){"closed-arc-round",
                       {line(10, 10, 40, 10), arc(40, 32, 22, 22, 0, -90, 180),
                        cubic(40, 54, 30, 40, 20, 60, 10, 50), line(10, 50, 10, 10)},
                       4, true, 5, SV_CAP_BUTT, SV_JOIN_ROUND, 4};
    cases[3] = (rpath){"tight-loop-bevel", {cubic(10, 50, 70, 0, -10, 0, 50, 50)}, 1, false, 10,
                       SV_CAP_ROUND, SV_JOIN_BEVEL, 4};
    cases[4] = (rpath){"ellipse-arc-bevel",
                       {arc(32, 32, 24, 12, 30, 160, 250), line(0, 0, 0, 0)}, 2, false, 3,
                       SV_CAP_BUTT, SV_JOIN_BEVEL, 4};
    /* the ellipse case continues with a line from the arc's end inwards */
    lpt d, e = rs_eval(&cases[4].seg[0], 1, &d);
    cases[4].seg[1] = line(e.x, e.y, 32, 32);
    for (int i = 0; i < 5; i++)
        stroke_case(o, &cases[i]);
}

/* ---------------------------------------------------------------- text */

/* The glyph's TrueType contours decoded here, flattened finely, in pixels. */
static void ref_glyph(ref_raster *r, const FT_Outline *ol, long double sc, long double ox,
                      long double oy)
{
    int start = 0;
    for (int c = 0; c < ol->n_contours; c++) {
        int end = ol->contours[c], n = end - start + 1;
        lpt *pts = malloc(sizeof(lpt) * (size_t)n);
        bool *on = malloc(sizeof(bool) * (size_t)n);
        for (int i = 0; i < n; i++) {
            pts[i] = L(ox + ol->points[start + i].x * sc, oy - ol->points[start + i].y * sc);
            on[i] = (ol->tags[start + i] & 1) != 0;
        }
        /* start at an on-curve point (or the midpoint of two off points) */
        int first = -1;
        for (int i = 0; i < n && first < 0; i++)
            if (on[i])
                first = i;
        lpt p0 = first >= 0 ? pts[first] : lmul(ladd(pts[0], pts[1]), 0.5L);
        if (first < 0)
            first = 0;
        lpt *poly = NULL;
        int np = 0, cap = 0;
#define PUSH(q)                                                                                  \
    do {                                                                                         \
        if (np == cap) {                                                                         \
            cap = cap ? 2 * cap : 256;                                                           \
            poly = realloc(poly, sizeof(lpt) * (size_t)cap);                                     \
        }                                                                                        \
        poly[np++] = (q);                                                                        \
    } while (0)
        PUSH(p0);
        lpt cur = p0;
        for (int k = 1; k <= n; k++) {
            int i = (first + k) % n;
            if (on[i]) {
                PUSH(pts[i]);
                cur = pts[i];
                continue;
            }
            /* off point: the conic ends at the next on point or the implied midpoint */
            int j = (i + 1) % n;
            lpt to = on[j] ? pts[j] : lmul(ladd(pts[i], pts[j]), 0.5L);
            long double len = llen(lsub(pts[i], cur)) + llen(lsub(to, pts[i]));
            int m = (int)fmaxl(16, 8 * len);
            for (int q = 1; q <= m; q++) {
                long double t = (long double)q / m, u = 1 - t;
                PUSH(ladd(ladd(lmul(cur, u * u), lmul(pts[i], 2 * u * t)), lmul(to, t * t)));
            }
            cur = to;
            if (on[j]) {
                k++; /* the conic consumed the next on point */
            }
        }
        long double *xy = malloc(sizeof(long double) * 2 * (size_t)np);
        for (int i = 0; i < np; i++) {
            xy[2 * i] = poly[i].x;
            xy[2 * i + 1] = poly[i].y;
        }
        ref_add_poly(r, xy, np);
        free(xy);
        free(poly);
        free(pts);
        free(on);
        start = end + 1;
#undef PUSH
    }
}

static void text_case(const svg_test_opts *o, const char *text, int em_px)
{
    /* the canvas is in pixels: em_px per em, baseline at 0.8 em */
    FT_Library lib;
    FT_Face face;
    FT_Init_FreeType(&lib);
    FT_New_Face(lib, SV_DEFAULT_FONT, 0, &face);
    long double sc = (long double)em_px / face->units_per_EM;
    double ox = em_px * 0.1, oy = em_px * 0.8;
    sv_path p;
    sv_path_init(&p);
    sv_text_metrics m;
    char err[256];
    int rule;
    sv_text_path(text, SV_DEFAULT_FONT, em_px, ox, oy, &p, &rule, &m, err, sizeof err);
    int w = (int)ceil(m.advance + em_px * 0.2), h = em_px;
    /* the core */
    cs_scene *scene = malloc(sizeof *scene);
    cs_scene_init(scene, (float)w, (float)h);
    cs_affine id = {1, 0, 0, 1, 0, 0};
    cs_paint white = {{1, 1, 1}, {1, 1, 1}, 1};
    cs_error e;
    cs_scene_add_cel(scene, &id, NULL, NULL, &e);
    CHECK(sv_text_add_region(scene, text, SV_DEFAULT_FONT, em_px, ox, oy, &white, err,
                                 sizeof err) == 0,
              "text region: %s", err);
    float *got = core_coverage(scene, w, h);
    /* the reference: the same pen positions (advances and kerning from the font) */
    ref_raster rr;
    ref_init(&rr, w, h);
    FT_UInt prev = 0;
    long double pen = 0;
    for (const char *c = text; *c; c++) {
        FT_UInt gi = FT_Get_Char_Index(face, (FT_ULong)(unsigned char)*c);
        FT_Vector kv = {0, 0};
        if (prev && FT_HAS_KERNING(face))
            FT_Get_Kerning(face, prev, gi, FT_KERNING_UNSCALED, &kv);
        pen += kv.x;
        FT_Load_Glyph(face, gi, FT_LOAD_NO_SCALE);
        ref_glyph(&rr, &face->glyph->outline, sc, ox + pen * sc, oy);
        pen += face->glyph->advance.x;
        prev = gi;
    }
    double *ref = malloc(sizeof(double) * (size_t)w * h);
    ref_render(&rr, 256, ref);
    cmp_result c = compare_cov(ref, got, w * h);
    double area_err = fabs(c.area - c.area_ref) / fmax(c.area_ref, 1);
    printf("  text \"%s\" %3d px em: max %.4f mean %.5f area %.5f%%\n", text, em_px, c.max,
           c.mean, 100 * area_err);
    CHECK(c.max <= MAX_BAR && c.mean <= MEAN_BAR && area_err <= AREA_BAR,
              "text at %d px: max %.4f mean %.5f area %.4f%%", em_px, c.max, c.mean, 100 * area_err);
    /* FreeType's rasterizer as a second opinion: its outline is rounded to 1/64 px and
     * its curves flattened, so only the mean is held to a (looser) bar */
    double ft_mean = 0;
    int ft_n = 0;
    {
        uint8_t *bm = calloc((size_t)w * h, 1);
        FT_Bitmap bitmap;
        FT_Bitmap_Init(&bitmap);
        bitmap.rows = (unsigned)h;
        bitmap.width = (unsigned)w;
        bitmap.pitch = w;
        bitmap.buffer = bm;
        bitmap.num_grays = 256;
        bitmap.pixel_mode = FT_PIXEL_MODE_GRAY;
        prev = 0;
        pen = 0;
        for (const char *ch = text; *ch; ch++) {
            FT_UInt gi = FT_Get_Char_Index(face, (FT_ULong)(unsigned char)*ch);
            FT_Vector kv = {0, 0};
            if (prev && FT_HAS_KERNING(face))
                FT_Get_Kerning(face, prev, gi, FT_KERNING_UNSCALED, &kv);
            pen += kv.x;
            FT_Load_Glyph(face, gi, FT_LOAD_NO_SCALE);
            FT_Outline *ol = &face->glyph->outline;
            for (int i = 0; i < ol->n_points; i++) { /* to 26.6 pixels, y up from the bottom */
                ol->points[i].x = (FT_Pos)lroundl((ox + (pen + ol->points[i].x) * sc) * 64);
                ol->points[i].y = (FT_Pos)lroundl((h - oy + ol->points[i].y * sc) * 64);
            }
            FT_Raster_Params params;
            memset(&params, 0, sizeof params);
            FT_Bitmap one;
            FT_Bitmap_Init(&one);
            uint8_t *tmp = calloc((size_t)w * h, 1);
            one = bitmap;
            one.buffer = tmp;
            FT_Outline_Get_Bitmap(lib, ol, &one);
            for (size_t i = 0; i < (size_t)w * h; i++) /* glyphs do not overlap here */
                bm[i] = (uint8_t)(bm[i] + tmp[i] > 255 ? 255 : bm[i] + tmp[i]);
            free(tmp);
            pen += face->glyph->advance.x;
            prev = gi;
        }
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                double f = bm[(size_t)y * w + x] / 255.0; /* positive pitch: top row first */
                double g = got[(size_t)y * w + x];
                if ((f > 0 && f < 1) || (g > 0 && g < 1)) {
                    ft_mean += fabs(f - g);
                    ft_n++;
                }
            }
        free(bm);
    }
    ft_mean = ft_n ? ft_mean / ft_n : 0;
    printf("  text \"%s\" %3d px em: FreeType rasterizer differs by %.4f on average at edges\n",
           text, em_px, ft_mean);
    CHECK(ft_mean <= 0.02, "text at %d px against FreeType: mean %.4f", em_px, ft_mean);
    if (o->verbose) {
        uint8_t *img = malloc((size_t)3 * w * h);
        for (size_t i = 0; i < (size_t)w * h; i++)
            img[3 * i] = img[3 * i + 1] = img[3 * i + 2] = (uint8_t)lround(255 * got[i]);
        char path[512];
        snprintf(path, sizeof path, "%s/text-%d.png", o->outdir, em_px);
        sv_png_write_rgb(path, img, w, h);
        free(img);
    }
    free(ref);
    ref_free(&rr);
    free(got);
    free(scene);
    sv_path_free(&p);
    FT_Done_Face(face);
    FT_Done_FreeType(lib);
}

void test_svg_cov(const svg_test_opts *o)
{
    printf("svg-coverage: strokes and text against independent references (bars: max %.3f, "
           "mean %.3f, area %.2f%%)\n", MAX_BAR, MEAN_BAR, 100 * AREA_BAR);
    test_strokes(o);
    static const int sizes[] = {16, 128, 512};
    /* at most 4096 px wide (CS_CFG_MAX_WIDTH): about 7 em at 512 px */
    for (int i = 0; i < 3; i++)
        text_case(o, "AVo&Qg 42", sizes[i]);
}
