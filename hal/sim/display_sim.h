/*
 * display_sim.h - the host-simulation display backend.
 *
 * A panel that lives in memory: every line it is sent is copied into an image
 * buffer that the caller owns, so the simulator can write the frame to a PNG
 * or hash it; a driver may instead render a row straight into the image
 * (display.h's line_buffer), and line_out then copies nothing. It also checks the protocol a real panel would rely on (lines
 * only inside a frame, each row at most once, rows in increasing order, the
 * right length, inside the frame's window) and end_frame reports a whole
 * frame with missing rows, so a driver that works against the simulator works
 * against a panel that latches lines. A windowed frame (display.h) updates
 * only its window and keeps the rest, as a panel with its own memory does.
 */
#ifndef HAL_SIM_DISPLAY_SIM_H
#define HAL_SIM_DISPLAY_SIM_H

#include <stddef.h>
#include <stdint.h>

#include "display.h"

typedef struct sim_display {
    hal_display d;        /* first: the operations get this pointer */
    uint8_t *image;       /* height rows of line_bytes each, top row first */
    size_t line_bytes;
    hal_window win;       /* of the current frame */
    int in_frame;         /* between begin_frame and end_frame */
    int next_y;           /* lowest row the next line_out may write */
    int rows_written;     /* rows received in the current frame */
    uint32_t frames_done; /* frames ended with every row of their window present */
} sim_display;

/* Bytes of image memory a width x height display in fmt needs (0 if invalid). */
size_t sim_display_image_bytes(int width, int height, cs_pixfmt fmt);

/*
 * Sets s up as a width x height display in fmt over the caller's image
 * buffer (image_len bytes, at least sim_display_image_bytes). The image
 * starts all zero. HAL_ERR_CONFIG (and s->d.err) for a bad size or format or
 * a buffer too small.
 */
hal_status sim_display_init(sim_display *s, int width, int height, cs_pixfmt fmt, uint8_t *image,
                            size_t image_len);

/* Row y of the image as last shown (NULL if y is out of range). */
const uint8_t *sim_display_row(const sim_display *s, int y);

#endif /* HAL_SIM_DISPLAY_SIM_H */
