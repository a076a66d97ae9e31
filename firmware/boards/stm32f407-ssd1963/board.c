/*
 * board.c - the board_api for an STM32F407 with an SSD1963 TFT on FSMC.
 *
 *  - Clock, time, console and stream link: the shared STM32F4 drivers
 *    (firmware/boards/stm32f4): 168 MHz from the 8 MHz HSE, SysTick time,
 *    console on USART1 TX, stream ingress on USART2 RX by interrupt into a
 *    ring, with RTS flow control on PA1.
 *  - Panel: SSD1963 on FSMC bank 1, commands at 0x60000000 and data at
 *    0x60020000 (A16 is D/C; on a 16-bit bus HADDR bit 17 drives A16).
 *  - Exit: no host to return to, so reset (faults end here too).
 */
#include "board.h"

#include "board_api.h"
#include "cm_regs.h"
#include "cm_startup.h"
#include "panel_ssd1963.h"

#define RCC_AHB3ENR CM_REG(0x40023838u)
#define FSMC_BCR1 CM_REG(0xA0000000u)
#define FSMC_BTR1 CM_REG(0xA0000004u)
#define PORT_D 3u
#define PORT_E 4u

static panel_ssd1963 tft;

static void delay_us(uint32_t us)
{
    hal_wait_until(&board_clock, hal_now(&board_clock) + (uint64_t)us * 1000u);
}

void board_init(void)
{
    stm32_clock_pll168();
    stm32_tick_init();
    cm_protect();
    stm32_usart_init(0);

    /* FSMC: D0..D15, NOE, NWE, NE1, A16 */
    RCC_AHB3ENR |= 1u;
    stm32_pins_af(PORT_D, 0xCFB3u, 12u); /* PD0 1 4 5 7 8 9 10 11 14 15 */
    stm32_pins_af(PORT_E, 0xFF80u, 12u); /* PE7..PE15 */
    FSMC_BTR1 = (1u << 16) | (6u << 8) | 3u; /* BUSTURN 1, DATAST 6, ADDSET 3 HCLK */
    FSMC_BCR1 = (1u << 12) | (1u << 4) | 1u; /* WREN, 16-bit, SRAM, MBKEN */
    tft.cmd = (volatile uint16_t *)0x60000000u;
    tft.data = (volatile uint16_t *)0x60020000u;
    tft.delay_us = delay_us;
    panel_ssd1963_init(&tft, BOARD_PANEL_WIDTH, BOARD_PANEL_HEIGHT);
}

void board_console_write(const char *text)
{
    stm32_console_write(text);
}

const char *board_cmdline(void)
{
    return "";
}

hal_display *board_panel(void)
{
    return &tft.d;
}

void board_exit(int status)
{
    (void)status;
    cm_dsb();
    SCB_AIRCR = SCB_AIRCR_RESET;
    for (;;)
        ;
}
