/*
 * stm32_clock.c - the STM32F4 system clock and board_time_us (stm32f4.h).
 *
 * Time is SysTick counting down from 2^24 - 1 on the core clock; its
 * interrupt counts the wraps (every 0.1 s at 168 MHz), so a frame that
 * takes longer than one wrap loses no time. A wrap the interrupt has not
 * counted yet (its exception is taken a few cycles late on the chip, and
 * QEMU reloads the counter before it even pends the exception) would make
 * time step back by a whole wrap; since time is read far more often than
 * once per wrap, a step back is such a wrap, and is counted here.
 */
#include "board.h"
#include "board_api.h"
#include "cm_regs.h"
#include "cm_startup.h"

#define RCC_CR CM_REG(0x40023800u)
#define RCC_PLLCFGR CM_REG(0x40023804u)
#define RCC_CFGR CM_REG(0x40023808u)
#define FLASH_ACR CM_REG(0x40023C00u)

#define SYST_CSR_ENABLE (1u << 0)
#define SYST_CSR_TICKINT (1u << 1)
#define SYST_CSR_CORE_CLOCK (1u << 2)
#define SYST_MAX 0xFFFFFFu

static struct {
    volatile uint32_t wraps; /* the interrupt's */
    uint64_t last;           /* cycles at the last board_time_us */
} tick;

void stm32_clock_pll168(void)
{
    RCC_CR |= 1u << 16; /* HSEON */
    while (!(RCC_CR & (1u << 17)))
        ;
    FLASH_ACR = (1u << 8) | (1u << 9) | (1u << 10) | 5u; /* PRFTEN ICEN DCEN, 5 WS */
    RCC_CFGR = (5u << 10) | (4u << 13);                  /* APB1 /4, APB2 /2 */
    RCC_PLLCFGR = 8u | (336u << 6) | (0u << 16) | (1u << 22) | (7u << 24); /* M 8 N 336 P 2 Q 7, HSE */
    RCC_CR |= 1u << 24; /* PLLON */
    while (!(RCC_CR & (1u << 25)))
        ;
    RCC_CFGR = (RCC_CFGR & ~3u) | 2u; /* SYSCLK = PLL */
    while ((RCC_CFGR & (3u << 2)) != (2u << 2))
        ;
}

void stm32_tick_isr(void)
{
    tick.wraps = tick.wraps + 1u;
}

void stm32_tick_init(void)
{
    tick.wraps = 0;
    tick.last = 0;
    SYST_RVR = SYST_MAX;
    SYST_CVR = 0;
    SYST_CSR = SYST_CSR_ENABLE | SYST_CSR_TICKINT | SYST_CSR_CORE_CLOCK;
}

uint64_t board_time_us(void)
{
    uint32_t wraps, value;
    do {
        wraps = tick.wraps;
        value = SYST_CVR;
    } while (wraps != tick.wraps);
    uint64_t cycles = ((uint64_t)wraps << 24) + (SYST_MAX - value);
    if (cycles < tick.last)
        cycles += SYST_MAX + 1u;
    tick.last = cycles;
    return cm_udiv64(cycles, BOARD_SYSCLK_HZ / 1000000u, 0);
}
