/*
 * sign_config_160x128.h - the core's capacities for a small sign: a 160x128
 * panel and simple content, an example of the one knob a consumer sets.
 *
 * `make install-lib MCU_CFG=examples/sign/sign_config_160x128.h` (in the
 * celscan tree) builds the microcontroller libraries with these capacities
 * and installs this header as their CS_CFG_FILE; a firmware built with
 * their pkg-config or CMake entries then sees the same structs as the
 * library. Anything not set here keeps core/cs_config.h's default.
 */
#ifndef SIGN_CONFIG_160X128_H
#define SIGN_CONFIG_160X128_H

#define CS_CFG_MAX_WIDTH 160
#define CS_CFG_MAX_HEIGHT 128
#define CS_CFG_MAX_CELS 8
#define CS_CFG_MAX_REGIONS 32
#define CS_CFG_MAX_CONTOURS 64
#define CS_CFG_MAX_POINTS 256
#define CS_CFG_MAX_SEGMENTS 96
#define CS_CFG_MAX_PIECES 128
#define CS_CFG_MAX_CROSSINGS 48
#define CS_CFG_INDEX_TYPE uint16_t
#define CS_CFG_MAX_FUNCS 2
#define CS_CFG_MAX_STOPS 4
#define CS_CFG_MAX_CSG 4
#define CS_CFG_MAX_OPERANDS 2
#define CS_CFG_MAX_TRACKS 8
#define CS_CFG_MAX_KEYS 32
#define CS_CFG_MAX_KEY_VALUES 192
#define CS_CFG_MAX_ANIM_POINTS 16
#define CS_CFG_STREAM_MAX_TXN (8u * 1024u)
#define CS_CFG_EXACT 0
#define CS_CFG_SRGB8_TABLE 0
#define CS_CFG_CACHE 0

#endif /* SIGN_CONFIG_160X128_H */
