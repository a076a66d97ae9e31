/*
 * sv_clip.c - exact clipping of filled paths by convex polygons.
 *
 * A clip path that is one convex polygon (the page rectangles editors add,
 * rotated rectangles, triangles) is applied to the geometry itself, which
 * costs the core nothing; other clip paths go to the core's CSG (sv_plan.c).
 * The gradient bands (sv_bands.c) use the same cut, and sv_path_reverse.
 * Clipping a closed curve to the half-plane a x + b y + c >= 0 is done the
 * Sutherland-Hodgman way without computing any new curve: every segment is
 * split where it crosses the line (exact sub-segments, sv_seg_sub), and the
 * pieces outside are projected onto the line. The projection moves no curve
 * across a point inside the half-plane, so every inside point keeps its
 * winding number while every outside point gets winding zero - for any fill
 * rule, and for strokes' nonzero outlines alike. A projected piece lies on
 * the line, where only its end points matter to points off the line, so it
 * is kept as the chord between them, and a run of such pieces as one line:
 * repeated clipping does not make the geometry grow.
 */
#include <math.h>

#include "sv_internal.h"

/*
 * f(t) = a X + b Y + c W for the homogeneous segment. A value within the
 * rounding error of its terms is 0: a piece lying on the line (a rectangle
 * cut by its own edge) must not cross it back and forth on noise.
 */
static double side(const sv_seg *s, double t, double a, double b, double c)
{
    sv_pt p = sv_seg_eval(s, t);
    double f = a * p.x + b * p.y + c;
    return fabs(f) <= 1e-12 * (fabs(a * p.x) + fabs(b * p.y) + fabs(c)) ? 0 : f;
}

/*
 * Parameters in (0,1) where the segment crosses the line, increasing. Sign
 * changes are bracketed between the last samples that are not exactly on
 * the line, so a crossing that falls on a sample point is still found.
 */
static int crossings(const sv_seg *s, double a, double b, double c, double *ts)
{
    enum { N = 48 };
    /* a curve lies in its control points' hull (weights > 0): one side, no crossing */
    bool pos = false, neg = false;
    for (int k = 0; k <= s->degree; k++) {
        double v = a * s->p[k].x + b * s->p[k].y + c;
        pos |= v > 0;
        neg |= v < 0;
    }
    if (!pos || !neg)
        return 0;
    int n = 0;
    double t0 = 0, f0 = side(s, 0, a, b, c);
    for (int i = 1; i <= N; i++) {
        double t1 = (double)i / N, f1 = side(s, t1, a, b, c);
        if (f1 == 0 && i < N)
            continue; /* decide at the next sample off the line */
        if ((f0 < 0 && f1 > 0) || (f0 > 0 && f1 < 0)) {
            double lo = t0, hi = t1, flo = f0;
            for (int k = 0; k < 60; k++) {
                double m = 0.5 * (lo + hi), fm = side(s, m, a, b, c);
                if (fm != 0 && (fm < 0) == (flo < 0)) {
                    lo = m;
                    flo = fm;
                } else {
                    hi = m;
                }
            }
            if (n < 6 && 0.5 * (lo + hi) > 1e-12 && 0.5 * (lo + hi) < 1 - 1e-12)
                ts[n++] = 0.5 * (lo + hi);
        }
        if (f1 != 0 || f0 == 0) {
            t0 = t1;
            f0 = f1;
        }
    }
    return n;
}

void sv_path_clip_halfplane(sv_path *p, double a, double b, double c)
{
    double nn = a * a + b * b;
    sv_path out;
    sv_path_init(&out);
    for (int i = 0; i < p->n; i++) {
        const sv_subpath *sp = &p->sub[i];
        if (sp->n == 0)
            continue;
        int emitted = 0;
        bool prev_outside = false;
        sv_pt first = sp->seg[0].p[0];
        for (int k = 0; k <= sp->n; k++) {
            sv_seg s;
            if (k < sp->n) {
                s = sp->seg[k];
            } else { /* the closing line */
                sv_pt last = sp->seg[sp->n - 1].p[sp->seg[sp->n - 1].degree];
                if (last.x == first.x && last.y == first.y)
                    break;
                sv_seg l = {1, {last, first}, 1};
                s = l;
            }
            double ts[6];
            int nc = crossings(&s, a, b, c, ts);
            for (int j = 0; j <= nc; j++) {
                double ta = j > 0 ? ts[j - 1] : 0, tb = j < nc ? ts[j] : 1;
                sv_seg piece = nc == 0 ? s : sv_seg_sub(&s, ta, tb);
                bool outside = side(&piece, 0.5, a, b, c) < 0;
                if (outside) {
                    /* The projected curve lies on the line; its chord is the same
                     * path for every point off the line, so keep just that. */
                    sv_pt e0 = piece.p[0], e1 = piece.p[piece.degree];
                    double f0 = (a * e0.x + b * e0.y + c) / nn, f1 = (a * e1.x + b * e1.y + c) / nn;
                    piece.degree = 1;
                    piece.w = 1;
                    piece.p[0] = sv_pt_make(e0.x - f0 * a, e0.y - f0 * b);
                    piece.p[1] = sv_pt_make(e1.x - f1 * a, e1.y - f1 * b);
                }
                if (emitted == 0) {
                    sv_path_move(&out, piece.p[0].x, piece.p[0].y);
                } else {
                    piece.p[0] = out.cur; /* keep the chain exactly joined */
                    sv_subpath *os = &out.sub[out.n - 1];
                    if (outside && prev_outside) { /* one run along the line: one line */
                        os->seg[os->n - 1].p[1] = piece.p[1];
                        out.cur = piece.p[1];
                        continue;
                    }
                }
                emitted++;
                prev_outside = outside;
                sv_path_add_seg(&out, &piece);
            }
        }
        sv_path_close(&out);
    }
    sv_path_free(p);
    *p = out;
}

