/*
 * board.c - the board_api for mps2-an386 under QEMU.
 *
 *  - Console and frame dumps: Arm semihosting (QEMU -semihosting-config
 *    enable=on,target=native); the command line comes from -append.
 *  - Stream ingress: CMSDK APB UART0 at its fastest rate (BAUDDIV 16:
 *    1.5625 Mbaud at 25 MHz; QEMU's model refuses less), received by its
 *    RX interrupt (IRQ 0) into a ring (hal/mcu/rx_ring.c), so bytes that
 *    arrive while a frame renders are kept. When the ring is full the
 *    interrupt leaves the byte in the UART and masks itself; QEMU's model
 *    then delivers nothing more until the main loop has made room and
 *    unmasked it. A receive overrun (STATE.RXOVERRUN: a byte overwrote an
 *    unread one) becomes a gap that the stream decoder is told about.
 *    `rxdrop=N` on the command line drops delivered byte N as an overrun
 *    would (the test of that path).
 *  - Clock: timer 1 of the CMSDK dual timer, free-running, 32 bits at the
 *    25 MHz system clock, extended to 64 bits by polling (it wraps every
 *    171 s; any board_time_us call in between keeps count).
 *  - Exit: SYS_EXIT_EXTENDED, so QEMU exits with the firmware's status.
 */
#include "board.h"

#include "board_api.h"
#include "cm_regs.h"
#include "cm_startup.h"
#include "fw_args.h"
#include "panel_semihost.h"
#include "rx_ring.h"
#include "semihost.h"

#define UART_DATA CM_REG(MPS2_UART0_BASE + 0x00u)
#define UART_STATE CM_REG(MPS2_UART0_BASE + 0x04u)
#define UART_CTRL CM_REG(MPS2_UART0_BASE + 0x08u)
#define UART_INTSTATUS CM_REG(MPS2_UART0_BASE + 0x0Cu) /* write 1 to clear */
#define UART_BAUDDIV CM_REG(MPS2_UART0_BASE + 0x10u)
#define UART_STATE_RXFULL (1u << 1)
#define UART_STATE_RXOVERRUN (1u << 3) /* write 1 to clear */
#define UART_CTRL_TXEN (1u << 0)
#define UART_CTRL_RXEN (1u << 1)
#define UART_CTRL_RXINTEN (1u << 3)
#define UART_INT_RX (1u << 1)

#define TIMER1_LOAD CM_REG(MPS2_DUALTIMER_BASE + 0x00u)
#define TIMER1_VALUE CM_REG(MPS2_DUALTIMER_BASE + 0x04u)
#define TIMER1_CONTROL CM_REG(MPS2_DUALTIMER_BASE + 0x08u)
#define TIMER_CTRL_32BIT (1u << 1)
#define TIMER_CTRL_ENABLE (1u << 7) /* TimerMode 0: free-running; prescale /1 */

static char cmdline[256];
static panel_semihost dump_panel;
static uint32_t timer_last;
static uint64_t timer_ticks;

/* What the UART receive interrupt shares with the main loop. */
static struct {
    rx_ring ring;
    uint8_t buf[BOARD_RX_RING];
} link;

void board_link_isr(void)
{
    UART_INTSTATUS = UART_INT_RX;
    if (!(UART_STATE & UART_STATE_RXFULL))
        return;
    if (rx_ring_full(&link.ring)) {
        UART_CTRL &= ~UART_CTRL_RXINTEN; /* hold the byte; board_link_read resumes */
        return;
    }
    if (UART_STATE & UART_STATE_RXOVERRUN) { /* the byte waiting overwrote an unread one */
        UART_STATE = UART_STATE_RXOVERRUN;
        rx_ring_gap(&link.ring);
    }
    rx_ring_put(&link.ring, (uint8_t)UART_DATA);
}

void board_init(void)
{
    cm_protect();
    TIMER1_CONTROL = 0;
    TIMER1_LOAD = 0xFFFFFFFFu;
    TIMER1_CONTROL = TIMER_CTRL_32BIT | TIMER_CTRL_ENABLE;
    timer_last = TIMER1_VALUE;
    timer_ticks = 0;
    if (sh_get_cmdline(cmdline, sizeof cmdline) != 0)
        cmdline[0] = 0;
    char dir[96];
    fw_arg(cmdline, "dump", dir, sizeof dir);
    panel_semihost_init(&dump_panel, dir, BOARD_PANEL_WIDTH, BOARD_PANEL_HEIGHT);
    uint32_t drop = 0;
    if (fw_arg(cmdline, "rxdrop", dir, sizeof dir))
        fw_parse_u32(dir, &drop);
    rx_ring_init(&link.ring, link.buf, sizeof link.buf, drop);
    UART_BAUDDIV = 16u;
    UART_CTRL = UART_CTRL_TXEN | UART_CTRL_RXEN | UART_CTRL_RXINTEN;
    cm_nvic_enable(MPS2_UART0_RX_IRQ);
}

void board_console_write(const char *text)
{
    sh_write0(text);
}

int board_link_read(uint8_t *byte)
{
    int got = rx_ring_get(&link.ring, byte);
    /* The ring has room again after a pause, or is empty: take the byte the
     * UART holds, if any (held while the ring was full, or an interrupt
     * missed), with the interrupt enabled again. */
    if (!got || (!(UART_CTRL & UART_CTRL_RXINTEN) && rx_ring_room(&link.ring))) {
        cm_irq_off();
        UART_CTRL |= UART_CTRL_RXINTEN;
        board_link_isr();
        cm_irq_on();
    }
    return got;
}

const rx_ring *board_link_ring(void)
{
    return &link.ring;
}

uint64_t board_time_us(void)
{
    uint32_t now = TIMER1_VALUE; /* counts down */
    timer_ticks += (uint32_t)(timer_last - now);
    timer_last = now;
    return cm_udiv64(timer_ticks, BOARD_SYSCLK_HZ / 1000000u, 0);
}

const char *board_cmdline(void)
{
    return cmdline;
}

/* Without a dump directory there is no glass, and so no panel: the frame's
 * CRC is then the display's running one (mcu_display.h). */
hal_display *board_panel(void)
{
    return dump_panel.dir[0] ? &dump_panel.d : NULL;
}

void board_exit(int status)
{
    sh_exit(status);
}
