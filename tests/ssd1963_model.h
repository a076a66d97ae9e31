/*
 * ssd1963_model.h - a model of the Solomon SSD1963 display controller on a
 * 16-bit 8080 bus, for running hal/mcu/panel_ssd1963.c on the host.
 *
 * It is written from the controller's command set (SSD1963 datasheet,
 * section 8), not from the driver: bus writes with D/C low are commands,
 * with D/C high a command's 8-bit parameters or, after write_memory_start
 * (0x2C) or write_memory_continue (0x3C), 16-bit RGB565 pixels stored at
 * the column and page address, which walk the window set by
 * set_column_address (0x2A) and set_page_address (0x2B): column SC..EC,
 * then the next page. Its frame memory is the glass's picture. Anything
 * the datasheet does not allow (an unknown command, a parameter above 8
 * bits or too many, a window beyond the glass or reversed, pixels before
 * the PLL is locked and the panel's mode and 16-bit interface are set,
 * a pixel past the window's last page, the PLL locked sooner than 100 us
 * after it was started, a command within 5 ms of a soft reset) is
 * recorded as the model's first fault, which the test checks is empty.
 *
 * The driver's bus pointers point into the model (ssd_model_attach), as an
 * FSMC bank's two addresses do on a board: the address's bit 1 is D/C, as
 * a board wires an address line to D/C. The panel source is compiled with
 * this header forced in (-include), which routes its bus writes here.
 */
#ifndef SSD1963_MODEL_H
#define SSD1963_MODEL_H

#include <stdbool.h>
#include <stdint.h>

#define SSD1963_BUS_WRITE(reg, v) ssd_model_write((reg), (uint16_t)(v))

typedef struct ssd_model {
    _Alignas(4) uint16_t bus[2]; /* first: bus[0] is D/C low (commands), bus[1] D/C high (data) */
    int width, height;           /* the glass */
    uint16_t *frame;             /* width x height RGB565 words, the controller's frame memory */
    uint8_t cmd;                 /* the command being parameterised or written */
    uint8_t args[8];
    int nargs;
    bool writing;                /* after 0x2C/0x3C: data words are pixels */
    int sc, ec, sp, ep;          /* the column and page window */
    int col, page;               /* the write address */
    bool pll_on, pll_locked, mode_set, display_on;
    int hdp, vdp;                /* horizontal and vertical display period - 1 (set_lcd_mode) */
    int pixel_interface;         /* set_pixel_data_interface; 3 = 16 bits, 565 */
    uint64_t now_us, pll_on_us, reset_us;
    bool reset_seen;             /* a soft reset was sent (at reset_us) */
    long pixels;                 /* pixel words written, in all */
    long commands;
    char fault[160];             /* the first fault; empty: none */
} ssd_model;

/* A model of a width x height glass whose memory holds `fill` in every pixel. */
bool ssd_model_init(ssd_model *m, int width, int height, uint16_t fill);
void ssd_model_free(ssd_model *m);

/* The command and data addresses to give the driver. */
void ssd_model_attach(ssd_model *m, volatile uint16_t **cmd, volatile uint16_t **data);

/* One bus write, as the driver's SSD1963_BUS_WRITE makes it. */
void ssd_model_write(volatile uint16_t *reg, uint16_t v);

/* Time passes (the driver's delay_us). */
void ssd_model_wait(ssd_model *m, uint32_t us);

#endif /* SSD1963_MODEL_H */
