/*
 * test_svg_unit.c - unit checks of the importer's pieces against values
 * worked out by hand or by closed forms: path grammar (every command,
 * relative and absolute, implicit repeats, packed numbers and arc flags),
 * arc geometry (points on the exact ellipse), transforms, colours, lengths,
 * CSS matching, contour conversion (degree, knots, exact elevation), the
 * stroke outliner's areas and offset distances, convex clipping, glyph
 * conversion (TrueType quadratics exact, CFF cubics) and kerning.
 */
#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_OUTLINE_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../tools/svg/sv.h"
#include "../tools/svg/sv_import.h"
#include "../tools/svg/sv_internal.h"
#include "../tools/svg/sv_font.h"
#include "../tools/svg/sv_text.h"
#include "svg_test.h"

static const sv_seg *seg_at(const sv_path *p, int sub, int k)
{
    return (sub < p->n && k < p->sub[sub].n) ? &p->sub[sub].seg[k] : NULL;
}

static bool pt_is(sv_pt p, double x, double y)
{
    return fabs(p.x - x) < 1e-12 && fabs(p.y - y) < 1e-12;
}

static void check_seg(const sv_path *p, int sub, int k, int degree, const double *xy,
                      const char *what)
{
    const sv_seg *s = seg_at(p, sub, k);
    bool ok = s && s->degree == degree;
    for (int i = 0; ok && i <= degree; i++)
        ok = pt_is(s->p[i], xy[2 * i], xy[2 * i + 1]);
    CHECK(ok, "%s: subpath %d segment %d", what, sub, k);
}

static void test_path_commands(void)
{
    sv_path p;
    char err[200];
    /* absolute */
    sv_path_init(&p);
    CHECK(sv_parse_path("M10 20 L30 40 H50 V60 C1 2 3 4 5 6 S7 8 9 10 Q11 12 13 14 T15 16 Z",
                            &p, err, sizeof err) == 0,
              "absolute commands parse");
    check_seg(&p, 0, 0, 1, (double[]){10, 20, 30, 40}, "L");
    check_seg(&p, 0, 1, 1, (double[]){30, 40, 50, 40}, "H");
    check_seg(&p, 0, 2, 1, (double[]){50, 40, 50, 60}, "V");
    check_seg(&p, 0, 3, 3, (double[]){50, 60, 1, 2, 3, 4, 5, 6}, "C");
    /* S reflects (3,4) about (5,6): (7,8) */
    check_seg(&p, 0, 4, 3, (double[]){5, 6, 7, 8, 7, 8, 9, 10}, "S after C");
    check_seg(&p, 0, 5, 2, (double[]){9, 10, 11, 12, 13, 14}, "Q");
    /* T reflects (11,12) about (13,14): (15,16) */
    check_seg(&p, 0, 6, 2, (double[]){13, 14, 15, 16, 15, 16}, "T after Q");
    CHECK(p.n == 1 && p.sub[0].closed, "Z closes the subpath");
    sv_path_free(&p);

    /* relative, with implicit repeats and a subpath after z */
    sv_path_init(&p);
    CHECK(sv_parse_path("m10 20 5 0 0 5 h-2 v-1 c1 0 2 0 3 1 s1 1 2 2 q1 0 1 1 t1 1 z l1 0",
                            &p, err, sizeof err) == 0,
              "relative commands parse");
    check_seg(&p, 0, 0, 1, (double[]){10, 20, 15, 20}, "m then implicit l");
    check_seg(&p, 0, 1, 1, (double[]){15, 20, 15, 25}, "second implicit l");
    check_seg(&p, 0, 2, 1, (double[]){15, 25, 13, 25}, "h");
    check_seg(&p, 0, 3, 1, (double[]){13, 25, 13, 24}, "v");
    check_seg(&p, 0, 4, 3, (double[]){13, 24, 14, 24, 15, 24, 16, 25}, "c");
    check_seg(&p, 0, 5, 3, (double[]){16, 25, 17, 26, 17, 26, 18, 27}, "s");
    check_seg(&p, 0, 6, 2, (double[]){18, 27, 19, 27, 19, 28}, "q");
    check_seg(&p, 0, 7, 2, (double[]){19, 28, 19, 29, 20, 29}, "t");
    check_seg(&p, 1, 0, 1, (double[]){10, 20, 11, 20}, "l after z starts at the subpath start");
    sv_path_free(&p);

    /* S and T without a previous curve use the current point */
    sv_path_init(&p);
    sv_parse_path("M0 0 S1 1 2 0 T4 0", &p, err, sizeof err);
    check_seg(&p, 0, 0, 3, (double[]){0, 0, 0, 0, 1, 1, 2, 0}, "S after M");
    check_seg(&p, 0, 1, 2, (double[]){2, 0, 2, 0, 4, 0}, "T after S");
    sv_path_free(&p);

    /* packed numbers: signs, dots and exponents separate */
    sv_path_init(&p);
    sv_parse_path("M.5.5L-1-2l1e1-.5e1", &p, err, sizeof err);
    check_seg(&p, 0, 0, 1, (double[]){0.5, 0.5, -1, -2}, "packed numbers");
    check_seg(&p, 0, 1, 1, (double[]){-1, -2, 9, -7}, "exponents");
    sv_path_free(&p);

    /* arc flags need no separators: a rx ry rot large sweep x y */
    sv_path_init(&p);
    CHECK(sv_parse_path("M0 0a5 5 0 1010 0", &p, err, sizeof err) == 0, "packed arc flags");
    sv_pt end = p.cur;
    CHECK(pt_is(end, 10, 0), "packed arc ends at (10,0): %g %g", end.x, end.y);
    sv_path_free(&p);

    /* errors keep what was drawn and say where */
    sv_path_init(&p);
    CHECK(sv_parse_path("M0 0 L10 10 L20", &p, err, sizeof err) < 0 && strstr(err, "offset"),
              "truncated data is an error with an offset (%s)", err);
    CHECK(p.n == 1 && p.sub[0].n == 1, "segments before the error are kept");
    sv_path_free(&p);
    sv_path_init(&p);
    CHECK(sv_parse_path("L10 10", &p, err, sizeof err) < 0, "data must start with M");
    CHECK(sv_parse_path("M0 0 X1 1", &p, err, sizeof err) < 0, "unknown command");
    sv_path_free(&p);

    /* polyline points */
    sv_path_init(&p);
    CHECK(sv_parse_points("0,0 10,0 10,10", &p, true) == 3 && p.sub[0].closed &&
                  p.sub[0].n == 2,
              "polygon points");
    sv_path_free(&p);
}

/* Every conic of the arc lies on the ellipse ((x-cx)/rx)^2 + ((y-cy)/ry)^2 = 1 (unrotated). */
static double arc_error(const sv_path *p, double cx, double cy, double rx, double ry, double rot)
{
    double e = 0, c = cos(rot * M_PI / 180), s = sin(rot * M_PI / 180);
    for (int i = 0; i < p->n; i++)
        for (int k = 0; k < p->sub[i].n; k++)
            for (int j = 0; j <= 64; j++) {
                sv_pt q = sv_seg_eval(&p->sub[i].seg[k], j / 64.0);
                double dx = q.x - cx, dy = q.y - cy;
                double u = (c * dx + s * dy) / rx, v = (-s * dx + c * dy) / ry;
                e = fmax(e, fabs(u * u + v * v - 1));
            }
    return e;
}

