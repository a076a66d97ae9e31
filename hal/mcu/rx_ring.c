/*
 * rx_ring.c - the receive ring between a UART interrupt and the main loop
 * (see rx_ring.h for the rules).
 */
#include "rx_ring.h"

void rx_ring_init(rx_ring *r, uint8_t *buf, uint32_t size, uint32_t drop_at)
{
    r->buf = buf;
    r->mask = size - 1u;
    r->head = r->tail = r->gaps = r->gaps_read = 0;
    r->gap_from = r->gap_to = r->high = 0;
    r->received = 0;
    r->drop_at = drop_at;
}

void rx_ring_gap(rx_ring *r)
{
    uint32_t head = r->head;
    if (r->gaps == r->gaps_read)
        r->gap_from = head;
    r->gap_to = head;
    r->gaps = r->gaps + 1u; /* last: the reader looks at gaps first */
}

void rx_ring_put(rx_ring *r, uint8_t byte)
{
    if (++r->received == r->drop_at) {
        rx_ring_gap(r); /* as an overrun loses it */
        return;
    }
    uint32_t head = r->head;
    r->buf[head & r->mask] = byte;
    r->head = head + 1u;
    if (head + 1u - r->tail > r->high)
        r->high = head + 1u - r->tail;
}

int rx_ring_get(rx_ring *r, uint8_t *byte)
{
    uint32_t tail = r->tail, gaps = r->gaps;
    /* At (or past, when a later gap widened it) the first unreported gap:
     * drop what lies up to the last one and report it. gap_to and gaps are
     * read until they agree, so the snapshot is consistent. */
    if (gaps != r->gaps_read && (int32_t)(tail - r->gap_from) >= 0) {
        uint32_t to;
        do {
            gaps = r->gaps;
            to = r->gap_to;
        } while (gaps != r->gaps);
        r->tail = to;
        r->gaps_read = gaps;
        return -1;
    }
    if (tail == r->head)
        return 0;
    *byte = r->buf[tail & r->mask];
    r->tail = tail + 1u;
    return 1;
}
