/*
 * main_mcu.c - the firmware's main loop on microcontroller boards.
 *
 * Scenes arrive over the link as a cel stream (fw_stream.c: decoder,
 * commits, errors) and are rendered by fw_render.c; the firmware also
 * carries a few built-in scenes (firmware/scenes) for the host-identity
 * check of the renderer alone. Nothing is allocated; the image links no C
 * library at all. Every frame prints its CRC-32 in the `celsim --crc` line
 * format and, on QEMU, can be dumped for a pixel comparison
 * (tools/fw_qemu_test.sh).
 *
 * Command-line words (QEMU -append, on boards with BOARD_CMDLINE; a board
 * without a host to ask renders the built-in jobs, then plays), all optional:
 *   stream=N         read N bytes of cel stream from the link (UART), and
 *                    after every commit or error render frames= from the
 *                    scene on display
 *   frames=WxH@T[:A],...  the frames to render: size, time in seconds
 *                    (decimal), sub-scanlines or "none" (default 16, as
 *                    celsim); default: the panel at t=0
 *   render=each|end  frames after every stream event (default), or once at
 *                    the end of the stream
 *   repeat=N step_ms=M   render each of frames= N times, M ms apart (times in
 *                    whole milliseconds from the frame's own)
 *   damage=1         render and send only what changed since the last frame
 *                    (cs_frame_damage; the panel keeps the rest)
 *   idle_ms=N        give up on the link after N ms without a byte (5000)
 *   jobs=all|I,J,..  which built-in jobs to render (default all, none with stream=)
 *   scene=NAME size=WxH time_ms=T aa=N   one built-in frame of your choosing
 *   dump=DIR         frame dumps to the host (board's panel)
 *   fcrc=1           also print a CRC-32 of each frame's linear-light floats
 *   uart=N           read N bytes of link input first and report their CRC
 *   play=N           after the rest, play N frames of the demo (or the scene
 *                    the link commits meanwhile) at the board clock's time
 *   crash=stack|udf|div0   fault on purpose (tests the fault path)
 */
#include "board.h"
#include "board_api.h"
#include "celscan_private.h"
#include "cm_startup.h"
#include "fw_args.h"
#include "fw_print.h"
#include "fw_render.h"
#include "fw_scenes.h"
#include "fw_stream.h"

/* The scene on display: built by cs_scene_init (built-in scenes) or copied
 * whole from a commit before every use, so reset need not clear it. */
static cs_scene scene_store __attribute__((section(".noinit.scene_store")));

/* Renders one built-in job; returns 0 if the frame was produced without error. */
static int render_job(int index, const fw_job *job)
{
    const fw_scene_info *info = &fw_scenes[job->scene];
    cs_render_opts opts = fw_job_opts(job);
    char label[16];
    fw_format(label, sizeof label, "job %d", index);
    fw_print("job %d scene %s time_ms %u size %ux%u aa %u\n", index, info->name,
             (unsigned)job->time_ms, (unsigned)job->width, (unsigned)job->height,
             (unsigned)job->subscan);
    cs_error err;
    cs_status st = info->build(&scene_store, opts.time, &err);
    if (st != CS_OK) {
        fw_report_error(label, "scene", st, &err);
        return 1;
    }
    return fw_render(&scene_store, &opts, label, false);
}

/*
 * Playback: show the scene on display, animated by the board clock, and
 * take stream bytes between frames. Until the first commit that is the
 * built-in demo (rebuilt at each frame's time: it animates itself); after
 * it, the committed scene, whose tracks the core samples at the frame's
 * time. While a transaction streams in, the loop only reads the link (the
 * workspace holds the transaction) and the panel keeps the last frame; a
 * sender silent for a second in mid-transaction counts as gone, which
 * drops the transaction. On real glass (BOARD_DEMO_LOOP) it runs for ever,
 * printing every 64th frame; `play=N` runs N frames, each printed with its
 * time (milliseconds, so the host can render the same instant) and the
 * commit it shows, and returns the failures.
 */
static int play(uint32_t frames)
{
    fw_job job = fw_jobs[0];
    job.width = BOARD_PANEL_WIDTH;
    job.height = BOARD_PANEL_HEIGHT;
    cs_render_opts opts = fw_job_opts(&job);
    cs_error err;
    int failed = 0;
    if (fw_scenes[job.scene].build(&scene_store, 0.0f, &err) != CS_OK)
        return 1;
    fw_stream_start(&scene_store, true);
    uint64_t start = board_time_us(), last_byte = start;
    for (uint32_t frame = 0; !frames || frame < frames;) {
        uint8_t b;
        int r;
        while ((r = board_link_read(&b)) != 0) {
            if (r > 0)
                fw_stream_byte(b);
            else
                fw_stream_gap();
            last_byte = board_time_us();
        }
        if (fw_stream_busy()) {
            if (board_time_us() - last_byte > 1000000u)
                fw_stream_finish();
            continue;
        }
        uint32_t ms = (uint32_t)cm_udiv64(board_time_us() - start, 1000u, 0);
        opts.time = (float)ms / 1000.0f;
        if (fw_stream_commits() == 0 &&
            fw_scenes[job.scene].build(&scene_store, opts.time, &err) != CS_OK)
            continue;
        if (frames)
            fw_print("play %u time %u.%03u commit %u\n", (unsigned)frame, (unsigned)(ms / 1000u),
                     (unsigned)(ms % 1000u), (unsigned)fw_stream_commits());
        failed += fw_render(&scene_store, &opts, "play", !frames && frame % 64u != 0);
        frame++;
    }
    fw_print("play: %u frames, %u commits, %u errors\n", (unsigned)frames,
             (unsigned)fw_stream_commits(), (unsigned)fw_stream_errors());
    fw_stream_link_report();
    return failed;
}

