/*
 * main_mcu.c - the firmware's main loop on microcontroller boards.
 *
 * All memory is static and sized by the board's core configuration
 * (CS_CFG_FILE): the scene store, the core's workspace, one line of
 * linear-light floats and one line of panel pixels. Nothing is allocated;
 * the image links no C library at all.
 *
 * Until the cel stream decoder feeds scenes over the UART, the firmware
 * renders its built-in scenes (firmware/scenes) as a list of jobs, prints
 * each frame's CRC-32 in the `celsim --crc` line format, and, on QEMU,
 * dumps the frames for a pixel comparison (tools/fw_qemu_test.sh). The
 * stream ingress is exercised already: `uart=N` reads N bytes from the
 * link and prints their CRC.
 *
 * Command-line words (QEMU -append), all optional:
 *   jobs=all|I,J,..  which built-in jobs to render (default all)
 *   scene=NAME size=WxH time_ms=T aa=N   one frame of your choosing
 *   dump=DIR         frame dumps to the host (board's panel)
 *   fcrc=1           also print a CRC-32 of each frame's linear-light floats
 *   uart=N           read N bytes of link input first and report them
 *   crash=stack|udf|div0   fault on purpose (tests the fault path)
 *
 * The fw_mark_* functions do nothing; a QEMU instruction-count plugin
 * (tools/qemu-insn) watches their addresses to split the count into frame
 * preparation, line rendering and line output.
 */
#include "board.h"
#include "board_api.h"
#include "celscan.h"
#include "cm_startup.h"
#include "fw_args.h"
#include "fw_print.h"
#include "fw_scenes.h"
#include "mcu_display.h"

#define PANEL_BPP 2 /* CS_PANEL_PIXFMT is RGB565 */
typedef char panel_bpp_check_[CS_PANEL_PIXFMT == CS_PIX_RGB565_SRGB ? 1 : -1];

/* The scene store is built by cs_scene_init before every use, so reset
 * need not clear it: .noinit. */
static cs_scene scene_store __attribute__((section(".noinit.scene_store")));
static cs_workspace workspace;
static cs_renderer renderer;
static float line[3 * CS_CFG_MAX_WIDTH];
static uint8_t panel_line[PANEL_BPP * CS_CFG_MAX_WIDTH];
static mcu_display display;

/* Markers for the instruction-count plugin: distinct, never inlined or
 * merged (noipa), and kept though they do nothing. */
#define FW_MARK(name)                                                                              \
    __attribute__((noipa, used)) void name(void);                                                  \
    __attribute__((noipa, used)) void name(void) { __asm volatile(""); }
FW_MARK(fw_mark_frame_begin)
FW_MARK(fw_mark_frame_ready)
FW_MARK(fw_mark_line_rendered)
FW_MARK(fw_mark_line_out)
FW_MARK(fw_mark_frame_end)

/* With fcrc=1, a CRC-32 of the linear-light floats themselves (as bytes,
 * little-endian like the host): it shows bit-identical arithmetic, which
 * the panel's 5/6-bit CRC alone could not (tiny differences round away). */
static bool float_crc_on;
static uint32_t float_crc;

static cs_status sink(void *user, int y, const float *rgb_linear, int width)
{
    if (float_crc_on)
        float_crc = cs_crc32(float_crc, rgb_linear, (size_t)width * 3u * sizeof(float));
    fw_mark_line_rendered();
    cs_status st = mcu_display_line(user, y, rgb_linear, width);
    fw_mark_line_out();
    return st;
}

static void report_error(int index, const char *what, cs_status st, const cs_error *err)
{
    fw_print("job %d error: %s: %s", index, what, cs_status_str(st));
    if (err && (err->cel >= 0 || err->region >= 0 || err->contour >= 0))
        fw_print(" (cel %d region %d contour %d item %d)", (int)err->cel, (int)err->region,
                 (int)err->contour, (int)err->item);
    fw_print("\n");
}

