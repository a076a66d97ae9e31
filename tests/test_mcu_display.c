/*
 * test_mcu_display.c - the MCU display backend, run on the host.
 *
 * hal/mcu/mcu_display.c turns rendered lines into panel bytes and keeps a
 * CRC-32 per frame. Checked here against independent truth: the bytes a
 * recording panel receives are hashed with zlib's crc32 and must equal the
 * backend's CRC; the bytes themselves must be the RGB565 little-endian
 * encoding of known colours (black, white, pure primaries, whose codes are
 * exact); the panel (a display of hal/display.h) gets each frame whole or
 * as a window; a failing panel is reported once while the frame and its
 * CRC still complete; bad arguments are refused. A frame may send only a
 * window: the bytes sent, the panel's patched picture and the whole frame's
 * CRC read back are checked the same way; a panel that reads back gets no
 * running CRC (it costs a frame ~5 instructions a byte), one that cannot
 * does. On tests/testlib.h; it ends
 * with `test_mcu_display: N passed, M failed`.
 */
#include <stdio.h>
#include <string.h>
#include <zlib.h>

#include "celscan.h"
#include "mcu_display.h"

#include "testlib.h"

#define W 8
#define H 3

typedef struct recorder {
    hal_display d; /* first: the operations get &r->d */
    uint8_t bytes[H][2 * W];
    int lines, begins, ends;
    int fail_at_line; /* -1: never */
    hal_window last_win;
} recorder;

static hal_status rec_begin(hal_display *d, const hal_window *win)
{
    recorder *r = (recorder *)d;
    r->begins++;
    r->last_win = win ? *win : (hal_window){0, 0, W, H}; /* NULL: the whole glass */
    return !win || (win->x1 <= W && win->y1 <= H) ? HAL_OK : HAL_ERR_CONFIG;
}

static hal_status rec_line(hal_display *d, int y, const uint8_t *px, size_t bytes)
{
    recorder *r = (recorder *)d;
    if (y == r->fail_at_line)
        return HAL_ERR_IO;
    if (y >= 0 && y < H && bytes == sizeof r->bytes[0])
        memcpy(r->bytes[y], px, bytes);
    r->lines++;
    return HAL_OK;
}

static hal_status rec_end(hal_display *d)
{
    ((recorder *)d)->ends++;
    return HAL_OK;
}

static const hal_display_api rec_api = {
    .name = "recorder", .begin_frame = rec_begin, .line_out = rec_line, .end_frame = rec_end};

static uint32_t draw_frame(mcu_display *d);

/* A panel that keeps its picture, as glass does: lines land in the frame's
 * window, and the picture can be read back. */
typedef struct keeper {
    hal_display d; /* first: the operations get &k->d */
    uint8_t picture[H][2 * W];
    int x0, windows;
} keeper;

static hal_status keep_begin(hal_display *d, const hal_window *win)
{
    keeper *k = (keeper *)d;
    k->x0 = win ? win->x0 : 0;
    k->windows += win != NULL;
    return HAL_OK;
}

static hal_status keep_line(hal_display *d, int y, const uint8_t *px, size_t bytes)
{
    keeper *k = (keeper *)d;
    if (y < 0 || y >= H || (size_t)k->x0 * 2u + bytes > sizeof k->picture[0])
        return HAL_ERR_CONFIG;
    memcpy(&k->picture[y][2 * k->x0], px, bytes);
    return HAL_OK;
}

static hal_status keep_read(hal_display *d, int y, uint8_t *buf, size_t bytes)
{
    keeper *k = (keeper *)d;
    if (y < 0 || y >= H || bytes != sizeof k->picture[0])
        return HAL_ERR_CONFIG;
    memcpy(buf, k->picture[y], bytes);
    return HAL_OK;
}

static const hal_display_api keep_api = {
    .name = "keeper", .begin_frame = keep_begin, .line_out = keep_line, .read_row = keep_read};

/*
 * A window of a frame: only its bytes go out (and into the running CRC of
 * a panel that cannot read back), the panel keeps the rest, and the whole
 * frame's CRC read back from the panel is zlib's over the patched picture. A window outside the frame is
 * refused; a panel that refuses a window reports it as a panel error.
 */
