/*
 * drm_mmap.c - mmap() that maps the emulated DRM card's dumb buffers.
 *
 * It replaces libc's mmap in the program it is linked into (test_drm) or
 * preloaded into (LD_PRELOAD, the celfw that test_drm starts). An offset
 * drm_mmap_offset(memfd) is mapped from that memfd of the process that runs
 * the fake card, reopened through /proc/$FAKE_DRM_PID/fd (or /proc/self/fd
 * in that process itself), as the kernel maps a GEM object for its fake
 * offset; a length beyond the buffer, or a buffer gone, is EINVAL as there.
 * Every other mapping goes to the kernel unchanged.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "drm_mmap.h"

static void *sys_mmap(void *addr, size_t len, int prot, int flags, int fd, off_t off)
{
    return (void *)syscall(SYS_mmap, addr, len, prot, flags, fd, off);
}

void *mmap(void *addr, size_t len, int prot, int flags, int fd, off_t off)
{
    uint64_t o = (uint64_t)off;
    if (fd < 0 || (o & ~((DRM_MMAP_MAGIC << 1) - 1)) || !(o & DRM_MMAP_MAGIC) ||
        (o & ((1ull << DRM_MMAP_SHIFT) - 1)))
        return sys_mmap(addr, len, prot, flags, fd, off);
    const char *pid = getenv("FAKE_DRM_PID");
    char path[64];
    snprintf(path, sizeof path, "/proc/%s/fd/%u", pid ? pid : "self",
             (unsigned)((o & (DRM_MMAP_MAGIC - 1)) >> DRM_MMAP_SHIFT));
    int bo = open(path, O_RDWR | O_CLOEXEC);
    struct stat st;
    if (bo < 0 || fstat(bo, &st) != 0 || (uint64_t)st.st_size < len) {
        if (bo >= 0)
            close(bo);
        errno = EINVAL;
        return MAP_FAILED;
    }
    void *p = sys_mmap(addr, len, prot, flags, bo, 0);
    close(bo);
    return p;
}
