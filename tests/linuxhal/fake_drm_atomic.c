/*
 * fake_drm_atomic.c - the emulated card's atomic modesetting: planes, properties, blobs, commits.
 *
 * Semantics follow drivers/gpu/drm (drm_ioctl.c set_client_cap,
 * drm_plane.c getplane_res/getplane, drm_mode_object.c obj_get_properties,
 * drm_property.c getproperty and blobs, drm_atomic_uapi.c atomic_ioctl,
 * drm_damage_helper.c): the primary plane is listed only to clients that
 * asked for universal planes or atomic; atomic properties only to atomic
 * clients; a commit names objects and properties in arrays, unknown ones
 * are ENOENT/EINVAL, a change of mode, ACTIVE or connector routing without
 * ALLOW_MODESET is EINVAL, a flip event on a CRTC that is off is EINVAL and
 * one while a flip is pending EBUSY, TEST_ONLY checks without applying, and
 * FB_DAMAGE_CLIPS is a blob of struct drm_mode_rect. The primary plane must
 * cover the whole mode (as on most simple drivers). Property enums and
 * value ranges are not listed (counts 0): libdrm and the backend only need
 * names and current values.
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include <drm_fourcc.h>

#include "fake_drm_priv.h"

/* Property ids (their objects are fixed: one plane, one CRTC, one connector). */
enum { P_TYPE = 100, P_FB_ID, P_CRTC_ID, P_SRC_X, P_SRC_Y, P_SRC_W, P_SRC_H, P_CRTC_X, P_CRTC_Y, P_CRTC_W,
       P_CRTC_H, P_DAMAGE, P_ACTIVE = 120, P_MODE_ID, P_CONN_CRTC = 130 };

typedef struct prop {
    uint32_t id, obj;
    const char *name;
    uint32_t flags;
} prop;

static const prop props[] = {
    {P_TYPE, ID_PLANE, "type", DRM_MODE_PROP_ENUM | DRM_MODE_PROP_IMMUTABLE},
    {P_FB_ID, ID_PLANE, "FB_ID", DRM_MODE_PROP_ATOMIC | DRM_MODE_PROP_OBJECT},
    {P_CRTC_ID, ID_PLANE, "CRTC_ID", DRM_MODE_PROP_ATOMIC | DRM_MODE_PROP_OBJECT},
    {P_SRC_X, ID_PLANE, "SRC_X", DRM_MODE_PROP_ATOMIC | DRM_MODE_PROP_RANGE},
    {P_SRC_Y, ID_PLANE, "SRC_Y", DRM_MODE_PROP_ATOMIC | DRM_MODE_PROP_RANGE},
    {P_SRC_W, ID_PLANE, "SRC_W", DRM_MODE_PROP_ATOMIC | DRM_MODE_PROP_RANGE},
    {P_SRC_H, ID_PLANE, "SRC_H", DRM_MODE_PROP_ATOMIC | DRM_MODE_PROP_RANGE},
    {P_CRTC_X, ID_PLANE, "CRTC_X", DRM_MODE_PROP_ATOMIC | DRM_MODE_PROP_SIGNED_RANGE},
    {P_CRTC_Y, ID_PLANE, "CRTC_Y", DRM_MODE_PROP_ATOMIC | DRM_MODE_PROP_SIGNED_RANGE},
    {P_CRTC_W, ID_PLANE, "CRTC_W", DRM_MODE_PROP_ATOMIC | DRM_MODE_PROP_RANGE},
    {P_CRTC_H, ID_PLANE, "CRTC_H", DRM_MODE_PROP_ATOMIC | DRM_MODE_PROP_RANGE},
    {P_DAMAGE, ID_PLANE, "FB_DAMAGE_CLIPS", DRM_MODE_PROP_ATOMIC | DRM_MODE_PROP_BLOB},
    {P_ACTIVE, ID_CRTC, "ACTIVE", DRM_MODE_PROP_ATOMIC | DRM_MODE_PROP_RANGE},
    {P_MODE_ID, ID_CRTC, "MODE_ID", DRM_MODE_PROP_ATOMIC | DRM_MODE_PROP_BLOB},
    {P_CONN_CRTC, ID_CONNECTOR, "CRTC_ID", DRM_MODE_PROP_ATOMIC | DRM_MODE_PROP_OBJECT},
};
#define NPROPS (sizeof props / sizeof props[0])

