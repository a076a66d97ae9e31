/*
 * display.h - the one display contract between the renderer and a panel.
 *
 * The core produces one finished line at a time and never holds a frame, so
 * a display is a sink of lines: begin a frame, send its lines top to bottom
 * in the display's own pixel format, end the frame. Every backend implements
 * the same const table of operations (hal_display_api), in the style of
 * Zephyr's display drivers: one typedef per operation, the table in ROM,
 * optional operations NULL. A backend's state embeds a hal_display as its
 * first member, so an operation casts the pointer it gets back to its own
 * type. Backends: hal/sim (memory, PNG), hal/host/null.c, hal/mcu panels
 * (semihost file, SSD1963), hal/gpio (HUB75), hal/usb (GUD), hal/drm
 * (DRM/KMS); hal/template is the commented one to copy.
 *
 * Three shapes of panel fit it:
 *  - A panel that latches every line (a frame buffer in a USB bridge, a
 *    controller's GRAM, a DRM dumb buffer) implements line_out, and
 *    begin_frame/end_frame where it has work to do around a frame. One whose
 *    picture is memory the program writes may also lend its rows
 *    (line_buffer), so a line is rendered where it is shown, not copied.
 *  - A panel that keeps its picture may take a frame limited to a window
 *    (rows y0..y1-1, columns x0..x1-1): only what changed travels. A backend
 *    that cannot narrow its writes refuses a window with HAL_ERR_CONFIG. An
 *    empty window (x0 == x1 or y0 == y1) is a frame where nothing changed:
 *    no line comes. After it, read_row may read the picture back. A backend
 *    that does not hold the last frame now (away, just reconnected) refuses
 *    a window the same way, and hal_display_present_window then sends the
 *    whole frame.
 *  - A panel that must be refreshed continuously and holds nothing (a HUB75
 *    matrix) implements the pull lane, present: it asks a hal_source for
 *    lines when its scan needs them, in one or more "lanes", each an
 *    independent stream of lines in increasing y (the order the core's
 *    active-piece list can move in).
 * hal_display_present drives either kind from a hal_source; a program that
 * has its lines in hand (the simulator) calls the push operations itself.
 *
 * A frame that fails after begin_frame (a refused line, a renderer error)
 * is abandoned, not ended: end_frame would show half a frame. The next
 * begin_frame starts afresh, and every backend must take it.
 *
 * Errors are one type, hal_status, and the backend writes what went wrong,
 * prefixed with its name, into d->err (hal_display_fail). On a
 * microcontroller HAL_ERR_LEN may be set small: the status still says what
 * kind of failure it was.
 */
#ifndef HAL_DISPLAY_H
#define HAL_DISPLAY_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "celscan.h"
#include "clock.h"

