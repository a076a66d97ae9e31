/*
 * fw_print.h - formatted status text for the firmware, without libc.
 *
 * The image links no C library, so this is the one formatter it has:
 * %s %c %d %u %x %X with an optional 0 flag and width, and the l / ll
 * length modifiers for 32- and 64-bit values. Output goes to
 * board_console_write in pieces of at most 128 bytes.
 */
#ifndef FW_PRINT_H
#define FW_PRINT_H

#include <stdarg.h>
#include <stddef.h>

void fw_print(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void fw_vprint(const char *fmt, va_list ap);

/* The same formatting into buf (always NUL-terminated when len > 0; cut to fit). */
void fw_format(char *buf, size_t len, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

#endif /* FW_PRINT_H */
