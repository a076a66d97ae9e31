/*
 * fake_gud.c - a GUD display behind emulated usbdevfs, for umockdev tests.
 *
 * URBs: SUBMITURB resolves the caller's struct usbdevfs_urb and its buffer
 * (umockdev copies them across), the device acts on it, and the URB waits in
 * the submitting fd's completion queue until REAPURBNDELAY hands its pointer
 * back (umockdev writes the URB and buffer back into the caller's memory). A
 * hung bulk URB waits in the pending list instead, until DISCARDURB completes
 * it with -ENOENT, which is what the kernel does when libusb times out.
 *
 * The handlers run on umockdev's worker thread; a mutex guards the device
 * state that the test reads.
 */
#include <errno.h>
#include <linux/usbdevice_fs.h>
#include <lz4.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>

#include "fake_gud.h"
#include "gud_wire.h"

typedef struct fd_state {
    unsigned gen;          /* device generation the fd was opened on */
    GQueue done, pending;  /* UMockdevIoctlData of URBs */
} fd_state;

struct fake_gud {
    UMockdevTestbed *tb;
    fake_gud_opts o;
    int bus, devnum;
    char syspath[256], node[64];
    UMockdevIoctlBase *base;
    GMutex mu;
    unsigned gen;   /* bumped on unplug: older fds are dead */
    bool unplugged;
    /* Nodes of earlier plugs, still served (every ioctl ENODEV, as the kernel
     * answers a process that holds a vanished device) until fake_gud_free:
     * detaching at the unplug reset the socket under a celfw mid-ioctl, and
     * umockdev's preload aborts on that. */
    char gone[8][64];
    int ngone;
    /* GUD state */
    uint8_t last_status;
    bool checked;
    uint8_t check_format, format;
    unsigned bpp;
    bool committed, controller_on, display_on;
    bool have_rect;
    gud_set_buffer rect;
    uint8_t *rx;
    size_t rx_len, rx_cap, expect;
    uint8_t *fb;
    bool halted;
    int stall_transfers, hang_transfers;
    uint8_t refuse_req, refuse_status;
    int refuse_times;
    fake_gud_stats st;
    fake_gud_rect *log;
    size_t nlog, caplog;
};

void fake_gud_opts_default(fake_gud_opts *o)
{
    memset(o, 0, sizeof *o);
    o->vid = 0x1d50;
    o->pid = 0x614d;
    o->width = 320;
    o->height = 180;
    o->formats[0] = GUD_FORMAT_RGB565;
    o->formats[1] = GUD_FORMAT_XRGB8888;
    o->nformats = 2;
    o->compression = GUD_COMPRESSION_LZ4;
    o->magic = GUD_MAGIC;
    o->version = 1;
}

/* --------------------------------------------------------------- GUD */

static bool valid_format(fake_gud *g, uint8_t f)
{
    for (int i = 0; i < g->o.nformats; i++)
        if (g->o.formats[i] == f)
            return gud_format_bpp(f) != 0;
    return false;
}

static void blit(fake_gud *g, const uint8_t *px)
{
    size_t pitch = (size_t)g->rect.width * g->bpp, fbpitch = (size_t)g->o.width * g->bpp;
    for (uint32_t r = 0; r < g->rect.height; r++)
        memcpy(g->fb + (size_t)(g->rect.y + r) * fbpitch + (size_t)g->rect.x * g->bpp,
               px + (size_t)r * pitch, pitch);
}

