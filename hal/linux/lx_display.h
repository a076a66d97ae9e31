/*
 * lx_display.h - the display seam of celfw, celscan's firmware for Linux boards.
 *
 * Linux boards drive two kinds of display that want lines in different ways.
 * A USB display bridge keeps its own frame buffer, so it wants each frame once,
 * top to bottom, and only the lines that changed. A HUB75 LED matrix keeps
 * nothing: it shows one row pair at a time and must be rescanned hundreds of
 * times a second, so it wants lines y and y + rows/2 together, over and over.
 * Neither may hold a frame of pixels. So the seam is a pull model: a backend
 * asks an lx_source for lines as its hardware needs them, in one or more
 * "lanes", each an independent stream of lines in increasing y (the order the
 * core's active-piece list can move in).
 *
 * This is celfw's own interface. hal/display.h is the push model of the
 * simulator and MCU ports; a push backend there can be wrapped as an
 * lx_display with one lane.
 */
#ifndef LX_DISPLAY_H
#define LX_DISPLAY_H

#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lx_clock.h"

typedef enum lx_status {
    LX_OK = 0,
    LX_ERR_CONFIG,    /* configuration is invalid; the message says which key */
    LX_ERR_NO_DEVICE, /* the device is absent or vanished */
    LX_ERR_IO,        /* a transfer or write failed */
    LX_ERR_TIMEOUT,   /* the device did not answer in time */
    LX_ERR_PROTOCOL,  /* the device answered something we cannot use */
    LX_ERR_RENDER,    /* the renderer failed (scene or capacity error) */
    LX_ERR_NOMEM
} lx_status;

const char *lx_status_str(lx_status st);

/* Where lines come from: the renderer side of the seam. */
typedef struct lx_source {
    int width, height;
    void *user;
    /* Starts a frame with `lanes` independent line streams (1 or 2). */
    lx_status (*begin)(void *user, int lanes);
    /* Renders line y into rgb (3*width floats, linear light). Within a lane,
     * y must increase from call to call; lines may be skipped. */
    lx_status (*line)(void *user, int lane, int y, float *rgb);
} lx_source;

/* What one present() did; backends add to it, celfw sums it. */
typedef struct lx_frame_stats {
    uint64_t lines_rendered;
    uint64_t lines_sent;   /* USB: lines that travelled (changed lines) */
    uint64_t rects;        /* USB: SET_BUFFER rectangles */
    uint64_t bytes_raw;    /* USB: pixel bytes of the rectangles */
    uint64_t bytes_wire;   /* USB: bytes on the bulk pipe (after LZ4) */
    uint64_t writes;       /* GPIO: bulk line writes */
    uint64_t line_misses;  /* lines (row pairs) finished after their deadline */
    uint64_t retries;      /* transfers repeated after an error */
    uint64_t errors;       /* transfers that failed for good */
} lx_frame_stats;

typedef void (*lx_log_fn)(void *user, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

typedef struct lx_display lx_display;

typedef struct lx_display_ops {
    const char *name;
    int lanes; /* lanes the backend pulls with */
    /*
     * Shows one frame, pulling its lines from src. Deadlines: line y (a row
     * pair for HUB75) is due at d->frame_start_ns + (y+1) * d->frame_period_ns
     * / height; later lines count as misses. Returns LX_ERR_NO_DEVICE while
     * the device is away (the caller keeps calling; the backend reconnects).
     */
    lx_status (*present)(lx_display *d, const lx_source *src, lx_frame_stats *st);
    /* true while the device is there and set up. */
    bool (*connected)(lx_display *d);
    /* Blanks the display if it can and frees everything. */
    void (*close)(lx_display *d);
} lx_display_ops;

struct lx_display {
    const lx_display_ops *ops;
    int width, height;
    const lx_clock *clock;
    uint64_t frame_start_ns, frame_period_ns;
    lx_log_fn log;
    void *log_user;
    char err[256]; /* the last error, for the caller's message */
};

/*
 * A backend's message to d's log (none without one), as "WHO: message":
 * backends wrap it in a printf-style function of their own (lx_display.c).
 */
void lx_display_vsay(const lx_display *d, const char *who, const char *fmt, va_list ap);

/* A display that renders every line and throws it away (tests, dry runs). */
lx_status lx_null_open(lx_display **out, int width, int height, const lx_clock *clock);

#endif /* LX_DISPLAY_H */
