/*
 * outline.c - a scene's NURBS contours as the Bezier paths cairo and
 * FreeType draw.
 *
 * A user who picks cairo or FreeType instead of celscan has to turn the
 * scene's closed periodic NURBS into Bezier paths first; this file is that
 * conversion, done independently of the core and in double precision. Each
 * knot span of non-zero length becomes one Bezier segment by blossoming: the
 * span's p+1 homogeneous control points go through de Boor's triangle with
 * the knots t(j) and t(j+1) as arguments, which yields the Bernstein control
 * points of the span exactly (up to double rounding). Where the resulting
 * weights are all equal the span is polynomial and is emitted as a line,
 * quadratic or cubic without any approximation. Where they differ (circles,
 * weighted NURBS) neither library has a rational curve, so the span is
 * replaced by cubic Hermite pieces (end points and end tangents of the true
 * curve), halved until no piece is farther than OL_RATIONAL_TOL device pixels
 * from the curve at the same parameter (checked at seven parameters per
 * piece; the distance at equal parameter bounds the true distance from
 * above). This is the conversion a peer needs, so the error it leaves counts
 * against the peer in the accuracy table, as it would in use.
 *
 * Paint colours map the beta model onto premultiplied alpha: with T the
 * region's transmittance, alpha = 1 - mean(T) and the straight colour is
 * E / alpha, sRGB-encoded. For the benchmark scenes (clear medium, unit
 * lights) that is exact; for others (the signage demo's gels) it is a close
 * stand-in, which costs the peers the same time.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

#define MAX_DEGREE 3

static double srgb_encode(double v)
{
    if (!(v > 0.0))
        return 0.0;
    if (v >= 1.0)
        return 1.0;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

void ol_cel_device_map(const cs_scene *scene, int ci, int width, int height, double m[6])
{
    const cs_affine *t = &scene->cels[ci].transform;
    double sx = (double)width / scene->canvas_w, sy = (double)height / scene->canvas_h;
    m[0] = t->a * sx;
    m[1] = t->b * sy;
    m[2] = t->c * sx;
    m[3] = t->d * sy;
    m[4] = t->e * sx;
    m[5] = t->f * sy;
}

static int push_cmd(ol_set *set, int op, const double *p)
{
    if (set->cmd_count == set->cmd_cap) {
        int cap = set->cmd_cap ? 2 * set->cmd_cap : 4096;
        ol_cmd *c = realloc(set->cmds, (size_t)cap * sizeof *c);
        if (!c)
            return -1;
        set->cmds = c;
        set->cmd_cap = cap;
    }
    ol_cmd *c = &set->cmds[set->cmd_count++];
    c->op = op;
    memcpy(c->p, p, sizeof c->p);
    return 0;
}

/* A rational Bezier span in homogeneous form: (w x, w y, w) per control point. */
typedef struct hbez {
    int p;
    double q[MAX_DEGREE + 1][3];
} hbez;

/* Point and first derivative of the rational curve at u. */
static void hbez_eval(const hbez *b, double u, double pt[2], double d[2])
{
    double t[MAX_DEGREE + 1][3];
    memcpy(t, b->q, sizeof t);
    double dh[3] = {0, 0, 0};
    for (int level = b->p; level > 0; level--) {
        if (level == 1)
            for (int k = 0; k < 3; k++)
                dh[k] = (double)b->p * (t[1][k] - t[0][k]);
        for (int i = 0; i < level; i++)
            for (int k = 0; k < 3; k++)
                t[i][k] = (1.0 - u) * t[i][k] + u * t[i + 1][k];
    }
    double w = t[0][2];
    pt[0] = t[0][0] / w;
    pt[1] = t[0][1] / w;
    d[0] = (dh[0] - pt[0] * dh[2]) / w;
    d[1] = (dh[1] - pt[1] * dh[2]) / w;
}

