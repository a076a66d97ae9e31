/*
 * frame_drive.c - core lines to HAL display lines (see frame_drive.h).
 *
 * Begin and end frame are optional display operations: -ENOSYS from them
 * means the panel needs no framing, not a failure.
 */
#include <string.h>

#include "frame_drive.h"

/* Line y, already rendered into the renderer's runs, to the display. */
static cs_status drive_line(frame_drive *d, const cs_renderer *r, int y)
{
    cs_line_pixels(r, d->geo.pixfmt, d->bytes);
    if (d->panel != NULL) {
        cs_line_pixels(r, CS_PANEL_PIXFMT, d->panel);
        d->crc = cs_crc32(d->crc, d->panel,
                          (size_t)d->geo.width * cs_pixfmt_bytes_per_pixel(CS_PANEL_PIXFMT));
    }
    int rc = hal_display_line_out(d->dev, y, d->bytes, d->geo.line_bytes);
    if (rc != 0) {
        d->hal_rc = rc;
        d->hal_y = y;
        /* Any refusal stops the frame; hal_rc keeps the errno for the caller. */
        return CS_ERR_IO;
    }
    return CS_OK;
}

int frame_drive_render(frame_drive *d, cs_renderer *r, cs_workspace *ws, const cs_scene *scene,
                       const cs_render_opts *opts)
{
    d->crc = 0;
    d->hal_rc = 0;
    d->hal_y = -1;
    d->err = (cs_error){CS_OK, -1, -1, -1, -1};

    /* With a viewport the display is the window, and its rows count from view_y. */
    bool win = opts->view_w != 0 || opts->view_h != 0;
    int y0 = win ? opts->view_y : 0, rows = win ? opts->view_h : opts->height;
    int rc = hal_display_get_geometry(d->dev, &d->geo);
    if (rc == 0 && (d->geo.width != (win ? opts->view_w : opts->width) || d->geo.height != rows))
        rc = -EINVAL;
    if (rc != 0) {
        d->hal_rc = rc;
        return FRAME_DRIVE_HAL;
    }

    cs_status st = cs_frame_begin(r, ws, scene, opts, &d->err);
    if (st != CS_OK) {
        d->err.status = st;
        return FRAME_DRIVE_CORE;
    }
    rc = hal_display_begin_frame(d->dev);
    if (rc != 0 && rc != -ENOSYS) {
        d->hal_rc = rc;
        return FRAME_DRIVE_HAL;
    }
    /* Lines go from the core's runs straight to display bytes: each run of
     * equal pixels is converted once (cs_line_pixels). */
    for (int y = 0; y < rows && st == CS_OK; y++) {
        st = cs_render_line_runs(r, y0 + y);
        if (st == CS_OK)
            st = drive_line(d, r, y);
    }
    if (st == CS_OK)
        st = cs_frame_error(r).status;
    if (d->hal_rc != 0)
        return FRAME_DRIVE_HAL;
    rc = hal_display_end_frame(d->dev);
    if (rc != 0 && rc != -ENOSYS) {
        d->hal_rc = rc;
        d->hal_y = -1;
        return FRAME_DRIVE_HAL;
    }
    if (st >= CS_ERR_CAP_CELS && st <= CS_ERR_CAP_CROSSINGS) {
        d->err = cs_frame_error(r);
        d->err.status = st;
        return FRAME_DRIVE_DEGRADED;
    }
    if (st != CS_OK) {
        d->err = (cs_error){st, -1, -1, -1, -1};
        return FRAME_DRIVE_CORE;
    }
    return FRAME_DRIVE_OK;
}
