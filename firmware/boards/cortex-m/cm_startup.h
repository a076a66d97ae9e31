/*
 * cm_startup.h - what the Cortex-M startup code offers the rest of the
 * firmware (see cm_startup.c).
 */
#ifndef CM_STARTUP_H
#define CM_STARTUP_H

#include <stdint.h>

/* Stack use: the measured high-water mark, the size, the guard address. */
uint32_t cm_stack_used(void);
uint32_t cm_stack_size(void);
uint32_t cm_stack_guard(void);

/* Fault routing, division-by-zero trap and the MPU stack guard; returns
 * 1 if the guard is armed (the core has an MPU). */
int cm_protect(void);

/*
 * n / d for d in 1..65535, the remainder in *rem (may be NULL): the clock's
 * cycles to microseconds and the printing of 64-bit numbers, in 32-bit
 * divisions (UDIV) 16 bits at a time, instead of libgcc's 700-byte
 * __udivmoddi4.
 */
uint64_t cm_udiv64(uint64_t n, uint32_t d, uint32_t *rem);

#endif /* CM_STARTUP_H */
