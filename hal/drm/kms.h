/*
 * kms.h - a Linux board's own screen (HDMI, DSI, DPI) through DRM/KMS and libdrm.
 *
 * celfw opens a DRM card (--drm-device, or the first /dev/dri/cardN with a
 * connected connector), takes the first connected connector, and a mode from
 * it: the preferred one, or the one --mode WxH[@Hz] names (a mode the
 * connector lacks is refused, naming the modes it has). It scans out two
 * dumb buffers in turn (double buffering): lines are written into the back
 * buffer, in XRGB8888 or in RGB565 (when the primary plane takes only
 * that, or the driver prefers 16-bit dumb buffers), as they are pushed
 * (hal/display.h: begin_frame, line_out, end_frame), and the back buffer
 * is shown with a page flip: an atomic commit whose FB_DAMAGE_CLIPS name the changed bands where
 * the driver has atomic modesetting and that property, else a legacy flip.
 * A driver that refuses flips gets one buffer, and the changed bands go to
 * it as DirtyFB damage clips if it takes them.
 *
 * Only the lines that differ from what a buffer holds are written into it,
 * known from one 64-bit hash per line and buffer (lx_damage), because dumb
 * buffers are often write-combined memory that is slow to touch; a frame
 * with no line differing from the screen is not flipped at all.
 *
 * Failures are values: a card that is not there (or that another program,
 * such as a desktop, holds as DRM master), a connector with nothing
 * connected, a connector that reports disconnected mid-run (checked every
 * probe_ms) or ioctls that fail with ENODEV (the card went away) turn
 * each frame's begin_frame into a cheap HAL_ERR_NO_DEVICE; the backend retries every
 * reconnect_ms and repaints the whole frame once the screen is back. With
 * `wait` it starts that way too, when the screen is not there at start.
 */
#ifndef KMS_H
#define KMS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "display.h"

typedef struct kms_config {
    char device[128];          /* "" = the first /dev/dri/cardN with a connected connector */
    int width, height;         /* the mode's size; 0 = the connector's preferred mode */
    int refresh;               /* Hz the mode must have; 0 = any */
    unsigned reconnect_ms;     /* between attempts while the screen is away */
    unsigned probe_ms;         /* between connector status checks; 0 = every frame */
    unsigned flip_timeout_ms;  /* longest wait for a page flip to complete */
    bool wait;                 /* open even with no screen there (needs width/height) */
} kms_config;

void kms_config_default(kms_config *c);

/* Parses a mode "WxH" or "WxH@Hz" into c; false if malformed or out of range. */
bool kms_parse_mode(const char *s, kms_config *c);

hal_status kms_open(hal_display **out, const kms_config *c, const hal_clock *clock, hal_log_fn log,
                   void *log_user, char *err, size_t errlen);

/* What the backend chose, for logs and tests. */
typedef struct kms_info {
    bool connected;
    char device[128];
    char connector[32];     /* e.g. HDMI-A-1 */
    uint32_t connector_id, crtc_id;
    int width, height, refresh;
    uint32_t fourcc;        /* DRM_FORMAT_XRGB8888 or DRM_FORMAT_RGB565 */
    bool flips;             /* page flips (false: one buffer + DirtyFB damage clips) */
    bool atomic;            /* atomic commits whose flips carry FB_DAMAGE_CLIPS */
    bool dirty_fb;          /* the driver takes DirtyFB damage clips */
    uint64_t flips_done, modesets, connects;
} kms_info;

void kms_get_info(hal_display *d, kms_info *info);

#endif /* KMS_H */
