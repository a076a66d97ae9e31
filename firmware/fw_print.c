/*
 * fw_print.c - a minimal printf for the firmware console (see fw_print.h).
 *
 * Text is gathered in a small buffer on the stack and flushed when full and
 * at the end, so one call costs a handful of semihosting or UART writes at
 * most and never allocates.
 */
#include "fw_print.h"

#include <stdbool.h>
#include <stdint.h>

#include "board_api.h"
#include "cm_startup.h"

typedef struct out {
    char buf[129];
    size_t n;
    char *dst;     /* fw_format: the caller's buffer instead of the console */
    size_t cap, dn;
} out;

static void flush(out *o)
{
    if (o->n) {
        o->buf[o->n] = 0;
        board_console_write(o->buf);
        o->n = 0;
    }
}

static void put(out *o, char c)
{
    if (o->dst) {
        if (o->dn + 1 < o->cap)
            o->dst[o->dn++] = c;
        return;
    }
    if (o->n == sizeof o->buf - 1)
        flush(o);
    o->buf[o->n++] = c;
}

static void put_number(out *o, uint64_t v, unsigned base, bool upper, bool negative, int width,
                       char pad)
{
    const char *digits = upper ? "0123456789ABCDEF" : "0123456789abcdef";
    char tmp[24];
    int n = 0;
    do {
        uint32_t digit;
        v = cm_udiv64(v, base, &digit);
        tmp[n++] = digits[digit];
    } while (v);
    if (negative)
        width--;
    if (negative && pad == '0')
        put(o, '-');
    for (int i = n; i < width; i++)
        put(o, pad);
    if (negative && pad != '0')
        put(o, '-');
    while (n > 0)
        put(o, tmp[--n]);
}

static void format(out *o, const char *fmt, va_list ap)
{
    for (const char *p = fmt; *p; p++) {
        if (*p != '%') {
            put(o, *p);
            continue;
        }
        p++;
        char pad = ' ';
        int width = 0, longs = 0;
        if (*p == '0') {
            pad = '0';
            p++;
        }
        while (*p >= '0' && *p <= '9')
            width = width * 10 + (*p++ - '0');
        while (*p == 'l') {
            longs++;
            p++;
        }
        switch (*p) {
        case 's': {
            const char *s = va_arg(ap, const char *);
            int len = 0;
            while (s[len])
                len++;
            for (int i = len; i < width; i++)
                put(o, ' ');
            while (*s)
                put(o, *s++);
            break;
        }
        case 'c':
            put(o, (char)va_arg(ap, int));
            break;
        case 'd': {
            int64_t v = longs >= 2 ? va_arg(ap, long long)
                                   : longs ? va_arg(ap, long) : va_arg(ap, int);
            uint64_t mag = v < 0 ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
            put_number(o, mag, 10, false, v < 0, width, pad);
            break;
        }
        case 'u':
        case 'x':
        case 'X': {
            uint64_t v = longs >= 2 ? va_arg(ap, unsigned long long)
                                    : longs ? va_arg(ap, unsigned long) : va_arg(ap, unsigned);
            put_number(o, v, *p == 'u' ? 10u : 16u, *p == 'X', false, width, pad);
            break;
        }
        case '%':
            put(o, '%');
            break;
        case 0:
            p--; /* a lone % at the end */
            break;
        default:
            put(o, '%');
            put(o, *p);
            break;
        }
    }
}

void fw_vprint(const char *fmt, va_list ap)
{
    out o;
    o.n = 0;
    o.dst = 0;
    format(&o, fmt, ap);
    flush(&o);
}

void fw_format(char *buf, size_t len, const char *fmt, ...)
{
    out o;
    o.n = 0;
    o.dst = buf;
    o.cap = len;
    o.dn = 0;
    va_list ap;
    va_start(ap, fmt);
    format(&o, fmt, ap);
    va_end(ap);
    if (len)
        buf[o.dn] = 0;
}

void fw_print(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fw_vprint(fmt, ap);
    va_end(ap);
}
