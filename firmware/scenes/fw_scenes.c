/*
 * fw_scenes.c - the firmware's built-in test scenes.
 *
 * Three scenes cover what the qemu test must show identical on host and
 * target: "signage" (demo-like: a panel with a rational blob, block letters,
 * a ring with a hole, an even-odd pentagram, translucent bubbles and a
 * self-intersecting cubic flourish that moves with t), "orbit" (an animated
 * scene: a rotating square and a sliding ellipse) and "gels" (a beta-model
 * stack on a light box: coloured gels, a foggy cel with its own lights and a
 * hold-out matte).
 *
 * Rotation uses the rational parametrisation cos = (1-s^2)/(1+s^2),
 * sin = 2s/(1+s^2), so no libm is needed and every number is the same on
 * every IEEE-754 target. Canvas units are the 480x272 panel's pixels.
 */
#include "fw_scenes.h"

#define SQRT_HALF 0.70710678f

/* Linear-light paint with a white medium unless told otherwise. */
static cs_paint paint(float r, float g, float b, float mr, float mg, float mb, float beta)
{
    cs_paint p = {{r, g, b}, {mr, mg, mb}, beta};
    return p;
}

static cs_status add_region(cs_scene *s, cs_fill_rule rule, cs_paint p, cs_error *err)
{
    return cs_scene_add_region(s, rule, &p, err);
}

static cs_status add_cel(cs_scene *s, const cs_affine *m, const float *front, const float *back,
                         cs_error *err)
{
    static const cs_affine identity = {1, 0, 0, 1, 0, 0};
    return cs_scene_add_cel(s, m ? m : &identity, front, back, err);
}

/* A circle as the degree-2 rational NURBS of the design notes; ccw=false
 * reverses it (a hole under the nonzero rule). */
static cs_status add_circle(cs_scene *s, float cx, float cy, float r, bool ccw, cs_error *err)
{
    static const float dir[8][3] = {
        {1, 0, 1}, {1, 1, SQRT_HALF}, {0, 1, 1}, {-1, 1, SQRT_HALF},
        {-1, 0, 1}, {-1, -1, SQRT_HALF}, {0, -1, 1}, {1, -1, SQRT_HALF},
    };
    static const float iv[8] = {1, 0, 1, 0, 1, 0, 1, 0};
    cs_point p[8];
    for (int i = 0; i < 8; i++) {
        int k = ccw ? i : (8 - i) % 8;
        p[i].x = cx + r * dir[k][0];
        p[i].y = cy + r * dir[k][1];
        p[i].w = dir[k][2];
    }
    return cs_scene_add_contour(s, 2, 8, p, iv, err);
}

/* A rounded rectangle: eight quadratic spans, arcs exact via weights. */
static cs_status add_round_rect(cs_scene *s, float x0, float y0, float x1, float y1, float r,
                                cs_error *err)
{
    cs_point p[16] = {
        {x1, y0 + r, 1}, {x1, (y0 + y1) * 0.5f, 1}, {x1, y1 - r, 1}, {x1, y1, SQRT_HALF},
        {x1 - r, y1, 1}, {(x0 + x1) * 0.5f, y1, 1}, {x0 + r, y1, 1}, {x0, y1, SQRT_HALF},
        {x0, y1 - r, 1}, {x0, (y0 + y1) * 0.5f, 1}, {x0, y0 + r, 1}, {x0, y0, SQRT_HALF},
        {x0 + r, y0, 1}, {(x0 + x1) * 0.5f, y0, 1}, {x1 - r, y0, 1}, {x1, y0, SQRT_HALF},
    };
    static const float iv[16] = {1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0};
    return cs_scene_add_contour(s, 2, 16, p, iv, err);
}

/* A polygon given as x,y pairs offset by (ox, oy) and scaled by k. */
static cs_status add_polygon(cs_scene *s, const float *xy, int n, float ox, float oy, float k,
                             cs_error *err)
{
    cs_point p[16];
    if (n > 16)
        return CS_ERR_ARG;
    for (int i = 0; i < n; i++) {
        p[i].x = ox + k * xy[2 * i];
        p[i].y = oy + k * xy[2 * i + 1];
        p[i].w = 1.0f;
    }
    return cs_scene_add_contour(s, 1, n, p, 0, err);
}

