/*
 * cs_config_480x272.h - the core's capacities on a 64 KiB-RAM board with a
 * 480x272 panel. Boards include it from their cs_board_config.h, which the
 * build names with -DCS_CFG_FILE (see core/cs_config.h).
 *
 * Where the RAM goes (bytes, Cortex-M4; tools/fw_budget.sh prints the
 * measured figures on every build):
 *   workspace      line buffers, 12 floats per pixel (area, cover,
 *                  claimed coverage, the cel's E and 1-T, the stack's T)
 *                  and the 16-bit opaque record: 24,018; segment arena
 *                  120 segments x 60 + 160 pieces x (24 + 3 x 2 index):
 *                  12,000; per region 64 x 26 (paint maps, cel): 1,664;
 *                  crossings 64 x 24 (with the interpolated cubic,
 *                  cs_line.c): 1,536; paint function maps and one
 *                  animated contour: 480
 *   staging store  the decoder's back store shares the workspace's RAM
 *                  (firmware/fw_render.c: a union), so it costs nothing
 *   scene store    cs_scene with the capacities below: 16,388 (>= 16 KiB)
 *   float line     the stack's E, then the pixels: 5,760
 * leaving the rest for the stack (2,048 + 32 guard; 1,500 measured), the
 * decoder (408), the semihosting command line (256) and board state; 304
 * bytes stay free on mps2-an386 (65,232 of 65,536 measured).
 *
 * Pieces: about one y-monotone piece per segment in practice (the built-in
 * scenes: 67 pieces for 73 segments; a horizontal edge gives none, a
 * segment whose y turns gives two or more, a wild rational cubic up to 5);
 * a frame that needs more than 160 reports CS_ERR_CAP_PIECES. (176 until
 * the crossings grew by 12 bytes each.)
 */
#ifndef CS_CONFIG_480X272_H
#define CS_CONFIG_480X272_H

#define CS_CFG_MAX_WIDTH 480
#define CS_CFG_MAX_HEIGHT 272
#define CS_CFG_MAX_CELS 16
#define CS_CFG_MAX_REGIONS 64
#define CS_CFG_MAX_CONTOURS 128
#define CS_CFG_MAX_POINTS 520
#define CS_CFG_MAX_SEGMENTS 120
#define CS_CFG_MAX_PIECES 160
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

#endif /* CS_CONFIG_480X272_H */
