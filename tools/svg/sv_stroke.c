/*
 * sv_stroke.c - strokes as regions: the outline of a stroked path.
 *
 * "Lines are simply elongated regions" (Willis & Oddy). SVG defines a
 * stroke as the union of the segments' bodies (every point c(t) + r n(t),
 * |r| <= w/2, n the unit normal), the joins at vertices and the caps at open
 * ends. This outliner emits that union literally: every body half (one side
 * of one piece of a segment), join and cap is its own closed contour,
 * oriented to wind positively, and the region is filled with the nonzero
 * rule. Overlaps - inner sides of joins, self-crossing paths, tight loops -
 * then only add winding, so no outline surgery is needed and nothing can
 * leave a hole.
 *
 * Offsets. Lines offset to lines and circular arcs to concentric arcs (a
 * homothety about the centre, exact on the conic's control points). Other
 * curves are cut where they turn more than 45 degrees, and each side of a
 * piece is fitted by a cubic with the offset's end points and end tangent
 * directions whose leg lengths make it pass through the offset's midpoint.
 * The fit is checked both ways at 7 points each - fitted points must lie at
 * distance w/2 from the curve, on the right side, within the tolerance, and
 * offset points within the tolerance of the fitted cubic - and the piece is
 * halved until it passes (at most 18 times; pieces still failing are
 * counted and reported). A caller's budget of control points
 * (sv_stroke_style.max_points) bounds the work on hostile input: the
 * outliner stops as soon as its output would exceed it.
 *
 * Where a side curves tighter than w/2 (h kappa > 1) its offset runs
 * backwards and the body half would wind negatively in part. There the side
 * is cut into pieces turning a few degrees, and each piece becomes two
 * positive lobes meeting where its end normals cross (the centre of
 * curvature): the curve's side, exact, and the far side, whose offset chord
 * is checked against the tolerance.
 *
 * Joins fill the outer wedge only (miter within the miter limit, else
 * bevel; round as an exact circular arc); caps are squares or exact
 * semicircles. Zero-length subpaths draw round or square dots, as SVG asks.
 */
#include <math.h>

#include "sv_internal.h"

#define MAX_DEPTH 18
#define SAMPLES 7

typedef struct stroker {
    const sv_stroke_style *st;
    double h, tol;
    sv_path *out;
    int missed;
    long points; /* control points emitted, against st->max_points */
    bool over;   /* st->max_points reached: stop */
} stroker;

static sv_pt perp(sv_pt t)
{
    return sv_pt_make(-t.y, t.x);
}

static sv_pt unit(sv_pt v)
{
    double l = sv_len(v);
    return l > 0 ? sv_scale(v, 1 / l) : sv_pt_make(1, 0);
}

static bool same_pt(sv_pt a, sv_pt b)
{
    return a.x == b.x && a.y == b.y;
}

/* End tangents from the control polygon: defined even where c'(t) = 0. */
static sv_pt tangent_start(const sv_seg *s)
{
    for (int k = 1; k <= s->degree; k++)
        if (!same_pt(s->p[k], s->p[0]))
            return unit(sv_sub(s->p[k], s->p[0]));
    return sv_pt_make(1, 0);
}

static sv_pt tangent_end(const sv_seg *s)
{
    for (int k = s->degree - 1; k >= 0; k--)
        if (!same_pt(s->p[k], s->p[s->degree]))
            return unit(sv_sub(s->p[s->degree], s->p[k]));
    return sv_pt_make(1, 0);
}

/* Unit tangent at t, falling back to the end tangents at the ends. */
static sv_pt tangent_at(const sv_seg *s, double t)
{
    if (t <= 0)
        return tangent_start(s);
    if (t >= 1)
        return tangent_end(s);
    sv_pt d = sv_seg_deriv(s, t);
    if (sv_len(d) < 1e-12 * (1 + fabs(s->p[0].x) + fabs(s->p[0].y)))
        return unit(sv_sub(sv_seg_eval(s, fmin(t + 1e-6, 1)), sv_seg_eval(s, fmax(t - 1e-6, 0))));
    return unit(d);
}

