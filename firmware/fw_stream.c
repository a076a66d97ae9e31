/*
 * fw_stream.c - cel stream ingress on MCU boards (see fw_stream.h).
 *
 * The decoder's state is one static cs_stream. Its back store is the
 * render workspace (fw_render_staging), so at a commit the new scene is
 * copied out into the front store before anything renders, and the decoder
 * is restarted on the same pair of stores with the front marked valid
 * (cs_stream_init documents exactly that use: a front store that already
 * holds the scene on display). Restarting loses nothing: after a commit
 * the decoder is between transactions with an empty header window; only
 * its byte count starts again, so the offset of the restart (the bytes
 * it had consumed) is kept here and added to every reported offset.
 */
#include "fw_stream.h"

#include "board_api.h"
#include "celscan_private.h"
#include "fw_print.h"
#include "fw_render.h"
#include "rx_ring.h"

static cs_stream stream;
static cs_scene *front_store;
static uint64_t base;      /* link bytes before the decoder's last restart */
static uint64_t fed;       /* bytes the decoder consumed since then */
static uint32_t commits, errors;

/* ------------------------------------------------------------ requests */

/* Seconds as decimal text: "0", "1.25", "-0.5". The value is N / 10^k for
 * the digits N (below 2^24) and k decimals, in single precision: both are
 * exact floats, so the one division rounds the exact decimal correctly,
 * which is what strtof does with the same text on the host. */
static int parse_time(const char *s, int n, float *out)
{
    static const float pow10[8] = {1e0f, 1e1f, 1e2f, 1e3f, 1e4f, 1e5f, 1e6f, 1e7f};
    int i = 0, decimals = -1, digits = 0;
    bool neg = false;
    uint32_t v = 0;
    if (i < n && s[i] == '-') {
        neg = true;
        i++;
    }
    for (; i < n; i++) {
        if (s[i] == '.' && decimals < 0) {
            decimals = 0;
        } else if (s[i] >= '0' && s[i] <= '9') {
            v = v * 10u + (uint32_t)(s[i] - '0');
            digits++;
            if (decimals >= 0)
                decimals++;
            if (v >= (1u << 24) || decimals > 7)
                return 0;
        } else {
            return 0;
        }
    }
    if (!digits)
        return 0;
    float t = (float)v / pow10[decimals < 0 ? 0 : decimals];
    *out = neg ? -t : t;
    return 1;
}

/* A decimal number in s[0..n), at most 65535. */
static int parse_num(const char *s, int n, uint32_t *out)
{
    uint32_t v = 0;
    if (n < 1)
        return 0;
    for (int i = 0; i < n; i++) {
        if (s[i] < '0' || s[i] > '9')
            return 0;
        v = v * 10u + (uint32_t)(s[i] - '0');
        if (v > 65535u)
            return 0;
    }
    *out = v;
    return 1;
}

/* One entry "WxH@T[:A]" in s[0..n). */
static int parse_req(const char *s, int n, fw_frame_req *f)
{
    int x = -1, at = -1, colon = -1;
    for (int i = 0; i < n; i++) {
        if (s[i] == 'x' && x < 0)
            x = i;
        else if (s[i] == '@' && at < 0)
            at = i;
        else if (s[i] == ':' && colon < 0)
            colon = i;
    }
    int tend = colon < 0 ? n : colon;
    uint32_t w, h, aa = 16;
    if (x < 1 || at < x + 2 || tend <= at + 1 || tend - at - 1 >= (int)sizeof f->time_text ||
        !parse_num(s, x, &w) || !parse_num(s + x + 1, at - x - 1, &h) || w < 1 || h < 1 ||
        !parse_time(s + at + 1, tend - at - 1, &f->time))
        return 0;
    if (colon >= 0) {
        const char *a = s + colon + 1;
        int an = n - colon - 1;
        if (an == 4 && a[0] == 'n' && a[1] == 'o' && a[2] == 'n' && a[3] == 'e')
            aa = 0;
        else if (!parse_num(a, an, &aa) || aa < 1 || aa > CS_CFG_MAX_SUBSCANLINES)
            return 0;
    }
    f->width = (uint16_t)w;
    f->height = (uint16_t)h;
    f->subscan = (uint8_t)aa;
    f->repeat = f->step_ms = 0;
    for (int i = 0; i < tend - at - 1; i++)
        f->time_text[i] = s[at + 1 + i];
    f->time_text[tend - at - 1] = 0;
    return 1;
}

int fw_frames_parse(const char *text, fw_frame_req *out, int max)
{
    int count = 0;
    const char *p = text;
    while (*p) {
        int n = 0;
        while (p[n] && p[n] != ',')
            n++;
        if (count == max || !parse_req(p, n, &out[count])) {
            fw_print("frames=: bad or too many entries at '%s' (want WxH@T[:A],... at most %d)\n",
                     p, max);
            return -1;
        }
        count++;
        p += n;
        if (*p == ',')
            p++;
    }
    return count;
}

cs_render_opts fw_frame_opts(const fw_frame_req *f)
{
    cs_render_opts o = cs_render_defaults(f->width, f->height);
    o.aa = f->subscan ? CS_AA_SUBSCAN : CS_AA_NONE;
    o.subscanlines = f->subscan ? f->subscan : 1;
    o.time = f->time;
    return o;
}

/* -------------------------------------------------------------- decoder */

void fw_stream_start(cs_scene *front, bool front_valid)
{
    front_store = front;
    base = fed = 0;
    commits = errors = 0;
    cs_stream_init(&stream, front, front_valid, fw_render_staging());
}

/* The committed scene sits in the staging store: copy it to the front and
 * restart the decoder there (see the top of the file). */
