/*
 * kms.c - showing frames on a DRM/KMS screen: dumb buffers, flips, damage, recovery.
 *
 * Two dumb buffers (DRM_IOCTL_MODE_CREATE_DUMB, an FB each, mapped with
 * MAP_DUMB + mmap) take turns. A frame's lines go into the back buffer as
 * they are rendered, and the first frame is shown with a mode set, the rest
 * with page flips whose completion event is awaited before the buffer that
 * was on screen is written again. A driver that refuses flips gets one mode
 * set and then a single buffer: lines are written where they are scanned
 * out and the changed bands are reported with DirtyFB, which is what the
 * drivers without flips (manual-update panels, virtual GPUs) need to upload
 * them; a driver without DirtyFB (ENOSYS) is not asked again. A legacy flip
 * carries no damage, so the kernel counts the whole plane as changed there;
 * where the driver has atomic modesetting and damage clips, kms_atomic.c
 * shows the frames instead, and its flips carry the changed bands.
 *
 * Which lines a buffer holds is known from a hash per line (lx_damage), so
 * an unchanged line costs no write to the (write-combined, slow to read)
 * buffer and a frame equal to the screen costs no flip.
 *
 * A frame may be a window (display.h): only its rows and columns come. The
 * back buffer holds the frame before last, so before it is shown the rows
 * outside the window that differ from the screen's (by their hashes: the
 * last frame's window) are copied from the front buffer, and a row of a
 * window narrower than the screen is brought up to date the same way before
 * the window's columns go in, then hashed from the buffer. The flip's clips
 * are the window's rows that changed, as wide as the window. A window is
 * refused (HAL_ERR_CONFIG: the frame driver sends the whole frame) until a
 * whole frame is on screen, so after a (re)connect.
 */
#include <errno.h>
#include <poll.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#include <drm_fourcc.h>

#include "celscan.h"
#include "cli_num.h"
#include "kms_priv.h"
#include "display.h"


void kms_config_default(kms_config *c)
{
    memset(c, 0, sizeof *c);
    c->reconnect_ms = 500;
    c->probe_ms = 500;
    c->flip_timeout_ms = 1000;
}

bool kms_parse_mode(const char *s, kms_config *c)
{
    char size[32];
    const char *at = strchr(s, '@');
    size_t n = at ? (size_t)(at - s) : strlen(s);
    if (n == 0 || n >= sizeof size)
        return false;
    memcpy(size, s, n);
    size[n] = 0;
    int w, h;
    long hz = 0;
    if (!cli_size(size, CS_CFG_MAX_WIDTH, CS_CFG_MAX_HEIGHT, &w, &h))
        return false;
    if (at && !cli_int(at + 1, 10, '\0', 1, 1000, &hz))
        return false;
    c->width = w;
    c->height = h;
    c->refresh = (int)hz;
    return true;
}

/* ------------------------------------------------------------ buffers */

static void drop_buffer(kms_dev *k, kms_buf *b)
{
    if (b->map)
        munmap(b->map, b->size);
    if (b->fb)
        drmModeRmFB(k->fd, b->fb);
    if (b->handle) {
        struct drm_mode_destroy_dumb dd = {.handle = b->handle};
        drmIoctl(k->fd, DRM_IOCTL_MODE_DESTROY_DUMB, &dd);
    }
    b->map = NULL;
    b->fb = b->handle = 0;
    lx_damage_invalidate(&b->held, 0, b->held.height);
}

