/*
 * panel_ssd1963.h - Solomon SSD1963 display controller on an 8080 bus.
 *
 * The SSD1963 holds its own frame memory, which is what lets celscan drive
 * a 480x272 TFT with no frame buffer in the MCU: each finished line is
 * streamed into the controller's memory as it is produced. The bus is
 * memory-mapped (an STM32 FSMC/FMC bank, or any external-memory
 * controller): one address with D/C low for commands, one with D/C high
 * for data, 16 bits wide, pixels in RGB565.
 */
#ifndef PANEL_SSD1963_H
#define PANEL_SSD1963_H

#include "mcu_display.h"

typedef struct panel_ssd1963 {
    hal_display d;            /* first: the operations get &p->d; d.width, d.height: the glass */
    volatile uint16_t *cmd;   /* bus address with D/C = 0 */
    volatile uint16_t *data;  /* bus address with D/C = 1 */
    void (*delay_us)(uint32_t us);
    hal_window win;           /* the frame's window; rows y1.. are refused (y1 = 0 between frames) */
    int next_y;               /* the row the controller's write address is on */
} panel_ssd1963;

/* Resets and configures the controller for a 4.3" width x height (480x272)
 * TFT (PLL from a 10 MHz crystal to 100 MHz, 9 MHz pixel clock, RGB565 on a
 * 16-bit bus) and turns the display on; cmd, data and delay_us are set. A
 * frame's window (display.h) becomes the controller's column and page
 * address window, so only its pixels cross the bus; a row skipped within
 * the window moves the write address with a page address set. A row out of
 * order or outside a frame is HAL_ERR_SEQUENCE, a window outside the glass
 * or a line of another width HAL_ERR_CONFIG (by status alone: an MCU build
 * has no room for messages). */
void panel_ssd1963_init(panel_ssd1963 *p, int width, int height);

#endif /* PANEL_SSD1963_H */
