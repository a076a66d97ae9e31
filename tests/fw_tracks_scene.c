/*
 * fw_tracks_scene.c - the animated stream test scene (see fw_tracks_scene.h).
 *
 * Three cels in front of a background card: a square turning about the
 * panel's centre (transform track, smooth), a translucent ellipse sliding
 * across whose own lights change (transform and cel lights tracks, linear),
 * and a cubic blob that morphs and changes colour (contour points and
 * region paint tracks); the stack's front light and the background card
 * are animated too. Rotations use the rational half-angle form, so no libm.
 */
#include "fw_tracks_scene.h"

#define SQRT_HALF 0.70710678f

#define TRY(call)                                                                                  \
    do {                                                                                           \
        cs_status st_ = (call);                                                                    \
        if (st_ != CS_OK)                                                                          \
            return st_;                                                                            \
    } while (0)

/* Rotation about (cx, cy) by the angle whose half-angle tangent is s, as
 * six floats a b c d e f. */
static void rotation(float s, float cx, float cy, float *m)
{
    float q = 1.0f + s * s;
    float c = (1.0f - s * s) / q, sn = (2.0f * s) / q;
    m[0] = c;
    m[1] = sn;
    m[2] = -sn;
    m[3] = c;
    m[4] = cx - (c * cx - sn * cy);
    m[5] = cy - (sn * cx + c * cy);
}

