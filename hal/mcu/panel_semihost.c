/*
 * panel_semihost.c - frame dumps over semihosting (see panel_semihost.h).
 *
 * A failed open or write is returned to the display backend, which reports
 * it once per frame; the frame itself still completes, so its CRC is still
 * printed and a test sees the dump missing rather than a hang.
 */
#include "panel_semihost.h"

#include "semihost.h"

void panel_semihost_init(panel_semihost *p, const char *dir)
{
    size_t i = 0;
    if (dir)
        for (; dir[i] && i + 1 < sizeof p->dir; i++)
            p->dir[i] = dir[i];
    p->dir[i] = 0;
    p->handle = -1;
    p->path[0] = 0;
    p->whole = false;
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

static int begin_frame(void *ctx, uint32_t frame, int width, int height)
{
    panel_semihost *p = ctx;
    if (!p->dir[0])
        return 0;
    /* The last frame's file stays open until now: a window starts from it. */
    bool whole = p->handle >= 0 && p->whole;
    uint32_t last = p->frame;
    int last_w = p->width, last_h = p->height;
    if (p->handle >= 0)
        sh_close(p->handle);
    p->whole = false;
    p->x0 = -1;
    p->frame = frame;
    p->width = width;
    p->height = height;
    frame_path(p, frame);
    p->handle = sh_open(p->path, 7 /* "w+b": read back too */);
    if (p->handle < 0)
        return -1;
    /* Remember whether the last frame can be the base of a window. */
    p->whole = whole && last_w == width && last_h == height && last + 1u == frame;
    return 0;
}

/* The last frame's picture copied into the open file, 64 bytes at a time
 * (a few kilobytes of stack are all a board has). */
static int copy_last(panel_semihost *p)
{
    frame_path(p, p->frame - 1u);
    int from = sh_open(p->path, 1 /* "rb" */);
    if (from < 0)
        return -1;
    uint8_t buf[64];
    int r = 0;
    for (size_t left = (size_t)p->width * (size_t)p->height * 2u; r == 0 && left > 0;) {
        size_t n = left < sizeof buf ? left : sizeof buf;
        r = sh_read(from, buf, n) == 0 && sh_write(p->handle, buf, n) == 0 ? 0 : -1;
        left -= n;
    }
    sh_close(from);
    return r;
}

static int set_window(void *ctx, int x0, int y0, int x1, int y1)
{
    panel_semihost *p = ctx;
    (void)y0;
    (void)x1;
    (void)y1;
    if (p->handle < 0)
        return 0;
    if (!p->whole) /* no picture to keep */
        return -1;
    p->x0 = x0;
    return copy_last(p);
}

static int line_out(void *ctx, int y, const uint8_t *pixels, size_t bytes)
{
    panel_semihost *p = ctx;
    if (p->handle < 0)
        return 0;
    if (p->x0 >= 0 &&
        sh_seek(p->handle, ((size_t)y * (size_t)p->width + (size_t)p->x0) * 2u) != 0)
        return -1;
    return sh_write(p->handle, pixels, bytes);
}

static int end_frame(void *ctx)
{
    panel_semihost *p = ctx;
    p->whole = p->handle >= 0;
    return 0;
}

static int read_row(void *ctx, int y, uint8_t *buf, size_t bytes)
{
    panel_semihost *p = ctx;
    if (p->handle < 0 || !p->whole)
        return -1;
    if (sh_seek(p->handle, (size_t)y * bytes) != 0)
        return -1;
    return sh_read(p->handle, buf, bytes);
}

const mcu_panel_api panel_semihost_api = {begin_frame, line_out, end_frame, set_window, read_row};
