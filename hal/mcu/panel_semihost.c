/*
 * panel_semihost.c - frame dumps over semihosting (see panel_semihost.h).
 *
 * A failed open or write is returned to the display backend, which reports
 * it once per frame; the frame itself still completes, so its CRC is still
 * printed and a test sees the dump missing rather than a hang.
 */
#include "panel_semihost.h"

#include "semihost.h"

static const hal_display_api panel_semihost_api;

void panel_semihost_init(panel_semihost *p, const char *dir, int width, int height)
{
    p->d.api = &panel_semihost_api;
    p->d.width = width;
    p->d.height = height;
    p->d.pixfmt = CS_PANEL_PIXFMT;
    p->frame = 0;
    size_t i = 0;
    if (dir)
        for (; dir[i] && i + 1 < sizeof p->dir; i++)
            p->dir[i] = dir[i];
    p->dir[i] = 0;
    p->handle = -1;
    p->path[0] = 0;
}

/* path = dir + "/frame" + two or more digits + ".rgb565" */
static void frame_path(panel_semihost *p, uint32_t frame)
{
    char digits[10];
    int nd = 0;
    do {
        digits[nd++] = (char)('0' + frame % 10u);
        frame /= 10u;
    } while (frame && nd < 10);
    if (nd < 2)
        digits[nd++] = '0';
    static const char mid[] = "/frame", tail[] = ".rgb565";
    size_t n = 0, cap = sizeof p->path - 1;
    for (size_t i = 0; p->dir[i] && n < cap; i++)
        p->path[n++] = p->dir[i];
    for (size_t i = 0; mid[i] && n < cap; i++)
        p->path[n++] = mid[i];
    while (nd > 0 && n < cap)
        p->path[n++] = digits[--nd];
    for (size_t i = 0; tail[i] && n < cap; i++)
        p->path[n++] = tail[i];
    p->path[n] = 0;
}

/* The file holds the lines as they come: a window's rows, or the frame's. */
static hal_status begin_frame(hal_display *d, const hal_window *win)
{
    panel_semihost *p = (panel_semihost *)d;
    (void)win;
    if (!p->dir[0])
        return HAL_OK;
    frame_path(p, p->frame++);
    p->handle = sh_open(p->path, 5 /* "wb" */);
    return p->handle < 0 ? HAL_ERR_IO : HAL_OK;
}

static hal_status line_out(hal_display *d, int y, const uint8_t *pixels, size_t bytes)
{
    panel_semihost *p = (panel_semihost *)d;
    (void)y;
    if (p->handle < 0)
        return HAL_OK;
    return sh_write(p->handle, pixels, bytes) ? HAL_ERR_IO : HAL_OK;
}

static hal_status end_frame(hal_display *d)
{
    panel_semihost *p = (panel_semihost *)d;
    if (p->handle < 0)
        return HAL_OK;
    int r = sh_close(p->handle);
    p->handle = -1;
    return r ? HAL_ERR_IO : HAL_OK;
}

static const hal_display_api panel_semihost_api = {
    .name = "semihost",
    .begin_frame = begin_frame,
    .line_out = line_out,
    .end_frame = end_frame,
};