static double seg_poly_len(const sv_seg *s)
{
    double l = 0;
    for (int k = 0; k < s->degree; k++)
        l += sv_len(sv_sub(s->p[k + 1], s->p[k]));
    return l;
}

/* ------------------------------------------------------------ contours */

/* Appends subpath `c` to the output, reversed if it winds negatively. */
static void emit(stroker *sk, sv_path *c)
{
    if (c->n == 0)
        return;
    sv_subpath *sp = &c->sub[0];
    double a = sv_subpath_area(sp);
    if (a < 0) {
        for (int i = 0, j = sp->n - 1; i < j; i++, j--) {
            sv_seg t = sp->seg[i];
            sp->seg[i] = sp->seg[j];
            sp->seg[j] = t;
        }
        for (int i = 0; i < sp->n; i++)
            sv_seg_reverse(&sp->seg[i]);
    }
    sp->closed = true;
    /* counted with or without area: the budget bounds the work as well */
    for (int i = 0; i < sp->n; i++)
        sk->points += sp->seg[i].degree;
    if (sk->st->max_points > 0 && sk->points > sk->st->max_points)
        sk->over = true;
    if (a != 0 && !sk->over)
        sv_path_append(sk->out, c);
    sv_path_free(c);
}

static void seg_to(sv_path *c, const sv_seg *s)
{
    sv_seg t = *s;
    if (c->n == 0 || !c->open_sub)
        sv_path_move(c, t.p[0].x, t.p[0].y);
    else
        t.p[0] = c->cur; /* chain exactly */
    sv_path_add_seg(c, &t);
}

static void line_to(sv_path *c, sv_pt p)
{
    if (!same_pt(c->cur, p))
        sv_path_line(c, p.x, p.y);
}

/* Circular arc about `ctr` from angle direction u (unit) turning by `ang` (signed). */
static void arc_to(sv_path *c, sv_pt ctr, double r, sv_pt u, double ang)
{
    int n = (int)ceil(fabs(ang) / (M_PI / 2) - 1e-9);
    if (n < 1)
        n = 1;
    double step = ang / n, w = cos(step / 2), a0 = atan2(u.y, u.x);
    for (int i = 0; i < n; i++) {
        double s0 = a0 + step * i, s1 = s0 + step, sm = 0.5 * (s0 + s1);
        sv_pt mid = sv_add(ctr, sv_pt_make(r * cos(sm) / w, r * sin(sm) / w));
        sv_pt to = sv_add(ctr, sv_pt_make(r * cos(s1), r * sin(s1)));
        sv_path_conic(c, mid.x, mid.y, w, to.x, to.y);
    }
}

/* ------------------------------------------------------------- offsets */

/* Offset point at t on side s (+1: along n = perp(tangent), -1 against). */
static sv_pt offset_at(const stroker *sk, const sv_seg *s, double t, int side)
{
    return sv_add(sv_seg_eval(s, t), sv_scale(perp(tangent_at(s, t)), side * sk->h));
}

/* Nearest point parameter on seg to q: dense samples, then golden section. */
static double nearest_t(const sv_seg *s, sv_pt q)
{
    enum { N = 48 };
    double best = 0, bd = INFINITY;
    for (int i = 0; i <= N; i++) {
        double t = (double)i / N, d = sv_len(sv_sub(sv_seg_eval(s, t), q));
        if (d < bd) {
            bd = d;
            best = t;
        }
    }
    double lo = fmax(0, best - 1.0 / N), hi = fmin(1, best + 1.0 / N);
    const double g = 0.6180339887498949;
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    double f1 = sv_len(sv_sub(sv_seg_eval(s, x1), q)), f2 = sv_len(sv_sub(sv_seg_eval(s, x2), q));
    for (int it = 0; it < 60; it++) {
        if (f1 < f2) {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - g * (hi - lo);
            f1 = sv_len(sv_sub(sv_seg_eval(s, x1), q));
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + g * (hi - lo);
            f2 = sv_len(sv_sub(sv_seg_eval(s, x2), q));
        }
    }
    return 0.5 * (lo + hi);
}

