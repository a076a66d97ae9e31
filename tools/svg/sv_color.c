/*
 * sv_color.c - CSS/SVG colour values: #rgb, #rgba, #rrggbb, #rrggbbaa,
 * rgb()/rgba() with numbers or percentages, hsl()/hsla(), the 148 CSS
 * named colours (CSS Color Module Level 4, section 6.1, including the
 * grey/gray twins and rebeccapurple), `transparent` and `currentColor`.
 * Results are sRGB-encoded 0..1 with a separate alpha, as the IR keeps them.
 */
#include <ctype.h>
#include <math.h>
#include <strings.h>

#include "sv_import.h"
#include "sv_internal.h"

static const struct {
    const char *name;
    unsigned rgb;
} named[] = {
    {"aliceblue", 0xf0f8ff}, {"antiquewhite", 0xfaebd7}, {"aqua", 0x00ffff},
    {"aquamarine", 0x7fffd4}, {"azure", 0xf0ffff}, {"beige", 0xf5f5dc},
    {"bisque", 0xffe4c4}, {"black", 0x000000}, {"blanchedalmond", 0xffebcd},
    {"blue", 0x0000ff}, {"blueviolet", 0x8a2be2}, {"brown", 0xa52a2a},
    {"burlywood", 0xdeb887}, {"cadetblue", 0x5f9ea0}, {"chartreuse", 0x7fff00},
    {"chocolate", 0xd2691e}, {"coral", 0xff7f50}, {"cornflowerblue", 0x6495ed},
    {"cornsilk", 0xfff8dc}, {"crimson", 0xdc143c}, {"cyan", 0x00ffff},
    {"darkblue", 0x00008b}, {"darkcyan", 0x008b8b}, {"darkgoldenrod", 0xb8860b},
    {"darkgray", 0xa9a9a9}, {"darkgreen", 0x006400}, {"darkgrey", 0xa9a9a9},
    {"darkkhaki", 0xbdb76b}, {"darkmagenta", 0x8b008b}, {"darkolivegreen", 0x556b2f},
    {"darkorange", 0xff8c00}, {"darkorchid", 0x9932cc}, {"darkred", 0x8b0000},
    {"darksalmon", 0xe9967a}, {"darkseagreen", 0x8fbc8f}, {"darkslateblue", 0x483d8b},
    {"darkslategray", 0x2f4f4f}, {"darkslategrey", 0x2f4f4f}, {"darkturquoise", 0x00ced1},
    {"darkviolet", 0x9400d3}, {"deeppink", 0xff1493}, {"deepskyblue", 0x00bfff},
    {"dimgray", 0x696969}, {"dimgrey", 0x696969}, {"dodgerblue", 0x1e90ff},
    {"firebrick", 0xb22222}, {"floralwhite", 0xfffaf0}, {"forestgreen", 0x228b22},
    {"fuchsia", 0xff00ff}, {"gainsboro", 0xdcdcdc}, {"ghostwhite", 0xf8f8ff},
    {"gold", 0xffd700}, {"goldenrod", 0xdaa520}, {"gray", 0x808080},
    {"green", 0x008000}, {"greenyellow", 0xadff2f}, {"grey", 0x808080},
    {"honeydew", 0xf0fff0}, {"hotpink", 0xff69b4}, {"indianred", 0xcd5c5c},
    {"indigo", 0x4b0082}, {"ivory", 0xfffff0}, {"khaki", 0xf0e68c},
    {"lavender", 0xe6e6fa}, {"lavenderblush", 0xfff0f5}, {"lawngreen", 0x7cfc00},
    {"lemonchiffon", 0xfffacd}, {"lightblue", 0xadd8e6}, {"lightcoral", 0xf08080},
    {"lightcyan", 0xe0ffff}, {"lightgoldenrodyellow", 0xfafad2}, {"lightgray", 0xd3d3d3},
    {"lightgreen", 0x90ee90}, {"lightgrey", 0xd3d3d3}, {"lightpink", 0xffb6c1},
    {"lightsalmon", 0xffa07a}, {"lightseagreen", 0x20b2aa}, {"lightskyblue", 0x87cefa},
    {"lightslategray", 0x778899}, {"lightslategrey", 0x778899}, {"lightsteelblue", 0xb0c4de},
    {"lightyellow", 0xffffe0}, {"lime", 0x00ff00}, {"limegreen", 0x32cd32},
    {"linen", 0xfaf0e6}, {"magenta", 0xff00ff}, {"maroon", 0x800000},
    {"mediumaquamarine", 0x66cdaa}, {"mediumblue", 0x0000cd}, {"mediumorchid", 0xba55d3},
    {"mediumpurple", 0x9370db}, {"mediumseagreen", 0x3cb371}, {"mediumslateblue", 0x7b68ee},
    {"mediumspringgreen", 0x00fa9a}, {"mediumturquoise", 0x48d1cc}, {"mediumvioletred", 0xc71585},
    {"midnightblue", 0x191970}, {"mintcream", 0xf5fffa}, {"mistyrose", 0xffe4e1},
    {"moccasin", 0xffe4b5}, {"navajowhite", 0xffdead}, {"navy", 0x000080},
    {"oldlace", 0xfdf5e6}, {"olive", 0x808000}, {"olivedrab", 0x6b8e23},
    {"orange", 0xffa500}, {"orangered", 0xff4500}, {"orchid", 0xda70d6},
    {"palegoldenrod", 0xeee8aa}, {"palegreen", 0x98fb98}, {"paleturquoise", 0xafeeee},
    {"palevioletred", 0xdb7093}, {"papayawhip", 0xffefd5}, {"peachpuff", 0xffdab9},
    {"peru", 0xcd853f}, {"pink", 0xffc0cb}, {"plum", 0xdda0dd},
    {"powderblue", 0xb0e0e6}, {"purple", 0x800080}, {"rebeccapurple", 0x663399},
    {"red", 0xff0000}, {"rosybrown", 0xbc8f8f}, {"royalblue", 0x4169e1},
    {"saddlebrown", 0x8b4513}, {"salmon", 0xfa8072}, {"sandybrown", 0xf4a460},
    {"seagreen", 0x2e8b57}, {"seashell", 0xfff5ee}, {"sienna", 0xa0522d},
    {"silver", 0xc0c0c0}, {"skyblue", 0x87ceeb}, {"slateblue", 0x6a5acd},
    {"slategray", 0x708090}, {"slategrey", 0x708090}, {"snow", 0xfffafa},
    {"springgreen", 0x00ff7f}, {"steelblue", 0x4682b4}, {"tan", 0xd2b48c},
    {"teal", 0x008080}, {"thistle", 0xd8bfd8}, {"tomato", 0xff6347},
    {"turquoise", 0x40e0d0}, {"violet", 0xee82ee}, {"wheat", 0xf5deb3},
    {"white", 0xffffff}, {"whitesmoke", 0xf5f5f5}, {"yellow", 0xffff00},
    {"yellowgreen", 0x9acd32},
};

