/*
 * clock.h - the monotonic clock interface.
 *
 * The renderer itself is timeless (a frame is rendered at the time it is
 * given), but the programs around it need a clock: the simulator to measure
 * render time, the firmware to pick each frame's time and to pace lines.
 * Exactly one backend is linked in (hal/sim/clock_host.c on the host, a timer
 * driver on a board), TinyUSB-port style, so the call costs no indirection.
 */
#ifndef HAL_CLOCK_H
#define HAL_CLOCK_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/*
 * Nanoseconds since an arbitrary fixed origin (e.g. boot). Never goes
 * backwards and is not affected by wall-clock changes; only differences are
 * meaningful.
 */
uint64_t hal_clock_now_ns(void);

#ifdef __cplusplus
}
#endif

#endif /* HAL_CLOCK_H */
