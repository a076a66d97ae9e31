/*
 * test_damage.c - frames redrawn only where cs_frame_damage says equal
 * whole renders, bit for bit.
 *
 * The truth is the whole render of every frame (cs_frame_begin and
 * cs_render_line on every line, the path every other test checks against
 * its references). Against it, a frame buffer that is kept from frame to
 * frame and only has the damage window rendered into it (as a viewport)
 * must hold the same linear floats after every frame, on random scenes:
 * cels of random NURBS contours with transform, TRS, paint, points and
 * light tracks, cel groups, a background, in every AA mode and both
 * blends, over a sequence of times with edits between frames (a cel's
 * transform set, a cel moved in the stack, one removed, control points
 * set, a background track added). A frame at the time of the last one, or
 * past every key, must have an empty window; a window must start at column
 * 0 exactly when the AA needs it to. The last line is
 * `test_damage: N passed, M failed`.
 */
#include <stdlib.h>
#include <string.h>

#include "common.h"

#define W 264 /* over 255: extents are kept in units of 2 pixels */
#define H 48
#define FRAMES 16

static cs_scene *scene;
static cs_workspace *ws;
static float want[3 * W * H], have[3 * W * H];

static float rnd(float lo, float hi)
{
    return (float)tc_uniform(lo, hi);
}

/* A closed contour of n points of `degree` around (cx, cy). */
static void add_contour(float cx, float cy, float r)
{
    cs_point p[6];
    int degree = 1 + (int)(tc_rand() * 3);
    int n = degree + 1 + (int)(tc_rand() * (double)(5 - degree));
    for (int k = 0; k < n; k++) {
        float a = 6.2831853f * (float)k / (float)n;
        float rr = r * rnd(0.5f, 1.0f);
        p[k].x = cx + rr * (a < 3.2f ? 1.0f - a / 1.6f : a / 1.6f - 3.0f);
        p[k].y = cy + rr * (a < 1.6f ? a / 1.6f : a < 4.7f ? 2.0f - a / 1.6f : a / 1.6f - 4.0f);
        p[k].w = rnd(0.5f, 2.0f);
    }
    cs_error e;
    CHECK_STATUS(cs_scene_add_contour(scene, degree, n, p, NULL, &e), CS_OK,
                 "add_contour");
}

static void random_paint(cs_paint *p)
{
    for (int k = 0; k < 3; k++) {
        p->pigment[k] = rnd(0.0f, 1.0f);
        p->medium[k] = rnd(0.0f, 1.0f);
    }
    p->beta = rnd(0.3f, 1.0f);
}

/* A track of `kind` on `target` with keys at 0.2 .. 0.8 s: frames before
 * and after them are still. */
static void add_track(cs_track_kind kind, uint32_t target, const float *base, float spread)
{
    uint32_t width = cs_scene_track_width(scene, kind, target);
    cs_error e;
    if (width == 0 || cs_scene_add_track(scene, kind, target, CS_EASE_LINEAR, &e) != CS_OK)
        return;
    for (int key = 0; key < 3; key++) {
        float v[64];
        for (uint32_t k = 0; k < width && k < 64u; k++)
            v[k] = base[k] + (key ? rnd(-spread, spread) : 0.0f);
        if (kind == CS_TRACK_PAINT || kind == CS_TRACK_CEL_LIGHTS || kind == CS_TRACK_BACKGROUND)
            for (uint32_t k = 0; k < width; k++)
                v[k] = v[k] < 0.0f ? 0.0f : v[k] > 1.0f ? 1.0f : v[k];
        if (kind == CS_TRACK_TRS)
            v[9] = v[9] < 0.0f ? 0.0f : v[9] > 1.0f ? 1.0f : v[9];
        if (kind == CS_TRACK_POINTS)
            for (uint32_t k = 2; k < width; k += 3)
                v[k] = base[k];
        CHECK_STATUS(cs_scene_add_key(scene, 0.2f + 0.3f * (float)key, v, &e), CS_OK, "add_key");
    }
}

