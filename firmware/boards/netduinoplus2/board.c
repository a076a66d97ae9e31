/*
 * board.c - the board_api for QEMU's netduinoplus2 (STM32F405): the STM32
 * drivers for time (SysTick) and the stream link (USART2 by interrupt into
 * a ring), semihosting for the console, the command line, the frame dump
 * panel and the exit status, as on mps2-an386. `rxdrop=N` drops delivered
 * byte N as an overrun would (the test of that path).
 */
#include "board.h"

#include "board_api.h"
#include "cm_startup.h"
#include "fw_args.h"
#include "panel_semihost.h"
#include "semihost.h"

static char cmdline[256];
static panel_semihost dump_panel;

void board_init(void)
{
    stm32_tick_init();
    cm_protect();
    if (sh_get_cmdline(cmdline, sizeof cmdline) != 0)
        cmdline[0] = 0;
    char arg[96];
    fw_arg(cmdline, "dump", arg, sizeof arg);
    panel_semihost_init(&dump_panel, arg, BOARD_PANEL_WIDTH, BOARD_PANEL_HEIGHT);
    uint32_t drop = 0;
    if (fw_arg(cmdline, "rxdrop", arg, sizeof arg))
        fw_parse_u32(arg, &drop);
    stm32_usart_init(drop);
}

void board_console_write(const char *text)
{
    sh_write0(text);
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
