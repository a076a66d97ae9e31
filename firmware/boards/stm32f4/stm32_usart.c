/*
 * stm32_usart.c - STM32F4 pins, the console USART and the stream link's
 * interrupt-driven receive (stm32f4.h has the rules).
 */
#include "board.h"
#include "board_api.h"
#include "cm_regs.h"
#include "rx_ring.h"

#define RCC_AHB1ENR CM_REG(0x40023830u)
#define RCC_APB1ENR CM_REG(0x40023840u)
#define RCC_APB2ENR CM_REG(0x40023844u)

#define GPIO(port) (0x40020000u + 0x400u * (port)) /* A = 0, B = 1, ... */
#define GPIO_MODER(p) CM_REG(GPIO(p) + 0x00u)
#define GPIO_OSPEEDR(p) CM_REG(GPIO(p) + 0x08u)
#define GPIO_AFR(p, i) CM_REG(GPIO(p) + 0x20u + 4u * (i))

#define USART_SR(u) CM_REG((u) + 0x00u)
#define USART_DR(u) CM_REG((u) + 0x04u)
#define USART_BRR(u) CM_REG((u) + 0x08u)
#define USART_CR1(u) CM_REG((u) + 0x0Cu)
#define USART_CR3(u) CM_REG((u) + 0x14u)
#define USART_SR_ORE (1u << 3)
#define USART_SR_RXNE (1u << 5)
#define USART_SR_TXE (1u << 7)
#define USART_CR1_UE (1u << 13)
#define USART_CR1_RXNEIE (1u << 5) /* interrupt on RXNE and ORE */
#define USART_CR1_TE (1u << 3)
#define USART_CR1_RE (1u << 2)
#define USART_CR3_RTSE (1u << 8)

/* What the USART2 receive interrupt shares with the main loop. */
static struct {
    rx_ring ring;
    uint8_t buf[BOARD_RX_RING];
} link;

void stm32_pins_af(uint32_t port, uint32_t mask, uint32_t af)
{
    RCC_AHB1ENR |= 1u << port;
    for (uint32_t pin = 0; pin < 16; pin++) {
        if (!(mask & (1u << pin)))
            continue;
        GPIO_MODER(port) = (GPIO_MODER(port) & ~(3u << 2 * pin)) | (2u << 2 * pin);
        GPIO_OSPEEDR(port) |= 3u << 2 * pin;
        uint32_t i = pin / 8u, shift = 4u * (pin % 8u);
        GPIO_AFR(port, i) = (GPIO_AFR(port, i) & ~(15u << shift)) | (af << shift);
    }
}

void stm32_usart_init(uint32_t drop_at)
{
    rx_ring_init(&link.ring, link.buf, sizeof link.buf, drop_at);
    RCC_APB1ENR |= 1u << 17; /* USART2 */
    RCC_APB2ENR |= 1u << 4;  /* USART1 */
    stm32_pins_af(0, (1u << 9) | (1u << 3) | (1u << 1), 7u); /* PA9, PA3, PA1 */
    USART_BRR(STM32_USART1) = 84000000u / 115200u;
    USART_CR1(STM32_USART1) = USART_CR1_UE | USART_CR1_TE;
    USART_BRR(STM32_USART2) = 42000000u / 115200u;
    USART_CR3(STM32_USART2) = USART_CR3_RTSE;
    USART_CR1(STM32_USART2) = USART_CR1_UE | USART_CR1_RE | USART_CR1_RXNEIE;
    cm_nvic_enable(STM32_USART2_IRQ);
}

void stm32_console_write(const char *text)
{
    for (; *text; text++) {
        if (*text == '\n') {
            while (!(USART_SR(STM32_USART1) & USART_SR_TXE))
                ;
            USART_DR(STM32_USART1) = '\r';
        }
        while (!(USART_SR(STM32_USART1) & USART_SR_TXE))
            ;
        USART_DR(STM32_USART1) = (uint8_t)*text;
    }
}

void stm32_link_isr(void)
{
    uint32_t sr = USART_SR(STM32_USART2);
    if (!(sr & (USART_SR_RXNE | USART_SR_ORE)))
        return;
    if (rx_ring_full(&link.ring)) {
        /* Hold the byte (RTS holds the sender off) and mask the interrupt in
         * the NVIC: clearing RXNEIE would not lower the line in QEMU 7.2's
         * model, which then interrupts for ever. */
        cm_nvic_disable(STM32_USART2_IRQ);
        return;
    }
    /* Reading SR then DR clears ORE; the byte in DR came before the lost ones. */
    rx_ring_put(&link.ring, (uint8_t)USART_DR(STM32_USART2));
    if (sr & USART_SR_ORE)
        rx_ring_gap(&link.ring);
}

int board_link_read(uint8_t *byte)
{
    int got = rx_ring_get(&link.ring, byte);
    /* Nothing waits: take a byte the interrupt missed. QEMU 7.2's model can
     * lower its line with a byte waiting (a read of DR lets its next byte
     * in, then lowers the line); on the chip this finds nothing. */
    if (!got) {
        cm_irq_off();
        stm32_link_isr();
        cm_irq_on();
        /* Then wait a moment (about 3 us at 168 MHz, a 30th of a byte at
         * 115,200 baud) before the caller polls again. Every USART read
         * takes QEMU's big lock, which its I/O thread needs to deliver the
         * next byte: a caller spinning on an empty link at full speed kept
         * it out on a loaded host, and the link went idle for seconds
         * (qemu-test netduinoplus2, 3 of 6 runs, once the clock's 64-bit
         * division stopped slowing the loop down). The chip loses nothing:
         * the interrupt fills the ring meanwhile. */
        for (volatile uint32_t i = 0; i < 100u; i++)
            ;
    }
    /* Unmasking with the byte still waiting takes the interrupt at once. */
    if (!cm_nvic_enabled(STM32_USART2_IRQ) && rx_ring_room(&link.ring))
        cm_nvic_enable(STM32_USART2_IRQ);
    return got;
}

const rx_ring *board_link_ring(void)
{
    return &link.ring;
}