/* The whole rectangle arrived: decode it into the panel. */
static void rect_done(fake_gud *g)
{
    uint8_t *px = g->rx;
    uint8_t *tmp = NULL;
    if (g->rect.compression & GUD_COMPRESSION_LZ4) {
        tmp = malloc(g->rect.length);
        int n = LZ4_decompress_safe((const char *)g->rx, (char *)tmp, (int)g->rx_len, (int)g->rect.length);
        if (n != (int)g->rect.length) {
            g->st.protocol_errors++;
            free(tmp);
            g->have_rect = false;
            return;
        }
        px = tmp;
    }
    blit(g, px);
    free(tmp);
    g->st.rects++;
    g->st.raw_bytes += g->rect.length;
    if (g->nlog == g->caplog) {
        g->caplog = g->caplog ? 2 * g->caplog : 256;
        g->log = realloc(g->log, g->caplog * sizeof *g->log);
    }
    g->log[g->nlog++] = (fake_gud_rect){g->rect.x,      g->rect.y,      g->rect.width, g->rect.height,
                                        g->rect.length, (uint32_t)g->rx_len, g->rect.compression != 0};
    /* FULL_UPDATE devices keep the rectangle for the next transfer */
    g->have_rect = (g->o.flags & GUD_FLAG_FULL_UPDATE) != 0;
    g->rx_len = 0;
}

static uint8_t set_buffer(fake_gud *g, const uint8_t *p, int len)
{
    gud_set_buffer b;
    if (len != GUD_SET_BUFFER_SIZE)
        return GUD_STATUS_PROTOCOL_ERROR;
    if (!g->committed || !g->controller_on)
        return GUD_STATUS_PROTOCOL_ERROR;
    gud_set_buffer_decode(p, &b);
    uint64_t len_px = (uint64_t)b.width * b.height * g->bpp;
    if (!b.width || !b.height || b.x + b.width > (uint32_t)g->o.width ||
        b.y + b.height > (uint32_t)g->o.height || b.length != len_px ||
        (g->o.max_buffer_size && b.length > g->o.max_buffer_size))
        return GUD_STATUS_INVALID_PARAMETER;
    if (b.compression & ~g->o.compression)
        return GUD_STATUS_INVALID_PARAMETER;
    if (b.compression && (b.compressed_length == 0 || b.compressed_length > (uint32_t)LZ4_compressBound((int)b.length)))
        return GUD_STATUS_INVALID_PARAMETER;
    g->rect = b;
    g->have_rect = true;
    g->expect = b.compression ? b.compressed_length : b.length;
    g->rx_len = 0;
    if (g->rx_cap < g->expect) {
        g->rx = realloc(g->rx, g->expect);
        g->rx_cap = g->expect;
    }
    g->st.set_buffers++;
    return GUD_STATUS_OK;
}

/*
 * A control transfer; buf holds the 8-byte setup packet and the data stage.
 * Returns the data bytes moved, or -EPIPE to stall.
 */