/*
 * Cubic through the offset's end points with its end tangent directions,
 * legs chosen so that B(1/2) is the offset's midpoint.
 */
static void fit_offset(const stroker *sk, const sv_seg *s, int side, sv_seg *fit)
{
    sv_pt t0 = tangent_start(s), t1 = tangent_end(s);
    sv_pt o0 = sv_add(s->p[0], sv_scale(perp(t0), side * sk->h));
    sv_pt o3 = sv_add(s->p[s->degree], sv_scale(perp(t1), side * sk->h));
    sv_pt om = offset_at(sk, s, 0.5, side);
    /* B(1/2) = (o0 + o3)/2 + 3/8 (a t0 - b t1) */
    sv_pt r = sv_scale(sv_sub(om, sv_scale(sv_add(o0, o3), 0.5)), 8.0 / 3);
    double det = sv_cross(t0, sv_scale(t1, -1));
    double a, b;
    if (fabs(det) > 1e-6) {
        a = sv_cross(r, sv_scale(t1, -1)) / det;
        b = sv_cross(t0, r) / det;
    } else { /* parallel end tangents: equal legs along them */
        double l = sv_dot(r, t0);
        a = b = l / 2;
        if (!(a > 0))
            a = b = sv_len(sv_sub(o3, o0)) / 3;
    }
    fit->degree = 3;
    fit->w = 1;
    fit->p[0] = o0;
    fit->p[1] = sv_add(o0, sv_scale(t0, a));
    fit->p[2] = sv_sub(o3, sv_scale(t1, b));
    fit->p[3] = o3;
}

/* Largest deviation of the fit from the offset, checked both ways. */
static double fit_error(const stroker *sk, const sv_seg *s, const sv_seg *fit, int side)
{
    double err = 0;
    for (int k = 1; k <= SAMPLES; k++) {
        double u = (double)k / (SAMPLES + 1);
        /* fitted point: at distance h from the curve, on the right side */
        sv_pt q = sv_seg_eval(fit, u);
        double t = nearest_t(s, q);
        sv_pt c = sv_seg_eval(s, t), d = sv_sub(q, c);
        double e = fabs(sv_len(d) - sk->h);
        if (sv_cross(tangent_at(s, t), d) * side < 0 && sv_len(d) > sk->tol)
            e = INFINITY;
        err = fmax(err, e);
        /* offset point: near the fitted curve */
        sv_pt o = offset_at(sk, s, u, side);
        double v = nearest_t(fit, o);
        err = fmax(err, sv_len(sv_sub(sv_seg_eval(fit, v), o)));
    }
    return err;
}

/* Whether the offset on this side runs backwards somewhere (h kappa > 1). */
static bool reverses(const stroker *sk, const sv_seg *s, int side)
{
    for (int k = 0; k <= 16; k++) {
        sv_pt c, c1, c2;
        sv_seg_derivs(s, k / 16.0, &c, &c1, &c2);
        double l = sv_len(c1);
        if (l < 1e-12)
            continue;
        double kappa = sv_cross(c1, c2) / (l * l * l); /* signed: > 0 turns toward n */
        if (side * sk->h * kappa > 1)
            return true;
    }
    return false;
}

/* Total turning of the tangent over the segment (radians), sampled. */
static double turning(const sv_seg *s)
{
    double sum = 0;
    sv_pt prev = tangent_start(s);
    for (int k = 1; k <= 16; k++) {
        sv_pt t = k == 16 ? tangent_end(s) : tangent_at(s, k / 16.0);
        sum += fabs(atan2(sv_cross(prev, t), sv_dot(prev, t)));
        prev = t;
    }
    return sum;
}

/* Body half between the curve and a fitted offset. */
static void emit_half(stroker *sk, const sv_seg *s, const sv_seg *off)
{
    sv_path c;
    sv_path_init(&c);
    seg_to(&c, s);
    line_to(&c, off->p[off->degree]);
    sv_seg r = *off;
    sv_seg_reverse(&r);
    seg_to(&c, &r);
    line_to(&c, s->p[0]);
    emit(sk, &c);
}