static bool client_cap(fake_drm *f, const char *cap)
{
    return f->cur && g_object_get_data(G_OBJECT(f->cur), cap) != NULL;
}

static bool prop_visible(fake_drm *f, const prop *p)
{
    if (!f->o.atomic)
        return p->id == P_TYPE;
    if (p->id == P_DAMAGE && !f->o.damage_clips)
        return false;
    return !(p->flags & DRM_MODE_PROP_ATOMIC) || client_cap(f, "fake-drm-atomic");
}

/* The plane's and CRTC's state as properties (what the legacy calls set, too). */
typedef struct state {
    uint64_t fb, plane_crtc, src[4], dst[4], active, conn_crtc;
    struct drm_mode_modeinfo mode;
    uint64_t damage;
} state;

static state current(fake_drm *f)
{
    state s = {0};
    s.fb = f->scanout_fb;
    if (f->mode_valid) {
        s.plane_crtc = s.conn_crtc = ID_CRTC;
        s.active = 1;
        s.mode = f->mode;
        s.src[2] = (uint64_t)f->mode.hdisplay << 16;
        s.src[3] = (uint64_t)f->mode.vdisplay << 16;
        s.dst[2] = f->mode.hdisplay;
        s.dst[3] = f->mode.vdisplay;
    }
    return s;
}

static uint64_t prop_value(const state *s, uint32_t id)
{
    switch (id) {
    case P_TYPE: return DRM_PLANE_TYPE_PRIMARY;
    case P_FB_ID: return s->fb;
    case P_CRTC_ID: return s->plane_crtc;
    case P_SRC_X: case P_SRC_Y: case P_SRC_W: case P_SRC_H: return s->src[id - P_SRC_X];
    case P_CRTC_X: case P_CRTC_Y: case P_CRTC_W: case P_CRTC_H: return s->dst[id - P_CRTC_X];
    case P_ACTIVE: return s->active;
    case P_CONN_CRTC: return s->conn_crtc;
    }
    return 0; /* blobs read back as 0: the fake keeps no committed blob ids */
}

int fake_drm_set_client_cap(fake_drm *f, UMockdevIoctlData *d)
{
    struct drm_set_client_cap *c = (struct drm_set_client_cap *)d->data;
    if (c->value > 1)
        return EINVAL;
    if (c->capability == DRM_CLIENT_CAP_UNIVERSAL_PLANES) {
        g_object_set_data(G_OBJECT(f->cur), "fake-drm-universal", c->value ? f : NULL);
        return 0;
    }
    if (c->capability == DRM_CLIENT_CAP_ATOMIC) {
        if (!f->o.atomic)
            return EOPNOTSUPP;
        g_object_set_data(G_OBJECT(f->cur), "fake-drm-atomic", c->value ? f : NULL);
        g_object_set_data(G_OBJECT(f->cur), "fake-drm-universal", c->value ? f : NULL);
        return 0;
    }
    return EINVAL;
}

/* Copies n values of size sz to the caller's array at field offset off. */
static int put_array(UMockdevIoctlData *d, size_t off, const void *src, size_t n, size_t sz)
{
    if (n == 0)
        return 0;
    GError *e = NULL;
    UMockdevIoctlData *a = umockdev_ioctl_data_resolve(d, off, n * sz, &e);
    if (e) {
        g_error_free(e);
        return EFAULT;
    }
    if (a)
        memcpy(a->data, src, n * sz);
    return 0;
}

