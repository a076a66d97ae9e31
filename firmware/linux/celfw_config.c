/*
 * celfw_config.c - parsing and checking celfw's settings.
 *
 * One table lists every setting with its parser and help text, so the
 * command line, the config file and --help cannot drift apart. Parsers write
 * a message saying what was expected; the caller adds where the value came
 * from ("celfw.conf:7" or "--planes").
 */
#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "bands.h"
#include "celfw_config.h"
#include "cli_num.h"
#include "gud_wire.h"

typedef bool (*parse_fn)(celfw_config *c, const char *v, char *err, size_t errlen);

typedef struct setting {
    const char *name;
    const char *arg;
    parse_fn parse;
    const char *help;
} setting;

/* Settings that say where credentials are: the config file only, never the
 * command line, which other users of the board can read (/proc/PID/cmdline). */
static bool file_only(const setting *s)
{
    static const char *const names[] = {"mqtt-username", "mqtt-password-file", "mqtt-ca",
                                        "mqtt-cert", "mqtt-key"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (!strcmp(s->name, names[i]))
            return true;
    return false;
}

/* Numbers are read strictly (cli_num.h): decimal, or hex after 0x. */
static bool parse_int(const char *v, long lo, long hi, long *out, char *err, size_t errlen)
{
    if (!cli_int(v, 0, '\0', lo, hi, out)) {
        snprintf(err, errlen, "'%s' is not an integer in %ld..%ld", v, lo, hi);
        return false;
    }
    return true;
}

static bool parse_num(const char *v, double lo, double hi, double *out, char *err, size_t errlen)
{
    if (!cli_real(v, '\0', lo, hi, out)) {
        snprintf(err, errlen, "'%s' is not a number in %g..%g", v, lo, hi);
        return false;
    }
    return true;
}

static bool parse_size(const char *v, int *w, int *h, char *err, size_t errlen)
{
    if (!cli_size(v, CS_CFG_MAX_WIDTH, CS_CFG_MAX_HEIGHT, w, h)) {
        snprintf(err, errlen, "'%s' is not a size WxH (width 1..%d, height 1..%d)", v, CS_CFG_MAX_WIDTH,
                 CS_CFG_MAX_HEIGHT);
        return false;
    }
    return true;
}

static bool parse_bool(const char *v, bool *out, char *err, size_t errlen)
{
    if (!strcmp(v, "yes") || !strcmp(v, "true") || !strcmp(v, "1") || !strcmp(v, "on")) {
        *out = true;
    } else if (!strcmp(v, "no") || !strcmp(v, "false") || !strcmp(v, "0") || !strcmp(v, "off")) {
        *out = false;
    } else {
        snprintf(err, errlen, "'%s' is not yes or no", v);
        return false;
    }
    return true;
}

static bool p_backend(celfw_config *c, const char *v, char *err, size_t n)
{
    if (!strcmp(v, "null"))
        c->backend = CELFW_NULL;
    else if (!strcmp(v, "gpio") || !strcmp(v, "hub75"))
        c->backend = CELFW_GPIO;
    else if (!strcmp(v, "usb") || !strcmp(v, "gud"))
        c->backend = CELFW_USB;
    else if (!strcmp(v, "drm") || !strcmp(v, "kms"))
        c->backend = CELFW_DRM;
    else {
        snprintf(err, n, "'%s' is not a backend (gpio, usb, drm or null)", v);
        return false;
    }
    return true;
}

static bool p_size(celfw_config *c, const char *v, char *err, size_t n)
{
    return parse_size(v, &c->width, &c->height, err, n);
}

static bool p_fps(celfw_config *c, const char *v, char *err, size_t n)
{
    c->fps_set = true;
    return parse_num(v, 0.0, 10000.0, &c->fps, err, n);
}

static bool p_aa(celfw_config *c, const char *v, char *err, size_t n)
{
    long k;
    if (!strcmp(v, "none")) {
        c->aa = CS_AA_NONE;
        return true;
    }
    if (!parse_int(v, 1, CS_CFG_MAX_SUBSCANLINES, &k, err, n)) {
        snprintf(err, n, "'%s' is not none or a sub-scanline count 1..%d", v, CS_CFG_MAX_SUBSCANLINES);
        return false;
    }
    c->aa = CS_AA_SUBSCAN;
    c->subscanlines = (int)k;
    return true;
}

static bool p_input(celfw_config *c, const char *v, char *err, size_t n)
{
    if (strcmp(v, "none") && strcmp(v, "stdin") && strncmp(v, "file:", 5) && strncmp(v, "tcp:", 4) &&
        strncmp(v, "tty:", 4) && !celfw_mqtt_spec(v)) {
        snprintf(err, n, "'%s' is not an input (none, stdin, file:PATH, tcp:[HOST:]PORT, tty:DEVICE[:BAUD], "
                 "mqtt[s]://HOST:PORT[/TOPIC])", v);
        return false;
    }
    snprintf(c->input, sizeof c->input, "%s", v);
    return true;
}

static bool p_input_timeout(celfw_config *c, const char *v, char *err, size_t n)
{
    return parse_num(v, 0.1, 86400.0, &c->input_timeout, err, n);
}

/* Repeatable: each --trust (or trust = line, file first) adds a key. */
static bool p_trust(celfw_config *c, const char *v, char *err, size_t n)
{
    if (c->trust_count == CELFW_MAX_TRUST) {
        snprintf(err, n, "at most %d trusted keys", CELFW_MAX_TRUST);
        return false;
    }
    if (!v[0] || strlen(v) >= sizeof c->trust[0]) {
        snprintf(err, n, "'%s' is not a key file path", v);
        return false;
    }
    snprintf(c->trust[c->trust_count++], sizeof c->trust[0], "%s", v);
    return true;
}

static bool p_state_dir(celfw_config *c, const char *v, char *err, size_t n)
{
    if (!v[0] || strlen(v) >= sizeof c->state_dir - 16) {
        snprintf(err, n, "'%s' is not a directory path", v);
        return false;
    }
    snprintf(c->state_dir, sizeof c->state_dir, "%s", v);
    return true;
}

static bool p_scene(celfw_config *c, const char *v, char *err, size_t n)
{
    (void)err;
    (void)n;
    snprintf(c->scene, sizeof c->scene, "%s", v);
    return true;
}

static bool p_log(celfw_config *c, const char *v, char *err, size_t n)
{
    return parse_num(v, 0.0, 86400.0, &c->log_interval, err, n);
}

static bool p_frames(celfw_config *c, const char *v, char *err, size_t n)
{
    long k;
    if (!parse_int(v, 0, 2147483647L, &k, err, n))
        return false;
    c->max_frames = (uint64_t)k;
    return true;
}

static bool p_duration(celfw_config *c, const char *v, char *err, size_t n)
{
    return parse_num(v, 0.0, 1e9, &c->duration, err, n);
}

static bool p_time_step(celfw_config *c, const char *v, char *err, size_t n)
{
    return parse_num(v, 0.0, 3600.0, &c->time_step, err, n);
}

/* at:SECONDS becomes ns as a scene's "epoch" does (scene_json.c), so at:E on a
 * scene whose epoch is E shows its time 0 exactly. */
static bool p_clock(celfw_config *c, const char *v, char *err, size_t n)
{
    double at = 0.0;
    bool fixed = !strncmp(v, "at:", 3);
    if (fixed ? !cli_real(v + 3, '\0', 0.0, 9.2e9, &at)
              : strcmp(v, "monotonic") != 0 && strcmp(v, "realtime") != 0) {
        snprintf(err, n, "'%s' is not a clock (monotonic, realtime, or at:SECONDS since 1970 in 0..9.2e9)", v);
        return false;
    }
    c->realtime = fixed || v[0] == 'r';
    c->clock_at = fixed;
    c->clock_at_ns = (uint64_t)(at * 1e9);
    return true;
}

static bool p_panel(celfw_config *c, const char *v, char *err, size_t n)
{
    return parse_size(v, &c->hub75.panel_w, &c->hub75.panel_h, err, n);
}

static bool p_threads(celfw_config *c, const char *v, char *err, size_t n)
{
    long k;
    if (!parse_int(v, 1, BANDS_MAX_THREADS, &k, err, n))
        return false;
    c->threads = (int)k;
    return true;
}

static bool p_damage(celfw_config *c, const char *v, char *err, size_t n)
{
    return parse_bool(v, &c->damage, err, n);
}

static bool p_chain(celfw_config *c, const char *v, char *err, size_t n)
{
    long k;
    if (!parse_int(v, 1, 64, &k, err, n))
        return false;
    c->hub75.chain = (int)k;
    return true;
}

static bool p_planes(celfw_config *c, const char *v, char *err, size_t n)
{
    long k;
    if (!parse_int(v, 1, HUB75_MAX_PLANES, &k, err, n))
        return false;
    c->hub75.planes = (int)k;
    return true;
}

static bool p_lsb(celfw_config *c, const char *v, char *err, size_t n)
{
    long k;
    if (!parse_int(v, 1, 1000000, &k, err, n))
        return false;
    c->hub75.lsb_ns = (uint32_t)k;
    return true;
}

/* A preset name, or name=line pairs: "r1=5,g1=13,...,oe=4" (also on top of a preset). */
static bool p_pins(celfw_config *c, const char *v, char *err, size_t n)
{
    if (hub75_pins_preset(v, &c->hub75.pins))
        return true;
    if (!strchr(v, '=')) {
        snprintf(err, n, "'%s' is not a pin preset (%s) or a list like r1=5,g1=13,...", v, hub75_presets());
        return false;
    }
    char buf[256];
    snprintf(buf, sizeof buf, "%s", v);
    for (char *save = NULL, *tok = strtok_r(buf, ", ", &save); tok; tok = strtok_r(NULL, ", ", &save)) {
        char *eq = strchr(tok, '=');
        long line;
        if (!eq) {
            snprintf(err, n, "'%s' in the pin list is not name=line", tok);
            return false;
        }
        *eq = 0;
        int f = hub75_func_by_name(tok);
        if (f < 0) {
            snprintf(err, n, "'%s' is not a HUB75 pin (r1 g1 b1 r2 g2 b2 a b c d e clk lat oe)", tok);
            return false;
        }
        if (!strcmp(eq + 1, "none")) {
            line = -1;
        } else if (!parse_int(eq + 1, 0, 511, &line, err, n)) {
            snprintf(err, n, "pin %s: '%s' is not a line offset 0..511 or none", tok, eq + 1);
            return false;
        }
        c->hub75.pins.pin[f] = (int)line;
    }
    return true;
}

static bool p_chip(celfw_config *c, const char *v, char *err, size_t n)
{
    (void)err;
    (void)n;
    snprintf(c->hub75.chip, sizeof c->hub75.chip, "%s", v);
    return true;
}

static bool p_usb_device(celfw_config *c, const char *v, char *err, size_t n)
{
    if (!strcmp(v, "any")) {
        c->usb.vid = c->usb.pid = 0;
        return true;
    }
    long vid, pid;
    const char *rest = cli_int(v, 16, ':', 0, 0xffff, &vid);
    if (!rest || !cli_int(rest, 16, '\0', 0, 0xffff, &pid)) {
        snprintf(err, n, "'%s' is not VID:PID in hex (e.g. 1d50:614d) or any", v);
        return false;
    }
    c->usb.vid = (uint16_t)vid;
    c->usb.pid = (uint16_t)pid;
    return true;
}

static bool p_usb_format(celfw_config *c, const char *v, char *err, size_t n)
{
    if (!strcmp(v, "auto"))
        c->usb.format = 0;
    else if (!strcmp(v, "rgb565"))
        c->usb.format = GUD_FORMAT_RGB565;
    else if (!strcmp(v, "xrgb8888"))
        c->usb.format = GUD_FORMAT_XRGB8888;
    else {
        snprintf(err, n, "'%s' is not auto, rgb565 or xrgb8888", v);
        return false;
    }
    return true;
}

static bool p_usb_compression(celfw_config *c, const char *v, char *err, size_t n)
{
    if (!strcmp(v, "auto"))
        c->usb.compression = -1;
    else if (!strcmp(v, "none"))
        c->usb.compression = 0;
    else if (!strcmp(v, "lz4"))
        c->usb.compression = 1;
    else {
        snprintf(err, n, "'%s' is not auto, none or lz4", v);
        return false;
    }
    return true;
}

static bool p_usb_timeout(celfw_config *c, const char *v, char *err, size_t n)
{
    long k;
    if (!parse_int(v, 10, 60000, &k, err, n))
        return false;
    c->usb.timeout_ms = (unsigned)k;
    return true;
}

static bool p_usb_retries(celfw_config *c, const char *v, char *err, size_t n)
{
    long k;
    if (!parse_int(v, 0, 20, &k, err, n))
        return false;
    c->usb.retries = (int)k;
    return true;
}

static bool p_usb_reconnect(celfw_config *c, const char *v, char *err, size_t n)
{
    long k;
    if (!parse_int(v, 10, 600000, &k, err, n))
        return false;
    c->usb.reconnect_ms = (unsigned)k;
    return true;
}

static bool p_usb_wait(celfw_config *c, const char *v, char *err, size_t n)
{
    return parse_bool(v, &c->usb.wait, err, n);
}

static bool p_wall(celfw_config *c, const char *v, char *err, size_t n)
{
    if (!cli_size(v, CS_CFG_MAX_WALL, CS_CFG_MAX_WALL, &c->wall_w, &c->wall_h)) {
        snprintf(err, n, "'%s' is not a wall size WxH (1..%d each)", v, CS_CFG_MAX_WALL);
        return false;
    }
    return true;
}

static bool p_viewport(celfw_config *c, const char *v, char *err, size_t n)
{
    if (!cli_viewport(v, &c->view[0], &c->view[1], &c->view[2], &c->view[3]) ||
        c->view[2] > CS_CFG_MAX_WIDTH || c->view[3] > CS_CFG_MAX_HEIGHT) {
        snprintf(err, n, "'%s' is not a viewport X,Y,W,H (W 1..%d, H 1..%d)", v, CS_CFG_MAX_WIDTH,
                 CS_CFG_MAX_HEIGHT);
        c->view[2] = 0;
        return false;
    }
    return true;
}

/* A copy of v into dst (of size cap), refused if it does not fit. */
static bool set_text(char *dst, size_t cap, const char *v, const char *what, char *err, size_t n)
{
    if (!v[0] || strlen(v) >= cap) {
        snprintf(err, n, "'%s' is not a %s (1..%zu characters)", v, what, cap - 1);
        return false;
    }
    memcpy(dst, v, strlen(v) + 1);
    return true;
}

/* A sign id names topics: letters, digits, '-', '_' and '.' only. */
static bool p_sign_id(celfw_config *c, const char *v, char *err, size_t n)
{
    if (v[strspn(v, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_.")]) {
        snprintf(err, n, "'%s' is not a sign id (letters, digits, '-', '_', '.')", v);
        return false;
    }
    return set_text(c->mqtt.sign_id, sizeof c->mqtt.sign_id, v, "sign id", err, n);
}

static bool p_mqtt_topic(celfw_config *c, const char *v, char *err, size_t n)
{
    if (c->mqtt.topic_count >= CELFW_MQTT_MAX_TOPICS) {
        snprintf(err, n, "at most %d group topics", CELFW_MQTT_MAX_TOPICS);
        return false;
    }
    if (!set_text(c->mqtt.topics[c->mqtt.topic_count], sizeof c->mqtt.topics[0], v, "topic", err, n))
        return false;
    c->mqtt.topic_count++;
    return true;
}

static bool p_mqtt_username(celfw_config *c, const char *v, char *err, size_t n)
{
    return set_text(c->mqtt.username, sizeof c->mqtt.username, v, "user name", err, n);
}

static bool p_mqtt_password(celfw_config *c, const char *v, char *err, size_t n)
{
    return set_text(c->mqtt.password_file, sizeof c->mqtt.password_file, v, "file name", err, n);
}

static bool p_mqtt_ca(celfw_config *c, const char *v, char *err, size_t n)
{
    return set_text(c->mqtt.ca_file, sizeof c->mqtt.ca_file, v, "file name", err, n);
}

static bool p_mqtt_cert(celfw_config *c, const char *v, char *err, size_t n)
{
    return set_text(c->mqtt.cert_file, sizeof c->mqtt.cert_file, v, "file name", err, n);
}

static bool p_mqtt_key(celfw_config *c, const char *v, char *err, size_t n)
{
    return set_text(c->mqtt.key_file, sizeof c->mqtt.key_file, v, "file name", err, n);
}

static bool p_drm_device(celfw_config *c, const char *v, char *err, size_t n)
{
    return set_text(c->drm.device, sizeof c->drm.device, v, "device path", err, n);
}

static bool p_mode(celfw_config *c, const char *v, char *err, size_t n)
{
    if (!kms_parse_mode(v, &c->drm)) {
        snprintf(err, n, "'%s' is not a mode WxH or WxH@HZ (width 1..%d, height 1..%d, 1..1000 Hz)", v,
                 CS_CFG_MAX_WIDTH, CS_CFG_MAX_HEIGHT);
        return false;
    }
    c->drm_mode_set = true;
    return true;
}

static bool p_drm_wait(celfw_config *c, const char *v, char *err, size_t n)
{
    return parse_bool(v, &c->drm.wait, err, n);
}

static bool p_bench(celfw_config *c, const char *v, char *err, size_t n)
{
    return parse_bool(v, &c->bench_gpio, err, n);
}

static const setting settings[] = {
    {"backend", "gpio|usb|drm|null", p_backend, "display backend (default null)"},
    {"size", "WxH", p_size, "render size (null: required; usb, drm: default the device's mode)"},
    {"fps", "N", p_fps, "frames per second (default 30); 0 = unpaced. HUB75 is always unpaced"},
    {"aa", "none|N", p_aa, "anti-aliasing: pixel centres, or N sub-scanlines (default 4)"},
    {"threads", "N", p_threads, "render bands of lines on N threads, 1..64 (default: the cores; "
                                "HUB75 renders on one)"},
    {"damage", "on|off", p_damage, "render only the window that changed since the last frame (default on; "
                                   "HUB75 rescans whole frames)"},
    {"input", "SPEC", p_input, "cel stream: none, stdin, file:PATH, tcp:PORT (loopback), tcp:ADDR:PORT, "
                              "tcp:[ADDR]:PORT, tty:DEV[:BAUD], mqtt[s]://HOST:PORT[/TOPIC]"},
    {"input-timeout", "SECONDS", p_input_timeout, "drop a TCP client that gets no transaction applied for this "
                                                  "long (default 10)"},
    {"trust", "FILE.pub", p_trust, "apply only transactions signed by this key (repeatable; celc keygen)"},
    {"state-dir", "DIR", p_state_dir, "keeps the last applied sequence per trusted key (needed with trust)"},
    {"sign-id", "ID", p_sign_id, "MQTT: client id; status on signs/ID/status, own topic signs/ID by default"},
    {"mqtt-topic", "TOPIC", p_mqtt_topic, "MQTT: a group topic to take content from too (repeatable)"},
    {"mqtt-username", "NAME", p_mqtt_username, "MQTT: broker user name"},
    {"mqtt-password-file", "PATH", p_mqtt_password, "MQTT: file holding the password (mode 0600)"},
    {"mqtt-ca", "PATH", p_mqtt_ca, "MQTT: CA certificate the broker's must chain to (mqtts)"},
    {"mqtt-cert", "PATH", p_mqtt_cert, "MQTT: client certificate (mqtts)"},
    {"mqtt-key", "PATH", p_mqtt_key, "MQTT: client key (mqtts; mode 0600)"},
    {"scene", "SPEC", p_scene, "scene until the stream commits one: builtin:demo|anim|bars, FILE.json, none"},
    {"log-interval", "SECONDS", p_log, "seconds between status lines (default 5; 0 = at exit only)"},
    {"frames", "N", p_frames, "stop after N frames (default: run until SIGTERM)"},
    {"duration", "SECONDS", p_duration, "stop after this long"},
    {"time-step", "SECONDS", p_time_step, "animation time advances by this per frame instead of the clock"},
    {"clock", "CLOCK", p_clock, "monotonic: animation time from the commit (default); realtime: wall clock less the stream's epoch; at:S: realtime with the clock fixed at S s since 1970"},
    {"wall", "WxH", p_wall, "video wall: the whole output's size, of which this board shows --viewport"},
    {"viewport", "X,Y,W,H", p_viewport, "video wall: this board's window of the wall (W x H = the display)"},
    {"panel", "WxH", p_panel, "HUB75: one panel, 64x32 (1/16 scan) or 64x64 (1/32 scan), ..."},
    {"chain", "N", p_chain, "HUB75: panels in the chain (default 1)"},
    {"planes", "N", p_planes, "HUB75: colour depth in bit planes, 1..12 (default 8)"},
    {"lsb-ns", "NS", p_lsb, "HUB75: lit time of the least significant plane (default 200)"},
    {"pins", "PRESET|LIST", p_pins, "HUB75: adafruit-hat (default), adafruit-hat-pwm, regular, or r1=5,..."},
    {"gpio-chip", "PATH", p_chip, "HUB75: GPIO character device (default /dev/gpiochip0)"},
    {"bench-gpio", "yes|no", p_bench, "HUB75: measure GPIO writes/s, print refresh estimates, exit"},
    {"usb-device", "VID:PID|any", p_usb_device, "USB: the display (default 1d50:614d)"},
    {"usb-format", "auto|rgb565|xrgb8888", p_usb_format, "USB: pixel format (default auto)"},
    {"usb-compression", "auto|none|lz4", p_usb_compression, "USB: LZ4 use (default auto)"},
    {"usb-timeout-ms", "MS", p_usb_timeout, "USB: per transfer (default 1000)"},
    {"usb-retries", "N", p_usb_retries, "USB: extra attempts per rectangle (default 2)"},
    {"usb-reconnect-ms", "MS", p_usb_reconnect, "USB: between reconnect attempts (default 500)"},
    {"usb-wait", "yes|no", p_usb_wait, "USB: start even if the display is absent (needs size)"},
    {"drm-device", "PATH", p_drm_device, "DRM: the card (default the first /dev/dri/cardN with a screen)"},
    {"mode", "WxH[@HZ]", p_mode, "DRM: the screen mode (default the connector's preferred one)"},
    {"drm-wait", "yes|no", p_drm_wait, "DRM: start even if no screen is connected (needs mode or size)"},
};

static const setting *find(const char *name)
{
    for (size_t i = 0; i < sizeof settings / sizeof settings[0]; i++)
        if (!strcmp(settings[i].name, name))
            return &settings[i];
    return NULL;
}

void celfw_usage(FILE *out)
{
    fprintf(out, "usage: celfw [--config FILE] [--SETTING VALUE ...]\n\n"
                 "celfw renders a cel stream continuously on a Linux board's display.\n"
                 "Settings (also valid as 'SETTING = VALUE' lines in the config file):\n");
    for (size_t i = 0; i < sizeof settings / sizeof settings[0]; i++)
        fprintf(out, "  --%-17s %-20s %s%s\n", settings[i].name, settings[i].arg, settings[i].help,
                file_only(&settings[i]) ? " (config file only)" : "");
    fprintf(out, "  --%-17s %-20s %s\n", "config", "FILE", "read settings from FILE first");
    fprintf(out, "\nStatus goes to stderr as 'celfw: status key=value ...' lines; SIGTERM stops cleanly.\n"
                 "Exit status: 0 done, 2 bad configuration, 3 input failed, 4 display failed.\n");
}

void celfw_config_default(celfw_config *c)
{
    memset(c, 0, sizeof *c);
    c->backend = CELFW_NULL;
    c->fps = 30.0;
    c->aa = CS_AA_SUBSCAN;
    c->subscanlines = 4;
    c->threads = bands_cores();
    c->damage = true;
    snprintf(c->input, sizeof c->input, "none");
    snprintf(c->scene, sizeof c->scene, "builtin:demo");
    c->input_timeout = 10.0;
    c->log_interval = 5.0;
    hub75_config_default(&c->hub75);
    gud_config_default(&c->usb);
    kms_config_default(&c->drm);
}

static char *trim(char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    char *e = s + strlen(s);
    while (e > s && isspace((unsigned char)e[-1]))
        *--e = 0;
    return s;
}

/* label says where the value came from: "config celfw.conf:7: planes" or "--planes". */
static bool apply(celfw_config *c, const setting *s, const char *value, const char *label, char *err,
                  size_t errlen)
{
    char why[200];
    if (!s->parse(c, value, why, sizeof why)) {
        snprintf(err, errlen, "%s: %s", label, why);
        return false;
    }
    return true;
}

static bool load_file(celfw_config *c, const char *path, char *err, size_t errlen)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, errlen, "config %s: %s", path, strerror(errno));
        return false;
    }
    char line[512];
    int no = 0;
    bool ok = true;
    while (ok && fgets(line, sizeof line, f)) {
        no++;
        char *hash = strchr(line, '#');
        if (hash)
            *hash = 0;
        char *s = trim(line);
        if (!*s)
            continue;
        char *eq = strchr(s, '=');
        if (!eq) {
            snprintf(err, errlen, "config %s:%d: expected 'setting = value', got '%s'", path, no, s);
            ok = false;
            break;
        }
        *eq = 0;
        const char *name = trim(s);
        const setting *st = find(name);
        if (!st) {
            snprintf(err, errlen, "config %s:%d: unknown setting '%s' (celfw --help lists them)", path, no,
                     name);
            ok = false;
            break;
        }
        char label[400];
        snprintf(label, sizeof label, "config %s:%d: %s", path, no, name);
        ok = apply(c, st, trim(eq + 1), label, err, errlen);
    }
    fclose(f);
    return ok;
}

