/*
 * cs_paint.c - functional paints: gradients and colour maps, per pixel.
 *
 * A paint field (pigment, medium or beta) may be a function of position.
 * Its geometry is given in the cel's canvas units; once per frame it is
 * compiled against the cel's device-to-canvas map into one affine map from
 * device pixels straight to the function's own space, so that evaluating a
 * pixel costs a few multiply-adds, a stop search and a lerp, and needs no
 * memory beyond the six floats per function the workspace holds.
 *
 *   LINEAR  t = projection onto p0 -> p1, scaled so p1 is at 1.
 *   RADIAL  in the frame where the circle is the unit circle centred on
 *           the origin and the focal point is f, t is where the point lies
 *           on the family of circles centred f (1 - t) with radius t (SVG's
 *           focal radial gradient): the positive root of
 *           (1 - |f|^2) t^2 - 2 (d.f) t - |d|^2 = 0 with d = u - f.
 *   MAP     (s, t) are the point's coordinates in the map's unit square;
 *           values are bilinear between the grid nodes. A 2x2 map is a
 *           four-corner colour patch, the paper's "colouring mapped from a
 *           colour space" in its smallest form.
 *
 * Stops interpolate in whichever space the frame composites in: linear
 * light by default, sRGB-encoded values under CS_BLEND_SRGB (as SVG does).
 */
#include "cs_internal.h"

void cs__func_compile(const cs_paint_func *fn, const cs_affine *inv, float xf[6])
{
    const float *g = fn->geom;
    /* q = inv(p): qx = a px + c py + e, qy = b px + d py + f */
    float a = inv->a, b = inv->b, c = inv->c, d = inv->d, e = inv->e, f = inv->f;
    switch (fn->kind) {
    case CS_FUNC_LINEAR: {
        float gx = g[2] - g[0], gy = g[3] - g[1];
        float k = 1.0f / (gx * gx + gy * gy);
        gx *= k;
        gy *= k;
        xf[0] = gx * a + gy * b;
        xf[1] = gx * c + gy * d;
        xf[2] = gx * (e - g[0]) + gy * (f - g[1]);
        xf[3] = xf[4] = xf[5] = 0.0f;
        break;
    }
    case CS_FUNC_RADIAL: {
        float k = 1.0f / g[2];
        xf[0] = a * k;
        xf[1] = c * k;
        xf[2] = (e - g[0]) * k;
        xf[3] = b * k;
        xf[4] = d * k;
        xf[5] = (f - g[1]) * k;
        break;
    }
    default: { /* CS_FUNC_MAP: q - o = s U + t V */
        float ux = g[2], uy = g[3], vx = g[4], vy = g[5];
        float k = 1.0f / (ux * vy - vx * uy);
        float su = vy * k, sv = -vx * k, tu = -uy * k, tv = ux * k;
        float ex = e - g[0], fy = f - g[1];
        xf[0] = su * a + sv * b;
        xf[1] = su * c + sv * d;
        xf[2] = su * ex + sv * fy;
        xf[3] = tu * a + tv * b;
        xf[4] = tu * c + tv * d;
        xf[5] = tu * ex + tv * fy;
        break;
    }
    }
}

/* Maps t into [0, 1] by the spread method. */
static float spread(float t, uint8_t mode)
{
    if (!(t == t))
        return 0.0f;
    /* Far outside, pad and repeat both are periodic or constant; clamping
     * keeps floor() in range. */
    t = cs__clampf(t, -1.0e6f, 1.0e6f);
    switch (mode) {
    case CS_SPREAD_REPEAT:
        return t - (float)cs__floori(t);
    case CS_SPREAD_REFLECT: {
        float h = t * 0.5f;
        float m = 2.0f * (h - (float)cs__floori(h)); /* 0..2 */
        return m > 1.0f ? 2.0f - m : m;
    }
    default:
        return cs__clampf(t, 0.0f, 1.0f);
    }
}

static void stop_value(const cs_paint_func *fn, int i, bool srgb, float out[3])
{
    for (int ch = 0; ch < 3; ch++) {
        float v = fn->stops[i].value[ch];
        out[ch] = srgb ? cs__encode(v) : v;
    }
}

static void lerp3(const float *a, const float *b, float w, float out[3])
{
    for (int ch = 0; ch < 3; ch++)
        out[ch] = a[ch] + (b[ch] - a[ch]) * w;
}

/* Value at t in [0,1] along the stops. */
static void stops_at(const cs_paint_func *fn, float t, bool srgb, float out[3])
{
    int n = fn->stop_count;
    if (t <= fn->stops[0].offset) {
        stop_value(fn, 0, srgb, out);
        return;
    }
    for (int i = 0; i + 1 < n; i++) {
        float o0 = fn->stops[i].offset, o1 = fn->stops[i + 1].offset;
        if (t < o1) { /* t >= o0 here, so o1 > o0 */
            float a[3], b[3];
            stop_value(fn, i, srgb, a);
            stop_value(fn, i + 1, srgb, b);
            lerp3(a, b, (t - o0) / (o1 - o0), out);
            return;
        }
    }
    stop_value(fn, n - 1, srgb, out);
}

/* Splits s in [0,1] over n nodes: lower node index and the fraction. */
static int grid_at(float s, int n, float *frac)
{
    if (n < 2) {
        *frac = 0.0f;
        return 0;
    }
    float p = s * (float)(n - 1);
    int i = cs__floori(p);
    if (i > n - 2)
        i = n - 2;
    if (i < 0)
        i = 0;
    *frac = p - (float)i;
    return i;
}

void cs__func_eval(const cs_paint_func *fn, const float xf[6], float px, float py, bool srgb,
                   float out[3])
{
    float u = xf[0] * px + xf[1] * py + xf[2];
    switch (fn->kind) {
    case CS_FUNC_LINEAR:
        stops_at(fn, spread(u, fn->spread), srgb, out);
        return;
    case CS_FUNC_RADIAL: {
        float v = xf[3] * px + xf[4] * py + xf[5];
        float r = 1.0f / fn->geom[2];
        float fx = (fn->geom[3] - fn->geom[0]) * r, fy = (fn->geom[4] - fn->geom[1]) * r;
        float dx = u - fx, dy = v - fy;
        float a = 1.0f - (fx * fx + fy * fy); /* > 0: the focus is inside */
        float df = dx * fx + dy * fy, dd = dx * dx + dy * dy;
        float t = (df + cs__sqrtf(df * df + a * dd)) / a;
        stops_at(fn, spread(t, fn->spread), srgb, out);
        return;
    }
    default: {
        float v = xf[3] * px + xf[4] * py + xf[5];
        int cols = fn->map_cols, rows = fn->stop_count / fn->map_cols;
        float fs, ft;
        int i = grid_at(spread(u, fn->spread), cols, &fs);
        int j = grid_at(spread(v, fn->spread), rows, &ft);
        int i1 = cols > 1 ? i + 1 : i, j1 = rows > 1 ? j + 1 : j;
        float v00[3], v10[3], v01[3], v11[3], top[3], bot[3];
        stop_value(fn, j * cols + i, srgb, v00);
        stop_value(fn, j * cols + i1, srgb, v10);
        stop_value(fn, j1 * cols + i, srgb, v01);
        stop_value(fn, j1 * cols + i1, srgb, v11);
        lerp3(v00, v10, fs, top);
        lerp3(v01, v11, fs, bot);
        lerp3(top, bot, ft, out);
        return;
    }
    }
}
