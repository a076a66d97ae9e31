/*
 * sv_geom.c - exact path geometry: affine maps, Bézier and conic segments,
 * SVG arcs, and the conversion of a path to closed NURBS contours.
 *
 * Nothing here approximates. Arcs become rational quadratics: an arc of
 * angle theta <= 90 degrees on the unit circle is the conic with end points
 * on the circle, middle point where the end tangents meet, and middle weight
 * cos(theta/2); an ellipse is an affine image of the circle and affine maps
 * act on control points without changing weights. Degree elevation works on
 * homogeneous points (w x, w y, w), which keeps rational segments exact.
 * A closed contour of K segments of degree d is the periodic NURBS with
 * knot intervals [1, 0 x (d-1)] per segment: every knot of multiplicity d
 * makes the curve pass through the shared on-curve point, and each span is
 * exactly the segment's Bézier.
 */
#include <math.h>

#include "sv_internal.h"

void *sv_xrealloc(void *p, size_t size)
{
    void *q = realloc(p, size ? size : 1);
    if (!q) {
        fprintf(stderr, "svg import: out of memory (%zu bytes)\n", size);
        exit(70);
    }
    return q;
}

char *sv_xstrndup(const char *s, size_t n)
{
    char *d = sv_xrealloc(NULL, n + 1);
    memcpy(d, s, n);
    d[n] = 0;
    return d;
}

char *sv_xstrdup(const char *s)
{
    return sv_xstrndup(s, strlen(s));
}

/* ------------------------------------------------------------- affine */

sv_affine sv_affine_identity(void)
{
    sv_affine m = {1, 0, 0, 1, 0, 0};
    return m;
}

sv_affine sv_affine_mul(sv_affine m1, sv_affine m2)
{
    sv_affine r;
    r.a = m1.a * m2.a + m1.c * m2.b;
    r.b = m1.b * m2.a + m1.d * m2.b;
    r.c = m1.a * m2.c + m1.c * m2.d;
    r.d = m1.b * m2.c + m1.d * m2.d;
    r.e = m1.a * m2.e + m1.c * m2.f + m1.e;
    r.f = m1.b * m2.e + m1.d * m2.f + m1.f;
    return r;
}

sv_pt sv_affine_apply(sv_affine m, sv_pt p)
{
    return sv_pt_make(m.a * p.x + m.c * p.y + m.e, m.b * p.x + m.d * p.y + m.f);
}

bool sv_affine_invert(sv_affine m, sv_affine *inv)
{
    double det = m.a * m.d - m.b * m.c;
    if (det == 0 || !isfinite(det))
        return false;
    inv->a = m.d / det;
    inv->b = -m.b / det;
    inv->c = -m.c / det;
    inv->d = m.a / det;
    inv->e = -(inv->a * m.e + inv->c * m.f);
    inv->f = -(inv->b * m.e + inv->d * m.f);
    return true;
}

double sv_affine_max_scale(sv_affine m)
{
    /* Singular values of [[a c][b d]]: sqrt of the eigenvalues of M^T M. */
    double p = m.a * m.a + m.b * m.b, q = m.c * m.c + m.d * m.d, r = m.a * m.c + m.b * m.d;
    double mean = 0.5 * (p + q), dev = sqrt(0.25 * (p - q) * (p - q) + r * r);
    return sqrt(mean + dev);
}

/* --------------------------------------------------------------- paths */

void sv_path_init(sv_path *p)
{
    memset(p, 0, sizeof *p);
}

void sv_path_free(sv_path *p)
{
    for (int i = 0; i < p->n; i++)
        free(p->sub[i].seg);
    free(p->sub);
    sv_path_init(p);
}

static sv_subpath *new_subpath(sv_path *p)
{
    SV_GROW(p->sub, p->n, p->cap);
    sv_subpath *s = &p->sub[p->n++];
    memset(s, 0, sizeof *s);
    p->open_sub = true;
    return s;
}

