/*
 * celfw_scenes.c - the built-in scenes: shapes as closed NURBS, made in C.
 *
 * Circles are exact rational quadratics (8 points, weights sqrt(1/2) at the
 * corners, intervals 1,0 repeated), polygons are degree-1 contours, and the
 * flourish is a self-intersecting closed cubic under the even-odd rule, so
 * the built-in scenes exercise the same curve kinds as scenes/demo.json.
 */
#include <math.h>
#include <string.h>

#include "celfw_scenes.h"

#define RSQRT2 0.70710678f

/* sRGB-encoded component to linear light (host code: libm is fine here). */
static float lin(float srgb)
{
    return srgb <= 0.04045f ? srgb / 12.92f : powf((srgb + 0.055f) / 1.055f, 2.4f);
}

static cs_paint opaque(float r, float g, float b)
{
    cs_paint p;
    p.pigment[0] = lin(r);
    p.pigment[1] = lin(g);
    p.pigment[2] = lin(b);
    p.medium[0] = p.medium[1] = p.medium[2] = 1.0f;
    p.beta = 1.0f;
    return p;
}

static cs_paint translucent(float r, float g, float b, float beta)
{
    cs_paint p = opaque(r, g, b);
    p.beta = beta;
    return p;
}

static void circle(cs_scene *s, float cx, float cy, float r)
{
    static const float dx[8] = {1, 1, 0, -1, -1, -1, 0, 1};
    static const float dy[8] = {0, 1, 1, 1, 0, -1, -1, -1};
    cs_point p[8];
    float iv[8];
    for (int i = 0; i < 8; i++) {
        p[i].x = cx + r * dx[i];
        p[i].y = cy + r * dy[i];
        p[i].w = (i & 1) ? RSQRT2 : 1.0f;
        iv[i] = (i & 1) ? 0.0f : 1.0f;
    }
    cs_scene_add_contour(s, 2, 8, p, iv, NULL);
}

static void polygon(cs_scene *s, const float *xy, int n)
{
    cs_point p[32];
    for (int i = 0; i < n && i < 32; i++) {
        p[i].x = xy[2 * i];
        p[i].y = xy[2 * i + 1];
        p[i].w = 1.0f;
    }
    cs_scene_add_contour(s, 1, n, p, NULL, NULL);
}

static void rect(cs_scene *s, float x0, float y0, float x1, float y1)
{
    float xy[8] = {x0, y0, x1, y0, x1, y1, x0, y1};
    polygon(s, xy, 4);
}

/*
 * A rounded rectangle as one degree-2 contour: per corner an on-curve tangent
 * point A, the corner C (weight sqrt(1/2): an exact quarter circle) and the
 * tangent point B, then the midpoint M of the straight edge to the next
 * corner. On- and off-curve points alternate with intervals 1, 0 as in the
 * circle, so every piece is a conic arc or a straight quadratic.
 */
static void round_rect(cs_scene *s, float x0, float y0, float x1, float y1, float r)
{
    const float A[4][2] = {{x1 - r, y0}, {x1, y1 - r}, {x0 + r, y1}, {x0, y0 + r}};
    const float C[4][2] = {{x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}};
    const float B[4][2] = {{x1, y0 + r}, {x1 - r, y1}, {x0, y1 - r}, {x0 + r, y0}};
    cs_point p[16];
    float iv[16];
    for (int k = 0; k < 4; k++) {
        const float *an = A[(k + 1) % 4];
        cs_point q[4] = {{A[k][0], A[k][1], 1.0f},
                         {C[k][0], C[k][1], RSQRT2},
                         {B[k][0], B[k][1], 1.0f},
                         {0.5f * (B[k][0] + an[0]), 0.5f * (B[k][1] + an[1]), 1.0f}};
        for (int j = 0; j < 4; j++) {
            p[4 * k + j] = q[j];
            iv[4 * k + j] = (j & 1) ? 0.0f : 1.0f;
        }
    }
    cs_scene_add_contour(s, 2, 16, p, iv, NULL);
}