/* Renders one job; returns 0 if the frame was produced without error. */
static int render_job(int index, const fw_job *job)
{
    const fw_scene_info *info = &fw_scenes[job->scene];
    cs_render_opts opts = fw_job_opts(job);
    fw_print("job %d scene %s time_ms %u size %ux%u aa %u\n", index, info->name,
             (unsigned)job->time_ms, (unsigned)job->width, (unsigned)job->height,
             (unsigned)job->subscan);
    cs_error err;
    cs_status st = info->build(&scene_store, opts.time, &err);
    if (st != CS_OK) {
        report_error(index, "scene", st, &err);
        return 1;
    }
    uint64_t t0 = board_time_us();
    fw_mark_frame_begin();
    st = cs_frame_begin(&renderer, &workspace, &scene_store, &opts, &err);
    fw_mark_frame_ready();
    if (st != CS_OK) {
        report_error(index, "frame", st, &err);
        return 1;
    }
    float_crc = 0;
    st = mcu_display_begin(&display, opts.width, opts.height);
    if (st == CS_OK)
        st = cs_render_frame(&renderer, line, sink, &display);
    uint32_t crc = mcu_display_end(&display);
    fw_mark_frame_end();
    uint64_t t1 = board_time_us();
    if (st != CS_OK) {
        report_error(index, "render", st, &renderer.sticky);
        return 1;
    }
    fw_print("frame crc32 %08X\n", (unsigned)crc);
    if (float_crc_on)
        fw_print("float crc32 %08X\n", (unsigned)float_crc);
    fw_print("job %d segments %u pieces %u render_us %llu%s\n", index,
             (unsigned)renderer.segment_count, (unsigned)renderer.piece_count,
             (unsigned long long)(t1 - t0), display.panel_error ? " panel-error" : "");
    return display.panel_error ? 1 : 0;
}

/* Reads `expect` bytes from the link and reports their count and CRC-32;
 * gives up after 5 s without a byte. */
static int link_check(uint32_t expect)
{
    uint32_t got = 0, crc = 0;
    uint64_t last = board_time_us();
    while (got < expect) {
        uint8_t b;
        if (board_link_read(&b)) {
            crc = cs_crc32(crc, &b, 1);
            got++;
            last = board_time_us();
        } else if (board_time_us() - last > 5000000u) {
            break;
        }
    }
    fw_print("link rx %u bytes crc32 %08X%s\n", (unsigned)got, (unsigned)crc,
             got < expect ? " (timeout)" : "");
    return got == expect ? 0 : 1;
}

/* Deliberate faults, so the test can show that a crash fails the run. */
static volatile uint32_t crash_sink, crash_dividend = 1000;

__attribute__((noinline)) static uint32_t dive(uint32_t depth)
{
    volatile uint32_t frame[16];
    frame[0] = depth;
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

#ifdef BOARD_DEMO_LOOP
/* On real glass: keep animating the first job's scene at the panel's size,
 * with the time taken from the board clock, and report now and then. */
static void demo_loop(void)
{
    fw_job job = fw_jobs[0];
    job.width = BOARD_PANEL_WIDTH;
    job.height = BOARD_PANEL_HEIGHT;
    cs_render_opts opts = fw_job_opts(&job);
    uint64_t start = board_time_us();
    for (uint32_t frame = 0;; frame++) {
        opts.time = (float)((board_time_us() - start) / 1000u) / 1000.0f;
        cs_error err;
        if (fw_scenes[job.scene].build(&scene_store, opts.time, &err) != CS_OK ||
            cs_frame_begin(&renderer, &workspace, &scene_store, &opts, &err) != CS_OK ||
            mcu_display_begin(&display, opts.width, opts.height) != CS_OK)
            continue;
        cs_status st = cs_render_frame(&renderer, line, sink, &display);
        uint32_t crc = mcu_display_end(&display);
        if (frame % 64u == 0)
            fw_print("demo frame %u crc32 %08X %s\n", (unsigned)frame, (unsigned)crc,
                     cs_status_str(st));
    }
}
#endif

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

int main(void)
{
    board_init();
    const char *cmd = board_cmdline();
    fw_print("celfw %s: panel %dx%d RGB565, scene store %u B, workspace %u B, stack guard %08x\n",
             BOARD_NAME, BOARD_PANEL_WIDTH, BOARD_PANEL_HEIGHT, (unsigned)sizeof scene_store,
             (unsigned)sizeof workspace, (unsigned)cm_stack_guard());
    mcu_display_init(&display, board_panel(), panel_line);

    char arg[64];
    float_crc_on = fw_arg(cmd, "fcrc", arg, sizeof arg) && arg[0] == '1';
    if (fw_arg(cmd, "crash", arg, sizeof arg))
        crash(arg);
    int failed = 0, frames = 0;
    uint32_t n;
    if (fw_arg(cmd, "uart", arg, sizeof arg) && fw_parse_u32(arg, &n))
        failed += link_check(n);

    fw_job custom;
    int c = custom_job(cmd, &custom);
    if (c < 0) {
        failed++;
    } else if (c > 0) {
        failed += render_job(0, &custom);
        frames++;
    } else {
        fw_arg(cmd, "jobs", arg, sizeof arg);
        for (int i = 0; i < FW_JOB_COUNT; i++)
            if (job_selected(arg, i)) {
                failed += render_job(i, &fw_jobs[i]);
                frames++;
            }
    }
    fw_print("stack high-water %u of %u bytes\n", (unsigned)cm_stack_used(),
             (unsigned)cm_stack_size());
    fw_print("celfw: %d frames, %d failed\n", frames, failed);
#ifdef BOARD_DEMO_LOOP
    demo_loop();
#endif
    return failed ? 1 : 0;
}
