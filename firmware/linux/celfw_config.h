/*
 * celfw_config.h - celfw's settings, from a small config file and the command line.
 *
 * Every setting has one name, used both as a command-line option
 * (--planes 8, --planes=8) and as a config-file line (planes = 8). The file
 * is read first and the command line overrides it. Errors name the file and
 * line or the option, the value, and what was expected.
 */
#ifndef CELFW_CONFIG_H
#define CELFW_CONFIG_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "celfw_mqtt.h"
#include "celscan.h"
#include "gud_host.h"
#include "hub75.h"
#include "kms.h"

#define CELFW_MAX_TRUST 16

typedef enum celfw_backend { CELFW_NULL = 0, CELFW_GPIO, CELFW_USB, CELFW_DRM } celfw_backend;

typedef struct celfw_config {
    celfw_backend backend;
    int width, height;     /* null: required; usb, drm: 0 = the device's mode; gpio: derived */
    double fps;            /* frame pacing; 0 = as fast as the display takes frames */
    bool fps_set;          /* fps was given (HUB75 is rescanned unpaced, so it may not be) */
    cs_aa_mode aa;
    int subscanlines;
    int threads;           /* render threads for one-lane displays (bands.h); 1: the main thread */
    bool damage;           /* render only what changed since the last frame (cs_frame_damage) */
    char input[256];       /* none | stdin | file:PATH | tcp:[HOST:]PORT | tty:DEVICE[:BAUD] |
                              mqtt[s]://HOST:PORT[/TOPIC] */
    char scene[256];       /* builtin:NAME | PATH.json | none */
    double input_timeout;  /* seconds a TCP client may go without a transaction applied */
    char trust[CELFW_MAX_TRUST][256]; /* public key files; any: only signed transactions apply */
    int trust_count;
    char state_dir[256];   /* where the last applied sequence per key is kept */
    double log_interval;   /* seconds between status lines; 0 = only at exit */
    uint64_t max_frames;   /* stop after this many frames; 0 = never */
    double duration;       /* stop after this many seconds; 0 = never */
    double time_step;      /* > 0: animation time = frame index * step, not the clock */
    bool realtime;         /* --clock realtime: wall clock less the stream's epoch (celfw_clock.h) */
    bool clock_at;         /* --clock at:SECONDS: realtime, the wall clock fixed at clock_at_ns */
    uint64_t clock_at_ns;  /* ns since 1970-01-01 UTC */
    bool bench_gpio;       /* measure GPIO write throughput, print refresh estimates, exit */
    int wall_w, wall_h;    /* a video wall's whole size; 0 = no wall */
    celfw_mqtt_config mqtt; /* sign-id, group topics, broker credentials */
    int view[4];           /* this board's viewport X, Y, W, H of the wall (W = 0: none) */
    hub75_config hub75;
    gud_config usb;
    kms_config drm;
    bool drm_mode_set;     /* --mode was given */
    char config_file[256];
} celfw_config;

void celfw_config_default(celfw_config *c);

/*
 * Reads argv (and the --config file it names) into c. Returns 0 when celfw
 * should run, 1 when it printed help or the version and should exit 0, and
 * -1 on an error, with the message in err.
 */
int celfw_config_parse(celfw_config *c, int argc, char **argv, char *err, size_t errlen);

/* Cross-checks settings after parsing (backend needs, sizes, pins) and
 * settles what depends on the backend (HUB75: unpaced). */
bool celfw_config_check(celfw_config *c, char *err, size_t errlen);

void celfw_usage(FILE *out);

#endif /* CELFW_CONFIG_H */
