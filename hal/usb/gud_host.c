/*
 * gud_host.c - the GUD host side over libusb-1.0: handshake, damage bands, recovery.
 *
 * The sequence follows the kernel's gud driver (drivers/gpu/drm/gud):
 *   probe     GET_DESCRIPTOR (magic, version 1, size limits), GET_FORMATS,
 *             GET_PROPERTIES, GET_CONNECTORS, GET_CONNECTOR_MODES(0);
 *   state     SET_STATE_CHECK(mode, format, connector 0, properties),
 *             SET_CONTROLLER_ENABLE(1), SET_STATE_COMMIT, SET_DISPLAY_ENABLE(1);
 *   pixels    SET_BUFFER(x, y, w, h, length, compression, compressed length)
 *             then the bytes on the bulk OUT endpoint.
 * A stalled control request is explained by GET_STATUS, as the kernel does,
 * and so is every SET when the device asks for it (STATUS_ON_SET).
 *
 * Frames are pushed top to bottom (display.h), each line already in the
 * device format, and hashed; a changed line is copied into the band buffer
 * and stays there, an unchanged one closes the band, which is then sent as
 * one full-width rectangle. Bands are bounded by max_band_bytes and by the
 * device's max_buffer_size, so memory never grows with the frame.
 *
 * A frame may be a window (display.h): the device keeps its picture, so only
 * the window's lines come, and its rectangles are as wide as the window. A
 * full-width window's lines are still skipped by hash; a narrower one's are
 * all sent and their hashes forgotten (a hash covers a whole line). A
 * window is refused (HAL_ERR_CONFIG: the frame driver sends the whole frame)
 * while the device is away, so a reconnect always starts with a whole frame,
 * and by a full-update device, which takes whole frames only.
 *
 * Everything the device reports is input like any other: descriptor and
 * mode list lengths, sizes (a 0-wide mode would divide by a zero pitch),
 * formats and buffer limits are checked before they size anything, and a
 * device may come back from a replug with a different face, so the band is
 * sized again from its bytes, not its line count. A device that fails these
 * checks is refused with a message naming the value; after a replug that
 * means the display stays down and is retried.
 */
#include <errno.h>
#include <libusb.h>
#include <lz4.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celscan.h"
#include "gud_host.h"
#include "gud_wire.h"
#include "lx_damage.h"

/* A full-update device takes whole frames: this bounds the buffer one costs. */
#define GUD_MAX_FULL_FRAME (64u * 1024u * 1024u)

typedef struct gud_host {
    hal_display d;
    gud_config cfg;
    libusb_context *ctx;
    libusb_device_handle *h;
    int iface;
    uint8_t ep_out;
    uint16_t vid, pid;
    int bus, address;
    gud_descriptor desc;
    uint8_t format;
    unsigned bpp;
    bool lz4, full_update, rotation_prop, need_set_buffer;
    gud_mode mode;
    int width, height; /* fixed for the life of the display: the source's size */
    size_t pitch;
    lx_damage damage;
    uint8_t *band, *zbuf;
    uint64_t *band_hash;
    int band_cap, band_y0, band_n;
    int win_x0, win_x1; /* the frame's columns; a narrower window's lines are not hashed */
    size_t line_bytes;  /* bytes of the frame's lines: the window's width */
    size_t band_bytes, zcap;
    bool connected;
    uint64_t next_attempt_ns, connects;
    int quiet_failures; /* reconnect attempts since the last message */
    hal_frame_stats unpresented;
    hal_status frame_status; /* the frame's first band that failed for good (HAL_ERR_IO), else HAL_OK */
    char why[200];      /* detail of the last failed transfer */
} gud_host;

void gud_config_default(gud_config *c)
{
    memset(c, 0, sizeof *c);
    c->vid = GUD_VID_OPENMOKO;
    c->pid = GUD_PID_GUD;
    c->compression = -1;
    c->timeout_ms = 1000;
    c->retries = 2;
    c->reconnect_ms = 500;
    c->max_band_bytes = 64u * 1024u; /* a transfer buffer, not a frame: 800x480 RGB565 takes 12 */
}

static hal_status from_libusb(int r)
{
    switch (r) {
    case LIBUSB_ERROR_NO_DEVICE:
    case LIBUSB_ERROR_NOT_FOUND:
        return HAL_ERR_NO_DEVICE;
    case LIBUSB_ERROR_TIMEOUT:
        return HAL_ERR_TIMEOUT;
    case LIBUSB_ERROR_PIPE:
    case LIBUSB_ERROR_OVERFLOW:
        return HAL_ERR_PROTOCOL;
    default:
        return HAL_ERR_IO;
    }
}

/* ----------------------------------------------------------- control */

