/*
 * lx_damage.h - which lines changed since the last frame, without a frame.
 *
 * A push display (a USB bridge, an SPI panel) keeps its own frame buffer, so
 * only changed lines need to travel. To know which changed without keeping a
 * copy of the frame, keep one 64-bit hash per line of what the display now
 * shows: O(height) memory. A rendered line travels when its hash differs;
 * its hash is committed only once the display has taken it, and a line whose
 * transfer failed is invalidated so it is sent again whatever comes next.
 */
#ifndef LX_DAMAGE_H
#define LX_DAMAGE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct lx_damage {
    int height;
    uint64_t *hash; /* 0 = unknown: the line must be sent */
} lx_damage;

/* Allocates the table; every line starts unknown. Returns false without memory. */
bool lx_damage_init(lx_damage *d, int height);
void lx_damage_free(lx_damage *d);
/* Marks lines [y0, y1) unknown (after a failed transfer or a reconnect). */
void lx_damage_invalidate(lx_damage *d, int y0, int y1);
/* Hash of a line's bytes; never 0. */
uint64_t lx_line_hash(const uint8_t *p, size_t n);
static inline bool lx_damage_changed(const lx_damage *d, int y, uint64_t h) { return d->hash[y] != h; }
static inline void lx_damage_commit(lx_damage *d, int y, uint64_t h) { d->hash[y] = h; }

#endif /* LX_DAMAGE_H */
