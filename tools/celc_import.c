/*
 * celc_import.c - the `celc import` and `celc text` subcommands.
 *
 * `celc import drawing.svg -o scene.json` runs the SVG importer (tools/svg)
 * and writes the scene JSON of the authoring contract (docs/SCENE.md:
 * gradients as paint functions, clip paths as CSG, and "canvas": {"blend":
 * "srgb"} so the scene asks to be blended as SVG renderers do); every
 * warning the importer raised (unsupported elements, gradients the core's
 * functions cannot draw, clips beyond CSG capacity) goes to stderr naming
 * the element. `-o out.cels` writes the binary cel stream instead
 * (write_cels() below, from the same IR the JSON writer gets).
 *
 * `celc text` sets a string in a font (FreeType) and writes it as a scene
 * with one region of glyph contours.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celc_import.h"
#include "celscan_private.h"
#include "cli_num.h"
#include "cels_write.h"
#include "svg/sv.h"
#include "svg/sv_import.h"
#include "svg/sv_font.h"
#include "svg/sv_text.h"

static int usage_import(void)
{
    fprintf(stderr,
            "usage: celc import DRAWING.svg -o SCENE.json [options]\n"
            "  --tolerance T    stroke outline tolerance in canvas units\n"
            "                   (default: 0.01 px at --nominal px on the longer side)\n"
            "  --nominal PX     output size the default tolerance is meant for (1024)\n"
            "  --background C   give the canvas an opaque background (#rrggbb, name)\n"
            "  --one-cel-per-shape  SVG's per-shape compositing instead of shared cels\n"
            "  --blend srgb|linear  blending the scene asks for: srgb (default, as the\n"
            "                   designer's tool showed it) or linear (celscan's own)\n"
            "  -q               no warnings\n");
    return 2;
}

static bool has_suffix(const char *s, const char *suf)
{
    size_t n = strlen(s), m = strlen(suf);
    return n >= m && strcmp(s + n - m, suf) == 0;
}

static int write_text(const char *path, const char *text)
{
    FILE *f = strcmp(path, "-") == 0 ? stdout : fopen(path, "w");
    if (!f) {
        perror(path);
        return 1;
    }
    fputs(text, f);
    fputc('\n', f);
    if (f != stdout && fclose(f) != 0) {
        perror(path);
        return 1;
    }
    return 0;
}

/*
 * Straight to a cel stream: the IR becomes a scene store through the core's
 * builder calls (the same back end the importer's tests render with), and
 * the host stream writer encodes that, as `celc compile` does for JSON.
 */
static int write_cels(const sv_doc *doc, const char *path)
{
    cs_scene *scene = malloc(sizeof *scene);
    if (!scene) {
        fprintf(stderr, "celc import: out of memory for the scene store\n");
        return 1;
    }
    sv_scene_opts so;
    memset(&so, 0, sizeof so);
    char err[512];
    int rc = 1;
    if (sv_doc_to_scene(doc, &so, scene, err, sizeof err) != 0) {
        fprintf(stderr, "celc import: %s: %s\n", path, err);
    } else {
        FILE *f = fopen(path, "wb");
        if (!f || cels_write_scene(scene, f) != 0 || fclose(f) != 0) {
            fprintf(stderr, "celc import: cannot write %s\n", path);
            remove(path);
        } else {
            rc = 0;
        }
    }
    free(scene);
    return rc;
}

/* One number (sep 0) or two separated by `sep`, the whole string, each
 * within [lo, hi] and read strictly (cli_num.h): "abc", "nan" and "1e400"
 * must not reach a scene file that no loader reads. */
static bool parse_numbers(const char *s, char sep, double lo, double hi, double *a, double *b)
{
    double first, second = 0.0;
    const char *rest = cli_real(s, sep, lo, hi, &first);
    if (!rest || (sep && !cli_real(rest, '\0', lo, hi, &second)))
        return false;
    *a = first;
    if (b)
        *b = second;
    return true;
}

