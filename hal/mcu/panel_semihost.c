/*
 * panel_semihost.c - frame dumps over semihosting (see panel_semihost.h).
 *
 * A failed open or write is returned to the display backend, which reports
 * it once per frame; the frame itself still completes, so its CRC is still
 * printed and a test sees the dump missing rather than a hang.
 *
 * A frame's file stays open until the next frame begins, so that a window
 * can start from it (copied into the new file, then its rows patched in
 * place) and the picture can be read back for the whole frame's CRC.
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
    p->width = p->rows = 0;
    p->x0 = -1;
    p->whole = false;
}

/* path = dir + "/frame" + two or more digits + ".rgb565". The path lives
 * on the stack of a frame's start, which is shallow next to a line's
 * render, and not in the panel's RAM. */
#define PATH_CAP 128
static void frame_path(const panel_semihost *p, uint32_t frame, char path[PATH_CAP])
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
    size_t n = 0, cap = PATH_CAP - 1;
    for (size_t i = 0; p->dir[i] && n < cap; i++)
        path[n++] = p->dir[i];
    for (size_t i = 0; mid[i] && n < cap; i++)
        path[n++] = mid[i];
    while (nd > 0 && n < cap)
        path[n++] = digits[--nd];
    for (size_t i = 0; tail[i] && n < cap; i++)
        path[n++] = tail[i];
    path[n] = 0;
}

/* The last frame's picture copied into the open file, 64 bytes at a time
 * (a few kilobytes of stack are all a board has). */
static hal_status copy_last(panel_semihost *p)
{
    char path[PATH_CAP];
    frame_path(p, p->frame - 2u, path);
    int from = sh_open(path, 1 /* "rb" */);
    if (from < 0)
        return HAL_ERR_IO;
    uint8_t buf[64];
    int r = 0;
    for (size_t left = (size_t)p->width * (size_t)p->rows * 2u; r == 0 && left > 0;) {
        size_t n = left < sizeof buf ? left : sizeof buf;
        r = sh_read(from, buf, n) == 0 && sh_write(p->handle, buf, n) == 0 ? 0 : -1;
        left -= n;
    }
    sh_close(from);
    return r ? HAL_ERR_IO : HAL_OK;
}

/*
 * A whole frame (win NULL) is written row after row, its width learnt from
 * its lines; a window starts from a copy of the last frame, which must be
 * complete (else there is no picture to keep: HAL_ERR_SEQUENCE).
 */
static hal_status begin_frame(hal_display *d, const hal_window *win)
{
    panel_semihost *p = (panel_semihost *)d;
    if (!p->dir[0])
        return HAL_OK;
    bool base = p->handle >= 0 && p->whole;
    if (p->handle >= 0)
        sh_close(p->handle);
    p->whole = false;
    p->x0 = -1;
    char path[PATH_CAP];
    frame_path(p, p->frame++, path);
    p->handle = sh_open(path, 7 /* "w+b": read back too */);
    if (p->handle < 0)
        return HAL_ERR_IO;
    if (!win) {
        p->width = p->rows = 0;
        return HAL_OK;
    }
    if (!base)
        return HAL_ERR_SEQUENCE;
    p->x0 = win->x0;
    return copy_last(p);
}

static hal_status line_out(hal_display *d, int y, const uint8_t *pixels, size_t bytes)
{
    panel_semihost *p = (panel_semihost *)d;
    if (p->handle < 0)
        return HAL_OK;
    if (p->x0 < 0) {
        p->width = (int)(bytes / 2u);
        p->rows++;
    } else if (sh_seek(p->handle, ((size_t)y * (size_t)p->width + (size_t)p->x0) * 2u) != 0) {
        return HAL_ERR_IO;
    }
    return sh_write(p->handle, pixels, bytes) ? HAL_ERR_IO : HAL_OK;
}

static hal_status end_frame(hal_display *d)
{
    panel_semihost *p = (panel_semihost *)d;
    p->whole = p->handle >= 0;
    return HAL_OK;
}

static hal_status read_row(hal_display *d, int y, uint8_t *buf, size_t bytes)
{
    panel_semihost *p = (panel_semihost *)d;
    if (p->handle < 0 || !p->whole)
        return HAL_ERR_SEQUENCE;
    if (sh_seek(p->handle, (size_t)y * bytes) != 0 || sh_read(p->handle, buf, bytes) != 0)
        return HAL_ERR_IO;
    return HAL_OK;
}

static const hal_display_api panel_semihost_api = {
    .name = "semihost",
    .begin_frame = begin_frame,
    .line_out = line_out,
    .end_frame = end_frame,
    .read_row = read_row,
};
