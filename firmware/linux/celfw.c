/*
 * celfw.c - the firmware of Linux display boards: stream in, frames out, forever.
 *
 * celfw opens its input (TCP, tty, stdin or a file) and its display (HUB75
 * through GPIO, a GUD display through USB, or nothing), then loops: render a
 * frame at the animation clock's time, pulling lines as the display wants
 * them, then wait for the next frame slot while feeding whatever input
 * arrived to the stream decoder. A commit swaps the two scene stores between
 * frames, so a frame never mixes two scenes. A frame slower than its budget
 * (a 16,000-point scene on a big panel) does not starve the input: between
 * lines, every few milliseconds, celfw reads what arrived and holds the whole frames (up
 * to CELFW_HOLD_MAX) until the picture is out, then applies them. The display
 * may come and go (USB); the loop keeps its clock and counts frames it could
 * not show. Animation time comes from celfw_clock.c (integer nanoseconds,
 * from the commit that brought the animation, or the stream's epoch).
 *
 * Every input's bytes take one path (on_bytes): cut into whole frames per
 * connection or file (celfw_frame.c), checked against the trusted keys
 * (celfw_trust.c: with any key, only transactions signed by one with a fresh
 * sequence number pass; the rest are refused whole with one word why), then
 * decoded; a signed transaction's sequence is recorded once it commits.
 *
 * Everything worth knowing goes to stderr as one line per event, in a form
 * scripts can parse (repeated kinds of event are rate-limited, celfw_log.h):
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

#include "celfw_clock.h"
#include "celfw_config.h"
#include "celfw_input.h"
#include "celfw_log.h"
#include "celfw_notify.h"
#include "celfw_scenes.h"
#include "celfw_stream.h"
#include "celfw_trust.h"
#include "celfw_wall.h"
#include "celscan_private.h"
#include "gud_host.h"
#include "hub75.h"
#include "kms.h"
#include "display.h"
#include "lx_scene_source.h"

enum { EXIT_CONFIG = 2, EXIT_INPUT = 3, EXIT_DISPLAY = 4 };
/* Kinds of event line that a sender can repeat at will, each rate-limited. */
enum { LOG_COMMIT, LOG_STREAM_ERROR, LOG_REFUSED, LOG_INPUT, LOG_KINDS };
static const char *const log_kind_name[LOG_KINDS] = {"stream commit", "stream error", "stream refused",
                                                     "input"};

/* Input is read between the lines of a frame at most this often... */
#define CELFW_SERVE_NS 4000000u
/* ...and held until the frame is out, up to this much (plus one read). */
#define CELFW_HOLD_MAX (1u << 20)

typedef struct celfw {
    celfw_config cfg;
    hal_display *disp;
    lx_scene_source src;
    cs_scene *scene[2];
    int front;
    char builtin[32];        /* a built-in scene being shown, "" otherwise */
    celfw_input *in;
    celfw_stream *stream;
    celfw_trust *trust;
    celfw_ratelimit limit[LOG_KINDS];
    uint64_t frames, dropped, stream_bytes, stream_errors, commits, failures, slow;
    uint64_t applied_seq;    /* the shown stream's signature sequence; 0 if unsigned */
    hal_frame_stats sum;
    cs_damage damage;        /* what the last frame showed, for the next one's window */
    bool display_up, render_warned;
    celfw_clock clk;         /* which animation time each frame shows */
    hal_clock wall_at;        /* --clock at:S: a wall clock that stays at cfg.clock_at_ns */
    char refusal[200];       /* why the last commit was refused */
    bool in_frame;           /* a frame is rendering: whole frames are held, not decoded */
    uint8_t *held;           /* held_frame records, each followed by its frame's bytes */
    size_t held_n, held_cap;
    uint64_t last_serve;
    float anim_t;            /* the last frame's, as the renderer took it */
    uint64_t t0, last_log, frames_at_log, pixels_at_log;
    celfw_notify notify; /* READY and watchdog pings to systemd */
} celfw;

static volatile sig_atomic_t stop_signal;

/* The fixed wall clock of --clock at:S. The wall clock never paces anything,
 * so its wait is never called; it returns at once, as for a time passed. */