static void test_arcs(void)
{
    sv_path p;
    char err[100];
    /* semicircle, sweep 1: through (5,-5) (positive angles, y down) */
    sv_path_init(&p);
    sv_parse_path("M0 0 A5 5 0 0 1 10 0", &p, err, sizeof err);
    CHECK(p.sub[0].n == 2, "180 degrees become two conics (%d)", p.sub[0].n);
    CHECK_NEAR(p.sub[0].seg[0].w, sqrt(0.5), 1e-15, "90-degree conic weight cos(45)");
    CHECK(arc_error(&p, 5, 0, 5, 5, 0) < 1e-13, "semicircle points on the circle");
    sv_pt mid = p.sub[0].seg[0].p[2];
    CHECK(pt_is(mid, 5, -5), "sweep-flag 1 passes through (5,-5): %g %g", mid.x, mid.y);
    sv_path_free(&p);
    /* sweep 0 goes the other way */
    sv_path_init(&p);
    sv_parse_path("M0 0 A5 5 0 0 0 10 0", &p, err, sizeof err);
    CHECK(pt_is(p.sub[0].seg[0].p[2], 5, 5), "sweep-flag 0 passes through (5,5)");
    sv_path_free(&p);
    /* radii too small are scaled up (F.6.6) */
    sv_path_init(&p);
    sv_parse_path("M0 0 A1 1 0 0 1 10 0", &p, err, sizeof err);
    CHECK(arc_error(&p, 5, 0, 5, 5, 0) < 1e-13, "scaled-up radii");
    sv_path_free(&p);
    /* large arc: 270 degrees of a circle of radius 10 from (0,0) to (10,10) */
    sv_path_init(&p);
    sv_parse_path("M0 0 A10 10 0 1 1 10 10", &p, err, sizeof err);
    CHECK(p.sub[0].n == 3, "270 degrees become three conics (%d)", p.sub[0].n);
    /* centre: the one for large+sweep, (10,0) */
    CHECK(arc_error(&p, 10, 0, 10, 10, 0) < 1e-13, "large arc on its circle");
    sv_path_free(&p);
    /* rotated ellipse, relative */
    sv_path_init(&p);
    sv_parse_path("M3 4 a8 4 30 0 1 6 5", &p, err, sizeof err);
    /* find the centre from the first conic: check all points on some rotated ellipse with
     * those radii by fitting the centre from the endpoints through the F.6.5 formulas is
     * circular; instead check the conic weights and the end point */
    CHECK(pt_is(p.cur, 9, 9), "relative arc end");
    double cmax = 0;
    for (int k = 0; k < p.sub[0].n; k++)
        cmax = fmax(cmax, p.sub[0].seg[k].w);
    CHECK(cmax <= 1 && cmax >= sqrt(0.5) - 1e-12, "arc pieces at most 90 degrees");
    sv_path_free(&p);
    /* rx = 0: a straight line */
    sv_path_init(&p);
    sv_parse_path("M0 0 A0 5 0 0 1 10 0", &p, err, sizeof err);
    CHECK(p.sub[0].n == 1 && p.sub[0].seg[0].degree == 1, "zero radius arc is a line");
    sv_path_free(&p);
    /* full ellipse: 4 conics, points on it */
    sv_path_init(&p);
    sv_path_ellipse(&p, 1, 2, 7, 3);
    CHECK(p.sub[0].n == 4 && arc_error(&p, 1, 2, 7, 3, 0) < 1e-13, "ellipse");
    CHECK_NEAR(sv_subpath_area(&p.sub[0]), M_PI * 21, 1e-9, "ellipse area by quadrature");
    sv_path_free(&p);
}

static bool aff_eq(sv_affine m, double a, double b, double c, double d, double e, double f)
{
    return fabs(m.a - a) < 1e-12 && fabs(m.b - b) < 1e-12 && fabs(m.c - c) < 1e-12 &&
           fabs(m.d - d) < 1e-12 && fabs(m.e - e) < 1e-12 && fabs(m.f - f) < 1e-12;
}

static void test_transforms(void)
{
    sv_affine m;
    CHECK(sv_parse_transform("translate(10)", &m) && aff_eq(m, 1, 0, 0, 1, 10, 0), "translate(x)");
    CHECK(sv_parse_transform("translate(10,-5)", &m) && aff_eq(m, 1, 0, 0, 1, 10, -5), "translate(x,y)");
    CHECK(sv_parse_transform("scale(2)", &m) && aff_eq(m, 2, 0, 0, 2, 0, 0), "scale(s)");
    CHECK(sv_parse_transform("scale(2 3)", &m) && aff_eq(m, 2, 0, 0, 3, 0, 0), "scale(sx sy)");
    CHECK(sv_parse_transform("rotate(90)", &m) && aff_eq(m, 0, 1, -1, 0, 0, 0), "rotate(90)");
    CHECK(sv_parse_transform("skewX(45)", &m) && aff_eq(m, 1, 0, 1, 1, 0, 0), "skewX(45)");
    CHECK(sv_parse_transform("skewY(45)", &m) && aff_eq(m, 1, 1, 0, 1, 0, 0), "skewY(45)");
    CHECK(sv_parse_transform("matrix(1,2,3,4,5,6)", &m) && aff_eq(m, 1, 2, 3, 4, 5, 6), "matrix");
    /* rotate about a point keeps the point */
    CHECK(sv_parse_transform("rotate(37 3 4)", &m), "rotate(a cx cy)");
    sv_pt q = sv_affine_apply(m, sv_pt_make(3, 4));
    CHECK(pt_is(q, 3, 4), "rotation centre fixed: %g %g", q.x, q.y);
    /* lists apply right to left to points: translate(10) scale(2) maps (1,1) to (12,2) */
    CHECK(sv_parse_transform("translate(10) scale(2)", &m), "transform list");
    q = sv_affine_apply(m, sv_pt_make(1, 1));
    CHECK(pt_is(q, 12, 2), "list order: %g %g", q.x, q.y);
    CHECK(sv_parse_transform("translate(1,2),scale(3)", &m) && aff_eq(m, 3, 0, 0, 3, 1, 2),
              "comma between transforms");
    CHECK(!sv_parse_transform("rotate(1 2)", &m), "rotate with two numbers is an error");
    CHECK(!sv_parse_transform("translate(1", &m), "unclosed parenthesis is an error");
    CHECK(!sv_parse_transform("spin(3)", &m), "unknown transform is an error");
    sv_affine inv;
    sv_parse_transform("matrix(2 1 -1 3 4 5)", &m);
    CHECK(sv_affine_invert(m, &inv) && aff_eq(sv_affine_mul(m, inv), 1, 0, 0, 1, 0, 0),
              "inverse");
    sv_parse_transform("scale(3 2) rotate(30)", &m);
    CHECK_NEAR(sv_affine_max_scale(m), 3, 1e-12, "largest stretch of scale(3 2) rotate(30)");
}

static bool col_is(const char *s, double r, double g, double b, double a)
{
    double rgb[3], al;
    return sv_parse_color(s, rgb, &al) == SV_COLOR_RGB && fabs(rgb[0] - r) < 1e-9 &&
           fabs(rgb[1] - g) < 1e-9 && fabs(rgb[2] - b) < 1e-9 && fabs(al - a) < 1e-9;
}

static void test_colors(void)
{
    CHECK(col_is("#fff", 1, 1, 1, 1), "#rgb");
    CHECK(col_is("#FF8000", 1, 128 / 255.0, 0, 1), "#rrggbb upper case");
    CHECK(col_is("#ff000080", 1, 0, 0, 128 / 255.0), "#rrggbbaa");
    CHECK(col_is("rgb(255, 0, 128)", 1, 0, 128 / 255.0, 1), "rgb()");
    CHECK(col_is("rgb(100%,50%,0%)", 1, 0.5, 0, 1), "rgb() percentages");
    CHECK(col_is("rgba(0,0,255,0.25)", 0, 0, 1, 0.25), "rgba()");
    CHECK(col_is("hsl(120, 100%, 50%)", 0, 1, 0, 1), "hsl()");
    CHECK(col_is("cornflowerblue", 100 / 255.0, 149 / 255.0, 237 / 255.0, 1), "named");
    CHECK(col_is(" RebeccaPurple ", 0x66 / 255.0, 0x33 / 255.0, 0x99 / 255.0, 1),
              "named, any case, spaces");
    CHECK(col_is("grey", 128 / 255.0, 128 / 255.0, 128 / 255.0, 1) &&
                  col_is("gray", 128 / 255.0, 128 / 255.0, 128 / 255.0, 1),
              "grey and gray");
    CHECK(col_is("transparent", 0, 0, 0, 0), "transparent");
    CHECK(sv_named_color_count() == 148, "148 CSS named colours (%d)", sv_named_color_count());
    double rgb[3], a;
    CHECK(sv_parse_color("currentColor", rgb, &a) == SV_COLOR_CURRENT, "currentColor");
    CHECK(sv_parse_color("#ggg", rgb, &a) == SV_COLOR_INVALID, "bad hex");
    CHECK(sv_parse_color("#12345", rgb, &a) == SV_COLOR_INVALID, "bad length");
    CHECK(sv_parse_color("nocolor", rgb, &a) == SV_COLOR_INVALID, "unknown name");
    CHECK_NEAR(sv_srgb_to_linear(0.5), 0.21404114048223255, 1e-15, "sRGB 0.5 to linear");
}