/* Cubic Hermite pieces for the rational span on [ua, ub], within OL_RATIONAL_TOL. */
static int approx_rational(ol_set *set, const hbez *b, double ua, double ub, int depth)
{
    double p0[2], d0[2], p3[2], d3[2];
    hbez_eval(b, ua, p0, d0);
    hbez_eval(b, ub, p3, d3);
    double h = (ub - ua) / 3.0;
    double c[6] = {p0[0] + h * d0[0], p0[1] + h * d0[1], p3[0] - h * d3[0], p3[1] - h * d3[1],
                   p3[0], p3[1]};
    bool ok = true;
    for (int k = 1; k < 8 && ok && depth < 20; k++) {
        double s = k / 8.0, r = 1.0 - s, pt[2], d[2];
        hbez_eval(b, ua + s * (ub - ua), pt, d);
        double x = r * r * r * p0[0] + 3 * r * r * s * c[0] + 3 * r * s * s * c[2] + s * s * s * c[4];
        double y = r * r * r * p0[1] + 3 * r * r * s * c[1] + 3 * r * s * s * c[3] + s * s * s * c[5];
        ok = hypot(x - pt[0], y - pt[1]) <= OL_RATIONAL_TOL;
    }
    if (!ok) {
        double um = 0.5 * (ua + ub);
        return approx_rational(set, b, ua, um, depth + 1) || approx_rational(set, b, um, ub, depth + 1);
    }
    set->approx_cubics++;
    return push_cmd(set, OL_CUBIC, c);
}

int ol_add_contour(ol_set *set, const cs_scene *scene, int contour, const double m[6],
                   ol_contour *out)
{
    const cs_contour *c = &scene->contours[contour];
    const cs_point *pts = &scene->points[c->first_point];
    const float *iv = &scene->intervals[c->first_point];
    int n = c->point_count, p = c->degree;
    /* Knots t(k) for k in [-p-1, n+p+1], stored at k + p + 1. */
    int nk = n + 2 * p + 3;
    double *t = malloc((size_t)nk * sizeof *t);
    double (*h)[3] = malloc((size_t)n * sizeof *h);
    if (!t || !h) {
        free(t);
        free(h);
        return -1;
    }
    int off = p + 1;
    t[off] = 0.0;
    for (int k = 1; k <= n + p + 1; k++)
        t[off + k] = t[off + k - 1] + iv[(k - 1) % n];
    for (int k = -1; k >= -p - 1; k--)
        t[off + k] = t[off + k + 1] - iv[((k % n) + n) % n];
    for (int k = 0; k < n; k++) {
        double x = pts[k].x, y = pts[k].y, w = pts[k].w;
        double dx = m[0] * x + m[2] * y + m[4], dy = m[1] * x + m[3] * y + m[5];
        h[k][0] = w * dx;
        h[k][1] = w * dy;
        h[k][2] = w;
    }
    out->first = set->cmd_count;
    out->scene_contour = contour;
    bool started = false;
    int rc = 0;
    for (int j = 0; j < n && rc == 0; j++) {
        if (!(iv[j] > 0.0f))
            continue;
        hbez b = {.p = p};
        /* Bezier point i is the blossom at (t(j+1) x i, t(j) x (p-i)). */
        for (int i = 0; i <= p; i++) {
            double d[MAX_DEGREE + 1][3];
            for (int r = 0; r <= p; r++) {
                int k = j - p + r;
                memcpy(d[r], h[((k % n) + n) % n], sizeof d[r]);
            }
            for (int level = 1; level <= p; level++) {
                double s = level <= i ? t[off + j + 1] : t[off + j];
                for (int r = p; r >= level; r--) {
                    int k = j - p + r;
                    double a = (s - t[off + k]) / (t[off + k + p + 1 - level] - t[off + k]);
                    for (int q = 0; q < 3; q++)
                        d[r][q] = (1.0 - a) * d[r - 1][q] + a * d[r][q];
                }
            }
            memcpy(b.q[i], d[p], sizeof b.q[i]);
        }
        if (!started) {
            out->x0 = b.q[0][0] / b.q[0][2];
            out->y0 = b.q[0][1] / b.q[0][2];
            started = true;
        }
        bool rational = false;
        for (int i = 1; i <= p; i++)
            rational |= fabs(b.q[i][2] - b.q[0][2]) > 1e-12 * fabs(b.q[0][2]);
        double e[6] = {0};
        for (int i = 1; i <= p; i++) {
            e[2 * (i - 1)] = b.q[i][0] / b.q[i][2];
            e[2 * (i - 1) + 1] = b.q[i][1] / b.q[i][2];
        }
        if (p == 1 || !rational) {
            rc = push_cmd(set, p, e); /* OL_LINE, OL_QUAD, OL_CUBIC are the degrees */
        } else {
            set->rational_segments++;
            rc = approx_rational(set, &b, 0.0, 1.0, 0);
        }
    }
    free(t);
    free(h);
    out->count = set->cmd_count - out->first;
    return rc;
}