static const char *req_name(uint8_t req)
{
    switch (req) {
    case GUD_REQ_GET_STATUS: return "GET_STATUS";
    case GUD_REQ_GET_DESCRIPTOR: return "GET_DESCRIPTOR";
    case GUD_REQ_GET_FORMATS: return "GET_FORMATS";
    case GUD_REQ_GET_PROPERTIES: return "GET_PROPERTIES";
    case GUD_REQ_GET_CONNECTORS: return "GET_CONNECTORS";
    case GUD_REQ_GET_CONNECTOR_MODES: return "GET_CONNECTOR_MODES";
    case GUD_REQ_SET_BUFFER: return "SET_BUFFER";
    case GUD_REQ_SET_STATE_CHECK: return "SET_STATE_CHECK";
    case GUD_REQ_SET_STATE_COMMIT: return "SET_STATE_COMMIT";
    case GUD_REQ_SET_CONTROLLER_ENABLE: return "SET_CONTROLLER_ENABLE";
    case GUD_REQ_SET_DISPLAY_ENABLE: return "SET_DISPLAY_ENABLE";
    }
    return "request";
}

/*
 * One vendor request to the interface. IN returns the byte count in *got.
 * A stall (or any SET, if the device asks) is followed by GET_STATUS so the
 * error can say what the device objected to.
 */
static hal_status ctrl(gud_host *g, bool in, uint8_t req, uint16_t value, uint8_t *buf, uint16_t len,
                      int *got)
{
    uint8_t type = LIBUSB_REQUEST_TYPE_VENDOR | LIBUSB_RECIPIENT_INTERFACE |
                   (in ? LIBUSB_ENDPOINT_IN : LIBUSB_ENDPOINT_OUT);
    int r = libusb_control_transfer(g->h, type, req, value, (uint16_t)g->iface, buf, len,
                                    g->cfg.timeout_ms);
    if (r == LIBUSB_ERROR_PIPE || (!in && r >= 0 && (g->desc.flags & GUD_FLAG_STATUS_ON_SET))) {
        uint8_t st = 0xff;
        int s = libusb_control_transfer(g->h, LIBUSB_REQUEST_TYPE_VENDOR | LIBUSB_RECIPIENT_INTERFACE |
                                                  LIBUSB_ENDPOINT_IN,
                                        GUD_REQ_GET_STATUS, 0, (uint16_t)g->iface, &st, 1,
                                        g->cfg.timeout_ms);
        if (s == 1 && st != GUD_STATUS_OK) {
            snprintf(g->why, sizeof g->why, "%s refused by the device: %s", req_name(req),
                     gud_status_name(st));
            return st == GUD_STATUS_BUSY ? HAL_ERR_TIMEOUT : HAL_ERR_PROTOCOL;
        }
        if (s < 0 && s != LIBUSB_ERROR_PIPE) {
            snprintf(g->why, sizeof g->why, "%s, then GET_STATUS: %s", req_name(req),
                     libusb_error_name(s));
            return from_libusb(s);
        }
        if (r == LIBUSB_ERROR_PIPE) {
            snprintf(g->why, sizeof g->why, "%s stalled (status %s)", req_name(req),
                     s == 1 ? gud_status_name(st) : "unavailable");
            return HAL_ERR_PROTOCOL;
        }
    }
    if (r < 0) {
        snprintf(g->why, sizeof g->why, "%s: %s", req_name(req), libusb_error_name(r));
        return from_libusb(r);
    }
    if (got)
        *got = r;
    else if (r != len) {
        snprintf(g->why, sizeof g->why, "%s moved %d of %u bytes", req_name(req), r, len);
        return HAL_ERR_PROTOCOL;
    }
    return HAL_OK;
}

static hal_status set_u8(gud_host *g, uint8_t req, uint8_t v)
{
    return ctrl(g, false, req, 0, &v, 1, NULL);
}

/* --------------------------------------------------------- handshake */

static void close_handle(gud_host *g)
{
    if (g->h) {
        libusb_release_interface(g->h, g->iface);
        libusb_close(g->h);
        g->h = NULL;
    }
    g->connected = false;
}

/* The vendor-class interface with a bulk OUT endpoint, if the device has one. */
static bool find_interface(libusb_device *dev, int *iface, uint8_t *ep)
{
    struct libusb_config_descriptor *cd;
    if (libusb_get_active_config_descriptor(dev, &cd) != 0 &&
        libusb_get_config_descriptor(dev, 0, &cd) != 0)
        return false;
    bool found = false;
    for (int i = 0; i < cd->bNumInterfaces && !found; i++) {
        if (cd->interface[i].num_altsetting < 1)
            continue;
        const struct libusb_interface_descriptor *id = &cd->interface[i].altsetting[0];
        if (id->bInterfaceClass != LIBUSB_CLASS_VENDOR_SPEC)
            continue;
        for (int e = 0; e < id->bNumEndpoints; e++) {
            const struct libusb_endpoint_descriptor *ed = &id->endpoint[e];
            if ((ed->bmAttributes & 0x3) == LIBUSB_TRANSFER_TYPE_BULK &&
                !(ed->bEndpointAddress & LIBUSB_ENDPOINT_IN)) {
                *iface = id->bInterfaceNumber;
                *ep = ed->bEndpointAddress;
                found = true;
                break;
            }
        }
    }
    libusb_free_config_descriptor(cd);
    return found;
}

