/*
 * fake_gpiochip.c - the GPIO v1 character-device uAPI, emulated for umockdev.
 *
 * Semantics follow drivers/gpio/gpiolib-cdev.c (linehandle_create,
 * linehandle_ioctl, lineinfo): a request names 1..64 offsets; unknown or
 * contradictory flags are EINVAL; an offset beyond the chip is EINVAL; a line
 * already requested (also twice in one request) is EBUSY and nothing is
 * taken; outputs start at !!default_values[i]; values are logical and
 * ACTIVE_LOW inverts the wire; SET on an input handle is EPERM; unknown
 * ioctls are EINVAL. The handlers run on umockdev's worker thread while the
 * calling thread waits, so state is guarded by one mutex for the test's reads.
 */
#include <errno.h>
#include <fcntl.h>
#include <linux/gpio.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include "fake_gpiochip.h"

typedef struct handle {
    unsigned n;
    unsigned offsets[GPIOHANDLES_MAX];
    uint32_t flags;
    bool live;
    UMockdevIoctlClient *client; /* the handle fd's connection, once accepted */
} handle;

struct fake_gpiochip {
    UMockdevTestbed *tb;
    int index;
    unsigned nlines;
    char label[32];
    char node[64], handle_node[64];
    UMockdevIoctlBase *chip_h, *handle_h;
    _Atomic uint64_t *vclock;
    uint64_t write_cost;
    GMutex mu;
    uint64_t wires;     /* physical levels */
    uint64_t requested; /* lines taken by a handle or held */
    uint64_t output, active_low;
    char consumer[64][32];
    GQueue pending; /* handles waiting for their fd's client to connect */
    GList *handles; /* live handles with a client */
    unsigned live_handles;
    fake_gpio_event *trace;
    size_t ntrace, captrace;
    unsigned count[FAKE_GPIO_NCOUNT];
    unsigned fail_sets; /* the next SET_LINE_VALUES that fail, with fail_errno */
    int fail_errno;
};

static void reap_closed(fake_gpiochip *c);

static void record(fake_gpiochip *c)
{
    if (c->ntrace == c->captrace) {
        c->captrace = c->captrace ? 2 * c->captrace : 65536;
        c->trace = realloc(c->trace, c->captrace * sizeof *c->trace);
        if (!c->trace)
            abort();
    }
    uint64_t t = c->vclock ? atomic_fetch_add(c->vclock, c->write_cost) : 0;
    c->trace[c->ntrace++] = (fake_gpio_event){t, c->wires};
}

static void set_line(fake_gpiochip *c, unsigned off, int logical)
{
    int phys = (logical != 0) ^ (int)((c->active_low >> off) & 1u);
    if (phys)
        c->wires |= 1ull << off;
    else
        c->wires &= ~(1ull << off);
}

static int get_line(fake_gpiochip *c, unsigned off)
{
    return (int)(((c->wires >> off) & 1u) ^ ((c->active_low >> off) & 1u));
}

static void done(UMockdevIoctlClient *client, int err)
{
    umockdev_ioctl_client_complete(client, err ? -1 : 0, err);
}

/* The v1 request flags the kernel accepts (gpiolib-cdev.c keeps this mask private). */
#define VALID_FLAGS                                                                      \
    (GPIOHANDLE_REQUEST_INPUT | GPIOHANDLE_REQUEST_OUTPUT | GPIOHANDLE_REQUEST_ACTIVE_LOW | \
     GPIOHANDLE_REQUEST_OPEN_DRAIN | GPIOHANDLE_REQUEST_OPEN_SOURCE |                     \
     GPIOHANDLE_REQUEST_BIAS_PULL_UP | GPIOHANDLE_REQUEST_BIAS_PULL_DOWN |                \
     GPIOHANDLE_REQUEST_BIAS_DISABLE)

