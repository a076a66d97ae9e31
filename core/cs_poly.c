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

float cs__solve_level(const float *num, const float *den, int degree, float level, float lo,
                      float hi)
{
    float g[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int i = 0; i <= degree; i++)
        g[i] = num[i] - level * den[i];
    float flo = cs__horner(g, degree, lo);
    float fhi = cs__horner(g, degree, hi);
    if (flo == 0.0f)
        return lo;
    if (fhi == 0.0f)
        return hi;
    if ((flo < 0.0f) == (fhi < 0.0f))
        return cs__absf(flo) <= cs__absf(fhi) ? lo : hi;
    return illinois(g, degree, lo, hi, flo, fhi);
}
