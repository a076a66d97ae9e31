/*
 * fake_gpiochip.h - an emulated GPIO character device for umockdev tests.
 *
 * The real libgpiod runs unchanged against it: the testbed gets
 * /dev/gpiochipN (with the sysfs "dev" attribute libgpiod checks) and an
 * ioctl handler that answers the GPIO v1 uAPI as the kernel's gpiolib-cdev
 * does: chip info, line info, line handles (validated flags, EBUSY for lines
 * in use, default values, active-low) and handle get/set values, where the
 * values address the handle's lines in request order. A line handle's fd is
 * a second emulated node opened by the handler itself, so the handle's
 * ioctls come back to this emulation; closing it releases the lines.
 *
 * Every SET_LINE_VALUES is recorded with the physical level of all wires and
 * a time from a virtual clock shared with the driver under test; each write
 * costs write_cost_ns of that clock.
 */
#ifndef FAKE_GPIOCHIP_H
#define FAKE_GPIOCHIP_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <umockdev.h>

typedef struct fake_gpio_event {
    uint64_t t_ns;  /* virtual time the write took effect */
    uint64_t wires; /* physical level of every line after it, bit = offset */
} fake_gpio_event;

enum { FAKE_GPIO_CHIPINFO, FAKE_GPIO_LINEINFO, FAKE_GPIO_LINEHANDLE, FAKE_GPIO_SET, FAKE_GPIO_GET,
       FAKE_GPIO_OTHER, FAKE_GPIO_NCOUNT };

typedef struct fake_gpiochip fake_gpiochip;

/* Adds /dev/gpiochip<index> with nlines (<= 64) lines to the testbed. */
fake_gpiochip *fake_gpiochip_add(UMockdevTestbed *tb, int index, unsigned nlines, const char *label,
                                 _Atomic uint64_t *vclock, uint64_t write_cost_ns);
void fake_gpiochip_free(fake_gpiochip *c);

/* The recorded writes. Only call while the driver is idle. */
size_t fake_gpiochip_trace(fake_gpiochip *c, const fake_gpio_event **events);
void fake_gpiochip_clear_trace(fake_gpiochip *c);

uint64_t fake_gpiochip_wires(fake_gpiochip *c);
/* true if the line is requested; copies the consumer label if asked. */
bool fake_gpiochip_requested(fake_gpiochip *c, unsigned line, char *consumer, size_t len);
/* Marks a line as held by another user (as a kernel driver would). */
void fake_gpiochip_hold(fake_gpiochip *c, unsigned line, const char *consumer);
unsigned fake_gpiochip_count(fake_gpiochip *c, int kind);
/* The next n line writes fail with errno err (a GPIO expander on a bus that errs: EIO). */
void fake_gpiochip_fail_sets(fake_gpiochip *c, unsigned n, int err);
/* Open line handles. */
unsigned fake_gpiochip_handles(fake_gpiochip *c);

#endif /* FAKE_GPIOCHIP_H */
