/*
 * cli_num.h - numbers that people type: command-line options and config
 * file values of the host programs (celsim, celc, svgimport, celfw, bench).
 *
 * Each program used to read its own numbers, three of them carefully and
 * bench with atoi and sscanf, whose result on "abc" is 0 and on overflow
 * undefined. Here strtol and strtod do the conversion (out of range is
 * ERANGE, not undefined) and the rest is checked around them, the same way
 * for every program: the text starts with a digit (or '-' and a digit, where
 * the range allows negatives), so " 5", "+5" and "" are refused; it ends
 * exactly where the caller says (the end of the string, or a separator such
 * as the 'x' of "WxH"); reals are finite ("nan", "inf", "1e400" fail) and
 * written in decimal; every value is within the caller's range.
 */
#ifndef CLI_NUM_H
#define CLI_NUM_H

#include <stdbool.h>

#include "celscan.h"

/*
 * A whole number in [lo, hi] at the start of s, written in `base`: 10, 16
 * (digits only, "1d50"), or 0 (decimal, or hex after "0x"; a leading zero
 * does not mean octal). It must be followed by `end` ('\0': the end of the
 * string). Returns the text after `end` (after the whole string if end is
 * '\0'), or NULL if s is not such a number.
 */
const char *cli_int(const char *s, int base, char end, long lo, long hi, long *out);

/* A finite decimal number in [lo, hi] at the start of s, followed by `end`;
 * returns as cli_int does. */
const char *cli_real(const char *s, char end, double lo, double hi, double *out);

/* "WxH": two whole numbers, 1..wmax and 1..hmax. */
bool cli_size(const char *s, long wmax, long hmax, int *w, int *h);

/* "X,Y,W,H": a viewport, X and Y 0..CS_CFG_MAX_WALL, W and H 1..CS_CFG_MAX_WALL
 * (whether it fits the output is the renderer's check, cs_render_opts). */
bool cli_viewport(const char *s, int *x, int *y, int *w, int *h);

/*
 * An anti-aliasing mode as the programs' --aa takes it: "none", "exact",
 * or a number of sub-scanlines 1..CS_CFG_MAX_SUBSCANLINES (*subscanlines is
 * set only then).
 */
bool cli_aa(const char *s, cs_aa_mode *mode, int *subscanlines);

#endif /* CLI_NUM_H */
