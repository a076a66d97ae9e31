/*
 * fw_args.c - command-line words for the firmware (see fw_args.h).
 */
#include "fw_args.h"

int fw_arg(const char *cmdline, const char *key, char *out, size_t len)
{
    size_t klen = 0;
    while (key[klen])
        klen++;
    if (len)
        out[0] = 0;
    for (const char *p = cmdline; p && *p;) {
        while (*p == ' ')
            p++;
        size_t i = 0;
        while (i < klen && p[i] == key[i])
            i++;
        if (i == klen && p[i] == '=') {
            p += klen + 1;
            size_t n = 0;
            while (*p && *p != ' ' && n + 1 < len)
                out[n++] = *p++;
            if (len)
                out[n] = 0;
            return 1;
        }
        while (*p && *p != ' ')
            p++;
    }
    return 0;
}

int fw_parse_u32(const char *s, uint32_t *value)
{
    uint32_t v = 0;
    if (!*s)
        return 0;
    for (; *s; s++) {
        if (*s < '0' || *s > '9' || v > (UINT32_MAX - 9u) / 10u)
            return 0;
        v = v * 10u + (uint32_t)(*s - '0');
    }
    *value = v;
    return 1;
}