static void test_lengths_css(void)
{
    double v;
    CHECK(sv_parse_length("10px", 12, 0, &v) && v == 10, "px");
    CHECK(sv_parse_length("1in", 12, 0, &v) && fabs(v - 96) < 1e-12, "in is 96 px");
    CHECK(sv_parse_length("2.54cm", 12, 0, &v) && fabs(v - 96) < 1e-12, "cm");
    CHECK(sv_parse_length("72pt", 12, 0, &v) && fabs(v - 96) < 1e-12, "pt");
    CHECK(sv_parse_length("50%", 12, 200, &v) && v == 100, "percent");
    CHECK(sv_parse_length("2em", 12, 0, &v) && v == 24, "em");
    CHECK(!sv_parse_length("abc", 12, 0, &v), "not a length");

    sv_doc doc;
    sv_doc_init(&doc);
    sv_css css = {0};
    sv_css_parse_sheet(&css,
                       "/* c */ .a { fill: red } #b{fill:blue;stroke:green}\n"
                       "path.a.c, rect { fill: #010203 !important } g > path { fill: none }\n"
                       "@media print { path { fill: black } }",
                       &doc);
    CHECK(css.n == 5, "five rules kept, the combinator's too (%d)", css.n);
    CHECK(doc.nwarnings == 1, "@media warned (%d)", doc.nwarnings);
    /* cascade on <path id="b" class="a c" fill="yellow" style="stroke-width:3"> */
    char *attrs[] = {"id", "b", "class", "a c", "fill", "yellow", "style", "stroke-width:3", NULL};
    sv_node n = {.name = "path", .attrs = attrs, .line = 1};
    sv_style root, s;
    sv_style_initial(&root);
    sv_style_compute(&s, &root, &n, &css, 100, &doc);
    /* path.a.c's !important beats #b (specificity 10000 over 201) */
    CHECK(s.fill.kind == SV_PAINT_COLOR && fabs(s.fill.rgb[2] - 3 / 255.0) < 1e-12,
              "!important wins the cascade");
    CHECK(s.stroke.kind == SV_PAINT_COLOR && fabs(s.stroke.rgb[1] - 128 / 255.0) < 1e-12,
              "stroke from the id rule");
    CHECK(s.stroke_width == 3, "style attribute applies last");
    char *attrs2[] = {"class", "a", "fill", "yellow", NULL};
    sv_node n2 = {.name = "circle", .attrs = attrs2, .line = 2};
    sv_style_compute(&s, &root, &n2, &css, 100, &doc);
    CHECK(s.fill.rgb[0] == 1 && s.fill.rgb[1] == 0, "class rule beats the presentation attribute");
    /* currentColor from the color property, inheritance */
    char *attrs3[] = {"style", "color:#00ff00; fill:currentColor; fill-opacity:50%", NULL};
    sv_node n3 = {.name = "g", .attrs = attrs3, .line = 3};
    sv_style_compute(&s, &root, &n3, NULL, 100, &doc);
    CHECK(s.fill.kind == SV_PAINT_CURRENT && s.color[1] == 1 && s.fill_opacity == 0.5,
              "currentColor and percentage opacity");
    char *attrs4[] = {"opacity", "0.5", "fill", "inherit", NULL};
    sv_node n4 = {.name = "rect", .attrs = attrs4, .line = 4};
    sv_style child;
    sv_style_compute(&child, &s, &n4, NULL, 100, &doc);
    CHECK(child.fill.kind == SV_PAINT_CURRENT && child.color[1] == 1 && child.opacity == 0.5 &&
                  child.fill_opacity == 0.5,
              "inherited fill, colour and fill-opacity; own opacity");
    sv_css_free(&css);

    /*
     * Combinators, attribute tests, :first-child, !important against the
     * style attribute, the transform property, on this tree:
     *   <svg> <g id="g" class="x"> <rect id="r1" x="1" lang="en-GB"/> <circle id="c"/> </g> </svg>
     */
    sv_css_parse_sheet(&css,
                       "svg > g > rect { fill: #010000 } g rect[x] { stroke: #020000 }\n"
                       "rect + circle { fill: #030000 } rect ~ circle { stroke: #040000 }\n"
                       "[lang|=en]:first-child { stroke-width: 7 !important }\n"
                       "[id^=r][id$='1'][class~=x], g > circle[id*=c] { opacity: 0.25 }\n"
                       "#c { transform: scale(2) } svg rect:hover { fill: red }",
                       &doc);
    CHECK(css.n == 8, "eight rules, :hover left out (%d)", css.n);
    char *ar[] = {"svg", NULL}, *ag[] = {"id", "g", "class", "x", NULL},
         *a1[] = {"id", "r1", "x", "1", "lang", "en-GB", "style", "stroke-width: 3", NULL},
         *ac[] = {"id", "c", NULL};
    sv_node nr = {.name = "svg", .attrs = ar}, ng = {.name = "g", .attrs = ag},
            n1 = {.name = "rect", .attrs = a1}, nc = {.name = "circle", .attrs = ac};
    sv_node *rk[] = {&ng}, *gk[] = {&n1, &nc};
    nr.kids = rk;
    nr.nkids = 1;
    ng.parent = &nr;
    ng.kids = gk;
    ng.nkids = 2;
    n1.parent = nc.parent = &ng;
    nc.index = 1;
    sv_style_compute(&s, &root, &n1, &css, 100, &doc);
    CHECK(s.fill.rgb[0] == 1 / 255.0 && s.stroke.rgb[0] == 2 / 255.0 && s.stroke_width == 7 &&
                  s.opacity == 1 && !s.has_transform,
              "rect: child and descendant combinators, [x], [lang|=en]:first-child !important "
              "over the style attribute; [class~=x] is not its own");
    sv_style_compute(&s, &root, &nc, &css, 100, &doc);
    CHECK(s.fill.rgb[0] == 3 / 255.0 && s.stroke.rgb[0] == 4 / 255.0 && s.stroke_width == 1 &&
                  s.opacity == 0.25 && s.has_transform && s.transform.a == 2,
              "circle: + and ~ siblings, [id*=c] under >, the transform property");
    sv_css_free(&css);
    sv_doc_free(&doc);
}

/* Independent evaluation of a contour span: rational Bezier from its points. */
static sv_pt contour_span_eval(const sv_contour *c, int span, double t)
{
    int d = c->degree;
    double X = 0, Y = 0, W = 0;
    for (int i = 0; i <= d; i++) {
        int k = (span * d + i) % c->count;
        double b = (d == 1 ? (i ? t : 1 - t)
                    : d == 2 ? (i == 0 ? (1 - t) * (1 - t) : i == 1 ? 2 * t * (1 - t) : t * t)
                             : (i == 0 ? pow(1 - t, 3) : i == 1 ? 3 * t * (1 - t) * (1 - t)
                                : i == 2 ? 3 * t * t * (1 - t) : t * t * t));
        double w = c->pts[3 * k + 2];
        X += b * w * c->pts[3 * k];
        Y += b * w * c->pts[3 * k + 1];
        W += b * w;
    }
    return sv_pt_make(X / W, Y / W);
}

