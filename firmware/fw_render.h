/*
 * fw_render.h - one frame from a scene store to the panel, and the RAM it
 * takes.
 *
 * This module owns the renderer's memory: the core workspace and one line
 * of linear-light floats, which the panel pixels are converted into. The workspace also
 * serves as the cel stream decoder's staging (back) store: the two are a
 * union, because the decoder writes its back store only while a
 * transaction is open (cs_stream_busy) and the firmware renders only while
 * none is (see fw_stream.c and firmware/README.md). Whoever renders must
 * therefore ask fw_stream first, or own the workspace outright (the
 * built-in jobs, which run before any stream byte is read).
 *
 * Every frame prints the `celsim --crc` contract line `frame crc32 X`,
 * with fcrc=1 also `float crc32 X` (a CRC-32 of the linear-light floats,
 * which shows bit-identical arithmetic), and one line of statistics.
 */
#ifndef FW_RENDER_H
#define FW_RENDER_H

#include <stdbool.h>
#include <stdint.h>

#include "celscan.h"

/* Paints the workspace (NaN everywhere: nothing may rely on its contents)
 * and sets up the panel. `want_float_crc` turns on the float CRC line. */
void fw_render_init(bool want_float_crc);

/* The decoder's staging store: the same RAM as the render workspace. */
cs_scene *fw_render_staging(void);

/* Bytes of the shared workspace / staging area. */
uint32_t fw_render_work_bytes(void);

/*
 * Renders `scene` at `opts` to the panel and prints the result lines
 * (only errors if `quiet`); `label` names the frame in them. Returns 0 if
 * the frame came out whole (no core or panel error).
 */
int fw_render(const cs_scene *scene, const cs_render_opts *opts, const char *label, bool quiet);

/*
 * Damage on: each frame renders and sends only the window that can differ
 * from the frame before (cs_frame_damage; the panel keeps the rest), and
 * prints the whole frame's CRC read back from the panel where it can
 * (`frame crc32`), else the window's (`window crc32`), and the window on
 * its statistics line. Turning it on or off forgets the last frame.
 */
void fw_render_damage(bool on);

/* The next frame is damaged everywhere (a new scene was committed). */
void fw_render_forget(void);

/* Frames completed so far (the panel's frame number of the next one). */
uint32_t fw_render_frames(void);

/* Prints a core error with its location: "LABEL error: WHAT: STATUS (cel ...)". */
void fw_report_error(const char *label, const char *what, cs_status st, const cs_error *err);

#endif /* FW_RENDER_H */