int sv_named_color_count(void)
{
    return (int)(sizeof named / sizeof named[0]);
}

static int hexval(int c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    c = tolower(c);
    return (c >= 'a' && c <= 'f') ? c - 'a' + 10 : -1;
}

static double clamp01(double v)
{
    return v < 0 ? 0 : (v > 1 ? 1 : v);
}

/* One rgb()/hsl() argument: a number (of `scale`) or a percentage. */
static bool func_arg(const char **s, double scale, double *v)
{
    const char *p = *s;
    while (*p == ' ' || *p == ',' || *p == '/' || *p == '\t')
        p++;
    if (!sv_parse_number(&p, v))
        return false;
    if (*p == '%') {
        *v /= 100;
        p++;
    } else {
        *v /= scale;
    }
    *s = p;
    return true;
}

static double hue_to_rgb(double m1, double m2, double h)
{
    h -= floor(h);
    if (h * 6 < 1)
        return m1 + (m2 - m1) * h * 6;
    if (h * 2 < 1)
        return m2;
    if (h * 3 < 2)
        return m1 + (m2 - m1) * (2.0 / 3 - h) * 6;
    return m1;
}

sv_color_kind sv_parse_color(const char *s, double rgb[3], double *alpha)
{
    while (isspace((unsigned char)*s))
        s++;
    size_t n = strlen(s);
    while (n > 0 && isspace((unsigned char)s[n - 1]))
        n--;
    *alpha = 1;
    if (n == 0)
        return SV_COLOR_INVALID;
    if (s[0] == '#') {
        int d[8], k = (int)n - 1;
        if (k != 3 && k != 4 && k != 6 && k != 8)
            return SV_COLOR_INVALID;
        for (int i = 0; i < k; i++)
            if ((d[i] = hexval((unsigned char)s[1 + i])) < 0)
                return SV_COLOR_INVALID;
        if (k <= 4) {
            for (int i = 0; i < 3; i++)
                rgb[i] = d[i] * 17 / 255.0;
            if (k == 4)
                *alpha = d[3] * 17 / 255.0;
        } else {
            for (int i = 0; i < 3; i++)
                rgb[i] = (d[2 * i] * 16 + d[2 * i + 1]) / 255.0;
            if (k == 8)
                *alpha = (d[6] * 16 + d[7]) / 255.0;
        }
        return SV_COLOR_RGB;
    }
    if (n == 12 && strncasecmp(s, "currentColor", 12) == 0)
        return SV_COLOR_CURRENT;
    if (n == 11 && strncasecmp(s, "transparent", 11) == 0) {
        rgb[0] = rgb[1] = rgb[2] = 0;
        *alpha = 0;
        return SV_COLOR_RGB;
    }
    if (strncasecmp(s, "rgb", 3) == 0 || strncasecmp(s, "hsl", 3) == 0) {
        bool hsl = tolower((unsigned char)s[0]) == 'h';
        const char *p = strchr(s, '(');
        if (!p)
            return SV_COLOR_INVALID;
        p++;
        double v[4];
        if (hsl) {
            if (!func_arg(&p, 360, &v[0]) || !func_arg(&p, 1, &v[1]) || !func_arg(&p, 1, &v[2]))
                return SV_COLOR_INVALID;
            /* a bare hue is in degrees; func_arg divided it by 360 already */
            double l = clamp01(v[2]), sat = clamp01(v[1]);
            double m2 = l <= 0.5 ? l * (sat + 1) : l + sat - l * sat, m1 = l * 2 - m2;
            rgb[0] = hue_to_rgb(m1, m2, v[0] + 1.0 / 3);
            rgb[1] = hue_to_rgb(m1, m2, v[0]);
            rgb[2] = hue_to_rgb(m1, m2, v[0] - 1.0 / 3);
        } else {
            for (int i = 0; i < 3; i++) {
                if (!func_arg(&p, 255, &v[i]))
                    return SV_COLOR_INVALID;
                rgb[i] = clamp01(v[i]);
            }
        }
        if (func_arg(&p, 1, &v[3]))
            *alpha = clamp01(v[3]);
        while (*p == ' ')
            p++;
        return *p == ')' ? SV_COLOR_RGB : SV_COLOR_INVALID;
    }
    for (size_t i = 0; i < sizeof named / sizeof named[0]; i++)
        if (strlen(named[i].name) == n && strncasecmp(named[i].name, s, n) == 0) {
            rgb[0] = ((named[i].rgb >> 16) & 255) / 255.0;
            rgb[1] = ((named[i].rgb >> 8) & 255) / 255.0;
            rgb[2] = (named[i].rgb & 255) / 255.0;
            return SV_COLOR_RGB;
        }
    return SV_COLOR_INVALID;
}

double sv_srgb_to_linear(double v)
{
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}
