/*
 * frame_drive.h - rendering one frame into a display through the HAL.
 *
 * This is the seam DESIGN.md draws between the core and the display: the
 * core renders each line into its runs of equal pixels, which become the
 * display's pixel format (cs_line_pixels) and go out with
 * hal_display_line_out, rendered in the display's own row where it lends
 * one (hal_display_line_buffer). It knows nothing of any backend, so the same driver
 * serves the simulator and a Linux board with a real panel.
 *
 * The caller owns every buffer; nothing here allocates, so a render can be
 * timed without the allocator in the measurement.
 */
#ifndef HOST_SIM_FRAME_DRIVE_H
#define HOST_SIM_FRAME_DRIVE_H

#include <stdint.h>

#include "bands.h"
#include "celscan.h"
#include "display.h"

typedef struct frame_drive {
    /* Set by the caller. */
    hal_display *dev;
    uint8_t *bytes;   /* hal_line_bytes of the display: one line in its format, for a
                       * display that lends no row of its own (hal_display_line_buffer) */
    uint8_t *panel;   /* NULL, or width * bytes-per-pixel of CS_PANEL_PIXFMT to hash the frame */
    /* Optional: lines rendered on the pool's threads and on the calling one,
     * which renders bands in the renderer it prepared while it waits for the
     * next line to show (bands_help). Each line is converted on the thread
     * that rendered it into frame_bytes (height lines of line_bytes), or
     * into the display's own rows where it lends them all, and, when panel
     * is set, frame_panel (height lines of panel pixels), then shown and
     * hashed in order, as one thread would. */
    bands *pool;
    uint8_t *frame_bytes;
    uint8_t *frame_panel;

    /* Set by frame_drive_render. */
    uint32_t crc;     /* CRC-32 of the frame in CS_PANEL_PIXFMT, rows top to bottom */
    cs_error err;     /* the core's failure, or its sticky capacity error */
    hal_status hal_st; /* first HAL failure (its message in dev->err), HAL_OK if none */
    int hal_y;        /* the row it happened on, -1 for begin/end frame */

    /* Private: the display's format and line length for this frame. */
    cs_pixfmt pixfmt;
    size_t line_bytes;
    uint8_t *band_bytes; /* where the pool's lines go: frame_bytes or the display's rows */
} frame_drive;

enum {
    FRAME_DRIVE_OK = 0,       /* every line rendered and shown */
    FRAME_DRIVE_DEGRADED = 1, /* every line shown, but the core ran out of capacity (d->err) */
    FRAME_DRIVE_CORE = -1,    /* the core could not start the frame (d->err) */
    FRAME_DRIVE_HAL = -2      /* the display refused a call (d->hal_st, d->hal_y) */
};

/*
 * Renders the scene at opts->time into d->dev, whose geometry must match
 * opts->width x opts->height, or the viewport's view_w x view_h when one is
 * set (the display's row 0 is then the wall's row view_y). Returns one of the FRAME_DRIVE_* values.
 */
int frame_drive_render(frame_drive *d, cs_renderer *r, cs_workspace *ws, const cs_scene *scene,
                       const cs_render_opts *opts);

#endif /* HOST_SIM_FRAME_DRIVE_H */