static hal_status make_buffer(kms_dev *k, kms_buf *b)
{
    struct drm_mode_create_dumb cd = {.width = (uint32_t)k->width, .height = (uint32_t)k->height, .bpp = k->bpp};
    if (drmIoctl(k->fd, DRM_IOCTL_MODE_CREATE_DUMB, &cd) != 0) {
        snprintf(k->why, sizeof k->why, "creating a %dx%d dumb buffer: %s", k->width, k->height, strerror(errno));
        return kms_errno_status(errno);
    }
    b->handle = cd.handle;
    size_t row = (size_t)k->width * k->bpp / 8u;
    if (cd.pitch < row || cd.size < (uint64_t)cd.pitch * (uint64_t)k->height) {
        snprintf(k->why, sizeof k->why, "the driver gave a dumb buffer of pitch %u, size %llu for %dx%d",
                 cd.pitch, (unsigned long long)cd.size, k->width, k->height);
        return HAL_ERR_PROTOCOL;
    }
    if (k->pitch && cd.pitch != k->pitch) {
        snprintf(k->why, sizeof k->why, "the two dumb buffers differ in pitch (%u, %u)", k->pitch, cd.pitch);
        return HAL_ERR_PROTOCOL;
    }
    k->pitch = cd.pitch;
    b->size = (size_t)cd.size;
    uint32_t handles[4] = {b->handle}, pitches[4] = {cd.pitch}, offsets[4] = {0};
    if (drmModeAddFB2(k->fd, (uint32_t)k->width, (uint32_t)k->height, k->fourcc, handles, pitches, offsets,
                      &b->fb, 0) != 0) {
        snprintf(k->why, sizeof k->why, "adding a framebuffer: %s", strerror(errno));
        b->fb = 0;
        return kms_errno_status(errno);
    }
    struct drm_mode_map_dumb md = {.handle = b->handle};
    if (drmIoctl(k->fd, DRM_IOCTL_MODE_MAP_DUMB, &md) != 0) {
        snprintf(k->why, sizeof k->why, "mapping a dumb buffer: %s", strerror(errno));
        return kms_errno_status(errno);
    }
    void *p = mmap(NULL, b->size, PROT_READ | PROT_WRITE, MAP_SHARED, k->fd, (off_t)md.offset);
    if (p == MAP_FAILED) {
        snprintf(k->why, sizeof k->why, "mmap of a dumb buffer: %s", strerror(errno));
        return kms_errno_status(errno);
    }
    b->map = p;
    lx_damage_invalidate(&b->held, 0, k->height);
    return HAL_OK;
}

/* Frees what the card holds of ours and closes it (after a loss or at close). */
static void disconnect(kms_dev *k)
{
    if (k->fd >= 0) {
        kms_atomic_release(k);
        drop_buffer(k, &k->buf[0]);
        drop_buffer(k, &k->buf[1]);
        kms_card_close(k);
    }
    k->connected = false;
    k->flip_pending = false;
    k->front = -1;
    k->pitch = 0;
}

/* The per-line state, sized once the first mode fixed the source's size. */
static bool alloc_lines(kms_dev *k)
{
    for (int i = 0; i < 2; i++)
        if (!k->buf[i].held.hash && !lx_damage_init(&k->buf[i].held, k->height))
            return false;
    return true;
}

/* Opens the card and makes both buffers; the next frame is a full mode set. */
static hal_status connect_card(kms_dev *k, char *err, size_t n)
{
    hal_status s = kms_card_open(k, err, n);
    if (s != HAL_OK)
        return s;
    if (!k->width) {
        k->width = k->mode.hdisplay;
        k->height = k->mode.vdisplay;
    }
    if (!alloc_lines(k)) {
        snprintf(k->why, sizeof k->why, "out of memory for %d lines", k->height);
        s = HAL_ERR_NOMEM;
    }
    for (int i = 0; i < 2 && s == HAL_OK; i++)
        s = make_buffer(k, &k->buf[i]);
    if (s != HAL_OK) {
        snprintf(err, n, "%.60s: %.190s", k->path, k->why);
        disconnect(k);
        return s;
    }
    k->d.pixfmt = k->fourcc == DRM_FORMAT_RGB565 ? CS_PIX_RGB565_SRGB : HAL_PIX_XRGB8888;
    k->flips = true;
    k->dirty_fb = true;
    kms_atomic_setup(k);
    k->connected = true;
    k->connects++;
    k->next_probe_ns = 0;
    return HAL_OK;
}

static void lost(kms_dev *k, const char *during)
{
    hal_display_say(&k->d, "screen lost (%s during %s); retrying every %u ms", k->why, during, k->cfg.reconnect_ms);
    disconnect(k);
    k->next_attempt_ns = hal_now(k->d.clock) + (uint64_t)k->cfg.reconnect_ms * 1000000u;
    k->quiet_failures = 0;
}

/* ------------------------------------------------------------- showing */

static void on_flip(int fd, unsigned seq, unsigned sec, unsigned usec, void *user)
{
    (void)fd, (void)seq, (void)sec, (void)usec;
    kms_dev *k = user;
    k->flip_pending = false;
    k->flips_done++;
}

