/*
 * fake_drm.h - an emulated DRM/KMS card (/dev/dri/cardN) for umockdev tests.
 *
 * The real libdrm runs unchanged against it: the testbed gets the node and
 * an ioctl handler that answers the legacy KMS uAPI as the kernel's DRM core
 * does for a simple driver with one connector (two modes, or as set), one
 * encoder, one CRTC, one primary plane: resources, connector, encoder, CRTC
 * get/set, dumb buffers (create, map, destroy), framebuffers (ADDFB2, RMFB),
 * page flips with their completion event (read(2) on the fd, also answered
 * here), DirtyFB, GET_CAP and SET_CLIENT_CAP; and, if asked, atomic
 * modesetting: planes, object properties, property blobs and ATOMIC
 * commits, with FB_DAMAGE_CLIPS on the plane if asked.
 *
 * umockdev forwards ioctl, read and write of an emulated node but not mmap,
 * so a dumb buffer's memory is a memfd the fake owns, and MAP_DUMB hands out
 * an offset naming it (shim/drm_mmap.h) that the mmap() of shim/drm_mmap.c,
 * linked into the test or preloaded into celfw, maps as the kernel maps the
 * GEM object. A child process needs FAKE_DRM_PID set to the test's pid.
 */
#ifndef FAKE_DRM_H
#define FAKE_DRM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

#include <umockdev.h>

typedef struct fake_drm_mode {
    int w, h, hz;
    bool preferred;
} fake_drm_mode;

typedef struct fake_drm_opts {
    int index;              /* /dev/dri/card<index> */
    fake_drm_mode modes[4];
    int nmodes;
    bool disconnected;      /* the connector reports no screen */
    unsigned preferred_depth; /* DRM_CAP_DUMB_PREFERRED_DEPTH: 24 or 16 */
    bool no_flip;           /* PAGE_FLIP fails with EINVAL, as on drivers without it */
    bool no_dirty;          /* DIRTYFB fails with ENOSYS, as on drivers without it */
    bool not_master;        /* another program is DRM master: master-only ioctls are EACCES */
    int pitch_short;        /* CREATE_DUMB lies: the pitch is this many bytes short of a line */
    uint32_t plane_formats[4]; /* what the primary plane scans out; none set = XRGB8888, RGB565 */
    bool atomic;            /* the driver offers atomic modesetting */
    bool damage_clips;      /* its primary plane has FB_DAMAGE_CLIPS */
} fake_drm_opts;

typedef struct fake_drm fake_drm;

fake_drm *fake_drm_add(UMockdevTestbed *tb, const fake_drm_opts *o);
void fake_drm_free(fake_drm *f);

/* A screen unplugged (false) or plugged back in (true). */
void fake_drm_set_connected(fake_drm *f, bool on);
/* The card gone: every ioctl and read fails with ENODEV. */
void fake_drm_set_gone(fake_drm *f, bool gone);
/* Another program takes DRM master (true) or lets it go (false). */
void fake_drm_set_not_master(fake_drm *f, bool taken);
/* Flips stay pending (no vblank comes) until released. */
void fake_drm_hold_flips(fake_drm *f, bool hold);

/* What the CRTC scans out now (only while the driver is idle). */
typedef struct fake_drm_scanout {
    const uint8_t *pixels;
    int width, height;
    uint32_t pitch, fourcc, fb_id;
    int mode_w, mode_h, mode_hz;
} fake_drm_scanout;

bool fake_drm_get_scanout(fake_drm *f, fake_drm_scanout *s);

enum { FAKE_DRM_SETCRTC, FAKE_DRM_FLIP, FAKE_DRM_DIRTY, FAKE_DRM_CREATE_DUMB, FAKE_DRM_EVENTS_READ,
       FAKE_DRM_ATOMIC, FAKE_DRM_NCOUNT };
unsigned fake_drm_count(fake_drm *f, int what);
/* Dumb buffers and framebuffers alive now. */
unsigned fake_drm_live_dumbs(fake_drm *f);
unsigned fake_drm_live_fbs(fake_drm *f);
/* The clips of the last DirtyFB or atomic commit with FB_DAMAGE_CLIPS: n,
 * and up to max of them as y1, y2 pairs. */
int fake_drm_last_clips(fake_drm *f, int *y, int max);

#endif /* FAKE_DRM_H */