static hal_status choose_format(gud_host *g, char *err, size_t errlen)
{
    uint8_t f[GUD_FORMATS_MAX];
    int n = 0;
    hal_status s = ctrl(g, true, GUD_REQ_GET_FORMATS, 0, f, sizeof f, &n);
    if (s != HAL_OK) {
        snprintf(err, errlen, "reading formats: %s", g->why);
        return s;
    }
    bool has565 = false, has8888 = false;
    char list[200] = "";
    size_t used = 0;
    for (int i = 0; i < n; i++) {
        has565 |= f[i] == GUD_FORMAT_RGB565;
        has8888 |= f[i] == GUD_FORMAT_XRGB8888;
        if (used < sizeof list)
            used += (size_t)snprintf(list + used, sizeof list - used, "%s%s(0x%02x)", i ? " " : "",
                                     gud_format_name(f[i]), f[i]);
    }
    if (g->cfg.format) {
        if ((g->cfg.format == GUD_FORMAT_RGB565 && has565) ||
            (g->cfg.format == GUD_FORMAT_XRGB8888 && has8888)) {
            g->format = g->cfg.format;
        } else {
            snprintf(err, errlen, "format %s was asked for, the device offers: %s",
                     gud_format_name(g->cfg.format), n ? list : "nothing");
            return HAL_ERR_PROTOCOL;
        }
    } else if (has565) {
        g->format = GUD_FORMAT_RGB565; /* half the bytes; the kernel prefers it too */
    } else if (has8888) {
        g->format = GUD_FORMAT_XRGB8888;
    } else {
        snprintf(err, errlen, "no pixel format celfw can send (RGB565 or XRGB8888); the device offers: %s",
                 n ? list : "nothing");
        return HAL_ERR_PROTOCOL;
    }
    g->bpp = gud_format_bpp(g->format);
    g->d.pixfmt = g->format == GUD_FORMAT_RGB565 ? CS_PIX_RGB565_SRGB : HAL_PIX_XRGB8888;
    return HAL_OK;
}

/* Whether celfw can render a mode (a pitch of 0 once divided by zero); why not in why. */
static bool mode_usable(const gud_mode *m, char *why, size_t n)
{
    if (m->hdisplay && m->vdisplay && m->hdisplay <= CS_CFG_MAX_WIDTH && m->vdisplay <= CS_CFG_MAX_HEIGHT)
        return true;
    if (why && (!m->hdisplay || !m->vdisplay))
        snprintf(why, n, "mode %ux%u has no pixels", m->hdisplay, m->vdisplay);
    else if (why)
        snprintf(why, n, "mode %ux%u is larger than celfw renders (%dx%d at most)", m->hdisplay, m->vdisplay,
                 CS_CFG_MAX_WIDTH, CS_CFG_MAX_HEIGHT);
    return false;
}