static void test_contours(void)
{
    sv_path p;
    char err[100];
    sv_contour *c = NULL;
    int n = 0;
    /* a polygon is degree 1 with unit intervals */
    sv_path_init(&p);
    sv_parse_path("M0 0 H10 V10 Z M20 20 L30 20 L30 20 Z M0 0 L5 5 M1 1", &p, err, sizeof err);
    sv_path_to_contours(&p, &c, &n);
    CHECK(n == 1, "lines without area and lone moves are dropped (%d)", n);
    CHECK(n >= 1 && c[0].degree == 1 && c[0].count == 3 && c[0].intervals[0] == 1 &&
                  c[0].intervals[2] == 1,
              "triangle: degree 1, 3 points, unit knots");
    for (int i = 0; i < n; i++)
        sv_contour_free(&c[i]);
    free(c);
    c = NULL;
    n = 0;
    sv_path_free(&p);

    /* line + conic arc: degree 2, knots [1,0] per segment, exact elevation of the line */
    sv_path_init(&p);
    sv_parse_path("M0 0 H10 A5 5 0 0 1 0 0 Z", &p, err, sizeof err);
    sv_path_to_contours(&p, &c, &n);
    CHECK(n == 1 && c[0].degree == 2 && c[0].count == 6, "line+arc: degree 2, 3 spans");
    bool knots = n == 1;
    for (int k = 0; knots && k < c[0].count; k++)
        knots = c[0].intervals[k] == (k % 2 == 0 ? 1 : 0);
    CHECK(knots, "degree 2 knots [1,0] per segment");
    double e = 0;
    for (int s = 0; n == 1 && s < 3; s++)
        for (int j = 0; j <= 20; j++) {
            const sv_seg *g = &p.sub[0].seg[s];
            sv_pt a = contour_span_eval(&c[0], s, j / 20.0), b = sv_seg_eval(g, j / 20.0);
            e = fmax(e, sv_len(sv_sub(a, b)));
        }
    CHECK(e < 1e-12, "elevated contour equals the path, same parameter (%g)", e);
    for (int i = 0; i < n; i++)
        sv_contour_free(&c[i]);
    free(c);
    c = NULL;
    n = 0;
    sv_path_free(&p);

    /* conic + cubic: degree 3, the conic elevated in homogeneous coordinates */
    sv_path_init(&p);
    sv_parse_path("M0 0 A10 10 0 0 1 10 10 C5 15 -5 15 0 0", &p, err, sizeof err);
    sv_path_to_contours(&p, &c, &n);
    CHECK(n == 1 && c[0].degree == 3 && c[0].count == 6, "conic+cubic: degree 3");
    e = 0;
    int nseg = n == 1 ? p.sub[0].n : 0;
    for (int s = 0; s < nseg; s++)
        for (int j = 0; j <= 20; j++) {
            sv_pt a = contour_span_eval(&c[0], s, j / 20.0);
            sv_pt b = sv_seg_eval(&p.sub[0].seg[s], j / 20.0);
            e = fmax(e, sv_len(sv_sub(a, b)));
        }
    CHECK(e < 1e-12, "rational cubic elevation exact (%g)", e);
    CHECK(n == 1 && fabs(c[0].pts[3 * 1 + 2] - (1 + 2 * sqrt(0.5)) / 3) < 1e-15,
              "elevated weight (1+2w)/3");
    for (int i = 0; i < n; i++)
        sv_contour_free(&c[i]);
    free(c);
    c = NULL;
    n = 0;
    sv_path_free(&p);

    /* one closed cubic alone is split to reach degree+1 points */
    sv_path_init(&p);
    sv_parse_path("M0 0 C10 0 10 10 0 0 Z", &p, err, sizeof err);
    sv_path_to_contours(&p, &c, &n);
    CHECK(n == 1 && c[0].count == 6, "single-segment contour halved (%d points)",
              n ? c[0].count : 0);
    for (int i = 0; i < n; i++)
        sv_contour_free(&c[i]);
    free(c);
    sv_path_free(&p);
}

/* Area of the union of closed subpaths (nonzero) by point sampling. */
static double union_area(const sv_path *p, double x0, double y0, double x1, double y1, int n)
{
    double cell = (x1 - x0) / n * ((y1 - y0) / n), area = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            sv_pt q = {x0 + (x1 - x0) * (i + 0.5) / n, y0 + (y1 - y0) * (j + 0.5) / n};
            int w = 0;
            for (int k = 0; k < p->n; k++)
                w += sv_subpath_winding(&p->sub[k], q);
            if (w != 0)
                area += cell;
        }
    return area;
}

static double sum_area(const sv_path *p, bool *all_positive)
{
    double a = 0;
    *all_positive = true;
    for (int k = 0; k < p->n; k++) {
        double s = sv_subpath_area(&p->sub[k]);
        *all_positive &= s > 0;
        a += s;
    }
    return a;
}

static void stroke_of(const char *d, double width, sv_cap cap, sv_join join, double limit,
                      sv_path *out)
{
    sv_path p;
    char err[100];
    sv_path_init(&p);
    sv_parse_path(d, &p, err, sizeof err);
    sv_stroke_style st = {width, cap, join, limit, 1e-4, 0};
    sv_path_init(out);
    sv_stroke_path(&p, &st, out);
    sv_path_free(&p);
}

