/*
 * cli_num.c - strict reading of typed numbers (see cli_num.h).
 *
 * The checks sit around strtol and strtod rather than replacing them: the
 * conversions themselves are the C library's, which does them well; what it
 * lets through (leading spaces and signs, a hex prefix in any base-0 or
 * base-16 text, "inf", "nan", hex floats, trailing text, ERANGE left for the
 * caller to notice) is what is refused here.
 */
#include "cli_num.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The text after a value that stopped at `stop`, if `end` follows it. */
static const char *after(const char *stop, char end)
{
    if (*stop != end)
        return NULL;
    return end ? stop + 1 : stop;
}

const char *cli_int(const char *s, int base, char end, long lo, long hi, long *out)
{
    const char *digits = s;
    if (*digits == '-' && lo < 0)
        digits++;
    if (base == 0) { /* decimal, or hex after 0x: never octal */
        base = 10;
        if (digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) {
            base = 16;
            digits += 2;
        }
    }
    if (base != 10 && base != 16)
        return NULL;
    if (!(base == 10 ? isdigit((unsigned char)*digits) : isxdigit((unsigned char)*digits)))
        return NULL;
    /* strtol would take a second "0x" in base 16 ("0x0x1"): refuse it */
    if (base == 16 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X'))
        return NULL;
    char *stop;
    errno = 0;
    long v = strtol(digits, &stop, base);
    if (errno != 0) /* ERANGE */
        return NULL;
    if (*s == '-') /* the sign was read here, not by strtol */
        v = -v;
    if (v < lo || v > hi)
        return NULL;
    const char *rest = after(stop, end);
    if (rest)
        *out = v;
    return rest;
}

const char *cli_real(const char *s, char end, double lo, double hi, double *out)
{
    const char *p = s;
    if (*p == '-')
        p++;
    if (!(isdigit((unsigned char)*p) || (*p == '.' && isdigit((unsigned char)p[1]))))
        return NULL;
    char *stop;
    errno = 0;
    double v = strtod(s, &stop);
    if (errno == ERANGE && fabs(v) > 1.0) /* overflow; an underflow is near enough 0 */
        return NULL;
    for (const char *q = s; q < stop; q++) /* a hex float: not what anyone types */
        if (*q == 'x' || *q == 'X')
            return NULL;
    if (!isfinite(v) || !(v >= lo && v <= hi))
        return NULL;
    const char *rest = after(stop, end);
    if (rest)
        *out = v;
    return rest;
}

bool cli_size(const char *s, long wmax, long hmax, int *w, int *h)
{
    long lw, lh;
    const char *rest = cli_int(s, 10, 'x', 1, wmax, &lw);
    if (!rest || !cli_int(rest, 10, '\0', 1, hmax, &lh))
        return false;
    *w = (int)lw;
    *h = (int)lh;
    return true;
}

bool cli_viewport(const char *s, int *x, int *y, int *w, int *h)
{
    long v[4];
    for (int k = 0; k < 4; k++) {
        s = cli_int(s, 10, k < 3 ? ',' : '\0', k < 2 ? 0 : 1, CS_CFG_MAX_WALL, &v[k]);
        if (!s)
            return false;
    }
    *x = (int)v[0];
    *y = (int)v[1];
    *w = (int)v[2];
    *h = (int)v[3];
    return true;
}

bool cli_aa(const char *s, cs_aa_mode *mode, int *subscanlines)
{
    long n;
    if (strcmp(s, "none") == 0) {
        *mode = CS_AA_NONE;
    } else if (strcmp(s, "exact") == 0) {
        *mode = CS_AA_EXACT;
    } else if (cli_int(s, 10, '\0', 1, CS_CFG_MAX_SUBSCANLINES, &n)) {
        *mode = CS_AA_SUBSCAN;
        *subscanlines = (int)n;
    } else {
        return false;
    }
    return true;
}
