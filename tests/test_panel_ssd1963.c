/*
 * test_panel_ssd1963.c - the MCU's SSD1963 panel (hal/mcu/panel_ssd1963.c)
 * passes the display conformance case on the host.
 *
 * The driver is compiled for the host with its bus writes routed into a
 * model of the controller (tests/ssd1963_model.c, from the datasheet's
 * command set), whose frame memory is what the glass shows. On it: the
 * set-up sequence leaves the controller in the modelled state with no
 * fault; the conformance frames show the CRC of the core's render at the
 * module's 480x272 and at an odd 97x41; a window changes only its pixels
 * and only its pixels cross the bus, also with rows skipped; the firmware's
 * own path (mcu_display, which CRCs what it sends) shows a frame whose
 * memory CRC equals the CRC the firmware prints; out-of-order calls, a bad
 * window and a line of another width are refused by status (an MCU panel
 * has no room for messages) and leave the picture alone.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "testlib.h"

#include "display_conformance.h"
#include "mcu_display.h"
#include "panel_ssd1963.h"
#include "ssd1963_model.h"

#define FILL 0xF81Fu /* magenta: the controller's memory before the first frame */

typedef struct rig {
    ssd_model m;
    panel_ssd1963 p;
} rig;

static ssd_model *delay_model; /* the driver's delay_us has no user pointer: the one model being set up */

static void rig_delay(uint32_t us)
{
    ssd_model_wait(delay_model, us);
}

static bool rig_open(rig *r, int w, int h)
{
    memset(r, 0, sizeof *r);
    if (!CHECK(ssd_model_init(&r->m, w, h, FILL), "model %dx%d", w, h))
        return false;
    ssd_model_attach(&r->m, &r->p.cmd, &r->p.data);
    r->p.delay_us = rig_delay;
    delay_model = &r->m;
    panel_ssd1963_init(&r->p, w, h);
    return CHECK(!r->m.fault[0] && r->m.pll_locked && r->m.mode_set && r->m.display_on &&
                     r->m.pixel_interface == 3,
                 "%dx%d set-up: '%s', PLL locked %d, display on %d", w, h, r->m.fault, r->m.pll_locked,
                 r->m.display_on);
}

static void rig_close(rig *r)
{
    if (r->p.d.api)
        hal_display_close(&r->p.d);
    ssd_model_free(&r->m);
}

/* What the glass shows, as RGB565 little-endian rows (the panel format). */
static bool model_shown(void *user, uint8_t *frame)
{
    const ssd_model *m = user;
    if (!m->display_on)
        return false;
    for (size_t i = 0; i < (size_t)m->width * (size_t)m->height; i++) {
        frame[2 * i] = (uint8_t)m->frame[i];
        frame[2 * i + 1] = (uint8_t)(m->frame[i] >> 8);
    }
    return true;
}

static void test_conformance(void)
{
    static const int sizes[2][2] = {{480, 272}, {97, 41}};
    for (int k = 0; k < 2; k++) {
        rig r;
        char name[48];
        snprintf(name, sizeof name, "ssd1963 %dx%d", sizes[k][0], sizes[k][1]);
        if (rig_open(&r, sizes[k][0], sizes[k][1])) {
            conf_backend b = {.d = &r.p.d, .shown = model_shown, .user = &r.m};
            conf_frames(&b, name);
            conf_geometry_error(&b, name);
            long px = r.m.pixels;
            /* a window inside, one at the glass's corner (the high address bytes), a single pixel */
            const int w = sizes[k][0], h = sizes[k][1];
            const hal_window wins[3] = {{10, 20, 50, 30}, {w - 40, h - 9, w, h}, {3, 4, 4, 5}};
            long want = 0;
            for (int i = 0; i < 3; i++)
                want += (long)conf_window(&b, name, wins[i]) * (wins[i].x1 - wins[i].x0);
            CHECK(want > 0 && r.m.pixels - px == want && !r.m.fault[0],
                  "%s: %ld pixels crossed the bus for windows of %ld: '%s'", name, r.m.pixels - px, want,
                  r.m.fault);
        }
        rig_close(&r);
    }
}

/* The firmware's path: mcu_display sends a rendered frame and returns the CRC it prints. */
static void test_firmware_path(void)
{
    enum { FW = 97, FH = 41 };
    rig r;
    static cs_scene scene;
    static cs_workspace ws;
    if (!rig_open(&r, FW, FH) || !conf_load("scenes/demo.json", &scene)) {
        rig_close(&r);
        return;
    }
    uint8_t px[2 * FW], shown[2 * FW * FH];
    float rgb[3 * FW];
    mcu_display md;
    mcu_display_init(&md, &r.p.d, px);
    cs_render_opts o = cs_render_defaults(FW, FH);
    cs_renderer ren;
    cs_error e;
    TL_MUST(cs_frame_begin(&ren, &ws, &scene, &o, &e));
    mcu_display_begin(&md, FW, FH, NULL);
    for (int y = 0; y < FH; y++) {
        cs_render_line(&ren, y, rgb);
        mcu_display_line(&md, y, rgb, FW);
    }
    uint32_t crc = mcu_display_end(&md);
    bool read = model_shown(&r.m, shown);
    CHECK(read && md.panel_error == HAL_OK && cs_crc32(0, shown, sizeof shown) == crc && !r.m.fault[0],
          "mcu_display's crc32 %08X, the glass's %08X (panel %s, model '%s')", (unsigned)crc,
          (unsigned)cs_crc32(0, shown, sizeof shown), hal_status_str(md.panel_error), r.m.fault);
    rig_close(&r);
}