/* Scene coordinates are refused by the core beyond this (cs_config.h). */
#define COORD_MAX 1.0e6

/* A command-line value parse_numbers refused: usage error, exit 2. */
static int bad_arg(const char *command, const char *option, const char *value, const char *want)
{
    fprintf(stderr, "celc %s: %s '%s': expected %s\n", command, option, value, want);
    return 2;
}

static bool parse_bg(const char *s, double rgb[3])
{
    double a;
    return sv_parse_color(s, rgb, &a) == SV_COLOR_RGB;
}

int celc_import_main(int argc, char **argv)
{
    const char *in = NULL, *out = NULL;
    sv_import_opts opts;
    memset(&opts, 0, sizeof opts);
    bool quiet = false, has_bg = false, blend_srgb = true;
    double bg[3];
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-o") && i + 1 < argc) {
            out = argv[++i];
        } else if (!strcmp(a, "--tolerance") && i + 1 < argc) {
            if (!parse_numbers(argv[++i], 0, 0.0, COORD_MAX, &opts.tolerance, NULL))
                return bad_arg("import", "--tolerance", argv[i], "a tolerance in 0..1e6 (0: default)");
        } else if (!strcmp(a, "--nominal") && i + 1 < argc) {
            if (!parse_numbers(argv[++i], 0, 0.0, COORD_MAX, &opts.nominal_px, NULL))
                return bad_arg("import", "--nominal", argv[i], "a size in pixels in 0..1e6 (0: 1024)");
        } else if (!strcmp(a, "--background") && i + 1 < argc) {
            if (!parse_bg(argv[++i], bg)) {
                fprintf(stderr, "celc import: bad colour '%s'\n", argv[i]);
                return 2;
            }
            has_bg = true;
        } else if (!strcmp(a, "--one-cel-per-shape")) {
            opts.one_cel_per_shape = true;
        } else if (!strcmp(a, "--blend") && i + 1 < argc) {
            const char *v = argv[++i];
            if (strcmp(v, "srgb") != 0 && strcmp(v, "linear") != 0)
                return usage_import();
            blend_srgb = strcmp(v, "srgb") == 0;
        } else if (!strcmp(a, "-q")) {
            quiet = true;
        } else if (a[0] == '-' && a[1]) {
            return usage_import();
        } else if (!in) {
            in = a;
        } else {
            return usage_import();
        }
    }
    if (!in || !out)
        return usage_import();
    sv_doc doc;
    char err[512];
    if (sv_import_file(in, &opts, &doc, err, sizeof err) < 0) {
        fprintf(stderr, "celc import: %s\n", err);
        return 1;
    }
    doc.blend_srgb = blend_srgb;
    if (!quiet)
        for (int i = 0; i < doc.nwarnings; i++)
            fprintf(stderr, "%s: warning: %s\n", in, doc.warnings[i]);
    int rc;
    if (has_suffix(out, ".cels")) {
        rc = write_cels(&doc, out);
    } else {
        char *json = sv_doc_to_json(&doc, has_bg ? bg : NULL);
        rc = json ? write_text(out, json) : 1;
        free(json);
    }
    if (rc == 0 && !quiet)
        fprintf(stderr, "%s: %d cels, %zu regions, %zu control points, %d warnings\n", in,
                doc.ncels, sv_doc_region_count(&doc), sv_doc_point_count(&doc), doc.nwarnings);
    sv_doc_free(&doc);
    return rc;
}

static int usage_text(void)
{
    fprintf(stderr, "usage: celc text STRING -o SCENE.json [--font FILE|FAMILY] [--size S]\n"
                    "       [--position X,Y] [--color C] [--canvas WxH] [--background C]\n");
    return 2;
}