static int control(fake_gud *g, uint8_t *buf, int buflen)
{
    uint8_t type = buf[0], req = buf[1];
    uint16_t value = gud_get16(buf + 2), index = gud_get16(buf + 4), wlen = gud_get16(buf + 6);
    uint8_t *data = buf + 8;
    (void)value;
    if (wlen > buflen - 8)
        return -EOVERFLOW;
    if ((type & 0x60) != 0x40 || (type & 0x1f) != 0x01 || index != 0)
        return -EPIPE; /* only vendor requests to interface 0 */
    bool in = type & 0x80;
    if (g->refuse_times > 0 && req == g->refuse_req) {
        g->refuse_times--;
        g->last_status = g->refuse_status;
        return -EPIPE;
    }
    if (in) {
        uint8_t out[GUD_MODE_SIZE * 4];
        int n = 0;
        switch (req) {
        case GUD_REQ_GET_STATUS:
            out[0] = g->last_status;
            n = 1;
            break;
        case GUD_REQ_GET_DESCRIPTOR: {
            gud_descriptor d = {g->o.magic, g->o.version, g->o.flags, g->o.compression,
                                g->o.max_buffer_size, (uint32_t)g->o.width, (uint32_t)g->o.width,
                                (uint32_t)g->o.height, (uint32_t)g->o.height};
            if (g->o.any_size) {
                d.min_width = d.min_height = 0;
                d.max_width = d.max_height = 65535;
            }
            gud_descriptor_encode(out, &d);
            n = g->o.descriptor_len ? g->o.descriptor_len : GUD_DESCRIPTOR_SIZE;
            break;
        }
        case GUD_REQ_GET_FORMATS:
            memcpy(out, g->o.formats, (size_t)g->o.nformats);
            n = g->o.nformats;
            break;
        case GUD_REQ_GET_PROPERTIES:
            gud_put16(out, GUD_PROPERTY_ROTATION);
            gud_put64(out + 2, GUD_ROTATION_0);
            n = GUD_PROPERTY_SIZE;
            break;
        case GUD_REQ_GET_CONNECTORS:
            out[0] = 0; /* panel */
            gud_put32(out + 1, 0);
            n = GUD_CONNECTOR_SIZE;
            break;
        case GUD_REQ_GET_CONNECTOR_MODES:
            if (!g->o.no_modes) {
                gud_mode m = {(uint32_t)((uint64_t)g->o.width * (uint64_t)g->o.height * 60u / 1000u),
                              (uint16_t)g->o.width, (uint16_t)g->o.width, (uint16_t)g->o.width,
                              (uint16_t)g->o.width, (uint16_t)g->o.height, (uint16_t)g->o.height,
                              (uint16_t)g->o.height, (uint16_t)g->o.height, GUD_MODE_FLAG_PREFERRED};
                gud_mode_encode(out, &m);
                n = g->o.modes_len ? g->o.modes_len : GUD_MODE_SIZE;
            }
            break;
        default:
            g->last_status = GUD_STATUS_REQUEST_NOT_SUPPORTED;
            return -EPIPE;
        }
        if (n > wlen)
            n = wlen;
        memcpy(data, out, (size_t)n);
        g->last_status = GUD_STATUS_OK;
        return n;
    }
    uint8_t st = GUD_STATUS_OK;
    switch (req) {
    case GUD_REQ_SET_BUFFER:
        st = set_buffer(g, data, wlen);
        break;
    case GUD_REQ_SET_STATE_CHECK: {
        g->st.state_checks++;
        gud_mode m;
        if (wlen < GUD_STATE_SIZE(0)) {
            st = GUD_STATUS_PROTOCOL_ERROR;
            break;
        }
        gud_mode_decode(data, &m);
        uint8_t f = data[GUD_MODE_SIZE], conn = data[GUD_MODE_SIZE + 1];
        if (m.hdisplay != g->o.width || m.vdisplay != g->o.height || !valid_format(g, f) || conn != 0 ||
            (wlen - GUD_STATE_SIZE(0)) % GUD_PROPERTY_SIZE != 0) {
            st = GUD_STATUS_INVALID_PARAMETER;
            g->checked = false;
        } else {
            g->checked = true;
            g->check_format = f;
        }
        break;
    }
    case GUD_REQ_SET_STATE_COMMIT:
        if (!g->checked) {
            st = GUD_STATUS_PROTOCOL_ERROR;
            break;
        }
        g->format = g->check_format;
        g->bpp = gud_format_bpp(g->format);
        free(g->fb);
        g->fb = calloc((size_t)g->o.width * (size_t)g->o.height, g->bpp);
        g->committed = true;
        g->have_rect = false;
        break;
    case GUD_REQ_SET_CONTROLLER_ENABLE:
    case GUD_REQ_SET_DISPLAY_ENABLE:
        if (wlen != 1 || data[0] > 1) {
            st = GUD_STATUS_INVALID_PARAMETER;
            break;
        }
        if (req == GUD_REQ_SET_CONTROLLER_ENABLE)
            g->controller_on = data[0];
        else
            g->display_on = data[0];
        break;
    default:
        st = GUD_STATUS_REQUEST_NOT_SUPPORTED;
    }
    g->last_status = st;
    if (st != GUD_STATUS_OK)
        return -EPIPE;
    return wlen;
}

/* Bulk OUT data; returns the URB status. */
static int bulk(fake_gud *g, const uint8_t *p, int len)
{
    if (!g->have_rect || g->rx_len + (size_t)len > g->expect) {
        g->st.protocol_errors++;
        return 0; /* the data is taken and dropped, as a device would */
    }
    memcpy(g->rx + g->rx_len, p, (size_t)len);
    g->rx_len += (size_t)len;
    g->st.bulk_bytes += (uint64_t)len;
    if (g->rx_len == g->expect)
        rect_done(g);
    return 0;
}