static void test_window(void)
{
    keeper k;
    memset(&k, 0, sizeof k);
    k.d = (hal_display){.api = &keep_api, .width = W, .height = H, .pixfmt = CS_PANEL_PIXFMT};
    uint8_t line_bytes[2 * W], row[2 * W];
    mcu_display d;
    mcu_display_init(&d, &k.d, line_bytes);
    draw_frame(&d);
    CHECK(k.windows == 0, "a whole frame set a window");
    uint8_t want[H][2 * W];
    memcpy(want, k.picture, sizeof want);
    /* Frame 2: columns 2..5 of rows 1..2 turn white. */
    float white[3 * W];
    for (int i = 0; i < 3 * W; i++)
        white[i] = 1.0f;
    CHECK(mcu_display_begin(&d, W, H, &(hal_window){2, 1, 6, 3}) == CS_OK, "window refused");
    CHECK(mcu_display_line(&d, 0, white, 4) == CS_ERR_ARG, "a line above the window accepted");
    CHECK(mcu_display_line(&d, 1, white, W) == CS_ERR_ARG, "a line of the frame's width accepted");
    uLong sent = crc32(0L, Z_NULL, 0);
    for (int y = 1; y < 3; y++) {
        CHECK(mcu_display_line(&d, y, white, 4) == CS_OK, "window line %d", y);
        memset(&want[y][4], 0xFF, 8);
        sent = crc32(sent, &want[y][4], 8);
    }
    /* The keeper reads back: no CRC is kept per line. */
    CHECK(mcu_display_end(&d) == 0 && !d.hash, "a panel that reads back had a running CRC");
    CHECK(k.windows == 1 && memcmp(k.picture, want, sizeof want) == 0,
          "the panel's picture is not the last one with the window patched in");
    uint32_t whole = 0;
    uLong ref = crc32(crc32(0L, Z_NULL, 0), &want[0][0], sizeof want);
    CHECK(mcu_display_frame_crc(&d, row, &whole) && whole == (uint32_t)ref,
          "whole frame CRC %08X read back, zlib over the picture %08lX", whole, ref);
    /* An empty window sends nothing and keeps the picture. */
    CHECK(mcu_display_begin(&d, W, H, &(hal_window){0, 0, 0, 0}) == CS_OK, "empty window refused");
    mcu_display_end(&d);
    CHECK(memcmp(k.picture, want, sizeof want) == 0, "an empty window changed the picture");
    CHECK(mcu_display_begin(&d, W, H, &(hal_window){2, 1, W + 1, 3}) == CS_ERR_ARG,
          "window past the right edge");
    CHECK(mcu_display_begin(&d, W, H, &(hal_window){3, 1, 2, 3}) == CS_ERR_ARG,
          "window with x1 < x0");
    /* The recorder refuses windows outside its glass and cannot read back. */
    recorder rec;
    memset(&rec, 0, sizeof rec);
    rec.d = (hal_display){.api = &rec_api, .width = W, .height = H, .pixfmt = CS_PANEL_PIXFMT};
    rec.fail_at_line = -1;
    mcu_display_init(&d, &rec.d, line_bytes);
    mcu_display_begin(&d, W, H, &(hal_window){2, 1, 6, 3});
    for (int y = 1; y < 3; y++)
        mcu_display_line(&d, y, white, 4);
    uint32_t crc = mcu_display_end(&d);
    CHECK(d.hash && crc == (uint32_t)sent, "window CRC %08X, zlib over the bytes sent %08lX", crc,
          sent);
    mcu_display_begin(&d, W + 1, H, &(hal_window){2, 1, W + 1, 3});
    CHECK(d.panel_error != HAL_OK, "a panel took a window outside its glass");
    mcu_display_end(&d);
    CHECK(!mcu_display_frame_crc(&d, row, &whole), "a panel without read_row read back");
}

