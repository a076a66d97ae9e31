/*
 * sv_font.h - fonts chosen as a browser chooses them: fontconfig sorts the
 * installed faces for a CSS font-family list (generic families included),
 * weight, style and language, and each character is set in the first face
 * of that order which has a glyph for it (per-glyph fallback, so CJK in a
 * Latin family draws from a CJK face instead of empty boxes).
 */
#ifndef SV_FONT_H
#define SV_FONT_H

#include <stdbool.h>
#include <stddef.h>

struct FT_FaceRec_;

/* Fonts of one import: fontconfig orders, FreeType faces and HarfBuzz fonts, cached. */
typedef struct sv_fonts sv_fonts;

/* `fixed_file` (may be NULL) sets every character in that one font file instead. */
sv_fonts *sv_fonts_new(const char *fixed_file);
void sv_fonts_free(sv_fonts *f);

/*
 * The face for code point `cp` under a style: `family` is a CSS list
 * ("'Noto Sans', serif"), `weight` 1..1000, `lang` an xml:lang tag or NULL.
 * Returns the first face of fontconfig's order that maps cp to a glyph, the
 * first face when none does (its .notdef box then shows what is missing),
 * or NULL when no usable outline font is installed (err says so). `file`
 * (may be NULL) receives the face's file name.
 */
struct FT_FaceRec_ *sv_font_face(sv_fonts *f, const char *family, int weight, bool italic,
                                 const char *lang, unsigned long cp, const char **file,
                                 char *err, size_t errlen);

/* HarfBuzz's font for a face sv_font_face returned, at one unit per font unit (cached). */
struct hb_font_t;
struct hb_font_t *sv_font_hb(sv_fonts *f, struct FT_FaceRec_ *face);

/* The file fontconfig picks for one character (the unit tests' entry). */
int sv_font_match(const char *family, int weight, bool italic, const char *lang,
                  unsigned long cp, char *file, size_t len);

#endif /* SV_FONT_H */
