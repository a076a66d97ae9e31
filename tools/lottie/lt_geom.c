/*
 * lt_geom.c - shape geometry of the Lottie importer at one frame.
 *
 * Builds a shape item's path in its group's space (paths as cubics,
 * ellipses and round corners as exact conics, rects and polystars from
 * rlottie's start points and directions), trims it, carries it up the group
 * transforms (After Effects' order: anchor, scale, skew, rotation,
 * position) to the style's group, strokes it there with the SVG importer's
 * stroker and dasher, and carries the result up to the layer, as closed
 * contours. Fills keep a fixed control-point layout per subpath (every
 * segment raised to the subpath's degree, a closing line added) so that
 * the same shape gives the same layout at every frame.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../svg/sv_internal.h"
#include "lt_shape.h"

/* A transform's matrix and opacity at frame f (the After Effects order). */
void lt_xf_eval(const lt_prop *a, const lt_prop *p, const lt_prop *s, const lt_prop *r,
                const lt_prop *sk, const lt_prop *sa, double f, sv_affine *m)
{
    double av[2], pv[2], sv[2], rv, kv, kav;
    lt_prop_eval(a, f, av);
    lt_prop_eval(p, f, pv);
    lt_prop_eval(s, f, sv);
    lt_prop_eval(r, f, &rv);
    lt_prop_eval(sk, f, &kv);
    lt_prop_eval(sa, f, &kav);
    double d = M_PI / 180;
    sv_affine acc = {sv[0] / 100, 0, 0, sv[1] / 100, -sv[0] / 100 * av[0], -sv[1] / 100 * av[1]};
    if (kv != 0) {
        double ca = cos(kav * d), sn = sin(kav * d), t = tan(-kv * d);
        sv_affine rn = {ca, -sn, sn, ca, 0, 0}, sh = {1, 0, t, 1, 0, 0}, rp = {ca, sn, -sn, ca, 0, 0};
        acc = sv_affine_mul(rp, sv_affine_mul(sh, sv_affine_mul(rn, acc)));
    }
    double cr = cos(rv * d), sr = sin(rv * d);
    sv_affine rot = {cr, sr, -sr, cr, pv[0], pv[1]};
    *m = sv_affine_mul(rot, acc);
}

/*
 * Copy k of a repeater at frame f, as rlottie draws it: with m = k + offset,
 * translate(m p) translate(a) scale(s^m) rotate(m r) translate(-a), so that
 * copy k is the repeater's transform applied k + offset times (exactly so
 * for a uniform scale, which is what repeaters use).
 */
static sv_affine rep_matrix(const sh_rep *r, int copy, double f)
{
    double off, a[2], p[2], s[2], rot;
    lt_prop_eval(&r->o, f, &off);
    lt_prop_eval(&r->a, f, a);
    lt_prop_eval(&r->p, f, p);
    lt_prop_eval(&r->s, f, s);
    lt_prop_eval(&r->r, f, &rot);
    double m = copy + off, d = M_PI / 180;
    double sx = pow(s[0] / 100, m), sy = pow(s[1] / 100, m);
    if (!isfinite(sx) || !isfinite(sy)) /* a negative scale to a fractional power */
        sx = sy = 0;
    double cr = cos(m * rot * d), sr = sin(m * rot * d);
    sv_affine t = {sx * cr, sy * sr, -sx * sr, sy * cr, 0, 0};
    t.e = a[0] + m * p[0] - (t.a * a[0] + t.c * a[1]);
    t.f = a[1] + m * p[1] - (t.b * a[0] + t.d * a[1]);
    return t;
}

/* Copy k's opacity: start to end opacity over k / copies; 0 from copy int(copies) on. */
static double rep_opacity(const sh_rep *r, int copy, double f)
{
    double cv, so, eo;
    lt_prop_eval(&r->c, f, &cv);
    lt_prop_eval(&r->so, f, &so);
    lt_prop_eval(&r->eo, f, &eo);
    if (copy >= (int)cv)
        return 0;
    return (so + (eo - so) * (copy / cv)) / 100;
}

sv_affine lt_node_matrix(const sh_node *n, double f)
{
    sv_affine m = sv_affine_identity();
    if (n->rep)
        return rep_matrix(n->rep, n->copy, f);
    if (n->has_xf)
        lt_xf_eval(&n->a, &n->p, &n->s, &n->r, &n->sk, &n->sa, f, &m);
    return m;
}

