/*
 * drm_mmap.h - how the emulated DRM card's MAP_DUMB offsets name a dumb buffer.
 *
 * umockdev forwards ioctl, read and write of an emulated node but not mmap,
 * so the fake card (fake_drm.c) keeps each dumb buffer in a memfd and its
 * MAP_DUMB offset carries that memfd's number; drm_mmap.c, linked into the
 * test and preloaded into the celfw it starts, maps such offsets.
 */
#ifndef DRM_MMAP_H
#define DRM_MMAP_H

#include <stdint.h>

#define DRM_MMAP_MAGIC (1ull << 44)  /* far above any real file offset the tests use */
#define DRM_MMAP_SHIFT 28            /* page-aligned, and room for any fd number below */

static inline uint64_t drm_mmap_offset(int memfd)
{
    return DRM_MMAP_MAGIC | ((uint64_t)(unsigned)memfd << DRM_MMAP_SHIFT);
}

#endif /* DRM_MMAP_H */