/* ------------------------------------------------------------ usbdevfs */

static fd_state *fd_of(UMockdevIoctlClient *client)
{
    return g_object_get_data(G_OBJECT(client), "fake-gud-fd");
}

static void fd_state_free(gpointer p)
{
    fd_state *f = p;
    UMockdevIoctlData *d;
    while ((d = g_queue_pop_head(&f->done)))
        g_object_unref(d);
    while ((d = g_queue_pop_head(&f->pending)))
        g_object_unref(d);
    free(f);
}

static void connected(UMockdevIoctlBase *base, UMockdevIoctlClient *client, gpointer user)
{
    (void)base;
    fake_gud *g = user;
    fd_state *f = calloc(1, sizeof *f);
    g_mutex_lock(&g->mu);
    f->gen = g->gen;
    g_mutex_unlock(&g->mu);
    g_queue_init(&f->done);
    g_queue_init(&f->pending);
    g_object_set_data_full(G_OBJECT(client), "fake-gud-fd", f, fd_state_free);
}

static void finish(UMockdevIoctlClient *client, int err)
{
    umockdev_ioctl_client_complete(client, err ? -1 : 0, err);
}

static int submit(fake_gud *g, fd_state *f, UMockdevIoctlData *arg)
{
    GError *e = NULL;
    UMockdevIoctlData *ud = umockdev_ioctl_data_resolve(arg, 0, sizeof(struct usbdevfs_urb), &e);
    if (!ud)
        return EFAULT;
    struct usbdevfs_urb *urb = (struct usbdevfs_urb *)ud->data;
    if (urb->buffer_length < 0)
        return EINVAL;
    UMockdevIoctlData *bd = NULL;
    if (urb->buffer_length > 0) {
        bd = umockdev_ioctl_data_resolve(ud, offsetof(struct usbdevfs_urb, buffer),
                                         (gsize)urb->buffer_length, &e);
        if (!bd)
            return EFAULT;
    }
    urb->actual_length = 0;
    urb->status = 0;
    if (urb->type == USBDEVFS_URB_TYPE_CONTROL && urb->endpoint == 0) {
        if (urb->buffer_length < 8)
            return EINVAL;
        int r = control(g, bd->data, urb->buffer_length);
        if (r < 0)
            urb->status = r;
        else
            urb->actual_length = r;
    } else if (urb->type == USBDEVFS_URB_TYPE_BULK && urb->endpoint == 0x01) {
        if (g->halted) {
            urb->status = -EPIPE;
        } else if (g->stall_transfers > 0) {
            g->stall_transfers--;
            g->halted = true;
            g->st.stalls++;
            g->have_rect = false; /* the device resets its receive state */
            urb->status = -EPIPE;
        } else if (g->hang_transfers > 0) {
            g_queue_push_tail(&f->pending, g_object_ref(ud));
            return 0;
        } else {
            urb->status = bulk(g, bd ? bd->data : NULL, urb->buffer_length);
            if (urb->status == 0)
                urb->actual_length = urb->buffer_length;
        }
    } else {
        return ENOENT; /* no such endpoint */
    }
    g_queue_push_tail(&f->done, g_object_ref(ud));
    return 0;
}

static int reap(fd_state *f, UMockdevIoctlData *arg, bool dead)
{
    UMockdevIoctlData *ud = g_queue_pop_head(&f->done);
    if (!ud)
        return dead ? ENODEV : EAGAIN;
    GError *e = NULL;
    UMockdevIoctlData *slot = umockdev_ioctl_data_resolve(arg, 0, sizeof(void *), &e);
    if (!slot) {
        g_object_unref(ud);
        return EFAULT;
    }
    /* hand back the caller's own URB pointer; umockdev writes the URB back */
    umockdev_ioctl_data_set_ptr(slot, 0, ud);
    g_object_unref(ud);
    return 0;
}

