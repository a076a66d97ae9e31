/*
 * sv_path.c - SVG path data ("d") and the number grammar it shares with
 * points, viewBox and transform lists.
 *
 * The grammar is SVG 1.1's (section 8.3.9 and its BNF): numbers may run
 * together where no ambiguity arises ("1-2", "0.5.5"), arc flags are single
 * digits that need no separator ("a1 1 0 00.5.5"), a command letter may be
 * omitted to repeat the previous command, and extra coordinate pairs after a
 * moveto are linetos. On an error the path drawn so far is kept, as SVG's
 * error handling asks, and the caller learns where the data went wrong.
 */
#include <ctype.h>
#include <math.h>

#include "sv_import.h"
#include "sv_internal.h"

static const char *skip_ws(const char *s)
{
    while (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r' || *s == '\f')
        s++;
    return s;
}

const char *sv_skip_wsp_comma(const char *s)
{
    s = skip_ws(s);
    if (*s == ',')
        s = skip_ws(s + 1);
    return s;
}

/*
 * Reads one number at *s (after optional whitespace/comma) in SVG's syntax,
 * which strtod would over-accept ("inf", hex). Returns false if none.
 */
bool sv_parse_number(const char **s, double *v)
{
    const char *p = sv_skip_wsp_comma(*s), *start = p;
    if (*p == '+' || *p == '-')
        p++;
    bool digits = false;
    while (isdigit((unsigned char)*p)) {
        p++;
        digits = true;
    }
    if (*p == '.') {
        p++;
        while (isdigit((unsigned char)*p)) {
            p++;
            digits = true;
        }
    }
    if (!digits)
        return false;
    if (*p == 'e' || *p == 'E') { /* only if a valid exponent follows ("1em" is not) */
        const char *e = p + 1;
        if (*e == '+' || *e == '-')
            e++;
        if (isdigit((unsigned char)*e)) {
            while (isdigit((unsigned char)*e))
                e++;
            p = e;
        }
    }
    char buf[128];
    size_t n = (size_t)(p - start);
    if (n >= sizeof buf)
        return false;
    memcpy(buf, start, n);
    buf[n] = 0;
    *v = strtod(buf, NULL);
    *s = p;
    return isfinite(*v);
}

static bool parse_flag(const char **s, bool *f)
{
    const char *p = sv_skip_wsp_comma(*s);
    if (*p != '0' && *p != '1')
        return false;
    *f = *p == '1';
    *s = p + 1;
    return true;
}

int sv_parse_numbers(const char *s, double *out, int max)
{
    int n = 0;
    double v;
    while (n < max && sv_parse_number(&s, &v))
        out[n++] = v;
    return n;
}

/* How many numbers each command takes. */
static int arg_count(char c)
{
    switch (toupper((unsigned char)c)) {
    case 'M': case 'L': case 'T': return 2;
    case 'H': case 'V': return 1;
    case 'C': return 6;
    case 'S': case 'Q': return 4;
    case 'A': return 7;
    case 'Z': return 0;
    default: return -1;
    }
}

int sv_parse_path(const char *d, sv_path *path, char *err, size_t errlen)
{
    const char *s = d;
    char cmd = 0, prev = 0;
    sv_pt ctrl = {0, 0}; /* last control point, for S and T reflection */
    for (;;) {
        s = skip_ws(s);
        if (!*s)
            return 0;
        if (isalpha((unsigned char)*s)) {
            if (!cmd && *s != 'M' && *s != 'm') {
                snprintf(err, errlen, "path data must start with a moveto (offset %ld)",
                         (long)(s - d));
                return -1;
            }
            cmd = *s++;
            if (arg_count(cmd) < 0) {
                snprintf(err, errlen, "unknown path command '%c' at offset %ld", cmd,
                         (long)(s - 1 - d));
                return -1;
            }
        } else if (!cmd) {
            snprintf(err, errlen, "path data must start with a moveto (offset %ld)", (long)(s - d));
            return -1;
        } else if (toupper((unsigned char)cmd) == 'Z') {
            snprintf(err, errlen, "number after closepath at offset %ld", (long)(s - d));
            return -1;
        } else if (*s == ',' && prev == 0) {
            s++;
        }
        bool rel = islower((unsigned char)cmd) != 0;
        char up = (char)toupper((unsigned char)cmd);
        double a[7];
        bool flags[2] = {false, false};
        int need = arg_count(cmd);
        const char *at = s;
        for (int i = 0; i < need; i++) {
            bool ok = (up == 'A' && (i == 3 || i == 4)) ? parse_flag(&s, &flags[i - 3])
                                                        : sv_parse_number(&s, &a[i]);
            if (!ok) {
                snprintf(err, errlen, "path command '%c' expects %d numbers at offset %ld", cmd,
                         need, (long)(at - d));
                return -1;
            }
        }
        sv_pt c = path->cur;
        double ox = rel ? c.x : 0, oy = rel ? c.y : 0;
        switch (up) {
        case 'M':
            sv_path_move(path, a[0] + ox, a[1] + oy);
            cmd = rel ? 'l' : 'L'; /* further pairs are implicit linetos */
            break;
        case 'L':
            sv_path_line(path, a[0] + ox, a[1] + oy);
            break;
        case 'H':
            sv_path_line(path, a[0] + ox, c.y);
            break;
        case 'V':
            sv_path_line(path, c.x, a[0] + oy);
            break;
        case 'C':
            sv_path_cubic(path, a[0] + ox, a[1] + oy, a[2] + ox, a[3] + oy, a[4] + ox, a[5] + oy);
            ctrl = sv_pt_make(a[2] + ox, a[3] + oy);
            break;
        case 'S': {
            sv_pt r = (prev == 'C' || prev == 'S') ? sv_sub(sv_scale(c, 2), ctrl) : c;
            sv_path_cubic(path, r.x, r.y, a[0] + ox, a[1] + oy, a[2] + ox, a[3] + oy);
            ctrl = sv_pt_make(a[0] + ox, a[1] + oy);
            break;
        }
        case 'Q':
            sv_path_quad(path, a[0] + ox, a[1] + oy, a[2] + ox, a[3] + oy);
            ctrl = sv_pt_make(a[0] + ox, a[1] + oy);
            break;
        case 'T': {
            sv_pt r = (prev == 'Q' || prev == 'T') ? sv_sub(sv_scale(c, 2), ctrl) : c;
            sv_path_quad(path, r.x, r.y, a[0] + ox, a[1] + oy);
            ctrl = r;
            break;
        }
        case 'A':
            sv_path_arc(path, a[0], a[1], a[2], flags[0], flags[1], a[5] + ox, a[6] + oy);
            break;
        case 'Z':
            sv_path_close(path);
            break;
        }
        prev = up == 'M' ? 'M' : up;
    }
}

int sv_parse_points(const char *s, sv_path *path, bool close)
{
    double x, y;
    int n = 0;
    while (sv_parse_number(&s, &x)) {
        if (!sv_parse_number(&s, &y))
            return -1; /* odd count: SVG renders up to the last full pair */
        if (n++ == 0)
            sv_path_move(path, x, y);
        else
            sv_path_line(path, x, y);
    }
    if (close)
        sv_path_close(path);
    return n;
}