double lt_node_opacity(const sh_node *n, double f)
{
    double o = 100;
    if (n->rep)
        return rep_opacity(n->rep, n->copy, f);
    if (n->has_xf)
        lt_prop_eval(&n->o, f, &o);
    return o / 100;
}


void lt_path_build(const double *vals, int n, sv_path *out)
{
    lt_path lp;
    lt_path_from_values(vals, n, &lp);
    sv_path_move(out, lp.v[0], lp.v[1]);
    int segs = lp.closed ? n : n - 1;
    for (int k = 0; k < segs; k++) {
        int j = (k + 1) % n;
        sv_path_cubic(out, lp.v[2 * k] + lp.out[2 * k], lp.v[2 * k + 1] + lp.out[2 * k + 1],
                      lp.v[2 * j] + lp.in[2 * j], lp.v[2 * j + 1] + lp.in[2 * j + 1],
                      lp.v[2 * j], lp.v[2 * j + 1]);
    }
    if (lp.closed)
        sv_path_close(out);
}

/*
 * A star, or a polygon with roundness, as rlottie builds it (VPath::addPolystar,
 * addPolygon): with roundness each side is a cubic whose handles lie along the tangents
 * of the circles through its ends, as long as the vertex's radius times its roundness
 * times 0.47829 / 0.28 over the point count (a star) or times 0.25 (a polygon, outer
 * roundness only); without, a line. A star's fractional point count gives a partial
 * point between the last and the first, as there.
 */
static void rlottie_polystar(const sh_path *p, const double *pv, double npt, double rot, double ir,
                           double orr, double is, double os, sv_path *out)
{
    double dir = p->reversed ? -1 : 1, cx = pv[0], cy = pv[1];
    double cur = (rot - 90) * M_PI / 180, x, y, x0, y0;
    if (p->star == 2) {
        int n = (int)floor(npt);
        double per = 2 * M_PI / n;
        x0 = x = orr * cos(cur), y0 = y = orr * sin(cur);
        cur += per * dir;
        sv_path_move(out, x + cx, y + cy);
        for (int i = 0; i < n; i++) {
            double px = x, py = y;
            x = i == n - 1 ? x0 : orr * cos(cur), y = i == n - 1 ? y0 : orr * sin(cur);
            double t1 = atan2(py, px) - M_PI / 2 * dir, t2 = atan2(y, x) - M_PI / 2 * dir;
            double k = orr * os * 0.25;
            sv_path_cubic(out, px - k * cos(t1) + cx, py - k * sin(t1) + cy,
                          x + k * cos(t2) + cx, y + k * sin(t2) + cy, x + cx, y + cy);
            cur += per * dir;
        }
        sv_path_close(out);
        return;
    }
    const double magic = 0.47829 / 0.28;
    double per = 2 * M_PI / npt, half = per / 2, partial = npt - floor(npt), pr = 0;
    int m = (int)ceil(npt) * 2;
    if (partial != 0) {
        cur += half * (1 - partial) * dir;
        pr = ir + partial * (orr - ir);
        x = pr * cos(cur), y = pr * sin(cur);
        cur += per * partial / 2 * dir;
    } else {
        x = orr * cos(cur), y = orr * sin(cur);
        cur += half * dir;
    }
    x0 = x, y0 = y;
    sv_path_move(out, x + cx, y + cy);
    bool outer = false; /* the side ends on an outer vertex */
    for (int i = 0; i < m; i++) {
        double radius = outer ? orr : ir, dth = half;
        if (pr != 0 && i == m - 2)
            dth = per * partial / 2;
        if (pr != 0 && i == m - 1)
            radius = pr;
        double px = x, py = y;
        x = radius * cos(cur), y = radius * sin(cur);
        if (i == m - 1)
            x = x0, y = y0; /* the start, exactly: no sliver of a closing side */
        double t1 = atan2(py, px) - M_PI / 2 * dir, t2 = atan2(y, x) - M_PI / 2 * dir;
        double k1 = (outer ? ir * is : orr * os) * magic / npt;
        double k2 = (outer ? orr * os : ir * is) * magic / npt;
        if (partial != 0 && (i == 0 || i == m - 1))
            k1 *= partial, k2 *= partial;
        if (is == 0 && os == 0) {
            if (i < m - 1) /* the last side is the close */
                sv_path_line(out, x + cx, y + cy);
        } else
            sv_path_cubic(out, px - k1 * cos(t1) + cx, py - k1 * sin(t1) + cy, x + k2 * cos(t2) + cx,
                      y + k2 * sin(t2) + cy, x + cx, y + cy);
        cur += dth * dir;
        outer = !outer;
    }
    sv_path_close(out);
}

