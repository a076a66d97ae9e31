/*
 * cm_startup.c - reset, vector table and fault reporting for Cortex-M4F
 * boards.
 *
 * Reset runs in assembly until C may run: it enables the FPU through CPACR
 * before any instruction could touch a float register (the compiler is
 * free to use VFP registers anywhere in C built with -mfloat-abi=hard),
 * paints the stack with a pattern so that its high-water mark can be
 * measured (cm_stack_used), then copies .data and zeroes .bss in C and
 * calls main. The layout comes from linker/sections.ld.
 *
 * Every fault vector leads to one handler. It first moves the stack
 * pointer back to the top of the stack, because the fault may be a stack
 * overflow into the MPU guard and the handler needs a stack of its own,
 * then reports the fault and its status registers on the console and
 * ends with a non-zero status (128 + exception number), so that a crash
 * under QEMU fails CI at once instead of hanging it. Unexpected interrupts
 * are reported the same way.
 */
#include <stdbool.h>
#include <stdint.h>

#include "board.h"
#include "board_api.h"
#include "cm_regs.h"
#include "cm_startup.h"
#include "fw_print.h"

#ifndef BOARD_IRQ_COUNT
#error "board.h must define BOARD_IRQ_COUNT (external interrupts in the vector table)"
#endif

#define STACK_PAINT 0xA5A5A5A5u

extern uint32_t __stack_guard[], __stack_bottom[], __stack_top[];
extern uint32_t __data_load[], __data_start[], __data_end[];
extern uint32_t __bss_start[], __bss_end[];

int main(void);
void reset_handler(void);
void cm_fault_entry(void);
void cm_startup_c(void) __attribute__((noreturn, used));
void cm_fault_report(const uint32_t *frame, uint32_t ipsr) __attribute__((noreturn, used));

__attribute__((naked, noreturn)) void reset_handler(void)
{
    __asm volatile(
        /* CPACR.CP10 = CP11 = full access: the FPU, before anything else */
        "movw r0, #0xED88\n"
        "movt r0, #0xE000\n"
        "ldr r1, [r0]\n"
        "orr r1, r1, #(0xF << 20)\n"
        "str r1, [r0]\n"
        "dsb\n"
        "isb\n"
        /* sp from the vector table may be absent under a debugger: set it */
        "movw r0, #:lower16:__stack_top\n"
        "movt r0, #:upper16:__stack_top\n"
        "msr msp, r0\n"
        /* paint [__stack_bottom, __stack_top): nothing is on it yet */
        "movw r1, #:lower16:__stack_bottom\n"
        "movt r1, #:upper16:__stack_bottom\n"
        "movw r2, #0xA5A5\n"
        "movt r2, #0xA5A5\n"
        "1: cmp r1, r0\n"
        "bhs 2f\n"
        "str r2, [r1], #4\n"
        "b 1b\n"
        "2: b cm_startup_c\n");
}

void cm_startup_c(void)
{
    for (uint32_t *src = __data_load, *dst = __data_start; dst < __data_end;)
        *dst++ = *src++;
    for (uint32_t *dst = __bss_start; dst < __bss_end;)
        *dst++ = 0;
    board_exit(main());
}

/* Bytes of stack ever used: the painted words not overwritten, from below. */
uint64_t cm_udiv64(uint64_t n, uint32_t d, uint32_t *rem)
{
    /* Long division in base 2^16: the running remainder stays below d, so
     * (r << 16) | digit fits in 32 bits. */
    uint64_t q = 0;
    uint32_t r = 0;
    for (int shift = 48; shift >= 0; shift -= 16) {
        uint32_t cur = (r << 16) | (uint32_t)((n >> shift) & 0xFFFFu);
        q = (q << 16) | (cur / d);
        r = cur % d;
    }
    if (rem)
        *rem = r;
    return q;
}

uint32_t cm_stack_used(void)
{
    const volatile uint32_t *p = __stack_bottom;
    while (p < __stack_top && *p == STACK_PAINT)
        p++;
    return (uint32_t)((uintptr_t)__stack_top - (uintptr_t)p);
}

uint32_t cm_stack_size(void)
{
    return (uint32_t)((uintptr_t)__stack_top - (uintptr_t)__stack_bottom);
}

uint32_t cm_stack_guard(void)
{
    return (uint32_t)(uintptr_t)__stack_guard;
}

