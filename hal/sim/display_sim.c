/*
 * display_sim.c - the in-memory display backend (see display_sim.h).
 *
 * It is deliberately strict: a real panel that latches lines as they arrive
 * shows garbage if a driver sends rows twice, out of order or outside a
 * frame, so the simulator rejects those calls instead of quietly storing
 * them, and the bug shows up on the host first.
 */
#include <string.h>

#include "sim/display_sim.h"

static int sim_get_geometry(const hal_display *dev, hal_display_geometry *geo)
{
    const sim_display_config *cfg = dev->config;
    const sim_display_data *data = dev->data;
    if (geo == NULL)
        return -EINVAL;
    geo->width = cfg->width;
    geo->height = cfg->height;
    geo->pixfmt = cfg->pixfmt;
    geo->line_bytes = data->line_bytes;
    return 0;
}

static int sim_begin_frame(const hal_display *dev)
{
    sim_display_data *data = dev->data;
    if (data->in_frame)
        return -EBUSY;
    data->in_frame = 1;
    data->next_y = 0;
    data->rows_written = 0;
    return 0;
}

static int sim_line_out(const hal_display *dev, int y, const uint8_t *bytes, size_t len)
{
    const sim_display_config *cfg = dev->config;
    sim_display_data *data = dev->data;
    if (!data->in_frame)
        return -EPERM;
    if (bytes == NULL || len != data->line_bytes || y < 0 || y >= cfg->height)
        return -EINVAL;
    /* Rows may be skipped (the core allows it) but never revisited. */
    if (y < data->next_y)
        return -EPERM;
    memcpy(data->image + (size_t)y * data->line_bytes, bytes, len);
    data->next_y = y + 1;
    data->rows_written++;
    return 0;
}

static int sim_end_frame(const hal_display *dev)
{
    const sim_display_config *cfg = dev->config;
    sim_display_data *data = dev->data;
    if (!data->in_frame)
        return -EPERM;
    data->in_frame = 0;
    /* A partial frame would leave stale rows from the last one on the glass. */
    if (data->rows_written != cfg->height)
        return -EIO;
    data->frames_done++;
    return 0;
}

static const hal_display_api sim_display_api = {
    .get_geometry = sim_get_geometry,
    .begin_frame = sim_begin_frame,
    .line_out = sim_line_out,
    .end_frame = sim_end_frame,
};

size_t sim_display_image_bytes(const sim_display_config *cfg)
{
    if (cfg == NULL || cfg->width <= 0 || cfg->height <= 0)
        return 0;
    size_t bpp = cs_pixfmt_bytes_per_pixel(cfg->pixfmt);
    if (bpp == 0)
        return 0;
    size_t w = (size_t)cfg->width, h = (size_t)cfg->height;
    if (w > SIZE_MAX / bpp || w * bpp > SIZE_MAX / h)
        return 0;
    return w * bpp * h;
}

int sim_display_init(hal_display *dev, const sim_display_config *cfg, sim_display_data *data,
                     uint8_t *image, size_t image_len)
{
    size_t need = sim_display_image_bytes(cfg);
    if (dev == NULL || data == NULL || image == NULL || need == 0 || image_len < need)
        return -EINVAL;
    memset(data, 0, sizeof *data);
    memset(image, 0, need);
    data->image = image;
    data->line_bytes = need / (size_t)cfg->height;
    dev->api = &sim_display_api;
    dev->config = cfg;
    dev->data = data;
    return 0;
}

const uint8_t *sim_display_row(const hal_display *dev, int y)
{
    const sim_display_config *cfg = dev->config;
    const sim_display_data *data = dev->data;
    if (y < 0 || y >= cfg->height)
        return NULL;
    return data->image + (size_t)y * data->line_bytes;
}
