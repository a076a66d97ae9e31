/*
 * panel_semihost.h - a "panel" that writes each frame to a host file.
 *
 * Under QEMU the board has no glass; this panel stands in for it and dumps
 * every frame through semihosting to <dir>/frameNN.rgb565 (panel format,
 * rows top to bottom) so that a test can compare pixels with the host
 * simulator. With no directory set it draws nothing.
 *
 * Like glass, it keeps its picture: a frame that sends only a window is
 * dumped whole, as the last frame's file with the window's rows patched in,
 * and the picture can be read back (read_row) for the whole frame's CRC.
 */
#ifndef PANEL_SEMIHOST_H
#define PANEL_SEMIHOST_H

#include <stdbool.h>

#include "mcu_display.h"

typedef struct panel_semihost {
    hal_display d;    /* first: the operations get &p->d */
    char dir[96];     /* host directory for dumps; empty: no dumps */
    int handle;       /* semihosting handle of the last frame's file, or -1 */
    uint32_t frame;   /* the number of the next frame's file */
    int width, rows;  /* the last whole frame's width (from its lines) and rows written */
    int x0;           /* this frame's window's first column; -1: whole rows in order */
    bool whole;       /* the last frame's file is complete: a window may start from it */
} panel_semihost;

/* Sets p up as a width x height panel dumping to `dir` (may be NULL or empty). */
void panel_semihost_init(panel_semihost *p, const char *dir, int width, int height);

#endif /* PANEL_SEMIHOST_H */
