/*
 * fake_drm.c - the legacy KMS uAPI of a one-connector card, emulated for umockdev.
 *
 * Semantics follow drivers/gpu/drm (drm_mode_config.c getresources,
 * drm_connector.c getconnector, drm_crtc.c getcrtc/setcrtc, drm_plane.c
 * page_flip, drm_framebuffer.c addfb2/rmfb/dirtyfb, drm_dumb_buffers.c,
 * drm_file.c read): arrays are copied only when the caller's count is large
 * enough and the count is always set to the real one; unknown ids are
 * ENOENT; a flip while one is pending is EBUSY; a flip on a CRTC that is off
 * is EINVAL; removing the framebuffer on screen turns the CRTC off; an event
 * is read whole or not at all, and an empty queue on a non-blocking fd is
 * EAGAIN. A disconnected connector has no modes. The handlers run on
 * umockdev's worker thread while the caller waits, so state is guarded by
 * one mutex for the test's reads.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include <drm_fourcc.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#include "fake_drm_priv.h"
#include "shim/drm_mmap.h"

void fake_drm_fill_mode(struct drm_mode_modeinfo *m, const fake_drm_mode *fm)
{
    memset(m, 0, sizeof *m);
    m->hdisplay = (uint16_t)fm->w;
    m->hsync_start = (uint16_t)(fm->w + 8);
    m->hsync_end = (uint16_t)(fm->w + 16);
    m->htotal = (uint16_t)(fm->w + 32);
    m->vdisplay = (uint16_t)fm->h;
    m->vsync_start = (uint16_t)(fm->h + 2);
    m->vsync_end = (uint16_t)(fm->h + 4);
    m->vtotal = (uint16_t)(fm->h + 8);
    m->vrefresh = (uint32_t)fm->hz;
    m->clock = (uint32_t)((uint64_t)m->htotal * m->vtotal * (uint64_t)fm->hz / 1000u);
    m->type = DRM_MODE_TYPE_DRIVER | (fm->preferred ? DRM_MODE_TYPE_PREFERRED : 0);
    snprintf(m->name, sizeof m->name, "%dx%d", fm->w, fm->h);
}

static dumb *find_dumb(fake_drm *f, uint32_t handle)
{
    for (int i = 0; i < MAX_DUMBS; i++)
        if (f->dumbs[i].handle == handle && f->dumbs[i].handle_live)
            return &f->dumbs[i];
    return NULL;
}

fb *fake_drm_find_fb(fake_drm *f, uint32_t id)
{
    for (int i = 0; i < MAX_FBS; i++)
        if (id && f->fbs[i].id == id)
            return &f->fbs[i];
    return NULL;
}

static void release_dumb(dumb *d)
{
    if (d->handle_live || d->fbs > 0)
        return;
    munmap(d->map, d->size);
    close(d->memfd);
    if (d->owner)
        g_object_unref(d->owner);
    memset(d, 0, sizeof *d);
}

static void remove_fb(fake_drm *f, fb *b)
{
    if (f->scanout_fb == b->id) { /* the kernel turns the CRTC off */
        f->scanout_fb = 0;
        f->mode_valid = false;
    }
    dumb *bo = b->bo;
    if (b->owner)
        g_object_unref(b->owner);
    memset(b, 0, sizeof *b);
    bo->fbs--;
    release_dumb(bo);
}

/*
 * Closing the fd frees the framebuffers and buffers made through it, as
 * drm_file's release does. umockdev 0.17 emits no signal for a vanished
 * client, so closed ones are reaped whenever the card is asked anything.
 * Call with the mutex held.
 */
static void reap_closed(fake_drm *f)
{
    for (int i = 0; i < MAX_FBS; i++)
        if (f->fbs[i].id && !umockdev_ioctl_client_get_connected(f->fbs[i].owner))
            remove_fb(f, &f->fbs[i]);
    for (int i = 0; i < MAX_DUMBS; i++)
        if (f->dumbs[i].handle_live && !umockdev_ioctl_client_get_connected(f->dumbs[i].owner)) {
            f->dumbs[i].handle_live = false;
            release_dumb(&f->dumbs[i]);
        }
}