/* Refused calls (and an empty window): by status, with nothing on the bus and the picture
 * unchanged. */
static void test_refusals(void)
{
    enum { RW = 64, RH = 32 };
    rig r;
    if (!rig_open(&r, RW, RH)) {
        rig_close(&r);
        return;
    }
    hal_display *d = &r.p.d;
    uint8_t line[2 * RW];
    memset(line, 0x11, sizeof line);
    long px = r.m.pixels;
    const hal_window outside = {0, 10, RW + 1, 20}, empty = {5, 5, 5, 9}, negative = {-1, 0, 8, 8};
    CHECK(hal_display_begin_frame(d, &outside) == HAL_ERR_CONFIG, "window wider than the glass");
    /* An empty window is a frame where nothing changed: taken, and no line may come. */
    CHECK(hal_display_begin_frame(d, &empty) == HAL_OK, "empty window refused");
    CHECK(hal_display_line_out(d, 5, line, 0) == HAL_ERR_SEQUENCE, "a line in an empty window");
    CHECK(hal_display_end_frame(d) == HAL_OK, "end of the empty frame");
    CHECK(hal_display_begin_frame(d, &negative) == HAL_ERR_CONFIG, "window left of the glass");
    CHECK(hal_display_line_out(d, 0, line, sizeof line) == HAL_ERR_SEQUENCE, "a line before any frame");
    CHECK(hal_display_begin_frame(d, NULL) == HAL_OK, "begin");
    CHECK(hal_display_line_out(d, 5, line, sizeof line) == HAL_OK, "line 5");
    CHECK(hal_display_line_out(d, 5, line, sizeof line) == HAL_ERR_SEQUENCE, "line 5 twice");
    CHECK(hal_display_line_out(d, 4, line, sizeof line) == HAL_ERR_SEQUENCE, "line 4 after 5");
    CHECK(hal_display_line_out(d, RH, line, sizeof line) == HAL_ERR_SEQUENCE, "line %d past the end", RH);
    CHECK(hal_display_line_out(d, 6, line, sizeof line - 2) == HAL_ERR_CONFIG, "a line one pixel short");
    CHECK(hal_display_end_frame(d) == HAL_OK, "end");
    CHECK(hal_display_line_out(d, 7, line, sizeof line) == HAL_ERR_SEQUENCE, "a line after the frame");
    int changed = 0, wrong = 0;
    for (int y = 0; y < RH; y++)
        for (int x = 0; x < RW; x++) {
            uint16_t v = r.m.frame[y * RW + x];
            changed += v != FILL;
            wrong += y == 5 ? v != 0x1111 : v != FILL;
        }
    CHECK(r.m.pixels - px == RW && changed == RW && wrong == 0 && !r.m.fault[0],
          "only line 5 was written: %ld pixels on the bus, %d changed, %d wrong, model '%s'", r.m.pixels - px,
          changed, wrong, r.m.fault);
    rig_close(&r);
}

/* The model itself catches what the datasheet forbids (so its silence above means something). */
static void test_model_faults(void)
{
    rig r;
    if (!rig_open(&r, 16, 8)) {
        rig_close(&r);
        return;
    }
    volatile uint16_t *cmd = r.p.cmd, *data = r.p.data;
    const uint16_t col[4] = {0, 0, 0, 16}; /* columns 0..16 on a 16-wide glass */
    SSD1963_BUS_WRITE(cmd, 0x2A);
    for (int i = 0; i < 4; i++)
        SSD1963_BUS_WRITE(data, col[i]);
    CHECK(strstr(r.m.fault, "beyond the glass"), "column beyond the glass: '%s'", r.m.fault);
    r.m.fault[0] = 0;
    SSD1963_BUS_WRITE(cmd, 0x2C);
    for (int i = 0; i < 16 * 8 + 1; i++)
        SSD1963_BUS_WRITE(data, 0);
    CHECK(strstr(r.m.fault, "past the window's last page"), "a pixel too many: '%s'", r.m.fault);
    r.m.fault[0] = 0;
    SSD1963_BUS_WRITE(cmd, 0x36);
    SSD1963_BUS_WRITE(data, 0x100);
    CHECK(strstr(r.m.fault, "8 bits"), "a 16-bit parameter: '%s'", r.m.fault);
    r.m.fault[0] = 0;
    SSD1963_BUS_WRITE(cmd, 0x01);
    SSD1963_BUS_WRITE(cmd, 0x29);
    CHECK(strstr(r.m.fault, "5 ms"), "a command right after a soft reset: '%s'", r.m.fault);
    r.m.fault[0] = 0;
    ssd_model_wait(&r.m, 5000);
    SSD1963_BUS_WRITE(cmd, 0x2C);
    CHECK(strstr(r.m.fault, "before the PLL is locked, the panel mode set"), "memory write after a reset: '%s'",
          r.m.fault);
    rig_close(&r);
}

int main(void)
{
    TL_RUN(test_conformance);
    TL_RUN(test_firmware_path);
    TL_RUN(test_refusals);
    TL_RUN(test_model_faults);
    return tl_summary("test_panel_ssd1963");
}
