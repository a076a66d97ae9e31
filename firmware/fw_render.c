/*
 * fw_render.c - one frame from a scene store to the panel (see fw_render.h).
 *
 * All memory is static and sized by the board's core configuration
 * (CS_CFG_FILE). The workspace and the decoder's staging store share one
 * union in .noinit: neither needs clearing at reset (cs_frame_begin clears
 * the accumulators it relies on, and every transaction starts its back
 * store afresh), and fw_render_init paints it with NaNs so that a frame
 * which did rely on old contents would show it, in the qemu test, as a
 * mismatch with the host.
 *
 * A frame is prepared and rendered in bands of rows when the scene has more
 * segments or pieces than the board's arena holds (CS_CFG_MAX_SEGMENTS,
 * CS_CFG_MAX_PIECES): each band is a full-width viewport, prepared with only
 * the pieces that meet its rows (cs_frame.c), so its lines are the bits the
 * whole frame gives them. On CS_ERR_CAP_SEGMENTS or CS_ERR_CAP_PIECES the
 * frame is cut into one band more and the band prepared again, down to one
 * row per band (FreeType's rasterizer halves a band whose cells overflow;
 * equal bands of height/k rows waste fewer rows than halving). A refused
 * trial costs what the preparation did before the arena ran out (about
 * 0.2 M instructions for the board demo), and every band prepares the
 * contours that reach its rows again, so a frame starts from the fewest
 * bands likely to fit (first_bands): a new scene from its knot spans over
 * the arena's segments (a lower bound: spans off screen aside, every span
 * is a segment of some band), a scene shown before from the last frame's
 * count, one fewer only when the last frame's busiest band, spread over
 * one band fewer, would still fit. The arena can so be sized for a busy
 * band rather than for the whole signage demo; a band prepares only the
 * contours that reach its rows (cs_frame.c), so bands cost little more
 * than one preparation.
 *
 * The fw_mark_* functions do nothing; a QEMU instruction-count plugin
 * (tools/qemu-insn) watches their addresses to split the count into frame
 * preparation, line rendering and line output.
 */
#include "fw_render.h"

#include "board.h"
#include "board_api.h"
#include "celscan_private.h"
#include "fw_print.h"
#include "mcu_display.h"

/* The staging store costs no RAM of its own only while the workspace is
 * the larger of the two. */
_Static_assert(sizeof(cs_workspace) >= sizeof(cs_scene),
               "the staging scene store must fit in the render workspace");

static union {
    cs_workspace ws;
    cs_scene staging;
} work __attribute__((section(".noinit.work")));
static cs_renderer renderer;
/* With damage on, what the last frame showed: a frame renders and sends
 * only the window that changed (cs_frame_damage), the panel keeping the
 * rest of its picture. */
static cs_damage damage;
static bool damage_on;
/* No line buffer: each line is rendered into the core's runs and converted
 * to panel pixels in workspace memory that is idle between lines
 * (cs_line_pixels_scratch). */
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

/* The floats of the line, as cs_render_line would give them, hashed run by run. */
static uint32_t crc_line_floats(uint32_t crc, const cs_renderer *r, int width)
{
    for (int x = 0; x < width;) {
        float rgb[3];
        int next = cs_line_run(r, x, rgb);
        for (; x < next; x++)
            crc = cs_crc32(crc, rgb, sizeof rgb);
    }
    return crc;
}

/* The bands the last frame was cut into (0: none yet, or a new scene) and
 * its busiest band's segments and pieces; the bands and the busiest band
 * of the frame being rendered. */
static int band_count;
static unsigned band_segments, band_pieces;
static unsigned frame_bands, most_segments, most_pieces;

/* The window of the frame to render: the damage, or the whole frame. Not
 * inlined: its stack is free again before the lines are rendered (the
 * deepest path). */
static __attribute__((noinline)) cs_status frame_window(const cs_scene *scene,
                                                        const cs_render_opts *opts, cs_rect *win)
{
    win->x0 = win->y0 = 0;
    win->x1 = opts->width;
    win->y1 = opts->height;
    return damage_on ? cs_frame_damage(&damage, scene, opts, win) : CS_OK;
}