int fake_drm_get_plane_resources(fake_drm *f, UMockdevIoctlData *d)
{
    struct drm_mode_get_plane_res *r = (struct drm_mode_get_plane_res *)d->data;
    uint32_t n = client_cap(f, "fake-drm-universal") ? 1u : 0u, id = ID_PLANE;
    int e = r->count_planes >= n ? put_array(d, offsetof(struct drm_mode_get_plane_res, plane_id_ptr), &id, n,
                                             sizeof id)
                                 : 0;
    r->count_planes = n;
    return e;
}

int fake_drm_get_plane(fake_drm *f, UMockdevIoctlData *d)
{
    struct drm_mode_get_plane *p = (struct drm_mode_get_plane *)d->data;
    if (p->plane_id != ID_PLANE || !client_cap(f, "fake-drm-universal"))
        return ENOENT;
    uint32_t formats[4] = {DRM_FORMAT_XRGB8888, DRM_FORMAT_RGB565}, n = 2;
    if (f->o.plane_formats[0])
        for (n = 0; n < 4 && f->o.plane_formats[n]; n++)
            formats[n] = f->o.plane_formats[n];
    int e = p->count_format_types >= n
                ? put_array(d, offsetof(struct drm_mode_get_plane, format_type_ptr), formats, n, sizeof formats[0])
                : 0;
    p->count_format_types = n;
    p->crtc_id = f->mode_valid ? ID_CRTC : 0;
    p->fb_id = f->scanout_fb;
    p->possible_crtcs = 1;
    p->gamma_size = 0;
    return e;
}

int fake_drm_obj_get_properties(fake_drm *f, UMockdevIoctlData *d)
{
    struct drm_mode_obj_get_properties *o = (struct drm_mode_obj_get_properties *)d->data;
    uint32_t want = o->obj_id == ID_PLANE ? DRM_MODE_OBJECT_PLANE
                    : o->obj_id == ID_CRTC ? DRM_MODE_OBJECT_CRTC
                    : o->obj_id == ID_CONNECTOR ? DRM_MODE_OBJECT_CONNECTOR : 0;
    if (!want || (o->obj_type && o->obj_type != want) || (want == DRM_MODE_OBJECT_PLANE &&
                                                           !client_cap(f, "fake-drm-universal")))
        return ENOENT;
    uint32_t ids[NPROPS];
    uint64_t vals[NPROPS];
    uint32_t n = 0;
    state s = current(f);
    for (size_t i = 0; i < NPROPS; i++)
        if (props[i].obj == o->obj_id && prop_visible(f, &props[i])) {
            ids[n] = props[i].id;
            vals[n++] = prop_value(&s, props[i].id);
        }
    int e = 0;
    if (o->count_props >= n) {
        e = put_array(d, offsetof(struct drm_mode_obj_get_properties, props_ptr), ids, n, sizeof ids[0]);
        if (!e)
            e = put_array(d, offsetof(struct drm_mode_obj_get_properties, prop_values_ptr), vals, n,
                          sizeof vals[0]);
    }
    o->count_props = n;
    o->obj_type = want;
    return e;
}

int fake_drm_get_property(fake_drm *f, UMockdevIoctlData *d)
{
    struct drm_mode_get_property *g = (struct drm_mode_get_property *)d->data;
    for (size_t i = 0; i < NPROPS; i++)
        if (props[i].id == g->prop_id && prop_visible(f, &props[i])) {
            memset(g->name, 0, sizeof g->name);
            strncpy(g->name, props[i].name, sizeof g->name - 1);
            g->flags = props[i].flags;
            g->count_values = 0;
            g->count_enum_blobs = 0;
            return 0;
        }
    return ENOENT;
}

static blob *find_blob(fake_drm *f, uint64_t id)
{
    for (int i = 0; i < MAX_BLOBS; i++)
        if (id && f->blobs[i].id == id)
            return &f->blobs[i];
    return NULL;
}