/* Copies n u32 ids into the caller's array at field offset off, if it has room. */
static int put_ids(UMockdevIoctlData *d, size_t off, uint32_t have, const uint32_t *ids, uint32_t n)
{
    if (have < n || n == 0)
        return 0;
    GError *e = NULL;
    UMockdevIoctlData *a = umockdev_ioctl_data_resolve(d, off, n * sizeof(uint32_t), &e);
    if (e) {
        g_error_free(e);
        return EFAULT;
    }
    if (a)
        memcpy(a->data, ids, n * sizeof(uint32_t));
    return 0;
}

static int get_resources(fake_drm *f, UMockdevIoctlData *d)
{
    struct drm_mode_card_res *r = (struct drm_mode_card_res *)d->data;
    uint32_t fbs[MAX_FBS], nfb = 0;
    for (int i = 0; i < MAX_FBS; i++)
        if (f->fbs[i].id)
            fbs[nfb++] = f->fbs[i].id;
    uint32_t crtc = ID_CRTC, enc = ID_ENCODER, conn = ID_CONNECTOR;
    int e = put_ids(d, offsetof(struct drm_mode_card_res, fb_id_ptr), r->count_fbs, fbs, nfb);
    e = e ? e : put_ids(d, offsetof(struct drm_mode_card_res, crtc_id_ptr), r->count_crtcs, &crtc, 1);
    e = e ? e : put_ids(d, offsetof(struct drm_mode_card_res, connector_id_ptr), r->count_connectors, &conn, 1);
    e = e ? e : put_ids(d, offsetof(struct drm_mode_card_res, encoder_id_ptr), r->count_encoders, &enc, 1);
    r->count_fbs = nfb;
    r->count_crtcs = r->count_connectors = r->count_encoders = 1;
    r->min_width = r->min_height = 1;
    r->max_width = r->max_height = 8192;
    return e;
}

static int get_connector(fake_drm *f, UMockdevIoctlData *d)
{
    struct drm_mode_get_connector *c = (struct drm_mode_get_connector *)d->data;
    if (c->connector_id != ID_CONNECTOR)
        return ENOENT;
    uint32_t n = f->connected ? (uint32_t)f->o.nmodes : 0u;
    if (c->count_modes >= n && n) {
        GError *e = NULL;
        UMockdevIoctlData *m = umockdev_ioctl_data_resolve(d, offsetof(struct drm_mode_get_connector, modes_ptr),
                                                           n * sizeof(struct drm_mode_modeinfo), &e);
        if (e) {
            g_error_free(e);
            return EFAULT;
        }
        for (uint32_t i = 0; m && i < n; i++)
            fake_drm_fill_mode((struct drm_mode_modeinfo *)m->data + i, &f->o.modes[i]);
    }
    uint32_t enc = ID_ENCODER;
    int e = put_ids(d, offsetof(struct drm_mode_get_connector, encoders_ptr), c->count_encoders, &enc, 1);
    c->count_modes = n;
    c->count_encoders = 1;
    c->count_props = 0;
    c->encoder_id = f->mode_valid ? ID_ENCODER : 0;
    c->connector_type = DRM_MODE_CONNECTOR_HDMIA;
    c->connector_type_id = 1;
    c->connection = f->connected ? DRM_MODE_CONNECTED : DRM_MODE_DISCONNECTED;
    c->mm_width = 160;
    c->mm_height = 90;
    c->subpixel = DRM_MODE_SUBPIXEL_UNKNOWN;
    return e;
}

static int get_encoder(fake_drm *f, UMockdevIoctlData *d)
{
    struct drm_mode_get_encoder *e = (struct drm_mode_get_encoder *)d->data;
    if (e->encoder_id != ID_ENCODER)
        return ENOENT;
    e->encoder_type = DRM_MODE_ENCODER_TMDS;
    e->crtc_id = f->mode_valid ? ID_CRTC : 0;
    e->possible_crtcs = 1;
    e->possible_clones = 0;
    return 0;
}

