/*
 * board.c - the board_api for mps2-an386 under QEMU.
 *
 *  - Console and frame dumps: Arm semihosting (QEMU -semihosting-config
 *    enable=on,target=native); the command line comes from -append.
 *  - Stream ingress: CMSDK APB UART0, polled. QEMU's CMSDK UART holds one
 *    received byte and does not accept the next until it is read, so a
 *    polling reader loses nothing, whatever the host feeds it.
 *  - Clock: timer 1 of the CMSDK dual timer, free-running, 32 bits at the
 *    25 MHz system clock, extended to 64 bits by polling (it wraps every
 *    171 s; any board_time_us call in between keeps count). No interrupt
 *    is enabled anywhere, so execution, and the instruction count a QEMU
 *    plugin measures, do not depend on host timing.
 *  - Exit: SYS_EXIT_EXTENDED, so QEMU exits with the firmware's status.
 */
#include "board.h"

#include "board_api.h"
#include "cm_regs.h"
#include "cm_startup.h"
#include "fw_args.h"
#include "panel_semihost.h"
#include "semihost.h"

#define UART_DATA CM_REG(MPS2_UART0_BASE + 0x00u)
#define UART_STATE CM_REG(MPS2_UART0_BASE + 0x04u)
#define UART_CTRL CM_REG(MPS2_UART0_BASE + 0x08u)
#define UART_BAUDDIV CM_REG(MPS2_UART0_BASE + 0x10u)
#define UART_STATE_RXFULL (1u << 1)
#define UART_CTRL_TXEN (1u << 0)
#define UART_CTRL_RXEN (1u << 1)

#define TIMER1_LOAD CM_REG(MPS2_DUALTIMER_BASE + 0x00u)
#define TIMER1_VALUE CM_REG(MPS2_DUALTIMER_BASE + 0x04u)
#define TIMER1_CONTROL CM_REG(MPS2_DUALTIMER_BASE + 0x08u)
#define TIMER_CTRL_32BIT (1u << 1)
#define TIMER_CTRL_ENABLE (1u << 7) /* TimerMode 0: free-running; prescale /1 */

static char cmdline[256];
static panel_semihost dump_panel;
static mcu_panel panel = {"semihost-dump", BOARD_PANEL_WIDTH, BOARD_PANEL_HEIGHT,
                          &panel_semihost_api, &dump_panel};
static uint32_t timer_last;
static uint64_t timer_ticks;

void board_init(void)
{
    cm_protect();
    UART_BAUDDIV = BOARD_SYSCLK_HZ / 115200u;
    UART_CTRL = UART_CTRL_TXEN | UART_CTRL_RXEN;
    TIMER1_CONTROL = 0;
    TIMER1_LOAD = 0xFFFFFFFFu;
    TIMER1_CONTROL = TIMER_CTRL_32BIT | TIMER_CTRL_ENABLE;
    timer_last = TIMER1_VALUE;
    timer_ticks = 0;
    if (sh_get_cmdline(cmdline, sizeof cmdline) != 0)
        cmdline[0] = 0;
    char dir[96];
    fw_arg(cmdline, "dump", dir, sizeof dir);
    panel_semihost_init(&dump_panel, dir);
}

void board_console_write(const char *text)
{
    sh_write0(text);
}

int board_link_read(uint8_t *byte)
{
    if (!(UART_STATE & UART_STATE_RXFULL))
        return 0;
    *byte = (uint8_t)UART_DATA;
    return 1;
}

uint64_t board_time_us(void)
{
    uint32_t now = TIMER1_VALUE; /* counts down */
    timer_ticks += (uint32_t)(timer_last - now);
    timer_last = now;
    return timer_ticks / (BOARD_SYSCLK_HZ / 1000000u);
}

const char *board_cmdline(void)
{
    return cmdline;
}

const mcu_panel *board_panel(void)
{
    return &panel;
}

void board_exit(int status)
{
    sh_exit(status);
}