static int discard(fake_gud *g, fd_state *f, UMockdevIoctlData *arg)
{
    unsigned long addr = *(unsigned long *)arg->data;
    for (GList *l = f->pending.head; l; l = l->next) {
        UMockdevIoctlData *ud = l->data;
        if (ud->client_addr == addr) {
            g_queue_delete_link(&f->pending, l);
            ((struct usbdevfs_urb *)ud->data)->status = -ENOENT;
            g_queue_push_tail(&f->done, ud);
            g->st.discards++;
            g->have_rect = false;
            if (f->pending.length == 0 && g->hang_transfers > 0)
                g->hang_transfers--; /* that transfer timed out: the next may go */
            return 0;
        }
    }
    return EINVAL; /* already completed: the kernel says EINVAL too */
}

static gboolean on_ioctl(UMockdevIoctlBase *base, UMockdevIoctlClient *client, gpointer user)
{
    (void)base;
    fake_gud *g = user;
    fd_state *f = fd_of(client);
    gulong req = umockdev_ioctl_client_get_request(client);
    UMockdevIoctlData *arg = umockdev_ioctl_client_get_arg(client);
    GError *e = NULL;
    int err = 0;
    g_mutex_lock(&g->mu);
    bool dead = !f || f->gen != g->gen;
    if (dead && req != USBDEVFS_REAPURBNDELAY && req != USBDEVFS_REAPURB) {
        err = ENODEV;
    } else if (req == USBDEVFS_GET_CAPABILITIES) {
        UMockdevIoctlData *d = umockdev_ioctl_data_resolve(arg, 0, sizeof(uint32_t), &e);
        uint32_t caps = USBDEVFS_CAP_ZERO_PACKET | USBDEVFS_CAP_BULK_CONTINUATION |
                        USBDEVFS_CAP_NO_PACKET_SIZE_LIM | USBDEVFS_CAP_REAP_AFTER_DISCONNECT;
        if (d)
            memcpy(d->data, &caps, sizeof caps);
        else
            err = EFAULT;
    } else if (req == USBDEVFS_CLAIMINTERFACE || req == USBDEVFS_RELEASEINTERFACE) {
        UMockdevIoctlData *d = umockdev_ioctl_data_resolve(arg, 0, sizeof(unsigned int), &e);
        if (!d || *(unsigned int *)d->data != 0)
            err = EINVAL;
    } else if (req == USBDEVFS_GETDRIVER) {
        err = ENODATA; /* no kernel driver bound */
    } else if (req == USBDEVFS_DISCONNECT_CLAIM) {
        /* no driver to disconnect: this just claims, as the kernel does */
        UMockdevIoctlData *d =
            umockdev_ioctl_data_resolve(arg, 0, sizeof(struct usbdevfs_disconnect_claim), &e);
        if (!d || ((struct usbdevfs_disconnect_claim *)d->data)->interface != 0)
            err = EINVAL;
    } else if (req == USBDEVFS_IOCTL) {
        /* driver (dis)connect requests: with no driver bound, DISCONNECT is ENODATA */
        UMockdevIoctlData *d = umockdev_ioctl_data_resolve(arg, 0, sizeof(struct usbdevfs_ioctl), &e);
        if (!d)
            err = EFAULT;
        else if (((struct usbdevfs_ioctl *)d->data)->ioctl_code == (int)USBDEVFS_DISCONNECT)
            err = ENODATA;
    } else if (req == USBDEVFS_SUBMITURB) {
        err = submit(g, f, arg);
    } else if (req == USBDEVFS_REAPURBNDELAY) {
        err = reap(f, arg, dead);
    } else if (req == USBDEVFS_DISCARDURB) {
        err = discard(g, f, arg);
    } else if (req == USBDEVFS_CLEAR_HALT) {
        UMockdevIoctlData *d = umockdev_ioctl_data_resolve(arg, 0, sizeof(unsigned int), &e);
        if (d && *(unsigned int *)d->data == 0x01) {
            g->halted = false;
            g->st.clear_halts++;
        } else {
            err = EINVAL;
        }
    } else if (req == USBDEVFS_RESET || req == USBDEVFS_SETINTERFACE ||
               req == USBDEVFS_SETCONFIGURATION) {
        err = 0;
    } else {
        err = ENOTTY;
    }
    g_mutex_unlock(&g->mu);
    if (e)
        g_error_free(e);
    finish(client, err);
    return TRUE;
}