/* A five-pointed star drawn as one self-intersecting pentagram (even-odd: hollow centre). */
static void pentagram(cs_scene *s, float cx, float cy, float r)
{
    static const float c[5][2] = {{0.0f, -1.0f}, {0.587785f, 0.809017f}, {-0.951057f, -0.309017f},
                                  {0.951057f, -0.309017f}, {-0.587785f, 0.809017f}};
    float xy[10];
    for (int i = 0; i < 5; i++) {
        xy[2 * i] = cx + r * c[i][0];
        xy[2 * i + 1] = cy + r * c[i][1];
    }
    polygon(s, xy, 5);
}

/* A looping flourish: a closed cubic B-spline whose control polygon crosses itself. */
static void flourish(cs_scene *s, float cx, float cy, float w, float h)
{
    static const float u[8][2] = {{-1.0f, 0.0f}, {-0.5f, -1.0f}, {0.5f, 1.0f}, {1.0f, 0.0f},
                                  {0.5f, -1.0f}, {-0.5f, 1.0f}, {-0.9f, 0.6f}, {-1.1f, -0.6f}};
    cs_point p[8];
    for (int i = 0; i < 8; i++) {
        p[i].x = cx + w * u[i][0];
        p[i].y = cy + h * u[i][1];
        p[i].w = (i == 2 || i == 5) ? 2.0f : 1.0f; /* rational: pulled towards two points */
    }
    cs_scene_add_contour(s, 3, 8, p, NULL, NULL);
}

static void background(cs_scene *s, float r, float g, float b)
{
    float bg[3] = {lin(r), lin(g), lin(b)};
    cs_scene_set_background(s, bg);
}

static void build_demo(cs_scene *s)
{
    cs_scene_init(s, 320.0f, 180.0f);
    background(s, 0.06f, 0.09f, 0.13f);
    cs_affine id = {1, 0, 0, 1, 0, 0};

    /* front: a translucent gel over the right half */
    cs_scene_add_cel(s, &id, NULL, NULL, NULL);
    cs_paint gel = translucent(0.2f, 0.6f, 1.0f, 0.35f);
    cs_scene_add_region(s, CS_FILL_NONZERO, &gel, NULL);
    circle(s, 250.0f, 120.0f, 48.0f);

    /* the flourish and the star */
    cs_scene_add_cel(s, &id, NULL, NULL, NULL);
    cs_paint gold = opaque(0.95f, 0.75f, 0.2f);
    cs_scene_add_region(s, CS_FILL_EVENODD, &gold, NULL);
    pentagram(s, 60.0f, 120.0f, 40.0f);
    cs_paint pink = opaque(0.9f, 0.3f, 0.5f);
    cs_scene_add_region(s, CS_FILL_EVENODD, &pink, NULL);
    flourish(s, 160.0f, 130.0f, 60.0f, 30.0f);

    /* title bar with a hole punched in it (a ring under nonzero: opposite winding) */
    cs_affine tilt = {0.98f, 0.03f, -0.03f, 0.98f, 4.0f, -2.0f};
    cs_scene_add_cel(s, &tilt, NULL, NULL, NULL);
    cs_paint red = opaque(0.85f, 0.2f, 0.2f);
    cs_scene_add_region(s, CS_FILL_NONZERO, &red, NULL);
    round_rect(s, 20.0f, 14.0f, 300.0f, 62.0f, 14.0f);
    cs_paint white = opaque(1.0f, 1.0f, 1.0f);
    cs_scene_add_region(s, CS_FILL_EVENODD, &white, NULL);
    circle(s, 50.0f, 38.0f, 16.0f);
    circle(s, 50.0f, 38.0f, 9.0f);
    rect(s, 80.0f, 30.0f, 280.0f, 34.0f);
    rect(s, 80.0f, 42.0f, 220.0f, 46.0f);
}

