/*
 * celfw.c - the firmware of Linux display boards: stream in, frames out, forever.
 *
 * celfw opens its input (TCP, tty, stdin or a file) and its display (HUB75
 * through GPIO, a GUD display through USB, or nothing), then loops: render a
 * frame at the animation clock's time, pulling lines as the display wants
 * them, then wait for the next frame slot while feeding whatever input
 * arrived to the stream decoder. A commit swaps the two scene stores between
 * frames, so a frame never mixes two scenes. The display may come and go
 * (USB); the loop keeps its clock and counts frames it could not show.
 *
 * Everything worth knowing goes to stderr as one line per event, in a form
 * scripts can parse:
 *   celfw: start key=value ...      once, with the resolved input address
 *   celfw: event <what>             display lost/back, clients, stream errors
 *   celfw: status key=value ...     every --log-interval seconds
 *   celfw: error <message>          configuration and device errors
 *   celfw: exit reason=... key=value ...
 * SIGTERM and SIGINT end the loop after the current frame; the display is
 * blanked and released, and the exit status is 0.
 */
#define _GNU_SOURCE /* ppoll */
#include <errno.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "celfw_config.h"
#include "celfw_input.h"
#include "celfw_notify.h"
#include "celfw_scenes.h"
#include "celfw_stream.h"
#include "celfw_wall.h"
#include "gud_host.h"
#include "hub75.h"
#include "lx_display.h"
#include "lx_scene_source.h"

enum { EXIT_CONFIG = 2, EXIT_INPUT = 3, EXIT_DISPLAY = 4 };

typedef struct celfw {
    celfw_config cfg;
    lx_display *disp;
    lx_scene_source src;
    cs_scene *scene[2];
    int front;
    char builtin[32];        /* a built-in scene being shown, "" otherwise */
    celfw_input *in;
    celfw_stream *stream;
    uint64_t iterations, frames, dropped, stream_bytes, stream_errors, commits, failures;
    lx_frame_stats sum;
    bool display_up, render_warned;
    double anim_t;
    uint64_t t0, last_log, frames_at_log;
    celfw_notify notify; /* READY and watchdog pings to systemd */
} celfw;

static volatile sig_atomic_t stop_signal;

static void on_signal(int sig)
{
    stop_signal = sig;
}