static int validate_flags(uint32_t f)
{
    const uint32_t bias = GPIOHANDLE_REQUEST_BIAS_PULL_UP | GPIOHANDLE_REQUEST_BIAS_PULL_DOWN |
                          GPIOHANDLE_REQUEST_BIAS_DISABLE;
    if (f & ~(uint32_t)VALID_FLAGS)
        return EINVAL;
    if ((f & GPIOHANDLE_REQUEST_INPUT) && (f & GPIOHANDLE_REQUEST_OUTPUT))
        return EINVAL;
    if ((f & GPIOHANDLE_REQUEST_OPEN_DRAIN) && (f & GPIOHANDLE_REQUEST_OPEN_SOURCE))
        return EINVAL;
    if (!(f & GPIOHANDLE_REQUEST_OUTPUT) &&
        (f & (GPIOHANDLE_REQUEST_OPEN_DRAIN | GPIOHANDLE_REQUEST_OPEN_SOURCE)))
        return EINVAL;
    if (!(f & (GPIOHANDLE_REQUEST_INPUT | GPIOHANDLE_REQUEST_OUTPUT)) && (f & bias))
        return EINVAL;
    if (__builtin_popcount(f & bias) > 1)
        return EINVAL;
    return 0;
}

static int linehandle(fake_gpiochip *c, struct gpiohandle_request *hr)
{
    if (hr->lines == 0 || hr->lines > GPIOHANDLES_MAX)
        return EINVAL;
    int e = validate_flags(hr->flags);
    if (e)
        return e;
    uint64_t take = 0;
    for (unsigned i = 0; i < hr->lines; i++) {
        unsigned off = hr->lineoffsets[i];
        if (off >= c->nlines)
            return EINVAL;
        if (((c->requested | take) >> off) & 1u)
            return EBUSY;
        take |= 1ull << off;
    }
    handle *h = calloc(1, sizeof *h);
    h->n = hr->lines;
    h->flags = hr->flags;
    h->live = true;
    memcpy(h->offsets, hr->lineoffsets, hr->lines * sizeof(unsigned));
    bool changed = false;
    for (unsigned i = 0; i < h->n; i++) {
        unsigned off = h->offsets[i];
        uint64_t bit = 1ull << off;
        c->requested |= bit;
        snprintf(c->consumer[off], sizeof c->consumer[off], "%s", hr->consumer_label);
        c->active_low = (hr->flags & GPIOHANDLE_REQUEST_ACTIVE_LOW) ? (c->active_low | bit)
                                                                     : (c->active_low & ~bit);
        if (hr->flags & GPIOHANDLE_REQUEST_OUTPUT) {
            uint64_t before = c->wires;
            c->output |= bit;
            set_line(c, off, hr->default_values[i] != 0);
            changed |= before != c->wires;
        } else {
            c->output &= ~bit;
        }
    }
    if (changed)
        record(c);
    /* The handle's fd: a second emulated node, opened here in the test
     * process, so its ioctls reach handle_ioctl with this handle attached. */
    g_queue_push_tail(&c->pending, h);
    int fd = open(c->handle_node, O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        g_queue_remove(&c->pending, h);
        for (unsigned i = 0; i < h->n; i++)
            c->requested &= ~(1ull << h->offsets[i]);
        free(h);
        return EMFILE;
    }
    c->live_handles++;
    hr->fd = fd;
    return 0;
}