static hal_status choose_mode(gud_host *g, int want_w, int want_h, char *err, size_t errlen)
{
    uint8_t buf[GUD_CONNECTOR_SIZE * 4];
    int n = 0;
    hal_status s = ctrl(g, true, GUD_REQ_GET_CONNECTORS, 0, buf, sizeof buf, &n);
    if (s != HAL_OK) {
        snprintf(err, errlen, "reading connectors: %s", g->why);
        return s;
    }
    if (n < GUD_CONNECTOR_SIZE) {
        snprintf(err, errlen, "the device reports no connector");
        return HAL_ERR_PROTOCOL;
    }
    uint8_t modes[GUD_MODE_SIZE * 32];
    n = 0;
    s = ctrl(g, true, GUD_REQ_GET_CONNECTOR_MODES, 0, modes, sizeof modes, &n);
    if (s != HAL_OK) {
        snprintf(err, errlen, "reading modes: %s", g->why);
        return s;
    }
    if (n % GUD_MODE_SIZE != 0) {
        snprintf(err, errlen, "the mode list is %d bytes, not a whole number of %d-byte modes", n,
                 GUD_MODE_SIZE);
        return HAL_ERR_PROTOCOL;
    }
    /* The configured size if given, else the preferred mode, else the first;
     * never a mode celfw cannot render (a device may list nonsense). */
    int count = n / GUD_MODE_SIZE, pick = -1, usable = 0;
    char list[200] = "", bad[120] = "";
    size_t used = 0;
    for (int i = 0; i < count; i++) {
        gud_mode m;
        gud_mode_decode(modes + i * GUD_MODE_SIZE, &m);
        if (used < sizeof list)
            used += (size_t)snprintf(list + used, sizeof list - used, "%s%ux%u", i ? " " : "",
                                     m.hdisplay, m.vdisplay);
        if (!mode_usable(&m, bad[0] ? NULL : bad, sizeof bad))
            continue;
        usable++;
        bool take;
        if (want_w)
            take = pick < 0 && m.hdisplay == want_w && m.vdisplay == want_h;
        else
            take = pick < 0 || ((m.flags & GUD_MODE_FLAG_PREFERRED) &&
                                !(g->mode.flags & GUD_MODE_FLAG_PREFERRED));
        if (take) {
            pick = i;
            g->mode = m;
        }
    }
    if (pick < 0 && count > 0 && !usable) {
        snprintf(err, errlen, "%s", bad); /* the device is broken, not the configuration */
        return HAL_ERR_PROTOCOL;
    }
    if (pick < 0 && count > 0) {
        snprintf(err, errlen, "no %dx%d mode; the device offers %s", want_w, want_h, list);
        return HAL_ERR_CONFIG;
    }
    if (pick < 0) {
        /* No mode list (an EDID-only device): describe the size asked for. */
        int w = want_w, h = want_h;
        if (!w && g->desc.min_width == g->desc.max_width && g->desc.min_height == g->desc.max_height) {
            if (g->desc.max_width > CS_CFG_MAX_WIDTH || g->desc.max_height > CS_CFG_MAX_HEIGHT) {
                snprintf(err, errlen, "the device's size %ux%u is larger than celfw renders (%dx%d at most)",
                         g->desc.max_width, g->desc.max_height, CS_CFG_MAX_WIDTH, CS_CFG_MAX_HEIGHT);
                return HAL_ERR_PROTOCOL;
            }
            w = (int)g->desc.max_width;
            h = (int)g->desc.max_height;
        }
        if (!w) {
            snprintf(err, errlen, "the device lists no modes; give the size (--size WxH)");
            return HAL_ERR_CONFIG;
        }
        memset(&g->mode, 0, sizeof g->mode);
        g->mode.hdisplay = g->mode.hsync_start = g->mode.hsync_end = g->mode.htotal = (uint16_t)w;
        g->mode.vdisplay = g->mode.vsync_start = g->mode.vsync_end = g->mode.vtotal = (uint16_t)h;
        g->mode.clock = (uint32_t)((uint64_t)w * (uint64_t)h * 60u / 1000u);
    }
    if (!mode_usable(&g->mode, err, errlen))
        return HAL_ERR_PROTOCOL; /* a size taken from the descriptor */
    if (g->mode.hdisplay < g->desc.min_width || g->mode.hdisplay > g->desc.max_width ||
        g->mode.vdisplay < g->desc.min_height || g->mode.vdisplay > g->desc.max_height) {
        snprintf(err, errlen, "mode %ux%u is outside the device's %ux%u..%ux%u", g->mode.hdisplay,
                 g->mode.vdisplay, g->desc.min_width, g->desc.min_height, g->desc.max_width,
                 g->desc.max_height);
        return HAL_ERR_PROTOCOL;
    }
    return HAL_OK;
}

static hal_status set_state(gud_host *g, char *err, size_t errlen)
{
    uint8_t st[GUD_STATE_SIZE(1)];
    int nprops = g->rotation_prop ? 1 : 0;
    gud_mode_encode(st, &g->mode);
    st[GUD_MODE_SIZE] = g->format;
    st[GUD_MODE_SIZE + 1] = 0; /* connector 0 */
    if (nprops) {
        gud_put16(st + GUD_MODE_SIZE + 2, GUD_PROPERTY_ROTATION);
        gud_put64(st + GUD_MODE_SIZE + 4, GUD_ROTATION_0);
    }
    hal_status s;
    if ((s = ctrl(g, false, GUD_REQ_SET_STATE_CHECK, 0, st, (uint16_t)GUD_STATE_SIZE(nprops), NULL)) ||
        (s = set_u8(g, GUD_REQ_SET_CONTROLLER_ENABLE, 1)) ||
        (s = ctrl(g, false, GUD_REQ_SET_STATE_COMMIT, 0, NULL, 0, NULL)) ||
        (s = set_u8(g, GUD_REQ_SET_DISPLAY_ENABLE, 1))) {
        snprintf(err, errlen, "setting the display state (%ux%u %s): %.150s", g->mode.hdisplay,
                 g->mode.vdisplay, gud_format_name(g->format), g->why);
        return s;
    }
    return HAL_OK;
}