static void test_stroker(void)
{
    sv_path o;
    bool pos;
    /* a line: body only with butt caps, plus squares or semicircles */
    stroke_of("M0 0 L10 0", 2, SV_CAP_BUTT, SV_JOIN_MITER, 4, &o);
    CHECK_NEAR(sum_area(&o, &pos), 20, 1e-12, "butt line area");
    CHECK(pos, "every outline contour winds positively");
    sv_path_free(&o);
    stroke_of("M0 0 L10 0", 2, SV_CAP_SQUARE, SV_JOIN_MITER, 4, &o);
    CHECK_NEAR(sum_area(&o, &pos), 24, 1e-12, "square caps add w/2 each end");
    sv_path_free(&o);
    stroke_of("M0 0 L10 0", 2, SV_CAP_ROUND, SV_JOIN_MITER, 4, &o);
    CHECK_NEAR(sum_area(&o, &pos), 20 + M_PI, 1e-8, "round caps are exact semicircles");
    sv_path_free(&o);
    /* a circle: concentric exact arcs, area 4 pi R h */
    stroke_of("M10 0 A10 10 0 0 1 -10 0 A10 10 0 0 1 10 0 Z", 4, SV_CAP_BUTT, SV_JOIN_MITER, 4, &o);
    CHECK_NEAR(sum_area(&o, &pos), 4 * M_PI * 10 * 2, 1e-8, "stroked circle area");
    CHECK(pos, "circle outline positive");
    sv_path_free(&o);
    /* an L: union areas for miter, bevel and round joins (w = 2, legs 10) */
    stroke_of("M0 0 L10 0 L10 10", 2, SV_CAP_BUTT, SV_JOIN_MITER, 4, &o);
    CHECK_NEAR(union_area(&o, -1, -2, 12, 11, 520), 40, 0.06, "miter L union area");
    sv_path_free(&o);
    stroke_of("M0 0 L10 0 L10 10", 2, SV_CAP_BUTT, SV_JOIN_BEVEL, 4, &o);
    CHECK_NEAR(union_area(&o, -1, -2, 12, 11, 520), 39.5, 0.06, "bevel L union area");
    sv_path_free(&o);
    stroke_of("M0 0 L10 0 L10 10", 2, SV_CAP_BUTT, SV_JOIN_ROUND, 4, &o);
    CHECK_NEAR(union_area(&o, -1, -2, 12, 11, 520), 39 + M_PI / 4, 0.06, "round L union area");
    sv_path_free(&o);
    /* miter limit: a 20 degree turn back needs ratio 1/sin(10deg) = 5.76 > 4: bevel */
    stroke_of("M0 0 L10 0 L0 3.5265", 2, SV_CAP_BUTT, SV_JOIN_MITER, 4, &o);
    double bevel = union_area(&o, -2, -2, 13, 6, 500);
    sv_path_free(&o);
    stroke_of("M0 0 L10 0 L0 3.5265", 2, SV_CAP_BUTT, SV_JOIN_MITER, 6, &o);
    double miter = union_area(&o, -2, -2, 13, 6, 500);
    sv_path_free(&o);
    /* the miter tip adds the triangle beyond the bevel: h^2 (1/tan(a/2) ... ) > 0.5 */
    CHECK(miter > bevel + 1.0, "miter beyond the limit becomes bevel (%g vs %g)", miter, bevel);

    /* offsets of a cubic lie at w/2 from the curve within the tolerance */
    sv_path p;
    char err[100];
    sv_path_init(&p);
    sv_parse_path("M0 0 C30 -40 60 40 90 0", &p, err, sizeof err);
    const sv_seg *base = &p.sub[0].seg[0];
    for (int ti = 0; ti < 2; ti++) {
        double tol = ti ? 1e-2 : 1e-4;
        sv_stroke_style st = {8, SV_CAP_BUTT, SV_JOIN_MITER, 4, tol, 0};
        sv_path_init(&o);
        int missed = sv_stroke_path(&p, &st, &o);
        CHECK(missed == 0, "tolerance %g met everywhere", tol);
        double worst = 0;
        int offsets = 0;
        for (int k = 0; k < o.n; k++)
            for (int s = 0; s < o.sub[k].n; s++) {
                const sv_seg *g = &o.sub[k].seg[s];
                if (g->degree != 3)
                    continue;
                for (int j = 0; j <= 40; j++) {
                    sv_pt q = sv_seg_eval(g, j / 40.0);
                    /* distance to the base curve by dense sampling and refinement */
                    double best = INFINITY, bt = 0;
                    for (int i = 0; i <= 4000; i++) {
                        double dd = sv_len(sv_sub(sv_seg_eval(base, i / 4000.0), q));
                        if (dd < best) {
                            best = dd;
                            bt = i / 4000.0;
                        }
                    }
                    for (double step = 1.0 / 4000; step > 1e-14; step /= 2) {
                        double a = fmax(0, bt - step), b = fmin(1, bt + step);
                        double da = sv_len(sv_sub(sv_seg_eval(base, a), q));
                        double db = sv_len(sv_sub(sv_seg_eval(base, b), q));
                        if (da < best) {
                            best = da;
                            bt = a;
                        }
                        if (db < best) {
                            best = db;
                            bt = b;
                        }
                    }
                    if (best > 1) { /* an offset piece, not the base curve itself */
                        worst = fmax(worst, fabs(best - 4));
                        offsets++;
                    }
                }
            }
        CHECK(offsets > 0 && worst <= tol * 1.05,
                  "cubic offset within tolerance %g: worst %.3g over %d points", tol, worst,
                  offsets);
        sv_path_free(&o);
    }
    sv_path_free(&p);

    /* a zero-length subpath draws a dot with round caps */
    stroke_of("M5 5 L5 5", 2, SV_CAP_ROUND, SV_JOIN_MITER, 4, &o);
    CHECK_NEAR(sum_area(&o, &pos), M_PI, 1e-8, "round dot");
    sv_path_free(&o);
    stroke_of("M5 5 L5 5", 2, SV_CAP_BUTT, SV_JOIN_MITER, 4, &o);
    CHECK(o.n == 0, "butt dot draws nothing");
    sv_path_free(&o);
}

/* Start and end x of each dash of a horizontal path. */
static int dash_spans(const char *d, const double *dash, int n, double off, double *xs)
{
    sv_path p, o;
    char err[100];
    sv_path_init(&p);
    sv_path_init(&o);
    sv_parse_path(d, &p, err, sizeof err);
    sv_path_dash(&p, dash, n, off, SV_MAX_DASHES, &o);
    int k = 0;
    for (int i = 0; i < o.n && k < 32; i++) {
        xs[k++] = o.sub[i].seg[0].p[0].x;
        const sv_seg *l = &o.sub[i].seg[o.sub[i].n - 1];
        xs[k++] = l->p[l->degree].x;
    }
    sv_path_free(&p);
    sv_path_free(&o);
    return k / 2;
}

static void test_dash(void)
{
    double xs[64];
    int n = dash_spans("M0 0 H10", (double[]){2, 1}, 2, 0, xs);
    CHECK(n == 4 && xs[0] == 0 && xs[1] == 2 && xs[2] == 3 && xs[3] == 5 && xs[6] == 9 &&
                  xs[7] == 10,
              "dashes 2,1 on a line (%d)", n);
    n = dash_spans("M0 0 H10", (double[]){2, 1}, 2, 1, xs);
    CHECK(n == 4 && xs[0] == 0 && xs[1] == 1 && xs[2] == 2 && xs[3] == 4, "dash offset");
    n = dash_spans("M0 0 H10", (double[]){1}, 1, 0, xs); /* odd lists repeat: 1,1 */
    CHECK(n == 5 && xs[2] == 2 && xs[3] == 3, "odd dash list repeats");
    n = dash_spans("M0 0 H10 M0 5 H10", (double[]){4, 4}, 2, 0, xs);
    CHECK(n == 4 && xs[4] == 0 && xs[5] == 4, "pattern restarts on each subpath");
    /* a closed square, dash on at both ends: the dash through the start is one piece */
    sv_path p, o;
    char err[100];
    sv_path_init(&p);
    sv_path_init(&o);
    sv_parse_path("M0 0 H10 V10 H0 Z", &p, err, sizeof err);
    /* offset 2: on [0,4], [8,14], [18,24], [28,34], [38,40]+[0,4] */
    sv_path_dash(&p, (double[]){6, 4}, 2, 2, SV_MAX_DASHES, &o);
    CHECK(o.n == 4, "closed square dashes (%d)", o.n);
    const sv_subpath *last = &o.sub[o.n - 1];
    CHECK(o.n == 4 && pt_is(last->seg[last->n - 1].p[1], 4, 0) && pt_is(last->seg[0].p[0], 0, 2),
              "last dash joined with the first through the start point");
    sv_path_free(&o);
    sv_path_free(&p);
    /* on a circle of radius 10 (length 20 pi) dashes of pi/2 every pi: 20 dashes, each
     * spanning 9 degrees of arc */
    sv_path_init(&p);
    sv_path_init(&o);
    sv_path_ellipse(&p, 0, 0, 10, 10);
    sv_path_dash(&p, (double[]){M_PI / 2, M_PI / 2}, 2, 0, SV_MAX_DASHES, &o);
    double worst = 0;
    for (int i = 0; i < o.n; i++) {
        sv_pt a = o.sub[i].seg[0].p[0];
        const sv_seg *l = &o.sub[i].seg[o.sub[i].n - 1];
        sv_pt b = l->p[l->degree];
        double ang = fabs(atan2(sv_cross(a, b), sv_dot(a, b)));
        worst = fmax(worst, fabs(ang - M_PI / 20));
    }
    CHECK(o.n == 20 && worst < 1e-9, "dashes on a circle by arc length (%d, %g)", o.n, worst);
    sv_path_free(&o);
    sv_path_free(&p);
}