/* Rotation by the angle whose half-angle tangent is s, about (cx, cy),
 * followed by a translation (tx, ty). */
static cs_affine rotation(float s, float cx, float cy, float tx, float ty)
{
    float q = 1.0f + s * s;
    float c = (1.0f - s * s) / q, sn = (2.0f * s) / q;
    cs_affine m = {c, sn, -sn, c, 0, 0};
    m.e = cx - (c * cx - sn * cy) + tx;
    m.f = cy - (sn * cx + c * cy) + ty;
    return m;
}

#define TRY(call)                                                                                  \
    do {                                                                                           \
        cs_status st_ = (call);                                                                    \
        if (st_ != CS_OK)                                                                          \
            return st_;                                                                            \
    } while (0)

/* Block letters C, E, L in a 6 x 8 grid. */
static const float letter_c[] = {0, 0, 6, 0, 6, 2, 2, 2, 2, 6, 6, 6, 6, 8, 0, 8};
static const float letter_e[] = {0, 0, 6, 0, 6, 2, 2, 2, 2, 3, 5, 3, 5, 5, 2, 5, 2, 6, 6, 6, 6, 8, 0, 8};
static const float letter_l[] = {0, 0, 2, 0, 2, 6, 6, 6, 6, 8, 0, 8};
/* A pentagram (self-intersecting) of radius 1, vertices every 144 degrees. */
static const float pentagram[] = {
    0.0f, -1.0f, 0.58778525f, 0.80901699f, -0.95105652f, -0.30901699f,
    0.95105652f, -0.30901699f, -0.58778525f, 0.80901699f,
};