/* Where the end normals of s cross: false if they do not within reach. */
static bool normals_meet(const sv_seg *s, sv_pt *x)
{
    sv_pt n0 = perp(tangent_start(s)), n1 = perp(tangent_end(s));
    sv_pt c0 = s->p[0], c1 = s->p[s->degree];
    double den = sv_cross(n0, n1);
    if (fabs(den) < 1e-12)
        return false;
    double lam = sv_cross(sv_sub(c1, c0), n1) / den;
    *x = sv_add(c0, sv_scale(n0, lam));
    return true;
}

static void half_reversed(stroker *sk, const sv_seg *s, int side, int depth);

static void half(stroker *sk, const sv_seg *s, int side, int depth)
{
    if (sk->over)
        return;
    if (reverses(sk, s, side)) {
        half_reversed(sk, s, side, depth);
        return;
    }
    sv_seg fit;
    fit_offset(sk, s, side, &fit);
    double e = fit_error(sk, s, &fit, side);
    if (e > sk->tol && depth < MAX_DEPTH && seg_poly_len(s) > 1e-9 * sk->h) {
        sv_seg a, b;
        sv_seg_split(s, 0.5, &a, &b);
        half(sk, &a, side, depth + 1);
        half(sk, &b, side, depth + 1);
        return;
    }
    if (e > sk->tol)
        sk->missed++;
    emit_half(sk, s, &fit);
}

/* A side whose offset runs backwards: lobes meeting at the end normals' crossing. */
static void half_reversed(stroker *sk, const sv_seg *s, int side, int depth)
{
    if (sk->over)
        return;
    sv_pt o0 = offset_at(sk, s, 0, side), o1 = offset_at(sk, s, 1, side);
    sv_pt om = offset_at(sk, s, 0.5, side);
    double sag = sv_len(sv_sub(om, sv_scale(sv_add(o0, o1), 0.5)));
    if ((turning(s) > 4 * M_PI / 180 || sag > sk->tol) && depth < MAX_DEPTH &&
        seg_poly_len(s) > 1e-9 * sk->h) {
        sv_seg a, b;
        sv_seg_split(s, 0.5, &a, &b);
        half(sk, &a, side, depth + 1); /* pieces may stop reversing */
        half(sk, &b, side, depth + 1);
        return;
    }
    sv_pt x;
    sv_pt c0 = s->p[0], c1 = s->p[s->degree];
    if (!normals_meet(s, &x) || sv_len(sv_sub(x, c0)) > sk->h || sv_len(sv_sub(x, c1)) > sk->h) {
        sv_seg chord = {1, {o0, o1}, 1}; /* does not actually fold: a thin body half */
        emit_half(sk, s, &chord);
        return;
    }
    if (sag > sk->tol)
        sk->missed++;
    sv_path c;
    sv_path_init(&c);
    seg_to(&c, s); /* lobe on the curve's side */
    line_to(&c, x);
    line_to(&c, c0);
    emit(sk, &c);
    sv_path_init(&c); /* lobe beyond the centre of curvature */
    sv_path_move(&c, o0.x, o0.y);
    line_to(&c, o1);
    line_to(&c, x);
    line_to(&c, o0);
    emit(sk, &c);
}

/* If the conic is a circular arc: its centre and signed curvature (toward n). */
static bool circular(const sv_seg *s, sv_pt *ctr, double *kappa)
{
    if (s->degree != 2)
        return false;
    sv_pt l0 = sv_sub(s->p[1], s->p[0]), l1 = sv_sub(s->p[2], s->p[1]);
    sv_pt chord = sv_sub(s->p[2], s->p[0]);
    double a = sv_len(l0), b = sv_len(l1), c = sv_len(chord);
    if (!(a > 0 && b > 0 && c > 0) || fabs(a - b) > 1e-9 * a)
        return false;
    double cos_half = sv_dot(l0, chord) / (a * c); /* angle at P0 is half the arc */
    if (fabs(cos_half - s->w) > 1e-9)
        return false;
    double sin_half = sqrt(fmax(0, 1 - cos_half * cos_half));
    if (sin_half < 1e-12)
        return false;
    double r = a * cos_half / sin_half; /* leg = r tan(half) */
    sv_pt n0 = perp(unit(l0));
    double turn = sv_cross(l0, l1) > 0 ? 1 : -1; /* toward +n or -n */
    *ctr = sv_add(s->p[0], sv_scale(n0, turn * r));
    *kappa = turn / r;
    return true;
}

