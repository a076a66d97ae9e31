/*
 * hub75_gpiod.c - drives a HUB75 panel chain through libgpiod (v1 API).
 *
 * All wired lines are requested as outputs in one bulk request, and every
 * change goes out with gpiod_line_set_value_bulk(): with libgpiod v1,
 * gpiod_line_set_value() on a line of a bulk request sets only the request's
 * first line, which would leave the panel's clock and data unconnected.
 *
 * One frame is one full scan of the panel. For each row pair r:
 *   1. render line r (lane 0) and line r + rows/2 (lane 1), quantise each
 *      channel to `planes` bits of linear light (LED PWM is linear), and
 *      split the two lines into bit planes: planes x width bytes, each byte
 *      holding the six data bits R1 G1 B1 R2 G2 B2 of one column;
 *   2. for each plane b: shift the columns in (data with CLK low, then CLK
 *      high: the data is stable at the rising edge), bring CLK low and set
 *      the address while the panel is blank, pulse LAT, then light the
 *      row pair (OE low) for lsb_ns * 2^b and blank it again.
 * Writes that would not change any wire are skipped.
 *
 * The lit time is measured from just before the OE-on write to just before
 * the OE-off write, so the cost of a write (~1 us through the character
 * device) appears at both ends and cancels: plane durations stay exact powers
 * of two however slow the GPIO path is, as long as lsb_ns exceeds one write.
 * Shifting happens with the row pair dark, which costs brightness but not
 * colour accuracy.
 */
#include <errno.h>
#include <gpiod.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hub75.h"

typedef struct hub75 {
    hal_display d;
    hub75_config cfg;
    int width, scan, abits;
    struct gpiod_chip *chip;
    struct gpiod_line_bulk bulk;
    bool requested;
    int nwired;
    int bulk_index[HUB75_NFUNC]; /* position in the bulk request, or -1 */
    int level[HUB75_NFUNC];      /* wire level per function */
    int out[HUB75_NFUNC];        /* the bulk values being written */
    int last[HUB75_NFUNC];       /* the bulk values last written */
    bool have_last;
    float *top, *bot;            /* the two lines of a row pair, 3 * width floats */
    uint8_t *planes;             /* planes x width: bit b of each column's six channels */
    uint64_t writes;
} hub75;

/* Writes the wire levels if any changed. Returns 0 or an errno. */
static int put(hub75 *h)
{
    for (int f = 0; f < HUB75_NFUNC; f++)
        if (h->bulk_index[f] >= 0)
            h->out[h->bulk_index[f]] = h->level[f];
    if (h->have_last && memcmp(h->out, h->last, (size_t)h->nwired * sizeof(int)) == 0)
        return 0;
    if (gpiod_line_set_value_bulk(&h->bulk, h->out) != 0)
        return errno ? errno : EIO;
    memcpy(h->last, h->out, (size_t)h->nwired * sizeof(int));
    h->have_last = true;
    h->writes++;
    return 0;
}

static uint32_t quantise(float v, uint32_t max)
{
    if (!(v > 0.0f))
        return 0;
    if (v >= 1.0f)
        return max;
    return (uint32_t)(v * (float)max + 0.5f);
}

/* Splits the row pair's two lines into bit planes. */
static void build_planes(hub75 *h)
{
    const int W = h->width, P = h->cfg.planes;
    const uint32_t max = (1u << P) - 1u;
    for (int x = 0; x < W; x++) {
        uint32_t ch[6];
        for (int c = 0; c < 3; c++) {
            ch[c] = quantise(h->top[3 * x + c], max);
            ch[3 + c] = quantise(h->bot[3 * x + c], max);
        }
        for (int b = 0; b < P; b++) {
            uint8_t v = 0;
            for (int c = 0; c < 6; c++)
                v |= (uint8_t)(((ch[c] >> b) & 1u) << c);
            h->planes[(size_t)b * (size_t)W + (size_t)x] = v;
        }
    }
}

static hal_status io_error(hub75 *h, int e)
{
    return hal_display_fail(&h->d, e == ENODEV ? HAL_ERR_NO_DEVICE : HAL_ERR_IO,
                            "writing GPIO lines on %s failed: %s", h->cfg.chip, strerror(e));
}

