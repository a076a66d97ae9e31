/*
 * test_clock.c - celfw's animation clock (celfw_clock.h) over months of uptime.
 *
 * The clock is injected (a virtual hal_clock, vclock.h) and set to 1 day, 30
 * days and 400 days after boot. Frames are rendered through the same source
 * celfw renders with (lx_scene_source) and compared byte for byte with the
 * frames of a board that has just booted:
 *  - a stream scene (scenes/motion.json: every kind of track, keys 0..3 s)
 *    committed at that uptime plays exactly as one committed at boot;
 *  - one committed at boot and left running shows, months later, exactly
 *    its last-key frame (tracks hold), as it did 1 s after that key;
 *  - the periodic built-in "anim" shows the same positions (the uptimes are
 *    whole periods), where float seconds since start, celfw's old clock,
 *    demonstrably do not at 30 days;
 *  - --clock realtime: two boards with different boot times and commit
 *    times agree frame for frame when they read the same wall clock, and
 *    show the epoch-relative time; before the epoch, the first frame.
 *  - a patch that leaves the tracks alone keeps the animation running; one
 *    that changes a key restarts it.
 */
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "celfw_clock.h"
#include "celfw_scenes.h"
#include "lx_scene_source.h"
#include "scene_json.h"
#include "testlib.h"
#include "vclock.h"

#define W 160
#define H 90
#define DAY (86400ull * 1000000000ull)
#define MS 1000000ull
#define BOOT (7ull * 1000000000ull) /* the monotonic clock's reading at celfw's start */

static cs_scene motion, anim, patched, walled;
static lx_scene_source src;

/* The frame of scene at time t, as celfw's display would get it (RGB565). */
static void frame(const cs_scene *s, float t, uint8_t *out)
{
    float rgb[W * 3];
    lx_scene_source_set(&src, s, t);
    hal_status st = src.src.begin(src.src.user, 1);
    CHECK(st == HAL_OK, "begin: %s", hal_status_str(st));
    for (int y = 0; y < H && st == HAL_OK; y++) {
        st = src.src.line(src.src.user, 0, y, rgb);
        cs_pixfmt_convert(CS_PIX_RGB565_SRGB, rgb, W, out + (size_t)y * W * 2u);
    }
}

/*
 * Plays `s` for `frames` frames of 40 ms with its commit at `commit` on the
 * monotonic clock (celfw started at BOOT), into out (frames * W * H * 2).
 */
static void play(const cs_scene *s, uint64_t commit, int frames, uint64_t period, uint8_t *out)
{
    _Atomic uint64_t mono = BOOT, wall = 0;
    hal_clock m = vclock_make(&mono), w = vclock_make(&wall);
    celfw_clock c;
    celfw_clock_init(&c, &m, &w, false, 0.0);
    celfw_clock_show(&c, NULL, &anim, 0); /* the --scene celfw starts with */
    mono = commit;
    celfw_clock_show(&c, &anim, s, period);
    for (int k = 0; k < frames; k++) {
        mono = commit + (uint64_t)k * 40u * MS;
        frame(s, celfw_clock_frame(&c, s), out + (size_t)k * W * H * 2u);
    }
}

