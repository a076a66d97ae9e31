/*
 * sv_font.c - font choice through fontconfig, per character.
 *
 * A browser resolves font-family by walking its list, generic families
 * included, with the weight, style and language, and falls back per
 * character to another installed face when the chosen one has no glyph.
 * fontconfig does the same work for desktop programs (librsvg, Firefox on
 * Linux): FcFontSort orders every installed face by how well it matches the
 * pattern (family list first, then language, style, weight), with generic
 * names expanded by the system's alias rules. So a style becomes one such
 * order, computed once per import, and a character takes the first face of
 * it whose charset holds the character. Bitmap and colour faces (emoji) are
 * skipped: the importer needs outlines.
 */
#include <fontconfig/fontconfig.h>
#include <ft2build.h>
#include FT_FREETYPE_H
#include <hb-ft.h>
#include <hb.h>

#include <stdio.h>

#include "sv_font.h"
#include "sv_internal.h"

typedef struct order {
    char *key; /* family | weight | italic | lang */
    FcFontSet *set;
} order;

typedef struct face {
    char *file;
    int index;
    FT_Face face; /* NULL when FreeType could not open it */
    hb_font_t *hb; /* made on first use */
} face;

struct sv_fonts {
    FT_Library lib;
    char *fixed;
    bool lib_ok;
    order *orders;
    int norders, caporders;
    face *faces;
    int nfaces, capfaces;
};

sv_fonts *sv_fonts_new(const char *fixed_file)
{
    sv_fonts *f = sv_xrealloc(NULL, sizeof *f);
    memset(f, 0, sizeof *f);
    f->fixed = fixed_file ? sv_xstrdup(fixed_file) : NULL;
    f->lib_ok = FT_Init_FreeType(&f->lib) == 0;
    return f;
}

void sv_fonts_free(sv_fonts *f)
{
    if (!f)
        return;
    for (int i = 0; i < f->norders; i++) {
        free(f->orders[i].key);
        if (f->orders[i].set)
            FcFontSetDestroy(f->orders[i].set);
    }
    for (int i = 0; i < f->nfaces; i++) {
        free(f->faces[i].file);
        if (f->faces[i].hb)
            hb_font_destroy(f->faces[i].hb);
        if (f->faces[i].face)
            FT_Done_Face(f->faces[i].face);
    }
    free(f->orders);
    free(f->faces);
    free(f->fixed);
    if (f->lib_ok)
        FT_Done_FreeType(f->lib);
    free(f);
}

/* Adds each name of a CSS family list, quotes and spaces stripped, in order. */
static void add_families(FcPattern *p, const char *list)
{
    const char *s = list;
    while (*s) {
        while (*s == ' ' || *s == '\t' || *s == ',')
            s++;
        if (!*s)
            break;
        char name[128];
        size_t n = 0;
        char quote = (*s == '"' || *s == '\'') ? *s++ : 0;
        while (*s && (quote ? *s != quote : *s != ',')) {
            if (n + 1 < sizeof name)
                name[n++] = *s;
            s++;
        }
        if (quote && *s)
            s++;
        while (n > 0 && (name[n - 1] == ' ' || name[n - 1] == '\t'))
            n--;
        name[n] = 0;
        if (n > 0)
            FcPatternAddString(p, FC_FAMILY, (const FcChar8 *)name);
        while (*s && *s != ',')
            s++;
    }
}

static FcFontSet *sort_faces(const char *family, int weight, bool italic, const char *lang)
{
    if (!FcInit())
        return NULL;
    FcPattern *p = FcPatternCreate();
    if (!p)
        return NULL;
    add_families(p, family);
    int w = weight < 1 ? 1 : weight > 1000 ? 1000 : weight;
    FcPatternAddInteger(p, FC_WEIGHT, FcWeightFromOpenType(w));
    FcPatternAddInteger(p, FC_SLANT, italic ? FC_SLANT_ITALIC : FC_SLANT_ROMAN);
    if (lang && *lang)
        FcPatternAddString(p, FC_LANG, (const FcChar8 *)lang);
    FcConfigSubstitute(NULL, p, FcMatchPattern);
    FcDefaultSubstitute(p);
    FcResult r;
    FcFontSet *set = FcFontSort(NULL, p, FcTrue, NULL, &r);
    FcPatternDestroy(p);
    return set;
}