static void adopt_commit(void)
{
    cs_scene_copy(front_store, fw_render_staging());
    base += fed;
    fed = 0;
    cs_stream_init(&stream, front_store, true, fw_render_staging());
    fw_render_forget(); /* a new scene: the next frame is drawn whole */
    commits++;
    const cs_scene *s = front_store;
    fw_print("stream commit %u at byte %llu: %u cels, %u regions, %u contours, %u points, "
             "%u tracks\n",
             (unsigned)commits, (unsigned long long)base, (unsigned)s->cel_count,
             (unsigned)s->region_count, (unsigned)s->contour_count, (unsigned)s->point_count,
             (unsigned)s->track_count);
}

/* The host reader's one-line message (cels_format_error), offsets made
 * absolute. */
static void report(const cs_stream_error *e)
{
    char text[256];
    errors++;
    cs_stream_error_text(e, base, text, sizeof text);
    fw_print("stream error: byte %llu: %s\n", (unsigned long long)(base + e->at), text);
}

static int handle(cs_stream_event ev)
{
    if (ev == CS_STREAM_COMMIT)
        adopt_commit();
    else if (ev == CS_STREAM_ERROR)
        report(cs_stream_last_error(&stream));
    return ev != CS_STREAM_MORE;
}

int fw_stream_byte(uint8_t byte)
{
    const uint8_t *p = &byte;
    size_t left = 1;
    int events = 0;
    for (;;) {
        size_t used;
        cs_stream_event ev = cs_stream_feed(&stream, p, left, &used);
        p += used;
        left -= used;
        fed += used;
        if (ev == CS_STREAM_MORE)
            return events; /* every byte consumed, nothing queued */
        events += handle(ev);
    }
}

int fw_stream_gap(void)
{
    int events = 0;
    cs_stream_event ev;
    while ((ev = cs_stream_gap(&stream)) != CS_STREAM_MORE)
        events += handle(ev);
    return events;
}

void fw_stream_link_report(void)
{
    const rx_ring *ring = board_link_ring();
    fw_print("link: ring high-water %u of %u bytes, %u gaps\n", (unsigned)ring->high,
             (unsigned)ring->mask + 1u, (unsigned)ring->gaps);
}

int fw_stream_finish(void)
{
    int events = 0;
    cs_stream_event ev;
    while ((ev = cs_stream_finish(&stream)) != CS_STREAM_MORE)
        events += handle(ev);
    return events;
}

bool fw_stream_busy(void)
{
    return cs_stream_busy(&stream);
}

const cs_scene *fw_stream_scene(void)
{
    return cs_stream_scene(&stream);
}

uint32_t fw_stream_commits(void)
{
    return commits;
}

uint32_t fw_stream_errors(void)
{
    return errors;
}

/* ------------------------------------------------------------ test flow */

static int render_requests(const fw_frame_req *reqs, int n)
{
    const cs_scene *scene = fw_stream_scene();
    int failed = 0;
    if (!scene)
        return 0;
    for (int i = 0; i < n; i++) {
        /* A repeated request: frames at its time (in whole milliseconds)
         * plus k steps, each time the float of its decimal text. */
        uint32_t ms = (uint32_t)(reqs[i].time * 1000.0f + 0.5f);
        for (uint32_t k = 0; k < (reqs[i].repeat ? reqs[i].repeat : 1u); k++) {
            char label[16], aa[8] = "none", when[16];
            fw_format(label, sizeof label, "frame %u", (unsigned)fw_render_frames());
            if (reqs[i].subscan)
                fw_format(aa, sizeof aa, "%u", (unsigned)reqs[i].subscan);
            cs_render_opts o = fw_frame_opts(&reqs[i]);
            if (reqs[i].repeat) {
                uint32_t t = ms + k * reqs[i].step_ms;
                o.time = (float)t / 1000.0f;
                fw_format(when, sizeof when, "%u.%03u", (unsigned)(t / 1000u),
                          (unsigned)(t % 1000u));
            }
            fw_print("%s size %ux%u time %s aa %s commit %u\n", label, (unsigned)reqs[i].width,
                     (unsigned)reqs[i].height, reqs[i].repeat ? when : reqs[i].time_text, aa,
                     (unsigned)commits);
            failed += fw_render(scene, &o, label, false);
        }
    }
    return failed;
}

int fw_stream_run(uint32_t expect, uint32_t idle_ms, const fw_frame_req *reqs, int n, bool each)
{
    uint32_t got = 0;
    int failed = 0;
    bool pending = false;
    uint64_t last = board_time_us();
    while (got < expect) {
        uint8_t b;
        int r = board_link_read(&b);
        if (r != 0) {
            got += r > 0;
            last = board_time_us();
            pending |= (r > 0 ? fw_stream_byte(b) : fw_stream_gap()) > 0;
        } else if (board_time_us() - last > (uint64_t)idle_ms * 1000u) {
            fw_print("stream: link idle for %u ms after %u of %u bytes\n", (unsigned)idle_ms,
                     (unsigned)got, (unsigned)expect);
            failed++;
            break;
        }
        /* Between transactions the workspace is free: show what changed. */
        if (each && pending && !fw_stream_busy()) {
            failed += render_requests(reqs, n);
            pending = false;
        }
    }
    pending |= fw_stream_finish() > 0;
    if (!each && !fw_stream_scene()) {
        fw_print("stream: nothing committed, no frame to render\n");
        failed++;
    } else if (pending || !each) {
        failed += render_requests(reqs, n);
    }
    fw_print("stream: %u bytes, %u commits, %u errors\n", (unsigned)got, (unsigned)commits,
             (unsigned)errors);
    fw_stream_link_report();
    return failed;
}