int celfw_config_parse(celfw_config *c, int argc, char **argv, char *err, size_t errlen)
{
    /* --config first, wherever it is, so that the command line wins over the file */
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            celfw_usage(stdout);
            return 1;
        }
        if (!strcmp(argv[i], "--version")) {
            printf("celfw (celscan) 0.1\n");
            return 1;
        }
        const char *path = NULL;
        if ((!strcmp(argv[i], "--config") || !strcmp(argv[i], "-c")) && i + 1 < argc)
            path = argv[++i];
        else if (!strncmp(argv[i], "--config=", 9))
            path = argv[i] + 9;
        if (path) {
            snprintf(c->config_file, sizeof c->config_file, "%s", path);
            if (!load_file(c, path, err, errlen))
                return -1;
        }
    }
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--config") || !strcmp(a, "-c")) {
            i++;
            continue;
        }
        if (!strncmp(a, "--config=", 9))
            continue;
        if (strncmp(a, "--", 2) != 0) {
            snprintf(err, errlen, "unexpected argument '%s' (settings are --name value)", a);
            return -1;
        }
        char name[64];
        const char *value;
        const char *eq = strchr(a, '=');
        if (eq) {
            snprintf(name, sizeof name, "%.*s", (int)(eq - a - 2), a + 2);
            value = eq + 1;
        } else {
            snprintf(name, sizeof name, "%s", a + 2);
            if (!find(name)) {
                snprintf(err, errlen, "unknown option '%s' (celfw --help lists them)", a);
                return -1;
            }
            if (i + 1 >= argc) {
                snprintf(err, errlen, "%s needs a value (%s)", a, find(name)->arg);
                return -1;
            }
            value = argv[++i];
        }
        const setting *st = find(name);
        if (!st) {
            snprintf(err, errlen, "unknown option '--%s' (celfw --help lists them)", name);
            return -1;
        }
        if (file_only(st)) {
            snprintf(err, errlen, "--%s may only be set in the config file (credentials stay off the "
                     "command line, where other users can read them)", name);
            return -1;
        }
        char label[80];
        snprintf(label, sizeof label, "--%s", name);
        if (!apply(c, st, value, label, err, errlen))
            return -1;
    }
    return 0;
}

