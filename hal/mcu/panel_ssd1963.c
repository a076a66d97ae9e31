/*
 * panel_ssd1963.c - SSD1963 over a memory-mapped 8080 bus (see the header).
 *
 * Command values and the set-up order follow the SSD1963 datasheet
 * (Solomon Systech, rev 1.x, sections 8 and 9): PLL first (the controller
 * runs from the crystal until the PLL is locked), then the pixel clock,
 * the panel's timing and the 16-bit 565 pixel interface. Timings are
 * those of the common 4.3" 480x272 modules; another glass needs its own.
 *
 * A frame sets the memory window once and then streams lines; the
 * controller advances its write address by itself, so a line costs
 * exactly `width` bus writes.
 *
 * Every bus write goes through SSD1963_BUS_WRITE. On a board it is a store
 * to the memory-mapped bus; the host test (tests/ssd1963_model.h) defines
 * it as a call into a model of the controller that interprets the writes,
 * so the conformance case runs on this very file.
 */
#include "panel_ssd1963.h"

#ifndef SSD1963_BUS_WRITE
#define SSD1963_BUS_WRITE(reg, v) (*(reg) = (v))
#endif

#define CMD_SOFT_RESET 0x01
#define CMD_DISPLAY_ON 0x29
#define CMD_SET_COLUMN 0x2A
#define CMD_SET_PAGE 0x2B
#define CMD_WRITE_MEMORY 0x2C
#define CMD_ADDRESS_MODE 0x36
#define CMD_SET_LCD_MODE 0xB0
#define CMD_SET_HORI_PERIOD 0xB4
#define CMD_SET_VERT_PERIOD 0xB6
#define CMD_SET_PLL 0xE0
#define CMD_SET_PLL_MN 0xE2
#define CMD_SET_LSHIFT_FREQ 0xE6
#define CMD_SET_PIXEL_INTERFACE 0xF0

static void command(panel_ssd1963 *p, uint8_t c, const uint8_t *args, int n)
{
    SSD1963_BUS_WRITE(p->cmd, c);
    for (int i = 0; i < n; i++)
        SSD1963_BUS_WRITE(p->data, args[i]);
}

/* A start and end address (inclusive), high bytes first: the column and page set's parameters. */
static void address_set(panel_ssd1963 *p, uint8_t c, int a0, int a1)
{
    const uint8_t arg[4] = {(uint8_t)(a0 >> 8), (uint8_t)a0, (uint8_t)(a1 >> 8), (uint8_t)a1};
    command(p, c, arg, 4);
}

static const hal_display_api panel_ssd1963_api;

void panel_ssd1963_init(panel_ssd1963 *p, int width, int height)
{
    p->d.api = &panel_ssd1963_api;
    p->d.width = width;
    p->d.height = height;
    p->d.pixfmt = CS_PANEL_PIXFMT;
    p->win = (hal_window){0, 0, 0, 0};
    p->next_y = 0;
    int hd = width - 1, vd = height - 1;
    command(p, CMD_SOFT_RESET, 0, 0);
    p->delay_us(5000);
    /* VCO = 10 MHz x (M + 1) = 300 MHz (M = 0x1D; 250..800 MHz allowed),
     * PLL = VCO / (N + 1) = 100 MHz (N = 2); 0x04 makes M and N effective. */
    static const uint8_t pll_mn[3] = {0x1D, 0x02, 0x04};
    command(p, CMD_SET_PLL_MN, pll_mn, 3);
    static const uint8_t pll_on[1] = {0x01}, pll_lock[1] = {0x03};
    command(p, CMD_SET_PLL, pll_on, 1);
    p->delay_us(100);
    command(p, CMD_SET_PLL, pll_lock, 1);
    p->delay_us(1000);
    command(p, CMD_SOFT_RESET, 0, 0);
    p->delay_us(5000);
    /* Pixel clock 9 MHz: LCDC_FPR = 9 MHz * 2^20 / 100 MHz - 1 = 94371. */
    static const uint8_t lshift[3] = {0x01, 0x70, 0xA3};
    command(p, CMD_SET_LSHIFT_FREQ, lshift, 3);
    const uint8_t mode[7] = {0x20, 0x00, (uint8_t)(hd >> 8), (uint8_t)hd,
                             (uint8_t)(vd >> 8), (uint8_t)vd, 0x00};
    command(p, CMD_SET_LCD_MODE, mode, 7);
    /* HT 531, HPS 43, HPW 10, LPS 8; VT 288, VPS 12, VPW 10, FPS 4. */
    static const uint8_t hori[8] = {0x02, 0x13, 0x00, 0x2B, 0x0A, 0x00, 0x08, 0x00};
    static const uint8_t vert[7] = {0x01, 0x20, 0x00, 0x0C, 0x0A, 0x00, 0x04};
    command(p, CMD_SET_HORI_PERIOD, hori, 8);
    command(p, CMD_SET_VERT_PERIOD, vert, 7);
    static const uint8_t rgb565[1] = {0x03}, normal[1] = {0x00};
    command(p, CMD_SET_PIXEL_INTERFACE, rgb565, 1);
    command(p, CMD_ADDRESS_MODE, normal, 1);
    command(p, CMD_DISPLAY_ON, 0, 0);
}

/* The window's rows and columns become the controller's write window. */
static hal_status begin_frame(hal_display *d, const hal_window *win)
{
    panel_ssd1963 *p = (panel_ssd1963 *)d;
    const hal_window all = {0, 0, d->width, d->height};
    if (!win)
        win = &all;
    if (!hal_window_inside(win, d->width, d->height))
        return HAL_ERR_CONFIG;
    p->win = *win;
    p->next_y = win->y0;
    if (win->x0 == win->x1 || win->y0 == win->y1) {
        p->win.y1 = win->y0; /* nothing changed: nothing crosses the bus, and no line may */
        return HAL_OK;
    }
    address_set(p, CMD_SET_COLUMN, win->x0, win->x1 - 1);
    address_set(p, CMD_SET_PAGE, win->y0, win->y1 - 1);
    SSD1963_BUS_WRITE(p->cmd, CMD_WRITE_MEMORY);
    return HAL_OK;
}

static hal_status line_out(hal_display *d, int y, const uint8_t *pixels, size_t bytes)
{
    panel_ssd1963 *p = (panel_ssd1963 *)d;
    if (y < p->next_y || y >= p->win.y1)
        return HAL_ERR_SEQUENCE;
    if (bytes != 2u * (size_t)(p->win.x1 - p->win.x0))
        return HAL_ERR_CONFIG;
    if (y != p->next_y) { /* rows skipped: write memory again from row y's first column */
        address_set(p, CMD_SET_PAGE, y, p->win.y1 - 1);
        SSD1963_BUS_WRITE(p->cmd, CMD_WRITE_MEMORY);
    }
    for (size_t i = 0; i + 1 < bytes; i += 2)
        SSD1963_BUS_WRITE(p->data, (uint16_t)(pixels[i] | pixels[i + 1] << 8)); /* RGB565, little-endian */
    p->next_y = y + 1;
    return HAL_OK;
}

/* The frame is over: lines until the next begin_frame are out of order. */
static hal_status end_frame(hal_display *d)
{
    ((panel_ssd1963 *)d)->win.y1 = 0;
    return HAL_OK;
}

static const hal_display_api panel_ssd1963_api = {
    .name = "ssd1963",
    .begin_frame = begin_frame,
    .line_out = line_out,
    .end_frame = end_frame,
};
