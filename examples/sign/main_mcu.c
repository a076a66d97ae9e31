/*
 * main_mcu.c - the sign's main loop on a microcontroller board.
 *
 * Bytes arrive on a UART, lines go to a panel controller's data port, and a
 * timer gives the time; the addresses are a made-up board's (put your own,
 * or your HAL's calls, in their place). Built for Cortex-M4F against the
 * installed library, this is a link check of the library and its headers
 * for the target, not a board port: see firmware/ for real boards.
 */
#include "sign.h"

#define UART_STATUS (*(volatile uint32_t *)0x40004004u) /* bit 0: a byte is waiting */
#define UART_DATA (*(volatile uint32_t *)0x40004000u)
#define PANEL_DATA (*(volatile uint16_t *)0x60020000u)
#define TIMER_MS (*(volatile uint32_t *)0x40001024u)

static sign board;

static void panel_write(void *user, int y, const uint8_t *rgb565, int width)
{
    (void)user, (void)y;
    for (int x = 0; x < width; x++)
        PANEL_DATA = (uint16_t)(rgb565[2 * x] | rgb565[2 * x + 1] << 8);
}

int main(void)
{
    if (sign_init(&board, CS_CFG_MAX_WIDTH, CS_CFG_MAX_HEIGHT, panel_write, 0) != CS_OK)
        for (;;) {
        }
    for (;;) {
        /* between frames: take what the link has */
        uint8_t buf[64];
        size_t n = 0;
        while (n < sizeof buf && (UART_STATUS & 1u))
            buf[n++] = (uint8_t)UART_DATA;
        sign_feed(&board, buf, n);
        uint32_t crc;
        if (sign_has_scene(&board))
            sign_frame(&board, (float)TIMER_MS / 1000.0f, &crc);
    }
}