void sv_path_move(sv_path *p, double x, double y)
{
    p->cur = p->start = sv_pt_make(x, y);
    /* An empty subpath is reused: "M a M b" draws from b. */
    if (p->n > 0 && p->open_sub && p->sub[p->n - 1].n == 0)
        return;
    p->open_sub = false;
}

void sv_path_add_seg(sv_path *p, const sv_seg *s)
{
    if (!p->open_sub || p->n == 0) {
        new_subpath(p);
        p->start = s->p[0];
    }
    sv_subpath *sp = &p->sub[p->n - 1];
    SV_GROW(sp->seg, sp->n, sp->cap);
    sp->seg[sp->n++] = *s;
    p->cur = s->p[s->degree];
}

void sv_path_line(sv_path *p, double x, double y)
{
    sv_seg s = {1, {p->cur, {x, y}}, 1};
    sv_path_add_seg(p, &s);
}

void sv_path_quad(sv_path *p, double x1, double y1, double x, double y)
{
    sv_seg s = {2, {p->cur, {x1, y1}, {x, y}}, 1};
    sv_path_add_seg(p, &s);
}

void sv_path_conic(sv_path *p, double x1, double y1, double w, double x, double y)
{
    sv_seg s = {2, {p->cur, {x1, y1}, {x, y}}, w};
    sv_path_add_seg(p, &s);
}

void sv_path_cubic(sv_path *p, double x1, double y1, double x2, double y2, double x, double y)
{
    sv_seg s = {3, {p->cur, {x1, y1}, {x2, y2}, {x, y}}, 1};
    sv_path_add_seg(p, &s);
}

void sv_path_close(sv_path *p)
{
    if (p->n > 0 && p->open_sub) {
        sv_subpath *sp = &p->sub[p->n - 1];
        if (sp->n > 0) {
            sp->closed = true;
            p->cur = p->start;
        }
    }
    p->open_sub = false; /* a segment after Z starts a new subpath at the start point */
}

void sv_path_append(sv_path *dst, const sv_path *src)
{
    for (int i = 0; i < src->n; i++) {
        const sv_subpath *s = &src->sub[i];
        sv_subpath *d = new_subpath(dst);
        d->closed = s->closed;
        for (int k = 0; k < s->n; k++) {
            SV_GROW(d->seg, d->n, d->cap);
            d->seg[d->n++] = s->seg[k];
        }
    }
    dst->open_sub = false;
}

void sv_path_transform(sv_path *p, sv_affine m)
{
    for (int i = 0; i < p->n; i++)
        for (int k = 0; k < p->sub[i].n; k++) {
            sv_seg *s = &p->sub[i].seg[k];
            for (int j = 0; j <= s->degree; j++)
                s->p[j] = sv_affine_apply(m, s->p[j]);
        }
    p->cur = sv_affine_apply(m, p->cur);
    p->start = sv_affine_apply(m, p->start);
}

/* Conic pieces of the unit-circle arc from angle a, sweep da, mapped by m. */
static void arc_pieces(sv_path *p, sv_affine m, double a, double da, sv_pt end)
{
    int n = (int)ceil(fabs(da) / (M_PI / 2) - 1e-9);
    if (n < 1)
        n = 1;
    double step = da / n, w = cos(step / 2);
    for (int i = 0; i < n; i++) {
        double a0 = a + step * i, a1 = a0 + step, am = 0.5 * (a0 + a1);
        sv_pt mid = sv_affine_apply(m, sv_pt_make(cos(am) / w, sin(am) / w));
        sv_pt to = i + 1 == n ? end : sv_affine_apply(m, sv_pt_make(cos(a1), sin(a1)));
        sv_path_conic(p, mid.x, mid.y, w, to.x, to.y);
    }
}

static double vec_angle(double ux, double uy, double vx, double vy)
{
    return atan2(ux * vy - uy * vx, ux * vx + uy * vy);
}