bool sv_path_convex_polygon(const sv_path *clip, sv_pt **poly, int *n)
{
    if (clip->n != 1)
        return false;
    const sv_subpath *sp = &clip->sub[0];
    sv_pt *v = sv_xrealloc(NULL, (size_t)(sp->n + 2) * sizeof *v);
    int m = 0;
    for (int k = 0; k < sp->n; k++) {
        if (sp->seg[k].degree != 1) {
            free(v);
            return false;
        }
        sv_pt q = sp->seg[k].p[0];
        if (m == 0 || q.x != v[m - 1].x || q.y != v[m - 1].y)
            v[m++] = q;
    }
    if (sp->n > 0) {
        sv_pt q = sp->seg[sp->n - 1].p[1];
        if (m == 0 || q.x != v[m - 1].x || q.y != v[m - 1].y)
            v[m++] = q;
    }
    if (m > 1 && v[0].x == v[m - 1].x && v[0].y == v[m - 1].y)
        m--;
    /*
     * Skip collinear vertices, then require one turning direction and one
     * turn in all: a pentagram turns one way at every vertex, but twice
     * around (it self-intersects, and is no convex polygon).
     */
    double sign = 0, turn = 0;
    bool ok = m >= 3;
    for (int k = 0; ok && k < m; k++) {
        sv_pt e1 = sv_sub(v[(k + 1) % m], v[k]), e2 = sv_sub(v[(k + 2) % m], v[(k + 1) % m]);
        double cr = sv_cross(e1, e2);
        turn += atan2(cr, sv_dot(e1, e2));
        if (fabs(cr) <= 1e-12 * (sv_len(e1) * sv_len(e2) + 1e-300))
            continue;
        if (sign == 0)
            sign = cr;
        else if ((cr > 0) != (sign > 0))
            ok = false;
    }
    if (!ok || sign == 0 || fabs(fabs(turn) - 2 * M_PI) > 0.5) {
        free(v);
        return false;
    }
    *poly = v;
    *n = m;
    return true;
}

void sv_path_clip_polygon(sv_path *p, const sv_pt *v, int n)
{
    double area = 0;
    for (int k = 0; k < n; k++)
        area += sv_cross(v[k], v[(k + 1) % n]);
    double s = area > 0 ? 1 : -1;
    for (int k = 0; k < n; k++) {
        sv_pt a = v[k], d = sv_sub(v[(k + 1) % n], a);
        if (d.x == 0 && d.y == 0)
            continue;
        /* keep s * cross(d, q - a) >= 0 */
        sv_path_clip_halfplane(p, -s * d.y, s * d.x, s * (d.y * a.x - d.x * a.y));
    }
}

void sv_path_reverse(sv_path *p)
{
    for (int i = 0; i < p->n; i++) {
        sv_subpath *sp = &p->sub[i];
        if (sp->n == 0)
            continue;
        sv_pt first = sp->seg[0].p[0], last = sp->seg[sp->n - 1].p[sp->seg[sp->n - 1].degree];
        if (first.x != last.x || first.y != last.y) { /* close it before turning it round */
            sv_seg l = {1, {last, first}, 1};
            SV_GROW(sp->seg, sp->n, sp->cap);
            sp->seg[sp->n++] = l;
        }
        for (int a = 0, b = sp->n - 1; a < b; a++, b--) {
            sv_seg t = sp->seg[a];
            sp->seg[a] = sp->seg[b];
            sp->seg[b] = t;
        }
        for (int k = 0; k < sp->n; k++)
            sv_seg_reverse(&sp->seg[k]);
    }
}