static hal_status drive_row_pair(hub75 *h, int r)
{
    const int W = h->width;
    int e;
    for (int b = 0; b < h->cfg.planes; b++) {
        const uint8_t *pl = h->planes + (size_t)b * (size_t)W;
        /* The first column shifted travels furthest: to the far end of the chain. */
        for (int x = W - 1; x >= 0; x--) {
            for (int c = 0; c < 6; c++)
                h->level[HUB75_R1 + c] = (pl[x] >> c) & 1;
            h->level[HUB75_CLK] = 0;
            if ((e = put(h)))
                return io_error(h, e);
            h->level[HUB75_CLK] = 1;
            if ((e = put(h)))
                return io_error(h, e);
        }
        h->level[HUB75_CLK] = 0;
        for (int a = 0; a < h->abits; a++)
            h->level[HUB75_A + a] = (r >> a) & 1;
        if ((e = put(h)))
            return io_error(h, e);
        h->level[HUB75_LAT] = 1;
        if ((e = put(h)))
            return io_error(h, e);
        h->level[HUB75_LAT] = 0;
        if ((e = put(h)))
            return io_error(h, e);
        uint64_t t0 = hal_now(h->d.clock);
        h->level[HUB75_OE] = 0;
        if ((e = put(h)))
            return io_error(h, e);
        hal_wait_until(h->d.clock, t0 + ((uint64_t)h->cfg.lsb_ns << b));
        h->level[HUB75_OE] = 1;
        if ((e = put(h)))
            return io_error(h, e);
    }
    return HAL_OK;
}

static hal_status hub75_present(hal_display *d, const hal_source *src, hal_frame_stats *st)
{
    hub75 *h = (hub75 *)d;
    if (src->width != h->width || src->height != h->cfg.panel_h)
        return hal_display_fail(d, HAL_ERR_CONFIG, "source is %dx%d, the panel chain is %dx%d", src->width,
                                src->height, h->width, h->cfg.panel_h);
    hal_status s = src->begin(src->user, 2);
    if (s != HAL_OK)
        return hal_display_fail(d, s, "the renderer could not start the frame");
    uint64_t writes0 = h->writes;
    for (int r = 0; r < h->scan; r++) {
        if ((s = src->line(src->user, 0, r, h->top)) != HAL_OK ||
            (s = src->line(src->user, 1, r + h->scan, h->bot)) != HAL_OK)
            return hal_display_fail(d, s, "the renderer failed on row pair %d", r);
        st->lines_rendered += 2;
        build_planes(h);
        s = drive_row_pair(h, r);
        st->writes += h->writes - writes0;
        writes0 = h->writes;
        if (s != HAL_OK)
            return s;
        if (d->frame_period_ns) {
            uint64_t due = d->frame_start_ns + (uint64_t)(r + 1) * d->frame_period_ns / (uint64_t)h->scan;
            if (hal_now(d->clock) > due)
                st->line_misses++;
        }
    }
    return HAL_OK;
}

static bool hub75_connected(hal_display *d)
{
    return ((hub75 *)d)->requested;
}

static void hub75_close(hal_display *d)
{
    hub75 *h = (hub75 *)d;
    if (h->requested) {
        /* Leave the panel dark: a stopped scan would burn one row pair bright. */
        h->level[HUB75_OE] = 1;
        (void)put(h);
        gpiod_line_release_bulk(&h->bulk);
    }
    if (h->chip)
        gpiod_chip_close(h->chip);
    free(h->top);
    free(h->bot);
    free(h->planes);
    free(h);
}

/* The pull lane: a HUB75 panel holds nothing and is rescanned every frame. */
static const hal_display_api hub75_api = {
    .name = "hub75",
    .present = hub75_present,
    .lanes = 2,
    .connected = hub75_connected,
    .close = hub75_close,
};

