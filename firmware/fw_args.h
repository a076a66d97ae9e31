/*
 * fw_args.h - key=value arguments from the host's command line.
 *
 * Under QEMU the firmware gets a command line through semihosting (the
 * -append text, after the image name). Words of the form key=value are
 * arguments; anything else is ignored.
 */
#ifndef FW_ARGS_H
#define FW_ARGS_H

#include <stddef.h>
#include <stdint.h>

/* Copies the value of `key=` into out (NUL-terminated, truncated to len)
 * and returns 1, or leaves out empty and returns 0 if the key is absent. */
int fw_arg(const char *cmdline, const char *key, char *out, size_t len);

/* Parses a decimal number; returns 1 if all of s was one. */
int fw_parse_u32(const char *s, uint32_t *value);

#endif /* FW_ARGS_H */