/* Waits until the last flip completed, so the old front buffer may be written. */
static hal_status wait_flip(kms_dev *k)
{
    uint64_t deadline = hal_now(k->d.clock) + (uint64_t)k->cfg.flip_timeout_ms * 1000000u;
    drmEventContext ev = {.version = 2, .page_flip_handler = on_flip};
    while (k->flip_pending) {
        /* The event has usually come while the frame rendered: read first, poll only if not. */
        int r = drmHandleEvent(k->fd, &ev);
        if (!k->flip_pending)
            break;
        if (r != 0 && errno != EAGAIN && errno != EINTR) {
            snprintf(k->why, sizeof k->why, "reading the flip event: %s", strerror(errno));
            return kms_errno_status(errno);
        }
        uint64_t now = hal_now(k->d.clock);
        if (now >= deadline) {
            snprintf(k->why, sizeof k->why, "page flip not completed after %u ms", k->cfg.flip_timeout_ms);
            k->flip_pending = false; /* the next flip says whether the CRTC is still busy */
            return HAL_ERR_TIMEOUT;
        }
        struct pollfd p = {.fd = k->fd, .events = POLLIN};
        poll(&p, 1, (int)((deadline - now + 999999u) / 1000000u));
    }
    return HAL_OK;
}

static hal_status modeset(kms_dev *k, int b)
{
    if (drmModeSetCrtc(k->fd, k->crtc_id, k->buf[b].fb, 0, 0, &k->conn_id, 1, &k->mode) != 0) {
        snprintf(k->why, sizeof k->why, "setting mode %ux%u on connector %s: %s", k->mode.hdisplay,
                 k->mode.vdisplay, k->conn_name, strerror(errno));
        return kms_errno_status(errno);
    }
    k->modesets++;
    return HAL_OK;
}

/* Puts buffer b on screen; clips are the bands that changed from the screen. */
static hal_status show(kms_dev *k, int b, drmModeClip *clips, int nclips)
{
    if (k->atomic.on && (k->front < 0 || b != k->front)) {
        hal_status s = kms_atomic_show(k, b, clips, nclips, k->front < 0);
        int e = errno;
        if (s == HAL_OK || s == HAL_ERR_NO_DEVICE || s == HAL_ERR_NOMEM || e == EBUSY)
            return s;
        hal_display_say(&k->d, "the driver refuses an atomic commit (%s): legacy calls from now on", k->why);
        kms_atomic_release(k);
    }
    if (k->front < 0)
        return modeset(k, b);
    if (b != k->front) {
        if (drmModePageFlip(k->fd, k->crtc_id, k->buf[b].fb, DRM_MODE_PAGE_FLIP_EVENT, k) == 0) {
            k->flip_pending = true;
            return HAL_OK;
        }
        int e = errno;
        snprintf(k->why, sizeof k->why, "page flip: %s", strerror(e));
        if (kms_errno_status(e) == HAL_ERR_NO_DEVICE || e == EBUSY)
            return kms_errno_status(e);
        hal_display_say(&k->d, "the driver refuses page flips (%s): one buffer from now on, with damage clips",
                strerror(e));
        k->flips = false;
        return modeset(k, b);
    }
    if (!k->dirty_fb || nclips == 0)
        return HAL_OK;
    if (drmModeDirtyFB(k->fd, k->buf[b].fb, clips, (uint32_t)nclips) == 0)
        return HAL_OK;
    int e = errno;
    if (e == ENOSYS || e == EOPNOTSUPP) {
        k->dirty_fb = false; /* the buffer is scanned out as it is: nothing to report */
        return HAL_OK;
    }
    snprintf(k->why, sizeof k->why, "DirtyFB of %d bands: %s", nclips, strerror(e));
    return kms_errno_status(e);
}

/* Extends the damage by line y (bands span the window's columns; the last absorbs overflow). */
static void add_damage(drmModeClip *clips, int *n, int y, const hal_window *w)
{
    if (*n && clips[*n - 1].y2 == (uint16_t)y) {
        clips[*n - 1].y2 = (uint16_t)(y + 1);
    } else if (*n == KMS_MAX_CLIPS) {
        clips[*n - 1].y2 = (uint16_t)(y + 1);
    } else {
        clips[*n] = (drmModeClip){(uint16_t)w->x0, (uint16_t)y, (uint16_t)w->x1, (uint16_t)(y + 1)};
        (*n)++;
    }
}

static hal_status reconnect(kms_dev *k)
{
    uint64_t now = hal_now(k->d.clock);
    if (now < k->next_attempt_ns)
        return hal_display_fail(&k->d, HAL_ERR_NO_DEVICE, "screen absent (%.200s)", k->why);
    char err[256];
    if (connect_card(k, err, sizeof err) != HAL_OK) {
        k->next_attempt_ns = now + (uint64_t)k->cfg.reconnect_ms * 1000000u;
        if (k->quiet_failures++ % 20 == 0) /* say why now and then, not on every attempt */
            hal_display_say(&k->d, "screen not back yet: %s", err);
        return hal_display_fail(&k->d, HAL_ERR_NO_DEVICE, "%.240s", err);
    }
    hal_display_say(&k->d, "screen connected: %s connector %s, %dx%d@%u %s", k->path, k->conn_name, k->width,
                    k->height, k->mode.vrefresh, k->bpp == 16 ? "RGB565" : "XRGB8888");
    return HAL_OK;
}