/* ----------------------------------------------------------- topology */

static void add_to_sysfs(fake_gud *g)
{
    const fake_gud_opts *o = &g->o;
    uint8_t dd[18 + 9 + 9 + 7] = {
        18, 1, 0x00, 0x02, 0, 0, 0, 64, (uint8_t)o->vid, (uint8_t)(o->vid >> 8), (uint8_t)o->pid,
        (uint8_t)(o->pid >> 8), 0x00, 0x01, 0, 0, 0, 1,
        /* configuration: one interface */
        9, 2, 25, 0, 1, 1, 0, 0x80, 0xfa,
        /* interface 0: vendor class, one endpoint */
        9, 4, 0, 0, 1, 0xff, 0, 0, 0,
        /* endpoint 0x01: bulk OUT, 512 bytes */
        7, 5, 0x01, 0x02, 0x00, 0x02, 0};
    char hex[2 * sizeof dd + 1];
    for (size_t i = 0; i < sizeof dd; i++)
        snprintf(hex + 2 * i, 3, "%02X", dd[i]);
    char rec[2048];
    snprintf(g->syspath, sizeof g->syspath, "/sys/devices/pci0000:00/0000:00:14.0/usb%d/%d-1", g->bus,
             g->bus);
    snprintf(g->node, sizeof g->node, "/dev/bus/usb/%03d/%03d", g->bus, g->devnum);
    snprintf(rec, sizeof rec,
             "P: /devices/pci0000:00/0000:00:14.0/usb%d/%d-1\n"
             "N: bus/usb/%03d/%03d\n"
             "E: SUBSYSTEM=usb\nE: DEVTYPE=usb_device\nE: DEVNAME=/dev/bus/usb/%03d/%03d\n"
             "E: BUSNUM=%03d\nE: DEVNUM=%03d\nE: PRODUCT=%x/%x/100\nE: DRIVER=usb\n"
             "A: busnum=%d\nA: devnum=%d\nA: bConfigurationValue=1\nA: bNumConfigurations=1\n"
             "A: speed=480\nA: idVendor=%04x\nA: idProduct=%04x\nA: dev=189:%d\n"
             "H: descriptors=%s\n\n",
             g->bus, g->bus, g->bus, g->devnum, g->bus, g->devnum, g->bus, g->devnum, o->vid, o->pid,
             g->bus, g->devnum, o->vid, o->pid, (g->bus - 1) * 128 + g->devnum - 1, hex);
    GError *e = NULL;
    if (!umockdev_testbed_add_from_string(g->tb, rec, &e)) {
        fprintf(stderr, "fake_gud: %s\n", e->message);
        abort();
    }
    if (!umockdev_testbed_attach_ioctl(g->tb, g->node, g->base, &e)) {
        fprintf(stderr, "fake_gud: %s\n", e->message);
        abort();
    }
}

fake_gud *fake_gud_add(UMockdevTestbed *tb, int bus, int devnum, const fake_gud_opts *o)
{
    fake_gud *g = calloc(1, sizeof *g);
    g->tb = tb;
    g->o = *o;
    g->bus = bus;
    g->devnum = devnum;
    g_mutex_init(&g->mu);
    g->base = umockdev_ioctl_base_new();
    g_signal_connect(g->base, "handle-ioctl", G_CALLBACK(on_ioctl), g);
    g_signal_connect(g->base, "client-connected", G_CALLBACK(connected), g);
    add_to_sysfs(g);
    return g;
}