/* Line y: pixel x is black, white, red, green or blue by (x + y) % 5. */
static void make_line(int y, float *rgb)
{
    static const float colour[5][3] = {{0, 0, 0}, {1, 1, 1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int x = 0; x < W; x++)
        memcpy(&rgb[3 * x], colour[(x + y) % 5], sizeof colour[0]);
}

static uint16_t expected_code(int x, int y)
{
    static const uint16_t code[5] = {0x0000, 0xFFFF, 0xF800, 0x07E0, 0x001F};
    return code[(x + y) % 5];
}

static uint32_t draw_frame(mcu_display *d)
{
    float rgb[3 * W];
    mcu_display_begin(d, W, H, NULL);
    for (int y = 0; y < H; y++) {
        make_line(y, rgb);
        mcu_display_line(d, y, rgb, W);
    }
    return mcu_display_end(d);
}

int main(void)
{
    recorder rec;
    memset(&rec, 0, sizeof rec);
    rec.fail_at_line = -1;
    rec.d = (hal_display){.api = &rec_api, .width = W, .height = H, .pixfmt = CS_PANEL_PIXFMT};
    uint8_t line_bytes[2 * W];
    mcu_display d;
    mcu_display_init(&d, &rec.d, line_bytes);

    uint32_t crc = draw_frame(&d);
    uLong ref = crc32(0L, Z_NULL, 0);
    for (int y = 0; y < H; y++)
        ref = crc32(ref, rec.bytes[y], sizeof rec.bytes[y]);
    CHECK(crc == (uint32_t)ref, "frame CRC %08X, zlib over the panel's bytes %08lX", crc, ref);
    CHECK(rec.begins == 1 && rec.lines == H && rec.ends == 1, "begin %d lines %d end %d",
          rec.begins, rec.lines, rec.ends);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            uint16_t got = (uint16_t)(rec.bytes[y][2 * x] | rec.bytes[y][2 * x + 1] << 8);
            CHECK(got == expected_code(x, y), "pixel %d,%d: %04X, expected %04X", x, y, got,
                  expected_code(x, y));
        }
    CHECK(d.frames == 1 && d.panel_error == HAL_OK, "frames %u error %d", d.frames, d.panel_error);

    /* The same frame again: same CRC, and the panel gets the frame as its window. */
    uint32_t again = draw_frame(&d);
    CHECK(again == crc, "second frame CRC %08X differs from %08X", again, crc);
    CHECK(rec.begins == 2 && rec.last_win.x0 == 0 && rec.last_win.y0 == 0 && rec.last_win.x1 == W &&
              rec.last_win.y1 == H,
          "frame %d: window %d,%d..%d,%d", rec.begins, rec.last_win.x0, rec.last_win.y0, rec.last_win.x1,
          rec.last_win.y1);

    /* A panel failing on line 1: reported, later lines not sent, the frame
     * and its CRC still complete. */
    rec.fail_at_line = 1;
    rec.lines = 0;
    uint32_t broken = draw_frame(&d);
    CHECK(broken == crc, "CRC with a failing panel %08X, expected %08X", broken, crc);
    CHECK(d.panel_error == HAL_ERR_IO, "panel error %d, expected HAL_ERR_IO", d.panel_error);
    CHECK(rec.lines == 1, "%d lines reached the panel after its failure, expected 1", rec.lines);
    rec.fail_at_line = -1;

    /* Bad arguments are refused, not written. */
    float rgb[3 * W];
    make_line(0, rgb);
    CHECK(mcu_display_begin(&d, 0, H, NULL) == CS_ERR_SIZE, "zero width accepted");
    mcu_display_begin(&d, W, H, NULL);
    CHECK(mcu_display_line(&d, H, rgb, W) == CS_ERR_ARG, "line past the bottom accepted");
    CHECK(mcu_display_line(&d, 0, rgb, W + 1) == CS_ERR_ARG, "wrong width accepted");
    mcu_display_end(&d);

    /* No panel at all: the CRC is still kept. */
    mcu_display bare;
    mcu_display_init(&bare, NULL, line_bytes);
    CHECK(draw_frame(&bare) == crc, "CRC without a panel differs");

    test_window();
    return tl_summary("test_mcu_display");
}
