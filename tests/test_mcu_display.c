/*
 * test_mcu_display.c - the MCU display backend, run on the host.
 *
 * hal/mcu/mcu_display.c turns rendered lines into panel bytes and keeps a
 * CRC-32 per frame. Checked here against independent truth: the bytes a
 * recording panel receives are hashed with zlib's crc32 and must equal the
 * backend's CRC; the bytes themselves must be the RGB565 little-endian
 * encoding of known colours (black, white, pure primaries, whose codes are
 * exact); a failing panel is reported once while the frame and its CRC
 * still complete; bad arguments are refused. A frame may send only a
 * window: the bytes sent, the panel's patched picture and the whole frame's
 * CRC read back are checked the same way. On tests/testlib.h; it ends
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
    uint8_t bytes[H][2 * W];
    int lines, begins, ends;
    int fail_at_line; /* -1: never */
    uint32_t last_frame;
} recorder;

static int rec_begin(void *ctx, uint32_t frame, int width, int height)
{
    recorder *r = ctx;
    r->begins++;
    r->last_frame = frame;
    return width == W && height == H ? 0 : -1;
}

static int rec_line(void *ctx, int y, const uint8_t *px, size_t bytes)
{
    recorder *r = ctx;
    if (y == r->fail_at_line)
        return -5;
    if (y >= 0 && y < H && bytes == sizeof r->bytes[0])
        memcpy(r->bytes[y], px, bytes);
    r->lines++;
    return 0;
}

static int rec_end(void *ctx)
{
    ((recorder *)ctx)->ends++;
    return 0;
}

static const mcu_panel_api rec_api = {rec_begin, rec_line, rec_end, 0, 0};

static uint32_t draw_frame(mcu_display *d);

/* A panel that keeps its picture, as glass does: lines land in the window
 * last set, and the picture can be read back. */
typedef struct keeper {
    uint8_t picture[H][2 * W];
    int x0, windows;
} keeper;

static int keep_begin(void *ctx, uint32_t frame, int width, int height)
{
    (void)frame;
    ((keeper *)ctx)->x0 = 0;
    return width == W && height == H ? 0 : -1;
}

static int keep_line(void *ctx, int y, const uint8_t *px, size_t bytes)
{
    keeper *k = ctx;
    if (y < 0 || y >= H || (size_t)k->x0 * 2u + bytes > sizeof k->picture[0])
        return -1;
    memcpy(&k->picture[y][2 * k->x0], px, bytes);
    return 0;
}

static int keep_window(void *ctx, int x0, int y0, int x1, int y1)
{
    keeper *k = ctx;
    (void)y0, (void)x1, (void)y1;
    k->x0 = x0;
    k->windows++;
    return 0;
}

static int keep_read(void *ctx, int y, uint8_t *buf, size_t bytes)
{
    keeper *k = ctx;
    if (y < 0 || y >= H || bytes != sizeof k->picture[0])
        return -1;
    memcpy(buf, k->picture[y], bytes);
    return 0;
}

static const mcu_panel_api keep_api = {keep_begin, keep_line, 0, keep_window, keep_read};

/*
 * A window of a frame: only its bytes go out (and into the running CRC),
 * the panel keeps the rest, and the whole frame's CRC read back from the
 * panel is zlib's over the patched picture. A window outside the frame is
 * refused; a panel without set_window reports a partial window as an error.
 */