static hal_status fail(kms_dev *k, hal_status s, const char *during)
{
    if (s == HAL_ERR_NO_DEVICE) {
        hal_display_fail(&k->d, s, "screen lost: %.200s", k->why);
        lost(k, during);
    } else {
        hal_display_fail(&k->d, s, "%.240s", k->why);
    }
    return s;
}

/* A frame starts: the screen is (re)connected and checked, the back buffer chosen. */
static hal_status kms_begin_frame(hal_display *d, const hal_window *win)
{
    kms_dev *k = (kms_dev *)d;
    hal_status s;
    if (win && (!k->connected || k->front < 0))
        return hal_display_fail(d, HAL_ERR_CONFIG, "a window needs a whole frame on screen first");
    if (win && !hal_window_inside(win, k->width, k->height))
        return hal_display_fail(d, HAL_ERR_CONFIG, "window %d,%d..%d,%d outside %dx%d", win->x0, win->y0,
                                win->x1, win->y1, k->width, k->height);
    if (!k->connected && (s = reconnect(k)) != HAL_OK)
        return s;
    uint64_t now = hal_now(d->clock);
    if (now >= k->next_probe_ns) {
        if ((s = kms_card_probe(k)) != HAL_OK)
            return fail(k, s, "a connector check");
        k->next_probe_ns = now + (uint64_t)k->cfg.probe_ms * 1000000u;
    }
    if ((s = wait_flip(k)) != HAL_OK)
        return fail(k, s, "a page flip");
    k->back = k->front < 0 ? 0 : k->flips ? 1 - k->front : k->front;
    k->nclips = 0;
    k->win = win ? *win : (hal_window){0, 0, k->width, k->height};
    if (!d->st)
        d->st = &k->unpresented; /* pushed without hal_display_present: counts go nowhere */
    return HAL_OK;
}

/* Row y of the back buffer made equal to the screen's, unless the hashes say it is. */
static void copy_from_front(kms_dev *k, kms_buf *b, int y)
{
    const kms_buf *f = &k->buf[k->front];
    if (b == f || (f->held.hash[y] && !lx_damage_changed(&b->held, y, f->held.hash[y])))
        return;
    memcpy(b->map + (size_t)y * k->pitch, f->map + (size_t)y * k->pitch, (size_t)k->width * k->bpp / 8u);
    lx_damage_commit(&b->held, y, f->held.hash[y]);
}

/* Line y goes into the back buffer only if that buffer holds something else;
 * it is damage if it differs from what the screen shows. */
static hal_status kms_line_out(hal_display *d, int y, const uint8_t *px, size_t len)
{
    kms_dev *k = (kms_dev *)d;
    size_t row = (size_t)k->width * k->bpp / 8u;
    size_t wrow = (size_t)(k->win.x1 - k->win.x0) * k->bpp / 8u;
    if (!k->connected || y < k->win.y0 || y >= k->win.y1 || len != wrow)
        return hal_display_fail(d, HAL_ERR_SEQUENCE, "line %d of %zu bytes outside a frame of lines %d..%d of %zu",
                                y, len, k->win.y0, k->win.y1 - 1, wrow);
    kms_buf *b = &k->buf[k->back];
    const kms_buf *f = k->front < 0 ? NULL : &k->buf[k->front];
    uint8_t *dst = b->map + (size_t)y * k->pitch;
    uint64_t h;
    bool wrote = false;
    if (wrow == row) {
        h = lx_line_hash(px, row);
        if ((wrote = lx_damage_changed(&b->held, y, h))) {
            memcpy(dst, px, row);
            d->st->bytes_raw += row;
        }
    } else {
        /* f is there: a window is refused before the first whole frame */
        copy_from_front(k, b, y);
        memcpy(dst + (size_t)k->win.x0 * k->bpp / 8u, px, wrow);
        d->st->bytes_raw += wrow;
        h = lx_line_hash(dst, row);
        wrote = lx_damage_changed(&b->held, y, h);
    }
    lx_damage_commit(&b->held, y, h);
    /* damage: the line differs from the screen; a single buffer is written
     * where it is scanned out, so there it is whatever changed the buffer */
    bool on_screen = b == f ? !wrote : f && !lx_damage_changed(&f->held, y, h);
    if (!on_screen) {
        add_damage(k->clips, &k->nclips, y, &k->win);
        d->st->lines_sent++;
    }
    return HAL_OK;
}