static gboolean chip_ioctl(UMockdevIoctlBase *base, UMockdevIoctlClient *client, gpointer user)
{
    (void)base;
    fake_gpiochip *c = user;
    gulong req = umockdev_ioctl_client_get_request(client);
    UMockdevIoctlData *arg = umockdev_ioctl_client_get_arg(client);
    GError *gerr = NULL;
    int e = 0;
    g_mutex_lock(&c->mu);
    reap_closed(c);
    if (req == GPIO_GET_CHIPINFO_IOCTL) {
        c->count[FAKE_GPIO_CHIPINFO]++;
        UMockdevIoctlData *d = umockdev_ioctl_data_resolve(arg, 0, sizeof(struct gpiochip_info), &gerr);
        struct gpiochip_info *ci = (struct gpiochip_info *)d->data;
        memset(ci, 0, sizeof *ci);
        snprintf(ci->name, sizeof ci->name, "gpiochip%d", c->index);
        snprintf(ci->label, sizeof ci->label, "%s", c->label);
        ci->lines = c->nlines;
    } else if (req == GPIO_GET_LINEINFO_IOCTL) {
        c->count[FAKE_GPIO_LINEINFO]++;
        UMockdevIoctlData *d = umockdev_ioctl_data_resolve(arg, 0, sizeof(struct gpioline_info), &gerr);
        struct gpioline_info *li = (struct gpioline_info *)d->data;
        unsigned off = li->line_offset;
        if (off >= c->nlines) {
            e = EINVAL;
        } else {
            memset(li, 0, sizeof *li);
            li->line_offset = off;
            snprintf(li->name, sizeof li->name, "GPIO%u", off);
            uint64_t bit = 1ull << off;
            if (c->requested & bit) {
                li->flags |= GPIOLINE_FLAG_KERNEL;
                snprintf(li->consumer, sizeof li->consumer, "%s", c->consumer[off]);
            }
            if (c->output & bit)
                li->flags |= GPIOLINE_FLAG_IS_OUT;
            if (c->active_low & bit)
                li->flags |= GPIOLINE_FLAG_ACTIVE_LOW;
        }
    } else if (req == GPIO_GET_LINEHANDLE_IOCTL) {
        c->count[FAKE_GPIO_LINEHANDLE]++;
        UMockdevIoctlData *d =
            umockdev_ioctl_data_resolve(arg, 0, sizeof(struct gpiohandle_request), &gerr);
        e = linehandle(c, (struct gpiohandle_request *)d->data);
    } else {
        c->count[FAKE_GPIO_OTHER]++;
        e = EINVAL;
    }
    g_mutex_unlock(&c->mu);
    if (gerr) {
        g_error_free(gerr);
        e = EFAULT;
    }
    done(client, e);
    return TRUE;
}

static gboolean handle_ioctl(UMockdevIoctlBase *base, UMockdevIoctlClient *client, gpointer user)
{
    (void)base;
    fake_gpiochip *c = user;
    handle *h = g_object_get_data(G_OBJECT(client), "fake-gpio-handle");
    gulong req = umockdev_ioctl_client_get_request(client);
    UMockdevIoctlData *arg = umockdev_ioctl_client_get_arg(client);
    GError *gerr = NULL;
    int e = 0;
    g_mutex_lock(&c->mu);
    if (!h) {
        e = EBADF;
    } else if (req == GPIOHANDLE_SET_LINE_VALUES_IOCTL) {
        c->count[FAKE_GPIO_SET]++;
        if (!(h->flags & GPIOHANDLE_REQUEST_OUTPUT)) {
            e = EPERM;
        } else if (c->fail_sets) {
            c->fail_sets--;
            e = c->fail_errno;
        } else {
            UMockdevIoctlData *d =
                umockdev_ioctl_data_resolve(arg, 0, sizeof(struct gpiohandle_data), &gerr);
            struct gpiohandle_data *hd = (struct gpiohandle_data *)d->data;
            for (unsigned i = 0; i < h->n; i++)
                set_line(c, h->offsets[i], hd->values[i] != 0);
            record(c);
        }
    } else if (req == GPIOHANDLE_GET_LINE_VALUES_IOCTL) {
        c->count[FAKE_GPIO_GET]++;
        UMockdevIoctlData *d = umockdev_ioctl_data_resolve(arg, 0, sizeof(struct gpiohandle_data), &gerr);
        struct gpiohandle_data *hd = (struct gpiohandle_data *)d->data;
        memset(hd, 0, sizeof *hd);
        for (unsigned i = 0; i < h->n; i++)
            hd->values[i] = (uint8_t)get_line(c, h->offsets[i]);
    } else {
        c->count[FAKE_GPIO_OTHER]++;
        e = EINVAL;
    }
    g_mutex_unlock(&c->mu);
    if (gerr) {
        g_error_free(gerr);
        e = EFAULT;
    }
    done(client, e);
    return TRUE;
}