cs_status fw_tracks_scene(cs_scene *s, cs_error *err)
{
    static const cs_affine identity = {1, 0, 0, 1, 0, 0};
    TRY(cs_scene_init(s, 480.0f, 272.0f));
    const float bg[3] = {0.02f, 0.03f, 0.05f};
    TRY(cs_scene_set_background(s, bg));

    /* Cel 0, region 0, contour 0: the square. */
    TRY(cs_scene_add_cel(s, &identity, 0, 0, err));
    const cs_paint orange = {{0.85f, 0.5f, 0.1f}, {1, 1, 1}, 0.9f};
    TRY(cs_scene_add_region(s, CS_FILL_NONZERO, &orange, err));
    const cs_point square[4] = {{180, 76, 1}, {300, 76, 1}, {300, 196, 1}, {180, 196, 1}};
    TRY(cs_scene_add_contour(s, 1, 4, square, 0, err));

    /* Cel 1, region 1, contour 1: a circle that its transform makes an ellipse. */
    const cs_affine slide0 = {1.6f, 0, 0, 0.7f, 40, 30};
    TRY(cs_scene_add_cel(s, &slide0, 0, 0, err));
    const cs_paint blue = {{0.2f, 0.6f, 0.9f}, {0.6f, 0.9f, 1.0f}, 0.6f};
    TRY(cs_scene_add_region(s, CS_FILL_NONZERO, &blue, err));
    {
        static const float dir[8][3] = {
            {1, 0, 1}, {1, 1, SQRT_HALF}, {0, 1, 1}, {-1, 1, SQRT_HALF},
            {-1, 0, 1}, {-1, -1, SQRT_HALF}, {0, -1, 1}, {1, -1, SQRT_HALF},
        };
        static const float iv[8] = {1, 0, 1, 0, 1, 0, 1, 0};
        cs_point p[8];
        for (int i = 0; i < 8; i++) {
            p[i].x = 30.0f + 40.0f * dir[i][0];
            p[i].y = 130.0f + 40.0f * dir[i][1];
            p[i].w = dir[i][2];
        }
        TRY(cs_scene_add_contour(s, 2, 8, p, iv, err));
    }

    /* Cel 2, region 2, contour 2: a rational cubic blob. */
    TRY(cs_scene_add_cel(s, &identity, 0, 0, err));
    const cs_paint green = {{0.1f, 0.7f, 0.4f}, {0.7f, 1.0f, 0.8f}, 0.8f};
    TRY(cs_scene_add_region(s, CS_FILL_NONZERO, &green, err));
    static const float blob0[7][3] = {{380, 150, 1}, {460, 160, 2}, {450, 250, 1},
                                      {390, 255, 0.7f}, {340, 230, 1}, {330, 180, 1.5f},
                                      {350, 140, 1}};
    cs_point bp[7];
    for (int i = 0; i < 7; i++) {
        bp[i].x = blob0[i][0];
        bp[i].y = blob0[i][1];
        bp[i].w = blob0[i][2];
    }
    TRY(cs_scene_add_contour(s, 3, 7, bp, 0, err));

    /* Tracks: keys at 0, 1, 2 s. */
    float v[21];
    TRY(cs_scene_add_track(s, CS_TRACK_TRANSFORM, 0, CS_EASE_SMOOTH, err));
    for (int k = 0; k < 3; k++) {
        rotation(0.3f * (float)k, 240.0f, 136.0f, v);
        TRY(cs_scene_add_key(s, (float)k, v, err));
    }
    TRY(cs_scene_add_track(s, CS_TRACK_TRANSFORM, 1, CS_EASE_LINEAR, err));
    const float slide[2][6] = {{1.6f, 0, 0, 0.7f, 40, 30}, {1.3f, 0.2f, -0.1f, 0.9f, 300, 50}};
    TRY(cs_scene_add_key(s, 0.0f, slide[0], err));
    TRY(cs_scene_add_key(s, 2.0f, slide[1], err));
    TRY(cs_scene_add_track(s, CS_TRACK_CEL_LIGHTS, 1, CS_EASE_LINEAR, err));
    const float lights[2][6] = {{1, 1, 1, 0, 0, 0}, {0.4f, 0.6f, 1.0f, 0.3f, 0.3f, 0.3f}};
    TRY(cs_scene_add_key(s, 0.0f, lights[0], err));
    TRY(cs_scene_add_key(s, 2.0f, lights[1], err));
    TRY(cs_scene_add_track(s, CS_TRACK_POINTS, 2, CS_EASE_SMOOTH, err));
    for (int k = 0; k < 3; k++) {
        for (int i = 0; i < 7; i++) {
            float wob = (float)(((i + k) % 3) - 1) * 12.0f * (float)k;
            v[3 * i] = blob0[i][0] + wob;
            v[3 * i + 1] = blob0[i][1] - 0.5f * wob;
            v[3 * i + 2] = blob0[i][2];
        }
        TRY(cs_scene_add_key(s, (float)k, v, err));
    }
    TRY(cs_scene_add_track(s, CS_TRACK_PAINT, 2, CS_EASE_LINEAR, err));
    const float paints[2][7] = {{0.1f, 0.7f, 0.4f, 0.7f, 1.0f, 0.8f, 0.8f},
                                {0.9f, 0.2f, 0.6f, 1.0f, 0.8f, 0.9f, 0.4f}};
    TRY(cs_scene_add_key(s, 0.0f, paints[0], err));
    TRY(cs_scene_add_key(s, 2.0f, paints[1], err));
    TRY(cs_scene_add_track(s, CS_TRACK_STACK_LIGHTS, 0, CS_EASE_SMOOTH, err));
    const float stack[2][6] = {{1, 1, 1, 0, 0, 0}, {0.8f, 0.9f, 1.0f, 0, 0, 0}};
    TRY(cs_scene_add_key(s, 0.0f, stack[0], err));
    TRY(cs_scene_add_key(s, 2.0f, stack[1], err));
    TRY(cs_scene_add_track(s, CS_TRACK_BACKGROUND, 0, CS_EASE_LINEAR, err));
    const float cards[2][3] = {{0.02f, 0.03f, 0.05f}, {0.1f, 0.05f, 0.02f}};
    TRY(cs_scene_add_key(s, 0.0f, cards[0], err));
    TRY(cs_scene_add_key(s, 2.0f, cards[1], err));
    return CS_OK;
}