/* Sizes the band to the device's buffer; allocates on the first connect. */
static hal_status setup_buffers(gud_host *g, char *err, size_t errlen)
{
    size_t cap = g->cfg.max_band_bytes;
    if (g->desc.max_buffer_size && g->desc.max_buffer_size < cap)
        cap = g->desc.max_buffer_size;
    g->pitch = (size_t)g->width * g->bpp; /* width and bpp were checked: never 0 */
    g->line_bytes = g->pitch; /* whole frames until a begin_frame says otherwise */
    g->win_x0 = 0;
    g->win_x1 = g->width;
    if (g->full_update) {
        cap = g->pitch * (size_t)g->height; /* the whole frame goes in one transfer */
        if (cap > GUD_MAX_FULL_FRAME) {
            snprintf(err, errlen, "a full-update frame of %zu bytes is more than celfw buffers (%u)", cap,
                     GUD_MAX_FULL_FRAME);
            return HAL_ERR_PROTOCOL;
        }
    }
    if (cap < g->pitch) {
        snprintf(err, errlen, "the device buffer (%zu bytes) cannot take one %zu-byte line", cap, g->pitch);
        return HAL_ERR_PROTOCOL;
    }
    int lines = (int)(cap / g->pitch);
    if (lines > g->height)
        lines = g->height;
    size_t bytes = (size_t)lines * g->pitch;
    if (lines != g->band_cap || bytes != g->band_bytes) { /* a replug may change the format */
        free(g->band);
        free(g->zbuf);
        free(g->band_hash);
        g->band_cap = lines;
        g->band_bytes = bytes;
        g->zcap = (size_t)LZ4_compressBound((int)bytes);
        g->band = malloc(bytes);
        g->zbuf = malloc(g->zcap);
        g->band_hash = malloc((size_t)lines * sizeof *g->band_hash);
        if (!g->band || !g->zbuf || !g->band_hash) {
            g->band_cap = 0;
            g->band_bytes = 0;
            return HAL_ERR_NOMEM;
        }
    }
    g->band_n = 0;
    return HAL_OK;
}

/* The probe and state setup on an opened, claimed device. */
static hal_status handshake(gud_host *g, char *err, size_t errlen)
{
    uint8_t raw[GUD_DESCRIPTOR_SIZE];
    int n = 0;
    memset(&g->desc, 0, sizeof g->desc);
    hal_status s = ctrl(g, true, GUD_REQ_GET_DESCRIPTOR, 0, raw, sizeof raw, &n);
    if (s != HAL_OK) {
        snprintf(err, errlen, "reading the display descriptor: %s", g->why);
        return s;
    }
    gud_descriptor desc;
    gud_descriptor_decode(raw, &desc);
    if (n != GUD_DESCRIPTOR_SIZE || desc.magic != GUD_MAGIC) {
        snprintf(err, errlen, "not a GUD display (descriptor of %d bytes, magic 0x%08x)", n, desc.magic);
        return HAL_ERR_PROTOCOL;
    }
    if (desc.version != 1 || !desc.max_width || !desc.max_height || desc.min_width > desc.max_width ||
        desc.min_height > desc.max_height) {
        snprintf(err, errlen, "unusable display descriptor (version %u, %ux%u..%ux%u)", desc.version,
                 desc.min_width, desc.min_height, desc.max_width, desc.max_height);
        return HAL_ERR_PROTOCOL;
    }
    g->desc = desc;
    g->full_update = (desc.flags & GUD_FLAG_FULL_UPDATE) != 0;
    if ((s = choose_format(g, err, errlen)) != HAL_OK)
        return s;
    bool offers_lz4 = (desc.compression & GUD_COMPRESSION_LZ4) && !g->full_update;
    if (g->cfg.compression == 1 && !offers_lz4) {
        snprintf(err, errlen, "LZ4 compression was asked for, the device does not offer it");
        return HAL_ERR_CONFIG;
    }
    g->lz4 = g->cfg.compression != 0 && offers_lz4;

    uint8_t props[GUD_PROPERTY_SIZE * GUD_PROPERTIES_MAX];
    n = 0;
    g->rotation_prop = false;
    if (ctrl(g, true, GUD_REQ_GET_PROPERTIES, 0, props, sizeof props, &n) == HAL_OK)
        for (int i = 0; i + GUD_PROPERTY_SIZE <= n; i += GUD_PROPERTY_SIZE)
            g->rotation_prop |= gud_get16(props + i) == GUD_PROPERTY_ROTATION;

    int want_w = g->width ? g->width : g->cfg.width, want_h = g->height ? g->height : g->cfg.height;
    if ((s = choose_mode(g, want_w, want_h, err, errlen)) != HAL_OK)
        return s;
    if (g->width && (g->mode.hdisplay != g->width || g->mode.vdisplay != g->height)) {
        snprintf(err, errlen, "the display came back as %ux%u, celfw renders %dx%d", g->mode.hdisplay,
                 g->mode.vdisplay, g->width, g->height);
        return HAL_ERR_CONFIG;
    }
    g->width = g->mode.hdisplay;
    g->height = g->mode.vdisplay;
    if ((s = set_state(g, err, errlen)) != HAL_OK)
        return s;
    return setup_buffers(g, err, errlen);
}