/* A path item at frame f in its group's space. */
static void build_path(const sh_path *p, double f, sv_path *out)
{
    if (p->type == SH_PATH) {
        int n = p->nverts;
        if (n < 1)
            return;
        double *vals = malloc((size_t)(1 + 6 * n) * sizeof *vals);
        if (!vals)
            return;
        lt_prop_eval(&p->k, f, vals);
        lt_path_build(vals, n, out);
        free(vals);
        return;
    }
    double pv[2], sv[2];
    lt_prop_eval(&p->p, f, pv);
    if (p->type == SH_ELLIPSE) {
        lt_prop_eval(&p->s, f, sv);
        double rx = fabs(sv[0]) / 2, ry = fabs(sv[1]) / 2, k = sqrt(0.5);
        /* From the top, clockwise on screen (rlottie's start point). */
        double cx = pv[0], cy = pv[1];
        sv_path_move(out, cx, cy - ry);
        if (!p->reversed) {
            sv_path_conic(out, cx + rx, cy - ry, k, cx + rx, cy);
            sv_path_conic(out, cx + rx, cy + ry, k, cx, cy + ry);
            sv_path_conic(out, cx - rx, cy + ry, k, cx - rx, cy);
            sv_path_conic(out, cx - rx, cy - ry, k, cx, cy - ry);
        } else {
            sv_path_conic(out, cx - rx, cy - ry, k, cx - rx, cy);
            sv_path_conic(out, cx - rx, cy + ry, k, cx, cy + ry);
            sv_path_conic(out, cx + rx, cy + ry, k, cx + rx, cy);
            sv_path_conic(out, cx + rx, cy - ry, k, cx, cy - ry);
        }
        sv_path_close(out);
        return;
    }
    if (p->type == SH_RECT) {
        double rr;
        lt_prop_eval(&p->s, f, sv);
        lt_prop_eval(&p->r, f, &rr);
        double w = fabs(sv[0]) / 2, h = fabs(sv[1]) / 2;
        double r = fmin(fmax(rr, 0), fmin(w, h)), k = sqrt(0.5);
        double x0 = pv[0] - w, x1 = pv[0] + w, y0 = pv[1] - h, y1 = pv[1] + h;
        /* Clockwise from the top right, as rlottie; corners as quarter conics. */
        double pts[8][2] = {{x1, y0 + r}, {x1, y1 - r}, {x1 - r, y1}, {x0 + r, y1},
                            {x0, y1 - r}, {x0, y0 + r}, {x0 + r, y0}, {x1 - r, y0}};
        double corner[4][2] = {{x1, y1}, {x0, y1}, {x0, y0}, {x1, y0}};
        if (p->reversed) {
            sv_path_move(out, pts[0][0], pts[0][1]);
            for (int i = 7; i >= 0; i--) {
                if (i % 2 == 1)
                    sv_path_line(out, pts[i][0], pts[i][1]);
                else if (r > 0)
                    sv_path_conic(out, corner[(i / 2 + 3) % 4][0], corner[(i / 2 + 3) % 4][1], k,
                                  pts[i][0], pts[i][1]);
                else
                    sv_path_line(out, pts[i][0], pts[i][1]);
            }
        } else {
            sv_path_move(out, pts[0][0], pts[0][1]);
            for (int i = 1; i <= 8; i++) {
                int j = i % 8;
                if (i % 2 == 1)
                    sv_path_line(out, pts[j][0], pts[j][1]);
                else if (r > 0)
                    sv_path_conic(out, corner[i / 2 - 1][0], corner[i / 2 - 1][1], k, pts[j][0],
                                  pts[j][1]);
                else
                    sv_path_line(out, pts[j][0], pts[j][1]);
            }
        }
        sv_path_close(out);
        return;
    }
    /* Polystar: from the top (rotation 0), clockwise unless reversed. */
    double npt, rot, ir, orr, is, os;
    lt_prop_eval(&p->pt, f, &npt);
    lt_prop_eval(&p->r, f, &rot);
    lt_prop_eval(&p->ir, f, &ir);
    lt_prop_eval(&p->or_, f, &orr);
    lt_prop_eval(&p->is, f, &is);
    lt_prop_eval(&p->os, f, &os);
    if (!(npt >= 2 && npt < 1001))
        return; /* checked as a float: the cast of a huge or NaN count is undefined */
    int n = (int)floor(npt);
    if (p->whole)
        npt = n, is = os = 0;
    /* rlottie turns a polystar by twice its rotation (Debian's librlottie, checked with
     * stars at 30 degrees and turning 0..184: 2r matches, r does not). */
    rot *= 2;
    if (p->star == 1 || os != 0) {
        rlottie_polystar(p, pv, npt, rot, ir, orr, is / 100, os / 100, out);
        return;
    }
    for (int i = 0; i < n; i++) {
        int k = p->reversed ? (n - i) % n : i;
        double ang = (rot - 90) * M_PI / 180 + 2 * M_PI * k / n;
        double x = pv[0] + orr * cos(ang), y = pv[1] + orr * sin(ang);
        if (i == 0)
            sv_path_move(out, x, y);
        else
            sv_path_line(out, x, y);
    }
    sv_path_close(out);
}

