/*
 * cs_board_config.h - core capacities for this board (CS_CFG_FILE): the
 * shared 480x272-in-64-KiB configuration, without the Lottie animation
 * parts (TRS tracks, cubic easing, cel groups: 1,608 B of code here). With
 * them the image is 65,732 B, past the 64 KiB flash this build is held to
 * (the STM32F407's own FSMC/SSD1963 drivers take the room the MPS2 board
 * spends on none); such streams are refused here with CS_ERR_TRACK or
 * CS_ERR_GROUP and play on the mps2-an386 board and on Linux boards.
 */
#ifndef CS_BOARD_CONFIG_H
#define CS_BOARD_CONFIG_H
#include "cs_config_480x272.h"
#define CS_CFG_ANIM_PARTS 0
#endif