static void test_clip(void)
{
    /* sub-segments of a conic are the exact pieces: same points, same parameters */
    sv_seg arc = {2, {{10, 0}, {10, 10}, {0, 10}}, sqrt(0.5)};
    sv_seg piece = sv_seg_sub(&arc, 0.3, 0.8);
    double e = 0;
    for (int j = 0; j <= 10; j++) {
        sv_pt q = sv_seg_eval(&piece, j / 10.0);
        e = fmax(e, fabs(sv_len(q) - 10));
    }
    CHECK(e < 1e-12 && sv_len(sv_sub(piece.p[0], sv_seg_eval(&arc, 0.3))) < 1e-12 &&
                  sv_len(sv_sub(piece.p[2], sv_seg_eval(&arc, 0.8))) < 1e-12,
              "exact conic sub-segment");
    /* a disc of radius 10 clipped to the square [0,20]^2: a quarter disc, exactly */
    sv_path p, c;
    sv_path_init(&p);
    sv_path_ellipse(&p, 0, 0, 10, 10);
    sv_path_init(&c);
    char err[100];
    sv_parse_path("M0 0 H20 V20 H0 Z", &c, err, sizeof err);
    sv_pt *poly;
    int n;
    CHECK(sv_path_convex_polygon(&c, &poly, &n) && n == 4, "square is a convex polygon");
    sv_path_clip_polygon(&p, poly, n);
    free(poly);
    double a = 0;
    for (int k = 0; k < p.n; k++)
        a += sv_subpath_area(&p.sub[k]);
    CHECK_NEAR(fabs(a), M_PI * 25, 1e-9, "clipped disc area");
    sv_path_free(&p);
    sv_path_free(&c);
    /* a crossing exactly on a sample point of the root search (t = 16/48) */
    sv_path_init(&p);
    sv_parse_path("M24 34 L28.705078125 38.27734375 L35 38.27734375 L35 34 Z", &p, err, sizeof err);
    double before = sv_subpath_area(&p.sub[0]);
    sv_path_clip_halfplane(&p, 0, 1, -35.42578125);
    a = 0;
    for (int k = 0; k < p.n; k++)
        a += sv_subpath_area(&p.sub[k]);
    /* the part above y = 35.42578125 of that quadrilateral, by the shoelace formula */
    sv_path q;
    sv_path_init(&q);
    sv_parse_path("M25.568359375 35.42578125 L28.705078125 38.27734375 L35 38.27734375 L35 35.42578125 Z",
                  &q, err, sizeof err);
    CHECK_NEAR(a, sv_subpath_area(&q.sub[0]), 1e-9, "clip with a crossing on a sample point");
    CHECK(fabs(before) > fabs(a), "clipping removed area");
    sv_path_free(&p);
    sv_path_free(&q);
    sv_path_init(&c);
    sv_parse_path("M0 0 H20 L10 5 L10 20 Z", &c, err, sizeof err);
    CHECK(!sv_path_convex_polygon(&c, &poly, &n), "a concave polygon is refused");
    sv_path_free(&c);
}

static void test_import_doc(void)
{
    const char *svg =
        "<svg xmlns='http://www.w3.org/2000/svg' xmlns:xlink='http://www.w3.org/1999/xlink'"
        " width='32' height='16' viewBox='0 0 16 8'>"
        "<style>.k{fill:#ff0000}</style>"
        "<defs><rect id='r' width='2' height='2'/></defs>"
        "<g transform='translate(1 1)' opacity='0.5'><rect class='k' width='4' height='4'/>"
        "<circle cx='2' cy='2' r='1' fill='blue'/></g>"
        "<use xlink:href='#r' x='10' fill-opacity='0.25'/>"
        "<path d='M0 0 L1 1' stroke='black' stroke-width='0.5'/>"
        "<image width='1' height='1'/><foo/>"
        "</svg>";
    sv_doc d;
    char err[200];
    CHECK(sv_import_buffer(svg, strlen(svg), NULL, &d, err, sizeof err) == 0, "import: %s", err);
    CHECK(d.width == 32 && d.height == 16, "canvas from width/height");
    CHECK(sv_doc_region_count(&d) == 4, "four painted regions (%zu)", sv_doc_region_count(&d));
    /* front-most first: the stroke, then the use, then the group's two shapes in one cel */
    bool order = d.ncels >= 1 && d.cels[0].nregions >= 1 &&
                 strstr(d.cels[0].regions[0].source, "path");
    CHECK(order, "document order reversed: the last element is front-most");
    int group_cel = -1;
    for (int c = 0; c < d.ncels; c++)
        for (int r = 0; r < d.cels[c].nregions; r++)
            if (strstr(d.cels[c].regions[r].source, "circle"))
                group_cel = c;
    CHECK(group_cel >= 0 && d.cels[group_cel].nregions == 2 &&
                  fabs(d.cels[group_cel].regions[0].paint.beta - 0.5) < 1e-12 &&
                  fabs(d.cels[group_cel].regions[1].paint.pigment[0] - 1) < 1e-12,
              "group opacity: both children share one cel with beta 0.5");
    /* the viewBox scales by 2: the group's rect spans canvas x 2..10 */
    const sv_region *rect = group_cel >= 0 ? &d.cels[group_cel].regions[1] : NULL;
    CHECK(rect && rect->bbox[0] == 2 && rect->bbox[2] == 10 && rect->bbox[3] == 10,
              "viewBox and transform applied");
    int warned = 0;
    for (int i = 0; i < d.nwarnings; i++)
        warned += strstr(d.warnings[i], "<image>") != NULL || strstr(d.warnings[i], "<foo>") != NULL;
    CHECK(warned == 2, "unsupported elements are warned by name (%d)", warned);
    char *json = sv_doc_to_json(&d, NULL);
    CHECK(json && strstr(json, "\"fill_rule\":\"nonzero\"") && strstr(json, "\"degree\":"),
              "scene JSON written");
    free(json);
    cs_scene *scene = malloc(sizeof *scene);
    CHECK(sv_doc_to_scene(&d, NULL, scene, err, sizeof err) == 0 &&
                  scene->region_count == 4,
              "cs_scene built (%s)", err);
    free(scene);
    sv_doc_free(&d);
    CHECK(sv_import_buffer("<svg><g></svg>", 14, NULL, &d, err, sizeof err) < 0 &&
                  strstr(err, "line 1"),
              "XML errors name the line (%s)", err);
    CHECK(sv_import_buffer("<html/>", 7, NULL, &d, err, sizeof err) < 0, "root must be svg");
    /* a single-byte encoding expat does not know, through iconv: "\xcf\xf0" is "Пр" in windows-1251 */
    const char *cp = "<?xml version=\"1.0\" encoding=\"windows-1251\"?><svg><text>\xcf\xf0</text></svg>";
    sv_node *root = sv_xml_parse(cp, strlen(cp), err, sizeof err);
    CHECK(root && root->nkids == 1 && root->kids[0]->text &&
                  !strcmp(root->kids[0]->text, "\xd0\x9f\xd1\x80"),
              "windows-1251 read as UTF-8 (%s)", root ? "" : err);
    sv_xml_free(root);
    const char *bogus = "<?xml version=\"1.0\" encoding=\"no-such\"?><svg/>";
    CHECK(!sv_xml_parse(bogus, strlen(bogus), err, sizeof err) && strstr(err, "encoding"),
              "an unknown encoding is an error naming it (%s)", err);
}

