/*
 * cs_board_config.h - core capacities for this board (CS_CFG_FILE): the
 * shared 480x272-in-64-KiB configuration.
 */
#ifndef CS_BOARD_CONFIG_H
#define CS_BOARD_CONFIG_H
#include "cs_config_480x272.h"
/* Its panel (semihost, dump=) reads back: no frame byte is hashed while a
 * frame renders, so the CRC-32 goes a nibble a step and the kilobyte of its
 * table pays for inlining in the line code (mk/firmware.mk FW_HOT_SRC). */
#define CS_CFG_CRC32_TABLE 0
/* Flash for the line code (mk/firmware.mk): the sRGB curve, which only
 * scenes blended in sRGB read here, from its 1.7 KB compact form instead of
 * the 4 KB table; the same floats (tests/test_srgb_compact.c). */
#define CS_CFG_SRGB_COMPACT 1
#endif