static void test_uptime(void)
{
    enum { N = 90 }; /* 3.6 s: every key of motion.json and past the last */
    size_t fb = (size_t)W * H * 2u;
    uint8_t *at_boot = malloc(N * fb), *later = malloc(N * fb), *one = malloc(fb);
    play(&motion, BOOT, N, 0, at_boot);
    CHECK(memcmp(at_boot, at_boot + 40 * fb, fb) != 0, "the scene moves (frames 0 and 40 differ)");
    static const struct {
        const char *name;
        uint64_t ns;
    } up[] = {{"1 day", DAY}, {"30 days", 30 * DAY}, {"400 days", 400 * DAY}};
    for (size_t i = 0; i < 3; i++) {
        play(&motion, BOOT + up[i].ns, N, 0, later);
        int bad = 0;
        for (int k = 0; k < N; k++)
            bad += memcmp(at_boot + (size_t)k * fb, later + (size_t)k * fb, fb) != 0;
        CHECK(bad == 0, "motion.json committed after %s of uptime: %d of %d frames differ from boot's", up[i].name,
              bad, N);

        /* committed at boot, still running: the last key's frame, as 1 s after it */
        _Atomic uint64_t mono = BOOT, wall = 0;
        hal_clock m = vclock_make(&mono), w = vclock_make(&wall);
        celfw_clock c;
        celfw_clock_init(&c, &m, &w, false, 0.0);
        celfw_clock_show(&c, NULL, &motion, 0);
        mono = BOOT + up[i].ns + 12345;
        float t = celfw_clock_frame(&c, &motion);
        frame(&motion, t, one);
        CHECK(t == 4.0f && memcmp(one, at_boot + 89 * fb, fb) == 0,
              "running since boot, at %s: t=%.9g s, the frame held after the last key", up[i].name, (double)t);

        /* the periodic built-in: the same positions as at boot */
        int moved = 0;
        for (int k = 0; k < 50; k++) {
            celfw_clock_init(&c, &m, &w, false, 0.0);
            mono = BOOT;
            celfw_clock_show(&c, NULL, &anim, celfw_scene_period_ns("anim"));
            mono = BOOT + (uint64_t)k * 40u * MS;
            float t0 = celfw_clock_frame(&c, &anim);
            mono = BOOT + up[i].ns + (uint64_t)k * 40u * MS;
            float t1 = celfw_clock_frame(&c, &anim);
            float x0, y0, x1, y1, xo, yo;
            celfw_anim_disc(t0, &x0, &y0);
            celfw_anim_disc(t1, &x1, &y1);
            /* celfw's old clock: float seconds since start */
            celfw_anim_disc((float)((double)(up[i].ns + (uint64_t)k * 40u * MS) / 1e9), &xo, &yo);
            float bx, by;
            celfw_anim_disc((float)k * 0.04f, &bx, &by);
            moved += xo != bx;
            CHECK(t0 == t1 && x0 == x1, "built-in anim at %s, frame %d: t %.9g vs %.9g", up[i].name, k,
                  (double)t1, (double)t0);
        }
        if (up[i].ns >= 30 * DAY)
            CHECK(moved > 40, "float seconds since start put the disc elsewhere at %s (%d of 50 frames)",
                  up[i].name, moved);
    }
    free(at_boot);
    free(later);
    free(one);
}

static void test_realtime(void)
{
    const uint64_t epoch = 1795000000ull * 1000000000ull; /* a stream's EPOCH, ns since 1970 */
    size_t fb = (size_t)W * H * 2u;
    uint8_t *a = malloc(fb), *b = malloc(fb), *ref = malloc(fb);
    _Atomic uint64_t mono_a = BOOT, mono_b = BOOT + 400 * DAY, wall = epoch - 3 * 1000000000ull;
    hal_clock ma = vclock_make(&mono_a), mb = vclock_make(&mono_b), w = vclock_make(&wall);
    celfw_clock ca, cb;
    celfw_clock_init(&ca, &ma, &w, true, 0.0);
    celfw_clock_init(&cb, &mb, &w, true, 0.0);
    cs_scene_copy(&walled, &motion);
    cs_scene_set_epoch(&walled, epoch);
    celfw_clock_show(&ca, NULL, &walled, 0);
    mono_b += 777 * MS; /* board b got the stream later, and booted long before */
    celfw_clock_show(&cb, NULL, &walled, 0);
    float t = celfw_clock_frame(&ca, &walled);
    CHECK(t == 0.0f, "before the epoch: the first frame (t=%g)", (double)t);
    int bad = 0;
    for (int k = 0; k < 40; k++) {
        wall = epoch + (uint64_t)k * 93u * MS;
        mono_a += 40 * MS;
        mono_b += 40 * MS;
        float ta = celfw_clock_frame(&ca, &walled), tb = celfw_clock_frame(&cb, &walled);
        frame(&motion, ta, a);
        frame(&motion, tb, b);
        frame(&motion, (float)k * 0.093f, ref);
        bad += ta != tb || memcmp(a, b, fb) != 0 || memcmp(a, ref, fb) != 0;
    }
    CHECK(bad == 0, "realtime: two boards agree with each other and the epoch (%d of 40 frames differ)", bad);
    /* a scene without an epoch is timed from its commit */
    celfw_clock_show(&ca, &walled, &anim, 0);
    mono_a += 250 * MS;
    t = celfw_clock_frame(&ca, &anim);
    CHECK(t == 0.25f, "realtime without an epoch: from the commit (t=%.9g)", (double)t);
    free(a);
    free(b);
    free(ref);
}