/*
 * Closing the handle fd closes its umockdev connection; the lines then go
 * back, as on close(2). umockdev 0.17 emits no signal for a vanished client,
 * so closed connections are reaped whenever the chip is asked anything.
 * Call with the mutex held.
 */
static void reap_closed(fake_gpiochip *c)
{
    GList *l = c->handles;
    while (l) {
        GList *next = l->next;
        handle *h = l->data;
        if (!umockdev_ioctl_client_get_connected(h->client)) {
            for (unsigned i = 0; i < h->n; i++) {
                c->requested &= ~(1ull << h->offsets[i]);
                c->consumer[h->offsets[i]][0] = 0;
            }
            h->live = false;
            c->live_handles--;
            c->handles = g_list_delete_link(c->handles, l);
            g_object_unref(h->client); /* frees h with the client's data */
        }
        l = next;
    }
}

static void handle_connected(UMockdevIoctlBase *base, UMockdevIoctlClient *client, gpointer user)
{
    (void)base;
    fake_gpiochip *c = user;
    g_mutex_lock(&c->mu);
    handle *h = g_queue_pop_head(&c->pending);
    if (h) {
        h->client = g_object_ref(client);
        g_object_set_data_full(G_OBJECT(client), "fake-gpio-handle", h, free);
        c->handles = g_list_prepend(c->handles, h);
    }
    /* else somebody opened the node directly: no lines, every ioctl is EBADF */
    g_mutex_unlock(&c->mu);
}

fake_gpiochip *fake_gpiochip_add(UMockdevTestbed *tb, int index, unsigned nlines, const char *label,
                                 _Atomic uint64_t *vclock, uint64_t write_cost_ns)
{
    if (nlines > 64)
        return NULL;
    fake_gpiochip *c = calloc(1, sizeof *c);
    c->tb = tb;
    c->index = index;
    c->nlines = nlines;
    c->vclock = vclock;
    c->write_cost = write_cost_ns;
    snprintf(c->label, sizeof c->label, "%s", label);
    snprintf(c->node, sizeof c->node, "/dev/gpiochip%d", index);
    snprintf(c->handle_node, sizeof c->handle_node, "/dev/fake-gpiochip%d-linehandle", index);
    g_mutex_init(&c->mu);
    g_queue_init(&c->pending);

    char rec[1024];
    snprintf(rec, sizeof rec,
             "P: /devices/platform/fake-gpio.%d/gpiochip%d\nN: gpiochip%d\nE: SUBSYSTEM=gpio\n"
             "E: DEVNAME=/dev/gpiochip%d\nA: dev=254:%d\n\n"
             "P: /devices/virtual/misc/fake-gpiochip%d-linehandle\nN: fake-gpiochip%d-linehandle\n"
             "E: SUBSYSTEM=misc\nE: DEVNAME=/dev/fake-gpiochip%d-linehandle\nA: dev=10:%d\n\n",
             index, index, index, index, index, index, index, index, 200 + index);
    GError *err = NULL;
    if (!umockdev_testbed_add_from_string(tb, rec, &err)) {
        fprintf(stderr, "fake_gpiochip: %s\n", err->message);
        abort();
    }
    /* libgpiod v1 checks that /sys/bus/gpio/devices/<chip>/dev names the
     * node's major:minor before it trusts the node as a GPIO chip. */
    char *root = umockdev_testbed_get_root_dir(tb);
    char path[512], devattr[600];
    snprintf(path, sizeof path, "%s/sys/bus/gpio/devices/gpiochip%d", root, index);
    g_mkdir_with_parents(path, 0755);
    snprintf(devattr, sizeof devattr, "%s/dev", path);
    char val[32];
    snprintf(val, sizeof val, "254:%d\n", index);
    g_file_set_contents(devattr, val, -1, NULL);
    g_free(root);

    c->chip_h = umockdev_ioctl_base_new();
    g_signal_connect(c->chip_h, "handle-ioctl", G_CALLBACK(chip_ioctl), c);
    c->handle_h = umockdev_ioctl_base_new();
    g_signal_connect(c->handle_h, "handle-ioctl", G_CALLBACK(handle_ioctl), c);
    g_signal_connect(c->handle_h, "client-connected", G_CALLBACK(handle_connected), c);
    if (!umockdev_testbed_attach_ioctl(tb, c->node, c->chip_h, &err) ||
        !umockdev_testbed_attach_ioctl(tb, c->handle_node, c->handle_h, &err)) {
        fprintf(stderr, "fake_gpiochip: %s\n", err->message);
        abort();
    }
    return c;
}