void sv_path_arc(sv_path *p, double rx, double ry, double rot_deg, bool large_arc, bool sweep,
                 double x2, double y2)
{
    double x1 = p->cur.x, y1 = p->cur.y;
    if (x1 == x2 && y1 == y2)
        return; /* F.6.2: an arc to the same point is omitted */
    rx = fabs(rx);
    ry = fabs(ry);
    if (rx == 0 || ry == 0) {
        sv_path_line(p, x2, y2);
        return;
    }
    double phi = rot_deg * M_PI / 180, cs = cos(phi), sn = sin(phi);
    double dx2 = 0.5 * (x1 - x2), dy2 = 0.5 * (y1 - y2);
    double x1p = cs * dx2 + sn * dy2, y1p = -sn * dx2 + cs * dy2;
    double lambda = x1p * x1p / (rx * rx) + y1p * y1p / (ry * ry);
    if (lambda > 1) { /* F.6.6: radii too small are scaled up */
        rx *= sqrt(lambda);
        ry *= sqrt(lambda);
    }
    double num = rx * rx * ry * ry - rx * rx * y1p * y1p - ry * ry * x1p * x1p;
    double den = rx * rx * y1p * y1p + ry * ry * x1p * x1p;
    double coef = den > 0 && num > 0 ? sqrt(num / den) : 0;
    if (large_arc == sweep)
        coef = -coef;
    double cxp = coef * rx * y1p / ry, cyp = -coef * ry * x1p / rx;
    double cx = cs * cxp - sn * cyp + 0.5 * (x1 + x2), cy = sn * cxp + cs * cyp + 0.5 * (y1 + y2);
    double ux = (x1p - cxp) / rx, uy = (y1p - cyp) / ry;
    double vx = (-x1p - cxp) / rx, vy = (-y1p - cyp) / ry;
    double th1 = vec_angle(1, 0, ux, uy), dth = vec_angle(ux, uy, vx, vy);
    if (!sweep && dth > 0)
        dth -= 2 * M_PI;
    else if (sweep && dth < 0)
        dth += 2 * M_PI;
    sv_affine m = {cs * rx, sn * rx, -sn * ry, cs * ry, cx, cy};
    arc_pieces(p, m, th1, dth, sv_pt_make(x2, y2));
}

void sv_path_ellipse(sv_path *p, double cx, double cy, double rx, double ry)
{
    sv_affine m = {rx, 0, 0, ry, cx, cy};
    sv_path_move(p, cx + rx, cy);
    arc_pieces(p, m, 0, 2 * M_PI, sv_pt_make(cx + rx, cy));
    sv_path_close(p);
}

/* ------------------------------------------------------------ segments */

void sv_seg_homogeneous(const sv_seg *s, double h[4][3])
{
    for (int i = 0; i <= s->degree; i++) {
        double w = (s->degree == 2 && i == 1) ? s->w : 1.0;
        h[i][0] = w * s->p[i].x;
        h[i][1] = w * s->p[i].y;
        h[i][2] = w;
    }
}

void sv_seg_elevate(const sv_seg *s, int degree, double h[4][3])
{
    double g[4][3];
    sv_seg_homogeneous(s, g);
    int d = s->degree;
    memcpy(h, g, sizeof g);
    while (d < degree) { /* Q_i = i/(d+1) P_{i-1} + (1 - i/(d+1)) P_i */
        double q[4][3];
        for (int i = 0; i <= d + 1; i++)
            for (int k = 0; k < 3; k++) {
                double a = (double)i / (d + 1);
                q[i][k] = (i > 0 ? a * h[i - 1][k] : 0) + (i <= d ? (1 - a) * h[i][k] : 0);
            }
        memcpy(h, q, sizeof q);
        d++;
    }
}

/* de Casteljau on homogeneous points; fills left/right polygons if asked. */
static void casteljau(double h[4][3], int d, double t, double left[4][3], double right[4][3])
{
    double w[4][3];
    memcpy(w, h, sizeof w);
    for (int k = 0; k < 3; k++) {
        if (left)
            left[0][k] = w[0][k];
        if (right)
            right[d][k] = w[d][k];
    }
    for (int r = 1; r <= d; r++) {
        for (int i = 0; i <= d - r; i++)
            for (int k = 0; k < 3; k++)
                w[i][k] = (1 - t) * w[i][k] + t * w[i + 1][k];
        for (int k = 0; k < 3; k++) {
            if (left)
                left[r][k] = w[0][k];
            if (right)
                right[d - r][k] = w[d - r][k];
        }
    }
}

