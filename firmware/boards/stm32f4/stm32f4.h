/*
 * stm32f4.h - the STM32F405/407 drivers the STM32 boards share: clock,
 * SysTick time, USARTs and the stream link's receive interrupt. Register
 * addresses and bits from RM0090; interrupt numbers from its vector table
 * (USART2 is IRQ 38, as QEMU's stm32f405_soc.c wires it too).
 *
 * The link is USART2 (RX on PA3, RTS on PA1), received by its RXNE
 * interrupt into a ring (hal/mcu/rx_ring.c): bytes that arrive while a
 * frame renders are kept. When the ring is full the interrupt masks itself
 * (in the NVIC) and leaves the byte in the data register; with RTS wired, USART2's
 * hardware flow control then holds the sender off (QEMU's model simply
 * waits); without it the next byte overruns, and the overrun (ORE) is a
 * gap the stream decoder is told about, never a silent loss.
 *
 * A board using these includes this header from its board.h and defines
 * BOARD_RX_RING (ring bytes, a power of two) first.
 */
#ifndef STM32F4_H
#define STM32F4_H

#include <stdint.h>

#define STM32_USART1 0x40011000u /* console on the real board: PA9 TX */
#define STM32_USART2 0x40004400u /* stream link: PA3 RX, PA1 RTS */
#define STM32_USART2_IRQ 38
#define STM32_IRQ_COUNT 82

void stm32_link_isr(void);
void stm32_tick_isr(void);
#define BOARD_VECTORS [15] = stm32_tick_isr, [16 + STM32_USART2_IRQ] = stm32_link_isr,

/* 8 MHz HSE -> PLL -> 168 MHz SYSCLK, APB1 42 and APB2 84 MHz, flash at 5
 * wait states. Only on a real chip: QEMU models no RCC (and runs at 168). */
void stm32_clock_pll168(void);

/* SysTick free-running on the core clock, its wrap interrupt extending it
 * to 64 bits: board_time_us. */
void stm32_tick_init(void);

/* Alternate function `af` at full speed on the pins of `mask` of a port
 * (0 = A, 1 = B, ...), clock of the port enabled. */
void stm32_pins_af(uint32_t port, uint32_t mask, uint32_t af);

/* USART1 TX (console) and USART2 RX (link, interrupt-driven, RTS flow
 * control) at 115200 8N1 with the 168 MHz clocks; the link drops its
 * delivered byte number `drop_at` as an overrun would (0: never; a test
 * hook). */
void stm32_usart_init(uint32_t drop_at);

/* Text out on USART1, polled, "\n" sent as "\r\n". */
void stm32_console_write(const char *text);

#endif /* STM32F4_H */