static uint64_t fixed_now(void *user)
{
    return *(const uint64_t *)user;
}

static void fixed_wait_until(void *user, uint64_t t)
{
    (void)user;
    (void)t;
}

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

static void say_held(int kind, uint64_t held)
{
    if (held)
        say("event", "%llu more '%s' lines not shown (at most %d per %d s)", (unsigned long long)held,
            log_kind_name[kind], CELFW_LOG_BURST, CELFW_LOG_WINDOW_S);
}

/* An event line of a kind a sender can repeat: rate-limited (celfw_log.h). */
static void tell(celfw *fw, int kind, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void tell(celfw *fw, int kind, const char *fmt, ...)
{
    uint64_t held;
    bool allow = celfw_ratelimit_allow(&fw->limit[kind], hal_now(&hal_clock_monotonic), &held);
    say_held(kind, held);
    if (!allow)
        return;
    char msg[600];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    say("event", "%s", msg);
}

/* Tells the counts held back in windows that have ended (every kind, at exit). */
static void tell_held(celfw *fw, bool final)
{
    uint64_t now = hal_now(&hal_clock_monotonic);
    for (int k = 0; k < LOG_KINDS; k++)
        say_held(k, celfw_ratelimit_due(&fw->limit[k], now, final));
}

/* ------------------------------------------------------------- stream */

/* Tells the input what the sign shows (a fleet input publishes it):
 * after a commit or an error, and with the frame rate from status(). */
static void report(celfw *fw, const char *error, double fps)
{
    celfw_report r = {fw->commits, fw->stream_errors, fps, error, fw->applied_seq};
    celfw_input_report(fw->in, &r);
}

static void stream_error(celfw *fw, const celfw_stream_error *err)
{
    fw->stream_errors++;
    tell(fw, LOG_STREAM_ERROR, "stream error at byte %llu: %s; scene kept", (unsigned long long)err->offset,
         err->what);
    report(fw, err->what, -1.0);
}

/* What the framer dropped (stray bytes, a cut or oversized frame), worded as the decoder words it. */
static void frame_error(celfw *fw, const celfw_frame *fr)
{
    celfw_stream_error err;
    celfw_stream_describe(fr->status, fr->what, fr->offset, fr->at, &err);
    stream_error(fw, &err);
}

/*
 * A committed scene that cannot render at the display's size (a canvas of
 * 1e-6 scaled beyond the coordinate limit, more segments than the renderer
 * holds) is refused here, before the swap, instead of failing every frame.
 */
static const char *check_commit(void *user, const cs_scene *next, cs_status *status, cs_error *where)
{
    celfw *fw = user;
    cs_status st = lx_scene_source_check(&fw->src, next, where);
    if (st == CS_OK)
        return NULL;
    *status = st;
    snprintf(fw->refusal, sizeof fw->refusal, "commit refused: the scene (canvas %gx%g) cannot render at %dx%d",
             (double)next->canvas_w, (double)next->canvas_h, fw->src.src.width, fw->src.src.height);
    return fw->refusal;
}

/*
 * One whole frame of one input: the trust check, then the decoder. This is
 * the one place every transaction from every input passes. `src` is NULL
 * for a held frame whose sender has gone since.
 */
static void apply_frame(celfw *fw, celfw_framer *src, const celfw_frame *fr)
{
    celfw_trust_txn tx = {.txn = fr->data, .len = fr->len, .key = -1};
    if (fr->kind != CELFW_FRAME_STREAM) {
        celfw_verdict v = celfw_trust_check(fw->trust, fr->data, fr->len, fr->kind == CELFW_FRAME_SIGNED, &tx);
        if (v == CELFW_TRUST_MALFORMED) {
            celfw_stream_error err;
            /* damage is reported where the decoder reports it: at the CRC field */
            uint64_t at = tx.status == CS_ERR_STREAM_CRC ? fr->offset + fr->len - 4 : fr->offset;
            celfw_stream_describe(tx.status, tx.why, fr->offset, at, &err);
            stream_error(fw, &err);
            return;
        }
        if (v != CELFW_TRUST_PASS) {
            char what[300];
            snprintf(what, sizeof what, "%s: %s", celfw_verdict_word(v), tx.why);
            fw->stream_errors++;
            tell(fw, LOG_REFUSED, "stream refused at byte %llu: %s (transaction at byte %llu dropped); "
                 "scene kept", (unsigned long long)fr->offset, what, (unsigned long long)fr->offset);
            report(fw, what, -1.0);
            return;
        }
    }
    celfw_stream_error err = {0};
    cs_scene *shown = fw->scene[fw->front], *back = fw->scene[fw->front ^ 1];
    celfw_stream_result r = celfw_stream_frame(fw->stream, tx.txn, tx.len, fr->offset + tx.offset, shown, back,
                                               &err);
    if (r == CELFW_STREAM_COMMIT) {
        /* between frames: the next frame shows the new scene whole; the
         * old one becomes the decoder's scratch (a patch copies what is
         * shown before it edits) */
        fw->front ^= 1;
        fw->builtin[0] = 0;
        cs_damage_reset(&fw->damage); /* a commit is shown whole */
        celfw_clock_show(&fw->clk, fw->scene[fw->front ^ 1], fw->scene[fw->front], 0);
        fw->commits++;
        if (src)
            src->applied++; /* the sender's progress, for the input's time-out */
        tell(fw, LOG_COMMIT, "stream commit %llu applied", (unsigned long long)fw->commits);
        char why[400];
        if (celfw_trust_applied(fw->trust, &tx, why, sizeof why) != 0)
            say("error", "the commit is shown but its sequence was not saved (a restart would accept "
                "it again): %s", why);
        fw->applied_seq = tx.key >= 0 ? tx.sequence : 0;
        report(fw, NULL, -1.0);
    } else if (r == CELFW_STREAM_ERROR) {
        stream_error(fw, &err);
    }
}

/*
 * A whole frame that arrived while a frame rendered: applying it then
 * could swap scenes mid-frame, so it is copied here and applied in order
 * once the frame is out. The record is followed by the frame's bytes,
 * padded to keep the next record aligned.
 */
typedef struct held_frame {
    celfw_framer *src;
    celfw_frame_kind kind;
    uint64_t offset;
    size_t len;
} held_frame;

#define HELD_ALIGN(n) (((n) + 7u) & ~(size_t)7u)

static void hold_frame(celfw *fw, celfw_framer *src, const celfw_frame *fr)
{
    size_t need = sizeof(held_frame) + HELD_ALIGN(fr->len);
    if (fw->held_n + need > fw->held_cap) {
        size_t cap = fw->held_cap ? fw->held_cap : 65536;
        while (cap < fw->held_n + need)
            cap *= 2;
        uint8_t *q = realloc(fw->held, cap);
        if (!q) {
            /* cannot happen within CELFW_HOLD_MAX on a board that started;
             * if it does, say what was lost */
            fw->stream_errors++;
            say("event", "out of memory holding a %zu-byte transaction at byte %llu during a frame: dropped",
                fr->len, (unsigned long long)fr->offset);
            return;
        }
        fw->held = q;
        fw->held_cap = cap;
    }
    held_frame h = {src, fr->kind, fr->offset, fr->len};
    memcpy(fw->held + fw->held_n, &h, sizeof h);
    memcpy(fw->held + fw->held_n + sizeof h, fr->data, fr->len);
    fw->held_n += need;
}

static void on_bytes(void *user, celfw_framer *src, const uint8_t *p, size_t n)
{
    celfw *fw = user;
    fw->stream_bytes += n;
    celfw_frame fr;
    do {
        size_t used = celfw_framer_push(src, p, n, &fr);
        p += used;
        n -= used;
        if (fr.kind == CELFW_FRAME_ERROR)
            frame_error(fw, &fr);
        else if (fr.kind != CELFW_FRAME_NONE && fw->in_frame)
            hold_frame(fw, src, &fr);
        else if (fr.kind != CELFW_FRAME_NONE)
            apply_frame(fw, src, &fr);
    } while (fr.kind != CELFW_FRAME_NONE);
}

static void on_reset(void *user, celfw_framer *src, const char *why)
{
    (void)why;
    celfw *fw = user;
    /* held frames of this sender still apply (they came whole), but its
     * framer is about to serve someone else */
    for (size_t at = 0; at < fw->held_n;) {
        held_frame h;
        memcpy(&h, fw->held + at, sizeof h);
        if (h.src == src) {
            h.src = NULL;
            memcpy(fw->held + at, &h, sizeof h);
        }
        at += sizeof h + HELD_ALIGN(h.len);
    }
    celfw_frame fr;
    if (celfw_framer_end(src, &fr))
        frame_error(fw, &fr);
}

/* The frame is out: apply what was held during it, in the order it came. */
static void release_held(celfw *fw)
{
    fw->in_frame = false;
    for (size_t at = 0; at < fw->held_n;) {
        held_frame h;
        memcpy(&h, fw->held + at, sizeof h);
        celfw_frame fr = {.kind = h.kind, .data = fw->held + at + sizeof h, .len = h.len, .offset = h.offset};
        apply_frame(fw, h.src, &fr);
        at += sizeof h + HELD_ALIGN(h.len);
    }
    fw->held_n = 0;
}

static void on_note(void *user, const char *what)
{
    tell(user, LOG_INPUT, "%s", what);
}

/* ------------------------------------------------------------- status */

/* The backend as --backend names it (the display's own name, which prefixes
 * its messages, is "hub75" for the gpio backend). */
static const char *backend_name(celfw_backend b)
{
    static const char *const names[] = {[CELFW_NULL] = "null", [CELFW_GPIO] = "gpio", [CELFW_USB] = "usb",
                                        [CELFW_DRM] = "drm"};
    return names[b];
}

static const char *display_state(const celfw *fw)
{
    return hal_display_connected(fw->disp) ? "up" : "absent";
}

static void status(celfw *fw, const char *kind, const char *extra)
{
    uint64_t now = hal_now(fw->clk.mono);
    bool final = !strcmp(kind, "exit"); /* the exit line gives the whole run's rate */
    uint64_t since = final ? fw->t0 : fw->last_log, base = final ? 0 : fw->frames_at_log;
    double dt = (double)(now - since) / 1e9;
    double fps = dt > 0 ? (double)(fw->frames - base) / dt : 0.0;
    uint64_t px = fw->sum.pixels_rendered - (final ? 0 : fw->pixels_at_log);
    double px_frame = fw->frames > base ? (double)px / (double)(fw->frames - base) : 0.0;
    say(kind,
        "%st=%.2f frames=%llu dropped=%llu misses=%llu slow=%llu stream_bytes=%llu stream_errors=%llu commits=%llu "
        "display=%s lines_sent=%llu rects=%llu bytes_raw=%llu bytes_wire=%llu gpio_writes=%llu "
        "retries=%llu errors=%llu lines_rendered=%llu pixels_per_frame=%.0f fps=%.1f anim_t=%.9g",
        extra, (double)(now - fw->t0) / 1e9, (unsigned long long)fw->frames,
        (unsigned long long)fw->dropped, (unsigned long long)fw->sum.line_misses, (unsigned long long)fw->slow,
        (unsigned long long)fw->stream_bytes, (unsigned long long)fw->stream_errors,
        (unsigned long long)fw->commits, display_state(fw), (unsigned long long)fw->sum.lines_sent,
        (unsigned long long)fw->sum.rects, (unsigned long long)fw->sum.bytes_raw,
        (unsigned long long)fw->sum.bytes_wire, (unsigned long long)fw->sum.writes,
        (unsigned long long)fw->sum.retries, (unsigned long long)(fw->sum.errors + fw->failures),
        (unsigned long long)fw->sum.lines_rendered, px_frame, fps, (double)fw->anim_t);
    fw->last_log = now;
    fw->frames_at_log = fw->frames;
    fw->pixels_at_log = fw->sum.pixels_rendered;
    if (!final)
        report(fw, NULL, fps);
}

static void add_stats(hal_frame_stats *a, const hal_frame_stats *b)
{
    a->lines_rendered += b->lines_rendered;
    a->pixels_rendered += b->pixels_rendered;
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
    hal_status s;
    celfw_config *c = &fw->cfg;
    switch (c->backend) {
    case CELFW_GPIO:
        s = hub75_open(&fw->disp, &c->hub75, &hal_clock_monotonic, err, sizeof err);
        break;
    case CELFW_USB:
        c->usb.width = c->width;
        c->usb.height = c->height;
        s = gud_open(&fw->disp, &c->usb, &hal_clock_monotonic, backend_log, fw, err, sizeof err);
        break;
    case CELFW_DRM:
        s = kms_open(&fw->disp, &c->drm, &hal_clock_monotonic, backend_log, fw, err, sizeof err);
        break;
    default:
        s = hal_null_open(&fw->disp, c->width, c->height, &hal_clock_monotonic);
        if (s != HAL_OK)
            snprintf(err, sizeof err, "null display: %s", hal_status_str(s));
        break;
    }
    if (s != HAL_OK) {
        say("error", "%s", err[0] ? err : hal_status_str(s));
        return s == HAL_ERR_CONFIG ? EXIT_CONFIG : EXIT_DISPLAY;
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
    cs_status st;
    cs_error where;
    if (!fw->builtin[0] && (st = lx_scene_source_check(&fw->src, s, &where)) != CS_OK) {
        /* the same check as a stream's commit: refuse now, not every frame */
        char at[64] = "";
        if (where.cel >= 0)
            snprintf(at, sizeof at, " (cel %d, region %d, contour %d)", (int)where.cel, (int)where.region,
                     (int)where.contour);
        say("error", "scene %s (canvas %gx%g) cannot render at %dx%d: %s%s", spec, (double)s->canvas_w,
            (double)s->canvas_h, fw->src.src.width, fw->src.src.height, cs_status_str(st), at);
        return EXIT_CONFIG;
    }
    memcpy(fw->scene[fw->front ^ 1], s, sizeof *s);
    celfw_clock_show(&fw->clk, NULL, s, fw->builtin[0] ? celfw_scene_period_ns(fw->builtin) : 0);
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

/* Loads the trusted keys and the state of their sequences. */
static int open_trust(celfw *fw)
{
    const celfw_config *c = &fw->cfg;
    char err[600];
    fw->trust = celfw_trust_new();
    if (!fw->trust) {
        say("error", "libsodium cannot start (no entropy source?)");
        return EXIT_CONFIG;
    }
    for (int i = 0; i < c->trust_count; i++)
        if (celfw_trust_add_key(fw->trust, c->trust[i], err, sizeof err) != 0) {
            say("error", "%s", err);
            return EXIT_CONFIG;
        }
    if (c->state_dir[0]) {
        bool fresh = false;
        if (celfw_trust_open_state(fw->trust, c->state_dir, &fresh, err, sizeof err) != 0) {
            say("error", "%s", err);
            return EXIT_CONFIG;
        }
        if (fresh)
            say("event", "trust state %s/trust-state not there yet: no sequence applied so far", c->state_dir);
    }
    return 0;
}

/* ----------------------------------------------------------------- loop */

static celfw_input_sink sink_of(celfw *fw)
{
    celfw_input_sink sink = {fw, on_bytes, on_reset, on_note};
    return sink;
}

/* Polls the input until `until` (once, if it has passed) and serves it. */
static void serve(celfw *fw, uint64_t until)
{
    celfw_input_sink sink = sink_of(fw);
    struct pollfd pfd[CELFW_INPUT_MAX_FDS];
    int n = fw->in ? celfw_input_pollfds(fw->in, pfd, CELFW_INPUT_MAX_FDS) : 0;
    uint64_t now = hal_now(fw->clk.mono);
    uint64_t left = until > now ? until - now : 0;
    struct timespec ts = {(time_t)(left / 1000000000u), (long)(left % 1000000000u)};
    if (ppoll(pfd, (nfds_t)n, &ts, NULL) > 0)
        celfw_input_service(fw->in, pfd, n, &sink);
}

/* Render threads: a backend that pulls two lanes (HUB75) renders them itself. */
static int render_threads(const celfw *fw)
{
    return hal_display_lanes(fw->disp) == 1 ? fw->cfg.threads : 1;
}

/* Between the lines of a frame: read what arrived, every CELFW_SERVE_NS. */
static void serve_between_lines(void *user)
{
    celfw *fw = user;
    if (!fw->in || fw->held_n >= CELFW_HOLD_MAX)
        return; /* enough held: the rest waits in the socket buffers */
    uint64_t now = hal_now(fw->clk.mono);
    if (now - fw->last_serve < CELFW_SERVE_NS)
        return;
    fw->last_serve = now;
    serve(fw, 0);
}

static void wait_and_serve(celfw *fw, uint64_t until)
{
    celfw_input_sink sink = sink_of(fw);
    if (fw->in)
        celfw_input_tick(fw->in, &sink);
    tell_held(fw, false);
    do {
        serve(fw, until);
    } while (!stop_signal && hal_now(fw->clk.mono) < until);
    fw->last_serve = hal_now(fw->clk.mono);
}

static const char *run(celfw *fw)
{
    const celfw_config *c = &fw->cfg;
    uint64_t period = c->fps > 0 ? (uint64_t)(1e9 / c->fps) : 0;
    uint64_t next = hal_now(fw->clk.mono);
    fw->t0 = fw->last_log = next;
    uint64_t log_every = (uint64_t)(c->log_interval * 1e9);
    uint64_t render_errors = 0;
    for (;;) {
        uint64_t start = hal_now(fw->clk.mono);
        celfw_notify_alive(&fw->notify, start); /* a hung loop stops the pings */
        float t = fw->anim_t = celfw_clock_frame(&fw->clk, fw->scene[fw->front]);
        if (fw->builtin[0] && celfw_scene_animated(fw->builtin))
            celfw_scene_build(fw->builtin, fw->scene[fw->front], t);
        lx_scene_source_set(&fw->src, fw->scene[fw->front], t);
        fw->disp->frame_start_ns = start;
        fw->disp->frame_period_ns = period;
        hal_frame_stats st = {0};
        hal_window win;
        fw->in_frame = true;
        cs_damage *damage = fw->cfg.damage ? &fw->damage : NULL;
        hal_status s = lx_scene_source_show(&fw->src, fw->disp, damage, &win, &st);
        release_held(fw);
        add_stats(&fw->sum, &st);
        uint64_t took = hal_now(fw->clk.mono) - start;
        if (period && took > period && s == HAL_OK) {
            /* the lines went out as they were rendered; nothing was blanked */
            fw->slow++;
            if (fw->slow <= 3 || fw->slow % 1000 == 0)
                say("event", "slow frame: %.1f ms for a %.1f ms budget (%llu so far); input served between lines",
                    (double)took / 1e6, (double)period / 1e6, (unsigned long long)fw->slow);
        }
        if (s == HAL_OK) {
            fw->frames++;
            if (!fw->display_up)
                fw->display_up = true;
            if (fw->src.err.status != CS_OK && !fw->render_warned) {
                fw->render_warned = true;
                say("event", "render: %s (cel %d region %d contour %d); frames go on without it",
                    cs_status_str(fw->src.err.status), fw->src.err.cel, fw->src.err.region,
                    fw->src.err.contour);
            }
        } else if (s == HAL_ERR_NO_DEVICE) {
            fw->dropped++;
            if (fw->display_up)
                say("event", "display lost: %s", fw->disp->err);
            fw->display_up = false;
        } else if (s == HAL_ERR_CONFIG) {
            say("error", "%s", fw->disp->err);
            return "error";
        } else {
            /* at panel rates a persistent fault would flood the log: say it
             * the first few times, then every thousandth */
            fw->failures++;
            bool tell = fw->failures <= 3 || fw->failures % 1000 == 0;
            if (s == HAL_ERR_RENDER && render_errors++ < 3)
                say("event", "render failed: %s (%s)", cs_status_str(fw->src.err.status), fw->disp->err);
            else if (s != HAL_ERR_RENDER && tell)
                say("event", "frame failed (%llu so far): %s: %s", (unsigned long long)fw->failures,
                    hal_status_str(s), fw->disp->err);
        }
        uint64_t now = hal_now(fw->clk.mono);
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
            next = s == HAL_ERR_NO_DEVICE ? now + 5000000u : now;
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
        hal_display_close(fw->disp);
        return rc;
    }
    fw->scene[0] = calloc(1, sizeof(cs_scene));
    fw->scene[1] = calloc(1, sizeof(cs_scene));
    fw->stream = celfw_stream_new();
    if (!fw->scene[0] || !fw->scene[1] || !fw->stream ||
        lx_scene_source_init(&fw->src, fw->disp->width, fw->disp->height, fw->cfg.aa,
                             fw->cfg.subscanlines) != HAL_OK ||
        lx_scene_source_threads(&fw->src, render_threads(fw)) != HAL_OK) {
        say("error", "out of memory for %dx%d", fw->disp->width, fw->disp->height);
        hal_display_close(fw->disp);
        return EXIT_DISPLAY;
    }
    if ((rc = celfw_wall_setup(&fw->src, &fw->cfg, fw->disp, err, sizeof err)) != 0) {
        say("error", "%s", err);
        hal_display_close(fw->disp);
        return rc;
    }
    fw->wall_at = (hal_clock){&fw->cfg.clock_at_ns, fixed_now, fixed_wait_until};
    celfw_clock_init(&fw->clk, &hal_clock_monotonic, fw->cfg.clock_at ? &fw->wall_at : &hal_clock_realtime,
                     fw->cfg.realtime, fw->cfg.time_step);
    celfw_stream_set_check(fw->stream, check_commit, fw);
    fw->src.between_lines = serve_between_lines;
    fw->src.between_user = fw;
    if ((rc = load_scene(fw)) != 0) {
        hal_display_close(fw->disp);
        return rc;
    }
    if ((rc = open_trust(fw)) != 0) {
        hal_display_close(fw->disp);
        return rc;
    }
    if (celfw_input_open_with(&fw->in, fw->cfg.input, &fw->cfg.mqtt, err, sizeof err) != 0) {
        say("error", "%s", err);
        hal_display_close(fw->disp);
        return EXIT_INPUT;
    }
    celfw_input_set_timeout(fw->in, fw->cfg.input_timeout);
    fw->display_up = hal_display_connected(fw->disp);
    char aa[16];
    if (fw->cfg.aa == CS_AA_NONE)
        snprintf(aa, sizeof aa, "none");
    else
        snprintf(aa, sizeof aa, "%d", fw->cfg.subscanlines);
    say("start", "backend=%s display=%dx%d fps=%g aa=%s input=%s scene=%s decoder=%s display_state=%s "
        "trusted_keys=%d threads=%d damage=%s",
        backend_name(fw->cfg.backend), fw->disp->width, fw->disp->height, fw->cfg.fps, aa,
        celfw_input_describe(fw->in), fw->cfg.scene, "cel-stream",
        display_state(fw), celfw_trust_key_count(fw->trust), render_threads(fw),
        fw->cfg.damage && !fw->disp->api->present ? "on" : "off");
    if (celfw_input_public(fw->in) && celfw_trust_key_count(fw->trust) == 0)
        say("warning", "input %s listens beyond loopback and no key is trusted: anyone who can reach it "
            "can change the picture (celc keygen, then celfw --trust KEY.pub --state-dir DIR)",
            celfw_input_describe(fw->in));
    celfw_notify_ready(&fw->notify, hal_now(&hal_clock_monotonic), "showing %s on %s %dx%d",
                       fw->cfg.scene, backend_name(fw->cfg.backend), fw->disp->width, fw->disp->height);

    const char *why = run(fw);
    tell_held(fw, true);
    celfw_notify_stopping();
    char reason[64];
    snprintf(reason, sizeof reason, "reason=%s ", why);
    status(fw, "exit", reason);
    hal_display_close(fw->disp);
    celfw_input_close(fw->in);
    celfw_stream_free(fw->stream);
    celfw_trust_free(fw->trust);
    lx_scene_source_free(&fw->src);
    free(fw->scene[0]);
    free(fw->scene[1]);
    free(fw->held);
    return strcmp(why, "error") == 0 ? EXIT_DISPLAY : 0;
}