void fake_gud_free(fake_gud *g)
{
    if (!g)
        return;
    if (!g->unplugged)
        umockdev_testbed_detach_ioctl(g->tb, g->node, NULL);
    for (int i = 0; i < g->ngone; i++)
        umockdev_testbed_detach_ioctl(g->tb, g->gone[i], NULL);
    g_object_unref(g->base);
    free(g->rx);
    free(g->fb);
    free(g->log);
    g_mutex_clear(&g->mu);
    free(g);
}

void fake_gud_unplug(fake_gud *g)
{
    g_mutex_lock(&g->mu);
    g->gen++;
    g->unplugged = true;
    g->committed = g->controller_on = g->display_on = g->checked = g->have_rect = false;
    g->halted = false;
    g_mutex_unlock(&g->mu);
    umockdev_testbed_uevent(g->tb, g->syspath, "remove");
    if (g->ngone < (int)(sizeof g->gone / sizeof g->gone[0]))
        memcpy(g->gone[g->ngone++], g->node, sizeof g->node);
    else
        umockdev_testbed_detach_ioctl(g->tb, g->node, NULL);
    umockdev_testbed_remove_device(g->tb, g->syspath);
}

void fake_gud_replug(fake_gud *g, int devnum)
{
    for (int i = 0; i < g->ngone; i++)
        if (atoi(strrchr(g->gone[i], '/') + 1) == devnum) {
            fprintf(stderr, "fake_gud: replug at devnum %d, which an earlier plug still holds\n", devnum);
            abort();
        }
    g_mutex_lock(&g->mu);
    g->devnum = devnum;
    g->unplugged = false;
    g->stall_transfers = g->hang_transfers = g->refuse_times = 0;
    g_mutex_unlock(&g->mu);
    add_to_sysfs(g);
    umockdev_testbed_uevent(g->tb, g->syspath, "add");
}

void fake_gud_set_opts(fake_gud *g, const fake_gud_opts *o)
{
    g_mutex_lock(&g->mu);
    uint16_t vid = g->o.vid, pid = g->o.pid;
    g->o = *o;
    g->o.vid = vid;
    g->o.pid = pid;
    free(g->fb); /* the panel memory follows the mode at the next commit */
    g->fb = NULL;
    g_mutex_unlock(&g->mu);
}

void fake_gud_framebuffer(fake_gud *g, uint8_t *out, size_t len)
{
    g_mutex_lock(&g->mu);
    size_t have = g->fb ? (size_t)g->o.width * (size_t)g->o.height * g->bpp : 0;
    memset(out, 0, len);
    memcpy(out, g->fb, have < len ? have : len);
    g_mutex_unlock(&g->mu);
}

void fake_gud_get_stats(fake_gud *g, fake_gud_stats *st)
{
    g_mutex_lock(&g->mu);
    *st = g->st;
    st->controller_on = g->controller_on;
    st->display_on = g->display_on;
    st->committed = g->committed;
    st->format = g->format;
    g_mutex_unlock(&g->mu);
}

size_t fake_gud_rects(fake_gud *g, fake_gud_rect *out, size_t max)
{
    g_mutex_lock(&g->mu);
    size_t n = g->nlog < max ? g->nlog : max;
    if (out)
        memcpy(out, g->log, n * sizeof *out);
    n = g->nlog;
    g_mutex_unlock(&g->mu);
    return n;
}

void fake_gud_clear_log(fake_gud *g)
{
    g_mutex_lock(&g->mu);
    g->nlog = 0;
    g_mutex_unlock(&g->mu);
}

void fake_gud_stall_bulk(fake_gud *g, int transfers)
{
    g_mutex_lock(&g->mu);
    g->stall_transfers = transfers;
    g_mutex_unlock(&g->mu);
}

void fake_gud_hang_bulk(fake_gud *g, int transfers)
{
    g_mutex_lock(&g->mu);
    g->hang_transfers = transfers;
    g_mutex_unlock(&g->mu);
}

void fake_gud_refuse(fake_gud *g, uint8_t request, uint8_t status, int times)
{
    g_mutex_lock(&g->mu);
    g->refuse_req = request;
    g->refuse_status = status;
    g->refuse_times = times;
    g_mutex_unlock(&g->mu);
}
