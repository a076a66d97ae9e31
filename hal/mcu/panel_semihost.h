/*
 * panel_semihost.h - a "panel" that writes each frame to a host file.
 *
 * Under QEMU the board has no glass; this panel stands in for it and dumps
 * every frame through semihosting to <dir>/frameNN.rgb565 (panel format,
 * rows top to bottom) so that a test can compare pixels with the host
 * simulator. With no directory set it draws nothing.
 *
 * Like glass, it keeps its picture: a frame that sends only a window
 * (set_window) is dumped whole, as the last frame's file with the window's
 * rows patched in, and the picture can be read back (read_row) for the
 * whole frame's CRC.
 */
#ifndef PANEL_SEMIHOST_H
#define PANEL_SEMIHOST_H

#include <stdbool.h>

#include "mcu_display.h"

typedef struct panel_semihost {
    char dir[96];     /* host directory for dumps; empty: no dumps */
    int handle;       /* semihosting handle of the last frame's file, or -1 */
    char path[128];
    int width, height; /* of that frame */
    int x0;           /* its window's first column; -1: whole rows in order */
    uint32_t frame;   /* its number */
    bool whole;       /* that frame's file is complete: a window may start from it */
} panel_semihost;

extern const mcu_panel_api panel_semihost_api;

/* Copies `dir` (may be NULL or empty) into the panel. */
void panel_semihost_init(panel_semihost *p, const char *dir);

#endif /* PANEL_SEMIHOST_H */
