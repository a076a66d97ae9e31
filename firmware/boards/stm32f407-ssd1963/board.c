/*
 * board.c - the board_api for an STM32F407 with an SSD1963 TFT on FSMC.
 *
 *  - Clocks: 8 MHz HSE -> PLL (M 8, N 336, P 2, Q 7) -> 168 MHz SYSCLK,
 *    AHB 168, APB1 42, APB2 84 MHz; flash at 5 wait states with caches.
 *  - Clock for board_time_us: the DWT cycle counter (32 bits at 168 MHz,
 *    widened to 64 bits by polling; it wraps every 25.6 s).
 *  - Console: USART1 TX, polled. Stream ingress: USART2 RX, polled; the
 *    one-byte data register means the stream must be paced or the decoder
 *    polled often enough (an RX DMA ring is the next step on hardware).
 *  - Panel: SSD1963 on FSMC bank 1, commands at 0x60000000 and data at
 *    0x60020000 (A16 is D/C; on a 16-bit bus HADDR bit 17 drives A16).
 *  - Exit: no host to return to, so reset (faults end here too).
 */
#include "board.h"

#include "board_api.h"
#include "cm_regs.h"
#include "cm_startup.h"
#include "panel_ssd1963.h"

#define REG(a) CM_REG(a)

#define RCC 0x40023800u
#define RCC_CR REG(RCC + 0x00u)
#define RCC_PLLCFGR REG(RCC + 0x04u)
#define RCC_CFGR REG(RCC + 0x08u)
#define RCC_AHB1ENR REG(RCC + 0x30u)
#define RCC_AHB3ENR REG(RCC + 0x38u)
#define RCC_APB1ENR REG(RCC + 0x40u)
#define RCC_APB2ENR REG(RCC + 0x44u)
#define FLASH_ACR REG(0x40023C00u)

#define GPIO(port) (0x40020000u + 0x400u * (port)) /* A = 0, B = 1, ... */
#define GPIO_MODER(p) REG(GPIO(p) + 0x00u)
#define GPIO_OSPEEDR(p) REG(GPIO(p) + 0x08u)
#define GPIO_AFR(p, i) REG(GPIO(p) + 0x20u + 4u * (i))
#define PORT_A 0u
#define PORT_D 3u
#define PORT_E 4u

#define USART1 0x40011000u
#define USART2 0x40004400u
#define USART_SR(u) REG((u) + 0x00u)
#define USART_DR(u) REG((u) + 0x04u)
#define USART_BRR(u) REG((u) + 0x08u)
#define USART_CR1(u) REG((u) + 0x0Cu)
#define USART_SR_RXNE (1u << 5)
#define USART_SR_TXE (1u << 7)
#define USART_CR1_UE (1u << 13)
#define USART_CR1_TE (1u << 3)
#define USART_CR1_RE (1u << 2)

#define FSMC_BCR1 REG(0xA0000000u)
#define FSMC_BTR1 REG(0xA0000004u)

static panel_ssd1963 tft;
static mcu_panel panel = {"ssd1963", BOARD_PANEL_WIDTH, BOARD_PANEL_HEIGHT, &panel_ssd1963_api,
                          &tft};
static uint32_t cycles_last;
static uint64_t cycles;

static void clocks_init(void)
{
    RCC_CR |= 1u << 16; /* HSEON */
    while (!(RCC_CR & (1u << 17)))
        ;
    FLASH_ACR = (1u << 8) | (1u << 9) | (1u << 10) | 5u; /* PRFTEN ICEN DCEN, 5 WS */
    RCC_CFGR = (5u << 10) | (4u << 13);                  /* APB1 /4, APB2 /2 */
    RCC_PLLCFGR = 8u | (336u << 6) | (0u << 16) | (1u << 22) | (7u << 24);
    RCC_CR |= 1u << 24; /* PLLON */
    while (!(RCC_CR & (1u << 25)))
        ;
    RCC_CFGR = (RCC_CFGR & ~3u) | 2u; /* SYSCLK = PLL */
    while ((RCC_CFGR & (3u << 2)) != (2u << 2))
        ;
    DEMCR |= 1u << 24; /* TRCENA */
    DWT_CYCCNT = 0;
    DWT_CTRL |= 1u;    /* CYCCNTENA */
}