/* Trims `path` to [s, e] of each subpath's length, shifted by o (rlottie's simultaneous mode). */
static void trim_path(const sh_trim *tm, double f, sv_path *path)
{
    double s, e, o;
    lt_prop_eval(&tm->s, f, &s);
    lt_prop_eval(&tm->e, f, &e);
    lt_prop_eval(&tm->o, f, &o);
    s /= 100, e /= 100, o /= 360;
    if (s > e) {
        double t = s;
        s = e, e = t;
    }
    s += o, e += o;
    double sh = floor(s);
    s -= sh, e -= sh;
    if (e - s >= 1 - 1e-9)
        return;
    sv_path out;
    sv_path_init(&out);
    for (int i = 0; i < path->n; i++) {
        sv_path one;
        sv_path_init(&one);
        one.sub = &path->sub[i];
        one.n = 1;
        /* The subpath's length, by flattening. */
        sv_pt *pts = NULL;
        int np = 0;
        sv_subpath_flatten(&path->sub[i], 32, &pts, &np);
        double len = 0;
        int last = path->sub[i].closed ? np : np - 1;
        for (int k = 0; k < last; k++)
            len += sv_hypot(pts[(k + 1) % np].x - pts[k].x, pts[(k + 1) % np].y - pts[k].y);
        free(pts);
        if (len <= 0 || e - s <= 0)
            continue;
        /* Visible [s, e], wrapping past 1 as two pieces: each one dash
         * followed by a gap longer than the path, so that the flattened
         * length's small shortfall never starts a second dash (a dot under
         * round caps) at the path's end. So each call makes at most two
         * dashes, far below the limit sv_path_dash asks for. */
        double big = 4 * len + 1;
        double first[2] = {(fmin(e, 1) - s) * len, big};
        sv_path_dash(&one, first, 2, -s * len, SV_MAX_DASHES, &out);
        if (e > 1) {
            double wrap[2] = {(e - 1) * len, big};
            sv_path_dash(&one, wrap, 2, 0, SV_MAX_DASHES, &out);
        }
    }
    sv_path_free(path);
    *path = out;
}

/* The chain of group transforms from node `from` up to (not including) `to`. */
sv_affine lt_chain(const sh_node *from, const sh_node *to, double f)
{
    sv_affine m = sv_affine_identity();
    for (const sh_node *n = from; n && n != to; n = n->parent)
        m = sv_affine_mul(lt_node_matrix(n, f), m);
    return m;
}

/* Closed contours of a path with a fixed layout: one per subpath, every
 * segment elevated to the subpath's highest degree, a closing line added. */
void lt_fixed_contours(const sv_path *p, sv_contour **out, int *n)
{
    for (int i = 0; i < p->n; i++) {
        const sv_subpath *sp = &p->sub[i];
        if (sp->n < 1)
            continue;
        int k = sp->n, degree = 1;
        for (int j = 0; j < sp->n; j++)
            degree = sp->seg[j].degree > degree ? sp->seg[j].degree : degree;
        sv_pt first = sp->seg[0].p[0], last = sp->seg[k - 1].p[sp->seg[k - 1].degree];
        bool close = first.x != last.x || first.y != last.y || k == 1;
        int nseg = k + (close ? 1 : 0);
        *out = sv_xrealloc(*out, (size_t)(*n + 1) * sizeof **out);
        sv_contour *c = &(*out)[(*n)++];
        c->degree = degree;
        c->count = nseg * degree;
        c->pts = sv_xrealloc(NULL, (size_t)c->count * 3 * sizeof(double));
        c->intervals = sv_xrealloc(NULL, (size_t)c->count * sizeof(double));
        for (int j = 0; j < nseg; j++) {
            sv_seg s = j < k ? sp->seg[j] : (sv_seg){1, {last, first}, 1};
            double h[4][3];
            sv_seg_elevate(&s, degree, h);
            for (int m = 0; m < degree; m++) {
                double *q = &c->pts[3 * (j * degree + m)];
                q[0] = h[m][0] / h[m][2];
                q[1] = h[m][1] / h[m][2];
                q[2] = h[m][2];
                c->intervals[j * degree + m] = m == 0 ? 1.0 : 0.0;
            }
        }
    }
}

