/*
 * sv_gradfn.c - an SVG gradient as the core's paint functions.
 *
 * SVG paints a gradient as colour c(t) with opacity a(t), both interpolated
 * between the stops unpremultiplied and then premultiplied (librsvg hands the
 * stops to cairo, whose gradient walker does exactly that). In the beta
 * model with medium [1,1,1] and front light 1 a paint shows E = beta p,
 * T = 1 - beta. So a pigment function with the stop colours and a beta
 * function with the stop opacities, at the same offsets and with the same
 * geometry and spread, give E = a(t) c(t) and T = 1 - a(t): SVG's gradient
 * exactly, translucent stops included. A field that does not vary along the
 * stops stays a constant, so most gradients take one function.
 *
 * Geometry. The core's functions live in the cel's own space, the space of
 * its contours. The IR's gradient maps gradient space to canvas units by
 * `transform` (objectBoundingBox, gradientTransform and the CTM folded in),
 * and the cel maps its space to the canvas, so the gradient reaches cel
 * space by G = cel^-1 * transform.
 *
 *  - Linear: t is an affine function of position under any affine map, so
 *    any invertible G works: t(q) = g.q + h, written as the segment from
 *    -h g/|g|^2 to that point plus g/|g|^2.
 *  - Radial: the core's radial function is a circle (centre, radius, focal
 *    point), so G must be a similarity; then centre and focal point map by
 *    G and the radius scales by its factor. A non-uniform or skewed G makes
 *    an ellipse, which the importer draws in a cel of its own whose
 *    transform turns a circle into that ellipse (sv_gradient_circle_space).
 *    SVG 2's focal radius fr has no counterpart in the core.
 *
 * Stops. The core takes CS_CFG_MAX_STOPS. Runs of stops at one offset
 * reduce to their first and last (that is all SVG draws of them); beyond
 * that, when there are still too many, the stop that a straight line
 * between its neighbours predicts best is dropped while the prediction is
 * within 0.5/255 in colour and opacity, which no 8-bit output can show.
 */
#include <math.h>

#include "sv_gradient.h"
#include "sv_internal.h"

/* Largest coordinate the functions may take (the core's limit is 1e6). */
#define COORD_MAX 1.0e5
/* Where the importer puts a focal point at or beyond the circle (SCENE.md). */
#define FOCAL_MAX 0.99

typedef struct vstop {
    double off, v[4]; /* r g b in sRGB, opacity */
} vstop;

static double stop_err(const vstop *a, const vstop *m, const vstop *b)
{
    if (!(b->off > a->off))
        return INFINITY;
    double u = (m->off - a->off) / (b->off - a->off), e = 0;
    for (int k = 0; k < 4; k++)
        e = fmax(e, fabs(a->v[k] + u * (b->v[k] - a->v[k]) - m->v[k]));
    return e;
}

static bool same_value(const vstop *a, const vstop *b)
{
    return a->v[0] == b->v[0] && a->v[1] == b->v[1] && a->v[2] == b->v[2] && a->v[3] == b->v[3];
}

/* Reduces the stops in place (see the note above); returns the new count. */
static int reduce_stops(vstop *s, int n)
{
    /* a run of three or more at one offset: only its ends are ever drawn */
    int m = 0;
    for (int i = 0; i < n; i++) {
        if (m >= 2 && s[m - 1].off == s[i].off && s[m - 2].off == s[i].off)
            s[m - 1] = s[i];
        else
            s[m++] = s[i];
    }
    n = m;
    /* equal neighbours: the first of two equal leading (or last of two
     * trailing) stops, and a stop equal to both neighbours, say nothing */
    m = 0;
    for (int i = 0; i < n; i++) {
        bool prev = m > 0 && same_value(&s[m - 1], &s[i]);
        bool next = i + 1 < n && same_value(&s[i + 1], &s[i]);
        if ((i == 0 && next) || (i == n - 1 && prev) || (prev && next))
            continue;
        s[m++] = s[i];
    }
    n = m;
    while (n > CS_CFG_MAX_STOPS) {
        int best = -1;
        double be = 0.5 / 255;
        for (int i = 1; i + 1 < n; i++) {
            double e = stop_err(&s[i - 1], &s[i], &s[i + 1]);
            if (e <= be) {
                be = e;
                best = i;
            }
        }
        if (best < 0)
            break;
        memmove(&s[best], &s[best + 1], (size_t)(n - best - 1) * sizeof *s);
        n--;
    }
    return n;
}