static int get_crtc(fake_drm *f, UMockdevIoctlData *d)
{
    struct drm_mode_crtc *c = (struct drm_mode_crtc *)d->data;
    if (c->crtc_id != ID_CRTC)
        return ENOENT;
    c->fb_id = f->scanout_fb;
    c->x = c->y = 0;
    c->gamma_size = 0;
    c->mode_valid = f->mode_valid;
    c->mode = f->mode_valid ? f->mode : (struct drm_mode_modeinfo){0};
    c->count_connectors = 0;
    return 0;
}

static int set_crtc(fake_drm *f, UMockdevIoctlData *d)
{
    struct drm_mode_crtc *c = (struct drm_mode_crtc *)d->data;
    if (c->crtc_id != ID_CRTC)
        return ENOENT;
    f->count[FAKE_DRM_SETCRTC]++;
    if (c->fb_id == 0 && !c->mode_valid) {
        f->mode_valid = false;
        f->scanout_fb = 0;
        return 0;
    }
    fb *b = fake_drm_find_fb(f, c->fb_id);
    if (!b)
        return ENOENT;
    if (!c->mode_valid || c->count_connectors != 1)
        return EINVAL;
    GError *e = NULL;
    UMockdevIoctlData *ids = umockdev_ioctl_data_resolve(d, offsetof(struct drm_mode_crtc, set_connectors_ptr),
                                                         sizeof(uint32_t), &e);
    if (e) {
        g_error_free(e);
        return EFAULT;
    }
    if (!ids || *(uint32_t *)ids->data != ID_CONNECTOR)
        return ENOENT;
    bool known = false;
    for (int i = 0; i < f->o.nmodes; i++) {
        struct drm_mode_modeinfo m;
        fake_drm_fill_mode(&m, &f->o.modes[i]);
        known |= m.hdisplay == c->mode.hdisplay && m.vdisplay == c->mode.vdisplay &&
                 m.vrefresh == c->mode.vrefresh && m.clock == c->mode.clock;
    }
    if (!known)
        return EINVAL;
    if (b->width < c->mode.hdisplay || b->height < c->mode.vdisplay)
        return ENOSPC; /* "Invalid CRTC viewport" */
    f->mode = c->mode;
    f->mode_valid = true;
    f->scanout_fb = b->id;
    return 0;
}

