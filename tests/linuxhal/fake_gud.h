/*
 * fake_gud.h - an emulated GUD USB display for umockdev tests.
 *
 * The real libusb runs unchanged against it: the testbed gets the device in
 * sysfs (descriptors, busnum, devnum, udev properties) and /dev/bus/usb/B/D
 * with an ioctl handler that answers usbdevfs as the kernel does for this
 * device: capabilities, claim/release, control and bulk URBs (SUBMITURB,
 * REAPURBNDELAY, DISCARDURB), CLEAR_HALT. Control requests are answered per
 * the GUD protocol with its validation (state before buffers, rectangles
 * inside the mode, lengths that add up), and bulk data is reassembled,
 * LZ4-decoded with liblz4, and written into the emulated panel's memory.
 *
 * Faults: stall the bulk endpoint (EPIPE until CLEAR_HALT), hang it (URBs
 * never complete, so the host times out and discards them), refuse a control
 * request with a GUD status, and unplug/replug (old file descriptors die with
 * ENODEV, as on a real disconnect; the device comes back at a new address).
 * Hostile devices: any size in the mode (0 wide, 0 high, 65535 wide), unknown
 * formats only, a descriptor or mode list cut to a length that lies, a
 * buffer limit smaller than a line, and a different face after a replug
 * (fake_gud_set_opts).
 */
#ifndef FAKE_GUD_H
#define FAKE_GUD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <umockdev.h>

typedef struct fake_gud_opts {
    uint16_t vid, pid;
    int width, height;
    uint8_t formats[32];
    int nformats;
    uint8_t compression;      /* GUD_COMPRESSION_LZ4 or 0 */
    uint32_t flags;           /* descriptor flags */
    uint32_t max_buffer_size; /* 0 = none given */
    uint32_t magic;           /* GUD_MAGIC unless testing a wrong one */
    uint8_t version;          /* 1 */
    bool no_modes;            /* list no modes (EDID-only device) */
    int descriptor_len;       /* bytes GET_DESCRIPTOR returns; 0 = all 30 */
    int modes_len;            /* bytes GET_CONNECTOR_MODES returns; 0 = the whole list */
    bool any_size;            /* descriptor limits 0x0..65535x65535 instead of the mode's size */
} fake_gud_opts;

/* Defaults: 1d50:614d, 320x180, RGB565 + XRGB8888, LZ4, no flags. */
void fake_gud_opts_default(fake_gud_opts *o);

typedef struct fake_gud_rect {
    uint32_t x, y, w, h, length, wire; /* wire: bytes that crossed the bulk pipe */
    bool lz4;
} fake_gud_rect;

typedef struct fake_gud_stats {
    unsigned rects, set_buffers, protocol_errors, clear_halts, discards, stalls;
    uint64_t bulk_bytes, raw_bytes;
    bool controller_on, display_on, committed;
    uint8_t format;
    unsigned state_checks;
} fake_gud_stats;

typedef struct fake_gud fake_gud;

fake_gud *fake_gud_add(UMockdevTestbed *tb, int bus, int devnum, const fake_gud_opts *o);
void fake_gud_free(fake_gud *g);

/* The panel memory in the negotiated format (width * height * bpp), under lock: copy it out. */
void fake_gud_framebuffer(fake_gud *g, uint8_t *out, size_t len);
void fake_gud_get_stats(fake_gud *g, fake_gud_stats *st);
/* Rectangles received since the last clear. */
size_t fake_gud_rects(fake_gud *g, fake_gud_rect *out, size_t max);
void fake_gud_clear_log(fake_gud *g);

void fake_gud_stall_bulk(fake_gud *g, int transfers);
void fake_gud_hang_bulk(fake_gud *g, int transfers);
void fake_gud_refuse(fake_gud *g, uint8_t request, uint8_t status, int times);

/* Pulls the plug: the device leaves sysfs (a remove uevent goes out) and
 * every open file descriptor on it fails with ENODEV from now on. */
void fake_gud_unplug(fake_gud *g);
/* Plugs it back in at a new device number (an add uevent goes out). */
void fake_gud_replug(fake_gud *g, int devnum);
/* What the device reports from its next replug on (its vid:pid stay). */
void fake_gud_set_opts(fake_gud *g, const fake_gud_opts *o);

#endif /* FAKE_GUD_H */
