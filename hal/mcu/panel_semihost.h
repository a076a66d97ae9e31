/*
 * panel_semihost.h - a "panel" that writes each frame to a host file.
 *
 * Under QEMU the board has no glass; this panel stands in for it and dumps
 * every frame through semihosting to <dir>/frameNN.rgb565 (panel format,
 * rows top to bottom) so that a test can compare pixels with the host
 * simulator. With no directory set it draws nothing.
 */
#ifndef PANEL_SEMIHOST_H
#define PANEL_SEMIHOST_H

#include "mcu_display.h"

typedef struct panel_semihost {
    hal_display d;    /* first: the operations get &p->d */
    char dir[96];     /* host directory for dumps; empty: no dumps */
    int handle;       /* semihosting handle of the open frame, or -1 */
    uint32_t frame;   /* the number of the next frame's file */
    char path[128];
} panel_semihost;

/* Sets p up as a width x height panel dumping to `dir` (may be NULL or empty). */
void panel_semihost_init(panel_semihost *p, const char *dir, int width, int height);

#endif /* PANEL_SEMIHOST_H */
