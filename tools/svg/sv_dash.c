/*
 * sv_dash.c - stroke-dasharray: a path cut into its dashes.
 *
 * Each subpath is walked by arc length, measured by Gauss-Legendre
 * quadrature of |c'(t)| over 32 pieces per segment and inverted by bisection
 * on that table, so dash ends land within ~1e-9 of the arc length at any
 * practical size. The dashes are exact pieces of the original segments
 * (de Casteljau splits), so a dashed stroke is still outlined from the true
 * curve. As in cairo and librsvg the pattern starts afresh on every
 * subpath, shifted by stroke-dashoffset; on a closed subpath a dash running
 * through the start point is one dash (joined there, not capped). An odd
 * list repeats to even length, as SVG says; lists with a negative value or a
 * zero sum are the caller's to reject (they mean a solid stroke). The
 * caller's limit on the number of dashes also bounds the walk: a pattern
 * far shorter than the path (or than a double's precision at its length)
 * stops there instead of exhausting memory.
 */
#include <math.h>

#include "sv_internal.h"

#define PIECES 32

typedef struct seg_len {
    double cum[PIECES + 1]; /* arc length from t = 0 to t = k / PIECES */
} seg_len;

static double speed(const sv_seg *s, double t)
{
    return sv_len(sv_seg_deriv(s, t));
}

static void measure(const sv_seg *s, seg_len *m)
{
    static const double gx[5] = {-0.9061798459386640, -0.5384693101056831, 0,
                                 0.5384693101056831, 0.9061798459386640};
    static const double gw[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                 0.4786286704993665, 0.2369268850561891};
    m->cum[0] = 0;
    for (int k = 0; k < PIECES; k++) {
        double a = (double)k / PIECES, h = 1.0 / PIECES, sum = 0;
        if (s->degree == 1) {
            sum = sv_len(sv_sub(s->p[1], s->p[0])) * h;
        } else {
            for (int i = 0; i < 5; i++)
                sum += gw[i] * speed(s, a + h * 0.5 * (gx[i] + 1));
            sum *= h * 0.5;
        }
        m->cum[k + 1] = m->cum[k] + sum;
    }
}

/* Parameter at arc length `l` from the segment start (0 <= l <= total). */
static double t_at_length(const sv_seg *s, const seg_len *m, double l)
{
    if (l <= 0)
        return 0;
    if (l >= m->cum[PIECES])
        return 1;
    int k = 0;
    while (k < PIECES - 1 && m->cum[k + 1] < l)
        k++;
    double lo = (double)k / PIECES, hi = (double)(k + 1) / PIECES;
    if (s->degree == 1) /* uniform speed */
        return lo + (hi - lo) * (l - m->cum[k]) / (m->cum[k + 1] - m->cum[k]);
    static const double gx[5] = {-0.9061798459386640, -0.5384693101056831, 0,
                                 0.5384693101056831, 0.9061798459386640};
    static const double gw[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                 0.4786286704993665, 0.2369268850561891};
    for (int it = 0; it < 50; it++) { /* bisection on the length within the piece */
        double mid = 0.5 * (lo + hi), from = (double)k / PIECES, sum = 0;
        for (int i = 0; i < 5; i++)
            sum += gw[i] * speed(s, from + (mid - from) * 0.5 * (gx[i] + 1));
        sum *= (mid - from) * 0.5;
        if (m->cum[k] + sum < l)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

typedef struct dasher {
    const double *dash;
    int n;
    int idx;       /* current entry of the pattern */
    double left;   /* length left in it */
    bool on;
} dasher;

static void dash_reset(dasher *d, double offset)
{
    double total = 0;
    for (int i = 0; i < d->n; i++)
        total += d->dash[i];
    offset = fmod(offset, total);
    if (offset < 0)
        offset += total;
    d->idx = 0;
    d->on = true;
    d->left = d->dash[0];
    while (offset > 0) {
        if (offset < d->left) {
            d->left -= offset;
            break;
        }
        offset -= d->left;
        d->idx = (d->idx + 1) % d->n;
        d->on = !d->on;
        d->left = d->dash[d->idx];
    }
}

int sv_path_dash(const sv_path *in, const double *dash_in, int ndash, double offset,
                 int max_dashes, sv_path *out)
{
    int dashes = 0;
    double dash[32];
    int n = 0;
    for (int r = 0; r < (ndash % 2 ? 2 : 1); r++)
        for (int i = 0; i < ndash && n < 32; i++)
            dash[n++] = dash_in[i];
    dasher d = {dash, n, 0, 0, true};
    for (int i = 0; i < in->n; i++) {
        const sv_subpath *sp = &in->sub[i];
        if (sp->n == 0)
            continue;
        sv_seg *segs = sv_xrealloc(NULL, (size_t)(sp->n + 1) * sizeof *segs);
        int ns = 0;
        for (int k = 0; k < sp->n; k++)
            segs[ns++] = sp->seg[k];
        sv_pt first = segs[0].p[0], last = segs[ns - 1].p[segs[ns - 1].degree];
        if (sp->closed && (first.x != last.x || first.y != last.y)) {
            sv_seg l = {1, {last, first}, 1};
            segs[ns++] = l;
        }
        dash_reset(&d, offset);
        bool started_on = d.on;
        int first_sub = out->n; /* the first dash of this subpath, if it starts on */
        bool pen = false;       /* a dash is open in out */
        for (int k = 0; k < ns; k++) {
            seg_len m;
            measure(&segs[k], &m);
            double total = m.cum[PIECES], pos = 0;
            while (pos < total) {
                double step = fmin(d.left, total - pos);
                if (d.on) {
                    double t0 = t_at_length(&segs[k], &m, pos);
                    double t1 = t_at_length(&segs[k], &m, pos + step);
                    sv_seg piece = t1 > t0 ? sv_seg_sub(&segs[k], t0, t1) : segs[k];
                    if (!(t1 > t0)) { /* a zero-length dash: a point (dot with round caps) */
                        sv_pt q = sv_seg_eval(&segs[k], t0);
                        piece.degree = 1;
                        piece.p[0] = piece.p[1] = q;
                    }
                    if (!pen) {
                        if (++dashes > max_dashes) {
                            free(segs);
                            return -1;
                        }
                        sv_path_move(out, piece.p[0].x, piece.p[0].y);
                        pen = true;
                    } else {
                        piece.p[0] = out->cur;
                    }
                    sv_path_add_seg(out, &piece);
                }
                pos += step;
                d.left -= step;
                if (d.left <= 1e-12 * (1 + total)) {
                    if (d.on)
                        pen = false; /* the dash ends */
                    d.idx = (d.idx + 1) % d.n;
                    d.on = !d.on;
                    d.left = d.dash[d.idx];
                }
            }
        }
        /* closed and "on" at both ends: the last dash continues into the first */
        if (sp->closed && pen && started_on && out->n - 1 > first_sub) {
            sv_subpath *a = &out->sub[out->n - 1], *b = &out->sub[first_sub];
            for (int k = 0; k < b->n; k++) {
                SV_GROW(a->seg, a->n, a->cap);
                a->seg[a->n++] = b->seg[k];
            }
            free(b->seg);
            memmove(&out->sub[first_sub], &out->sub[first_sub + 1],
                    (size_t)(out->n - first_sub - 1) * sizeof *out->sub);
            out->n--;
        }
        out->open_sub = false;
        free(segs);
    }
    return dashes;
}