static bool coords_ok(const float *g, int n)
{
    for (int i = 0; i < n; i++)
        if (!(fabsf(g[i]) <= (float)COORD_MAX))
            return false;
    return true;
}

/* Whether the linear part of m is a similarity (rotation or reflection and
 * one scale factor), to a relative tolerance; its factor in *s. */
static bool is_similarity(sv_affine m, double *s)
{
    double n = sqrt(fabs(m.a * m.d - m.b * m.c));
    double tol = 1e-6 * (fabs(m.a) + fabs(m.b) + fabs(m.c) + fabs(m.d));
    *s = n;
    if (!(n > 0))
        return false;
    bool rot = fabs(m.a - m.d) <= tol && fabs(m.b + m.c) <= tol;
    bool refl = fabs(m.a + m.d) <= tol && fabs(m.b - m.c) <= tol;
    return rot || refl;
}

bool sv_gradient_circle_space(const sv_gradient *g, sv_affine *cel)
{
    double s;
    if (g->type != SV_GRAD_RADIAL || is_similarity(g->transform, &s))
        return false;
    /*
     * Cel space = gradient space scaled by k = sqrt|det|, so cel coordinates
     * keep the canvas's scale; the cel transform is the gradient's map with
     * its linear part divided by k. A very thin ellipse would put the
     * contours far out in cel space: left to the bands.
     */
    sv_affine m = g->transform;
    double k = sqrt(fabs(m.a * m.d - m.b * m.c));
    double smax = sv_affine_max_scale(m), smin = k > 0 ? k * k / smax : 0;
    if (!(smin > 0) || smax / smin > 1.0e3)
        return false;
    sv_affine c = {m.a / k, m.b / k, m.c / k, m.d / k, m.e, m.f};
    *cel = c;
    return true;
}

bool sv_gradient_circular_in(const sv_gradient *g, sv_affine cel)
{
    sv_affine inv;
    double s;
    if (g->type != SV_GRAD_RADIAL)
        return true;
    if (!sv_affine_invert(cel, &inv))
        return false;
    return is_similarity(sv_affine_mul(inv, g->transform), &s);
}

const char *sv_fn_status_str(sv_fn_status st)
{
    switch (st) {
    case SV_FN_OK:
        return "ok";
    case SV_FN_SOLID:
        return "one colour";
    case SV_FN_STOPS:
        return "more stops than CS_CFG_MAX_STOPS (" SV_STR(CS_CFG_MAX_STOPS) ")";
    case SV_FN_ELLIPSE:
        return "radial gradient elliptical in its cel";
    case SV_FN_FOCAL:
        return "focal radius fr not supported by the core";
    case SV_FN_RANGE:
        return "gradient geometry beyond the core's coordinate range";
    }
    return "?";
}

