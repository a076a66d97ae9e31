/*
 * sv_import.h - the importer's internal interfaces: the element tree built
 * with expat, CSS rules and computed styles, and the parsers of SVG's small
 * languages (numbers, path data, colours, transforms, lengths). Unit tests
 * include it to test the pieces one by one.
 */
#ifndef SV_IMPORT_H
#define SV_IMPORT_H

#include "sv.h"

/* ------------------------------------------------------------- parsers */

const char *sv_skip_wsp_comma(const char *s);
bool sv_parse_number(const char **s, double *v);
/* Up to max numbers separated by whitespace and/or commas; returns how many. */
int sv_parse_numbers(const char *s, double *out, int max);
/* Path data into `path` (appended). 0, or -1 with err (what was drawn stays). */
int sv_parse_path(const char *d, sv_path *path, char *err, size_t errlen);
/* polyline/polygon points; returns the number of points, -1 on an odd count. */
int sv_parse_points(const char *s, sv_path *path, bool close);
/* A transform list ("translate(3) rotate(45 1 1)"); false on a syntax error. */
bool sv_parse_transform(const char *s, sv_affine *m);

typedef enum sv_color_kind {
    SV_COLOR_INVALID = 0,
    SV_COLOR_RGB,
    SV_COLOR_CURRENT
} sv_color_kind;
sv_color_kind sv_parse_color(const char *s, double rgb[3], double *alpha);
int sv_named_color_count(void);

/* SVG 1.1 section 7.8: viewBox vb onto viewport (x, y, w, h) under preserveAspectRatio par. */
sv_affine sv_viewbox_map(const double vb[4], const char *par, double x, double y, double w,
                         double h);

/* Length units; percentages need the reference length `percent_of`. */
bool sv_parse_length(const char *s, double font_size, double percent_of, double *v);

/* ----------------------------------------------------------- XML tree */

typedef struct sv_node {
    char *name;   /* local name for SVG elements; "ns:" prefix for foreign ones */
    char **attrs; /* name, value, name, value, ..., NULL */
    struct sv_node *parent;
    int index; /* in parent->kids */
    struct sv_node **kids;
    int nkids, capkids;
    char *text; /* character data directly inside the element */
    size_t textlen;
    int line;
} sv_node;

/* Parses XML into a tree (NULL with err on a parse error). */
sv_node *sv_xml_parse(const char *data, size_t len, char *err, size_t errlen);
void sv_xml_free(sv_node *n);
const char *sv_attr(const sv_node *n, const char *name);

/* ---------------------------------------------------------------- CSS */

typedef struct sv_decl {
    char *name, *value;
    bool important; /* "!important": it beats the style attribute and other rules */
} sv_decl;

/* An attribute test: [name] (op 0), or [name op value] with op one of = ~ ^ $ * | */
typedef struct sv_css_attr {
    char *name, *value;
    char op;
} sv_css_attr;

typedef struct sv_css_rule {
    /* the subject's compound selector: element name (or NULL), id (or NULL), classes, ... */
    char *tag, *id;
    char **classes;
    int nclasses;
    sv_css_attr *attrs;
    int nattrs;
    bool first_child;
    /* the compound to the left (NULL: none) and how it relates: ' ' an ancestor,
     * '>' the parent, '+' the previous sibling, '~' an earlier sibling */
    struct sv_css_rule *left;
    char comb;
    int specificity; /* ids * 10000 + (classes, attributes, pseudo-classes) * 100 + tags */
    int order;
    sv_decl *decls;
    int ndecls;
} sv_css_rule;

typedef struct sv_css {
    sv_css_rule *rules;
    int n, cap;
} sv_css;

/*
 * Adds the rules of a style sheet: compound selectors (type, universal,
 * class, id, attribute tests, :first-child) joined by the combinators
 * ' ', '>', '+' and '~'. Other pseudo-classes, pseudo-elements and @-rules
 * are skipped with a warning through `doc`.
 */
void sv_css_parse_sheet(sv_css *css, const char *text, sv_doc *doc);
void sv_css_free(sv_css *css);
/* Parses "a: b; c: d" declarations (style attribute); returns the count. */
int sv_css_parse_decls(const char *text, sv_decl **out);
void sv_decls_free(sv_decl *d, int n);
bool sv_css_matches(const sv_css_rule *r, const sv_node *n);

/* --------------------------------------------------------------- style */

typedef enum sv_paint_kind {
    SV_PAINT_NONE = 0,
    SV_PAINT_COLOR,
    SV_PAINT_CURRENT,
    SV_PAINT_URL
} sv_paint_kind;

typedef struct sv_paint_spec {
    sv_paint_kind kind;
    double rgb[3];
    double alpha; /* from #rrggbbaa / rgba() */
    char url[128];
    sv_paint_kind fallback_kind; /* "url(#a) red": used when the url is unusable */
    double fallback_rgb[3];
} sv_paint_spec;

typedef struct sv_style {
    /* inherited */
    sv_paint_spec fill, stroke;
    double fill_opacity, stroke_opacity;
    int fill_rule, clip_rule;
    double stroke_width;
    sv_cap cap;
    sv_join join;
    double miter_limit;
    double color[3];
    bool visible;
    bool has_dash;
    double dash[16];
    int ndash;
    double dash_offset;
    double font_size;
    char font_family[128];
    int font_weight; /* 1..1000: 400 normal, 700 bold */
    bool font_italic;
    int text_anchor; /* 0 start, 1 middle, 2 end */
    char paint_order[4]; /* 'F'ill, 'S'troke, 'M'arkers in painting order: "FSM" normally */
    char marker[3][128]; /* marker-start, -mid, -end: ids, "" for none */
    /* not inherited */
    bool has_transform; /* the transform property (CSS, style attribute): it replaces the attribute */
    sv_affine transform;
    double opacity;
    bool display_none;
    char clip_path[128], mask[128], filter[128];
    double stop_color[3], stop_opacity;
} sv_style;

void sv_style_initial(sv_style *s);
/* A child's starting style: the parent's inherited properties, others initial. */
void sv_style_inherit(sv_style *child, const sv_style *parent);
/*
 * Applies one property. Unknown properties are ignored; known ones with
 * values this importer cannot honour return false so the caller can warn.
 */
bool sv_style_set(sv_style *s, const sv_style *parent, const char *name, const char *value,
                  double viewport_diag);
/* Presentation attributes, then matching CSS rules, then the style attribute. */
void sv_style_compute(sv_style *s, const sv_style *parent, const sv_node *n, const sv_css *css,
                      double viewport_diag, sv_doc *doc);

#endif /* SV_IMPORT_H */