/* Alternate function `af` at full speed on the pins of `mask`. */
static void pins_af(uint32_t port, uint32_t mask, uint32_t af)
{
    for (uint32_t pin = 0; pin < 16; pin++) {
        if (!(mask & (1u << pin)))
            continue;
        GPIO_MODER(port) = (GPIO_MODER(port) & ~(3u << 2 * pin)) | (2u << 2 * pin);
        GPIO_OSPEEDR(port) |= 3u << 2 * pin;
        uint32_t i = pin / 8u, shift = 4u * (pin % 8u);
        GPIO_AFR(port, i) = (GPIO_AFR(port, i) & ~(15u << shift)) | (af << shift);
    }
}

static void delay_us(uint32_t us)
{
    uint32_t start = DWT_CYCCNT, span = us * (BOARD_SYSCLK_HZ / 1000000u);
    while (DWT_CYCCNT - start < span)
        ;
}

void board_init(void)
{
    clocks_init();
    cm_protect();
    RCC_AHB1ENR |= (1u << 0) | (1u << 3) | (1u << 4); /* GPIOA, GPIOD, GPIOE */
    RCC_AHB3ENR |= 1u;                                /* FSMC */
    RCC_APB1ENR |= 1u << 17;                          /* USART2 */
    RCC_APB2ENR |= 1u << 4;                           /* USART1 */

    pins_af(PORT_A, (1u << 9) | (1u << 3), 7u); /* USART1 TX, USART2 RX */
    USART_BRR(USART1) = 84000000u / 115200u;
    USART_CR1(USART1) = USART_CR1_UE | USART_CR1_TE;
    USART_BRR(USART2) = 42000000u / 115200u;
    USART_CR1(USART2) = USART_CR1_UE | USART_CR1_RE;

    /* FSMC: D0..D15, NOE, NWE, NE1, A16 */
    pins_af(PORT_D, 0xCFB3u, 12u); /* PD0 1 4 5 7 8 9 10 11 14 15 */
    pins_af(PORT_E, 0xFF80u, 12u); /* PE7..PE15 */
    FSMC_BTR1 = (1u << 16) | (6u << 8) | 3u; /* BUSTURN 1, DATAST 6, ADDSET 3 HCLK */
    FSMC_BCR1 = (1u << 12) | (1u << 4) | 1u; /* WREN, 16-bit, SRAM, MBKEN */
    tft.cmd = (volatile uint16_t *)0x60000000u;
    tft.data = (volatile uint16_t *)0x60020000u;
    tft.delay_us = delay_us;
    tft.width = BOARD_PANEL_WIDTH;
    tft.height = BOARD_PANEL_HEIGHT;
    panel_ssd1963_init(&tft);
    cycles_last = DWT_CYCCNT;
    cycles = 0;
}

void board_console_write(const char *text)
{
    for (; *text; text++) {
        if (*text == '\n') {
            while (!(USART_SR(USART1) & USART_SR_TXE))
                ;
            USART_DR(USART1) = '\r';
        }
        while (!(USART_SR(USART1) & USART_SR_TXE))
            ;
        USART_DR(USART1) = (uint8_t)*text;
    }
}

int board_link_read(uint8_t *byte)
{
    if (!(USART_SR(USART2) & USART_SR_RXNE))
        return 0;
    *byte = (uint8_t)USART_DR(USART2);
    return 1;
}

uint64_t board_time_us(void)
{
    uint32_t now = DWT_CYCCNT;
    cycles += (uint32_t)(now - cycles_last);
    cycles_last = now;
    return cycles / (BOARD_SYSCLK_HZ / 1000000u);
}

const char *board_cmdline(void)
{
    return "";
}

const mcu_panel *board_panel(void)
{
    return &panel;
}

void board_exit(int status)
{
    (void)status;
    cm_dsb();
    SCB_AIRCR = SCB_AIRCR_RESET;
    for (;;)
        ;
}
