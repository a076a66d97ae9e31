/*
 * kms_card.c - finding the screen: card, connector, mode, CRTC and format.
 *
 * This is the part of the DRM backend that runs at start and again after
 * every reconnect. It follows what a KMS client without a compositor does
 * (as in the kernel's own examples and modetest): resources, the first
 * connector reporting a connected screen, a mode from its list, an encoder
 * that can drive it and a CRTC that encoder can use. A screen may come back
 * from a replug with other modes, so the mode is chosen again each time and
 * must keep the size the renderer was set up for.
 *
 * Everything the card reports is input: counts, ids and mode sizes are
 * checked before they are used.
 */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "celscan.h"
#include "kms_priv.h"

/* EACCES: another program took the screen (DRM master); it is ours again only after it lets go. */
hal_status kms_errno_status(int e)
{
    return e == ENODEV || e == ENXIO || e == ENOENT || e == EACCES ? HAL_ERR_NO_DEVICE : HAL_ERR_IO;
}

static void connector_name(const drmModeConnector *c, char *out, size_t n)
{
    const char *type = drmModeGetConnectorTypeName(c->connector_type);
    snprintf(out, n, "%s-%u", type ? type : "Unknown", c->connector_type_id);
}

/* The modes a connector offers, for a message: "96x64@60, 64x48@75". */
static void list_modes(const drmModeConnector *c, char *out, size_t n)
{
    size_t used = 0;
    out[0] = 0;
    for (int i = 0; i < c->count_modes && used + 1 < n; i++) {
        int w = snprintf(out + used, n - used, "%s%ux%u@%u", i ? ", " : "", c->modes[i].hdisplay,
                         c->modes[i].vdisplay, c->modes[i].vrefresh);
        if (w < 0)
            break;
        used += (size_t)w;
    }
}

/* The mode to use: of size w x h (and refresh hz if set), else the preferred one. */
static int pick_mode(const drmModeConnector *c, int w, int h, int hz)
{
    int found = -1;
    for (int i = 0; i < c->count_modes; i++) {
        const drmModeModeInfo *m = &c->modes[i];
        if (m->hdisplay == 0 || m->vdisplay == 0 || m->hdisplay > CS_CFG_MAX_WIDTH ||
            m->vdisplay > CS_CFG_MAX_HEIGHT)
            continue; /* a mode the renderer cannot fill is not a choice */
        bool preferred = (m->type & DRM_MODE_TYPE_PREFERRED) != 0;
        if (w == 0) {
            if (found < 0 || preferred)
                found = i;
            if (preferred)
                break;
        } else if (m->hdisplay == w && m->vdisplay == h && (hz == 0 || (int)m->vrefresh == hz)) {
            if (found < 0 || preferred)
                found = i;
        }
    }
    return found;
}

/* A CRTC for the connector: its encoder's current one, else any its encoders can use. */
static uint32_t pick_crtc(int fd, const drmModeRes *res, const drmModeConnector *c)
{
    for (int pass = 0; pass < 2; pass++) {
        for (int i = 0; i < c->count_encoders; i++) {
            if (pass == 0 && c->encoders[i] != c->encoder_id)
                continue;
            drmModeEncoder *e = drmModeGetEncoder(fd, c->encoders[i]);
            if (!e)
                continue;
            uint32_t crtc = 0;
            if (pass == 0 && e->crtc_id)
                crtc = e->crtc_id;
            for (int j = 0; !crtc && j < res->count_crtcs && j < 32; j++)
                if (e->possible_crtcs & (1u << j))
                    crtc = res->crtcs[j];
            drmModeFreeEncoder(e);
            if (crtc)
                return crtc;
        }
    }
    return 0;
}

/* Chooses connector, mode and CRTC on an open card. */
static hal_status pick_output(kms_dev *k, drmModeRes *res, char *err, size_t n)
{
    int w = k->cfg.width, h = k->cfg.height;
    if (k->width) { /* reconnecting: the renderer's size is fixed */
        w = k->width;
        h = k->height;
    }
    for (int i = 0; i < res->count_connectors; i++) {
        drmModeConnector *c = drmModeGetConnector(k->fd, res->connectors[i]);
        if (!c) {
            if (errno == ENODEV) {
                snprintf(err, n, "%s: reading connector %u: %s", k->path, res->connectors[i], strerror(errno));
                return HAL_ERR_NO_DEVICE;
            }
            continue;
        }
        if (c->connection != DRM_MODE_CONNECTED) {
            drmModeFreeConnector(c);
            continue;
        }
        char name[32], modes[200];
        connector_name(c, name, sizeof name);
        int m = pick_mode(c, w, h, k->cfg.refresh);
        if (m < 0) {
            list_modes(c, modes, sizeof modes);
            if (w)
                snprintf(err, n, "%s: connector %s has no mode %dx%d%s%.0d (it has %s)", k->path, name, w, h,
                         k->cfg.refresh ? "@" : "", k->cfg.refresh, modes[0] ? modes : "none");
            else
                snprintf(err, n, "%s: connector %s offers no usable mode (it has %s)", k->path, name,
                         modes[0] ? modes : "none");
            drmModeFreeConnector(c);
            return HAL_ERR_CONFIG;
        }
        uint32_t crtc = pick_crtc(k->fd, res, c);
        if (!crtc) {
            snprintf(err, n, "%s: no CRTC can drive connector %s", k->path, name);
            drmModeFreeConnector(c);
            return HAL_ERR_PROTOCOL;
        }
        k->mode = c->modes[m];
        k->conn_id = c->connector_id;
        k->crtc_id = crtc;
        snprintf(k->conn_name, sizeof k->conn_name, "%s", name);
        drmModeFreeConnector(c);
        return HAL_OK;
    }
    snprintf(err, n, "%s: no connector has a screen connected (%d connectors)", k->path, res->count_connectors);
    return HAL_ERR_NO_DEVICE;
}

