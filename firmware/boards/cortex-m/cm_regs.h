/*
 * cm_regs.h - the few ARMv7-M system registers the firmware touches.
 *
 * Written out from the ARMv7-M Architecture Reference Manual (B3.2 System
 * Control Space, B3.3 SysTick, B3.5 PMSAv7 MPU, C1.8 DWT) rather than taken
 * from CMSIS, which Debian does not package; only what is used is here.
 */
#ifndef CM_REGS_H
#define CM_REGS_H

#include <stdint.h>

#define CM_REG(addr) (*(volatile uint32_t *)(uintptr_t)(addr))

/* System control block */
#define SCB_VTOR CM_REG(0xE000ED08u)
#define SCB_AIRCR CM_REG(0xE000ED0Cu)
#define SCB_CCR CM_REG(0xE000ED14u)
#define SCB_SHCSR CM_REG(0xE000ED24u)
#define SCB_CFSR CM_REG(0xE000ED28u)
#define SCB_HFSR CM_REG(0xE000ED2Cu)
#define SCB_MMFAR CM_REG(0xE000ED34u)
#define SCB_BFAR CM_REG(0xE000ED38u)
#define SCB_CPACR CM_REG(0xE000ED88u)

#define SCB_AIRCR_RESET 0x05FA0004u       /* VECTKEY | SYSRESETREQ */
#define SCB_CCR_DIV_0_TRP (1u << 4)
#define SCB_SHCSR_FAULTS ((1u << 16) | (1u << 17) | (1u << 18)) /* MemManage, Bus, Usage */

/* SysTick */
#define SYST_CSR CM_REG(0xE000E010u)
#define SYST_RVR CM_REG(0xE000E014u)
#define SYST_CVR CM_REG(0xE000E018u)

/* NVIC: interrupt set-enable and clear-enable, one bit per external
 * interrupt (reading either gives the enabled state) */
#define NVIC_ISER(n) CM_REG(0xE000E100u + 4u * (n))
#define NVIC_ICER(n) CM_REG(0xE000E180u + 4u * (n))

/* PMSAv7 MPU */
#define MPU_TYPE CM_REG(0xE000ED90u)
#define MPU_CTRL CM_REG(0xE000ED94u)
#define MPU_RNR CM_REG(0xE000ED98u)
#define MPU_RBAR CM_REG(0xE000ED9Cu)
#define MPU_RASR CM_REG(0xE000EDA0u)

/* Debug: trace enable and the cycle counter */
#define DEMCR CM_REG(0xE000EDFCu)
#define DWT_CTRL CM_REG(0xE0001000u)
#define DWT_CYCCNT CM_REG(0xE0001004u)

static inline void cm_dsb(void) { __asm volatile("dsb" ::: "memory"); }
static inline void cm_isb(void) { __asm volatile("isb" ::: "memory"); }
static inline void cm_irq_off(void) { __asm volatile("cpsid i" ::: "memory"); }
static inline void cm_irq_on(void) { __asm volatile("cpsie i" ::: "memory"); }
static inline void cm_nvic_enable(unsigned irq) { NVIC_ISER(irq / 32u) = 1u << (irq % 32u); }
static inline void cm_nvic_disable(unsigned irq) { NVIC_ICER(irq / 32u) = 1u << (irq % 32u); }
static inline int cm_nvic_enabled(unsigned irq) { return (NVIC_ISER(irq / 32u) >> (irq % 32u)) & 1u; }

#endif /* CM_REGS_H */