int fake_drm_create_blob(fake_drm *f, UMockdevIoctlData *d)
{
    struct drm_mode_create_blob *c = (struct drm_mode_create_blob *)d->data;
    if (!f->o.atomic)
        return EOPNOTSUPP;
    if (c->length == 0 || c->length > 65536)
        return EINVAL;
    blob *slot = NULL;
    for (int i = 0; i < MAX_BLOBS && !slot; i++)
        if (!f->blobs[i].id)
            slot = &f->blobs[i];
    if (!slot)
        return ENOMEM;
    GError *e = NULL;
    UMockdevIoctlData *src = umockdev_ioctl_data_resolve(d, offsetof(struct drm_mode_create_blob, data), c->length,
                                                         &e);
    if (e || !src) {
        if (e)
            g_error_free(e);
        return EFAULT;
    }
    slot->data = malloc(c->length);
    memcpy(slot->data, src->data, c->length);
    slot->len = c->length;
    slot->id = BLOB_ID_BASE + f->next_blob++;
    c->blob_id = slot->id;
    return 0;
}

int fake_drm_destroy_blob(fake_drm *f, UMockdevIoctlData *d)
{
    blob *b = find_blob(f, ((struct drm_mode_destroy_blob *)d->data)->blob_id);
    if (!b)
        return ENOENT;
    free(b->data);
    memset(b, 0, sizeof *b);
    return 0;
}

/* Sets one property in the staged state. */
static int stage(fake_drm *f, state *s, uint32_t obj, uint32_t id, uint64_t v, bool *mode_change)
{
    const prop *p = NULL;
    for (size_t i = 0; i < NPROPS; i++)
        if (props[i].id == id && props[i].obj == obj && prop_visible(f, &props[i]))
            p = &props[i];
    if (!p || (p->flags & DRM_MODE_PROP_IMMUTABLE))
        return EINVAL;
    switch (id) {
    case P_FB_ID:
        if (v && !fake_drm_find_fb(f, (uint32_t)v))
            return ENOENT;
        s->fb = v;
        return 0;
    case P_CRTC_ID: s->plane_crtc = v; return 0;
    case P_SRC_X: case P_SRC_Y: case P_SRC_W: case P_SRC_H: s->src[id - P_SRC_X] = v; return 0;
    case P_CRTC_X: case P_CRTC_Y: case P_CRTC_W: case P_CRTC_H: s->dst[id - P_CRTC_X] = v; return 0;
    case P_DAMAGE: {
        blob *b = find_blob(f, v);
        if (v && (!b || b->len % sizeof(struct drm_mode_rect)))
            return EINVAL;
        s->damage = v;
        return 0;
    }
    case P_ACTIVE:
        *mode_change |= s->active != v;
        s->active = v;
        return v > 1 ? EINVAL : 0;
    case P_MODE_ID: {
        blob *b = find_blob(f, v);
        if (v && (!b || b->len != sizeof(struct drm_mode_modeinfo)))
            return EINVAL;
        struct drm_mode_modeinfo m = {0};
        if (b)
            memcpy(&m, b->data, sizeof m);
        *mode_change |= memcmp(&m, &s->mode, sizeof m) != 0;
        s->mode = m;
        return 0;
    }
    case P_CONN_CRTC:
        *mode_change |= s->conn_crtc != v;
        s->conn_crtc = v;
        return 0;
    }
    return EINVAL;
}

/* A state the hardware can show: an active CRTC with a known mode, all of it covered by the plane. */
static int check(fake_drm *f, const state *s)
{
    if (!s->active)
        return 0;
    bool known = false;
    for (int i = 0; i < f->o.nmodes; i++) {
        struct drm_mode_modeinfo m;
        fake_drm_fill_mode(&m, &f->o.modes[i]);
        known |= m.hdisplay == s->mode.hdisplay && m.vdisplay == s->mode.vdisplay && m.clock == s->mode.clock;
    }
    fb *b = fake_drm_find_fb(f, (uint32_t)s->fb);
    if (!known || s->conn_crtc != ID_CRTC || s->plane_crtc != ID_CRTC || !b)
        return EINVAL;
    uint64_t w = s->mode.hdisplay, h = s->mode.vdisplay;
    if (s->src[0] || s->src[1] || s->dst[0] || s->dst[1] || s->src[2] != w << 16 || s->src[3] != h << 16 ||
        s->dst[2] != w || s->dst[3] != h)
        return EINVAL;
    return b->width >= w && b->height >= h ? 0 : ENOSPC;
}

