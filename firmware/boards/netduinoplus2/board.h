/*
 * board.h - QEMU's netduinoplus2 machine: an STM32F405 (Cortex-M4F at
 * 168 MHz, the F407's USART, NVIC, RCC and SysTick blocks), running the
 * STM32 board's drivers (firmware/boards/stm32f4) in CI. QEMU has no FSMC
 * (nor GPIO or RCC: their registers read 0 and ignore writes), so the
 * panel is the semihosting frame dump of the mps2 board, the console and
 * the command line are semihosting too, and the clock is not set up (QEMU
 * runs the core at 168 MHz from reset). The stream link is USART2, QEMU's
 * second -serial (the first is USART1).
 */
#ifndef BOARD_H
#define BOARD_H

#define BOARD_NAME "netduinoplus2"
#define BOARD_SYSCLK_HZ 168000000u
#define BOARD_RX_RING 64 /* bytes; QEMU's USART waits while the ring is full */
#include "stm32f4.h"
#define BOARD_IRQ_COUNT STM32_IRQ_COUNT

/* Words from the host's command line (QEMU -append, over semihosting). */
#define BOARD_CMDLINE 1

#define BOARD_PANEL_WIDTH 480
#define BOARD_PANEL_HEIGHT 272

#endif /* BOARD_H */
