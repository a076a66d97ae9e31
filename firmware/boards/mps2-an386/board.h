/*
 * board.h - Arm MPS2 with the AN386 FPGA image (Cortex-M4F), as QEMU's
 * mps2-an386 machine models it. Addresses from QEMU's hw/arm/mps2.c and
 * Arm AN386; the CMSDK peripherals are documented in the Cortex-M System
 * Design Kit TRM (DDI 0479).
 */
#ifndef BOARD_H
#define BOARD_H

#define BOARD_NAME "mps2-an386"
#define BOARD_SYSCLK_HZ 25000000u
#define BOARD_IRQ_COUNT 32

/* The panel the firmware renders for: a 480x272 RGB565 TFT, here only a
 * frame dump through semihosting. */
/* Words from the host's command line (QEMU -append, over semihosting). */
#define BOARD_CMDLINE 1

#define BOARD_PANEL_WIDTH 480
#define BOARD_PANEL_HEIGHT 272

/* CMSDK APB UART0: stream ingress (QEMU's first -serial); its receive
 * interrupt is IRQ 0 (QEMU hw/arm/mps2.c, as on the AN385/AN386 FPGA). */
#define MPS2_UART0_BASE 0x40004000u
#define MPS2_UART0_RX_IRQ 0
#define BOARD_RX_RING 64 /* bytes; QEMU's UART waits while it is full */
void board_link_isr(void);
#define BOARD_VECTORS [16 + MPS2_UART0_RX_IRQ] = board_link_isr,
/* CMSDK APB dual timer: timer 1 runs free as the clock. */
#define MPS2_DUALTIMER_BASE 0x40002000u

#endif /* BOARD_H */
