/*
 * celfw_notify.h - celfw's side of the service manager's notify protocol.
 *
 * Under systemd (Type=notify, WatchdogSec=) celfw says READY=1 once its
 * display, scene and input are up, and pings WATCHDOG=1 from its frame loop,
 * so a renderer that hangs (a stuck device, a loop that never returns) stops
 * the pings and is killed and restarted by the manager. Outside a service
 * (no NOTIFY_SOCKET) every call is a no-op.
 */
#ifndef CELFW_NOTIFY_H
#define CELFW_NOTIFY_H

#include <stdint.h>

typedef struct celfw_notify {
    uint64_t interval_ns; /* between pings; 0: no watchdog asked for */
    uint64_t last_ns;     /* when the last ping went out */
} celfw_notify;

/* Reads the watchdog period the manager asked for (WATCHDOG_USEC, for this
 * process only) and says READY=1 with a one-line STATUS= made from fmt. */
void celfw_notify_ready(celfw_notify *n, uint64_t now_ns, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Called once per loop iteration: pings WATCHDOG=1 when a third of the
 * period has passed since the last ping. */
void celfw_notify_alive(celfw_notify *n, uint64_t now_ns);

/* Says STOPPING=1, so the manager knows the exit that follows is intended. */
void celfw_notify_stopping(void);

#endif /* CELFW_NOTIFY_H */