static void say(const char *kind, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void say(const char *kind, const char *fmt, ...)
{
    char msg[600];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    fprintf(stderr, "celfw: %s %s\n", kind, msg);
    fflush(stderr);
}

static void backend_log(void *user, const char *fmt, ...)
{
    (void)user;
    char msg[500];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    say("event", "%s", msg);
}

/* ------------------------------------------------------------- stream */

/* Tells the input what the sign shows (a fleet input publishes it):
 * after a commit or an error, and with the frame rate from status(). */
static void report(celfw *fw, const char *error, double fps)
{
    celfw_report r = {fw->commits, fw->stream_errors, fps, error, 0};
    celfw_input_report(fw->in, &r);
}

static void on_bytes(void *user, const uint8_t *p, size_t n)
{
    celfw *fw = user;
    while (n > 0) {
        size_t used = 0;
        celfw_stream_error err = {0};
        cs_scene *shown = fw->scene[fw->front], *back = fw->scene[fw->front ^ 1];
        celfw_stream_result r = celfw_stream_feed(fw->stream, p, n, &used, shown, back, &err);
        if (used > n)
            used = n;
        p += used;
        n -= used;
        fw->stream_bytes += used;
        if (r == CELFW_STREAM_COMMIT) {
            /* between frames: the next frame shows the new scene whole; the
             * old one becomes the decoder's scratch (a patch copies what is
             * shown before it edits) */
            fw->front ^= 1;
            fw->builtin[0] = 0;
            fw->commits++;
            say("event", "stream commit %llu applied", (unsigned long long)fw->commits);
            report(fw, NULL, -1.0);
        } else if (r == CELFW_STREAM_ERROR) {
            fw->stream_errors++;
            say("event", "stream error at byte %llu: %s; scene kept", (unsigned long long)err.offset,
                err.what);
            report(fw, err.what, -1.0);
        } else if (used == 0) {
            break;
        }
    }
}

static void on_reset(void *user, const char *why)
{
    (void)why;
    celfw *fw = user;
    celfw_stream_error err;
    while (celfw_stream_reset(fw->stream, &err) == CELFW_STREAM_ERROR) {
        fw->stream_errors++;
        say("event", "stream error at byte %llu: %s; scene kept", (unsigned long long)err.offset,
            err.what);
        report(fw, err.what, -1.0);
    }
}

static void on_note(void *user, const char *what)
{
    (void)user;
    say("event", "%s", what);
}

/* ------------------------------------------------------------- status */

static const char *display_state(const celfw *fw)
{
    return fw->disp->ops->connected(fw->disp) ? "up" : "absent";
}

static void status(celfw *fw, const char *kind, const char *extra)
{
    uint64_t now = lx_now(&lx_clock_monotonic);
    bool final = !strcmp(kind, "exit"); /* the exit line gives the whole run's rate */
    uint64_t since = final ? fw->t0 : fw->last_log, base = final ? 0 : fw->frames_at_log;
    double dt = (double)(now - since) / 1e9;
    double fps = dt > 0 ? (double)(fw->frames - base) / dt : 0.0;
    say(kind,
        "%st=%.2f frames=%llu dropped=%llu misses=%llu stream_bytes=%llu stream_errors=%llu commits=%llu "
        "display=%s lines_sent=%llu rects=%llu bytes_raw=%llu bytes_wire=%llu gpio_writes=%llu "
        "retries=%llu errors=%llu fps=%.1f anim_t=%.9g",
        extra, (double)(now - fw->t0) / 1e9, (unsigned long long)fw->frames,
        (unsigned long long)fw->dropped, (unsigned long long)fw->sum.line_misses,
        (unsigned long long)fw->stream_bytes, (unsigned long long)fw->stream_errors,
        (unsigned long long)fw->commits, display_state(fw), (unsigned long long)fw->sum.lines_sent,
        (unsigned long long)fw->sum.rects, (unsigned long long)fw->sum.bytes_raw,
        (unsigned long long)fw->sum.bytes_wire, (unsigned long long)fw->sum.writes,
        (unsigned long long)fw->sum.retries, (unsigned long long)(fw->sum.errors + fw->failures), fps,
        fw->anim_t);
    fw->last_log = now;
    fw->frames_at_log = fw->frames;
    if (!final)
        report(fw, NULL, fps);
}

static void add_stats(lx_frame_stats *a, const lx_frame_stats *b)
{
    a->lines_rendered += b->lines_rendered;
    a->lines_sent += b->lines_sent;
    a->rects += b->rects;
    a->bytes_raw += b->bytes_raw;
    a->bytes_wire += b->bytes_wire;
    a->writes += b->writes;
    a->line_misses += b->line_misses;
    a->retries += b->retries;
    a->errors += b->errors;
}

/* ------------------------------------------------------------- set-up */

static int open_display(celfw *fw)
{
    char err[320] = "";
    lx_status s;
    celfw_config *c = &fw->cfg;
    switch (c->backend) {
    case CELFW_GPIO:
        s = hub75_open(&fw->disp, &c->hub75, &lx_clock_monotonic, err, sizeof err);
        break;
    case CELFW_USB:
        c->usb.width = c->width;
        c->usb.height = c->height;
        s = gud_open(&fw->disp, &c->usb, &lx_clock_monotonic, backend_log, fw, err, sizeof err);
        break;
    default:
        s = lx_null_open(&fw->disp, c->width, c->height, &lx_clock_monotonic);
        if (s != LX_OK)
            snprintf(err, sizeof err, "null display: %s", lx_status_str(s));
        break;
    }
    if (s != LX_OK) {
        say("error", "%s", err[0] ? err : lx_status_str(s));
        return s == LX_ERR_CONFIG ? EXIT_CONFIG : EXIT_DISPLAY;
    }
    fw->disp->log = backend_log;
    fw->disp->log_user = fw;
    return 0;
}

static int load_scene(celfw *fw)
{
    const char *spec = fw->cfg.scene;
    cs_scene *s = fw->scene[fw->front];
    char err[400];
    if (!strncmp(spec, "builtin:", 8)) {
        if (!celfw_scene_build(spec + 8, s, 0.0f)) {
            say("error", "scene '%s': no such built-in scene (have: %s)", spec, celfw_scene_names());
            return EXIT_CONFIG;
        }
        snprintf(fw->builtin, sizeof fw->builtin, "%s", spec + 8);
    } else if (!strcmp(spec, "none") || !spec[0]) {
        cs_scene_init(s, (float)fw->src.opts.width, (float)fw->src.opts.height);
    } else if (!celfw_scene_json(spec, s, err, sizeof err)) {
        say("error", "scene %s", err);
        return EXIT_CONFIG;
    }
    memcpy(fw->scene[fw->front ^ 1], s, sizeof *s);
    return 0;
}

static int bench_gpio(celfw *fw)
{
    const hub75_config *c = &fw->cfg.hub75;
    double wps = hub75_measure_writes(fw->disp, 20000);
    if (wps <= 0) {
        say("error", "bench-gpio: writing the lines failed");
        return EXIT_DISPLAY;
    }
    double wns = 1e9 / wps;
    say("bench", "chip=%s writes_per_s=%.0f ns_per_write=%.0f", c->chip, wps, wns);
    for (int planes = 1; planes <= HUB75_MAX_PLANES; planes++) {
        hub75_config k = *c;
        k.planes = planes;
        say("bench", "panel=%dx%d chain=%d scan=1/%d planes=%d lsb_ns=%u writes_per_frame=%llu refresh_hz=%.1f",
            k.panel_w, k.panel_h, k.chain, hub75_scan(&k), planes, k.lsb_ns,
            (unsigned long long)hub75_writes_per_frame(&k), hub75_refresh_estimate(&k, wns));
    }
    return 0;
}

/* ----------------------------------------------------------------- loop */

static void wait_and_serve(celfw *fw, uint64_t until)
{
    static const celfw_input_sink sink_proto = {NULL, on_bytes, on_reset, on_note};
    celfw_input_sink sink = sink_proto;
    sink.user = fw;
    if (fw->in)
        celfw_input_tick(fw->in, &sink);
    do {
        struct pollfd pfd[2];
        int n = fw->in ? celfw_input_pollfds(fw->in, pfd, 2) : 0;
        uint64_t now = lx_now(&lx_clock_monotonic);
        uint64_t left = until > now ? until - now : 0;
        struct timespec ts = {(time_t)(left / 1000000000u), (long)(left % 1000000000u)};
        int r = ppoll(pfd, (nfds_t)n, &ts, NULL);
        if (r > 0)
            celfw_input_service(fw->in, pfd, n, &sink);
    } while (!stop_signal && lx_now(&lx_clock_monotonic) < until);
}

static const char *run(celfw *fw)
{
    const celfw_config *c = &fw->cfg;
    uint64_t period = c->fps > 0 ? (uint64_t)(1e9 / c->fps) : 0;
    uint64_t next = lx_now(&lx_clock_monotonic);
    fw->t0 = fw->last_log = next;
    uint64_t log_every = (uint64_t)(c->log_interval * 1e9);
    uint64_t render_errors = 0;
    for (;;) {
        uint64_t start = lx_now(&lx_clock_monotonic);
        celfw_notify_alive(&fw->notify, start); /* a hung loop stops the pings */
        fw->anim_t = c->time_step > 0 ? (double)fw->iterations * c->time_step : (double)(start - fw->t0) / 1e9;
        float t = (float)fw->anim_t;
        fw->anim_t = t; /* report the value the renderer used */
        if (fw->builtin[0] && celfw_scene_animated(fw->builtin))
            celfw_scene_build(fw->builtin, fw->scene[fw->front], t);
        lx_scene_source_set(&fw->src, fw->scene[fw->front], t);
        fw->disp->frame_start_ns = start;
        fw->disp->frame_period_ns = period;
        lx_frame_stats st = {0};
        lx_status s = fw->disp->ops->present(fw->disp, &fw->src.src, &st);
        add_stats(&fw->sum, &st);
        fw->iterations++;
        if (s == LX_OK) {
            fw->frames++;
            if (!fw->display_up)
                fw->display_up = true;
            if (fw->src.err.status != CS_OK && !fw->render_warned) {
                fw->render_warned = true;
                say("event", "render: %s (cel %d region %d contour %d); frames go on without it",
                    cs_status_str(fw->src.err.status), fw->src.err.cel, fw->src.err.region,
                    fw->src.err.contour);
            }
        } else if (s == LX_ERR_NO_DEVICE) {
            fw->dropped++;
            if (fw->display_up)
                say("event", "display lost: %s", fw->disp->err);
            fw->display_up = false;
        } else if (s == LX_ERR_CONFIG) {
            say("error", "%s", fw->disp->err);
            return "error";
        } else {
            /* at panel rates a persistent fault would flood the log: say it
             * the first few times, then every thousandth */
            fw->failures++;
            bool tell = fw->failures <= 3 || fw->failures % 1000 == 0;
            if (s == LX_ERR_RENDER && render_errors++ < 3)
                say("event", "render failed: %s (%s)", cs_status_str(fw->src.err.status), fw->disp->err);
            else if (s != LX_ERR_RENDER && tell)
                say("event", "frame failed (%llu so far): %s: %s", (unsigned long long)fw->failures,
                    lx_status_str(s), fw->disp->err);
        }
        uint64_t now = lx_now(&lx_clock_monotonic);
        if (log_every && now - fw->last_log >= log_every)
            status(fw, "status", "");
        if (stop_signal)
            return "signal";
        if (c->max_frames && fw->frames >= c->max_frames)
            return "frames";
        if (c->duration > 0 && (double)(now - fw->t0) / 1e9 >= c->duration)
            return "duration";
        if (period) {
            next += period;
            if (next < now)
                next = now; /* late: start the next frame at once, without a burst */
        } else {
            /* unpaced; but with the display away, do not spin on reconnects */
            next = s == LX_ERR_NO_DEVICE ? now + 5000000u : now;
        }
        wait_and_serve(fw, next);
    }
}

int main(int argc, char **argv)
{
    static celfw fw_storage;
    celfw *fw = &fw_storage;
    char err[512];
    celfw_config_default(&fw->cfg);
    int pr = celfw_config_parse(&fw->cfg, argc, argv, err, sizeof err);
    if (pr > 0)
        return 0;
    if (pr < 0 || !celfw_config_check(&fw->cfg, err, sizeof err)) {
        say("error", "%s", err);
        return EXIT_CONFIG;
    }
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGINT, &sa, NULL);
    signal(SIGPIPE, SIG_IGN);

    int rc = open_display(fw);
    if (rc)
        return rc;
    if (fw->cfg.bench_gpio) {
        rc = bench_gpio(fw);
        fw->disp->ops->close(fw->disp);
        return rc;
    }
    fw->scene[0] = calloc(1, sizeof(cs_scene));
    fw->scene[1] = calloc(1, sizeof(cs_scene));
    fw->stream = celfw_stream_new();
    if (!fw->scene[0] || !fw->scene[1] || !fw->stream ||
        lx_scene_source_init(&fw->src, fw->disp->width, fw->disp->height, fw->cfg.aa,
                             fw->cfg.subscanlines) != LX_OK) {
        say("error", "out of memory for %dx%d", fw->disp->width, fw->disp->height);
        fw->disp->ops->close(fw->disp);
        return EXIT_DISPLAY;
    }
    if ((rc = celfw_wall_setup(&fw->src, &fw->cfg, fw->disp, err, sizeof err)) != 0) {
        say("error", "%s", err);
        fw->disp->ops->close(fw->disp);
        return rc;
    }
    if ((rc = load_scene(fw)) != 0) {
        fw->disp->ops->close(fw->disp);
        return rc;
    }
    if (celfw_input_open_with(&fw->in, fw->cfg.input, &fw->cfg.mqtt, err, sizeof err) != 0) {
        say("error", "%s", err);
        fw->disp->ops->close(fw->disp);
        return EXIT_INPUT;
    }
    fw->display_up = fw->disp->ops->connected(fw->disp);
    char aa[16];
    if (fw->cfg.aa == CS_AA_NONE)
        snprintf(aa, sizeof aa, "none");
    else
        snprintf(aa, sizeof aa, "%d", fw->cfg.subscanlines);
    say("start", "backend=%s display=%dx%d fps=%g aa=%s input=%s scene=%s decoder=%s display_state=%s",
        fw->disp->ops->name, fw->disp->width, fw->disp->height, fw->cfg.fps, aa,
        celfw_input_describe(fw->in), fw->cfg.scene, celfw_stream_available() ? "cel-stream" : "none",
        display_state(fw));
    if (!celfw_stream_available() && strcmp(fw->cfg.input, "none") != 0)
        say("event", "stream decoder not in this build: input bytes are counted, not decoded");
    celfw_notify_ready(&fw->notify, lx_now(&lx_clock_monotonic), "showing %s on %s %dx%d",
                       fw->cfg.scene, fw->disp->ops->name, fw->disp->width, fw->disp->height);

    const char *why = run(fw);
    celfw_notify_stopping();
    char reason[64];
    snprintf(reason, sizeof reason, "reason=%s ", why);
    status(fw, "exit", reason);
    fw->disp->ops->close(fw->disp);
    celfw_input_close(fw->in);
    celfw_stream_free(fw->stream);
    lx_scene_source_free(&fw->src);
    free(fw->scene[0]);
    free(fw->scene[1]);
    return strcmp(why, "error") == 0 ? EXIT_DISPLAY : 0;
}