sv_pt sv_seg_eval(const sv_seg *s, double t)
{
    double h[4][3], l[4][3];
    sv_seg_homogeneous(s, h);
    casteljau(h, s->degree, t, l, NULL);
    double *q = l[s->degree];
    return sv_pt_make(q[0] / q[2], q[1] / q[2]);
}

sv_pt sv_seg_deriv(const sv_seg *s, double t)
{
    double h[4][3], d[4][3];
    int n = s->degree;
    sv_seg_homogeneous(s, h);
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++)
            d[i][k] = n * (h[i + 1][k] - h[i][k]);
    double l[4][3], ld[4][3];
    casteljau(h, n, t, l, NULL);
    double P[3] = {l[n][0], l[n][1], l[n][2]}, D[3] = {0, 0, 0};
    if (n > 1) {
        casteljau(d, n - 1, t, ld, NULL);
        for (int k = 0; k < 3; k++)
            D[k] = ld[n - 1][k];
    } else {
        for (int k = 0; k < 3; k++)
            D[k] = d[0][k];
    }
    /* (P/W)' = (P' W - P W') / W^2 */
    double W = P[2];
    return sv_pt_make((D[0] * W - P[0] * D[2]) / (W * W), (D[1] * W - P[1] * D[2]) / (W * W));
}

void sv_seg_derivs(const sv_seg *s, double t, sv_pt *c, sv_pt *c1, sv_pt *c2)
{
    /* Homogeneous P(t) and its first two derivatives from the hodographs. */
    double h[4][3], d1[4][3], d2[4][3], l[4][3];
    int n = s->degree;
    sv_seg_homogeneous(s, h);
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++)
            d1[i][k] = n * (h[i + 1][k] - h[i][k]);
    for (int i = 0; i + 1 < n; i++)
        for (int k = 0; k < 3; k++)
            d2[i][k] = (n - 1) * (d1[i + 1][k] - d1[i][k]);
    double P[3], D[3] = {0, 0, 0}, E[3] = {0, 0, 0};
    casteljau(h, n, t, l, NULL);
    for (int k = 0; k < 3; k++)
        P[k] = l[n][k];
    if (n >= 1) {
        casteljau(d1, n - 1, t, l, NULL);
        for (int k = 0; k < 3; k++)
            D[k] = l[n - 1][k];
    }
    if (n >= 2) {
        casteljau(d2, n - 2, t, l, NULL);
        for (int k = 0; k < 3; k++)
            E[k] = l[n - 2][k];
    }
    /* C = P/W, C' = (P' - C W')/W, C'' = (P'' - 2 C' W' - C W'')/W */
    double W = P[2];
    sv_pt C = {P[0] / W, P[1] / W};
    sv_pt C1 = {(D[0] - C.x * D[2]) / W, (D[1] - C.y * D[2]) / W};
    sv_pt C2 = {(E[0] - 2 * C1.x * D[2] - C.x * E[2]) / W, (E[1] - 2 * C1.y * D[2] - C.y * E[2]) / W};
    if (c)
        *c = C;
    if (c1)
        *c1 = C1;
    if (c2)
        *c2 = C2;
}

/* Back from homogeneous points to a standard-form segment (end weights 1). */
static void from_homogeneous(double h[4][3], int d, sv_seg *s)
{
    s->degree = d;
    s->w = 1;
    if (d == 2) {
        /* Reparametrise so both end weights are 1: w1' = w1 / sqrt(w0 w2). */
        s->w = h[1][2] / sqrt(h[0][2] * h[2][2]);
    }
    for (int i = 0; i <= d; i++)
        s->p[i] = sv_pt_make(h[i][0] / h[i][2], h[i][1] / h[i][2]);
}

