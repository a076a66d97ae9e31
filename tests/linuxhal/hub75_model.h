/*
 * hub75_model.h - a HUB75 panel chain, simulated from its input wires.
 *
 * The model is the test's independent truth for the GPIO backend: it knows
 * nothing of the driver, only what a panel does with the wires. The column
 * drivers shift the six data bits on each CLK rising edge (the bit clocked
 * first ends at the far end of the chain); while LAT is high the output
 * latches follow the shift register; the address lines select the row pair;
 * while OE is low the row pair shows the latched bits. Fed the recorded
 * wire changes with their times, it integrates how long each LED was lit and
 * how long each row pair was lit at all, and turns that into an image of
 * `planes`-bit levels: level = on_time * (2^planes - 1) / row_lit_time.
 *
 * It also counts what a real panel would punish: data changing in the same
 * write as a CLK rising edge (no setup time), clocking while LAT is high,
 * changing the address while lit (ghosting), and it records every lit
 * interval so tests can check the bit-plane timing itself.
 */
#ifndef HUB75_MODEL_H
#define HUB75_MODEL_H

#include <stdint.h>

#include "fake_gpiochip.h"
#include "hub75.h"

typedef struct hub75_pulse {
    int row_pair;
    uint64_t t_on, duration;
} hub75_pulse;

typedef struct hub75_model {
    int width, height, scan, abits;
    int pin[HUB75_NFUNC];
    /* state */
    uint8_t *shift, *latch; /* six bits per column */
    int addr;
    int lit;
    uint64_t t_last, wires_last;
    uint64_t *on_time;      /* width * height * 3, ns */
    uint64_t *row_lit;      /* scan, ns */
    /* diagnostics */
    uint64_t clock_edges, latches, setup_violations, clock_while_latched, ghost_changes;
    hub75_pulse *pulses;
    size_t npulses, cappulses;
} hub75_model;

void hub75_model_init(hub75_model *m, const hub75_config *c, uint64_t initial_wires);
void hub75_model_free(hub75_model *m);
/* Feeds one recorded write. */
void hub75_model_feed(hub75_model *m, const fake_gpio_event *ev);
/* Writes the decoded levels (width * height * 3) for `planes` bits.
 * Returns the number of row pairs that were never lit (those pixels are 0). */
int hub75_model_image(const hub75_model *m, int planes, uint16_t *levels);

#endif /* HUB75_MODEL_H */
