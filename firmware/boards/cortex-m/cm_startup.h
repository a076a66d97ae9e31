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

#endif /* CM_STARTUP_H */