static void bounds_add(ol_region *r, double x, double y)
{
    if (x < r->bx0)
        r->bx0 = x;
    if (x > r->bx1)
        r->bx1 = x;
    if (y < r->by0)
        r->by0 = y;
    if (y > r->by1)
        r->by1 = y;
}

int ol_build(ol_set *set, const cs_scene *scene, int width, int height)
{
    memset(set, 0, sizeof *set);
    set->width = width;
    set->height = height;
    set->regions = calloc(scene->region_count + 1, sizeof *set->regions);
    set->contours = calloc(scene->contour_count + 1, sizeof *set->contours);
    if (!set->regions || !set->contours)
        return -1;
    for (int k = 0; k < 3; k++) {
        double bg = scene->has_background ? (double)scene->background[k] * scene->stack_front[k]
                                          : scene->stack_back[k];
        set->background[k] = srgb_encode(bg);
    }
    set->background[3] = 1.0;
    int skipped = 0;
    for (uint32_t ci = 0; ci < scene->cel_count; ci++) {
        const cs_cel *cel = &scene->cels[ci];
        const float *front = cel->has_front ? cel->front : scene->stack_front;
        double m[6];
        ol_cel_device_map(scene, (int)ci, width, height, m);
        for (uint32_t ri = cel->first_region; ri < cel->first_region + cel->region_count; ri++) {
            const cs_region *reg = &scene->regions[ri];
            if (reg->csg_len) {
                skipped++;
                continue;
            }
            ol_region *r = &set->regions[set->region_count++];
            r->first = set->contour_count;
            r->scene_region = (int)ri;
            r->cel = (int)ci;
            r->evenodd = reg->fill_rule == CS_FILL_EVENODD;
            const cs_paint *pt = &reg->paint;
            double E[3], T = 0.0;
            for (int k = 0; k < 3; k++) {
                double clear = (1.0 - pt->beta) * pt->medium[k];
                E[k] = pt->beta * pt->pigment[k] * front[k] + clear * cel->back[k];
                T += clear / 3.0;
            }
            double alpha = 1.0 - T;
            for (int k = 0; k < 3; k++)
                r->rgba[k] = alpha > 1e-6 ? srgb_encode(E[k] / alpha) : 0.0;
            r->rgba[3] = alpha;
            r->bx0 = r->by0 = INFINITY;
            r->bx1 = r->by1 = -INFINITY;
            for (uint32_t k = 0; k < reg->contour_count; k++) {
                ol_contour *c = &set->contours[set->contour_count++];
                if (ol_add_contour(set, scene, (int)(reg->first_contour + k), m, c) != 0)
                    return -1;
                bounds_add(r, c->x0, c->y0);
                for (int i = c->first; i < c->first + c->count; i++)
                    for (int q = 0; q < set->cmds[i].op; q++)
                        bounds_add(r, set->cmds[i].p[2 * q], set->cmds[i].p[2 * q + 1]);
            }
            r->count = set->contour_count - r->first;
        }
    }
    return skipped;
}

void ol_free(ol_set *set)
{
    free(set->regions);
    free(set->contours);
    free(set->cmds);
    memset(set, 0, sizeof *set);
}