__attribute__((naked, noreturn)) void cm_fault_entry(void)
{
    __asm volatile(
        "mrs r0, msp\n"      /* the exception frame, if stacking worked */
        "mrs r1, ipsr\n"
        "movw r2, #:lower16:__stack_top\n"
        "movt r2, #:upper16:__stack_top\n"
        "msr msp, r2\n"      /* a fresh stack: this may be an overflow */
        "b cm_fault_report\n");
}

static const char *exception_name(uint32_t n)
{
    switch (n) {
    case 2: return "NMI";
    case 3: return "HardFault";
    case 4: return "MemManage";
    case 5: return "BusFault";
    case 6: return "UsageFault";
    case 11: return "SVCall";
    case 12: return "DebugMonitor";
    case 14: return "PendSV";
    case 15: return "SysTick";
    default: return n >= 16 ? "IRQ" : "reserved";
    }
}

void cm_fault_report(const uint32_t *frame, uint32_t ipsr)
{
    /* Take the stacked pc and lr first: this handler's own stack starts at
     * the top again and printing may overwrite the frame. Only read them
     * if the frame lies inside the stack, above the guard: after an
     * overflow it does not. */
    bool framed = (uintptr_t)frame >= (uintptr_t)__stack_bottom &&
                  (uintptr_t)frame + 32u <= (uintptr_t)__stack_top;
    uint32_t pc = framed ? frame[6] : 0, lr = framed ? frame[5] : 0;
    uint32_t n = ipsr & 0x1FFu;
    fw_print("FAULT: %s (exception %u) cfsr=%08x hfsr=%08x mmfar=%08x bfar=%08x sp=%08x\n",
             exception_name(n), (unsigned)n, (unsigned)SCB_CFSR, (unsigned)SCB_HFSR,
             (unsigned)SCB_MMFAR, (unsigned)SCB_BFAR, (unsigned)(uintptr_t)frame);
    if (framed)
        fw_print("FAULT: pc=%08x lr=%08x\n", (unsigned)pc, (unsigned)lr);
    else
        fw_print("FAULT: stack pointer outside the stack (overflow into the guard at %08x)\n",
                 (unsigned)cm_stack_guard());
    board_exit(128 + (int)(n < 16 ? n : 16));
}

typedef void (*cm_vector)(void);

/* Initial sp, then the 15 system exceptions, then the board's interrupts.
 * A board's own handlers (BOARD_VECTORS in its board.h: its UART receive
 * interrupt, a clock tick) take their slots over from the fault entry. */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Woverride-init"
__attribute__((section(".vectors"), used)) static const cm_vector vectors[16 + BOARD_IRQ_COUNT] = {
    [0] = (cm_vector)(uintptr_t)__stack_top,
    [1] = reset_handler,
    [2] = cm_fault_entry,  /* NMI */
    [3] = cm_fault_entry,  /* HardFault */
    [4] = cm_fault_entry,  /* MemManage */
    [5] = cm_fault_entry,  /* BusFault */
    [6] = cm_fault_entry,  /* UsageFault */
    [11] = cm_fault_entry, /* SVCall: nothing issues SVC */
    [12] = cm_fault_entry, /* DebugMonitor */
    [14] = cm_fault_entry, /* PendSV */
    [15] = cm_fault_entry, /* SysTick, unless the board's clock uses it */
    [16 ... 16 + BOARD_IRQ_COUNT - 1] = cm_fault_entry,
#ifdef BOARD_VECTORS
    BOARD_VECTORS
#endif
};
#pragma GCC diagnostic pop

/* Routes MemManage, BusFault and UsageFault to their own vectors (instead
 * of HardFault), traps integer division by zero, and makes the 32 bytes
 * below the stack inaccessible with MPU region 0, so an overflow faults
 * before it can reach anything else. Returns 0 if the MPU is absent. */
int cm_protect(void)
{
    SCB_SHCSR |= SCB_SHCSR_FAULTS;
    SCB_CCR |= SCB_CCR_DIV_0_TRP;
    if (((MPU_TYPE >> 8) & 0xFFu) == 0)
        return 0;
    MPU_RNR = 0;
    MPU_RBAR = (uint32_t)(uintptr_t)__stack_guard;
    /* XN, AP = 000 (no access), SIZE = 4 (2^(4+1) = 32 bytes), ENABLE */
    MPU_RASR = (1u << 28) | (0u << 24) | (4u << 1) | 1u;
    MPU_CTRL = (1u << 2) | 1u; /* PRIVDEFENA: the default map elsewhere; ENABLE */
    cm_dsb();
    cm_isb();
    return 1;
}
