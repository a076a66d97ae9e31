/*
 * gud_host.h - USB display bridges speaking GUD, driven through libusb-1.0.
 *
 * celfw finds the display by VID:PID or, with no id given, by any vendor-class
 * interface that answers GUD's descriptor request with the GUD magic. It reads
 * the display descriptor, formats, properties, connectors and modes, sets the
 * state (check, controller on, commit, display on), and then sends each frame
 * as SET_BUFFER rectangles of full-width bands of changed lines, in RGB565 or
 * XRGB8888, LZ4-compressed where the device offers it. Which lines changed is
 * known from a 64-bit hash per line of what the display shows (lx_damage), so
 * no copy of the frame is kept: memory is one band buffer plus O(height).
 *
 * Failures are values: a stalled transfer is retried after clearing the halt,
 * a timed-out one is retried, and lines that still failed are marked so they
 * travel again next frame; the frame's other bands still go, and the frame
 * ends in HAL_ERR_IO naming the rectangle that failed. An unplugged device turns begin_frame into a cheap
 * HAL_ERR_NO_DEVICE until the device is back, when the handshake runs again
 * and the whole frame is resent.
 */
#ifndef GUD_HOST_H
#define GUD_HOST_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "display.h"

typedef struct gud_config {
    uint16_t vid, pid;      /* 0:0 = any GUD display, found by interface class */
    int width, height;      /* 0 = the device's preferred mode */
    uint8_t format;         /* 0 = auto (RGB565, else XRGB8888), or a GUD_FORMAT_* */
    int compression;        /* -1 = auto (LZ4 if offered), 0 = none, 1 = LZ4 (required) */
    unsigned timeout_ms;    /* per transfer */
    int retries;            /* extra attempts per band after a stall or timeout */
    unsigned reconnect_ms;  /* between attempts while the device is away */
    size_t max_band_bytes;  /* largest rectangle, before compression */
    bool wait;              /* open even if the device is absent or unusable (needs width/height) */
} gud_config;

void gud_config_default(gud_config *c);

/* Known GUD VID:PIDs (the Linux driver's table). */
#define GUD_VID_OPENMOKO 0x1d50
#define GUD_PID_GUD 0x614d

hal_status gud_open(hal_display **out, const gud_config *c, const hal_clock *clock, hal_log_fn log,
                   void *log_user, char *err, size_t errlen);

/* What the backend negotiated, for logs and tests. */
typedef struct gud_info {
    bool connected;
    uint16_t vid, pid;
    int bus, address;
    uint8_t format;
    bool lz4;
    uint32_t max_buffer_size;
    int width, height;
    uint64_t connects; /* successful handshakes so far */
} gud_info;

void gud_get_info(hal_display *d, gud_info *info);

#endif /* GUD_HOST_H */