static int create_dumb(fake_drm *f, UMockdevIoctlData *d)
{
    struct drm_mode_create_dumb *c = (struct drm_mode_create_dumb *)d->data;
    f->count[FAKE_DRM_CREATE_DUMB]++;
    if (c->width == 0 || c->height == 0 || c->width > 8192 || c->height > 8192 || (c->bpp != 16 && c->bpp != 32))
        return EINVAL;
    dumb *slot = NULL;
    for (int i = 0; i < MAX_DUMBS && !slot; i++)
        if (!f->dumbs[i].handle)
            slot = &f->dumbs[i];
    if (!slot)
        return ENOMEM;
    uint32_t pitch = (c->width * (c->bpp / 8u) + 63u) & ~63u; /* drivers align pitch; callers must use it */
    if (f->o.pitch_short)
        pitch = c->width * (c->bpp / 8u) - (uint32_t)f->o.pitch_short;
    size_t size = ((size_t)pitch * c->height + 4095u) & ~(size_t)4095u;
    int fd = memfd_create("fake-drm-dumb", MFD_CLOEXEC);
    if (fd < 0 || ftruncate(fd, (off_t)size) != 0) {
        if (fd >= 0)
            close(fd);
        return ENOMEM;
    }
    void *map = mmap(NULL, size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    if (map == MAP_FAILED) {
        close(fd);
        return ENOMEM;
    }
    *slot = (dumb){++f->next_handle, g_object_ref(f->cur), true, 0, fd, map, size, pitch, c->width, c->height,
                   c->bpp};
    c->handle = slot->handle;
    c->pitch = pitch;
    c->size = size;
    return 0;
}

static int add_fb2(fake_drm *f, UMockdevIoctlData *d)
{
    struct drm_mode_fb_cmd2 *c = (struct drm_mode_fb_cmd2 *)d->data;
    dumb *bo = find_dumb(f, c->handles[0]);
    if (!bo)
        return ENOENT;
    uint32_t bpp = c->pixel_format == DRM_FORMAT_XRGB8888 ? 32 : c->pixel_format == DRM_FORMAT_RGB565 ? 16 : 0;
    if (!bpp || c->width == 0 || c->height == 0 || c->flags || c->handles[1])
        return EINVAL;
    if (c->pitches[0] < c->width * bpp / 8u ||
        (uint64_t)c->offsets[0] + (uint64_t)c->pitches[0] * c->height > bo->size)
        return EINVAL;
    fb *slot = NULL;
    for (int i = 0; i < MAX_FBS && !slot; i++)
        if (!f->fbs[i].id)
            slot = &f->fbs[i];
    if (!slot)
        return ENOMEM;
    *slot = (fb){FB_ID_BASE + f->next_fb++, g_object_ref(f->cur), bo, c->width, c->height, c->pitches[0],
                 c->pixel_format, c->offsets[0]};
    bo->fbs++;
    c->fb_id = slot->id;
    return 0;
}

static int rm_fb(fake_drm *f, UMockdevIoctlData *d)
{
    fb *b = fake_drm_find_fb(f, *(uint32_t *)d->data);
    if (!b)
        return ENOENT;
    remove_fb(f, b);
    return 0;
}

static int map_dumb(fake_drm *f, UMockdevIoctlData *d)
{
    struct drm_mode_map_dumb *m = (struct drm_mode_map_dumb *)d->data;
    if (!find_dumb(f, m->handle))
        return ENOENT;
    m->offset = drm_mmap_offset(find_dumb(f, m->handle)->memfd);
    return 0;
}

static int destroy_dumb(fake_drm *f, UMockdevIoctlData *d)
{
    dumb *bo = find_dumb(f, ((struct drm_mode_destroy_dumb *)d->data)->handle);
    if (!bo)
        return ENOENT;
    bo->handle_live = false;
    release_dumb(bo);
    return 0;
}

static int page_flip(fake_drm *f, UMockdevIoctlData *d)
{
    struct drm_mode_crtc_page_flip *p = (struct drm_mode_crtc_page_flip *)d->data;
    if (p->crtc_id != ID_CRTC)
        return ENOENT;
    if (f->o.no_flip)
        return EINVAL;
    fb *b = fake_drm_find_fb(f, p->fb_id);
    if (!b)
        return ENOENT;
    if (!f->mode_valid || (p->flags & ~(uint32_t)DRM_MODE_PAGE_FLIP_FLAGS))
        return EINVAL;
    if (f->flip_pending || f->nevents == MAX_EVENTS)
        return EBUSY;
    f->count[FAKE_DRM_FLIP]++;
    f->scanout_fb = b->id;
    if (p->flags & DRM_MODE_PAGE_FLIP_EVENT)
        fake_drm_queue_flip(f, p->user_data);
    return 0;
}

bool fake_drm_queue_flip(fake_drm *f, uint64_t user_data)
{
    if (f->flip_pending || f->nevents == MAX_EVENTS)
        return false;
    struct drm_event_vblank *ev = &f->events[f->nevents++];
    memset(ev, 0, sizeof *ev);
    ev->base.type = DRM_EVENT_FLIP_COMPLETE;
    ev->base.length = sizeof *ev;
    ev->user_data = user_data;
    ev->sequence = f->count[FAKE_DRM_FLIP] + f->count[FAKE_DRM_ATOMIC];
    ev->crtc_id = ID_CRTC;
    f->flip_pending = f->hold; /* held: no vblank, the event stays unreadable */
    return true;
}

static int dirty_fb(fake_drm *f, UMockdevIoctlData *d)
{
    struct drm_mode_fb_dirty_cmd *c = (struct drm_mode_fb_dirty_cmd *)d->data;
    if (!fake_drm_find_fb(f, c->fb_id))
        return ENOENT;
    if (f->o.no_dirty)
        return ENOSYS;
    if (c->num_clips > DRM_MODE_FB_DIRTY_MAX_CLIPS || (c->num_clips && !c->clips_ptr))
        return EINVAL;
    f->count[FAKE_DRM_DIRTY]++;
    f->nclips = (int)c->num_clips;
    if (c->num_clips) {
        GError *e = NULL;
        UMockdevIoctlData *cl = umockdev_ioctl_data_resolve(d, offsetof(struct drm_mode_fb_dirty_cmd, clips_ptr),
                                                            c->num_clips * sizeof(struct drm_clip_rect), &e);
        if (e) {
            g_error_free(e);
            return EFAULT;
        }
        const struct drm_clip_rect *r = (const struct drm_clip_rect *)cl->data;
        for (uint32_t i = 0; i < c->num_clips && i < 64; i++) {
            f->clip_y[2 * i] = r[i].y1;
            f->clip_y[2 * i + 1] = r[i].y2;
        }
    }
    return 0;
}

/* drmIsMaster() asks to authenticate magic 0: EINVAL for the master, EACCES for others. */
static int auth_magic(fake_drm *f, UMockdevIoctlData *d)
{
    (void)d;
    return f->o.not_master ? EACCES : EINVAL;
}

static int get_cap(fake_drm *f, UMockdevIoctlData *d)
{
    struct drm_get_cap *c = (struct drm_get_cap *)d->data;
    switch (c->capability) {
    case DRM_CAP_DUMB_BUFFER: c->value = 1; return 0;
    case DRM_CAP_DUMB_PREFERRED_DEPTH: c->value = f->o.preferred_depth ? f->o.preferred_depth : 24; return 0;
    case DRM_CAP_DUMB_PREFER_SHADOW: c->value = 0; return 0;
    case DRM_CAP_TIMESTAMP_MONOTONIC: c->value = 1; return 0;
    }
    return EINVAL;
}

typedef struct op {
    unsigned long req;
    size_t size;
    int (*fn)(fake_drm *f, UMockdevIoctlData *d);
} op;

static const op ops[] = {
    {DRM_IOCTL_GET_CAP, sizeof(struct drm_get_cap), get_cap},
    {DRM_IOCTL_AUTH_MAGIC, sizeof(struct drm_auth), auth_magic},
    {DRM_IOCTL_MODE_GETRESOURCES, sizeof(struct drm_mode_card_res), get_resources},
    {DRM_IOCTL_MODE_GETCONNECTOR, sizeof(struct drm_mode_get_connector), get_connector},
    {DRM_IOCTL_MODE_GETENCODER, sizeof(struct drm_mode_get_encoder), get_encoder},
    {DRM_IOCTL_MODE_GETCRTC, sizeof(struct drm_mode_crtc), get_crtc},
    {DRM_IOCTL_MODE_SETCRTC, sizeof(struct drm_mode_crtc), set_crtc},
    {DRM_IOCTL_MODE_CREATE_DUMB, sizeof(struct drm_mode_create_dumb), create_dumb},
    {DRM_IOCTL_MODE_MAP_DUMB, sizeof(struct drm_mode_map_dumb), map_dumb},
    {DRM_IOCTL_MODE_DESTROY_DUMB, sizeof(struct drm_mode_destroy_dumb), destroy_dumb},
    {DRM_IOCTL_MODE_ADDFB2, sizeof(struct drm_mode_fb_cmd2), add_fb2},
    {DRM_IOCTL_MODE_RMFB, sizeof(uint32_t), rm_fb},
    {DRM_IOCTL_MODE_PAGE_FLIP, sizeof(struct drm_mode_crtc_page_flip), page_flip},
    {DRM_IOCTL_MODE_DIRTYFB, sizeof(struct drm_mode_fb_dirty_cmd), dirty_fb},
    {DRM_IOCTL_SET_CLIENT_CAP, sizeof(struct drm_set_client_cap), fake_drm_set_client_cap},
    {DRM_IOCTL_MODE_GETPLANERESOURCES, sizeof(struct drm_mode_get_plane_res), fake_drm_get_plane_resources},
    {DRM_IOCTL_MODE_GETPLANE, sizeof(struct drm_mode_get_plane), fake_drm_get_plane},
    {DRM_IOCTL_MODE_OBJ_GETPROPERTIES, sizeof(struct drm_mode_obj_get_properties), fake_drm_obj_get_properties},
    {DRM_IOCTL_MODE_GETPROPERTY, sizeof(struct drm_mode_get_property), fake_drm_get_property},
    {DRM_IOCTL_MODE_CREATEPROPBLOB, sizeof(struct drm_mode_create_blob), fake_drm_create_blob},
    {DRM_IOCTL_MODE_DESTROYPROPBLOB, sizeof(struct drm_mode_destroy_blob), fake_drm_destroy_blob},
    {DRM_IOCTL_MODE_ATOMIC, sizeof(struct drm_mode_atomic), fake_drm_atomic},
};

static gboolean on_ioctl(UMockdevIoctlBase *base, UMockdevIoctlClient *client, gpointer user)
{
    (void)base;
    fake_drm *f = user;
    unsigned long req = umockdev_ioctl_client_get_request(client);
    UMockdevIoctlData *arg = umockdev_ioctl_client_get_arg(client);
    int e = ENOTTY;
    g_mutex_lock(&f->mu);
    reap_closed(f);
    f->cur = client;
    for (size_t i = 0; i < sizeof ops / sizeof ops[0]; i++) {
        if (ops[i].req != req)
            continue;
        if (f->gone) {
            e = ENODEV;
            break;
        }
        GError *gerr = NULL;
        UMockdevIoctlData *d = umockdev_ioctl_data_resolve(arg, 0, ops[i].size, &gerr);
        if (gerr || !d) {
            if (gerr)
                g_error_free(gerr);
            e = EFAULT;
            break;
        }
        bool master_only = req == DRM_IOCTL_MODE_SETCRTC || req == DRM_IOCTL_MODE_PAGE_FLIP ||
                           req == DRM_IOCTL_MODE_ATOMIC;
        e = f->o.not_master && master_only ? EACCES : ops[i].fn(f, d);
        break;
    }
    g_mutex_unlock(&f->mu);
    umockdev_ioctl_client_complete(client, e ? -1 : 0, e);
    return TRUE;
}

/* read(2): whole events while they fit; none pending is EAGAIN (the fd is non-blocking). */
static gboolean on_read(UMockdevIoctlBase *base, UMockdevIoctlClient *client, gpointer user)
{
    (void)base;
    fake_drm *f = user;
    UMockdevIoctlData *arg = umockdev_ioctl_client_get_arg(client);
    long res;
    int e = 0;
    g_mutex_lock(&f->mu);
    int ready = f->flip_pending ? 0 : f->nevents;
    if (f->gone) {
        e = ENODEV;
    } else if (ready == 0) {
        e = EAGAIN;
    } else {
        size_t room = arg->data_len, used = 0;
        int n = 0;
        while (n < ready && used + sizeof f->events[0] <= room) {
            umockdev_ioctl_data_update(arg, used, (guint8 *)&f->events[n], (gint)sizeof f->events[0]);
            used += sizeof f->events[0];
            n++;
        }
        memmove(f->events, f->events + n, (size_t)(f->nevents - n) * sizeof f->events[0]);
        f->nevents -= n;
        f->count[FAKE_DRM_EVENTS_READ] += (unsigned)n;
        if (n == 0)
            e = EINVAL;
        res = (long)used;
    }
    g_mutex_unlock(&f->mu);
    umockdev_ioctl_client_complete(client, e ? -1 : res, e);
    return TRUE;
}

fake_drm *fake_drm_add(UMockdevTestbed *tb, const fake_drm_opts *o)
{
    fake_drm *f = calloc(1, sizeof *f);
    f->tb = tb;
    f->o = *o;
    f->connected = !o->disconnected;
    snprintf(f->node, sizeof f->node, "/dev/dri/card%d", o->index);
    g_mutex_init(&f->mu);
    char rec[512];
    snprintf(rec, sizeof rec,
             "P: /devices/platform/fake-drm.%d/drm/card%d\nN: dri/card%d=00\nE: SUBSYSTEM=drm\n"
             "E: DEVTYPE=drm_minor\nE: DEVNAME=/dev/dri/card%d\nA: dev=226:%d\n\n",
             o->index, o->index, o->index, o->index, o->index);
    /* (a node with contents is a plain file, which the testbed can remove and
     * add again; a content-less one would be a pty it cannot) */
    GError *err = NULL;
    if (!umockdev_testbed_add_from_string(tb, rec, &err)) {
        fprintf(stderr, "fake_drm: %s\n", err->message);
        abort();
    }
    f->h = umockdev_ioctl_base_new();
    g_signal_connect(f->h, "handle-ioctl", G_CALLBACK(on_ioctl), f);
    g_signal_connect(f->h, "handle-read", G_CALLBACK(on_read), f);
    if (!umockdev_testbed_attach_ioctl(tb, f->node, f->h, &err)) {
        fprintf(stderr, "fake_drm: %s\n", err->message);
        abort();
    }
    return f;
}

void fake_drm_free(fake_drm *f)
{
    if (!f)
        return;
    umockdev_testbed_detach_ioctl(f->tb, f->node, NULL);
    g_object_unref(f->h);
    char sysdir[128];
    snprintf(sysdir, sizeof sysdir, "/sys/devices/platform/fake-drm.%d/drm/card%d", f->o.index, f->o.index);
    umockdev_testbed_remove_device(f->tb, sysdir);
    for (int i = 0; i < MAX_FBS; i++)
        if (f->fbs[i].id)
            remove_fb(f, &f->fbs[i]);
    for (int i = 0; i < MAX_BLOBS; i++)
        free(f->blobs[i].data);
    for (int i = 0; i < MAX_DUMBS; i++)
        if (f->dumbs[i].handle) {
            f->dumbs[i].handle_live = false;
            release_dumb(&f->dumbs[i]);
        }
    g_mutex_clear(&f->mu);
    free(f);
}

void fake_drm_set_connected(fake_drm *f, bool on)
{
    g_mutex_lock(&f->mu);
    f->connected = on;
    g_mutex_unlock(&f->mu);
}

void fake_drm_set_gone(fake_drm *f, bool gone)
{
    g_mutex_lock(&f->mu);
    f->gone = gone;
    g_mutex_unlock(&f->mu);
}

void fake_drm_set_not_master(fake_drm *f, bool taken)
{
    g_mutex_lock(&f->mu);
    f->o.not_master = taken;
    g_mutex_unlock(&f->mu);
}

void fake_drm_hold_flips(fake_drm *f, bool hold)
{
    g_mutex_lock(&f->mu);
    f->hold = hold;
    if (!hold)
        f->flip_pending = false;
    g_mutex_unlock(&f->mu);
}

bool fake_drm_get_scanout(fake_drm *f, fake_drm_scanout *s)
{
    g_mutex_lock(&f->mu);
    fb *b = f->mode_valid ? fake_drm_find_fb(f, f->scanout_fb) : NULL;
    if (b)
        *s = (fake_drm_scanout){b->bo->map + b->offset, (int)b->width, (int)b->height, b->pitch, b->fourcc, b->id,
                                f->mode.hdisplay, f->mode.vdisplay, (int)f->mode.vrefresh};
    g_mutex_unlock(&f->mu);
    return b != NULL;
}

unsigned fake_drm_count(fake_drm *f, int what)
{
    g_mutex_lock(&f->mu);
    unsigned n = f->count[what];
    g_mutex_unlock(&f->mu);
    return n;
}

unsigned fake_drm_live_dumbs(fake_drm *f)
{
    unsigned n = 0;
    g_mutex_lock(&f->mu);
    reap_closed(f);
    for (int i = 0; i < MAX_DUMBS; i++)
        n += f->dumbs[i].handle_live;
    g_mutex_unlock(&f->mu);
    return n;
}

unsigned fake_drm_live_fbs(fake_drm *f)
{
    unsigned n = 0;
    g_mutex_lock(&f->mu);
    reap_closed(f);
    for (int i = 0; i < MAX_FBS; i++)
        n += f->fbs[i].id != 0;
    g_mutex_unlock(&f->mu);
    return n;
}

int fake_drm_last_clips(fake_drm *f, int *y, int max)
{
    g_mutex_lock(&f->mu);
    int n = f->nclips;
    for (int i = 0; i < n && i < max && i < 64; i++) {
        y[2 * i] = f->clip_y[2 * i];
        y[2 * i + 1] = f->clip_y[2 * i + 1];
    }
    g_mutex_unlock(&f->mu);
    return n;
}