/* Finds, opens and sets up the display. */
static hal_status connect_device(gud_host *g, char *err, size_t errlen)
{
    libusb_device **list = NULL;
    ssize_t n = libusb_get_device_list(g->ctx, &list);
    if (n < 0) {
        snprintf(err, errlen, "cannot list USB devices: %s", libusb_error_name((int)n));
        return HAL_ERR_IO;
    }
    hal_status result = HAL_ERR_NO_DEVICE;
    if (g->cfg.vid || g->cfg.pid)
        snprintf(err, errlen, "no USB device %04x:%04x", g->cfg.vid, g->cfg.pid);
    else
        snprintf(err, errlen, "no USB device with a vendor-class interface answering as a GUD display");
    for (ssize_t i = 0; i < n; i++) {
        struct libusb_device_descriptor dd;
        if (libusb_get_device_descriptor(list[i], &dd) != 0)
            continue;
        if ((g->cfg.vid || g->cfg.pid) && (dd.idVendor != g->cfg.vid || dd.idProduct != g->cfg.pid))
            continue;
        int iface;
        uint8_t ep;
        if (!find_interface(list[i], &iface, &ep)) {
            if (g->cfg.vid || g->cfg.pid) {
                snprintf(err, errlen, "USB device %04x:%04x has no vendor-class interface with a bulk OUT endpoint",
                         dd.idVendor, dd.idProduct);
                result = HAL_ERR_PROTOCOL;
            }
            continue;
        }
        int r = libusb_open(list[i], &g->h);
        if (r != 0) {
            snprintf(err, errlen, "cannot open USB device %04x:%04x on bus %d address %d: %s%s",
                     dd.idVendor, dd.idProduct, libusb_get_bus_number(list[i]),
                     libusb_get_device_address(list[i]), libusb_error_name(r),
                     r == LIBUSB_ERROR_ACCESS ? " (permissions of /dev/bus/usb: a udev rule is needed)" : "");
            result = from_libusb(r);
            g->h = NULL;
            continue;
        }
        libusb_set_auto_detach_kernel_driver(g->h, 1);
        r = libusb_claim_interface(g->h, iface);
        if (r != 0) {
            snprintf(err, errlen, "cannot claim interface %d of %04x:%04x: %s", iface, dd.idVendor,
                     dd.idProduct, libusb_error_name(r));
            result = from_libusb(r);
            libusb_close(g->h);
            g->h = NULL;
            continue;
        }
        g->iface = iface;
        g->ep_out = ep;
        g->vid = dd.idVendor;
        g->pid = dd.idProduct;
        g->bus = libusb_get_bus_number(list[i]);
        g->address = libusb_get_device_address(list[i]);
        char herr[240];
        result = handshake(g, herr, sizeof herr);
        if (result == HAL_OK) {
            g->connected = true;
            g->connects++;
            lx_damage_invalidate(&g->damage, 0, g->height);
            g->need_set_buffer = true;
            break;
        }
        snprintf(err, errlen, "USB device %04x:%04x (bus %d address %d): %s", dd.idVendor, dd.idProduct,
                 g->bus, g->address, herr);
        close_handle(g);
        if (g->cfg.vid || g->cfg.pid)
            break; /* the device named in the configuration is broken: say so */
    }
    libusb_free_device_list(list, 1);
    return result;
}

/* --------------------------------------------------------------- pixels */

static void lost(gud_host *g, const char *during)
{
    hal_display_say(&g->d, "display disconnected (%s during %s); retrying every %u ms", g->why, during,
        g->cfg.reconnect_ms);
    close_handle(g);
    g->next_attempt_ns = hal_now(g->d.clock) + (uint64_t)g->cfg.reconnect_ms * 1000000u;
    g->quiet_failures = 0;
}

/* One SET_BUFFER + bulk OUT. */
static hal_status send_rect(gud_host *g, const gud_set_buffer *req, const uint8_t *payload, int len)
{
    if (!g->full_update || g->need_set_buffer) {
        uint8_t raw[GUD_SET_BUFFER_SIZE];
        gud_set_buffer_encode(raw, req);
        hal_status s = ctrl(g, false, GUD_REQ_SET_BUFFER, 0, raw, sizeof raw, NULL);
        if (s != HAL_OK)
            return s;
    }
    int done = 0;
    int r = libusb_bulk_transfer(g->h, g->ep_out, (unsigned char *)payload, len, &done, g->cfg.timeout_ms);
    if (r == 0 && done == len) {
        g->need_set_buffer = false;
        return HAL_OK;
    }
    g->need_set_buffer = true;
    if (r == 0) {
        snprintf(g->why, sizeof g->why, "bulk OUT moved %d of %d bytes", done, len);
        return HAL_ERR_IO;
    }
    snprintf(g->why, sizeof g->why, "bulk OUT of %d bytes: %s", len, libusb_error_name(r));
    if (r == LIBUSB_ERROR_PIPE) {
        /* The endpoint halted: clear it so the next transfer can go. */
        int c = libusb_clear_halt(g->h, g->ep_out);
        if (c == LIBUSB_ERROR_NO_DEVICE)
            return HAL_ERR_NO_DEVICE;
    }
    return from_libusb(r);
}