static void build_scene(void)
{
    cs_error e;
    cs_scene_init(scene, 40.0f, 30.0f);
    if (tc_rand() < 0.7) {
        float bg[3] = {rnd(0, 1), rnd(0, 1), rnd(0, 1)};
        cs_scene_set_background(scene, bg);
    }
    int cels = 2 + (int)(tc_rand() * 5);
    for (int c = 0; c < cels; c++) {
        cs_affine m = {rnd(0.7f, 1.3f), rnd(-0.2f, 0.2f), rnd(-0.2f, 0.2f), rnd(0.7f, 1.3f),
                       rnd(-3, 3), rnd(-3, 3)};
        float back[3] = {rnd(0, 0.3f), rnd(0, 0.3f), rnd(0, 0.3f)};
        CHECK_STATUS(cs_scene_add_cel(scene, &m, NULL, back, &e), CS_OK, "add_cel");
        float cx = rnd(4, 36), cy = rnd(4, 26), r = rnd(2, 9);
        int regions = 1 + (int)(tc_rand() * 2);
        for (int g = 0; g < regions; g++) {
            cs_paint p;
            random_paint(&p);
            CHECK_STATUS(cs_scene_add_region(scene, tc_rand() < 0.5 ? CS_FILL_NONZERO
                                                                     : CS_FILL_EVENODD,
                                             &p, &e),
                         CS_OK, "add_region");
            add_contour(cx + rnd(-2, 2), cy + rnd(-2, 2), r);
            if (tc_rand() < 0.3)
                add_contour(cx, cy, r * 0.5f);
        }
    }
    /* Tracks on some of them; a group. */
    for (uint32_t c = 0; c < scene->cel_count; c++) {
        double pick = tc_rand();
        if (pick < 0.3) {
            const cs_affine *t = &scene->cels[c].transform;
            float base[6] = {t->a, t->b, t->c, t->d, t->e, t->f};
            add_track(CS_TRACK_TRANSFORM, c, base, 4.0f);
        } else if (pick < 0.45) {
            float base[10] = {0, 0, 20, 15, 1, 1, 0, 0, 0, 1}; /* about the canvas centre */
            base[0] = 20, base[1] = 15;
            add_track(CS_TRACK_TRS, c, base, 2.0f);
        } else if (pick < 0.55) {
            float base[6] = {1, 1, 1, 0, 0, 0};
            add_track(CS_TRACK_CEL_LIGHTS, c, base, 0.5f);
        }
    }
    for (uint32_t ri = 0; ri < scene->region_count; ri++)
        if (tc_rand() < 0.2) {
            const cs_paint *p = &scene->regions[ri].paint;
            float base[7] = {p->pigment[0], p->pigment[1], p->pigment[2], p->medium[0],
                             p->medium[1],  p->medium[2],  p->beta};
            add_track(CS_TRACK_PAINT, ri, base, 0.4f);
        }
    for (uint32_t ki = 0; ki < scene->contour_count; ki++)
        if (tc_rand() < 0.2) {
            const cs_contour *k = &scene->contours[ki];
            add_track(CS_TRACK_POINTS, ki, &scene->points[k->first_point].x, 3.0f);
        }
    if (scene->cel_count > 2 && tc_rand() < 0.3)
        cs_scene_set_cel_parent(scene, 1, 0, &e);
}

/* Edits between frames, as stream patches make them. */
static void edit(int frame)
{
    cs_error e;
    uint32_t c = (uint32_t)(tc_rand() * scene->cel_count);
    switch (frame) {
    case 5: {
        cs_affine m = scene->cels[c].transform;
        m.e += rnd(-5, 5);
        cs_scene_set_transform(scene, c, &m, &e);
        break;
    }
    case 8:
        cs_scene_move_cel(scene, c, scene->cel_count - 1u, &e);
        break;
    case 10:
        if (scene->cel_count > 1)
            cs_scene_remove_cel(scene, c, &e);
        break;
    case 11: {
        const cs_contour *k = &scene->contours[0];
        cs_point p[64];
        memcpy(p, &scene->points[k->first_point], k->point_count * sizeof *p);
        p[0].x += 2.0f;
        cs_scene_set_points(scene, 0, k->point_count, p, NULL, &e);
        break;
    }
    case 13: {
        float base[3] = {0.2f, 0.5f, 0.7f};
        if (scene->has_background)
            add_track(CS_TRACK_BACKGROUND, 0, base, 0.3f);
        break;
    }
    default:
        break;
    }
}

/* The window of o's output into `into` (a whole frame), as a viewport. */
static void render_window(cs_render_opts o, const cs_rect *win, float *into)
{
    cs_renderer r;
    cs_error e;
    static float line[3 * W];
    o.view_x = win->x0;
    o.view_y = win->y0;
    o.view_w = win->x1 - win->x0;
    o.view_h = win->y1 - win->y0;
    CHECK_STATUS(cs_frame_begin(&r, ws, scene, &o, &e), CS_OK, "cs_frame_begin (window)");
    for (int y = 0; y < o.view_h; y++) {
        CHECK_STATUS(cs_render_line(&r, win->y0 + y, line), CS_OK, "cs_render_line (window)");
        memcpy(into + 3 * ((size_t)(win->y0 + y) * W + (size_t)win->x0), line,
               3u * sizeof(float) * (size_t)o.view_w);
    }
}

static int first_diff(void)
{
    for (int i = 0; i < 3 * W * H; i++)
        if (memcmp(&want[i], &have[i], sizeof(float)) != 0)
            return i / 3;
    return -1;
}

