/*
 * cs_config_480x272.h - the core's capacities on a 64 KiB-RAM board with a
 * 480x272 panel. Boards include it from their cs_board_config.h, which the
 * build names with -DCS_CFG_FILE (see core/cs_config.h).
 *
 * Where the RAM goes (bytes, Cortex-M4; tools/fw_budget.sh prints the
 * measured figures on every build and keeps 10 % of flash and RAM free):
 *   workspace      39,888: line buffers, 12 floats per pixel (area, cover,
 *                  claimed coverage, the cel's E and 1-T, the stack's E
 *                  and T) and the 16-bit run ends: about 29,900; segment
 *                  arena 72 segments x 60 + 84 pieces x (24 + 3 x 2
 *                  index): 6,840; per region 32 x 26 (paint maps, cel):
 *                  832; crossings 64 x 24 (with the interpolated cubic,
 *                  cs_cross.c): 1,536; paint function maps, one animated
 *                  contour, the contour being converted: 616
 *   staging store  the decoder's back store shares the workspace's RAM
 *                  (firmware/fw_render.c: a union), so it costs nothing
 *   scene store    cs_scene with the capacities below: 15,504; 16 bytes a
 *                  control point (x y w and its knot interval, floats),
 *                  4 + 4 x width a key (its time and values)
 * leaving the rest for the stack (2,048 + 32 guard; 1,828 measured), the
 * decoder (416), the semihosting command line (256) and board state:
 * 58,760 of 65,536 on mps2-an386 (10.3 % free).
 *
 * Capacities: the full signage demo (scenes/demo.json: 10 cels, 15
 * regions, 39 contours, 571 points) fits the store; the imported Lottie
 * files that lottie-qemu plays need at most 8 tracks, 32 keys and 350 key
 * values. Regions and contours were 64 and 128 (1,664 + 512 bytes of
 * store, 832 of workspace), points 520.
 *
 * The arena holds a band of rows, not the frame: a frame whose segments
 * or pieces do not fit is rendered in bands (firmware/fw_render.c), each
 * prepared with only the contours and pieces that reach its rows
 * (core/cs_frame.c), with the same bits. The demo at 480x272 needs 249
 * segments and 287 pieces at once, and at most 68 and 80 in any of six
 * bands of 46 rows. Pieces are about one per segment (a horizontal edge
 * gives none, a segment whose y turns two or more); a band that still
 * overflows at one row reports CS_ERR_CAP_SEGMENTS or CS_ERR_CAP_PIECES.
 */
#ifndef CS_CONFIG_480X272_H
#define CS_CONFIG_480X272_H

#define CS_CFG_MAX_WIDTH 480
#define CS_CFG_MAX_HEIGHT 272
#define CS_CFG_MAX_CELS 16
#define CS_CFG_MAX_REGIONS 32
#define CS_CFG_MAX_CONTOURS 64
#define CS_CFG_MAX_POINTS 600
#define CS_CFG_MAX_SEGMENTS 72
#define CS_CFG_MAX_PIECES 84
#define CS_CFG_MAX_CROSSINGS 64
/* No data cache to straddle: crossings stay 24 bytes (cs_config.h). */
#define CS_CFG_CROSSING_ALIGN 4
#define CS_CFG_INDEX_TYPE uint16_t
/* Functional paints and CSG are kept small: signage uses a few gradients. */
#define CS_CFG_MAX_FUNCS 4
#define CS_CFG_MAX_STOPS 8
#define CS_CFG_MAX_CSG 8
#define CS_CFG_MAX_OPERANDS 4
/* Animation: a few tracks, keys and one animated contour of up to 32 points. */
#define CS_CFG_MAX_TRACKS 16
#define CS_CFG_MAX_KEYS 64
#define CS_CFG_MAX_KEY_VALUES 384
#define CS_CFG_MAX_ANIM_POINTS 32
#define CS_CFG_STREAM_MAX_TXN (16u * 1024u)
/* Sub-scanline anti-aliasing only: no exact-area band state. */
#define CS_CFG_EXACT 0
/* The panel is RGB565: the 5 KB table for 8-bit sRGB would only cost flash. */
#define CS_CFG_SRGB8_TABLE 0
/* One copy of the run code (the grey path costs ~5 KB of flash). */
#define CS_CFG_GREY 0
/* No pre-combined cache: it needs more RAM than the whole board has. */
#define CS_CFG_CACHE 0
/* A cel composites by walking its runs: the list would take 960 B of RAM. */
#define CS_CFG_CEL_LIST 0

#endif /* CS_CONFIG_480X272_H */
