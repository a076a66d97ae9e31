/*
 * board_api.h - what a board gives the firmware's main loop.
 *
 * One small interface, in the manner of TinyUSB's board_api.h: each board
 * folder (firmware/boards/<board>/) implements it in its board.c, and the
 * build picks the board with BOARD=<name>. The main loop and the MCU
 * display backend know nothing else about the hardware.
 */
#ifndef BOARD_API_H
#define BOARD_API_H

#include <stddef.h>
#include <stdint.h>

#include "mcu_display.h"

/* Clocks, the UART, the MPU stack guard, the panel. Called once by main. */
void board_init(void);

/* Status text for people and tests (semihosting console or a UART). */
void board_console_write(const char *text);

/* Stream ingress: one received byte into *byte and 1, 0 if none waits, or
 * -1 where bytes were lost (a receive overrun: the bytes after it do not
 * follow the ones before). Never blocks. */
int board_link_read(uint8_t *byte);

/* The receive ring behind it (for its high-water mark and size). */
const struct rx_ring *board_link_ring(void);

/* Monotonic time in microseconds since board_init. */
uint64_t board_time_us(void);

/* The same timer as the one clock interface, hal/clock.h (firmware/fw_clock.c). */
extern const hal_clock board_clock;

/* Arguments from the host (QEMU's -append via semihosting), or "". */
const char *board_cmdline(void);

/* The panel that finished lines go to: a display of hal/display.h taking
 * CS_PANEL_PIXFMT lines, its size the glass's; NULL if the board has none
 * (QEMU without dump=). */
hal_display *board_panel(void);

/* Ends the program with an exit status: the emulator exits with it; real
 * hardware resets. Fault handlers call it too, with a non-zero status. */
void board_exit(int status) __attribute__((noreturn));

#endif /* BOARD_API_H */
