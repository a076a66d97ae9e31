/*
 * mcu_display.h - display out for microcontroller boards.
 *
 * The renderer hands over finished lines of linear-light floats (a
 * cs_line_sink). This backend turns each into the panel's pixel format
 * (CS_PANEL_PIXFMT: RGB565, little-endian), keeps a running CRC-32 of the
 * frame exactly as `celsim --crc` computes it (rows top to bottom), and
 * passes the bytes to the board's panel driver: an SPI or 8080 bus on a
 * real part, or a semihosting file on QEMU so that tests can compare
 * pixels.
 *
 * A panel is a const table of operations plus its own context, in the
 * manner of Zephyr's display drivers; optional operations may be NULL.
 * This is the MCU side's own small interface; an adapter to hal/display.h
 * (the host's display-out ops) is a few lines, as both are geometry +
 * format + begin/line/end.
 */
#ifndef MCU_DISPLAY_H
#define MCU_DISPLAY_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "celscan.h"

typedef struct mcu_panel_api {
    /* A frame of width x height starts; `frame` counts frames from 0. */
    int (*begin_frame)(void *ctx, uint32_t frame, int width, int height);
    /* Line y in the panel format, `bytes` long. Required. */
    int (*line_out)(void *ctx, int y, const uint8_t *pixels, size_t bytes);
    int (*end_frame)(void *ctx);
    /* Optional: only columns [x0, x1) of rows [y0, y1) of this frame are
     * sent (after begin_frame, before the lines; lines are then x1 - x0
     * pixels, and y still counts the frame's rows); the panel keeps the rest
     * of its picture. Without it, only whole frames can be shown. */
    int (*set_window)(void *ctx, int x0, int y0, int x1, int y1);
    /* Optional: row y of the picture the panel now holds, `bytes` long, read
     * back into buf (after end_frame): the whole frame's CRC of a frame that
     * sent only a window. */
    int (*read_row)(void *ctx, int y, uint8_t *buf, size_t bytes);
} mcu_panel_api;

typedef struct mcu_panel {
    const char *name;
    int width, height;       /* native geometry */
    const mcu_panel_api *api;
    void *ctx;
} mcu_panel;

typedef struct mcu_display {
    const mcu_panel *panel;
    uint8_t *pixels;         /* one line in CS_PANEL_PIXFMT, width * 2 bytes */
    int width, height;       /* of the frame being drawn */
    int x0, y0, x1, y1;      /* its window: what is sent (mcu_display_window) */
    uint32_t crc;            /* CRC-32 of the frame's lines so far */
    uint32_t frames;         /* frames completed */
    int panel_error;         /* first non-zero result of the panel this frame */
} mcu_display;

/* `pixels` must hold a line of the widest frame in the panel format; it may
 * be NULL if only mcu_display_line_px is used. */
void mcu_display_init(mcu_display *d, const mcu_panel *panel, uint8_t *pixels);

cs_status mcu_display_begin(mcu_display *d, int width, int height);

/* The cs_line_sink: `user` is the mcu_display. */
cs_status mcu_display_line(void *user, int y, const float *rgb_linear, int width);

/*
 * Sends only columns [x0, x1) of rows [y0, y1) of this frame (call it after
 * mcu_display_begin, before the lines; lines are then x1 - x0 pixels), the
 * panel keeping the rest; an empty window sends nothing. The running CRC
 * then covers the window's bytes; mcu_display_frame_crc gives the whole
 * frame's. CS_ERR_ARG for a window outside the frame; a panel that cannot
 * take a window (no set_window) reports a panel error.
 */
cs_status mcu_display_window(mcu_display *d, int x0, int y0, int x1, int y1);

/*
 * After mcu_display_end: the CRC-32 of the whole frame the panel now holds,
 * rows top to bottom, as `celsim --crc` computes it, read back row by row
 * into `row` (a line in the panel format). False if the panel cannot read
 * back (no read_row) or failed.
 */
bool mcu_display_frame_crc(const mcu_display *d, uint8_t *row, uint32_t *crc);

/* Line y already in CS_PANEL_PIXFMT (the window's width), e.g. from
 * cs_line_pixels_scratch: hashed and sent as mcu_display_line does. */
cs_status mcu_display_line_px(mcu_display *d, int y, const uint8_t *pixels);

/* Ends the frame and returns its CRC-32. */
uint32_t mcu_display_end(mcu_display *d);

#endif /* MCU_DISPLAY_H */