/* Dumb buffers are a must; the plane's formats and their preferred depth say RGB565 or XRGB8888. */
static hal_status pick_format(kms_dev *k, char *err, size_t n)
{
    uint64_t dumb = 0, depth = 0;
    if (drmGetCap(k->fd, DRM_CAP_DUMB_BUFFER, &dumb) != 0 || !dumb) {
        snprintf(err, n, "%s: the driver offers no dumb buffers", k->path);
        return errno == ENODEV ? HAL_ERR_NO_DEVICE : HAL_ERR_PROTOCOL;
    }
    bool prefer16 = drmGetCap(k->fd, DRM_CAP_DUMB_PREFERRED_DEPTH, &depth) == 0 && depth == 16;
    return kms_plane_format(k, prefer16, err, n);
}

static hal_status open_path(kms_dev *k, const char *path, char *err, size_t n)
{
    snprintf(k->path, sizeof k->path, "%s", path);
    k->fd = open(path, O_RDWR | O_CLOEXEC | O_NONBLOCK);
    if (k->fd < 0) {
        snprintf(err, n, "%s: %s", path, strerror(errno));
        return HAL_ERR_NO_DEVICE;
    }
    drmModeRes *res = drmModeGetResources(k->fd);
    hal_status s;
    if (res && !drmIsMaster(k->fd)) {
        /* Mode sets and flips would fail with EACCES on every frame. */
        snprintf(err, n, "%s: another program (a desktop or compositor?) holds the screen as DRM master", path);
        s = HAL_ERR_NO_DEVICE;
    } else if (!res) {
        int e = errno;
        snprintf(err, n, "%s is not a KMS device (%s)", path, strerror(e));
        s = e == ENODEV ? HAL_ERR_NO_DEVICE : HAL_ERR_PROTOCOL;
    } else {
        s = pick_output(k, res, err, n);
        drmModeFreeResources(res);
    }
    if (s == HAL_OK)
        s = pick_format(k, err, n);
    if (s == HAL_OK) {
        drmModeFreeCrtc(k->saved);
        k->saved = drmModeGetCrtc(k->fd, k->crtc_id);
        return HAL_OK;
    }
    close(k->fd);
    k->fd = -1;
    return s;
}

hal_status kms_card_open(kms_dev *k, char *err, size_t errlen)
{
    if (k->cfg.device[0])
        return open_path(k, k->cfg.device, err, errlen);
    /* The reason worth telling is that of the first card there, not of the last one tried. */
    char path[32], why[256], first[256] = "";
    for (int i = 0; i < KMS_MAX_CARDS; i++) {
        snprintf(path, sizeof path, "/dev/dri/card%d", i);
        if (access(path, F_OK) != 0)
            continue;
        hal_status s = open_path(k, path, why, sizeof why);
        if (s == HAL_OK)
            return s;
        if (s == HAL_ERR_CONFIG) {
            snprintf(err, errlen, "%s", why);
            return s;
        }
        if (!first[0])
            snprintf(first, sizeof first, "%s", why);
    }
    snprintf(err, errlen, "no DRM card with a connected screen in /dev/dri/card0..%d (%s)", KMS_MAX_CARDS - 1,
             first[0] ? first : "there is none");
    return HAL_ERR_NO_DEVICE;
}

hal_status kms_card_probe(kms_dev *k)
{
    drmModeConnector *c = drmModeGetConnectorCurrent(k->fd, k->conn_id);
    if (!c) {
        snprintf(k->why, sizeof k->why, "connector %s: %s", k->conn_name, strerror(errno));
        return kms_errno_status(errno);
    }
    bool on = c->connection == DRM_MODE_CONNECTED;
    drmModeFreeConnector(c);
    if (!on) {
        snprintf(k->why, sizeof k->why, "connector %s reports no screen connected", k->conn_name);
        return HAL_ERR_NO_DEVICE;
    }
    return HAL_OK;
}

void kms_card_close(kms_dev *k)
{
    if (k->fd < 0)
        return;
    if (k->saved && k->saved->mode_valid)
        drmModeSetCrtc(k->fd, k->saved->crtc_id, k->saved->buffer_id, k->saved->x, k->saved->y, &k->conn_id, 1,
                       &k->saved->mode);
    drmModeFreeCrtc(k->saved);
    k->saved = NULL;
    close(k->fd);
    k->fd = -1;
}