#ifdef BOARD_CMDLINE
/* ------------------------------------------ words from the host's command line */

/* Reads `expect` bytes from the link and reports their count and CRC-32;
 * gives up after 5 s without a byte. */
static int link_check(uint32_t expect)
{
    uint32_t got = 0, crc = 0;
    uint64_t last = board_time_us();
    int r = 0;
    while (got < expect) {
        uint8_t b;
        r = board_link_read(&b);
        if (r < 0) {
            break; /* bytes lost: the CRC below cannot match */
        } else if (r > 0) {
            crc = cs_crc32(crc, &b, 1);
            got++;
            last = board_time_us();
        } else if (board_time_us() - last > 5000000u) {
            break;
        }
    }
    fw_print("link rx %u bytes crc32 %08X%s\n", (unsigned)got, (unsigned)crc,
             got == expect ? "" : r < 0 ? " (bytes lost)" : " (timeout)");
    return got == expect ? 0 : 1;
}

/* Deliberate faults, so the test can show that a crash fails the run. */
static volatile uint32_t crash_sink, crash_dividend = 1000;

/* Every word of each frame is written: a frame (72 bytes) is larger than
 * the 32-byte MPU guard, and one that wrote only its ends could step over
 * the guard, as it did once main's own frame changed size. */
__attribute__((noinline)) static uint32_t dive(uint32_t depth)
{
    volatile uint32_t frame[16];
    for (int i = 15; i >= 0; i--)
        frame[i] = depth;
    if (depth == UINT32_MAX) /* never: keeps the recursion from being infinite to the compiler */
        return 0;
    return dive(depth + 1) + frame[0];
}

static void crash(const char *how)
{
    fw_print("crash=%s: faulting on purpose\n", how);
    if (how[0] == 's')
        crash_sink = dive(0);
    else if (how[0] == 'd')
        crash_sink = crash_dividend / crash_sink; /* crash_sink is 0: UDIV traps */
    else
        __builtin_trap();
    fw_print("crash=%s: no fault happened\n", how);
}


/* Parses "WxH". */
static int parse_size(const char *s, uint32_t *w, uint32_t *h)
{
    char a[12], b[12];
    size_t i = 0, j = 0;
    while (s[i] && s[i] != 'x' && i + 1 < sizeof a) {
        a[i] = s[i];
        i++;
    }
    a[i] = 0;
    if (s[i] != 'x')
        return 0;
    for (s += i + 1; s[j] && j + 1 < sizeof b; j++)
        b[j] = s[j];
    b[j] = 0;
    return fw_parse_u32(a, w) && fw_parse_u32(b, h);
}

/* A job from scene=, size=, time_ms=, aa= words; returns 0 if none given,
 * -1 if they are wrong. */
static int custom_job(const char *cmd, fw_job *job)
{
    char v[32];
    if (!fw_arg(cmd, "scene", v, sizeof v))
        return 0;
    int s = fw_scene_find(v);
    uint32_t w = BOARD_PANEL_WIDTH, h = BOARD_PANEL_HEIGHT, t = 0, aa = 5;
    if (s < 0) {
        fw_print("unknown scene '%s'\n", v);
        return -1;
    }
    if ((fw_arg(cmd, "size", v, sizeof v) && !parse_size(v, &w, &h)) ||
        (fw_arg(cmd, "time_ms", v, sizeof v) && !fw_parse_u32(v, &t)) ||
        (fw_arg(cmd, "aa", v, sizeof v) && !fw_parse_u32(v, &aa)) || w > UINT16_MAX ||
        h > UINT16_MAX || aa > 255) {
        fw_print("bad size=, time_ms= or aa=\n");
        return -1;
    }
    job->scene = (uint8_t)s;
    job->subscan = (uint8_t)aa;
    job->width = (uint16_t)w;
    job->height = (uint16_t)h;
    job->time_ms = t;
    return 1;
}

