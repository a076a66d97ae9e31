/*
 * test_hub75.c - the HUB75 backend against an emulated GPIO chip.
 *
 * Runs under umockdev (make test-linuxhal does LD_PRELOAD): the real
 * libgpiod talks to fake_gpiochip through the kernel's GPIO v1 ioctls. The
 * recorded wire changes go through hub75_model, a panel simulation that
 * knows nothing of the driver, and the image it decodes must equal the
 * scene rendered directly with the core in this test (one renderer, lines
 * in order), quantised to the panel's bit depth. The display conformance
 * case (display_conformance.h) runs on the same rig: HUB75 is the pull lane.
 */
#include <errno.h>
#include <fcntl.h>
#include <gpiod.h>
#include <linux/gpio.h>
#include <sys/ioctl.h>
#include <sys/syscall.h>
#include <unistd.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "celfw_scenes.h"
#include "fake_gpiochip.h"
#include "hub75.h"
#include "hub75_model.h"
#include "lx_scene_source.h"
#include "testlib.h"

#include "display_conformance.h"
#include "vclock.h"

static _Atomic uint64_t vtime;
static cs_scene scene;

/* The panel's "format": each channel quantised to `planes` bits of linear light, as 16-bit words. */
static void hub75_encode(const void *user, const float *rgb, int width, uint8_t *dst)
{
    const hub75_config *c = user;
    float max = (float)((1u << c->planes) - 1u);
    for (int i = 0; i < 3 * width; i++) {
        uint16_t v = (uint16_t)floorf(fminf(fmaxf(rgb[i], 0.0f), 1.0f) * max + 0.5f);
        memcpy(dst + 2 * i, &v, 2);
    }
}

/* The truth (the conformance reference, display_conformance.h) as levels of c->planes bits. */
static uint16_t *expected_levels(const cs_scene *s, const hub75_config *c, int w, int h)
{
    uint8_t *img = conf_reference_image(s, 0.0f, w, h, (size_t)w * 6u, hub75_encode, c);
    if (!img)
        abort(); /* out of memory or an unrenderable test scene: nothing to compare with */
    return (uint16_t *)(void *)img;
}

typedef struct run_result {
    int mismatches, dark_rows;
    int first_x, first_y;
    uint64_t writes, set_calls;
    hub75_model m;
} run_result;

/* Shows one frame of `s` on an open panel and decodes it with the model. */
static void run_frame(hal_display *d, fake_gpiochip *chip, const hub75_config *c, const cs_scene *s,
                      run_result *res)
{
    int w = c->panel_w * c->chain, h = c->panel_h;
    lx_scene_source src;
    CHECK(lx_scene_source_init(&src, w, h, CS_AA_SUBSCAN, 4) == HAL_OK, "source init");
    lx_scene_source_set(&src, s, 0.0f);
    uint64_t wires0 = fake_gpiochip_wires(chip);
    unsigned sets0 = fake_gpiochip_count(chip, FAKE_GPIO_SET);
    fake_gpiochip_clear_trace(chip);
    hal_frame_stats st = {0};
    hal_status ps = hal_display_present(d, &src.src, &st);
    CHECK(ps == HAL_OK, "present: %s (%s)", hal_status_str(ps), d->err);

    const fake_gpio_event *ev;
    size_t n = fake_gpiochip_trace(chip, &ev);
    hub75_model_init(&res->m, c, wires0);
    for (size_t i = 0; i < n; i++)
        hub75_model_feed(&res->m, &ev[i]);
    uint16_t *got = calloc((size_t)w * (size_t)h * 3u, sizeof *got);
    res->dark_rows = hub75_model_image(&res->m, c->planes, got);
    uint16_t *want = expected_levels(s, c, w, h);
    res->mismatches = 0;
    res->first_x = res->first_y = -1;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int k = 0; k < 3; k++) {
                size_t i = ((size_t)y * (size_t)w + (size_t)x) * 3u + (size_t)k;
                if (got[i] != want[i]) {
                    if (res->mismatches++ == 0) {
                        res->first_x = x;
                        res->first_y = y;
                        fprintf(stderr, "  first mismatch at (%d,%d) ch %d: panel %u, renderer %u\n", x,
                                y, k, got[i], want[i]);
                    }
                }
            }
    res->writes = st.writes;
    res->set_calls = fake_gpiochip_count(chip, FAKE_GPIO_SET) - sets0;
    free(got);
    free(want);
    lx_scene_source_free(&src);
}

