/*
 * sign.c - stream in, frames out, for any board (see sign.h).
 *
 * The line sink is where a board's display driver would be: here it
 * converts the core's linear-light floats with cs_pixfmt_convert, adds the
 * bytes to the frame's CRC and hands them to the panel. That is a separate
 * path from celsim's (which renders runs and converts them with
 * cs_line_pixels), so equal CRCs say both produce the same pixels.
 */
#include "sign.h"

static cs_status to_panel(void *user, int y, const float *rgb_linear, int width)
{
    sign *s = user;
    cs_pixfmt_convert(CS_PIX_RGB565_SRGB, rgb_linear, width, s->px);
    s->crc = cs_crc32(s->crc, s->px, (size_t)width * 2u);
    if (s->write)
        s->write(s->user, y, s->px, width);
    return CS_OK;
}

static void handle(sign *s, cs_stream_event ev)
{
    if (ev == CS_STREAM_COMMIT) {
        cs_stream_swap(&s->stream);
    } else if (ev == CS_STREAM_ERROR) {
        s->errors++;
        s->last = *cs_stream_last_error(&s->stream);
    }
}

cs_status sign_init(sign *s, int width, int height, sign_panel_write write, void *user)
{
    if (width < 1 || height < 1 || width > CS_CFG_MAX_WIDTH || height > CS_CFG_MAX_HEIGHT || !write)
        return CS_ERR_ARG;
    s->width = width;
    s->height = height;
    s->write = write;
    s->user = user;
    s->errors = 0;
    return cs_stream_init(&s->stream, &s->scenes[0], false, &s->scenes[1]);
}

void sign_feed(sign *s, const uint8_t *data, size_t len)
{
    size_t off = 0, used;
    cs_stream_event ev;
    while (off < len) {
        ev = cs_stream_feed(&s->stream, data + off, len - off, &used);
        off += used;
        handle(s, ev);
    }
    /* an error may have another queued behind it */
    while ((ev = cs_stream_feed(&s->stream, data, 0, &used)) != CS_STREAM_MORE)
        handle(s, ev);
}

void sign_end_of_input(sign *s)
{
    cs_stream_event ev;
    while ((ev = cs_stream_finish(&s->stream)) != CS_STREAM_MORE)
        handle(s, ev);
}

int sign_has_scene(const sign *s)
{
    return cs_stream_scene(&s->stream) != 0;
}

cs_status sign_frame(sign *s, float time, uint32_t *crc)
{
    const cs_scene *scene = cs_stream_scene(&s->stream);
    if (!scene)
        return CS_ERR_STATE;
    cs_render_opts opts = cs_render_defaults(s->width, s->height);
    opts.time = time;
    cs_error err;
    cs_status st = cs_frame_begin(&s->r, &s->ws, scene, &opts, &err);
    if (st != CS_OK)
        return st;
    s->crc = 0;
    st = cs_render_frame(&s->r, s->line, to_panel, s);
    *crc = s->crc;
    return st;
}