int fake_drm_atomic(fake_drm *f, UMockdevIoctlData *d)
{
    struct drm_mode_atomic *a = (struct drm_mode_atomic *)d->data;
    if (!client_cap(f, "fake-drm-atomic"))
        return EOPNOTSUPP;
    if ((a->flags & ~(uint32_t)(DRM_MODE_ATOMIC_FLAGS)) || a->reserved || a->count_objs > 8)
        return EINVAL;
    if ((a->flags & DRM_MODE_ATOMIC_TEST_ONLY) && (a->flags & DRM_MODE_PAGE_FLIP_EVENT))
        return EINVAL;
    GError *e = NULL;
    UMockdevIoctlData *objs = umockdev_ioctl_data_resolve(d, offsetof(struct drm_mode_atomic, objs_ptr),
                                                          a->count_objs * sizeof(uint32_t), &e);
    UMockdevIoctlData *counts = e ? NULL : umockdev_ioctl_data_resolve(
        d, offsetof(struct drm_mode_atomic, count_props_ptr), a->count_objs * sizeof(uint32_t), &e);
    uint32_t total = 0;
    for (uint32_t i = 0; counts && i < a->count_objs; i++)
        total += ((uint32_t *)counts->data)[i];
    if (total > 64)
        return EINVAL;
    UMockdevIoctlData *ids = e || !total ? NULL : umockdev_ioctl_data_resolve(
        d, offsetof(struct drm_mode_atomic, props_ptr), total * sizeof(uint32_t), &e);
    UMockdevIoctlData *vals = e || !total ? NULL : umockdev_ioctl_data_resolve(
        d, offsetof(struct drm_mode_atomic, prop_values_ptr), total * sizeof(uint64_t), &e);
    if (e) {
        g_error_free(e);
        return EFAULT;
    }
    if (a->count_objs && (!objs || !counts || (total && (!ids || !vals))))
        return EFAULT;
    state s = current(f);
    s.damage = 0;
    bool mode_change = false;
    uint32_t k = 0;
    for (uint32_t i = 0; i < a->count_objs; i++) {
        uint32_t obj = ((uint32_t *)objs->data)[i];
        if (obj != ID_PLANE && obj != ID_CRTC && obj != ID_CONNECTOR)
            return ENOENT;
        for (uint32_t j = 0; j < ((uint32_t *)counts->data)[i]; j++, k++) {
            int r = stage(f, &s, obj, ((uint32_t *)ids->data)[k], ((uint64_t *)vals->data)[k], &mode_change);
            if (r)
                return r;
        }
    }
    if (mode_change && !(a->flags & DRM_MODE_ATOMIC_ALLOW_MODESET))
        return EINVAL;
    int r = check(f, &s);
    if (r)
        return r;
    if (a->flags & DRM_MODE_PAGE_FLIP_EVENT) {
        if (!s.active)
            return EINVAL;
        if (f->flip_pending || f->nevents == MAX_EVENTS)
            return EBUSY;
    }
    if (a->flags & DRM_MODE_ATOMIC_TEST_ONLY)
        return 0;
    f->count[FAKE_DRM_ATOMIC]++;
    f->scanout_fb = s.active ? (uint32_t)s.fb : 0;
    f->mode_valid = s.active != 0;
    f->mode = s.mode;
    if (s.damage) {
        const blob *b = find_blob(f, s.damage);
        const struct drm_mode_rect *rc = (const struct drm_mode_rect *)b->data;
        f->nclips = (int)(b->len / sizeof *rc);
        for (int i = 0; i < f->nclips && i < 64; i++) {
            f->clip_y[2 * i] = rc[i].y1;
            f->clip_y[2 * i + 1] = rc[i].y2;
        }
    }
    if (a->flags & DRM_MODE_PAGE_FLIP_EVENT)
        fake_drm_queue_flip(f, a->user_data);
    return 0;
}
