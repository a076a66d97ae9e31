/*
 * mcu_display.h - display out for microcontroller boards.
 *
 * The renderer hands over finished lines of linear-light floats (a
 * cs_line_sink). This backend turns each into the panel's pixel format
 * (CS_PANEL_PIXFMT: RGB565, little-endian) and passes the bytes to the
 * board's panel: an SPI or 8080 bus on a real part, or a semihosting file
 * on QEMU so that tests can compare pixels.
 *
 * A panel is a display of the one contract, hal/display.h (a hal_display
 * first in the panel's state, a const table of operations in flash). Only
 * its inline wrappers are used here, so the contract costs an MCU build
 * no code of its own; firmware builds set HAL_ERR_LEN small, as panels
 * report by status alone.
 *
 * Each frame has a CRC-32 exactly as `celsim --crc` computes it (rows top
 * to bottom), for the tests: read back from the panel after the frame
 * where the panel can (read_row), so that it costs the frame nothing; else
 * kept as a running CRC of the bytes sent.
 */
#ifndef MCU_DISPLAY_H
#define MCU_DISPLAY_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "celscan.h"
#include "display.h"

typedef struct mcu_display {
    hal_display *panel;      /* takes lines in CS_PANEL_PIXFMT */
    uint8_t *pixels;         /* one line in CS_PANEL_PIXFMT, width * 2 bytes */
    int width, height;       /* of the frame being drawn */
    hal_window win;          /* its window: what is sent */
    uint32_t crc;            /* CRC-32 of the bytes sent so far, if hash */
    bool hash;               /* keep the running CRC: the panel cannot read back (a
                              * caller that prints no CRC may clear it after begin) */
    uint32_t frames;         /* frames completed */
    hal_status panel_error;  /* the panel's first failure this frame */
} mcu_display;

/* `pixels` must hold a line of the widest frame in the panel format; it may
 * be NULL if only mcu_display_line_px is used. */
void mcu_display_init(mcu_display *d, hal_display *panel, uint8_t *pixels);

/*
 * A frame of width x height starts. `win` NULL: the whole frame is sent;
 * else only its columns [x0, x1) of rows [y0, y1) (lines are then x1 - x0
 * pixels, y still counting the frame's rows), the panel keeping the rest of
 * its picture; an empty window sends no line. The running CRC, kept only
 * for a panel that cannot read back, covers the bytes sent;
 * mcu_display_frame_crc gives the whole frame's. CS_ERR_SIZE
 * for an empty frame, CS_ERR_ARG for a window outside it; a panel that
 * cannot take a window reports a panel error.
 */
cs_status mcu_display_begin(mcu_display *d, int width, int height, const hal_window *win);

/* The cs_line_sink: `user` is the mcu_display. */
cs_status mcu_display_line(void *user, int y, const float *rgb_linear, int width);

/*
 * After mcu_display_end: the CRC-32 of the whole frame the panel now holds,
 * rows top to bottom, as `celsim --crc` computes it, read back row by row
 * into `row` (a line in the panel format). False if the panel cannot read
 * back (no read_row) or failed.
 */
bool mcu_display_frame_crc(mcu_display *d, uint8_t *row, uint32_t *crc);

/* Line y already in CS_PANEL_PIXFMT (the window's width), e.g. from
 * cs_line_pixels_scratch: sent (and hashed) as mcu_display_line does. */
cs_status mcu_display_line_px(mcu_display *d, int y, const uint8_t *pixels);

/* Ends the frame and returns the CRC-32 of the bytes sent if it was kept
 * (the panel cannot read back, d->hash), else 0. */
uint32_t mcu_display_end(mcu_display *d);

#endif /* MCU_DISPLAY_H */