static void arc_body(stroker *sk, const sv_seg *s, sv_pt ctr, double kappa)
{
    for (int side = -1; side <= 1; side += 2) {
        double k = 1 - side * sk->h * kappa; /* homothety factor about the centre */
        sv_seg off = *s;
        for (int i = 0; i < 3; i++)
            off.p[i] = sv_add(ctr, sv_scale(sv_sub(s->p[i], ctr), k));
        if (k >= 0) {
            emit_half(sk, s, &off);
            continue;
        }
        /* folded: the pie slice and the reflected slice, both exact */
        sv_path c;
        sv_path_init(&c);
        seg_to(&c, s);
        line_to(&c, ctr);
        line_to(&c, s->p[0]);
        emit(sk, &c);
        sv_path_init(&c);
        seg_to(&c, &off);
        line_to(&c, ctr);
        line_to(&c, off.p[0]);
        emit(sk, &c);
    }
}

static void body(stroker *sk, const sv_seg *s, int depth)
{
    if (sk->over)
        return;
    if (s->degree == 1) {
        sv_pt n = sv_scale(perp(tangent_start(s)), sk->h);
        sv_path c;
        sv_path_init(&c);
        sv_pt a = sv_add(s->p[0], n), b = sv_add(s->p[1], n);
        sv_pt d = sv_sub(s->p[1], n), e = sv_sub(s->p[0], n);
        sv_path_move(&c, a.x, a.y);
        sv_path_line(&c, b.x, b.y);
        sv_path_line(&c, d.x, d.y);
        sv_path_line(&c, e.x, e.y);
        emit(sk, &c);
        return;
    }
    sv_pt ctr;
    double kappa;
    if (circular(s, &ctr, &kappa)) {
        arc_body(sk, s, ctr, kappa);
        return;
    }
    if (turning(s) > M_PI / 4 && depth < MAX_DEPTH && seg_poly_len(s) > 1e-9 * sk->h) {
        sv_seg a, b;
        sv_seg_split(s, 0.5, &a, &b);
        body(sk, &a, depth + 1);
        body(sk, &b, depth + 1);
        return;
    }
    half(sk, s, 1, depth);
    half(sk, s, -1, depth);
}

/* ------------------------------------------------------- joins, caps */

static void join(stroker *sk, sv_pt v, sv_pt ta, sv_pt tb)
{
    double cr = sv_cross(ta, tb), dt = sv_dot(ta, tb);
    double ang = atan2(cr, dt); /* turn from a to b */
    if (fabs(ang) < 1e-9)
        return;
    int out = cr > 0 ? -1 : 1; /* the outer side is away from the turn */
    if (cr == 0) /* a full reversal: both sides are outer; round covers, others have none */
        out = 1;
    sv_pt na = sv_scale(perp(ta), out * sk->h), nb = sv_scale(perp(tb), out * sk->h);
    sv_pt pa = sv_add(v, na), pb = sv_add(v, nb);
    sv_path c;
    sv_path_init(&c);
    sv_path_move(&c, v.x, v.y);
    sv_path_line(&c, pa.x, pa.y);
    if (sk->st->join == SV_JOIN_ROUND) {
        arc_to(&c, v, sk->h, unit(na), cr == 0 ? M_PI : ang);
        if (cr == 0) { /* the other half of the disc too */
            arc_to(&c, v, sk->h, unit(nb), M_PI);
        }
    } else {
        double cos_half = sqrt(fmax(0, (1 + sv_dot(unit(na), unit(nb))) / 2)); /* cos(phi/2) */
        if (sk->st->join == SV_JOIN_MITER && cos_half > 0 &&
            1 / cos_half <= sk->st->miter_limit) {
            sv_pt bis = unit(sv_add(na, nb));
            sv_pt tip = sv_add(v, sv_scale(bis, sk->h / cos_half));
            sv_path_line(&c, tip.x, tip.y);
        }
        sv_path_line(&c, pb.x, pb.y);
    }
    line_to(&c, v);
    emit(sk, &c);
}