static void test_patches(void)
{
    _Atomic uint64_t mono = BOOT, wall = 0;
    hal_clock m = vclock_make(&mono), w = vclock_make(&wall);
    celfw_clock c;
    celfw_clock_init(&c, &m, &w, false, 0.0);
    celfw_clock_show(&c, NULL, &motion, 0);
    mono += 1500 * MS;
    cs_scene_copy(&patched, &motion);
    cs_paint p = patched.regions[0].paint;
    p.pigment[0] = 0.5f;
    cs_error e;
    CHECK(cs_scene_set_paint(&patched, 0, (cs_fill_rule)patched.regions[0].fill_rule, &p, &e) == CS_OK, "patch a paint");
    celfw_clock_show(&c, &motion, &patched, 0);
    float t = celfw_clock_frame(&c, &patched);
    CHECK(t == 1.5f, "a paint patch keeps the animation running (t=%.9g)", (double)t);
    cs_scene_copy(&patched, &motion);
    patched.key_times[1] += 0.25f;
    mono += 500 * MS;
    celfw_clock_show(&c, &motion, &patched, 0);
    mono += 100 * MS;
    t = celfw_clock_frame(&c, &patched);
    CHECK(t == 0.1f, "a key change restarts it (t=%.9g)", (double)t);
    /* --time-step: fixed steps from the commit */
    celfw_clock_init(&c, &m, &w, false, 0.04);
    celfw_clock_show(&c, NULL, &motion, 0);
    for (int k = 0; k < 10; k++)
        t = celfw_clock_frame(&c, &motion);
    CHECK(t == 0.36f, "time step: frame 9 at %.9g", (double)t);
}

/* Scene JSON gives the epoch as seconds since 1970 UTC ("canvas": {"epoch": ...}). */
static void test_json_epoch(void)
{
    char path[] = "/tmp/test_clock_XXXXXX";
    int fd = mkstemp(path);
    const char *json = "{\"canvas\": {\"width\": 10, \"height\": 10, \"epoch\": 1795000000.25}, \"cels\": []}";
    CHECK(fd >= 0 && write(fd, json, strlen(json)) == (ssize_t)strlen(json), "write %s", path);
    close(fd);
    static cs_scene s;
    char err[SCENE_JSON_ERRLEN] = "";
    int rc = scene_json_load(path, &s, err, sizeof err);
    uint64_t want = 1795000000250000000ull;
    uint64_t d = s.epoch_ns > want ? s.epoch_ns - want : want - s.epoch_ns;
    CHECK(rc == 0 && d <= 256, "epoch %llu ns (want %llu): %s", (unsigned long long)s.epoch_ns,
          (unsigned long long)want, err);
    fd = open(path, O_WRONLY | O_TRUNC);
    const char *bad = "{\"canvas\": {\"width\": 10, \"height\": 10, \"epoch\": -5}, \"cels\": []}";
    CHECK(write(fd, bad, strlen(bad)) == (ssize_t)strlen(bad), "write");
    close(fd);
    rc = scene_json_load(path, &s, err, sizeof err);
    CHECK(rc != 0 && strstr(err, "epoch") && strstr(err, "seconds since 1970"), "negative epoch refused: %s", err);
    unlink(path);
}

int main(void)
{
    char err[SCENE_JSON_ERRLEN];
    if (scene_json_load("scenes/motion.json", &motion, err, sizeof err) != 0) {
        fprintf(stderr, "test_clock: scenes/motion.json: %s\n", err);
        return 2;
    }
    celfw_scene_build("anim", &anim, 0.0f);
    if (lx_scene_source_init(&src, W, H, CS_AA_SUBSCAN, 4) != HAL_OK)
        return 2;
    test_uptime();
    test_realtime();
    test_patches();
    test_json_epoch();
    lx_scene_source_free(&src);
    return tl_summary("test_clock");
}
