/*
 * cs_poly.c - real roots of low-degree polynomials on an interval.
 *
 * The renderer needs two kinds of root: where a segment's y turns (to split
 * it into y-monotone pieces, once per frame), and where a monotone piece
 * meets a scanline (many times per line). Both are solved by bracketing:
 * the roots of a polynomial lie between consecutive roots of its derivative,
 * where it is monotone, so each sub-interval holds at most one root and a
 * sign change tells whether it does. The refinement is the Illinois variant
 * of regula falsi, which keeps the bracket (so it can never wander off the
 * piece) and converges superlinearly; its iteration count is capped, so the
 * time per root is bounded whatever the input. Closed-form cubic and
 * quartic solutions were avoided on purpose: they lose accuracy near double
 * roots and need cbrt/acos, which the core does not have.
 */
#include "cs_internal.h"

#define ILLINOIS_MAX_ITER 48

float cs__poly_eval(const float *c, int degree, float u)
{
    float v = c[degree];
    for (int i = degree - 1; i >= 0; i--)
        v = v * u + c[i];
    return v;
}

/* Root of c in [a, b] given fa = c(a), fb = c(b) of opposite signs. */
static float illinois(const float *c, int degree, float a, float b, float fa, float fb)
{
    int side = 0;
    for (int it = 0; it < ILLINOIS_MAX_ITER; it++) {
        float m = (a * fb - b * fa) / (fb - fa);
        if (!(m > a && m < b)) {
            m = 0.5f * (a + b);
            if (!(m > a && m < b))
                break; /* the bracket is two adjacent floats */
        }
        float fm = cs__horner(c, degree, m);
        if (fm == 0.0f)
            return m;
        if ((fm < 0.0f) == (fb < 0.0f)) {
            b = m;
            fb = fm;
            if (side == -1)
                fa *= 0.5f;
            side = -1;
        } else {
            a = m;
            fa = fm;
            if (side == 1)
                fb *= 0.5f;
            side = 1;
        }
        if (b - a <= 1.0e-7f)
            break;
    }
    float m = (a * fb - b * fa) / (fb - fa);
    return (m >= a && m <= b) ? m : 0.5f * (a + b);
}

int cs__poly_roots(const float *c, int degree, float lo, float hi, float *roots)
{
    while (degree > 0 && c[degree] == 0.0f)
        degree--;
    if (degree <= 0)
        return 0;
    if (degree == 1) {
        float r = -c[0] / c[1];
        if (r > lo && r < hi) {
            roots[0] = r;
            return 1;
        }
        return 0;
    }
    /* Critical points split (lo, hi) into monotone stretches. The recursion
     * depth is the degree (at most 4), never something the input sets. */
    float d[4], crit[4];
    for (int i = 1; i <= degree; i++)
        d[i - 1] = (float)i * c[i];
    int nc = cs__poly_roots(d, degree - 1, lo, hi, crit);
    int n = 0;
    float a = lo, fa = cs__poly_eval(c, degree, lo);
    for (int k = 0; k <= nc; k++) {
        float b = k < nc ? crit[k] : hi;
        float fb = cs__poly_eval(c, degree, b);
        if (fb == 0.0f) {
            if (b > lo && b < hi && (n == 0 || roots[n - 1] < b))
                roots[n++] = b;
        } else if (fa != 0.0f && (fa < 0.0f) != (fb < 0.0f)) {
            float r = illinois(c, degree, a, b, fa, fb);
            if (r > lo && r < hi && (n == 0 || roots[n - 1] < r))
                roots[n++] = r;
        }
        a = b;
        fa = fb;
    }
    return n;
}

/*
 * Root of g in [a, b] (fa, fb of opposite signs) by Newton's method from
 * `guess`, keeping the bracket: every evaluation moves one end of it, and a
 * step that would leave it (a flat or turning stretch, or a poor guess)
 * hands the narrowed bracket to the Illinois iteration instead.
 */
static float newton(const float *g, int degree, float a, float b, float fa, float fb, float guess)
{
    float u = guess;
    if (!(u > a && u < b))
        return illinois(g, degree, a, b, fa, fb);
    for (int it = 0; it < CS__NEWTON_MAX_ITER; it++) {
        float d, f = cs__horner_d(g, degree, u, &d);
        if (f == 0.0f)
            return u;
        if ((f < 0.0f) == (fa < 0.0f)) {
            a = u;
            fa = f;
        } else {
            b = u;
            fb = f;
        }
        float next = u - f / d;
        if (next == u) /* converged (see cs__solve_level_from) */
            return u;
        if (!(next > a && next < b))
            break;
        if (cs__absf(next - u) <= 1.0e-7f)
            return next;
        u = next;
    }
    return illinois(g, degree, a, b, fa, fb);
}

float cs__solve_level(const float *num, const float *den, int degree, float level, float lo,
                      float hi)
{
    float g[4];
    cs__level_poly(num, den, degree, level, g);
    float flo = cs__horner(g, degree, lo);
    float fhi = cs__horner(g, degree, hi);
    if (flo == 0.0f)
        return lo;
    if (fhi == 0.0f)
        return hi;
    if ((flo < 0.0f) == (fhi < 0.0f))
        return cs__absf(flo) <= cs__absf(fhi) ? lo : hi;
    if (degree == 1) /* a straight piece: the root in closed form */
        return cs__clampf(-g[0] / g[1], lo, hi);
    /* Newton from the regula falsi point, the first guess Illinois would make. */
    return newton(g, degree, lo, hi, flo, fhi, (lo * fhi - hi * flo) / (fhi - flo));
}

int cs__turns(const float *c, const float *w, int degree, float lo, float hi, float *roots)
{
#if defined(__GNUC__)
    /* A segment's degree is 1..3 (cs__check_contour): bounded so, the
     * loops below are peeled whole where the build peels (-O3). */
    if (degree < 1 || degree > 3)
        __builtin_unreachable();
#endif
    float n[5] = {0, 0, 0, 0, 0};
    for (int i = 0; i <= degree; i++)
        for (int j = 0; j <= degree; j++)
            if (i != j) /* then i + j - 1 lies in 0 .. 2 degree - 2 */
                n[i + j - 1] += (float)(i - j) * c[i] * w[j];
    return cs__poly_roots(n, 2 * degree - 2, lo, hi, roots);
}
