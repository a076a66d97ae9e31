/*
 * display.h - the display-out interface between the renderer and a panel.
 *
 * The core produces one finished line at a time and never holds a frame, so a
 * display is driven as a stream: begin a frame, send its lines top to bottom,
 * end the frame. Every backend (the host simulator in hal/sim, libgpiod, USB,
 * bare-metal MCU) implements the same const table of operations, in the style
 * of Zephyr's display driver API: one typedef per operation, the table in ROM,
 * constant configuration (ROM) split from mutable state (RAM), and callers
 * going through the inline wrappers below, which NULL-check the optional
 * operations and return -ENOSYS for them. All operations return 0 or a
 * negative errno value.
 *
 * A line is sent in the display's own pixel format (cs_pixfmt), already
 * converted: the display reports the format it wants and the caller converts
 * with cs_pixfmt_convert, so backends never see floats.
 *
 * Required operations: get_geometry, line_out.
 * Optional operations: begin_frame, end_frame (a panel that latches every line
 * as it comes needs neither).
 */
#ifndef HAL_DISPLAY_H
#define HAL_DISPLAY_H

#include <errno.h>
#include <stddef.h>
#include <stdint.h>

#include "celscan.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What a display shows: its size in pixels and the format of its lines. */
typedef struct hal_display_geometry {
    int width, height;
    cs_pixfmt pixfmt;
    size_t line_bytes; /* width * bytes per pixel: the length line_out expects */
} hal_display_geometry;

/*
 * One display instance. `api` is the backend's operation table, `config` its
 * constant configuration (wiring, size; may live in ROM) and `data` its mutable
 * state. The interface never looks inside config or data.
 */
typedef struct hal_display hal_display;

typedef int (*hal_display_get_geometry_fn)(const hal_display *dev, hal_display_geometry *geo);
typedef int (*hal_display_begin_frame_fn)(const hal_display *dev);
/* `bytes` holds geo.line_bytes bytes of row y (0 = top) in geo.pixfmt. */
typedef int (*hal_display_line_out_fn)(const hal_display *dev, int y, const uint8_t *bytes,
                                       size_t len);
typedef int (*hal_display_end_frame_fn)(const hal_display *dev);

typedef struct hal_display_api {
    hal_display_get_geometry_fn get_geometry; /* required */
    hal_display_begin_frame_fn begin_frame;   /* optional */
    hal_display_line_out_fn line_out;         /* required */
    hal_display_end_frame_fn end_frame;       /* optional */
} hal_display_api;

struct hal_display {
    const hal_display_api *api;
    const void *config;
    void *data;
};

static inline int hal_display_get_geometry(const hal_display *dev, hal_display_geometry *geo)
{
    return dev->api->get_geometry(dev, geo);
}

static inline int hal_display_begin_frame(const hal_display *dev)
{
    if (dev->api->begin_frame == NULL)
        return -ENOSYS;
    return dev->api->begin_frame(dev);
}

static inline int hal_display_line_out(const hal_display *dev, int y, const uint8_t *bytes,
                                       size_t len)
{
    return dev->api->line_out(dev, y, bytes, len);
}

static inline int hal_display_end_frame(const hal_display *dev)
{
    if (dev->api->end_frame == NULL)
        return -ENOSYS;
    return dev->api->end_frame(dev);
}

#ifdef __cplusplus
}
#endif

#endif /* HAL_DISPLAY_H */