static void test_random_sequences(void)
{
    static const struct {
        cs_aa_mode aa;
        int n;
    } modes[] = {{CS_AA_NONE, 1}, {CS_AA_SUBSCAN, 1}, {CS_AA_SUBSCAN, 4}, {CS_AA_SUBSCAN, 5},
                 {CS_AA_SUBSCAN, 16}, {CS_AA_EXACT, 1}};
    int bad_frames = 0, frames = 0, empty_bad = 0, left_bad = 0;
    long long damaged = 0;
    char where[160] = "";
    for (uint64_t seed = 1; seed <= 24; seed++) {
        for (size_t m = 0; m < sizeof modes / sizeof modes[0]; m++) {
            tc_seed(seed * 7919u + m);
            build_scene();
            cs_render_opts o = cs_render_defaults(W, H);
            o.aa = modes[m].aa;
            o.subscanlines = modes[m].n;
            o.blend = seed % 3 == 0 ? CS_BLEND_SRGB : CS_BLEND_LINEAR;
            cs_damage d;
            memset(&d, 0xA5, sizeof d);
            cs_damage_reset(&d);
            for (int f = 0; f < FRAMES; f++) {
                edit(f);
                /* Times 0 .. 1.4 s; frame 3 repeats frame 2's time. */
                o.time = 0.1f * (float)(f == 3 ? 2 : f);
                cs_rect win;
                CHECK_STATUS(cs_frame_damage(&d, scene, &o, &win), CS_OK, "cs_frame_damage");
                if (win.x0 < win.x1 && win.y0 < win.y1) {
                    render_window(o, &win, have);
                    damaged += (long long)(win.x1 - win.x0) * (win.y1 - win.y0);
                }
                bool narrow = o.aa == CS_AA_NONE || (o.aa == CS_AA_SUBSCAN && o.subscanlines != 5);
                if (!narrow && win.x0 < win.x1 && win.x0 != 0)
                    left_bad++;
                if ((f == 3 || f == FRAMES - 1) && win.x0 < win.x1)
                    empty_bad++; /* nothing moves then (frame 15: past every key) */
                cs_render_opts whole = o;
                cs_renderer r;
                cs_error e;
                CHECK_STATUS(cs_frame_begin(&r, ws, scene, &whole, &e), CS_OK, "cs_frame_begin");
                for (int y = 0; y < H; y++)
                    cs_render_line(&r, y, want + 3 * (size_t)y * W);
                frames++;
                int px = first_diff();
                if (px >= 0) {
                    if (bad_frames++ == 0)
                        snprintf(where, sizeof where,
                                 "seed %llu aa %d/%d frame %d pixel (%d, %d), window %d,%d..%d,%d",
                                 (unsigned long long)seed, (int)o.aa, o.subscanlines, f, px % W,
                                 px / W, win.x0, win.y0, win.x1, win.y1);
                    memcpy(have, want, sizeof have); /* go on from the truth */
                }
            }
        }
    }
    CHECK(bad_frames == 0, "%d of %d damaged frames differ from the whole render (first: %s)",
          bad_frames, frames, where);
    CHECK(empty_bad == 0, "%d still frames had a non-empty damage window", empty_bad);
    CHECK(left_bad == 0, "%d windows did not start at column 0 where the AA needs it", left_bad);
    CHECK(damaged < (long long)frames * W * H, "damage covered every pixel of every frame (%lld)",
          damaged);
    printf("  %d frames, %.1f %% of their pixels rendered\n", frames,
           100.0 * (double)damaged / ((double)frames * W * H));
}

static void test_refusals(void)
{
    cs_damage d;
    cs_rect win = {1, 2, 3, 4};
    cs_render_opts o = cs_render_defaults(W, H);
    cs_scene_init(scene, 40.0f, 30.0f);
    cs_damage_reset(&d);
    CHECK_STATUS(cs_frame_damage(NULL, scene, &o, &win), CS_ERR_ARG, "no damage state");
    CHECK_STATUS(cs_frame_damage(&d, NULL, &o, &win), CS_ERR_ARG, "no scene");
    CHECK_STATUS(cs_frame_damage(&d, scene, &o, NULL), CS_ERR_ARG, "no window");
    o.width = 0;
    CHECK_STATUS(cs_frame_damage(&d, scene, &o, &win), CS_ERR_ARG, "width 0");
    o = cs_render_defaults(W, H);
    CHECK_STATUS(cs_frame_damage(&d, scene, &o, &win), CS_OK, "empty scene");
    CHECK(win.x0 == 0 && win.y0 == 0 && win.x1 == W && win.y1 == H,
          "first frame: the whole output, got %d,%d..%d,%d", win.x0, win.y0, win.x1, win.y1);
    CHECK_STATUS(cs_frame_damage(&d, scene, &o, &win), CS_OK, "empty scene again");
    CHECK(win.x0 >= win.x1, "an unchanged empty scene: no damage, got %d,%d..%d,%d", win.x0,
          win.y0, win.x1, win.y1);
    o.height = H - 1;
    CHECK_STATUS(cs_frame_damage(&d, scene, &o, &win), CS_OK, "new size");
    CHECK(win.x1 == W && win.y1 == H - 1, "a new size: the whole output");
}

int main(int argc, char **argv)
{
    (void)argc;
    scene = tl_calloc(1, sizeof *scene);
    ws = tl_calloc(1, sizeof *ws);
    TL_RUN(test_refusals);
    TL_RUN(test_random_sequences);
    free(scene);
    free(ws);
    return tl_summary(argv[0]);
}
