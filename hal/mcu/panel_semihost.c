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
    (void)width;
    (void)height;
    if (!p->dir[0])
        return 0;
    frame_path(p, frame);
    p->handle = sh_open(p->path, 5 /* "wb" */);
    return p->handle < 0 ? -1 : 0;
}

static int line_out(void *ctx, int y, const uint8_t *pixels, size_t bytes)
{
    panel_semihost *p = ctx;
    (void)y;
    if (p->handle < 0)
        return 0;
    return sh_write(p->handle, pixels, bytes);
}

static int end_frame(void *ctx)
{
    panel_semihost *p = ctx;
    if (p->handle < 0)
        return 0;
    int r = sh_close(p->handle);
    p->handle = -1;
    return r;
}

const mcu_panel_api panel_semihost_api = {begin_frame, line_out, end_frame};
