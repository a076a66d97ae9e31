/*
 * gud_wire.h - the GUD (Generic USB Display) protocol on the wire.
 *
 * GUD is the protocol of the Linux kernel's gud driver (drivers/gpu/drm/gud,
 * documented in include/drm/gud.h). A display is a USB interface of vendor
 * class with one bulk OUT endpoint. Everything but pixels is a vendor control
 * request addressed to that interface (wIndex = interface number); pixels go
 * as a SET_BUFFER control request naming a rectangle, followed by the
 * rectangle's bytes (optionally LZ4 block compressed) on the bulk endpoint.
 * State is set in two steps: SET_STATE_CHECK with the whole state, then
 * SET_STATE_COMMIT. Structures are packed and little-endian, so this header
 * gives their sizes and encodes/decodes them byte by byte instead of relying
 * on the compiler's struct layout.
 */
#ifndef GUD_WIRE_H
#define GUD_WIRE_H

#include <stdint.h>
#include <string.h>

#define GUD_MAGIC 0x1d50614du

/* Control requests (bRequest). */
#define GUD_REQ_GET_STATUS 0x00
#define GUD_REQ_GET_DESCRIPTOR 0x01
#define GUD_REQ_GET_FORMATS 0x40
#define GUD_REQ_GET_PROPERTIES 0x41
#define GUD_REQ_GET_CONNECTORS 0x50
#define GUD_REQ_GET_CONNECTOR_PROPERTIES 0x51
#define GUD_REQ_SET_CONNECTOR_FORCE_DETECT 0x53
#define GUD_REQ_GET_CONNECTOR_STATUS 0x54
#define GUD_REQ_GET_CONNECTOR_MODES 0x55
#define GUD_REQ_GET_CONNECTOR_EDID 0x56
#define GUD_REQ_SET_BUFFER 0x60
#define GUD_REQ_SET_STATE_CHECK 0x61
#define GUD_REQ_SET_STATE_COMMIT 0x62
#define GUD_REQ_SET_CONTROLLER_ENABLE 0x63
#define GUD_REQ_SET_DISPLAY_ENABLE 0x64

/* GET_STATUS values: why the last request failed. */
#define GUD_STATUS_OK 0x00
#define GUD_STATUS_BUSY 0x01
#define GUD_STATUS_REQUEST_NOT_SUPPORTED 0x02
#define GUD_STATUS_PROTOCOL_ERROR 0x03
#define GUD_STATUS_INVALID_PARAMETER 0x04
#define GUD_STATUS_ERROR 0x05

/* Display descriptor flags and compression bits. */
#define GUD_FLAG_STATUS_ON_SET (1u << 0)
#define GUD_FLAG_FULL_UPDATE (1u << 1)
#define GUD_COMPRESSION_LZ4 (1u << 0)

/* Pixel formats (GET_FORMATS returns a byte array of these). */
#define GUD_FORMAT_R1 0x01
#define GUD_FORMAT_R8 0x08
#define GUD_FORMAT_XRGB1111 0x20
#define GUD_FORMAT_RGB332 0x30
#define GUD_FORMAT_RGB565 0x40
#define GUD_FORMAT_XRGB8888 0x80
#define GUD_FORMAT_ARGB8888 0x81
#define GUD_FORMATS_MAX 32

#define GUD_PROPERTY_ROTATION 50
#define GUD_ROTATION_0 (1u << 0)
#define GUD_PROPERTIES_MAX 32
#define GUD_CONNECTORS_MAX 32
#define GUD_MODES_MAX 128
#define GUD_MODE_FLAG_PREFERRED (1u << 10)

/* Packed sizes. */
#define GUD_DESCRIPTOR_SIZE 30  /* magic4 version1 flags4 compression1 maxbuf4 minw4 maxw4 minh4 maxh4 */
#define GUD_PROPERTY_SIZE 10    /* prop2 val8 */
#define GUD_MODE_SIZE 24        /* clock4 h*4x2 v*4x2 flags4 */
#define GUD_CONNECTOR_SIZE 5    /* type1 flags4 */
#define GUD_SET_BUFFER_SIZE 25  /* x4 y4 w4 h4 length4 compression1 compressed_length4 */
#define GUD_STATE_SIZE(nprops) (GUD_MODE_SIZE + 2 + GUD_PROPERTY_SIZE * (nprops))