void sv_seg_split(const sv_seg *s, double t, sv_seg *a, sv_seg *b)
{
    double h[4][3], l[4][3], r[4][3];
    sv_seg_homogeneous(s, h);
    casteljau(h, s->degree, t, l, r);
    sv_seg sa, sb;
    from_homogeneous(l, s->degree, &sa);
    from_homogeneous(r, s->degree, &sb);
    /* The split point is shared exactly. */
    sb.p[0] = sa.p[s->degree];
    if (a)
        *a = sa;
    if (b)
        *b = sb;
}

sv_seg sv_seg_sub(const sv_seg *s, double t0, double t1)
{
    /* Homogeneous splits keep u = t / t1 linear; only the result is renormalised. */
    double h[4][3], l[4][3], r[4][3];
    sv_seg_homogeneous(s, h);
    casteljau(h, s->degree, t1, l, NULL);
    double u = t1 > 0 ? t0 / t1 : 0;
    casteljau(l, s->degree, u, NULL, r);
    sv_seg out;
    from_homogeneous(r, s->degree, &out);
    return out;
}

void sv_seg_reverse(sv_seg *s)
{
    for (int i = 0, j = s->degree; i < j; i++, j--) {
        sv_pt t = s->p[i];
        s->p[i] = s->p[j];
        s->p[j] = t;
    }
}

void sv_path_bbox(const sv_path *p, double box[4])
{
    box[0] = box[1] = INFINITY;
    box[2] = box[3] = -INFINITY;
    for (int i = 0; i < p->n; i++)
        for (int k = 0; k < p->sub[i].n; k++) {
            const sv_seg *s = &p->sub[i].seg[k];
            for (int j = 0; j <= s->degree; j++) {
                box[0] = fmin(box[0], s->p[j].x);
                box[1] = fmin(box[1], s->p[j].y);
                box[2] = fmax(box[2], s->p[j].x);
                box[3] = fmax(box[3], s->p[j].y);
            }
        }
}

/* --------------------------------------------------------- area, winding */

double sv_subpath_area(const sv_subpath *s)
{
    static const double gx[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                 -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                 0.7966664774136267,  0.9602898564975363};
    static const double gw[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                 0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                 0.2223810344533745, 0.1012285362903763};
    double a = 0;
    for (int k = 0; k < s->n; k++) {
        const sv_seg *g = &s->seg[k];
        if (g->degree == 1) {
            a += sv_cross(g->p[0], g->p[1]);
            continue;
        }
        for (int i = 0; i < 8; i++) {
            double t = 0.5 * (gx[i] + 1);
            sv_pt p = sv_seg_eval(g, t), d = sv_seg_deriv(g, t);
            a += 0.5 * gw[i] * sv_cross(p, d);
        }
    }
    if (s->n > 0) { /* closing line */
        sv_pt e = s->seg[s->n - 1].p[s->seg[s->n - 1].degree];
        a += sv_cross(e, s->seg[0].p[0]);
    }
    return 0.5 * a;
}

void sv_subpath_flatten(const sv_subpath *s, int per_seg, sv_pt **pts, int *n)
{
    int cap = 0;
    *pts = NULL;
    *n = 0;
    for (int k = 0; k < s->n; k++) {
        const sv_seg *g = &s->seg[k];
        int m = g->degree == 1 ? 1 : per_seg;
        for (int i = 0; i < m; i++) {
            SV_GROW(*pts, *n, cap);
            (*pts)[(*n)++] = i == 0 ? g->p[0] : sv_seg_eval(g, (double)i / m);
        }
    }
    if (s->n > 0) { /* the end of an unclosed subpath; the polygon closes itself */
        sv_pt e = s->seg[s->n - 1].p[s->seg[s->n - 1].degree];
        if (e.x != s->seg[0].p[0].x || e.y != s->seg[0].p[0].y) {
            SV_GROW(*pts, *n, cap);
            (*pts)[(*n)++] = e;
        }
    }
}