/* Every row pair shows planes 0..P-1 for lsb * 2^b, in that order, once. */
static int check_pulses(const hub75_model *m, const hub75_config *c)
{
    int bad = 0;
    size_t expect = (size_t)hub75_scan(c) * (size_t)c->planes;
    if (m->npulses != expect)
        return -1;
    for (size_t i = 0; i < m->npulses; i++) {
        int r = (int)(i / (size_t)c->planes), b = (int)(i % (size_t)c->planes);
        if (m->pulses[i].row_pair != r || m->pulses[i].duration != ((uint64_t)c->lsb_ns << b))
            bad++;
    }
    return bad;
}

static void test_frame(UMockdevTestbed *tb, const char *what, int chipno, int pw, int ph, int chain,
                       int planes, const char *scene_name, float t)
{
    fake_gpiochip *chip = fake_gpiochip_add(tb, chipno, 28, "pinctrl-fake", &vtime, 100);
    hub75_config c;
    hub75_config_default(&c);
    c.panel_w = pw;
    c.panel_h = ph;
    c.chain = chain;
    c.planes = planes;
    c.lsb_ns = 150;
    snprintf(c.chip, sizeof c.chip, "/dev/gpiochip%d", chipno);
    hal_clock clk = vclock_make(&vtime);
    hal_display *d = NULL;
    char err[256] = "";
    hal_status s = hub75_open(&d, &c, &clk, err, sizeof err);
    CHECK(s == HAL_OK, "%s: open: %s", what, err);
    if (s != HAL_OK) {
        fake_gpiochip_free(chip);
        return;
    }
    char consumer[32] = "";
    CHECK(fake_gpiochip_requested(chip, (unsigned)c.pins.pin[HUB75_CLK], consumer, sizeof consumer) &&
              strcmp(consumer, "celfw-hub75") == 0,
          "%s: CLK line requested by celfw (consumer '%s')", what, consumer);
    CHECK((fake_gpiochip_wires(chip) >> c.pins.pin[HUB75_OE]) & 1u, "%s: panel starts dark (OE high)",
          what);

    CHECK(celfw_scene_build(scene_name, &scene, t), "scene %s", scene_name);
    run_result r;
    run_frame(d, chip, &c, &scene, &r);
    int w = pw * chain;
    CHECK(r.mismatches == 0, "%s: %d channel values differ from the renderer's", what, r.mismatches);
    CHECK(r.dark_rows == 0, "%s: %d row pairs never lit", what, r.dark_rows);
    CHECK(r.m.setup_violations == 0 && r.m.clock_while_latched == 0 && r.m.ghost_changes == 0,
          "%s: protocol: %llu setup, %llu clock-in-latch, %llu ghost", what,
          (unsigned long long)r.m.setup_violations, (unsigned long long)r.m.clock_while_latched,
          (unsigned long long)r.m.ghost_changes);
    CHECK(r.m.clock_edges == (uint64_t)hub75_scan(&c) * (uint64_t)planes * (uint64_t)w,
          "%s: %llu clock edges, expected scan*planes*width", what,
          (unsigned long long)r.m.clock_edges);
    CHECK(r.m.latches == (uint64_t)hub75_scan(&c) * (uint64_t)planes, "%s: %llu latches", what,
          (unsigned long long)r.m.latches);
    int bad = check_pulses(&r.m, &c);
    CHECK(bad == 0, "%s: %d OE pulses off the lsb*2^b pattern (%zu pulses)", what, bad, r.m.npulses);
    CHECK(r.writes == r.set_calls, "%s: driver counted %llu writes, chip saw %llu", what,
          (unsigned long long)r.writes, (unsigned long long)r.set_calls);
    CHECK(r.writes <= hub75_writes_per_frame(&c), "%s: %llu writes > bound %llu", what,
          (unsigned long long)r.writes, (unsigned long long)hub75_writes_per_frame(&c));
    printf("%s: %dx%d (%d x %dx%d), %d planes: %llu bulk writes/frame, image matches: %s\n", what, w,
           ph, chain, pw, ph, planes, (unsigned long long)r.writes, r.mismatches ? "no" : "yes");
    hub75_model_free(&r.m);

    hal_display_close(d);
    /* close(2) of the handle reaches the emulation asynchronously */
    for (int i = 0; i < 200 && fake_gpiochip_handles(chip); i++)
        g_usleep(5000);
    CHECK(fake_gpiochip_handles(chip) == 0, "%s: line handle closed", what);
    CHECK(!fake_gpiochip_requested(chip, (unsigned)c.pins.pin[HUB75_CLK], NULL, 0),
          "%s: lines released on close", what);
    CHECK((fake_gpiochip_wires(chip) >> c.pins.pin[HUB75_OE]) & 1u, "%s: panel left dark", what);
    fake_gpiochip_free(chip);
}