void fake_gpiochip_free(fake_gpiochip *c)
{
    if (!c)
        return;
    g_mutex_lock(&c->mu);
    for (GList *l = c->handles; l; l = l->next)
        g_object_unref(((handle *)l->data)->client);
    g_list_free(c->handles);
    g_mutex_unlock(&c->mu);
    umockdev_testbed_detach_ioctl(c->tb, c->node, NULL);
    umockdev_testbed_detach_ioctl(c->tb, c->handle_node, NULL);
    g_object_unref(c->chip_h);
    g_object_unref(c->handle_h);
    free(c->trace);
    g_mutex_clear(&c->mu);
    free(c);
}

size_t fake_gpiochip_trace(fake_gpiochip *c, const fake_gpio_event **events)
{
    *events = c->trace;
    return c->ntrace;
}

void fake_gpiochip_clear_trace(fake_gpiochip *c)
{
    g_mutex_lock(&c->mu);
    c->ntrace = 0;
    g_mutex_unlock(&c->mu);
}

uint64_t fake_gpiochip_wires(fake_gpiochip *c)
{
    g_mutex_lock(&c->mu);
    uint64_t w = c->wires;
    g_mutex_unlock(&c->mu);
    return w;
}

bool fake_gpiochip_requested(fake_gpiochip *c, unsigned line, char *consumer, size_t len)
{
    g_mutex_lock(&c->mu);
    reap_closed(c);
    bool r = line < 64 && ((c->requested >> line) & 1u);
    if (r && consumer)
        snprintf(consumer, len, "%s", c->consumer[line]);
    g_mutex_unlock(&c->mu);
    return r;
}

void fake_gpiochip_hold(fake_gpiochip *c, unsigned line, const char *consumer)
{
    g_mutex_lock(&c->mu);
    c->requested |= 1ull << line;
    snprintf(c->consumer[line], sizeof c->consumer[line], "%s", consumer);
    g_mutex_unlock(&c->mu);
}

void fake_gpiochip_fail_sets(fake_gpiochip *c, unsigned n, int err)
{
    g_mutex_lock(&c->mu);
    c->fail_sets = n;
    c->fail_errno = err;
    g_mutex_unlock(&c->mu);
}

unsigned fake_gpiochip_count(fake_gpiochip *c, int kind)
{
    g_mutex_lock(&c->mu);
    unsigned n = c->count[kind];
    g_mutex_unlock(&c->mu);
    return n;
}

unsigned fake_gpiochip_handles(fake_gpiochip *c)
{
    g_mutex_lock(&c->mu);
    reap_closed(c);
    unsigned n = c->live_handles;
    g_mutex_unlock(&c->mu);
    return n;
}