static cs_status build_signage(cs_scene *s, float t, cs_error *err)
{
    TRY(cs_scene_init(s, 480.0f, 272.0f));
    const float bg[3] = {0.004f, 0.008f, 0.02f};
    TRY(cs_scene_set_background(s, bg));

    /* Cel 0: a self-intersecting cubic figure-eight that drifts with t. */
    cs_affine drift = rotation(0.05f * t, 240.0f, 200.0f, 24.0f * t - 12.0f, 0.0f);
    TRY(add_cel(s, &drift, 0, 0, err));
    TRY(add_region(s, CS_FILL_NONZERO, paint(1.0f, 0.6f, 0.15f, 1.0f, 0.85f, 0.5f, 0.7f), err));
    {
        const float cx = 240.0f, cy = 200.0f, a = 150.0f, b = 46.0f;
        cs_point p[12] = {
            {cx, cy, 1}, {cx + 0.5f * a, cy - b, 1}, {cx + a, cy - b, 1},
            {cx + a, cy, 1}, {cx + a, cy + b, 1}, {cx + 0.5f * a, cy + b, 1},
            {cx, cy, 1}, {cx - 0.5f * a, cy - b, 1}, {cx - a, cy - b, 1},
            {cx - a, cy, 1}, {cx - a, cy + b, 1}, {cx - 0.5f * a, cy + b, 1},
        };
        static const float iv[12] = {1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0};
        TRY(cs_scene_add_contour(s, 3, 12, p, iv, err));
    }

    /* Cel 1: the title: block letters, a ring with a hole, a pentagram. */
    const float title_front[3] = {1.0f, 0.97f, 0.9f};
    TRY(add_cel(s, 0, title_front, 0, err));
    TRY(add_region(s, CS_FILL_NONZERO, paint(0.9f, 0.9f, 0.85f, 1, 1, 1, 1.0f), err));
    TRY(add_polygon(s, letter_c, 8, 48.0f, 40.0f, 10.0f, err));
    TRY(add_polygon(s, letter_e, 12, 120.0f, 40.0f, 10.0f, err));
    TRY(add_polygon(s, letter_l, 6, 192.0f, 40.0f, 10.0f, err));
    TRY(add_region(s, CS_FILL_NONZERO, paint(0.9f, 0.3f, 0.04f, 1, 1, 1, 1.0f), err));
    TRY(add_circle(s, 300.0f, 80.0f, 40.0f, true, err));
    TRY(add_circle(s, 300.0f, 80.0f, 22.5f, false, err));
    TRY(add_region(s, CS_FILL_EVENODD, paint(0.95f, 0.75f, 0.08f, 1, 1, 1, 1.0f), err));
    TRY(add_polygon(s, pentagram, 5, 400.0f, 82.0f, 44.0f, err));

    /* Cel 2: translucent bubbles with tinted media, overlapping in one cel. */
    TRY(add_cel(s, 0, 0, 0, err));
    static const float bub[4][3] = {
        {0.8f, 0.08f, 0.08f}, {0.1f, 0.7f, 0.15f}, {0.1f, 0.2f, 0.85f}, {0.75f, 0.1f, 0.7f}};
    for (int i = 0; i < 4; i++) {
        TRY(add_region(s, CS_FILL_NONZERO,
                       paint(bub[i][0], bub[i][1], bub[i][2], 0.5f + 0.5f * bub[i][0],
                             0.5f + 0.5f * bub[i][1], 0.5f + 0.5f * bub[i][2], 0.45f),
                       err));
        TRY(add_circle(s, 96.0f + 72.0f * (float)i, 178.0f + 6.0f * (float)(i & 1), 44.5f, true,
                       err));
    }

    /* Cel 3: the panel, with a weighted non-uniform cubic blob in front. */
    TRY(add_cel(s, 0, 0, 0, err));
    TRY(add_region(s, CS_FILL_NONZERO, paint(0.1f, 0.35f, 0.6f, 0.5f, 0.7f, 1.0f, 0.8f), err));
    {
        cs_point p[6] = {{380, 150, 1}, {470, 170, 2.5f}, {450, 260, 1},
                         {360, 250, 0.6f}, {330, 200, 1.5f}, {350, 140, 1}};
        static const float iv[6] = {1, 2, 1, 0.5f, 1, 1.5f};
        TRY(cs_scene_add_contour(s, 3, 6, p, iv, err));
    }
    TRY(add_region(s, CS_FILL_NONZERO, paint(0.015f, 0.04f, 0.12f, 1, 1, 1, 1.0f), err));
    TRY(add_round_rect(s, 16.0f, 16.0f, 464.0f, 256.0f, 28.0f, err));
    return CS_OK;
}

static cs_status build_orbit(cs_scene *s, float t, cs_error *err)
{
    TRY(cs_scene_init(s, 480.0f, 272.0f));
    const float bg[3] = {0.05f, 0.05f, 0.06f};
    TRY(cs_scene_set_background(s, bg));

    /* A square turning about the centre. */
    cs_affine spin = rotation(0.3f * t, 240.0f, 136.0f, 0.0f, 0.0f);
    TRY(add_cel(s, &spin, 0, 0, err));
    TRY(add_region(s, CS_FILL_NONZERO, paint(0.85f, 0.5f, 0.1f, 1, 1, 1, 0.9f), err));
    static const float square[] = {-1, -1, 1, -1, 1, 1, -1, 1};
    TRY(add_polygon(s, square, 4, 240.0f, 136.0f, 60.0f, err));

    /* An ellipse (a scaled circle) sliding right by a non-integral amount. */
    cs_affine slide = {1.6f, 0.0f, 0.0f, 0.7f, 40.0f + 131.3f * t, 30.0f + 9.7f * t};
    TRY(add_cel(s, &slide, 0, 0, err));
    TRY(add_region(s, CS_FILL_NONZERO, paint(0.2f, 0.6f, 0.9f, 0.6f, 0.9f, 1.0f, 0.6f), err));
    TRY(add_circle(s, 30.0f, 130.0f, 40.0f, true, err));

    /* A still backdrop of concentric rings (even-odd). */
    TRY(add_cel(s, 0, 0, 0, err));
    TRY(add_region(s, CS_FILL_EVENODD, paint(0.3f, 0.3f, 0.35f, 1, 1, 1, 1.0f), err));
    for (int i = 0; i < 4; i++)
        TRY(add_circle(s, 240.0f, 136.0f, 120.0f - 20.0f * (float)i, true, err));
    return CS_OK;
}