void celfw_anim_disc(float t, float *x, float *y)
{
    /* Back and forth along a straight track, 2 s per pass, at a fixed height
     * so that only the lines of the track change. */
    float ph = t * 0.5f;
    ph -= (float)(int)ph;
    float u = ph < 0.5f ? 2.0f * ph : 2.0f - 2.0f * ph;
    *x = 30.0f + 260.0f * u;
    *y = 150.0f;
}

static void build_anim(cs_scene *s, float t)
{
    cs_scene_init(s, 320.0f, 180.0f);
    background(s, 0.05f, 0.05f, 0.08f);
    cs_affine id = {1, 0, 0, 1, 0, 0};
    /* front: the small moving disc */
    float dx, dy;
    celfw_anim_disc(t, &dx, &dy);
    cs_scene_add_cel(s, &id, NULL, NULL, NULL);
    cs_paint lime = opaque(0.5f, 1.0f, 0.2f);
    cs_scene_add_region(s, CS_FILL_NONZERO, &lime, NULL);
    circle(s, dx, dy, CELFW_ANIM_R);
    /* behind: a still sign */
    cs_scene_add_cel(s, &id, NULL, NULL, NULL);
    cs_paint blue = opaque(0.2f, 0.35f, 0.8f);
    cs_scene_add_region(s, CS_FILL_NONZERO, &blue, NULL);
    round_rect(s, 16.0f, 16.0f, 304.0f, 110.0f, 20.0f);
    cs_paint gold = opaque(0.95f, 0.75f, 0.2f);
    cs_scene_add_region(s, CS_FILL_EVENODD, &gold, NULL);
    pentagram(s, 70.0f, 63.0f, 34.0f);
    circle(s, 200.0f, 63.0f, 30.0f);
}

static void build_bars(cs_scene *s)
{
    static const float c[8][3] = {{1, 1, 1}, {1, 1, 0}, {0, 1, 1}, {0, 1, 0},
                                  {1, 0, 1}, {1, 0, 0}, {0, 0, 1}, {0.5f, 0.5f, 0.5f}};
    cs_scene_init(s, 320.0f, 180.0f);
    background(s, 0.0f, 0.0f, 0.0f);
    cs_affine id = {1, 0, 0, 1, 0, 0};
    cs_scene_add_cel(s, &id, NULL, NULL, NULL);
    for (int i = 0; i < 8; i++) {
        cs_paint p = opaque(c[i][0], c[i][1], c[i][2]);
        cs_scene_add_region(s, CS_FILL_NONZERO, &p, NULL);
        rect(s, 40.0f * (float)i, 0.0f, 40.0f * (float)(i + 1), 120.0f);
    }
    /* a grey ramp under the bars */
    for (int i = 0; i < 16; i++) {
        float v = (float)i / 15.0f;
        cs_paint p = opaque(v, v, v);
        cs_scene_add_region(s, CS_FILL_NONZERO, &p, NULL);
        rect(s, 20.0f * (float)i, 120.0f, 20.0f * (float)(i + 1), 180.0f);
    }
}

bool celfw_scene_build(const char *name, cs_scene *scene, float t)
{
    if (strcmp(name, "demo") == 0)
        build_demo(scene);
    else if (strcmp(name, "anim") == 0)
        build_anim(scene, t);
    else if (strcmp(name, "bars") == 0)
        build_bars(scene);
    else
        return false;
    return true;
}

uint64_t celfw_scene_period_ns(const char *name)
{
    return strcmp(name, "anim") == 0 ? 2000000000u : 0u; /* celfw_anim_disc: one pass there and back */
}

bool celfw_scene_animated(const char *name)
{
    return strcmp(name, "anim") == 0;
}

const char *celfw_scene_names(void)
{
    return "demo anim bars";
}
