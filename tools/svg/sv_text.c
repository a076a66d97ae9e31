/*
 * sv_text.c - glyph outlines from FreeType as exact contours.
 *
 * Glyphs are loaded with FT_LOAD_NO_SCALE, so the outline is in font units
 * with no hinting, and scaled to canvas units here in double precision.
 * FT_Outline_Decompose turns TrueType's on/off-curve points into conics and
 * lines (and CFF's into cubics); it computes the implied on-curve point
 * between two off-curve points with an integer halving, which would round
 * odd sums. Decomposing with shift = 1 doubles every coordinate first, so
 * every midpoint is exact, and the callbacks halve again in double.
 */
#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_OUTLINE_H

#include <ctype.h>
#include <math.h>

#include "sv_import.h"
#include "sv_internal.h"
#include "sv_text.h"

typedef struct sink {
    sv_path *path;
    double scale, x, y; /* canvas = (x + u * scale, y - v * scale), u v in font units */
    bool open;
} sink;

static sv_pt map_pt(const sink *k, const FT_Vector *v)
{
    /* shift = 1 doubled the coordinates */
    return sv_pt_make(k->x + 0.5 * (double)v->x * k->scale, k->y - 0.5 * (double)v->y * k->scale);
}

static int cb_move(const FT_Vector *to, void *u)
{
    sink *k = u;
    if (k->open)
        sv_path_close(k->path);
    sv_pt p = map_pt(k, to);
    sv_path_move(k->path, p.x, p.y);
    k->open = true;
    return 0;
}

static int cb_line(const FT_Vector *to, void *u)
{
    sink *k = u;
    sv_pt p = map_pt(k, to);
    sv_path_line(k->path, p.x, p.y);
    return 0;
}

static int cb_conic(const FT_Vector *c, const FT_Vector *to, void *u)
{
    sink *k = u;
    sv_pt a = map_pt(k, c), p = map_pt(k, to);
    sv_path_quad(k->path, a.x, a.y, p.x, p.y);
    return 0;
}

static int cb_cubic(const FT_Vector *c1, const FT_Vector *c2, const FT_Vector *to, void *u)
{
    sink *k = u;
    sv_pt a = map_pt(k, c1), b = map_pt(k, c2), p = map_pt(k, to);
    sv_path_cubic(k->path, a.x, a.y, b.x, b.y, p.x, p.y);
    return 0;
}

int sv_text_outline_path(const struct FT_Outline_ *outline, double scale, double x, double y,
                         sv_path *out)
{
    static const FT_Outline_Funcs funcs = {cb_move, cb_line, cb_conic, cb_cubic, 1, 0};
    sink k = {out, scale, x, y, false};
    FT_Error e = FT_Outline_Decompose((FT_Outline *)outline, &funcs, &k);
    if (k.open)
        sv_path_close(out);
    return e ? -1 : 0;
}

unsigned long sv_utf8_next(const unsigned char **s, const unsigned char *end)
{
    const unsigned char *p = *s;
    unsigned long c = *p++;
    int extra = c >= 0xf0 ? 3 : c >= 0xe0 ? 2 : c >= 0xc0 ? 1 : 0;
    if (c >= 0x80 && extra == 0) {
        *s = p;
        return 0xfffd;
    }
    c &= extra == 3 ? 0x07 : extra == 2 ? 0x0f : extra == 1 ? 0x1f : 0x7f;
    for (int i = 0; i < extra; i++) {
        if ((end && p >= end) || (*p & 0xc0) != 0x80) {
            *s = p;
            return 0xfffd;
        }
        c = (c << 6) | (*p++ & 0x3f);
    }
    *s = p;
    return c;
}

