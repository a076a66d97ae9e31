/*
 * kms_priv.h - the DRM/KMS backend's state, shared by its two files.
 *
 * kms_card.c finds the card, connector, mode and CRTC (what a reconnect does
 * again) with kms_plane.c (the primary plane and its formats); kms.c owns the
 * dumb buffers and shows frames, through kms_atomic.c where the driver has
 * atomic modesetting with damage clips. Nothing here is
 * for callers: they see kms.h only.
 */
#ifndef KMS_PRIV_H
#define KMS_PRIV_H

#include <xf86drm.h>
#include <xf86drmMode.h>

#include "kms.h"
#include "lx_damage.h"

#define KMS_MAX_CLIPS 64 /* bands per DirtyFB; more are merged (the kernel takes 256) */
#define KMS_MAX_CARDS 8 /* /dev/dri/card0..7 are tried when no device is named */

typedef struct kms_buf {
    uint32_t handle, fb;
    uint8_t *map;
    size_t size;
    lx_damage held; /* hash of each line the buffer holds (0 = unknown) */
} kms_buf;

/* The atomic path: property ids of the objects a commit touches. */
enum { KP_FB_ID, KP_CRTC_ID, KP_SRC_X, KP_SRC_Y, KP_SRC_W, KP_SRC_H, KP_CRTC_X, KP_CRTC_Y, KP_CRTC_W,
       KP_CRTC_H, KP_FB_DAMAGE_CLIPS, KP_NPLANE };
typedef struct kms_atomic {
    bool on;                 /* commits go through the atomic API */
    uint32_t plane;          /* the CRTC's primary plane */
    uint32_t plane_prop[KP_NPLANE];
    uint32_t crtc_mode_id, crtc_active, conn_crtc_id;
    uint32_t mode_blob;
} kms_atomic;

typedef struct kms_dev {
    hal_display d;
    kms_config cfg;
    int fd;
    char path[128];
    uint32_t conn_id, crtc_id;
    uint32_t plane;     /* the CRTC's primary plane; 0 = the driver lists none */
    char conn_name[32];
    drmModeModeInfo mode;
    drmModeCrtc *saved; /* the CRTC as we found it, put back at close */
    uint32_t fourcc;
    unsigned bpp;
    uint32_t pitch;
    kms_buf buf[2];
    int front;          /* the buffer on screen; -1 = none of ours yet */
    bool flips, dirty_fb, flip_pending;
    kms_atomic atomic;
    int width, height;  /* fixed for the life of the display: the source's size */
    int back;           /* the buffer the current frame goes into */
    hal_window win;     /* the current frame's window (display.h): the whole screen if none */
    int nclips;         /* the current frame's damage: bands that differ from the screen */
    drmModeClip clips[KMS_MAX_CLIPS];
    bool connected;
    uint64_t next_attempt_ns, next_probe_ns;
    uint64_t flips_done, modesets, connects;
    int quiet_failures;
    hal_frame_stats unpresented;
    char why[200];      /* detail of the last failure */
} kms_dev;

/* HAL_ERR_NO_DEVICE for errno values that mean the card or screen went away (or was taken). */
hal_status kms_errno_status(int e);

/*
 * Opens the card (the configured one, or the first with a connected
 * connector) and chooses connector, mode (of k->width x k->height once that
 * is fixed), CRTC and pixel format. On failure the fd is closed and err says
 * why; HAL_ERR_CONFIG means the connector lacks the mode asked for.
 */
hal_status kms_card_open(kms_dev *k, char *err, size_t errlen);
/* Puts the CRTC back as it was (if the card is still there) and closes the fd. */
void kms_card_close(kms_dev *k);
/* HAL_OK while the connector still reports a connected screen. */
hal_status kms_card_probe(kms_dev *k);

/*
 * Finds the CRTC's primary plane (k->plane) and chooses the pixel format it
 * takes: XRGB8888, or RGB565 if the plane takes only that or prefer16 and
 * it takes both. HAL_ERR_PROTOCOL, naming its formats, if it takes neither.
 */
hal_status kms_plane_format(kms_dev *k, bool prefer16, char *err, size_t n);
/*
 * Looks up the properties `names` of object id (type) into ids (0 = absent)
 * and the value of property `value_of`, if asked. false if the object's
 * properties cannot be read.
 */
bool kms_find_props(int fd, uint32_t id, uint32_t type, const char *const *names, int n, uint32_t *ids,
                    const char *value_of, uint64_t *value);
/*
 * Turns the atomic path on when the driver offers atomic modesetting and the
 * CRTC's primary plane takes FB_DAMAGE_CLIPS; otherwise leaves it off (the
 * legacy calls then serve). Never fails: the legacy path is always there.
 */
void kms_atomic_setup(kms_dev *k);
/* One commit showing buffer b: a full mode set if modeset, else a flip with
 * the damage clips and a completion event. */
hal_status kms_atomic_show(kms_dev *k, int b, const drmModeClip *clips, int nclips, bool modeset);
/* Frees the mode blob (before the fd is closed). */
void kms_atomic_release(kms_dev *k);

#endif /* KMS_PRIV_H */
