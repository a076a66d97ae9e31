/*
 * celfw_notify.c - READY, WATCHDOG and STOPPING through libsystemd's sd_notify.
 *
 * libsystemd speaks the protocol (the socket address forms, credentials,
 * WATCHDOG_PID matching); this file only decides when to speak. Pings go
 * out at a third of the period rather than every frame: at 60 fps a
 * datagram per frame is wasted work, and a third leaves two chances before
 * the manager gives up. A ping is sent from the loop itself, never from a
 * timer or thread, so it proves that frames still come round.
 */
#include "celfw_notify.h"

#include <stdarg.h>
#include <stdio.h>

#include <systemd/sd-daemon.h>

void celfw_notify_ready(celfw_notify *n, uint64_t now_ns, const char *fmt, ...)
{
    char status[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(status, sizeof status, fmt, ap);
    va_end(ap);
    uint64_t usec = 0;
    n->interval_ns = 0;
    /* > 0 only when WATCHDOG_USEC is set and WATCHDOG_PID (if set) is us */
    if (sd_watchdog_enabled(0, &usec) > 0 && usec > 0)
        n->interval_ns = usec * 1000u / 3u;
    n->last_ns = now_ns;
    sd_notifyf(0, "READY=1\nSTATUS=%s", status);
}

void celfw_notify_alive(celfw_notify *n, uint64_t now_ns)
{
    if (n->interval_ns == 0 || now_ns - n->last_ns < n->interval_ns)
        return;
    n->last_ns = now_ns;
    sd_notify(0, "WATCHDOG=1");
}

void celfw_notify_stopping(void)
{
    sd_notify(0, "STOPPING=1");
}
