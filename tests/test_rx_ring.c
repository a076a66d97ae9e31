/*
 * test_rx_ring.c - the UART receive ring (hal/mcu/rx_ring.c), on the host.
 *
 * The truth is the sequence of bytes a simulated UART delivered, each
 * numbered. A random interleaving of interrupt steps (a byte stored, a byte
 * held back while the ring is full, an overrun that loses a byte) and
 * reader steps must give the reader every byte in order, and a gap (-1)
 * between two bytes exactly when some delivered byte between them was lost;
 * no byte twice, none invented, a gap never without a loss. Then the fixed
 * cases: the test hook that drops byte N, a full ring, the high-water mark.
 * Ends with `test_rx_ring: N passed, M failed`.
 */
#include <stdint.h>
#include <stdio.h>

#include "rx_ring.h"

#include "testlib.h"

static uint32_t rng = 2463534242u;
static uint32_t rnd(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    return rng;
}

#define DELIVER 20000u

static void test_random_interleavings(void)
{
    static uint32_t index_of[DELIVER + 1]; /* stored position -> delivered number */
    static uint8_t lost[DELIVER + 1];
    int bad = 0, gaps_seen = 0, losses = 0;
    char first[160] = "";
    for (int run = 0; run < 40; run++) {
        uint8_t buf[16];
        rx_ring r;
        uint32_t size = 1u << (1 + run % 4); /* 2, 4, 8, 16 */
        rx_ring_init(&r, buf, size, 0);
        uint32_t next = 0;    /* delivered bytes so far */
        int64_t last = -1;    /* number of the last byte the reader got */
        int gap_pending = 0;  /* a gap reported since `last` */
        for (uint32_t i = 0; i <= DELIVER; i++)
            lost[i] = 0;
        while (next < DELIVER || r.tail != r.head || r.gaps != r.gaps_read) {
            uint32_t dice = rnd() % 100;
            if (next < DELIVER && dice < 45) { /* the interrupt */
                if (dice < 2u + (uint32_t)run % 3u) {/* an overrun: this byte is lost */
                    lost[next++] = 1;
                    rx_ring_gap(&r);
                    losses++;
                } else if (!rx_ring_full(&r)) {
                    index_of[r.head] = next;
                    rx_ring_put(&r, (uint8_t)(next * 7u));
                    next++;
                } /* else held back in the UART until there is room */
                continue;
            }
            uint32_t pos = r.tail;
            uint8_t b;
            int got = rx_ring_get(&r, &b);
            if (got < 0) {
                gaps_seen++;
                gap_pending = 1;
            } else if (got > 0) {
                uint32_t n = index_of[pos];
                int missing = (int64_t)n > last + 1; /* lost, or dropped with a gap */
                if (b != (uint8_t)(n * 7u) || (int64_t)n <= last || missing != gap_pending) {
                    if (!bad++)
                        snprintf(first, sizeof first,
                                 "run %d: byte %u after %lld, value %u, gap reported %d",
                                 run, (unsigned)n, (long long)last, b, gap_pending);
                }
                last = n;
                gap_pending = 0;
            }
        }
        /* Losses at the very end leave a gap reported and nothing after it. */
        int tail_lost = 0;
        for (int64_t k = last + 1; k < (int64_t)DELIVER; k++)
            tail_lost |= lost[k];
        if (tail_lost && !gap_pending && !bad++)
            snprintf(first, sizeof first, "run %d: bytes lost at the end, no gap", run);
    }
    CHECK(bad == 0, "%d faults in 40 random runs of %u bytes; first: %s", bad, DELIVER, first);
    CHECK(losses > 0 && gaps_seen > 0 && gaps_seen <= losses,
          "%d gaps reported for %d losses (at least one, at most one per loss)", gaps_seen,
          losses);
}

static void test_drop_hook_and_full(void)
{
    uint8_t buf[8], b;
    rx_ring r;
    rx_ring_init(&r, buf, 8, 5);
    for (uint8_t v = 1; v <= 8; v++)
        rx_ring_put(&r, v);
    uint8_t got[12];
    int n = 0, gap_at = -1, g;
    while ((g = rx_ring_get(&r, &b)) != 0 && n < 12) {
        if (g < 0)
            gap_at = n;
        else
            got[n++] = b;
    }
    CHECK(n == 7 && gap_at == 4 && got[3] == 4 && got[4] == 6 && got[6] == 8,
          "drop_at=5: bytes 1-4, a gap, bytes 6-8 (got %d bytes, gap before byte %d)", n,
          gap_at);
    rx_ring_init(&r, buf, 8, 0);
    for (uint8_t v = 0; v < 8; v++)
        rx_ring_put(&r, v);
    CHECK(rx_ring_full(&r) && !rx_ring_room(&r) && r.high == 8, "8 bytes fill a ring of 8");
    CHECK(rx_ring_get(&r, &b) == 1 && b == 0 && rx_ring_room(&r), "taking one makes room");
    rx_ring_gap(&r);
    rx_ring_put(&r, 99);
    int bytes = 0;
    while ((g = rx_ring_get(&r, &b)) > 0)
        bytes++;
    CHECK(bytes == 7 && g == -1 && rx_ring_get(&r, &b) == 1 && b == 99 &&
              rx_ring_get(&r, &b) == 0,
          "an overrun after 8 stored bytes: 7 more, the gap, then the next byte");
}

int main(void)
{
    TL_RUN(test_random_interleavings);
    TL_RUN(test_drop_hook_and_full);
    return tl_summary("test_rx_ring");
}