/* Sends the band of changed lines; on success their hashes become current. */
static hal_status flush_band(gud_host *g, hal_frame_stats *st)
{
    if (g->band_n == 0)
        return HAL_OK;
    int n = g->band_n;
    g->band_n = 0;
    size_t len = (size_t)n * g->line_bytes;
    gud_set_buffer req = {(uint32_t)g->win_x0, (uint32_t)g->band_y0, (uint32_t)(g->win_x1 - g->win_x0),
                          (uint32_t)n, (uint32_t)len, 0, 0};
    const uint8_t *payload = g->band;
    int plen = (int)len;
    if (g->lz4) {
        int c = LZ4_compress_default((const char *)g->band, (char *)g->zbuf, (int)len, (int)g->zcap);
        if (c > 0 && (size_t)c < len) { /* incompressible bands go raw */
            req.compression = GUD_COMPRESSION_LZ4;
            req.compressed_length = (uint32_t)c;
            payload = g->zbuf;
            plen = c;
        }
    }
    hal_status s = HAL_ERR_IO;
    for (int attempt = 0; attempt <= g->cfg.retries; attempt++) {
        if (attempt)
            st->retries++;
        s = send_rect(g, &req, payload, plen);
        if (s == HAL_OK || s == HAL_ERR_NO_DEVICE)
            break;
        if (attempt < g->cfg.retries)
            hal_display_say(&g->d, "rectangle y=%d..%d: %s; retrying", g->band_y0, g->band_y0 + n - 1, g->why);
    }
    if (s == HAL_OK) {
        for (int i = 0; i < n; i++)
            lx_damage_commit(&g->damage, g->band_y0 + i, g->band_hash[i]);
        st->rects++;
        st->lines_sent += (uint64_t)n;
        st->bytes_raw += len;
        st->bytes_wire += (uint64_t)plen;
        return HAL_OK;
    }
    lx_damage_invalidate(&g->damage, g->band_y0, g->band_y0 + n);
    st->errors++;
    if (s == HAL_ERR_NO_DEVICE) {
        lost(g, "a frame");
        return s;
    }
    /* The frame goes on (its other bands still travel) and these lines travel
     * again next frame; end_frame reports the write that failed. */
    if (g->frame_status == HAL_OK)
        g->frame_status = hal_display_fail(&g->d, HAL_ERR_IO,
                                           "rectangle y=%d..%d: %s, %d attempts; sent again next frame",
                                           g->band_y0, g->band_y0 + n - 1, g->why, 1 + g->cfg.retries);
    return HAL_OK;
}

/* A frame starts: the display is (re)connected if it was away. */
static hal_status gud_begin_frame(hal_display *d, const hal_window *win)
{
    gud_host *g = (gud_host *)d;
    if (win && (!g->connected || g->full_update))
        return hal_display_fail(d, HAL_ERR_CONFIG, "%s", g->connected ? "a full-update device takes whole frames"
                                                                         : "a reconnect needs a whole frame");
    if (win && !hal_window_inside(win, g->width, g->height))
        return hal_display_fail(d, HAL_ERR_CONFIG, "window %d,%d..%d,%d outside %dx%d", win->x0, win->y0,
                                win->x1, win->y1, g->width, g->height);
    if (!g->connected) {
        uint64_t now = hal_now(d->clock);
        if (now < g->next_attempt_ns)
            return hal_display_fail(d, HAL_ERR_NO_DEVICE, "display absent");
        char err[256];
        hal_status s = connect_device(g, err, sizeof err);
        if (s != HAL_OK) {
            g->next_attempt_ns = now + (uint64_t)g->cfg.reconnect_ms * 1000000u;
            /* say why now and then, not on every attempt */
            if (g->quiet_failures++ % 20 == 0)
                hal_display_say(d, "display not back yet: %s", err);
            return hal_display_fail(d, HAL_ERR_NO_DEVICE, "%.240s", err);
        }
        hal_display_say(d, "display connected: %04x:%04x bus %d address %d, %dx%d %s%s", g->vid, g->pid,
                        g->bus, g->address, g->width, g->height, gud_format_name(g->format),
                        g->lz4 ? " lz4" : "");
    }
    if (!d->st)
        d->st = &g->unpresented; /* pushed without hal_display_present: counts go nowhere */
    g->band_n = 0;
    g->frame_status = HAL_OK;
    g->win_x0 = win ? win->x0 : 0;
    g->win_x1 = win ? win->x1 : g->width;
    g->line_bytes = (size_t)(g->win_x1 - g->win_x0) * g->bpp;
    return HAL_OK;
}

/* A changed line joins the band; an unchanged one closes it (sent as one rectangle). */
static hal_status gud_line_out(hal_display *d, int y, const uint8_t *px, size_t len)
{
    gud_host *g = (gud_host *)d;
    if (!g->connected || y < 0 || y >= g->height || len != g->line_bytes)
        return hal_display_fail(d, HAL_ERR_SEQUENCE, "line %d of %zu bytes outside a frame of %d lines of %zu",
                                y, len, g->height, g->line_bytes);
    hal_status s = HAL_OK;
    bool full_width = g->line_bytes == g->pitch;
    uint64_t h = full_width ? lx_line_hash(px, g->pitch) : 0; /* 0: unknown, sent next time */
    if (g->full_update || !full_width || lx_damage_changed(&g->damage, y, h)) {
        if (g->band_n == 0)
            g->band_y0 = y;
        memcpy(g->band + (size_t)g->band_n * g->line_bytes, px, g->line_bytes);
        g->band_hash[g->band_n++] = h;
        if (g->band_n == g->band_cap)
            s = flush_band(g, d->st);
    } else if (g->band_n) {
        s = flush_band(g, d->st);
    }
    if (s == HAL_ERR_NO_DEVICE)
        return hal_display_fail(d, s, "display disconnected: %s", g->why);
    return s;
}