int sv_text_path(const char *text, const char *font_path, double size, double x, double y,
                 sv_path *out, int *fill_rule, sv_text_metrics *m, char *err, size_t errlen)
{
    sv_text_metrics local;
    if (!m)
        m = &local;
    memset(m, 0, sizeof *m);
    if (fill_rule)
        *fill_rule = CS_FILL_NONZERO;
    if (!font_path)
        font_path = SV_DEFAULT_FONT;
    if (!(size > 0) || !isfinite(size)) {
        snprintf(err, errlen, "text size must be > 0");
        return -1;
    }
    FT_Library lib;
    FT_Face face;
    if (FT_Init_FreeType(&lib)) {
        snprintf(err, errlen, "FreeType initialisation failed");
        return -1;
    }
    if (FT_New_Face(lib, font_path, 0, &face)) {
        snprintf(err, errlen, "%s: cannot open as a font", font_path);
        FT_Done_FreeType(lib);
        return -1;
    }
    if (!FT_IS_SCALABLE(face) || face->units_per_EM == 0) {
        snprintf(err, errlen, "%s: not a scalable (outline) font", font_path);
        FT_Done_Face(face);
        FT_Done_FreeType(lib);
        return -1;
    }
    double scale = size / face->units_per_EM, pen = 0;
    m->has_kerning = FT_HAS_KERNING(face) != 0;
    FT_UInt prev = 0;
    int rc = 0;
    const unsigned char *s = (const unsigned char *)text;
    while (*s) {
        unsigned long cp = sv_utf8_next(&s, NULL);
        FT_UInt gi = FT_Get_Char_Index(face, cp);
        if (prev && m->has_kerning) {
            FT_Vector kv;
            if (!FT_Get_Kerning(face, prev, gi, FT_KERNING_UNSCALED, &kv) && kv.x != 0) {
                pen += (double)kv.x;
                m->kern_pairs++;
            }
        }
        if (FT_Load_Glyph(face, gi, FT_LOAD_NO_SCALE | FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP)) {
            snprintf(err, errlen, "%s: cannot load the glyph of U+%04lX", font_path, cp);
            rc = -1;
            break;
        }
        FT_GlyphSlot g = face->glyph;
        if (g->format == FT_GLYPH_FORMAT_OUTLINE) {
            if (fill_rule && (g->outline.flags & FT_OUTLINE_EVEN_ODD_FILL))
                *fill_rule = CS_FILL_EVENODD;
            sv_text_outline_path((const struct FT_Outline_ *)&g->outline, scale,
                                 x + pen * scale, y, out);
        }
        pen += (double)g->advance.x; /* font units under FT_LOAD_NO_SCALE */
        prev = gi;
        m->glyphs++;
    }
    m->advance = pen * scale;
    FT_Done_Face(face);
    FT_Done_FreeType(lib);
    return rc;
}

int sv_text_add_region(cs_scene *scene, const char *text, const char *font_path, double size,
                       double x, double y, const cs_paint *paint, char *err, size_t errlen)
{
    sv_path p;
    sv_path_init(&p);
    int rule;
    if (sv_text_path(text, font_path, size, x, y, &p, &rule, NULL, err, errlen) < 0) {
        sv_path_free(&p);
        return -1;
    }
    sv_contour *cs = NULL;
    int n = 0;
    sv_path_to_contours(&p, &cs, &n);
    sv_path_free(&p);
    cs_error e;
    cs_status st = cs_scene_add_region(scene, (cs_fill_rule)rule, paint, &e);
    for (int i = 0; i < n && st == CS_OK; i++) {
        cs_point *pts = sv_xrealloc(NULL, (size_t)cs[i].count * sizeof *pts);
        float *iv = sv_xrealloc(NULL, (size_t)cs[i].count * sizeof *iv);
        for (int k = 0; k < cs[i].count; k++) {
            pts[k].x = (float)cs[i].pts[3 * k];
            pts[k].y = (float)cs[i].pts[3 * k + 1];
            pts[k].w = (float)cs[i].pts[3 * k + 2];
            iv[k] = (float)cs[i].intervals[k];
        }
        st = cs_scene_add_contour(scene, cs[i].degree, cs[i].count, pts, iv, &e);
        free(pts);
        free(iv);
    }
    for (int i = 0; i < n; i++)
        sv_contour_free(&cs[i]);
    free(cs);
    if (st != CS_OK) {
        snprintf(err, errlen, "text \"%.40s\": %s", text, cs_status_str(st));
        return -1;
    }
    return 0;
}