bool celfw_config_check(celfw_config *c, char *err, size_t errlen)
{
    c->mqtt.status_interval = c->log_interval;
    if (celfw_mqtt_spec(c->input) && !c->mqtt.sign_id[0]) {
        snprintf(err, errlen, "input %s needs sign-id (the client id and status topic)", c->input);
        return false;
    }
    if ((c->view[2] > 0) != (c->wall_w > 0)) {
        snprintf(err, errlen, "a video wall needs both --wall WxH and --viewport X,Y,W,H");
        return false;
    }
    if (c->view[2] > 0) {
        if (c->view[0] > c->wall_w - c->view[2] || c->view[1] > c->wall_h - c->view[3]) {
            snprintf(err, errlen, "viewport %d,%d,%d,%d does not fit in the %dx%d wall", c->view[0],
                     c->view[1], c->view[2], c->view[3], c->wall_w, c->wall_h);
            return false;
        }
        if (c->backend == CELFW_NULL && c->width &&
            (c->width != c->view[2] || c->height != c->view[3])) {
            snprintf(err, errlen, "size %dx%d differs from the viewport's %dx%d", c->width,
                     c->height, c->view[2], c->view[3]);
            return false;
        }
    }
    char why[256];
    switch (c->backend) {
    case CELFW_NULL:
        if (!c->width && c->view[2] > 0) { /* the board is its viewport */
            c->width = c->view[2];
            c->height = c->view[3];
        }
        if (!c->width) {
            snprintf(err, errlen, "backend null needs --size WxH");
            return false;
        }
        break;
    case CELFW_GPIO:
        if (c->fps_set && c->fps > 0) {
            snprintf(err, errlen, "fps %g: a HUB75 panel shows nothing between scans, so celfw rescans it "
                     "continuously (each scan is a frame); leave fps out", c->fps);
            return false;
        }
        if (hub75_config_check(&c->hub75, why, sizeof why) != HAL_OK) {
            snprintf(err, errlen, "%s", why);
            return false;
        }
        if (c->width && (c->width != c->hub75.panel_w * c->hub75.chain || c->height != c->hub75.panel_h)) {
            snprintf(err, errlen, "size %dx%d does not match the HUB75 chain (%d x %dx%d = %dx%d); leave size out",
                     c->width, c->height, c->hub75.chain, c->hub75.panel_w, c->hub75.panel_h,
                     c->hub75.chain * c->hub75.panel_w, c->hub75.panel_h);
            return false;
        }
        break;
    case CELFW_USB:
        if (c->usb.wait && !c->width) {
            snprintf(err, errlen, "usb-wait needs --size WxH (the display may not be there to ask)");
            return false;
        }
        break;
    case CELFW_DRM:
        if (c->width && c->drm_mode_set && (c->width != c->drm.width || c->height != c->drm.height)) {
            snprintf(err, errlen, "size %dx%d differs from mode %dx%d; leave size out", c->width, c->height,
                     c->drm.width, c->drm.height);
            return false;
        }
        if (c->width && !c->drm_mode_set) { /* the size asks for the mode of that size */
            c->drm.width = c->width;
            c->drm.height = c->height;
        }
        if (c->drm.wait && !c->drm.width) {
            snprintf(err, errlen, "drm-wait needs --mode or --size (the screen may not be there to ask)");
            return false;
        }
        break;
    }
    if (c->backend == CELFW_GPIO)
        c->fps = 0.0;
    if (c->trust_count > 0 && !c->state_dir[0]) {
        snprintf(err, errlen, "trust needs state-dir DIR: the last sequence applied from each key must "
                 "outlive a restart, or an old signed stream could roll the sign back");
        return false;
    }
    if (c->bench_gpio && c->backend != CELFW_GPIO) {
        snprintf(err, errlen, "bench-gpio needs backend gpio");
        return false;
    }
    return true;
}