int celc_text_main(int argc, char **argv)
{
    const char *text = NULL, *out = NULL, *font = SV_DEFAULT_FONT;
    double size = 48, x = 0, y = 0, cw = 0, ch = 0, color[3] = {0, 0, 0}, bg[3];
    bool has_bg = false, y_given = false;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        double al;
        if (!strcmp(a, "-o") && i + 1 < argc)
            out = argv[++i];
        else if (!strcmp(a, "--font") && i + 1 < argc)
            font = argv[++i];
        else if (!strcmp(a, "--size") && i + 1 < argc) {
            if (!parse_numbers(argv[++i], 0, 1e-3, COORD_MAX, &size, NULL))
                return bad_arg("text", "--size", argv[i], "a text size in 0.001..1e6");
        } else if (!strcmp(a, "--position") && i + 1 < argc) {
            if (!parse_numbers(argv[++i], ',', -COORD_MAX, COORD_MAX, &x, &y))
                return bad_arg("text", "--position", argv[i], "X,Y within +-1e6");
            y_given = true;
        } else if (!strcmp(a, "--canvas") && i + 1 < argc) {
            if (!parse_numbers(argv[++i], 'x', 1e-3, COORD_MAX, &cw, &ch))
                return bad_arg("text", "--canvas", argv[i], "WxH, each in 0.001..1e6");
        } else if (!strcmp(a, "--color") && i + 1 < argc) {
            if (sv_parse_color(argv[++i], color, &al) != SV_COLOR_RGB)
                return usage_text();
        } else if (!strcmp(a, "--background") && i + 1 < argc) {
            if (!parse_bg(argv[++i], bg))
                return usage_text();
            has_bg = true;
        } else if (a[0] == '-' && a[1])
            return usage_text();
        else if (!text)
            text = a;
        else
            return usage_text();
    }
    if (!text || !out)
        return usage_text();
    if (!y_given)
        y = size; /* baseline one em down by default */
    char matched[1024];
    if (!strchr(font, '/')) { /* a family name: fontconfig's face for the text's first character */
        const unsigned char *t = (const unsigned char *)text;
        unsigned long cp = *t ? sv_utf8_next(&t, NULL) : 'A';
        if (sv_font_match(font, 400, false, NULL, cp, matched, sizeof matched) < 0) {
            fprintf(stderr, "celc text: fontconfig finds no font for '%s'\n", font);
            return 1;
        }
        font = matched;
    }
    sv_path p;
    sv_path_init(&p);
    int rule;
    sv_text_metrics m;
    char err[400];
    if (sv_text_path(text, font, size, x, y, &p, &rule, &m, err, sizeof err) < 0) {
        fprintf(stderr, "celc text: %s\n", err);
        sv_path_free(&p);
        return 1;
    }
    sv_doc doc;
    sv_doc_init(&doc);
    doc.width = cw > 0 ? cw : x + m.advance + size * 0.25;
    doc.height = ch > 0 ? ch : y + size * 0.35;
    doc.ncels = 1;
    doc.cels = calloc(1, sizeof *doc.cels);
    doc.cels[0].name = strdup("text");
    doc.cels[0].nregions = 1;
    doc.cels[0].regions = calloc(1, sizeof(sv_region));
    sv_region *r = &doc.cels[0].regions[0];
    r->fill_rule = rule;
    memcpy(r->paint.pigment, color, sizeof color);
    r->paint.medium[0] = r->paint.medium[1] = r->paint.medium[2] = 1;
    r->paint.beta = 1;
    r->paint.gradient = -1;
    r->clip = -1;
    r->source = strdup("text");
    sv_path_to_contours(&p, &r->contours, &r->ncontours);
    sv_path_free(&p);
    char *json = sv_doc_to_json(&doc, has_bg ? bg : NULL);
    int rc = json ? write_text(out, json) : 1;
    free(json);
    fprintf(stderr, "celc text: %d glyphs from %s, %d kerning pairs%s, advance %.3f\n", m.glyphs,
            font, m.kern_pairs, m.has_kerning ? "" : " (font has no kern table)", m.advance);
    sv_doc_free(&doc);
    return rc;
}