sv_fn_status sv_gradient_funcs(const sv_gradient *g, double opacity, sv_affine cel, sv_gradfn *out)
{
    memset(out, 0, sizeof *out);
    if (g->nstops < 1)
        return SV_FN_SOLID;
    vstop *s = sv_xrealloc(NULL, (size_t)g->nstops * sizeof *s);
    for (int i = 0; i < g->nstops; i++) {
        s[i].off = g->stops[i].offset;
        memcpy(s[i].v, g->stops[i].rgb, 3 * sizeof(double));
        s[i].v[3] = fmin(1, fmax(0, g->stops[i].opacity * opacity));
    }
    int n = reduce_stops(s, g->nstops);
    sv_fn_status st = SV_FN_OK;
    bool vary_rgb = false, vary_a = false;
    for (int i = 1; i < n; i++) {
        vary_rgb |= s[i].v[0] != s[0].v[0] || s[i].v[1] != s[0].v[1] || s[i].v[2] != s[0].v[2];
        vary_a |= s[i].v[3] != s[0].v[3];
    }
    memcpy(out->pigment_const, s[0].v, 3 * sizeof(double));
    out->beta_const = s[0].v[3];
    cs_paint_func f;
    memset(&f, 0, sizeof f);
    sv_affine inv_cel, G, Ginv;
    if (!vary_rgb && !vary_a) {
        st = SV_FN_SOLID;
    } else if (n > CS_CFG_MAX_STOPS) {
        st = SV_FN_STOPS;
    } else if (!sv_affine_invert(cel, &inv_cel) ||
               !sv_affine_invert(G = sv_affine_mul(inv_cel, g->transform), &Ginv)) {
        st = SV_FN_SOLID; /* a degenerate map */
    } else if (g->type == SV_GRAD_LINEAR) {
        double dx = g->x2 - g->x1, dy = g->y2 - g->y1, l2 = dx * dx + dy * dy;
        if (!(l2 > 0)) {
            st = SV_FN_SOLID; /* x1,y1 = x2,y2: the last stop's colour */
        } else {
            /* t = (Ginv q - p1).d / |d|^2 = gx qx + gy qy + h */
            double gx = (Ginv.a * dx + Ginv.b * dy) / l2, gy = (Ginv.c * dx + Ginv.d * dy) / l2;
            double h = ((Ginv.e - g->x1) * dx + (Ginv.f - g->y1) * dy) / l2;
            double gg = gx * gx + gy * gy;
            if (!(gg > 0)) {
                st = SV_FN_SOLID;
            } else {
                f.kind = CS_FUNC_LINEAR;
                f.geom[0] = (float)(-h * gx / gg);
                f.geom[1] = (float)(-h * gy / gg);
                f.geom[2] = (float)((1 - h) * gx / gg);
                f.geom[3] = (float)((1 - h) * gy / gg);
                if (!coords_ok(f.geom, 4))
                    st = SV_FN_RANGE;
            }
        }
    } else {
        double k;
        if (g->fr > 0) {
            st = SV_FN_FOCAL;
        } else if (!is_similarity(G, &k)) {
            st = SV_FN_ELLIPSE;
        } else if (!(g->r > 0)) {
            st = SV_FN_SOLID; /* r = 0: SVG paints the last stop */
        } else {
            double fx = g->fx - g->cx, fy = g->fy - g->cy, d = hypot(fx, fy);
            if (d > FOCAL_MAX * g->r) { /* SVG 1.1: onto the circle; the core: inside it */
                fx *= FOCAL_MAX * g->r / d;
                fy *= FOCAL_MAX * g->r / d;
            }
            sv_pt c = sv_affine_apply(G, sv_pt_make(g->cx, g->cy));
            sv_pt fp = sv_affine_apply(G, sv_pt_make(g->cx + fx, g->cy + fy));
            f.kind = CS_FUNC_RADIAL;
            f.geom[0] = (float)c.x;
            f.geom[1] = (float)c.y;
            f.geom[2] = (float)(g->r * k);
            f.geom[3] = (float)fp.x;
            f.geom[4] = (float)fp.y;
            if (!coords_ok(f.geom, 5) || !(f.geom[2] > 1e-6f))
                st = SV_FN_RANGE;
        }
    }
    if (st == SV_FN_SOLID && (vary_rgb || vary_a)) {
        /* degenerate geometry: SVG paints the area in the last stop's colour */
        memcpy(out->pigment_const, s[n - 1].v, 3 * sizeof(double));
        out->beta_const = s[n - 1].v[3];
    }
    if (st == SV_FN_OK) {
        f.spread = g->spread == SV_SPREAD_REFLECT  ? CS_SPREAD_REFLECT
                   : g->spread == SV_SPREAD_REPEAT ? CS_SPREAD_REPEAT
                                                   : CS_SPREAD_PAD;
        f.stop_count = (uint8_t)n;
        f.map_cols = 1;
        out->pigment = f;
        out->beta = f;
        for (int i = 0; i < n; i++) {
            float off = (float)s[i].off;
            out->pigment.stops[i].offset = out->beta.stops[i].offset = off;
            for (int k = 0; k < 3; k++) {
                out->pigment.stops[i].value[k] = (float)s[i].v[k];
                out->beta.stops[i].value[k] = (float)s[i].v[3];
            }
        }
        out->has_pigment = vary_rgb;
        out->has_beta = vary_a;
    }
    free(s);
    return st;
}
