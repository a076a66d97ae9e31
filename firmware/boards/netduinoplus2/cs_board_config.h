/*
 * cs_board_config.h - core capacities for this board (CS_CFG_FILE): the
 * shared 480x272-in-64-KiB configuration.
 */
#ifndef CS_BOARD_CONFIG_H
#define CS_BOARD_CONFIG_H
#include "cs_config_480x272.h"
#endif
