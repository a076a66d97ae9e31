/*
 * hub75_config.c - HUB75 pin presets, defaults, validation and timing estimates.
 *
 * The presets are the wirings of common Raspberry Pi adapter boards, in BCM
 * line numbers, as documented by the rpi-rgb-led-matrix project (its
 * "adafruit-hat", "adafruit-hat-pwm" and "regular" mappings). Validation
 * names the setting that is wrong, because a wrong pin map on a board shows
 * up only as a dark or scrambled panel.
 */
#include <stdio.h>
#include <string.h>

#include "hub75.h"

static const char *const func_names[HUB75_NFUNC] = {
    "r1", "g1", "b1", "r2", "g2", "b2", "a", "b", "c", "d", "e", "clk", "lat", "oe"};

const char *hub75_func_name(int f)
{
    return (f >= 0 && f < HUB75_NFUNC) ? func_names[f] : "?";
}

int hub75_func_by_name(const char *name)
{
    for (int f = 0; f < HUB75_NFUNC; f++)
        if (strcmp(name, func_names[f]) == 0)
            return f;
    return -1;
}

typedef struct preset {
    const char *name;
    /* r1 g1 b1 r2 g2 b2 a b c d e clk lat oe */
    int pin[HUB75_NFUNC];
} preset;

static const preset presets[] = {
    /* Adafruit RGB Matrix HAT/Bonnet; E (for 1/32 scan) needs a jumper to 24. */
    {"adafruit-hat", {5, 13, 6, 12, 16, 23, 22, 26, 27, 20, 24, 17, 21, 4}},
    /* The same HAT with the OE-to-GPIO18 modification for hardware PWM. */
    {"adafruit-hat-pwm", {5, 13, 6, 12, 16, 23, 22, 26, 27, 20, 24, 17, 21, 18}},
    /* The "regular" passive adapter wiring. */
    {"regular", {11, 27, 7, 8, 9, 10, 22, 23, 24, 25, 15, 17, 4, 18}},
};

bool hub75_pins_preset(const char *name, hub75_pins *pins)
{
    for (size_t i = 0; i < sizeof presets / sizeof presets[0]; i++) {
        if (strcmp(name, presets[i].name) == 0) {
            memcpy(pins->pin, presets[i].pin, sizeof pins->pin);
            return true;
        }
    }
    return false;
}

const char *hub75_presets(void)
{
    return "adafruit-hat adafruit-hat-pwm regular";
}

void hub75_config_default(hub75_config *c)
{
    memset(c, 0, sizeof *c);
    c->panel_w = 64;
    c->panel_h = 32;
    c->chain = 1;
    c->planes = 8;
    c->lsb_ns = 200;
    hub75_pins_preset("adafruit-hat", &c->pins);
    snprintf(c->chip, sizeof c->chip, "/dev/gpiochip0");
}

int hub75_scan(const hub75_config *c)
{
    return c->panel_h / 2;
}

int hub75_addr_bits(const hub75_config *c)
{
    int bits = 0;
    while ((1 << bits) < hub75_scan(c))
        bits++;
    return bits;
}

hal_status hub75_config_check(const hub75_config *c, char *err, size_t errlen)
{
    if (c->panel_h != 16 && c->panel_h != 32 && c->panel_h != 64) {
        snprintf(err, errlen,
                 "hub75 panel height %d: supported are 16 (1/8 scan), 32 (1/16 scan) and 64 (1/32 scan)",
                 c->panel_h);
        return HAL_ERR_CONFIG;
    }
    if (c->panel_w < 1 || c->panel_w > 1024 || c->panel_w % 8 != 0) {
        snprintf(err, errlen, "hub75 panel width %d: expected a multiple of 8 in 8..1024", c->panel_w);
        return HAL_ERR_CONFIG;
    }
    if (c->chain < 1 || c->panel_w * c->chain > 4096) {
        snprintf(err, errlen, "hub75 chain %d: expected 1.. (total width at most 4096)", c->chain);
        return HAL_ERR_CONFIG;
    }
    if (c->planes < 1 || c->planes > HUB75_MAX_PLANES) {
        snprintf(err, errlen, "hub75 planes %d: expected 1..%d", c->planes, HUB75_MAX_PLANES);
        return HAL_ERR_CONFIG;
    }
    if (c->lsb_ns < 1 || c->lsb_ns > 1000000) {
        snprintf(err, errlen, "hub75 lsb-ns %u: expected 1..1000000", c->lsb_ns);
        return HAL_ERR_CONFIG;
    }
    int abits = hub75_addr_bits(c);
    for (int f = 0; f < HUB75_NFUNC; f++) {
        bool needed = !(f >= HUB75_A && f <= HUB75_E) || (f - HUB75_A) < abits;
        int p = c->pins.pin[f];
        if (!needed)
            continue;
        if (p < 0) {
            snprintf(err, errlen, "hub75 pin %s is not set%s", hub75_func_name(f),
                     f == HUB75_E ? " (a 64-row panel scans 1/32 and needs address line E)" : "");
            return HAL_ERR_CONFIG;
        }
        if (p > 511) {
            snprintf(err, errlen, "hub75 pin %s=%d: line offsets are 0..511", hub75_func_name(f), p);
            return HAL_ERR_CONFIG;
        }
        for (int g = 0; g < f; g++) {
            bool gneeded = !(g >= HUB75_A && g <= HUB75_E) || (g - HUB75_A) < abits;
            if (gneeded && c->pins.pin[g] == p) {
                snprintf(err, errlen, "hub75 pins %s and %s are both line %d", hub75_func_name(g),
                         hub75_func_name(f), p);
                return HAL_ERR_CONFIG;
            }
        }
    }
    if (!c->chip[0]) {
        snprintf(err, errlen, "hub75 gpio-chip is empty");
        return HAL_ERR_CONFIG;
    }
    return HAL_OK;
}

uint64_t hub75_writes_per_frame(const hub75_config *c)
{
    uint64_t w = (uint64_t)c->panel_w * (uint64_t)c->chain;
    return (uint64_t)hub75_scan(c) * (uint64_t)c->planes * (2u * w + 5u);
}

double hub75_refresh_estimate(const hub75_config *c, double write_ns)
{
    double lit = (double)hub75_scan(c) * (double)((1u << c->planes) - 1u) * (double)c->lsb_ns;
    double t = (double)hub75_writes_per_frame(c) * write_ns + lit;
    return 1e9 / t;
}