static hal_status kms_end_frame(hal_display *d)
{
    kms_dev *k = (kms_dev *)d;
    if (k->front >= 0 && k->nclips == 0)
        return HAL_OK; /* the screen already shows this frame */
    if (k->front >= 0 && k->back != k->front)
        for (int y = 0; y < k->height; y++)
            if (y < k->win.y0 || y >= k->win.y1)
                copy_from_front(k, &k->buf[k->back], y); /* the rows the window left out */
    d->st->rects += (uint64_t)k->nclips;
    hal_status s = show(k, k->back, k->clips, k->nclips);
    if (s != HAL_OK) {
        if (s != HAL_ERR_NO_DEVICE)
            d->st->errors++;
        return fail(k, s, "a frame");
    }
    k->front = k->back;
    return HAL_OK;
}

static bool kms_connected(hal_display *d)
{
    return ((kms_dev *)d)->connected;
}

static void kms_close(hal_display *d)
{
    kms_dev *k = (kms_dev *)d;
    if (k->connected && k->flip_pending)
        wait_flip(k); /* a buffer must not go while the CRTC still flips to it */
    disconnect(k);
    lx_damage_free(&k->buf[0].held);
    lx_damage_free(&k->buf[1].held);
    free(k);
}

static const hal_display_api kms_api = {
    .name = "drm",
    .noun = "the screen",
    .begin_frame = kms_begin_frame,
    .line_out = kms_line_out,
    .end_frame = kms_end_frame,
    .connected = kms_connected,
    .close = kms_close,
};

hal_status kms_open(hal_display **out, const kms_config *c, const hal_clock *clock, hal_log_fn log,
                   void *log_user, char *err, size_t errlen)
{
    if (c->width < 0 || c->height < 0 || c->width > CS_CFG_MAX_WIDTH || c->height > CS_CFG_MAX_HEIGHT ||
        (c->width == 0) != (c->height == 0) || c->refresh < 0 || (c->refresh && !c->width) ||
        (c->wait && !c->width)) {
        snprintf(err, errlen, "drm: mode %dx%d@%d out of range (%dx%d at most; a rate, and waiting for an "
                 "absent screen, need a size)", c->width, c->height, c->refresh, CS_CFG_MAX_WIDTH,
                 CS_CFG_MAX_HEIGHT);
        return HAL_ERR_CONFIG;
    }
    kms_dev *k = calloc(1, sizeof *k);
    if (!k)
        return HAL_ERR_NOMEM;
    k->cfg = *c;
    k->fd = -1;
    k->front = -1;
    k->d.api = &kms_api;
    k->d.pixfmt = HAL_PIX_XRGB8888;
    k->d.clock = clock;
    k->d.log = log;
    k->d.log_user = log_user;
    char why[256];
    hal_status s = connect_card(k, why, sizeof why);
    /* Waiting, a card that is absent, busy or broken counts as absent: the
     * screen may come. A connector without the mode asked for is the user's to fix. */
    if (s != HAL_OK && !(c->wait && s != HAL_ERR_CONFIG && s != HAL_ERR_NOMEM)) {
        snprintf(err, errlen, "drm: %s", why);
        kms_close(&k->d);
        return s;
    }
    if (s != HAL_OK) {
        k->width = c->width;
        k->height = c->height;
        if (!alloc_lines(k)) {
            kms_close(&k->d);
            return HAL_ERR_NOMEM;
        }
        snprintf(k->why, sizeof k->why, "%.190s", why);
        hal_display_say(&k->d, "no screen yet (%s); waiting", why);
    }
    k->d.width = k->width;
    k->d.height = k->height;
    *out = &k->d;
    return HAL_OK;
}

void kms_get_info(hal_display *d, kms_info *info)
{
    kms_dev *k = (kms_dev *)d;
    memset(info, 0, sizeof *info);
    info->connected = k->connected;
    snprintf(info->device, sizeof info->device, "%s", k->path);
    snprintf(info->connector, sizeof info->connector, "%s", k->conn_name);
    info->connector_id = k->conn_id;
    info->crtc_id = k->crtc_id;
    info->width = k->width;
    info->height = k->height;
    info->refresh = (int)k->mode.vrefresh;
    info->fourcc = k->fourcc;
    info->flips = k->flips;
    info->atomic = k->atomic.on;
    info->dirty_fb = k->dirty_fb;
    info->flips_done = k->flips_done;
    info->modesets = k->modesets;
    info->connects = k->connects;
}