static inline uint16_t gud_get16(const uint8_t *p) { return (uint16_t)(p[0] | p[1] << 8); }
static inline uint32_t gud_get32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}
static inline void gud_put16(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}
static inline void gud_put32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}
static inline void gud_put64(uint8_t *p, uint64_t v)
{
    for (int i = 0; i < 8; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}

typedef struct gud_descriptor {
    uint32_t magic;
    uint8_t version;
    uint32_t flags;
    uint8_t compression;
    uint32_t max_buffer_size;
    uint32_t min_width, max_width, min_height, max_height;
} gud_descriptor;

static inline void gud_descriptor_decode(const uint8_t *p, gud_descriptor *d)
{
    d->magic = gud_get32(p);
    d->version = p[4];
    d->flags = gud_get32(p + 5);
    d->compression = p[9];
    d->max_buffer_size = gud_get32(p + 10);
    d->min_width = gud_get32(p + 14);
    d->max_width = gud_get32(p + 18);
    d->min_height = gud_get32(p + 22);
    d->max_height = gud_get32(p + 26);
}

static inline void gud_descriptor_encode(uint8_t *p, const gud_descriptor *d)
{
    gud_put32(p, d->magic);
    p[4] = d->version;
    gud_put32(p + 5, d->flags);
    p[9] = d->compression;
    gud_put32(p + 10, d->max_buffer_size);
    gud_put32(p + 14, d->min_width);
    gud_put32(p + 18, d->max_width);
    gud_put32(p + 22, d->min_height);
    gud_put32(p + 26, d->max_height);
}

typedef struct gud_mode {
    uint32_t clock; /* kHz */
    uint16_t hdisplay, hsync_start, hsync_end, htotal;
    uint16_t vdisplay, vsync_start, vsync_end, vtotal;
    uint32_t flags;
} gud_mode;

static inline void gud_mode_decode(const uint8_t *p, gud_mode *m)
{
    m->clock = gud_get32(p);
    m->hdisplay = gud_get16(p + 4);
    m->hsync_start = gud_get16(p + 6);
    m->hsync_end = gud_get16(p + 8);
    m->htotal = gud_get16(p + 10);
    m->vdisplay = gud_get16(p + 12);
    m->vsync_start = gud_get16(p + 14);
    m->vsync_end = gud_get16(p + 16);
    m->vtotal = gud_get16(p + 18);
    m->flags = gud_get32(p + 20);
}

static inline void gud_mode_encode(uint8_t *p, const gud_mode *m)
{
    gud_put32(p, m->clock);
    gud_put16(p + 4, m->hdisplay);
    gud_put16(p + 6, m->hsync_start);
    gud_put16(p + 8, m->hsync_end);
    gud_put16(p + 10, m->htotal);
    gud_put16(p + 12, m->vdisplay);
    gud_put16(p + 14, m->vsync_start);
    gud_put16(p + 16, m->vsync_end);
    gud_put16(p + 18, m->vtotal);
    gud_put32(p + 20, m->flags);
}

typedef struct gud_set_buffer {
    uint32_t x, y, width, height, length;
    uint8_t compression;
    uint32_t compressed_length;
} gud_set_buffer;

static inline void gud_set_buffer_encode(uint8_t *p, const gud_set_buffer *b)
{
    gud_put32(p, b->x);
    gud_put32(p + 4, b->y);
    gud_put32(p + 8, b->width);
    gud_put32(p + 12, b->height);
    gud_put32(p + 16, b->length);
    p[20] = b->compression;
    gud_put32(p + 21, b->compressed_length);
}

static inline void gud_set_buffer_decode(const uint8_t *p, gud_set_buffer *b)
{
    b->x = gud_get32(p);
    b->y = gud_get32(p + 4);
    b->width = gud_get32(p + 8);
    b->height = gud_get32(p + 12);
    b->length = gud_get32(p + 16);
    b->compression = p[20];
    b->compressed_length = gud_get32(p + 21);
}

/* Bytes per pixel of the formats celfw sends; 0 for the others. */
static inline unsigned gud_format_bpp(uint8_t f)
{
    return f == GUD_FORMAT_RGB565 ? 2u : f == GUD_FORMAT_XRGB8888 ? 4u : 0u;
}

static inline const char *gud_format_name(uint8_t f)
{
    switch (f) {
    case GUD_FORMAT_R1: return "R1";
    case GUD_FORMAT_R8: return "R8";
    case GUD_FORMAT_XRGB1111: return "XRGB1111";
    case GUD_FORMAT_RGB332: return "RGB332";
    case GUD_FORMAT_RGB565: return "RGB565";
    case GUD_FORMAT_XRGB8888: return "XRGB8888";
    case GUD_FORMAT_ARGB8888: return "ARGB8888";
    }
    return "unknown";
}

static inline const char *gud_status_name(uint8_t s)
{
    switch (s) {
    case GUD_STATUS_OK: return "ok";
    case GUD_STATUS_BUSY: return "busy";
    case GUD_STATUS_REQUEST_NOT_SUPPORTED: return "request not supported";
    case GUD_STATUS_PROTOCOL_ERROR: return "protocol error";
    case GUD_STATUS_INVALID_PARAMETER: return "invalid parameter";
    case GUD_STATUS_ERROR: return "error";
    }
    return "unknown status";
}

#endif /* GUD_WIRE_H */