#ifdef __cplusplus
extern "C" {
#endif

#if !defined(HAL_ERR_LEN)
#define HAL_ERR_LEN 256 /* bytes of d->err, the last error's message (an MCU build sets it small) */
#endif

typedef enum hal_status {
    HAL_OK = 0,
    HAL_ERR_CONFIG,    /* configuration or geometry is invalid; the message says which */
    HAL_ERR_NO_DEVICE, /* the device is absent or vanished */
    HAL_ERR_IO,        /* a transfer or write failed */
    HAL_ERR_TIMEOUT,   /* the device did not answer in time */
    HAL_ERR_PROTOCOL,  /* the device answered something we cannot use */
    HAL_ERR_RENDER,    /* the renderer failed (scene or capacity error) */
    HAL_ERR_NOMEM,
    HAL_ERR_SEQUENCE   /* a call out of order: a line outside a frame, a row sent twice */
} hal_status;

/*
 * The formats a display takes: any cs_pixfmt, or HAL_PIX_XRGB8888 (32 bits,
 * little-endian, so B, G, R, X in memory: the layout DRM and GUD scan out,
 * which the core does not produce).
 */
typedef int hal_pixfmt;
#define HAL_PIX_XRGB8888 0x100

/* A frame's window: rows y0..y1-1 and columns x0..x1-1 (half-open). */
typedef struct hal_window {
    int x0, y0, x1, y1;
} hal_window;

/* Whether w lies within a width x height display (an empty window does). */
static inline bool hal_window_inside(const hal_window *w, int width, int height)
{
    return w->x0 >= 0 && w->y0 >= 0 && w->x0 <= w->x1 && w->y0 <= w->y1 && w->x1 <= width &&
           w->y1 <= height;
}

/* Where lines come from, for the pull lane and hal_display_present. */
typedef struct hal_source {
    int width, height;
    void *user;
    /* Starts a frame with `lanes` independent line streams (1 or 2). */
    hal_status (*begin)(void *user, int lanes);
    /* Renders line y into rgb (3*width floats, linear light). Within a lane,
     * y must increase from call to call; lines may be skipped. */
    hal_status (*line)(void *user, int lane, int y, float *rgb);
    /* Optional: the next begin() renders only `win` (NULL: the whole
     * output); line() then gives its rows, 3*(x1-x0) floats of its columns.
     * hal_display_present_window calls it before begin(). */
    hal_status (*window)(void *user, const hal_window *win);
} hal_source;

/* What frames did; hal_display_present adds a frame's counts to the caller's. */
typedef struct hal_frame_stats {
    uint64_t lines_rendered;
    uint64_t pixels_rendered; /* the rendered lines' pixels (a window's lines are narrower) */
    uint64_t lines_sent;   /* lines that travelled (changed lines) */
    uint64_t rects;        /* rectangles sent (USB SET_BUFFER, DRM damage clips) */
    uint64_t bytes_raw;    /* pixel bytes of the rectangles */
    uint64_t bytes_wire;   /* USB: bytes on the bulk pipe (after LZ4) */
    uint64_t writes;       /* GPIO: bulk line writes */
    uint64_t line_misses;  /* lines (row pairs) finished after their deadline */
    uint64_t retries;      /* transfers repeated after an error */
    uint64_t errors;       /* transfers that failed for good */
} hal_frame_stats;

typedef void (*hal_log_fn)(void *user, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

typedef struct hal_display hal_display;

/* A frame starts; win is NULL for the whole display, or within it. */
typedef hal_status (*hal_begin_frame_fn)(hal_display *d, const hal_window *win);
/* Row y of the frame in d->pixfmt: the window's columns, len bytes
 * (hal_line_bytes of the window's width). Rows increase within a frame. */
typedef hal_status (*hal_line_out_fn)(hal_display *d, int y, const uint8_t *px, size_t len);
/* Optional, for a display whose picture is memory the program can write (a
 * frame buffer in RAM: the simulator's image, a memory-mapped panel): where
 * row y of the frame goes, len bytes, so that a driver renders the row in
 * place and hands line_out that same pointer, which then copies nothing.
 * NULL where the display lends nothing now (outside a frame, a row outside
 * the window or behind the last one sent, another length): the driver uses
 * a buffer of its own. A row lent stays lent until the frame ends: a
 * driver may take several rows ahead and fill them in any order (threads),
 * then hand each to line_out in order. What is written there before
 * line_out is on the glass already, as a half-sent row would be if the
 * frame is abandoned. */
typedef uint8_t *(*hal_line_buffer_fn)(hal_display *d, int y, size_t len);
typedef hal_status (*hal_end_frame_fn)(hal_display *d);
/* The pull lane: shows one frame, pulling its lines from src as the panel
 * needs them. Deadlines: line y (a row pair for HUB75) is due at
 * d->frame_start_ns + (y+1) * d->frame_period_ns / d->height; later lines
 * count as misses. */
typedef hal_status (*hal_present_fn)(hal_display *d, const hal_source *src, hal_frame_stats *st);
/* Row y of the picture a display that keeps its picture now holds, len
 * bytes in d->pixfmt: the whole frame's CRC after a frame sent as a window. */
typedef hal_status (*hal_read_row_fn)(hal_display *d, int y, uint8_t *px, size_t len);
typedef bool (*hal_connected_fn)(hal_display *d);
typedef void (*hal_close_fn)(hal_display *d);

typedef struct hal_display_api {
    const char *name;               /* prefix of the messages: "usb", "drm", ... */
    const char *noun;               /* optional: what its users call it in messages ("the
                                     * screen"); NULL: "the display" */
    hal_begin_frame_fn begin_frame; /* optional */
    hal_line_out_fn line_out;       /* required, unless present is given */
    hal_line_buffer_fn line_buffer; /* optional: rows written in place */
    hal_end_frame_fn end_frame;     /* optional */
    hal_present_fn present;         /* optional: the pull lane */
    int lanes;                      /* lanes present pulls with (1 or 2) */
    hal_read_row_fn read_row;       /* optional: reading the picture back */
    hal_connected_fn connected;     /* optional: NULL means always there */
    hal_close_fn close;             /* optional: blanks and frees what open took */
} hal_display_api;

struct hal_display {
    const hal_display_api *api;
    int width, height;        /* what the display shows now (a hot-plugged one may change) */
    hal_pixfmt pixfmt;        /* the format of the lines it takes */
    const hal_clock *clock;   /* for deadlines and reconnect timers; may be NULL on an MCU */
    uint64_t frame_start_ns, frame_period_ns; /* deadlines; period 0: none */
    hal_log_fn log;           /* where backends' messages go; may be NULL */
    void *log_user;
    hal_frame_stats *st;      /* where a frame's counts go: set by hal_display_present for
                               * its frame (a pointer, so an MCU panel pays 4 bytes of RAM) */
    struct hal_push_lines *lines; /* hal_display_present's line buffers (host): made by the
                               * first frame it pushes, again only if a hot-plugged display
                               * changed width or format, freed by hal_display_close; NULL
                               * at open */
    char err[HAL_ERR_LEN];    /* the last error: "name: what, where" */
};

/* The operations, through inline wrappers so that an MCU build costs no
 * flash for them: optional operations that are absent succeed. */
static inline hal_status hal_display_begin_frame(hal_display *d, const hal_window *win)
{
    return d->api->begin_frame ? d->api->begin_frame(d, win) : HAL_OK;
}

static inline hal_status hal_display_line_out(hal_display *d, int y, const uint8_t *px, size_t len)
{
    return d->api->line_out(d, y, px, len);
}

/* Row y's bytes in the display's own memory, or NULL (a buffer of the caller's then). */
static inline uint8_t *hal_display_line_buffer(hal_display *d, int y, size_t len)
{
    return d->api->line_buffer ? d->api->line_buffer(d, y, len) : NULL;
}

static inline hal_status hal_display_end_frame(hal_display *d)
{
    return d->api->end_frame ? d->api->end_frame(d) : HAL_OK;
}

/* A display that cannot read its picture back says HAL_ERR_CONFIG. */
static inline hal_status hal_display_read_row(hal_display *d, int y, uint8_t *px, size_t len)
{
    return d->api->read_row ? d->api->read_row(d, y, px, len) : HAL_ERR_CONFIG;
}

static inline bool hal_display_connected(hal_display *d)
{
    return d->api->connected ? d->api->connected(d) : true;
}

/* Lanes a frame of d pulls from its source (a push display: one). */
static inline int hal_display_lanes(const hal_display *d)
{
    return d->api->present ? d->api->lanes : 1;
}

/* ---- host side (hal/host/display_host.c) ---- */

/* "ok", "device absent", ...: the kind of failure in words. */
const char *hal_status_str(hal_status st);

/* Bytes of a line of `width` pixels in fmt; 0 for an unknown format. */
size_t hal_line_bytes(hal_pixfmt fmt, int width);

/* Converts width pixels of linear RGB floats to fmt at dst. */
void hal_pixfmt_convert(hal_pixfmt fmt, const float *rgb, int width, uint8_t *dst);

/* Writes "name: message" into d->err and returns st. */
hal_status hal_display_fail(hal_display *d, hal_status st, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* A backend's message to d's log (none without one), as "name: message". */
void hal_display_say(const hal_display *d, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/*
 * Shows one frame of src: through the pull lane where the backend has one,
 * else by pushing every line (converted to d->pixfmt) between begin_frame
 * and end_frame, counting lines finished after their deadline. Adds the
 * frame's counts to *st. A source of another size than the display is
 * HAL_ERR_CONFIG; a failure stops the frame with d->err set.
 */
hal_status hal_display_present(hal_display *d, const hal_source *src, hal_frame_stats *st);

/*
 * Shows one frame of src limited to *win, the window of the display that can
 * differ from the last frame shown (an empty window: nothing changed, no
 * line is rendered), where the display takes that window: a pull-lane
 * display, a source without a window operation, or a backend whose
 * begin_frame refuses the window with HAL_ERR_CONFIG (it is away, or does
 * not hold the last frame) gets the whole frame instead, and *win is set to
 * the whole display. NULL win: the whole frame, as hal_display_present.
 */
hal_status hal_display_present_window(hal_display *d, const hal_source *src, hal_window *win,
                                      hal_frame_stats *st);

/* Frees the frame driver's line buffers, then what the backend's open took
 * (its close blanks the panel). NULL is allowed. */
void hal_display_close(hal_display *d);

/* A display that takes every line and shows nothing (dry runs, render timing). */
hal_status hal_null_open(hal_display **out, int width, int height, const hal_clock *clock);

#ifdef __cplusplus
}
#endif

#endif /* HAL_DISPLAY_H */
