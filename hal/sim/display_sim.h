/*
 * display_sim.h - the host-simulation display backend.
 *
 * A panel that lives in memory: every line it is sent is copied into an image
 * buffer that the caller owns, so the simulator can write the frame to a PNG
 * or hash it. It also checks the protocol a real panel would rely on (lines
 * only inside a frame, each row at most once, rows in increasing order, the
 * right length) and end_frame reports a frame with missing rows, so a driver
 * that works against the simulator works against a panel that latches lines.
 *
 * Layout: constant configuration (size, format) in sim_display_config, mutable
 * state in sim_display_data, joined in a hal_display by sim_display_init.
 */
#ifndef HAL_SIM_DISPLAY_SIM_H
#define HAL_SIM_DISPLAY_SIM_H

#include <stddef.h>
#include <stdint.h>

#include "display.h"

typedef struct sim_display_config {
    int width, height;
    cs_pixfmt pixfmt;
} sim_display_config;

typedef struct sim_display_data {
    uint8_t *image;       /* height rows of line_bytes each, top row first */
    size_t line_bytes;
    int in_frame;         /* between begin_frame and end_frame */
    int next_y;           /* lowest row the next line_out may write */
    int rows_written;     /* rows received in the current frame */
    uint32_t frames_done; /* frames ended with every row present */
} sim_display_data;

/* Bytes of image memory a display with this configuration needs (0 if invalid). */
size_t sim_display_image_bytes(const sim_display_config *cfg);

/*
 * Joins cfg, data and the caller's image buffer (image_len bytes, at least
 * sim_display_image_bytes(cfg)) into dev. The image starts all zero.
 * Returns 0, or -EINVAL for a bad configuration or a buffer too small.
 * cfg and data must outlive dev.
 */
int sim_display_init(hal_display *dev, const sim_display_config *cfg, sim_display_data *data,
                     uint8_t *image, size_t image_len);

/* Row y of the image as last shown (NULL if y is out of range). */
const uint8_t *sim_display_row(const hal_display *dev, int y);

#endif /* HAL_SIM_DISPLAY_SIM_H */