/* Is job i selected by jobs=all or jobs=I,J,...? */
static int job_selected(const char *list, int i)
{
    if (!list[0] || (list[0] == 'a' && list[1] == 'l' && list[2] == 'l' && !list[3]))
        return 1;
    uint32_t v = 0;
    int have = 0;
    for (const char *p = list;; p++) {
        if (*p >= '0' && *p <= '9') {
            v = v * 10u + (uint32_t)(*p - '0');
            have = 1;
        } else {
            if (have && v == (uint32_t)i)
                return 1;
            v = 0;
            have = 0;
            if (!*p)
                return 0;
        }
    }
}

/* What the command line asks for, in order: a deliberate fault, the raw
 * link check, built-in jobs, a stream, playback. Returns the failures. */
static int commands(const char *cmd)
{
    char arg[192];
    if (fw_arg(cmd, "crash", arg, sizeof arg))
        crash(arg);
    int failed = 0;
    uint32_t n;
    if (fw_arg(cmd, "uart", arg, sizeof arg) && fw_parse_u32(arg, &n))
        failed += link_check(n);

    /* Built-in jobs: all by default, none if a stream or playback is asked for. */
    bool stream = fw_arg(cmd, "stream", arg, sizeof arg);
    uint32_t expect = 0;
    if (stream && !fw_parse_u32(arg, &expect)) {
        fw_print("stream= wants the number of bytes to read\n");
        failed++;
        stream = false;
    }
    fw_job custom;
    int c = custom_job(cmd, &custom);
    if (c < 0) {
        failed++;
    } else if (c > 0) {
        failed += render_job(0, &custom);
    } else if (fw_arg(cmd, "jobs", arg, sizeof arg) || (!stream && !fw_arg(cmd, "play", 0, 0))) {
        for (int i = 0; i < FW_JOB_COUNT; i++)
            if (job_selected(arg, i))
                failed += render_job(i, &fw_jobs[i]);
    }

    if (stream) {
        fw_frame_req reqs[FW_MAX_FRAME_REQS] = {
            {BOARD_PANEL_WIDTH, BOARD_PANEL_HEIGHT, 16, 0.0f, "0", 0, 0}};
        int count = 1;
        uint32_t idle_ms = 5000;
        bool each = !(fw_arg(cmd, "render", arg, sizeof arg) && arg[0] == 'e' && arg[1] == 'n');
        if (fw_arg(cmd, "frames", arg, sizeof arg))
            count = fw_frames_parse(arg, reqs, FW_MAX_FRAME_REQS);
        if (fw_arg(cmd, "idle_ms", arg, sizeof arg) && !fw_parse_u32(arg, &idle_ms))
            count = -1;
        uint32_t repeat = 0, step_ms = 0;
        if ((fw_arg(cmd, "repeat", arg, sizeof arg) &&
             (!fw_parse_u32(arg, &repeat) || repeat > 10000u)) ||
            (fw_arg(cmd, "step_ms", arg, sizeof arg) &&
             (!fw_parse_u32(arg, &step_ms) || step_ms > 60000u)))
            count = -1;
        for (int i = 0; i < count; i++) {
            reqs[i].repeat = (uint16_t)repeat;
            reqs[i].step_ms = (uint16_t)step_ms;
        }
        if (count < 0) {
            failed++;
        } else {
            fw_stream_start(&scene_store, false);
            failed += fw_stream_run(expect, idle_ms, reqs, count, each);
        }
    }
    if (fw_arg(cmd, "play", arg, sizeof arg) && fw_parse_u32(arg, &n) && n > 0)
        failed += play(n);
    return failed;
}
#endif /* BOARD_CMDLINE */

int main(void)
{
    board_init();
#ifdef BOARD_CMDLINE
    const char *cmd = board_cmdline();
    char fcrc[4];
    fw_render_init(fw_arg(cmd, "fcrc", fcrc, sizeof fcrc) && fcrc[0] == '1');
    fw_render_damage(fw_arg(cmd, "damage", fcrc, sizeof fcrc) && fcrc[0] == '1');
#else
    fw_render_init(false);
#endif
    fw_print("celfw %s: panel %dx%d RGB565, scene store %u B, workspace and staging store %u B, "
             "stack guard %08x\n",
             BOARD_NAME, BOARD_PANEL_WIDTH, BOARD_PANEL_HEIGHT, (unsigned)sizeof scene_store,
             (unsigned)fw_render_work_bytes(), (unsigned)cm_stack_guard());
#ifdef BOARD_CMDLINE
    int failed = commands(cmd);
#else
    /* No host to ask: the built-in jobs, their CRCs on the console for a
     * comparison with the host's. */
    int failed = 0;
    for (int i = 0; i < FW_JOB_COUNT; i++)
        failed += render_job(i, &fw_jobs[i]);
#endif
    fw_print("stack high-water %u of %u bytes\n", (unsigned)cm_stack_used(),
             (unsigned)cm_stack_size());
    fw_print("celfw: %u frames, %d failed\n", (unsigned)fw_render_frames(), failed);
#ifdef BOARD_DEMO_LOOP
    fw_render_damage(true); /* the glass keeps its picture: send what changed */
    play(0);
#endif
    return failed ? 1 : 0;
}