static cs_status build_gels(cs_scene *s, float t, cs_error *err)
{
    (void)t;
    TRY(cs_scene_init(s, 480.0f, 272.0f));
    /* A light box: no background card, the stack's back light shines through. */
    const float front[3] = {0.3f, 0.3f, 0.3f}, back[3] = {1.0f, 1.0f, 0.95f};
    TRY(cs_scene_set_lights(s, front, back));

    /* A foggy cel, partly scattering, lit by its own warm front and dim back light. */
    const float fog_front[3] = {1.0f, 0.85f, 0.7f}, fog_back[3] = {0.2f, 0.2f, 0.25f};
    TRY(add_cel(s, 0, fog_front, fog_back, err));
    TRY(add_region(s, CS_FILL_NONZERO, paint(0.9f, 0.9f, 0.9f, 0.8f, 0.9f, 1.0f, 0.3f), err));
    TRY(add_round_rect(s, 300.0f, 30.0f, 450.0f, 240.0f, 20.0f, err));

    /* Three coloured gels (beta = 0), one per cel, overlapping. */
    static const float gel[3][3] = {{0, 1, 1}, {1, 0, 1}, {1, 1, 0}};
    static const float at[3][2] = {{180, 100}, {240, 170}, {300, 100}};
    for (int i = 0; i < 3; i++) {
        TRY(add_cel(s, 0, 0, 0, err));
        TRY(add_region(s, CS_FILL_NONZERO, paint(0, 0, 0, gel[i][0], gel[i][1], gel[i][2], 0.0f),
                       err));
        TRY(add_circle(s, at[i][0], at[i][1], 80.0f, true, err));
    }

    /* A hold-out matte (E = 0, T = 0) and a soft matte (partial T) behind. */
    TRY(add_cel(s, 0, 0, 0, err));
    TRY(add_region(s, CS_FILL_NONZERO, paint(0, 0, 0, 1, 1, 1, 1.0f), err));
    static const float bar[] = {0, 0, 1, 0, 1, 1, 0, 1};
    TRY(add_polygon(s, bar, 4, 20.0f, 200.0f, 50.0f, err));
    TRY(add_region(s, CS_FILL_NONZERO, paint(0, 0, 0, 0.5f, 0.5f, 0.5f, 0.0f), err));
    TRY(add_polygon(s, bar, 4, 0.0f, 0.0f, 140.0f, err));
    return CS_OK;
}

const fw_scene_info fw_scenes[FW_SCENE_COUNT] = {
    {"signage", build_signage},
    {"orbit", build_orbit},
    {"gels", build_gels},
};

int fw_scene_find(const char *name)
{
    for (int i = 0; i < FW_SCENE_COUNT; i++) {
        const char *a = fw_scenes[i].name, *b = name;
        while (*a && *a == *b) {
            a++;
            b++;
        }
        if (*a == 0 && *b == 0)
            return i;
    }
    return -1;
}

/* The demo, the animated scene at three instants, the beta stack, and the
 * demo again at a quarter of the area (resolution independence). */
const fw_job fw_jobs[FW_JOB_COUNT] = {
    {0, 5, 480, 272, 0},    {0, 5, 480, 272, 750},  {1, 5, 480, 272, 0},
    {1, 5, 480, 272, 500},  {1, 5, 480, 272, 1250}, {2, 5, 480, 272, 0},
    {0, 5, 240, 136, 0},
};

cs_render_opts fw_job_opts(const fw_job *job)
{
    cs_render_opts o = cs_render_defaults(job->width, job->height);
    o.aa = job->subscan ? CS_AA_SUBSCAN : CS_AA_NONE;
    o.subscanlines = job->subscan ? job->subscan : 1;
    o.time = (float)job->time_ms / 1000.0f;
    return o;
}
