/*
 * cs_config_480x272.h - the core's capacities on a 64 KiB-RAM board with a
 * 480x272 panel. Boards include it from their cs_board_config.h, which the
 * build names with -DCS_CFG_FILE (see core/cs_config.h).
 *
 * Where the RAM goes (bytes, Cortex-M4; tools/fw_budget.sh prints the
 * measured figures on every build):
 *   line buffers   15 floats per pixel (the stack's E in the caller's
 *                  output line, T, the cel's E and 1-T, the coverage
 *                  claimed, area, cover): 28,816
 *   scene store    cs_scene with the capacities below: 16,576 (>= 16 KiB)
 *   segment arena  144 segments x 52 + 208 pieces x (24 + 3 x 2 index):
 *                  13,728
 *   per region     64 x 26 (paint maps and cel of each region): 1,664
 *   crossings      64 x 8 per region and sub-scanline: 512
 * which is 61,296 of 65,536, leaving 4,240 for the stack (2,048 + 32 guard;
 * 868 measured), the RGB565 panel line (960), the semihosting command line
 * (256) and board state; about 550 bytes stay free on mps2-an386.
 *
 * The stream decoder's second (staging) store cannot be another cs_scene
 * of this size next to these line buffers; see firmware/README.md.
 *
 * Pieces: about one y-monotone piece per segment in practice (the built-in
 * scenes: 67 pieces for 73 segments; a horizontal edge gives none, a
 * segment whose y turns gives two or more, a wild rational cubic up to 5);
 * a frame that needs more than 208 reports CS_ERR_CAP_PIECES.
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
#define CS_CFG_MAX_PIECES 176
#define CS_CFG_MAX_CROSSINGS 64
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
/* No pre-combined cache: it needs more RAM than the whole board has. */
#define CS_CFG_CACHE 0

#endif /* CS_CONFIG_480X272_H */