static FcFontSet *order_for(sv_fonts *f, const char *family, int weight, bool italic,
                            const char *lang)
{
    char key[300];
    snprintf(key, sizeof key, "%s|%d|%d|%s", family, weight, italic, lang ? lang : "");
    for (int i = 0; i < f->norders; i++)
        if (!strcmp(f->orders[i].key, key))
            return f->orders[i].set;
    SV_GROW(f->orders, f->norders, f->caporders);
    order *o = &f->orders[f->norders++];
    o->key = sv_xstrdup(key);
    o->set = sort_faces(family, weight, italic, lang);
    return o->set;
}

static bool usable(FcPattern *font)
{
    FcBool b;
    if (FcPatternGetBool(font, FC_OUTLINE, 0, &b) == FcResultMatch && !b)
        return false;
#ifdef FC_COLOR
    if (FcPatternGetBool(font, FC_COLOR, 0, &b) == FcResultMatch && b)
        return false;
#endif
    return true;
}

static bool has_char(FcPattern *font, unsigned long cp)
{
    FcCharSet *cs;
    return FcPatternGetCharSet(font, FC_CHARSET, 0, &cs) == FcResultMatch &&
           FcCharSetHasChar(cs, (FcChar32)cp);
}

/* The first usable face of the order holding cp, else the first usable one. */
static FcPattern *pick(FcFontSet *set, unsigned long cp)
{
    FcPattern *first = NULL;
    for (int i = 0; set && i < set->nfont; i++) {
        FcPattern *font = set->fonts[i];
        if (!usable(font))
            continue;
        if (!first)
            first = font;
        if (has_char(font, cp))
            return font;
    }
    return first;
}

static face *open_face(sv_fonts *f, const char *file, int index)
{
    for (int i = 0; i < f->nfaces; i++)
        if (f->faces[i].index == index && !strcmp(f->faces[i].file, file))
            return &f->faces[i];
    SV_GROW(f->faces, f->nfaces, f->capfaces);
    face *fc = &f->faces[f->nfaces++];
    fc->file = sv_xstrdup(file);
    fc->index = index;
    fc->face = NULL;
    fc->hb = NULL;
    FT_Face ft;
    if (f->lib_ok && FT_New_Face(f->lib, file, index, &ft) == 0) {
        if (FT_IS_SCALABLE(ft) && ft->units_per_EM > 0)
            fc->face = ft;
        else
            FT_Done_Face(ft);
    }
    return fc;
}

struct FT_FaceRec_ *sv_font_face(sv_fonts *f, const char *family, int weight, bool italic,
                                 const char *lang, unsigned long cp, const char **file,
                                 char *err, size_t errlen)
{
    const char *path = f->fixed;
    int index = 0;
    if (!path) {
        FcPattern *font = pick(order_for(f, family, weight, italic, lang), cp);
        FcChar8 *fp;
        if (!font || FcPatternGetString(font, FC_FILE, 0, &fp) != FcResultMatch) {
            snprintf(err, errlen, "fontconfig finds no outline font for '%s'", family);
            return NULL;
        }
        FcPatternGetInteger(font, FC_INDEX, 0, &index);
        path = (const char *)fp;
    }
    face *fc = open_face(f, path, index);
    if (!fc->face) {
        snprintf(err, errlen, "%s: cannot open as a scalable font", fc->file);
        return NULL;
    }
    if (file)
        *file = fc->file;
    return fc->face;
}

struct hb_font_t *sv_font_hb(sv_fonts *f, struct FT_FaceRec_ *ft)
{
    for (int i = 0; i < f->nfaces; i++) {
        face *fc = &f->faces[i];
        if (fc->face != ft)
            continue;
        if (!fc->hb) {
            hb_face_t *hf = hb_ft_face_create_referenced(ft);
            fc->hb = hb_font_create(hf);
            hb_face_destroy(hf);
            hb_font_set_scale(fc->hb, ft->units_per_EM, ft->units_per_EM);
        }
        return fc->hb;
    }
    return NULL;
}

int sv_font_match(const char *family, int weight, bool italic, const char *lang,
                  unsigned long cp, char *file, size_t len)
{
    FcFontSet *set = sort_faces(family, weight, italic, lang);
    FcPattern *font = pick(set, cp);
    FcChar8 *path;
    int rc = -1;
    if (font && FcPatternGetString(font, FC_FILE, 0, &path) == FcResultMatch) {
        snprintf(file, len, "%s", (const char *)path);
        rc = 0;
    }
    if (set)
        FcFontSetDestroy(set);
    return rc;
}
