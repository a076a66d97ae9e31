/*
 * fw_stream.h - cel stream ingress on MCU boards: link bytes to the
 * decoder, commits to the scene store on display, frames on request.
 *
 * The decoder (core/cs_stream.c) needs two scene stores: the front one on
 * display and a back one that a transaction is built in. The front store
 * is the firmware's scene store; the back store is the render workspace
 * itself (fw_render_staging), which is free whenever no frame is being
 * rendered. The rule that makes this safe is simple: the firmware feeds
 * the decoder only between frames, and renders only while the decoder is
 * not busy (cs_stream_busy: no transaction open, no commit waiting). At a
 * commit the new scene is copied into the front store and the decoder
 * carries on from there; a dropped transaction leaves the front store, and
 * so the picture, exactly as it was. While a transaction streams in, no
 * new frame is drawn; the panel keeps showing the last one.
 *
 * Events are reported on the console, offsets counting bytes from the
 * first byte the link delivered:
 *   stream commit K at byte B: C cels, R regions, N contours, P points, T tracks
 *   stream error: byte A: STATUS[: what][ (cel c, region r, ...)] (transaction at byte O dropped)
 * (the error text is the host reader's, tools/cels_read.c, without the file name).
 */
#ifndef FW_STREAM_H
#define FW_STREAM_H

#include <stdbool.h>
#include <stdint.h>

#include "celscan.h"

/* A frame someone asked for: size, time and anti-aliasing. */
typedef struct fw_frame_req {
    uint16_t width, height;
    uint8_t subscan;      /* sub-scanlines; 0 means CS_AA_NONE */
    float time;           /* seconds: the float strtof gives for time_text */
    char time_text[12];   /* as given, for the log and the host reference */
    uint16_t repeat;      /* 0: once at `time`; else this many frames from `time` in whole */
    uint16_t step_ms;     /* milliseconds, step_ms apart (repeat=, step_ms=) */
} fw_frame_req;

#define FW_MAX_FRAME_REQS 8

/*
 * Parses a frame list "WxH@T[:A],..." (T seconds with at most 7 decimals,
 * A sub-scanlines 1..64 or "none", default 16 as celsim). Returns the count, or -1
 * (with a message printed) if the text is malformed or has more than `max`.
 */
int fw_frames_parse(const char *text, fw_frame_req *out, int max);

/* The render options of a request. */
cs_render_opts fw_frame_opts(const fw_frame_req *f);

/* Starts the decoder with `front` as the store on display; `front_valid`
 * if it already holds a scene that patch transactions may change. */
void fw_stream_start(cs_scene *front, bool front_valid);

/* Feeds one byte; returns how many events (commits and errors) it caused. */
int fw_stream_byte(uint8_t byte);

/* The link lost bytes here (board_link_read said -1): an open transaction
 * is dropped and reported; returns events caused. */
int fw_stream_gap(void);

/* End of input: reports a transaction cut short; returns events caused. */
int fw_stream_finish(void);

/* True while a transaction is open or a commit waits: do not render. */
bool fw_stream_busy(void);

/* The scene on display, or NULL if none was committed (nor given valid). */
const cs_scene *fw_stream_scene(void);

/* Prints the link's receive ring use: "link: ring high-water H of S bytes, G gaps". */
void fw_stream_link_report(void);

/* Commits and errors so far. */
uint32_t fw_stream_commits(void);
uint32_t fw_stream_errors(void);

/*
 * The QEMU flow: reads `expect` bytes from the link (giving up after
 * `idle_ms` without a byte) and renders each of the `n` requested frames
 * from the scene on display: if `each`, after every event (commit or
 * error) as soon as the decoder is not busy, else once at the end of
 * input. Returns the number of failures (frames not rendered whole).
 */
int fw_stream_run(uint32_t expect, uint32_t idle_ms, const fw_frame_req *reqs, int n, bool each);

#endif /* FW_STREAM_H */
