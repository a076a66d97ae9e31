/*
 * rx_ring.h - the receive ring between a UART interrupt and the main loop.
 *
 * One writer (the board's receive interrupt) and one reader (the main
 * loop, between frames), no lock: each index is written by one side only.
 * The ring keeps bytes that arrive while a frame renders. When it is full
 * the interrupt stops taking bytes (the board masks its receive interrupt
 * and leaves the byte in the UART, which holds the sender off where there
 * is flow control, or overruns where there is not); the reader unmasks it
 * once there is room again (rx_ring_room).
 *
 * Loss is never silent. A receive overrun the UART flags, or a byte the
 * test hook drops on purpose, is a gap in the byte sequence: the reader
 * gets -1 at exactly that place, and the stream decoder is told
 * (cs_stream_gap). If a second gap comes before the first is read, the
 * bytes between them are dropped with them and reported as one more gap:
 * nothing is pieced together across a loss.
 *
 * Plain C with no hardware access, so its unit test runs on the host.
 */
#ifndef RX_RING_H
#define RX_RING_H

#include <stdbool.h>
#include <stdint.h>

typedef struct rx_ring {
    uint8_t *buf;
    uint32_t mask;                 /* size - 1; the size is a power of two */
    volatile uint32_t head;        /* bytes stored, ever (interrupt) */
    volatile uint32_t tail;        /* bytes taken or dropped, ever (reader) */
    volatile uint32_t gaps;        /* gaps flagged, ever (interrupt) */
    volatile uint32_t gaps_read;   /* gaps reported, ever (reader) */
    volatile uint32_t gap_from;    /* head at the first unreported gap (interrupt) */
    volatile uint32_t gap_to;      /* head at the last one (interrupt) */
    volatile uint32_t high;        /* most bytes ever waiting (interrupt) */
    uint32_t received;             /* bytes the UART delivered, ever (interrupt) */
    uint32_t drop_at;              /* test hook: drop delivered byte number N (1-based), 0 none */
} rx_ring;

/* `size` bytes at `buf`, a power of two; `drop_at` as in the struct. */
void rx_ring_init(rx_ring *r, uint8_t *buf, uint32_t size, uint32_t drop_at);

/* Interrupt side. */
static inline bool rx_ring_full(const rx_ring *r)
{
    return r->head - r->tail > r->mask;
}
void rx_ring_put(rx_ring *r, uint8_t byte); /* only when not full */
void rx_ring_gap(rx_ring *r);               /* bytes were lost here */

/* Reader side: 1 and *byte, 0 if nothing waits, -1 at a gap. */
int rx_ring_get(rx_ring *r, uint8_t *byte);

static inline bool rx_ring_room(const rx_ring *r)
{
    return !rx_ring_full(r);
}

#endif /* RX_RING_H */