/* Cap at p where the path leaves in direction t (pointing away from the stroke). */
static void cap(stroker *sk, sv_pt p, sv_pt t)
{
    if (sk->st->cap == SV_CAP_BUTT)
        return;
    sv_pt n = sv_scale(perp(t), sk->h), a = sv_add(p, n), b = sv_sub(p, n);
    sv_path c;
    sv_path_init(&c);
    sv_path_move(&c, a.x, a.y);
    if (sk->st->cap == SV_CAP_SQUARE) {
        sv_pt e = sv_scale(t, sk->h);
        sv_path_line(&c, a.x + e.x, a.y + e.y);
        sv_path_line(&c, b.x + e.x, b.y + e.y);
        sv_path_line(&c, b.x, b.y);
    } else {
        /* from +n through +t to -n: turning by -pi/2 twice relative to n */
        double dir = sv_cross(n, t) > 0 ? 1 : -1;
        arc_to(&c, p, sk->h, unit(n), dir * M_PI);
    }
    line_to(&c, a);
    emit(sk, &c);
}

static void dot(stroker *sk, sv_pt p)
{
    if (sk->st->cap == SV_CAP_BUTT)
        return;
    sv_path c;
    sv_path_init(&c);
    if (sk->st->cap == SV_CAP_ROUND) {
        sv_path_ellipse(&c, p.x, p.y, sk->h, sk->h);
    } else { /* SVG: a square aligned with the user space x axis */
        sv_path_move(&c, p.x - sk->h, p.y - sk->h);
        sv_path_line(&c, p.x + sk->h, p.y - sk->h);
        sv_path_line(&c, p.x + sk->h, p.y + sk->h);
        sv_path_line(&c, p.x - sk->h, p.y + sk->h);
    }
    emit(sk, &c);
}

int sv_stroke_path(const sv_path *in, const sv_stroke_style *st, sv_path *out)
{
    stroker sk = {st, st->width / 2, st->tolerance > 0 ? st->tolerance : 1e-3 * st->width, out, 0,
                  0, false};
    if (!(sk.h > 0))
        return 0;
    for (int i = 0; i < in->n && !sk.over; i++) {
        const sv_subpath *sp = &in->sub[i];
        sv_seg *seg = sv_xrealloc(NULL, (size_t)(sp->n + 1) * sizeof *seg);
        int n = 0;
        for (int k = 0; k < sp->n; k++) {
            const sv_seg *s = &sp->seg[k];
            bool point = true;
            for (int j = 1; j <= s->degree; j++)
                point &= same_pt(s->p[j], s->p[0]);
            if (!point)
                seg[n++] = *s;
        }
        if (n == 0) {
            if (sp->n > 0)
                dot(&sk, sp->seg[0].p[0]);
            free(seg);
            continue;
        }
        sv_pt first = seg[0].p[0], last = seg[n - 1].p[seg[n - 1].degree];
        if (sp->closed && !same_pt(first, last)) {
            sv_seg l = {1, {last, first}, 1};
            seg[n++] = l;
        }
        for (int k = 0; k < n && !sk.over; k++) {
            body(&sk, &seg[k], 0);
            if (k + 1 < n)
                join(&sk, seg[k].p[seg[k].degree], tangent_end(&seg[k]),
                     tangent_start(&seg[k + 1]));
        }
        if (sp->closed) {
            join(&sk, first, tangent_end(&seg[n - 1]), tangent_start(&seg[0]));
        } else {
            cap(&sk, first, sv_scale(tangent_start(&seg[0]), -1));
            cap(&sk, seg[n - 1].p[seg[n - 1].degree], tangent_end(&seg[n - 1]));
        }
        free(seg);
    }
    return sk.over ? -1 : sk.missed;
}