void fw_render_damage(bool on)
{
    damage_on = on;
    cs_damage_reset(&damage);
}

void fw_render_forget(void)
{
    cs_damage_reset(&damage);
    band_count = 0; /* the last scene's bands say nothing about this one */
}

/* Rows per band when a frame of `height` rows is cut into `bands`. */
static int band_rows(int height, int bands)
{
    return (height + bands - 1) / bands;
}

/* The bands a frame of `height` rows of `scene` starts from (see the top
 * of the file). */
static int first_bands(const cs_scene *scene, int height)
{
    int bands = band_count;
    if (bands == 0) {
        uint32_t spans = 0; /* a knot span of non-zero length is a segment */
        for (uint32_t i = 0; i < scene->point_count; i++)
            spans += scene->intervals[i] != 0.0f;
        bands = (int)((spans + CS_CFG_MAX_SEGMENTS - 1u) / CS_CFG_MAX_SEGMENTS);
    } else if (bands > 1) {
        unsigned fewer = (unsigned)bands - 1u;
        if (band_segments * (fewer + 1u) <= fewer * CS_CFG_MAX_SEGMENTS &&
            band_pieces * (fewer + 1u) <= fewer * CS_CFG_MAX_PIECES)
            bands--;
    }
    return bands < 1 ? 1 : bands > height ? height : bands;
}

/*
 * Prepares the band of rows from y of the window `win` of the frame `opts`
 * asks for (its own viewport, if any, is not used: the firmware renders
 * whole frames or their damage), the window cut into *bands equal bands
 * (the last cut at the bottom); while the arena overflows, into one band
 * more.
 */
static cs_status begin_band(const cs_scene *scene, const cs_render_opts *opts, const cs_rect *win,
                            int y, int *bands, cs_error *err)
{
    int height = win->y1 - win->y0;
    for (;;) {
        int rows = band_rows(height, *bands);
        cs_render_opts o = *opts;
        o.view_x = win->x0;
        o.view_w = win->x1 - win->x0;
        o.view_y = y;
        o.view_h = rows < win->y1 - y ? rows : win->y1 - y;
        cs_status st = cs_frame_begin(&renderer, &work.ws, scene, &o, err);
        if ((st != CS_ERR_CAP_SEGMENTS && st != CS_ERR_CAP_PIECES) || rows == 1) {
            if (st == CS_OK) {
                frame_bands++;
                if (renderer.segment_count > most_segments)
                    most_segments = renderer.segment_count;
                if (renderer.piece_count > most_pieces)
                    most_pieces = renderer.piece_count;
            }
            return st;
        }
        /* The next count that makes the bands shorter (rows never grow). */
        while (*bands < height && band_rows(height, *bands) == rows)
            (*bands)++;
    }
}

/* Renders rows [y, y + rows) of the band prepared in `renderer`. */
static cs_status render_lines(const cs_rect *win, int y0, int rows)
{
    for (int y = y0; y < y0 + rows; y++) {
        cs_status st = cs_render_line_runs(&renderer, y);
        if (st != CS_OK)
            return st;
        if (float_crc_on)
            float_crc = crc_line_floats(float_crc, &renderer, win->x1 - win->x0);
        fw_mark_line_rendered();
        st = mcu_display_line_px(&display, y,
                                 cs_line_pixels_scratch(&renderer, CS_PANEL_PIXFMT));
        fw_mark_line_out();
        if (st != CS_OK)
            return st;
    }
    return cs_frame_error(&renderer).status;
}

/* The window in `bands` bands, the first already prepared; *err says what
 * a later band's preparation refused. */
static cs_status render_bands(const cs_scene *scene, const cs_render_opts *opts,
                              const cs_rect *win, int bands, cs_error *err)
{
    cs_status st = CS_OK;
    for (int y = win->y0, rows = 0; st == CS_OK && y < win->y1; y += rows) {
        if (y > win->y0 && (st = begin_band(scene, opts, win, y, &bands, err)) != CS_OK)
            break;
        rows = band_rows(win->y1 - win->y0, bands);
        st = render_lines(win, y, rows < win->y1 - y ? rows : win->y1 - y);
        if (st != CS_OK)
            *err = cs_frame_error(&renderer);
    }
    if (st == CS_OK) {
        band_count = bands;
        band_segments = most_segments;
        band_pieces = most_pieces;
    }
    return st;
}