static void test_glyphs(void)
{
    sv_path p;
    sv_path_init(&p);
    int rule;
    sv_text_metrics m;
    char err[200];
    CHECK(sv_text_path("O", SV_DEFAULT_FONT, 100, 0, 100, &p, &rule, &m, err, sizeof err) == 0,
              "DejaVu Sans loads: %s", err);
    sv_contour *c = NULL;
    int n = 0;
    sv_path_to_contours(&p, &c, &n);
    CHECK(n == 2 && c[0].degree == 2 && c[1].degree == 2, "'O': two quadratic contours");
    /* Every glyph point must be the font's point (or an implied midpoint) scaled exactly. */
    FT_Library lib;
    FT_Face face;
    FT_Init_FreeType(&lib);
    FT_New_Face(lib, SV_DEFAULT_FONT, 0, &face);
    FT_Load_Char(face, 'O', FT_LOAD_NO_SCALE);
    FT_Outline *ol = &face->glyph->outline;
    double sc = 100.0 / face->units_per_EM;
    int matched = 0, total = 0;
    for (int s = 0; s < p.n; s++)
        for (int k = 0; k < p.sub[s].n; k++) {
            sv_pt q = p.sub[s].seg[k].p[p.sub[s].seg[k].degree];
            total++;
            for (int i = 0; i < ol->n_points; i++) {
                int j = i + 1 < ol->n_points ? i + 1 : i;
                double x1 = ol->points[i].x * sc, y1 = 100 - ol->points[i].y * sc;
                double xm = 0.5 * (ol->points[i].x + ol->points[j].x) * sc;
                double ym = 100 - 0.5 * (ol->points[i].y + ol->points[j].y) * sc;
                if ((q.x == x1 && q.y == y1) || (q.x == xm && q.y == ym)) {
                    matched++;
                    break;
                }
            }
        }
    CHECK(total > 0 && matched == total, "on-curve points exact (%d of %d)", matched, total);
    for (int i = 0; i < n; i++)
        sv_contour_free(&c[i]);
    free(c);
    sv_path_free(&p);

    /* a CFF-style outline (cubic tags) becomes degree 3 */
    FT_Vector pts[] = {{0, 0}, {100, 0}, {100, 100}, {0, 100}};
    char tags[] = {FT_CURVE_TAG_ON, FT_CURVE_TAG_CUBIC, FT_CURVE_TAG_CUBIC, FT_CURVE_TAG_ON};
    short ends[] = {3};
    FT_Outline cff = {1, 4, pts, tags, ends, 0};
    sv_path_init(&p);
    CHECK(sv_text_outline_path((const struct FT_Outline_ *)&cff, 1, 0, 0, &p) == 0, "decompose");
    c = NULL;
    n = 0;
    sv_path_to_contours(&p, &c, &n);
    CHECK(n == 1 && c[0].degree == 3 && c[0].count == 6, "cubic outline: degree 3 contour");
    check_seg(&p, 0, 0, 3, (double[]){0, 0, 100, 0, 100, -100, 0, -100}, "cubic glyph segment");
    for (int i = 0; i < n; i++)
        sv_contour_free(&c[i]);
    free(c);
    sv_path_free(&p);

    /* advances add up; kerning, where the font has a kern table, moves pairs */
    sv_text_metrics m1, m2;
    sv_path_init(&p);
    sv_text_path("i", SV_DEFAULT_FONT, 50, 0, 0, &p, NULL, &m1, err, sizeof err);
    sv_text_path("iii", SV_DEFAULT_FONT, 50, 0, 0, &p, NULL, &m2, err, sizeof err);
    CHECK_NEAR(m2.advance, 3 * m1.advance, 1e-9, "advances add up");
    FT_Load_Char(face, 'i', FT_LOAD_NO_SCALE);
    CHECK_NEAR(m1.advance, face->glyph->advance.x * 50.0 / face->units_per_EM, 1e-12,
             "advance from the font");
    sv_path_free(&p);
    sv_text_metrics ma, mv, mav;
    sv_path_init(&p);
    sv_text_path("A", SV_DEFAULT_FONT, 50, 0, 0, &p, NULL, &ma, err, sizeof err);
    sv_text_path("V", SV_DEFAULT_FONT, 50, 0, 0, &p, NULL, &mv, err, sizeof err);
    sv_text_path("AV", SV_DEFAULT_FONT, 50, 0, 0, &p, NULL, &mav, err, sizeof err);
    if (mav.has_kerning) {
        FT_Vector kv;
        FT_Get_Kerning(face, FT_Get_Char_Index(face, 'A'), FT_Get_Char_Index(face, 'V'),
                       FT_KERNING_UNSCALED, &kv);
        CHECK(kv.x < 0 && mav.kern_pairs == 1, "the font kerns AV");
        CHECK_NEAR(mav.advance, ma.advance + mv.advance + kv.x * 50.0 / face->units_per_EM, 1e-9,
                 "kerned advance");
    } else {
        printf("note: %s has no 'kern' table; kerning not exercised\n", SV_DEFAULT_FONT);
    }
    sv_path_free(&p);
    CHECK(sv_text_path("x", "/nonexistent.ttf", 10, 0, 0, &p, NULL, NULL, err, sizeof err) < 0 &&
                  strstr(err, "nonexistent"),
              "missing font named in the error");
    FT_Done_Face(face);
    FT_Done_FreeType(lib);
}

static void test_svg_text(void)
{
    /* "AB" set as one run equals "A" then a tspan "B" continuing the pen */
    const char *one = "<svg xmlns='http://www.w3.org/2000/svg' width='200' height='50'>"
                      "<text x='10' y='40' font-size='20'>AB</text></svg>";
    const char *two = "<svg xmlns='http://www.w3.org/2000/svg' width='200' height='50'>"
                      "<text x='10' y='40' font-size='20'>  A\n<tspan fill='red'>B </tspan>  </text></svg>";
    const char *moved = "<svg xmlns='http://www.w3.org/2000/svg' width='200' height='50'>"
                        "<text x='10' y='40' font-size='20'>A<tspan x='100' y='30'>B</tspan></text>"
                        "<text x='100' y='40' font-size='20' text-anchor='middle'>AB</text></svg>";
    sv_doc d1, d2, d3;
    char err[200];
    sv_import_buffer(one, strlen(one), NULL, &d1, err, sizeof err);
    sv_import_buffer(two, strlen(two), NULL, &d2, err, sizeof err);
    sv_import_buffer(moved, strlen(moved), NULL, &d3, err, sizeof err);
    CHECK(sv_doc_region_count(&d1) == 1 && sv_doc_region_count(&d2) == 2,
              "a tspan with its own fill is its own region (%zu, %zu)", sv_doc_region_count(&d1),
              sv_doc_region_count(&d2));
    /* the tspan's B sits where B sits in "AB" minus kerning: compare bounding boxes */
    double b1 = d1.cels[0].regions[0].bbox[2], b2 = 0;
    for (int c = 0; c < d2.ncels; c++)
        for (int r = 0; r < d2.cels[c].nregions; r++)
            b2 = fmax(b2, d2.cels[c].regions[r].bbox[2]);
    CHECK_NEAR(b2, b1, 0.05, "whitespace collapsed and the pen continues into the tspan");
    double bx = 1e9, mid0 = 1e9, mid1 = -1e9;
    for (int c = 0; c < d3.ncels; c++)
        for (int r = 0; r < d3.cels[c].nregions; r++) {
            const sv_region *g = &d3.cels[c].regions[r];
            if (g->bbox[3] < 35) /* the B moved up to y = 30 */
                bx = fmin(bx, g->bbox[0]);
            else if (g->bbox[0] > 60) { /* the anchored text */
                mid0 = fmin(mid0, g->bbox[0]);
                mid1 = fmax(mid1, g->bbox[2]);
            }
        }
    CHECK(bx >= 100 && bx < 102, "tspan x starts a new chunk at 100 (%g)", bx);
    /* letter-spacing after every character, word-spacing after a space, inherited from a
       group; Inkscape's zero spacings and "normal" values warn nothing */
    static const char *const spaced[] = {
        "<text x='10' y='40' font-size='20' font-family='Noto Sans'>A<tspan fill='red'>B"
        "</tspan></text>",
        "<g letter-spacing='3'><text x='10' y='40' font-size='20' font-family='Noto Sans' "
        "style='word-spacing:0px;font-variant:normal'>A<tspan fill='red'>B</tspan></text></g>",
        "<text x='10' y='40' font-size='20' font-family='Noto Sans'>A <tspan fill='red'>B"
        "</tspan></text>",
        "<text x='10' y='40' font-size='20' font-family='Noto Sans' word-spacing='5'>A "
        "<tspan fill='red'>B</tspan></text>"};
    double bpos[4] = {0, 0, 0, 0};
    for (int k = 0; k < 4; k++) {
        char svg[600];
        snprintf(svg, sizeof svg, "<svg xmlns='http://www.w3.org/2000/svg' width='200' "
                 "height='50'>%s</svg>", spaced[k]);
        sv_doc dd;
        if (sv_import_buffer(svg, strlen(svg), NULL, &dd, err, sizeof err) < 0)
            continue;
        CHECK(dd.nwarnings == 0, "spacing case %d: no warning (%s)", k,
                  dd.nwarnings ? dd.warnings[0] : "");
        for (int c = 0; c < dd.ncels; c++)
            for (int r = 0; r < dd.cels[c].nregions; r++)
                if (dd.cels[c].regions[r].paint.pigment[0] == 1) /* red: the B */
                    bpos[k] = dd.cels[c].regions[r].bbox[0];
        sv_doc_free(&dd);
    }
    /* bidi (UAX #9): two Hebrew letters in a left-to-right paragraph read right to left,
       so the second (blue) stands left of the first (red); the Latin around keeps its order */
    const char *bidi = "<svg xmlns='http://www.w3.org/2000/svg' width='200' height='50'>"
                       "<text x='10' y='40' font-size='20' font-family='Noto Sans'>A<tspan "
                       "fill='red'>\xd7\x90</tspan><tspan fill='blue'>\xd7\x91</tspan>B</text>"
                       "</svg>";
    double xa = 1e9, xr = 1e9, xb = 1e9; /* the leftmost of each colour */
    sv_doc db;
    if (sv_import_buffer(bidi, strlen(bidi), NULL, &db, err, sizeof err) == 0) {
        for (int c = 0; c < db.ncels; c++)
            for (int r = 0; r < db.cels[c].nregions; r++) {
                const sv_region *g = &db.cels[c].regions[r];
                double *x = g->paint.pigment[0] == 1 ? &xr : g->paint.pigment[2] == 1 ? &xb : &xa;
                *x = fmin(*x, g->bbox[0]);
            }
        sv_doc_free(&db);
    }
    CHECK(xa < xb && xb < xr && xr < 1e9, "bidi: A, then the Hebrew pair reversed (%g %g %g)",
              xa, xb, xr);
    CHECK_NEAR(bpos[1] - bpos[0], 3, 1e-9, "letter-spacing from the group moves B by 3");
    CHECK_NEAR(bpos[3] - bpos[2], 5, 1e-9, "word-spacing moves B after the space by 5");
    CHECK_NEAR(0.5 * (mid0 + mid1), 100, 1.5, "text-anchor middle centres the chunk");
    sv_doc_free(&d1);
    sv_doc_free(&d2);
    sv_doc_free(&d3);
}

