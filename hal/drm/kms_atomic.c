/*
 * kms_atomic.c - page flips that carry damage clips, through the atomic API.
 *
 * A legacy page flip says nothing about what changed, so the kernel counts
 * the whole plane as damaged; drivers that upload the picture (SPI and USB
 * panels, virtual GPUs) then send all of it. The atomic API lets a flip
 * carry the changed rectangles in the plane's FB_DAMAGE_CLIPS property:
 * "which area of the framebuffer changed since the last plane update",
 * whichever buffer was shown before, which is exactly the bands of lines
 * that differ from the screen. So where the driver offers atomic
 * modesetting and the primary plane has that property, the first frame is
 * one ALLOW_MODESET commit (connector -> CRTC, mode blob, plane -> CRTC with
 * its source and destination) and every later frame one non-blocking commit
 * of the plane's FB_ID and damage blob with a flip event. Anything missing
 * leaves the legacy path in charge; a commit the driver refuses for another
 * reason than a vanished device turns the atomic path off for good.
 */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "kms_priv.h"

static const char *const plane_names[KP_NPLANE] = {
    "FB_ID", "CRTC_ID", "SRC_X", "SRC_Y", "SRC_W", "SRC_H", "CRTC_X", "CRTC_Y", "CRTC_W", "CRTC_H",
    "FB_DAMAGE_CLIPS",
};

void kms_atomic_setup(kms_dev *k)
{
    kms_atomic *a = &k->atomic;
    memset(a, 0, sizeof *a);
    if (!k->plane || drmSetClientCap(k->fd, DRM_CLIENT_CAP_ATOMIC, 1) != 0)
        return; /* no atomic modesetting: the legacy calls serve */
    a->plane = k->plane;
    static const char *const crtc_names[] = {"MODE_ID", "ACTIVE"};
    static const char *const conn_names[] = {"CRTC_ID"};
    uint32_t crtc_ids[2], conn_ids[1];
    bool ok = a->plane &&
              kms_find_props(k->fd, a->plane, DRM_MODE_OBJECT_PLANE, plane_names, KP_NPLANE, a->plane_prop, NULL,
                         NULL) &&
              kms_find_props(k->fd, k->crtc_id, DRM_MODE_OBJECT_CRTC, crtc_names, 2, crtc_ids, NULL, NULL) &&
              kms_find_props(k->fd, k->conn_id, DRM_MODE_OBJECT_CONNECTOR, conn_names, 1, conn_ids, NULL, NULL);
    for (int i = 0; ok && i < KP_NPLANE; i++)
        ok = a->plane_prop[i] != 0; /* FB_DAMAGE_CLIPS too: without it atomic brings nothing here */
    a->crtc_mode_id = crtc_ids[0];
    a->crtc_active = crtc_ids[1];
    a->conn_crtc_id = conn_ids[0];
    ok = ok && a->crtc_mode_id && a->crtc_active && a->conn_crtc_id;
    if (ok && drmModeCreatePropertyBlob(k->fd, &k->mode, sizeof k->mode, &a->mode_blob) != 0)
        ok = false;
    a->on = ok;
    if (ok)
        hal_display_say(&k->d, "atomic modesetting, damage clips on plane %u", a->plane);
}

void kms_atomic_release(kms_dev *k)
{
    if (k->atomic.mode_blob && k->fd >= 0)
        drmModeDestroyPropertyBlob(k->fd, k->atomic.mode_blob);
    memset(&k->atomic, 0, sizeof k->atomic);
}

hal_status kms_atomic_show(kms_dev *k, int b, const drmModeClip *clips, int nclips, bool modeset)
{
    kms_atomic *a = &k->atomic;
    drmModeAtomicReq *req = drmModeAtomicAlloc();
    if (!req) {
        snprintf(k->why, sizeof k->why, "out of memory for an atomic commit");
        return HAL_ERR_NOMEM;
    }
    const uint32_t *pp = a->plane_prop;
    uint32_t blob = 0;
    uint32_t flags;
    bool ok = drmModeAtomicAddProperty(req, a->plane, pp[KP_FB_ID], k->buf[b].fb) > 0;
    if (modeset) {
        uint64_t w = (uint64_t)k->width, h = (uint64_t)k->height;
        const uint64_t v[] = {k->crtc_id, 0, 0, w << 16, h << 16, 0, 0, w, h};
        for (int i = 0; i < 9; i++)
            ok = ok && drmModeAtomicAddProperty(req, a->plane, pp[KP_CRTC_ID + i], v[i]) > 0;
        ok = ok && drmModeAtomicAddProperty(req, k->crtc_id, a->crtc_mode_id, a->mode_blob) > 0 &&
             drmModeAtomicAddProperty(req, k->crtc_id, a->crtc_active, 1) > 0 &&
             drmModeAtomicAddProperty(req, k->conn_id, a->conn_crtc_id, k->crtc_id) > 0;
        flags = DRM_MODE_ATOMIC_ALLOW_MODESET;
    } else {
        struct drm_mode_rect rects[64];
        int n = nclips < 64 ? nclips : 64;
        for (int i = 0; i < n; i++)
            rects[i] = (struct drm_mode_rect){clips[i].x1, clips[i].y1, clips[i].x2, clips[i].y2};
        if (n && drmModeCreatePropertyBlob(k->fd, rects, (size_t)n * sizeof rects[0], &blob) != 0) {
            int e = errno;
            drmModeAtomicFree(req);
            snprintf(k->why, sizeof k->why, "damage blob: %s", strerror(e));
            return kms_errno_status(e);
        }
        ok = ok && drmModeAtomicAddProperty(req, a->plane, pp[KP_FB_DAMAGE_CLIPS], blob) > 0;
        flags = DRM_MODE_PAGE_FLIP_EVENT | DRM_MODE_ATOMIC_NONBLOCK;
    }
    int r = ok ? drmModeAtomicCommit(k->fd, req, flags, k) : -1;
    int e = ok ? errno : ENOMEM;
    drmModeAtomicFree(req);
    if (blob)
        drmModeDestroyPropertyBlob(k->fd, blob); /* the committed state holds its own reference */
    if (r == 0) {
        if (modeset)
            k->modesets++;
        else
            k->flip_pending = true;
        return HAL_OK;
    }
    snprintf(k->why, sizeof k->why, "atomic %s: %s", modeset ? "mode set" : "flip", strerror(e));
    errno = e; /* the caller tells a busy CRTC from a refusal */
    return kms_errno_status(e);
}