void fw_render_init(bool want_float_crc)
{
    volatile uint32_t *w = (volatile uint32_t *)(void *)&work;
    for (uint32_t i = 0; i < sizeof work / 4u; i++)
        w[i] = 0xFFFFFFFFu; /* a NaN as a float, UINT32_MAX as an index */
    float_crc_on = want_float_crc;
    mcu_display_init(&display, board_panel(), NULL);
}

cs_scene *fw_render_staging(void)
{
    return &work.staging;
}

uint32_t fw_render_work_bytes(void)
{
    return (uint32_t)sizeof work;
}

uint32_t fw_render_frames(void)
{
    return display.frames;
}

void fw_report_error(const char *label, const char *what, cs_status st, const cs_error *err)
{
    fw_print("%s error: %s: %s", label, what, cs_status_str(st));
    if (err && (err->cel >= 0 || err->region >= 0 || err->contour >= 0))
        fw_print(" (cel %d region %d contour %d item %d)", (int)err->cel, (int)err->region,
                 (int)err->contour, (int)err->item);
    fw_print("\n");
}

int fw_render(const cs_scene *scene, const cs_render_opts *opts, const char *label, bool quiet)
{
    cs_error err;
    uint64_t t0 = board_time_us();
    int bands = 1;
    frame_bands = most_segments = most_pieces = 0;
    fw_mark_frame_begin();
    cs_rect win;
    cs_status st = frame_window(scene, opts, &win);
    bool empty = win.x0 >= win.x1 || win.y0 >= win.y1;
    if (st == CS_OK && !empty) {
        bands = first_bands(scene, win.y1 - win.y0);
        st = begin_band(scene, opts, &win, win.y0, &bands, &err);
    }
    fw_mark_frame_ready();
    if (st != CS_OK) {
        cs_damage_reset(&damage); /* the panel may not show the last frame's picture */
        fw_report_error(label, "frame", st, &err);
        return 1;
    }
    float_crc = 0;
    const hal_window panel_win = {win.x0, win.y0, win.x1, win.y1};
    st = mcu_display_begin(&display, opts->width, opts->height, &panel_win);
    if (quiet)
        display.hash = false; /* no CRC is printed: glass frames hash no byte */
    if (st == CS_OK && !empty)
        st = render_bands(scene, opts, &win, bands, &err);
    uint32_t crc = mcu_display_end(&display);
    fw_mark_frame_end();
    uint64_t t1 = board_time_us();
    if (st != CS_OK || display.panel_error)
        cs_damage_reset(&damage);
    if (st != CS_OK) {
        fw_report_error(label, "render", st, &err);
        return 1;
    }
    if (quiet)
        return display.panel_error ? 1 : 0;
    /* The whole frame's CRC is read back from a panel that can, after the
     * frame's counted instructions; a panel that cannot read back has the
     * running CRC of the bytes sent, the window's with damage. */
    if (mcu_display_frame_crc(&display, (uint8_t *)(void *)&work, &crc))
        fw_print("frame crc32 %08X\n", (unsigned)crc);
    else if (display.hash)
        fw_print("%s crc32 %08X\n", damage_on ? "window" : "frame", (unsigned)crc);
    if (float_crc_on)
        fw_print("float crc32 %08X\n", (unsigned)float_crc);
    fw_print("%s segments %u pieces %u bands %u render_us %llu%s", label, most_segments,
             most_pieces, frame_bands,
             (unsigned long long)(t1 - t0), display.panel_error ? " panel-error" : "");
    if (damage_on)
        fw_print(" window %d %d %d %d", win.x0, win.y0, win.x1, win.y1);
    fw_print("\n");
    return display.panel_error ? 1 : 0;
}