/* The libgpiod v1 pitfall, shown against the kernel semantics of the fake:
 * gpiod_line_set_value() on the third line of a bulk request drives the first. */
static void test_bulk_pitfall(UMockdevTestbed *tb)
{
    fake_gpiochip *chip = fake_gpiochip_add(tb, 10, 28, "pitfall", &vtime, 0);
    struct gpiod_chip *gc = gpiod_chip_open("/dev/gpiochip10");
    CHECK(gc != NULL, "open chip: %s", strerror(errno));
    unsigned offs[3] = {5, 13, 6};
    int zero[3] = {0, 0, 0};
    struct gpiod_line_bulk bulk;
    CHECK(gpiod_chip_get_lines(gc, offs, 3, &bulk) == 0, "get lines");
    CHECK(gpiod_line_request_bulk_output(&bulk, "pitfall", zero) == 0, "request");
    struct gpiod_line *third = gpiod_line_bulk_get_line(&bulk, 2);
    CHECK(gpiod_line_set_value(third, 1) == 0, "set_value");
    uint64_t w = fake_gpiochip_wires(chip);
    CHECK(((w >> 5) & 1u) == 1 && ((w >> 6) & 1u) == 0,
          "set_value(line 6) of a bulk request drove line 5 (wires %#llx)", (unsigned long long)w);
    int v[3] = {0, 0, 1};
    CHECK(gpiod_line_set_value_bulk(&bulk, v) == 0, "set_value_bulk");
    w = fake_gpiochip_wires(chip);
    CHECK(((w >> 5) & 1u) == 0 && ((w >> 6) & 1u) == 1, "set_value_bulk drives line 6");
    int got[3] = {-1, -1, -1};
    CHECK(gpiod_line_get_value_bulk(&bulk, got) == 0 && got[0] == 0 && got[1] == 0 && got[2] == 1,
          "get_value_bulk reads back 0 0 1 (got %d %d %d)", got[0], got[1], got[2]);
    struct gpiod_line *l6 = gpiod_chip_get_line(gc, 6);
    CHECK(gpiod_line_update(l6) == 0 && gpiod_line_is_used(l6) &&
              gpiod_line_direction(l6) == GPIOD_LINE_DIRECTION_OUTPUT &&
              strcmp(gpiod_line_consumer(l6), "pitfall") == 0,
          "line info: used, output, consumer 'pitfall'");
    /* kernel semantics: a second request of a taken line is EBUSY */
    struct gpiod_line *l13 = gpiod_chip_get_line(gc, 13);
    errno = 0;
    CHECK(gpiod_line_request_output(l13, "other", 0) != 0 && errno == EBUSY, "EBUSY on a taken line");
    gpiod_line_release_bulk(&bulk);
    gpiod_chip_close(gc);
    fake_gpiochip_free(chip);
}

