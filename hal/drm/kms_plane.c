/*
 * kms_plane.c - the CRTC's primary plane: which formats it scans out, and its properties.
 *
 * With the universal-planes client capability (kernels since 3.15 take it,
 * atomic or not) the primary plane is listed like any other, with the pixel
 * formats it can scan out. That list, more than the driver's preferred dumb
 * buffer depth, says whether lines go out as XRGB8888 or RGB565: a plane
 * that takes only RGB565 gets RGB565 whatever depth is preferred. Drivers
 * that list no planes leave the preferred depth to decide. The atomic path
 * (kms_atomic.c) finds the plane's properties with kms_find_props.
 */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include <drm_fourcc.h>

#include "kms_priv.h"

bool kms_find_props(int fd, uint32_t id, uint32_t type, const char *const *names, int n, uint32_t *ids,
                    const char *value_of, uint64_t *value)
{
    drmModeObjectProperties *props = drmModeObjectGetProperties(fd, id, type);
    if (!props)
        return false;
    memset(ids, 0, (size_t)n * sizeof *ids);
    for (uint32_t i = 0; i < props->count_props; i++) {
        drmModePropertyRes *p = drmModeGetProperty(fd, props->props[i]);
        if (!p)
            continue;
        for (int j = 0; j < n; j++)
            if (!strcmp(p->name, names[j]))
                ids[j] = p->prop_id;
        if (value_of && !strcmp(p->name, value_of))
            *value = props->prop_values[i];
        drmModeFreeProperty(p);
    }
    drmModeFreeObjectProperties(props);
    return true;
}

/* The index of the CRTC among the card's CRTCs (what possible_crtcs bits count). */
static int crtc_index(int fd, uint32_t crtc)
{
    drmModeRes *res = drmModeGetResources(fd);
    int idx = -1;
    for (int i = 0; res && i < res->count_crtcs; i++)
        if (res->crtcs[i] == crtc)
            idx = i;
    drmModeFreeResources(res);
    return idx;
}

static uint32_t primary_plane(kms_dev *k)
{
    int idx = crtc_index(k->fd, k->crtc_id);
    drmModePlaneRes *pr = drmModeGetPlaneResources(k->fd);
    uint32_t found = 0;
    for (uint32_t i = 0; pr && idx >= 0 && idx < 32 && i < pr->count_planes && !found; i++) {
        drmModePlane *pl = drmModeGetPlane(k->fd, pr->planes[i]);
        if (!pl)
            continue;
        uint64_t type = DRM_PLANE_TYPE_OVERLAY;
        uint32_t none;
        if ((pl->possible_crtcs & (1u << idx)) &&
            kms_find_props(k->fd, pl->plane_id, DRM_MODE_OBJECT_PLANE, NULL, 0, &none, "type", &type) &&
            type == DRM_PLANE_TYPE_PRIMARY)
            found = pl->plane_id;
        drmModeFreePlane(pl);
    }
    drmModeFreePlaneResources(pr);
    return found;
}

static bool has_format(const drmModePlane *pl, uint32_t fourcc)
{
    for (uint32_t i = 0; i < pl->count_formats; i++)
        if (pl->formats[i] == fourcc)
            return true;
    return false;
}

hal_status kms_plane_format(kms_dev *k, bool prefer16, char *err, size_t n)
{
    k->plane = 0;
    bool xrgb = true, rgb565 = true;
    drmModePlane *pl = NULL;
    if (drmSetClientCap(k->fd, DRM_CLIENT_CAP_UNIVERSAL_PLANES, 1) == 0 && (k->plane = primary_plane(k)) != 0 &&
        (pl = drmModeGetPlane(k->fd, k->plane)) != NULL) {
        xrgb = has_format(pl, DRM_FORMAT_XRGB8888);
        rgb565 = has_format(pl, DRM_FORMAT_RGB565);
    }
    if (!xrgb && !rgb565) {
        char list[160] = "";
        size_t used = 0;
        for (uint32_t i = 0; pl && i < pl->count_formats && i < 16 && used + 6 < sizeof list; i++) {
            uint32_t f = pl->formats[i];
            used += (size_t)snprintf(list + used, sizeof list - used, "%s%c%c%c%c", i ? " " : "", (char)(f & 0x7f),
                                     (char)((f >> 8) & 0x7f), (char)((f >> 16) & 0x7f), (char)((f >> 24) & 0x7f));
        }
        snprintf(err, n, "%s: the primary plane takes neither XRGB8888 nor RGB565 (it takes %s)", k->path,
                 list[0] ? list : "nothing");
        drmModeFreePlane(pl);
        return HAL_ERR_PROTOCOL;
    }
    drmModeFreePlane(pl);
    bool use565 = !xrgb || (prefer16 && rgb565);
    k->fourcc = use565 ? DRM_FORMAT_RGB565 : DRM_FORMAT_XRGB8888;
    k->bpp = use565 ? 16 : 32;
    return HAL_OK;
}