/* A region's contours at frame f, in the layer's space. */
void lt_region_contours(lt_ctx *c, const sh_style *s, double f, sv_contour **out, int *n)
{
    sv_path all;
    sv_path_init(&all);
    for (int i = 0; i < s->npaths; i++) {
        const sh_path *p = s->paths[i];
        sv_path one;
        sv_path_init(&one);
        build_path(p, f, &one);
        for (int k = 0; k < p->ntrims; k++)
            trim_path(p->trims[k], f, &one);
        sv_path_transform(&one, lt_chain(p->node, s->node, f));
        sv_path_append(&all, &one);
        sv_path_free(&one);
    }
    sv_affine up = lt_chain(s->node, NULL, f);
    /* Outlining costs about a few dozen floats per segment: charged first. */
    int nseg = 0;
    for (int i = 0; i < all.n; i++)
        nseg += all.sub[i].n;
    if (!lt_charge(c, (s->type == ST_STROKE || s->type == ST_GSTROKE ? 64.0 : 4.0) * nseg)) {
        sv_path_free(&all);
        return;
    }
    if (s->type == ST_STROKE || s->type == ST_GSTROKE) {
        double w;
        lt_prop_eval(&s->w, f, &w);
        sv_path src = all;
        sv_path dashed;
        sv_path_init(&dashed);
        if (s->has_dash) {
            double d[16], off, sum = 0;
            for (int k = 0; k < s->ndash; k++) {
                lt_prop_eval(&s->dash[k], f, &d[k]);
                d[k] = fmax(d[k], 0);
                sum += d[k];
            }
            lt_prop_eval(&s->dash_offset, f, &off);
            if (sum > 0 && sv_path_dash(&all, d, s->ndash, off, SV_MAX_DASHES, &dashed) < 0) {
                lt_fail(c, "a stroke's dash pattern makes more than %d dashes (SV_MAX_DASHES: the "
                        "scene store's control points hold no more): refused", SV_MAX_DASHES);
                sv_path_free(&dashed);
                sv_path_free(&all);
                return;
            }
            if (sum > 0)
                src = dashed;
        }
        sv_path outline;
        sv_path_init(&outline);
        if (w > 0) {
            /* Tolerance in the style's space: the canvas one over the scale above. */
            double scale = sv_affine_max_scale(up);
            /* One region's outline can never need more than the whole store's points. */
            sv_stroke_style st = {w, s->cap, s->join, s->miter,
                                  c->tolerance / (scale > 1e-9 ? scale : 1), CS_CFG_MAX_POINTS};
            if (sv_stroke_path(&src, &st, &outline) < 0)
                lt_fail(c, "a stroke's outline needs more than the scene store's %ld control "
                        "points (CS_CFG_MAX_POINTS): refused", (long)CS_CFG_MAX_POINTS);
        }
        sv_path_transform(&outline, up);
        sv_path_to_contours(&outline, out, n);
        sv_path_free(&outline);
        sv_path_free(&dashed);
    } else {
        sv_path_transform(&all, up);
        lt_fixed_contours(&all, out, n);
    }
    sv_path_free(&all);
}

bool lt_same_layout(const sv_contour *a, int na, const sv_contour *b, int nb)
{
    if (na != nb)
        return false;
    for (int i = 0; i < na; i++)
        if (a[i].degree != b[i].degree || a[i].count != b[i].count ||
            memcmp(a[i].intervals, b[i].intervals, (size_t)a[i].count * sizeof(double)) != 0)
            return false;
    return true;
}

void lt_free_contours(sv_contour *c, int n)
{
    for (int i = 0; i < n; i++)
        sv_contour_free(&c[i]);
    free(c);
}
