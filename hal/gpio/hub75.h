/*
 * hub75.h - HUB75 RGB LED-matrix panels driven from Linux GPIO lines.
 *
 * A HUB75 panel of R rows shows two rows at once, y and y + R/2 (a "row
 * pair", 1/(R/2) scan): six data lines R1 G1 B1 R2 G2 B2 feed shift registers
 * one column per CLK rising edge; LAT copies the shift registers to the
 * column drivers; the address lines A..E select the row pair; OE (active low)
 * lights it. Chained panels are one longer shift register. The panel keeps no
 * image, so the driver rescans it continuously, and colour depth comes from
 * binary-code modulation: bit plane b is latched and lit for lsb_ns * 2^b.
 *
 * celfw renders the lines of each row pair as the panel scans them and keeps
 * only that row pair's bit planes: width x planes bytes, never a frame.
 *
 * Pin numbers are line offsets on the GPIO chip (BCM numbers on a Raspberry
 * Pi's gpiochip0). The Adafruit RGB Matrix HAT layout is a preset.
 */
#ifndef HUB75_H
#define HUB75_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "display.h"

/* Wire functions, also the order of hub75_pins' fields. */
enum {
    HUB75_R1, HUB75_G1, HUB75_B1, HUB75_R2, HUB75_G2, HUB75_B2,
    HUB75_A, HUB75_B, HUB75_C, HUB75_D, HUB75_E,
    HUB75_CLK, HUB75_LAT, HUB75_OE,
    HUB75_NFUNC
};

/* Line offset of each function; -1 = not wired (only E may be unwired). */
typedef struct hub75_pins {
    int pin[HUB75_NFUNC];
} hub75_pins;

#define HUB75_MAX_PLANES 12

typedef struct hub75_config {
    int panel_w, panel_h;  /* one panel: e.g. 64x32 (1/16 scan) or 64x64 (1/32 scan) */
    int chain;             /* panels in the chain, side by side */
    int planes;            /* bit planes of colour depth, 1..HUB75_MAX_PLANES */
    uint32_t lsb_ns;       /* OE time of the least significant plane */
    hub75_pins pins;
    char chip[128];        /* GPIO chip device, e.g. /dev/gpiochip0 */
} hub75_config;

/* Name of function f ("r1", "oe", ...). */
const char *hub75_func_name(int f);
/* Function index for a name, or -1. */
int hub75_func_by_name(const char *name);

/* Fills pins from a preset: "adafruit-hat", "adafruit-hat-pwm", "regular".
 * Returns false for an unknown name. */
bool hub75_pins_preset(const char *name, hub75_pins *pins);
/* Names of the presets, space separated, for messages. */
const char *hub75_presets(void);

/* Defaults: 64x32, chain 1, 8 planes, 200 ns LSB, Adafruit HAT pins, /dev/gpiochip0. */
void hub75_config_default(hub75_config *c);

/* Checks a configuration; on failure writes a message naming the setting. */
hal_status hub75_config_check(const hub75_config *c, char *err, size_t errlen);

/* Row pairs of the panel (panel_h / 2) and address lines they need. */
int hub75_scan(const hub75_config *c);
int hub75_addr_bits(const hub75_config *c);

/*
 * Opens the chip, requests every wired line as an output in one bulk request
 * (OE starts inactive: panel dark) and returns the display. The clock times
 * the bit planes; pass &hal_clock_monotonic on a board.
 */
hal_status hub75_open(hal_display **out, const hub75_config *c, const hal_clock *clock,
                     char *err, size_t errlen);

/*
 * Measures bulk write throughput on an open HUB75 display: `writes` bulk
 * writes that toggle CLK. Returns writes per second (0 on failure).
 */
double hub75_measure_writes(hal_display *d, int writes);

/*
 * Estimated refresh rate (full panel scans per second) of a configuration for
 * a given time per bulk write, ignoring render time: each plane of each row
 * pair costs (2*width + 5) writes plus its lit time.
 */
double hub75_refresh_estimate(const hub75_config *c, double write_ns);

/* Bulk writes per full scan (frame). */
uint64_t hub75_writes_per_frame(const hub75_config *c);

#endif /* HUB75_H */