/* fontconfig's choice as a browser's: family list, weight, style, per-glyph fallback */
static void test_fonts(void)
{
    static const struct {
        const char *family;
        int weight;
        bool italic;
        unsigned long cp;
        const char *want; /* in the file name (fonts-noto-core, fonts-noto-cjk) */
    } cases[] = {
        {"Noto Sans", 400, false, 'A', "NotoSans-Regular."},
        {"'Noto Sans'", 700, false, 'A', "NotoSans-Bold."},
        {"Noto Sans", 400, true, 'A', "NotoSans-Italic."},
        {"\"No Such Face\", Noto Serif, sans-serif", 400, false, 'A', "NotoSerif-Regular."},
        {"Noto Sans", 400, false, 0x5203, "CJK"}, /* 刃: not in Noto Sans, from a CJK face */
        {"monospace", 400, false, 'A', "Mono"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char file[512] = "";
        int rc = sv_font_match(cases[i].family, cases[i].weight, cases[i].italic, NULL,
                               cases[i].cp, file, sizeof file);
        CHECK(rc == 0 && strstr(file, cases[i].want), "font for '%s' %d%s U+%04lX: %s (want %s)",
                  cases[i].family, cases[i].weight, cases[i].italic ? " italic" : "", cases[i].cp,
                  file, cases[i].want);
    }
    /* in an import: the CJK characters of a Latin family get outlines (no .notdef box of
       two contours: U+6D77 has many) */
    const char *cjk = "<svg xmlns='http://www.w3.org/2000/svg' width='100' height='40'>"
                      "<text x='0' y='30' font-family='Noto Sans' font-size='20'>A\xe6\xb5\xb7"
                      "</text></svg>";
    sv_doc d;
    char err[200];
    CHECK(sv_import_buffer(cjk, strlen(cjk), NULL, &d, err, sizeof err) == 0, "%s", err);
    int contours = 0;
    for (int c = 0; c < d.ncels; c++)
        for (int r = 0; r < d.cels[c].nregions; r++)
            contours += d.cels[c].regions[r].ncontours;
    CHECK(contours >= 2 + 5, "A and U+6D77 set from two faces (%d contours)", contours);
    sv_doc_free(&d);

    /* objectBoundingBox of text: the glyph cells (advances by the font's ascender and
       descender, FreeType's hhea values here), not the outlines */
    const char *grad = "<svg xmlns='http://www.w3.org/2000/svg' width='100' height='60'>"
                       "<linearGradient id='g'><stop offset='0' stop-color='red'/>"
                       "<stop offset='1' stop-color='blue'/></linearGradient>"
                       "<text x='10' y='40' font-family='Noto Sans' font-size='20' "
                       "fill='url(#g)'>x</text></svg>";
    char file[512];
    FT_Library lib;
    FT_Face face;
    if (sv_font_match("Noto Sans", 400, false, NULL, 'x', file, sizeof file) == 0 &&
        FT_Init_FreeType(&lib) == 0) {
        if (FT_New_Face(lib, file, 0, &face) == 0) {
            double k = 20.0 / face->units_per_EM;
            FT_Load_Glyph(face, FT_Get_Char_Index(face, 'x'), FT_LOAD_NO_SCALE);
            double adv = (double)face->glyph->advance.x * k;
            double top = 40 - face->ascender * k, height = (face->ascender - face->descender) * k;
            CHECK(sv_import_buffer(grad, strlen(grad), NULL, &d, err, sizeof err) == 0, "%s",
                      err);
            CHECK(d.ngradients == 1, "the text's gradient (%d)", d.ngradients);
            if (d.ngradients == 1) {
                sv_affine t = d.gradients[0].transform;
                CHECK_NEAR(t.e, 10, 1e-9, "text box starts at the pen");
                CHECK_NEAR(t.a, adv, 1e-9, "text box is the advance wide");
                CHECK_NEAR(t.f, top, 1e-9, "text box top is the ascender");
                CHECK_NEAR(t.d, height, 1e-9, "text box height is ascender - descender");
            }
            sv_doc_free(&d);
            /* text-decoration underline: a line under the whole advance, from the font's
               'post' metrics (FreeType's centre, drawn where resvg draws it) */
            const char *ul = "<svg xmlns='http://www.w3.org/2000/svg' width='100' height='60'>"
                             "<text x='10' y='40' font-family='Noto Sans' font-size='20' "
                             "text-decoration='underline'>x</text></svg>";
            CHECK(sv_import_buffer(ul, strlen(ul), NULL, &d, err, sizeof err) == 0, "%s", err);
            if (d.ncels == 1 && d.cels[0].nregions == 1) {
                const double *b = d.cels[0].regions[0].bbox;
                double line_bot = 40 - face->underline_position * k;
                CHECK_NEAR(b[0], 10, 1e-9, "underline starts at the pen");
                CHECK_NEAR(b[2], 10 + adv, 1e-9, "underline spans the advance");
                CHECK_NEAR(b[3], line_bot, 1e-9, "underline's bottom at the font's position");
            }
            CHECK(d.nwarnings == 0, "underline drawn, not warned");
            sv_doc_free(&d);
            FT_Done_Face(face);
        }
        FT_Done_FreeType(lib);
    }
}

void test_svg_unit(const svg_test_opts *o)
{
    (void)o;
    int before = tl_failed;
    test_path_commands();
    test_arcs();
    test_transforms();
    test_colors();
    test_lengths_css();
    test_contours();
    test_stroker();
    test_dash();
    test_clip();
    test_import_doc();
    test_glyphs();
    test_svg_text();
    test_fonts();
    printf("svg-unit: %s\n", tl_failed == before ? "all checks pass" : "FAILURES above");
}