static void test_errors(UMockdevTestbed *tb)
{
    hub75_config c;
    char err[256];
    hal_display *d = NULL;
    hal_clock clk = vclock_make(&vtime);

    hub75_config_default(&c);
    snprintf(c.chip, sizeof c.chip, "/dev/gpiochip9");
    err[0] = 0;
    CHECK(hub75_open(&d, &c, &clk, err, sizeof err) == HAL_ERR_NO_DEVICE && strstr(err, "/dev/gpiochip9"),
          "missing chip: '%s'", err);

    fake_gpiochip *small = fake_gpiochip_add(tb, 11, 20, "small", &vtime, 0);
    hub75_config_default(&c);
    snprintf(c.chip, sizeof c.chip, "/dev/gpiochip11");
    err[0] = 0;
    CHECK(hub75_open(&d, &c, &clk, err, sizeof err) == HAL_ERR_CONFIG && strstr(err, "lines 0..19"),
          "pin beyond chip: '%s'", err);
    fake_gpiochip_free(small);

    fake_gpiochip *busy = fake_gpiochip_add(tb, 12, 28, "busy", &vtime, 0);
    fake_gpiochip_hold(busy, 21, "spi0 CS");
    hub75_config_default(&c);
    snprintf(c.chip, sizeof c.chip, "/dev/gpiochip12");
    err[0] = 0;
    CHECK(hub75_open(&d, &c, &clk, err, sizeof err) != HAL_OK && strstr(err, "Device or resource busy") &&
              strstr(err, "spi0 CS"),
          "busy line: '%s'", err);
    CHECK(!fake_gpiochip_requested(busy, 17, NULL, 0), "nothing taken after EBUSY");
    fake_gpiochip_free(busy);

    hub75_config_default(&c);
    c.panel_h = 64;
    c.pins.pin[HUB75_E] = -1;
    CHECK(hub75_config_check(&c, err, sizeof err) == HAL_ERR_CONFIG && strstr(err, "pin e"),
          "1/32 scan without E: '%s'", err);
    hub75_config_default(&c);
    c.pins.pin[HUB75_LAT] = c.pins.pin[HUB75_CLK];
    CHECK(hub75_config_check(&c, err, sizeof err) == HAL_ERR_CONFIG && strstr(err, "both line"),
          "duplicate pins: '%s'", err);
    hub75_config_default(&c);
    c.panel_h = 48;
    CHECK(hub75_config_check(&c, err, sizeof err) == HAL_ERR_CONFIG && strstr(err, "48"),
          "odd height: '%s'", err);
    hub75_config_default(&c);
    c.planes = 13;
    CHECK(hub75_config_check(&c, err, sizeof err) == HAL_ERR_CONFIG, "13 planes: '%s'", err);
}

/*
 * The cheapest a character-device write can be on this host: an ioctl the
 * kernel turns down at once (GPIOHANDLE_SET_LINE_VALUES on /dev/null). A real
 * GPIO write adds gpiolib and the pin controller on top. syscall(2) goes
 * around umockdev's ioctl wrapper, which would otherwise dominate.
 */
static double syscall_floor_ns(void)
{
    int fd = open("/dev/null", O_RDONLY);
    struct gpiohandle_data hd;
    memset(&hd, 0, sizeof hd);
    const int n = 200000;
    hal_clock clk = hal_clock_monotonic;
    uint64_t t0 = hal_now(&clk);
    for (int i = 0; i < n; i++)
        (void)syscall(SYS_ioctl, fd, GPIOHANDLE_SET_LINE_VALUES_IOCTL, &hd);
    uint64_t t1 = hal_now(&clk);
    close(fd);
    return (double)(t1 - t0) / n;
}

static void estimate(const char *what, int pw, int ph, int chain, int planes, double wns)
{
    hub75_config c;
    hub75_config_default(&c);
    c.panel_w = pw;
    c.panel_h = ph;
    c.chain = chain;
    c.planes = planes;
    printf("hub75 estimate: %-9s %3dx%-2d chain %d, %2d planes, lsb %u ns: %7llu writes/frame -> %7.1f Hz\n",
           what, pw, ph, chain, planes, c.lsb_ns, (unsigned long long)hub75_writes_per_frame(&c),
           hub75_refresh_estimate(&c, wns));
}

/* Write throughput through the emulated chip, and what it would mean. */
static void report_throughput(UMockdevTestbed *tb)
{
    fake_gpiochip *chip = fake_gpiochip_add(tb, 13, 28, "bench", NULL, 0);
    hub75_config c;
    hub75_config_default(&c);
    snprintf(c.chip, sizeof c.chip, "/dev/gpiochip13");
    hal_display *d = NULL;
    char err[256];
    if (hub75_open(&d, &c, &hal_clock_monotonic, err, sizeof err) == HAL_OK) {
        double wps = hub75_measure_writes(d, 4000);
        printf("hub75: emulated chip (umockdev socket round trip): %.0f bulk writes/s = %.2f us/write\n",
               wps, 1e6 / wps);
        hal_display_close(d);
    }
    fake_gpiochip_free(chip);
    /* what the drive sequence allows at a given cost per write */
    double floor = syscall_floor_ns();
    printf("hub75: syscall floor on this host (ioctl turned down by the kernel): %.0f ns\n", floor);
    const double per_write[3] = {floor, 1000.0, 2000.0};
    const char *label[3] = {"floor", "1us/wr", "2us/wr"};
    for (int i = 0; i < 3; i++) {
        estimate(label[i], 64, 32, 1, 8, per_write[i]);
        estimate(label[i], 64, 32, 1, 11, per_write[i]);
        estimate(label[i], 64, 64, 1, 8, per_write[i]);
        estimate(label[i], 64, 32, 2, 8, per_write[i]);
    }
}

