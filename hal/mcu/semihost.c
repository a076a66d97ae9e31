/*
 * semihost.c - the semihosting calls the firmware uses (see semihost.h).
 */
#include "semihost.h"

#include "cm_regs.h"

#define SYS_OPEN 0x01
#define SYS_CLOSE 0x02
#define SYS_WRITE0 0x04
#define SYS_WRITE 0x05
#define SYS_READ 0x06
#define SYS_SEEK 0x0A
#define SYS_GET_CMDLINE 0x15
#define SYS_EXIT 0x18
#define SYS_EXIT_EXTENDED 0x20
#define ADP_Stopped_ApplicationExit 0x20026

static uintptr_t sh_call(uintptr_t op, const void *arg)
{
    register uintptr_t r0 __asm("r0") = op;
    register const void *r1 __asm("r1") = arg;
    /* The host reads the block and buffers as a debugger does, and QEMU
     * translates such an access through the MPU a whole 1 KiB page at a
     * time: the 32-byte stack guard (cm_startup.c) at the bottom of RAM
     * would make every byte of its page unreadable, so text printed from
     * deep in the stack was silently lost. A probe's access port bypasses
     * the MPU; so does this, around the one instruction (an interrupt
     * taken in the few instructions between runs without the guard). */
    uint32_t mpu = MPU_CTRL;
    MPU_CTRL = mpu & ~1u;
    __asm volatile("dsb\n\tisb" ::: "memory");
    /* "memory": the host reads and writes the parameter block and buffers. */
    __asm volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    MPU_CTRL = mpu;
    __asm volatile("dsb\n\tisb" ::: "memory");
    return r0;
}

static size_t length(const char *s)
{
    size_t n = 0;
    while (s[n])
        n++;
    return n;
}

int sh_open(const char *path, int mode)
{
    uintptr_t block[3] = {(uintptr_t)path, (uintptr_t)mode, length(path)};
    return (int)sh_call(SYS_OPEN, block);
}

int sh_close(int handle)
{
    uintptr_t block[1] = {(uintptr_t)handle};
    return (int)sh_call(SYS_CLOSE, block);
}

int sh_write(int handle, const void *buf, size_t len)
{
    uintptr_t block[3] = {(uintptr_t)handle, (uintptr_t)buf, len};
    return sh_call(SYS_WRITE, block) == 0 ? 0 : -1;
}

int sh_read(int handle, void *buf, size_t len)
{
    uintptr_t block[3] = {(uintptr_t)handle, (uintptr_t)buf, len};
    return sh_call(SYS_READ, block) == 0 ? 0 : -1; /* the host returns the bytes not read */
}

int sh_seek(int handle, size_t pos)
{
    uintptr_t block[2] = {(uintptr_t)handle, pos};
    return sh_call(SYS_SEEK, block) == 0 ? 0 : -1;
}

void sh_write0(const char *text)
{
    sh_call(SYS_WRITE0, text);
}

int sh_get_cmdline(char *buf, size_t len)
{
    uintptr_t block[2] = {(uintptr_t)buf, len};
    if (len == 0)
        return -1;
    buf[0] = 0;
    if (sh_call(SYS_GET_CMDLINE, block) != 0)
        return -1;
    buf[block[1] < len ? block[1] : len - 1] = 0;
    return 0;
}

void sh_exit(int status)
{
    uintptr_t block[2] = {ADP_Stopped_ApplicationExit, (uintptr_t)status};
    sh_call(SYS_EXIT_EXTENDED, block);
    /* A host without the extension: at least say success or failure. */
    sh_call(SYS_EXIT, (const void *)(uintptr_t)(status == 0 ? ADP_Stopped_ApplicationExit
                                                            : 0x20023 /* RunTimeErrorUnknown */));
    for (;;)
        __asm volatile("wfi");
}