static hal_status gud_end_frame(hal_display *d)
{
    gud_host *g = (gud_host *)d;
    hal_status s = flush_band(g, d->st);
    if (s == HAL_ERR_NO_DEVICE)
        return hal_display_fail(d, s, "display disconnected: %s", g->why);
    return s == HAL_OK ? g->frame_status : s;
}

static bool gud_connected(hal_display *d)
{
    return ((gud_host *)d)->connected;
}

static void gud_close(hal_display *d)
{
    gud_host *g = (gud_host *)d;
    if (g->connected) {
        set_u8(g, GUD_REQ_SET_DISPLAY_ENABLE, 0);
        set_u8(g, GUD_REQ_SET_CONTROLLER_ENABLE, 0);
    }
    close_handle(g);
    if (g->ctx)
        libusb_exit(g->ctx);
    lx_damage_free(&g->damage);
    free(g->band);
    free(g->zbuf);
    free(g->band_hash);
    free(g);
}

static const hal_display_api gud_api = {
    .name = "usb",
    .begin_frame = gud_begin_frame,
    .line_out = gud_line_out,
    .end_frame = gud_end_frame,
    .connected = gud_connected,
    .close = gud_close,
};

hal_status gud_open(hal_display **out, const gud_config *c, const hal_clock *clock, hal_log_fn log,
                   void *log_user, char *err, size_t errlen)
{
    if (c->wait && (c->width <= 0 || c->height <= 0)) {
        snprintf(err, errlen, "usb: waiting for an absent display needs its size (--size WxH)");
        return HAL_ERR_CONFIG;
    }
    if (c->width < 0 || c->height < 0 || c->width > CS_CFG_MAX_WIDTH || c->height > CS_CFG_MAX_HEIGHT) {
        snprintf(err, errlen, "usb: size %dx%d out of range (%dx%d at most)", c->width, c->height,
                 CS_CFG_MAX_WIDTH, CS_CFG_MAX_HEIGHT);
        return HAL_ERR_CONFIG;
    }
    gud_host *g = calloc(1, sizeof *g);
    if (!g)
        return HAL_ERR_NOMEM;
    g->cfg = *c;
    if (g->cfg.timeout_ms == 0)
        g->cfg.timeout_ms = 1000;
    g->d.api = &gud_api;
    g->d.pixfmt = HAL_PIX_XRGB8888; /* until a device says what it takes */
    g->d.clock = clock;
    g->d.log = log;
    g->d.log_user = log_user;
    int r = libusb_init(&g->ctx);
    if (r != 0) {
        snprintf(err, errlen, "usb: libusb cannot start: %s%s", libusb_error_name(r),
                 r == LIBUSB_ERROR_OTHER ? " (no /dev/bus/usb?)" : "");
        g->ctx = NULL;
        gud_close(&g->d);
        return HAL_ERR_NO_DEVICE;
    }
    hal_status s = connect_device(g, err, errlen);
    /* Waiting, a device that is there but unusable (a hostile or broken
     * descriptor, a failed transfer) counts as absent: it may be replaced.
     * A contradiction with the configuration (no mode of the size asked
     * for) is the user's to fix. */
    bool absent = s == HAL_ERR_NO_DEVICE || s == HAL_ERR_PROTOCOL || s == HAL_ERR_IO || s == HAL_ERR_TIMEOUT;
    if (s != HAL_OK && !(c->wait && absent)) {
        char msg[300];
        snprintf(msg, sizeof msg, "usb: %s", err);
        snprintf(err, errlen, "%s", msg);
        gud_close(&g->d);
        return s;
    }
    if (s != HAL_OK) {
        g->width = c->width;
        g->height = c->height;
        hal_display_say(&g->d, "no display yet (%s); waiting", err);
    }
    g->d.width = g->width;
    g->d.height = g->height;
    if (!lx_damage_init(&g->damage, g->height)) {
        gud_close(&g->d);
        return HAL_ERR_NOMEM;
    }
    if (!g->connected)
        g->next_attempt_ns = 0;
    *out = &g->d;
    return HAL_OK;
}

void gud_get_info(hal_display *d, gud_info *info)
{
    gud_host *g = (gud_host *)d;
    memset(info, 0, sizeof *info);
    info->connected = g->connected;
    info->vid = g->vid;
    info->pid = g->pid;
    info->bus = g->bus;
    info->address = g->address;
    info->format = g->format;
    info->lz4 = g->lz4;
    info->max_buffer_size = g->desc.max_buffer_size;
    info->width = g->width;
    info->height = g->height;
    info->connects = g->connects;
}
