/*
 * display_template.h - the backend to copy when adding a display.
 *
 * It drives the simplest panel there is, and the commonest on boards with an
 * LCD controller: a frame buffer the display scans out by itself, mapped at
 * an address (an STM32 LTDC layer, an i.MX eLCDIF buffer, a Linux /dev/fb0
 * mapping), plus an optional flush for panels that must be told what
 * changed (a cache clean before DMA, a partial-refresh command). Copy this
 * folder to hal/<yourpanel>/, rename the tpl_ prefix, replace the memcpy in
 * tpl_line_out with your bus writes and the flush with your controller's
 * command, and run your backend through tests/display_conformance.h (see
 * README.md here). Keep the shape: a config the caller fills (it may live
 * in ROM), a state struct whose first member is the hal_display, one const
 * table of operations.
 */
#ifndef HAL_DISPLAY_TEMPLATE_H
#define HAL_DISPLAY_TEMPLATE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "display.h"

typedef struct tpl_config {
    int width, height;   /* the glass, in pixels */
    hal_pixfmt pixfmt;   /* what the controller scans out */
    uint8_t *fb;         /* the frame buffer it scans out: height rows of pitch bytes */
    size_t pitch;        /* bytes from one row to the next (at least a line's bytes) */
    /* Optional: tells the panel that rows win->y0..y1-1 changed; false if it
     * could not (a bus error), which the frame reports as HAL_ERR_IO. */
    bool (*flush)(void *user, const hal_window *win);
    void *flush_user;
} tpl_config;

typedef struct tpl_display {
    hal_display d;       /* first: the operations get &t->d and cast it back */
    const tpl_config *cfg;
    hal_window win;      /* the current frame's window */
    int next_y;          /* the lowest row line_out may write next */
    bool in_frame;
} tpl_display;

/* Checks cfg and sets t up as a display (no allocation: t is the caller's).
 * HAL_ERR_CONFIG, with t->d.err saying what is wrong, for a bad config. */
hal_status tpl_open(tpl_display *t, const tpl_config *cfg, const hal_clock *clock);

#endif /* HAL_DISPLAY_TEMPLATE_H */