int sv_subpath_winding(const sv_subpath *s, sv_pt q)
{
    sv_pt *v;
    int n, wn = 0;
    sv_subpath_flatten(s, 32, &v, &n);
    for (int i = 0; i < n; i++) {
        sv_pt a = v[i], b = v[(i + 1) % n];
        if (a.y <= q.y) {
            if (b.y > q.y && sv_cross(sv_sub(b, a), sv_sub(q, a)) > 0)
                wn++;
        } else if (b.y <= q.y && sv_cross(sv_sub(b, a), sv_sub(q, a)) < 0) {
            wn--;
        }
    }
    free(v);
    return wn;
}

/* ------------------------------------------------------------ contours */

void sv_contour_free(sv_contour *c)
{
    free(c->pts);
    free(c->intervals);
    c->pts = c->intervals = NULL;
    c->count = 0;
}

static bool seg_is_point(const sv_seg *s)
{
    for (int i = 1; i <= s->degree; i++)
        if (s->p[i].x != s->p[0].x || s->p[i].y != s->p[0].y)
            return false;
    return true;
}

/* Whether every control point lies on one line: such a contour has no area. */
static bool collinear(const sv_seg *segs, int k)
{
    sv_pt o = segs[0].p[0], far = o;
    double best = 0;
    for (int j = 0; j < k; j++)
        for (int m = 0; m <= segs[j].degree; m++) {
            double d = sv_len(sv_sub(segs[j].p[m], o));
            if (d > best) {
                best = d;
                far = segs[j].p[m];
            }
        }
    sv_pt dir = sv_sub(far, o);
    for (int j = 0; j < k; j++)
        for (int m = 0; m <= segs[j].degree; m++)
            if (fabs(sv_cross(sv_sub(segs[j].p[m], o), dir)) > 1e-12 * best * best)
                return false;
    return true;
}

void sv_path_to_contours(const sv_path *p, sv_contour **out, int *n)
{
    for (int i = 0; i < p->n; i++) {
        const sv_subpath *sp = &p->sub[i];
        /* Segments worth keeping, plus the closing line. */
        sv_seg *segs = sv_xrealloc(NULL, (size_t)(sp->n + 2) * sizeof *segs);
        int k = 0, degree = 1;
        for (int j = 0; j < sp->n; j++) {
            if (seg_is_point(&sp->seg[j]))
                continue;
            segs[k] = sp->seg[j];
            degree = segs[k].degree > degree ? segs[k].degree : degree;
            k++;
        }
        if (k == 0 || collinear(segs, k)) {
            free(segs);
            continue; /* no area: nothing to fill */
        }
        sv_pt first = segs[0].p[0], last = segs[k - 1].p[segs[k - 1].degree];
        if (first.x != last.x || first.y != last.y) {
            sv_seg close = {1, {last, first}, 1};
            segs[k++] = close;
        }
        if (k == 1) { /* one segment gives too few control points: halve it */
            sv_seg_split(&segs[0], 0.5, &segs[0], &segs[1]);
            k = 2;
        }
        *out = sv_xrealloc(*out, (size_t)(*n + 1) * sizeof **out);
        sv_contour *c = &(*out)[(*n)++];
        c->degree = degree;
        c->count = k * degree;
        c->pts = sv_xrealloc(NULL, (size_t)c->count * 3 * sizeof(double));
        c->intervals = sv_xrealloc(NULL, (size_t)c->count * sizeof(double));
        for (int j = 0; j < k; j++) {
            double h[4][3];
            sv_seg_elevate(&segs[j], degree, h);
            for (int m = 0; m < degree; m++) {
                double *q = &c->pts[3 * (j * degree + m)];
                q[0] = h[m][0] / h[m][2];
                q[1] = h[m][1] / h[m][2];
                q[2] = h[m][2];
                c->intervals[j * degree + m] = m == 0 ? 1.0 : 0.0;
            }
        }
        free(segs);
    }
}
