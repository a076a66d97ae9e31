/*
 * lx_damage.c - per-line hashes for damage tracking.
 *
 * The hash works a 64-bit word at a time (multiply, xor-shift), then mixes in
 * the length and finishes with the murmur3 avalanche. A collision would leave
 * one stale line on the glass until it changes again; with 64 bits and a few
 * thousand lines per frame that is not a practical concern, and the hash
 * costs well under a microsecond per line at panel widths.
 */
#include <stdlib.h>
#include <string.h>

#include "lx_damage.h"

bool lx_damage_init(lx_damage *d, int height)
{
    d->height = height;
    d->hash = calloc((size_t)height, sizeof *d->hash);
    return d->hash != NULL;
}

void lx_damage_free(lx_damage *d)
{
    free(d->hash);
    d->hash = NULL;
}

void lx_damage_invalidate(lx_damage *d, int y0, int y1)
{
    if (y0 < 0)
        y0 = 0;
    if (y1 > d->height)
        y1 = d->height;
    for (int y = y0; y < y1; y++)
        d->hash[y] = 0;
}

static uint64_t fmix64(uint64_t k)
{
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdull;
    k ^= k >> 33;
    k *= 0xc4ceb9fe1a85ec53ull;
    k ^= k >> 33;
    return k;
}

uint64_t lx_line_hash(const uint8_t *p, size_t n)
{
    uint64_t h = 0x9e3779b97f4a7c15ull;
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
        uint64_t w;
        memcpy(&w, p + i, 8);
        h = (h ^ (w * 0x87c37b91114253d5ull)) * 0x4cf5ad432745937full;
        h ^= h >> 29;
    }
    uint64_t tail = 0;
    for (size_t k = 0; i < n; i++, k++)
        tail |= (uint64_t)p[i] << (8 * k);
    h = (h ^ (tail * 0x87c37b91114253d5ull)) * 0x4cf5ad432745937full;
    h = fmix64(h ^ (uint64_t)n);
    return h ? h : 1;
}
