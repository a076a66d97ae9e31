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

/* The outline of an FT_Outline-like glyph given as FreeType would decompose it (tests). */
struct FT_Outline_;
int sv_text_outline_path(const struct FT_Outline_ *outline, double scale, double x, double y,
                         sv_path *out);

struct sv_node;
struct sv_style;
/*
 * SVG <text>: the element's character data (tspans concatenated, whitespace
 * collapsed) at its first x/y with its font-size and text-anchor, in user
 * space. font-family maps to the DejaVu faces (sans, serif, mono; bold,
 * italic); anything this cannot honour is a warning in doc.
 */
void sv_svg_text_path(const struct sv_node *n, const struct sv_style *s, double vp_w,
                      double vp_h, const char *font_path, sv_path *out, sv_doc *doc);

#endif /* SV_TEXT_H */
