/*
 * sv_text.h - text set in a font through FreeType, as exact outlines.
 *
 * The JSON loader's hook is sv_text_add_region(): a scene JSON element
 *   { "text": "Hello", "font": "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
 *     "size": 48, "position": [x, y], "paint": {...} }
 * becomes one nonzero region of glyph contours in the current (last) cel.
 */
#ifndef SV_TEXT_H
#define SV_TEXT_H

#include "sv.h"

#define SV_DEFAULT_FONT "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"

typedef struct sv_text_metrics {
    double advance;  /* pen advance of the whole string, canvas units */
    int glyphs;      /* glyphs set (missing characters use the font's .notdef) */
    int kern_pairs;  /* pairs the font's kerning moved */
    bool has_kerning;
} sv_text_metrics;

/*
 * Outlines of UTF-8 `text` in the font file at `size` canvas units per em,
 * pen starting at (x, y) on the baseline, y down. Glyphs are loaded unscaled
 * and unhinted and scaled here in double precision, so the contours are the
 * font's own curves: TrueType quadratics stay degree 2 (lines elevated,
 * implied on-curve points exact), CFF cubics degree 3. Kerning comes from
 * the font (FT_Get_Kerning, the 'kern' table). Appends to `out`; the fill
 * rule is written to *fill_rule (nonzero unless the font asks for even-odd).
 * Returns 0, or -1 with a message.
 */
int sv_text_path(const char *text, const char *font_path, double size, double x, double y,
                 sv_path *out, int *fill_rule, sv_text_metrics *metrics, char *err,
                 size_t errlen);

/*
 * The scene JSON `text` element: appends one region with `paint` (linear
 * light, as the loader builds paints) holding the glyph contours to the last
 * cel of `scene`. Returns 0, or -1 with a message naming what failed (font
 * file, capacity, ...); the scene is unchanged on failure of the region
 * itself but contours added before a capacity error remain, as with any
 * cs_scene_add_* sequence.
 */
int sv_text_add_region(cs_scene *scene, const char *text, const char *font_path, double size,
                       double x, double y, const cs_paint *paint, char *err, size_t errlen);

/* Next code point of UTF-8 text, advancing *s (U+FFFD for malformed bytes); `end` bounds
 * the text, or NULL for a NUL-terminated one. */
unsigned long sv_utf8_next(const unsigned char **s, const unsigned char *end);

/* The outline of an FT_Outline-like glyph given as FreeType would decompose it (tests). */
struct FT_Outline_;
int sv_text_outline_path(const struct FT_Outline_ *outline, double scale, double x, double y,
                         sv_path *out);

struct sv_node;
struct sv_style;
struct sv_css;
struct sv_fonts;
/* One run of SVG text: glyph outlines in user space, the element they belong
 * to (<text> or <tspan>) and its computed style (fill, stroke, opacity). */
typedef struct sv_text_run {
    const struct sv_node *node;
    struct sv_style *style;
    sv_path path;
    /* the whole <text>'s box of glyph cells (advance by ascender to descender), user
     * space: its objectBoundingBox, as browsers and resvg take it, not the outlines' box */
    double cell_box[4];
} sv_text_run;

/*
 * Lays out SVG <text> (sv_text_svg.c): character data and <tspan>s in
 * document order, per-character x/y/dx/dy/rotate, text-anchor per text
 * chunk, xml:space, each character in the face fontconfig picks for its
 * style from `fonts` (the import's cache, sv_font.h), shaped by HarfBuzz.
 * Returns the number of runs (malloc'd into *runs); anything it cannot
 * honour is a warning in doc.
 */
int sv_svg_text_layout(const struct sv_node *text, const struct sv_style *style,
                       const struct sv_css *css, double vp_w, double vp_h, struct sv_fonts *fonts,
                       sv_text_run **runs, sv_doc *doc);
void sv_text_runs_free(sv_text_run *runs, int n);

#endif /* SV_TEXT_H */