/* The conformance rig: the chip's trace since the last frame read, decoded by the panel model. */
typedef struct conf_rig {
    fake_gpiochip *chip;
    hub75_config c;
    uint64_t wires0;
} conf_rig;

static bool hub75_shown(void *user, uint8_t *frame)
{
    conf_rig *r = user;
    const fake_gpio_event *ev;
    size_t n = fake_gpiochip_trace(r->chip, &ev);
    hub75_model m;
    hub75_model_init(&m, &r->c, r->wires0);
    for (size_t i = 0; i < n; i++)
        hub75_model_feed(&m, &ev[i]);
    int dark = hub75_model_image(&m, r->c.planes, (uint16_t *)(void *)frame);
    hub75_model_free(&m);
    r->wires0 = fake_gpiochip_wires(r->chip);
    fake_gpiochip_clear_trace(r->chip);
    return dark == 0;
}

/* The chip's line writes fail (EIO) for the next frame's first row pair. */
static void hub75_fail_writes(void *user)
{
    fake_gpiochip_fail_sets(((conf_rig *)user)->chip, 1, EIO);
}

/* The conformance case every backend passes, through the pull lane. */
static void test_conformance(UMockdevTestbed *tb)
{
    conf_rig r;
    r.chip = fake_gpiochip_add(tb, 7, 28, "pinctrl-fake", &vtime, 100);
    hub75_config_default(&r.c);
    r.c.panel_w = 64;
    r.c.panel_h = 32;
    r.c.planes = 6;
    r.c.lsb_ns = 150;
    snprintf(r.c.chip, sizeof r.c.chip, "/dev/gpiochip7");
    hal_clock clk = vclock_make(&vtime);
    hal_display *d = NULL;
    char err[256] = "";
    hal_status s = hub75_open(&d, &r.c, &clk, err, sizeof err);
    if (CHECK(s == HAL_OK, "conformance open: %s", err)) {
        r.wires0 = fake_gpiochip_wires(r.chip);
        fake_gpiochip_clear_trace(r.chip);
        conf_backend b = {.d = d, .line_bytes = 64u * 3u * 2u, .encode = hub75_encode, .encode_user = &r.c,
                          .shown = hub75_shown, .user = &r};
        conf_frames(&b, "gpio HUB75");
        conf_geometry_error(&b, "gpio HUB75");
        CHECK(!strcmp(d->err, "hub75: source is 65x32, the panel chain is 64x32"), "HUB75's words: '%s'", d->err);
        conf_failed_write(&b, "gpio HUB75", hub75_fail_writes, "writing GPIO lines on /dev/gpiochip7 failed");
        hal_display_close(d);
        for (int i = 0; i < 200 && fake_gpiochip_handles(r.chip); i++)
            g_usleep(5000);
    }
    fake_gpiochip_free(r.chip);
}

int main(void)
{
    UMockdevTestbed *tb = umockdev_testbed_new();
    if (!umockdev_in_mock_environment()) {
        fprintf(stderr, "test_hub75: run under umockdev-wrapper (LD_PRELOAD=libumockdev-preload.so)\n");
        return 2;
    }
    test_frame(tb, "demo 64x32 1/16", 0, 64, 32, 1, 8, "demo", 0.0f);
    test_frame(tb, "anim t=0.3 64x32", 1, 64, 32, 1, 6, "anim", 0.3f);
    test_frame(tb, "anim t=1.1 64x32", 2, 64, 32, 1, 6, "anim", 1.1f);
    test_frame(tb, "chain 2x 32x32", 3, 32, 32, 2, 5, "demo", 0.0f);
    test_frame(tb, "64x64 1/32", 4, 64, 64, 1, 4, "bars", 0.0f);
    test_bulk_pitfall(tb);
    test_errors(tb);
    test_conformance(tb);
    report_throughput(tb);
    g_object_unref(tb);
    return tl_summary("test_hub75");
}