static void test_window(void)
{
    keeper k;
    memset(&k, 0, sizeof k);
    mcu_panel panel = {"keeper", W, H, &keep_api, &k};
    uint8_t line_bytes[2 * W], row[2 * W];
    mcu_display d;
    mcu_display_init(&d, &panel, line_bytes);
    draw_frame(&d);
    CHECK(k.windows == 0, "a whole frame set a window");
    uint8_t want[H][2 * W];
    memcpy(want, k.picture, sizeof want);
    /* Frame 2: columns 2..5 of rows 1..2 turn white. */
    float white[3 * W];
    for (int i = 0; i < 3 * W; i++)
        white[i] = 1.0f;
    mcu_display_begin(&d, W, H);
    CHECK(mcu_display_window(&d, 2, 1, 6, 3) == CS_OK, "window refused");
    CHECK(mcu_display_line(&d, 0, white, 4) == CS_ERR_ARG, "a line above the window accepted");
    CHECK(mcu_display_line(&d, 1, white, W) == CS_ERR_ARG, "a line of the frame's width accepted");
    uLong sent = crc32(0L, Z_NULL, 0);
    for (int y = 1; y < 3; y++) {
        CHECK(mcu_display_line(&d, y, white, 4) == CS_OK, "window line %d", y);
        memset(&want[y][4], 0xFF, 8);
        sent = crc32(sent, &want[y][4], 8);
    }
    uint32_t crc = mcu_display_end(&d);
    CHECK(crc == (uint32_t)sent, "window CRC %08X, zlib over the bytes sent %08lX", crc, sent);
    CHECK(k.windows == 1 && memcmp(k.picture, want, sizeof want) == 0,
          "the panel's picture is not the last one with the window patched in");
    uint32_t whole = 0;
    uLong ref = crc32(crc32(0L, Z_NULL, 0), &want[0][0], sizeof want);
    CHECK(mcu_display_frame_crc(&d, row, &whole) && whole == (uint32_t)ref,
          "whole frame CRC %08X read back, zlib over the picture %08lX", whole, ref);
    /* An empty window sends nothing and keeps the picture. */
    mcu_display_begin(&d, W, H);
    CHECK(mcu_display_window(&d, 0, 0, 0, 0) == CS_OK, "empty window refused");
    mcu_display_end(&d);
    CHECK(memcmp(k.picture, want, sizeof want) == 0, "an empty window changed the picture");
    mcu_display_begin(&d, W, H);
    CHECK(mcu_display_window(&d, 2, 1, W + 1, 3) == CS_ERR_ARG, "window past the right edge");
    CHECK(mcu_display_window(&d, 3, 1, 2, 3) == CS_ERR_ARG, "window with x1 < x0");
    mcu_display_end(&d);
    /* The recorder has no set_window and no read_row. */
    recorder rec;
    memset(&rec, 0, sizeof rec);
    rec.fail_at_line = -1;
    mcu_panel plain = {"recorder", W, H, &rec_api, &rec};
    mcu_display_init(&d, &plain, line_bytes);
    mcu_display_begin(&d, W, H);
    mcu_display_window(&d, 2, 1, 6, 3);
    CHECK(d.panel_error != 0, "a panel without set_window took a window");
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
    mcu_display_begin(d, W, H);
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
    mcu_panel panel = {"recorder", W, H, &rec_api, &rec};
    uint8_t line_bytes[2 * W];
    mcu_display d;
    mcu_display_init(&d, &panel, line_bytes);

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
    CHECK(d.frames == 1 && d.panel_error == 0, "frames %u error %d", d.frames, d.panel_error);

    /* The same frame again: same CRC, and the panel sees frame number 1. */
    uint32_t again = draw_frame(&d);
    CHECK(again == crc, "second frame CRC %08X differs from %08X", again, crc);
    CHECK(rec.last_frame == 1, "panel got frame number %u", rec.last_frame);

    /* A panel failing on line 1: reported, later lines not sent, the frame
     * and its CRC still complete. */
    rec.fail_at_line = 1;
    rec.lines = 0;
    uint32_t broken = draw_frame(&d);
    CHECK(broken == crc, "CRC with a failing panel %08X, expected %08X", broken, crc);
    CHECK(d.panel_error == -5, "panel error %d, expected -5", d.panel_error);
    CHECK(rec.lines == 1, "%d lines reached the panel after its failure, expected 1", rec.lines);
    rec.fail_at_line = -1;

    /* Bad arguments are refused, not written. */
    float rgb[3 * W];
    make_line(0, rgb);
    CHECK(mcu_display_begin(&d, 0, H) == CS_ERR_SIZE, "zero width accepted");
    mcu_display_begin(&d, W, H);
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
