/*
 * fake_drm_priv.h - the emulated DRM card's state, shared by its two files.
 *
 * fake_drm.c answers the legacy KMS uAPI, events and buffers;
 * fake_drm_atomic.c the atomic one (planes, properties, blobs, commits).
 * Handlers run with the card's mutex held; `cur` is the asking client.
 */
#ifndef FAKE_DRM_PRIV_H
#define FAKE_DRM_PRIV_H

#include <xf86drm.h>
#include <xf86drmMode.h>

#include "fake_drm.h"

#define MAX_DUMBS 8
#define MAX_FBS 8
#define MAX_EVENTS 4
#define ID_CRTC 31u
#define ID_ENCODER 32u
#define ID_CONNECTOR 33u
#define FB_ID_BASE 40u
#define ID_PLANE 30u
#define BLOB_ID_BASE 200u
#define MAX_BLOBS 16

typedef struct blob {
    uint32_t id; /* 0 = free slot */
    size_t len;
    uint8_t *data;
} blob;

typedef struct dumb {
    uint32_t handle; /* 0 = free slot */
    UMockdevIoctlClient *owner; /* the open file that made it */
    bool handle_live;
    int fbs;         /* framebuffers holding it */
    int memfd;
    uint8_t *map;
    size_t size;
    uint32_t pitch, width, height, bpp;
} dumb;

typedef struct fb {
    uint32_t id; /* 0 = free slot */
    UMockdevIoctlClient *owner;
    dumb *bo;
    uint32_t width, height, pitch, fourcc, offset;
} fb;

struct fake_drm {
    UMockdevTestbed *tb;
    fake_drm_opts o;
    char node[64];
    UMockdevIoctlBase *h;
    GMutex mu;
    bool connected, gone, hold, flip_pending;
    dumb dumbs[MAX_DUMBS];
    fb fbs[MAX_FBS];
    uint32_t next_handle, next_fb;
    uint32_t scanout_fb;
    bool mode_valid;
    struct drm_mode_modeinfo mode;
    struct drm_event_vblank events[MAX_EVENTS];
    int nevents;
    unsigned count[FAKE_DRM_NCOUNT];
    int nclips, clip_y[2 * 64];
    UMockdevIoctlClient *cur; /* the caller of the ioctl being answered */
    blob blobs[MAX_BLOBS];
    uint32_t next_blob;
};

void fake_drm_fill_mode(struct drm_mode_modeinfo *m, const fake_drm_mode *fm);
fb *fake_drm_find_fb(fake_drm *f, uint32_t id);
/* Queues a flip-complete event for the CRTC; false if one is pending (EBUSY). */
bool fake_drm_queue_flip(fake_drm *f, uint64_t user_data);

int fake_drm_set_client_cap(fake_drm *f, UMockdevIoctlData *d);
int fake_drm_get_plane_resources(fake_drm *f, UMockdevIoctlData *d);
int fake_drm_get_plane(fake_drm *f, UMockdevIoctlData *d);
int fake_drm_obj_get_properties(fake_drm *f, UMockdevIoctlData *d);
int fake_drm_get_property(fake_drm *f, UMockdevIoctlData *d);
int fake_drm_create_blob(fake_drm *f, UMockdevIoctlData *d);
int fake_drm_destroy_blob(fake_drm *f, UMockdevIoctlData *d);
int fake_drm_atomic(fake_drm *f, UMockdevIoctlData *d);

#endif /* FAKE_DRM_PRIV_H */