hal_status hub75_open(hal_display **out, const hub75_config *c, const hal_clock *clock, char *err,
                     size_t errlen)
{
    hal_status s = hub75_config_check(c, err, errlen);
    if (s != HAL_OK)
        return s;
    hub75 *h = calloc(1, sizeof *h);
    if (!h)
        return HAL_ERR_NOMEM;
    h->cfg = *c;
    h->width = c->panel_w * c->chain;
    h->scan = hub75_scan(c);
    h->abits = hub75_addr_bits(c);
    h->d.api = &hub75_api;
    h->d.width = h->width;
    h->d.height = c->panel_h;
    h->d.clock = clock;
    h->top = calloc((size_t)h->width * 3u, sizeof(float));
    h->bot = calloc((size_t)h->width * 3u, sizeof(float));
    h->planes = calloc((size_t)h->width * (size_t)c->planes, 1);
    if (!h->top || !h->bot || !h->planes) {
        hub75_close(&h->d);
        return HAL_ERR_NOMEM;
    }

    h->chip = gpiod_chip_open(c->chip);
    if (!h->chip) {
        int e = errno;
        snprintf(err, errlen, "hub75: cannot open GPIO chip %s: %s%s", c->chip, strerror(e),
                 e == ENOTTY || e == ENODEV ? " (not a GPIO character device)" : "");
        hub75_close(&h->d);
        return HAL_ERR_NO_DEVICE;
    }
    unsigned int nchip = gpiod_chip_num_lines(h->chip);
    unsigned int offsets[HUB75_NFUNC];
    int defaults[HUB75_NFUNC];
    for (int f = 0; f < HUB75_NFUNC; f++) {
        h->bulk_index[f] = -1;
        bool needed = !(f >= HUB75_A && f <= HUB75_E) || (f - HUB75_A) < h->abits;
        if (!needed)
            continue;
        int p = c->pins.pin[f];
        if ((unsigned)p >= nchip) {
            snprintf(err, errlen, "hub75: pin %s=%d, but %s has only lines 0..%u", hub75_func_name(f),
                     p, c->chip, nchip ? nchip - 1 : 0);
            hub75_close(&h->d);
            return HAL_ERR_CONFIG;
        }
        h->bulk_index[f] = h->nwired;
        offsets[h->nwired] = (unsigned)p;
        h->level[f] = f == HUB75_OE ? 1 : 0; /* OE is active low: start dark */
        defaults[h->nwired] = h->level[f];
        h->nwired++;
    }
    if (gpiod_chip_get_lines(h->chip, offsets, (unsigned)h->nwired, &h->bulk) != 0) {
        snprintf(err, errlen, "hub75: cannot look up lines on %s: %s", c->chip, strerror(errno));
        hub75_close(&h->d);
        return HAL_ERR_IO;
    }
    if (gpiod_line_request_bulk_output(&h->bulk, "celfw-hub75", defaults) != 0) {
        int e = errno;
        char who[96] = "";
        if (e == EBUSY) {
            for (int i = 0; i < h->nwired; i++) {
                struct gpiod_line *l = gpiod_line_bulk_get_line(&h->bulk, (unsigned)i);
                if (gpiod_line_update(l) == 0 && gpiod_line_is_used(l)) {
                    snprintf(who, sizeof who, " (line %u is held by \"%s\")", offsets[i],
                             gpiod_line_consumer(l) ? gpiod_line_consumer(l) : "the kernel");
                    break;
                }
            }
        }
        snprintf(err, errlen, "hub75: cannot request output lines on %s: %s%s", c->chip,
                 strerror(e), who);
        hub75_close(&h->d);
        return e == EBUSY ? HAL_ERR_IO : HAL_ERR_NO_DEVICE;
    }
    h->requested = true;
    memcpy(h->last, defaults, (size_t)h->nwired * sizeof(int));
    h->have_last = true;
    *out = &h->d;
    return HAL_OK;
}

double hub75_measure_writes(hal_display *d, int writes)
{
    hub75 *h = (hub75 *)d;
    if (writes < 2)
        return 0.0;
    h->level[HUB75_OE] = 1;
    uint64_t t0 = hal_now(d->clock);
    for (int i = 0; i < writes; i++) {
        h->level[HUB75_CLK] = i & 1;
        if (put(h) != 0)
            return 0.0;
    }
    uint64_t t1 = hal_now(d->clock);
    h->level[HUB75_CLK] = 0;
    (void)put(h);
    return t1 > t0 ? (double)writes * 1e9 / (double)(t1 - t0) : 0.0;
}
