/*
 * lx_display.c - what every Linux display backend shares (lx_display.h):
 * the one way a backend's messages reach the caller's log, prefixed with
 * the backend's name, so that each backend does not format its own.
 */
#include <stdarg.h>
#include <stdio.h>

#include "lx_display.h"

void lx_display_vsay(const lx_display *d, const char *who, const char *fmt, va_list ap)
{
    if (!d->log)
        return;
    char msg[400];
    vsnprintf(msg, sizeof msg, fmt, ap);
    d->log(d->log_user, "%s: %s", who, msg);
}
