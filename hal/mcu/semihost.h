/*
 * semihost.h - Arm semihosting: host I/O for a target under a debugger or
 * an emulator.
 *
 * Calls follow the Arm "Semihosting for AArch32 and AArch64" specification
 * (v2): operation number in r0, a pointer to a parameter block in r1, then
 * BKPT 0xAB on M-profile; the result comes back in r0. QEMU implements it
 * with -semihosting-config enable=on,target=native.
 *
 * On real hardware without a debugger BKPT faults, so only boards that run
 * under QEMU (or always with a probe) use this.
 */
#ifndef SEMIHOST_H
#define SEMIHOST_H

#include <stddef.h>
#include <stdint.h>

/* Opens a host file; mode as fopen: 0 "r", 1 "rb", 4 "w", 5 "wb", 7 "w+b",
 * 8 "a". Returns a handle >= 0 or -1. */
int sh_open(const char *path, int mode);
int sh_close(int handle);
/* Writes all of buf; 0 on success. */
int sh_write(int handle, const void *buf, size_t len);
/* Reads all of len bytes into buf; 0 on success. */
int sh_read(int handle, void *buf, size_t len);
/* Moves to byte pos from the start of the file; 0 on success. */
int sh_seek(int handle, size_t pos);
/* Writes a NUL-terminated string to the debug console. */
void sh_write0(const char *text);
/* The command line the host passed (QEMU: -append); 0 on success. */
int sh_get_cmdline(char *buf, size_t len);
/* Ends the session with an exit status. On AArch32 plain SYS_EXIT can only
 * say success or failure; SYS_EXIT_EXTENDED (0x20) carries the status. */
void sh_exit(int status) __attribute__((noreturn));

#endif /* SEMIHOST_H */
