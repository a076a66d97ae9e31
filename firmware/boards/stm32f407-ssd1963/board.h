/*
 * board.h - an STM32F407 board (e.g. the common "STM32F407VET6 black"
 * boards) with a 4.3" 480x272 TFT behind an SSD1963 controller on the
 * FSMC 8080 bus: a real part with a common panel. Register addresses are
 * from RM0090 (STM32F405/407 reference manual).
 *
 * Wiring: FSMC bank 1 (NE1 = PD7), 16-bit data D0..D15, NOE PD4, NWE PD5,
 * D/C on A16 (PD11); console on USART1 (PA9 TX), stream ingress on USART2
 * (PA3 RX, PA1 RTS for flow control), both 115200 8N1; 8 MHz HSE crystal.
 */
#ifndef BOARD_H
#define BOARD_H

#define BOARD_NAME "stm32f407-ssd1963"
#define BOARD_SYSCLK_HZ 168000000u
#define BOARD_RX_RING 256 /* bytes of USART2 input kept while a frame renders */
#include "stm32f4.h"
#define BOARD_IRQ_COUNT STM32_IRQ_COUNT

#define BOARD_PANEL_WIDTH 480
#define BOARD_PANEL_HEIGHT 272

/* After the built-in jobs, keep animating the demo on the glass. */
#define BOARD_DEMO_LOOP 1

#endif /* BOARD_H */
