/*
 * sv_text_svg.c - layout of SVG <text>: runs of glyph outlines in user space.
 *
 * Character data and <tspan>s are taken in document order (the element tree
 * keeps character data as "#text" children for this) and flattened into one
 * list of characters, each remembering the element it belongs to. White
 * space follows xml:space: by default newlines are removed, tabs become
 * spaces, runs of spaces collapse across tspans, and the text is trimmed at
 * both ends; "preserve" keeps every space.
 *
 * Positions follow SVG 1.1 section 10.5: the i-th value of x, y, dx, dy on
 * an element belongs to the i-th character inside it, the innermost element
 * with a value for that character wins, and rotate's last value holds for
 * the characters after it. An absolute x or y starts a new text chunk, and
 * text-anchor moves each chunk by half or all of its advance.
 *
 * letter-spacing (after every character) and word-spacing (after each space)
 * move the pen as CSS says; they inherit, "normal" is 0.
 *
 * Each character is set in the face fontconfig picks for its style and
 * script (sv_font.c: the family list, weight, style, xml:lang, and per
 * character fallback). Each stretch of characters in one face, size and
 * language, up to the next absolute position, is shaped by HarfBuzz as one,
 * across tspan edges as browsers do (GPOS kerning, ligatures, marks, Arabic
 * joining, in the script it guesses); each glyph goes into its character's
 * element's run, at the pen, turned by the character's rotate angle about
 * its origin. Directions come from FriBidi (UAX #9, the paragraph direction
 * the `direction` property's, ltr by default, which also swaps text-anchor
 * start and end): a chunk is cut at level changes too, each segment shaped
 * in its direction, and the segments go along the pen in visual order (L2).
 */
#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_TRUETYPE_TABLES_H
#include <fribidi.h>
#include <hb-ft.h>
#include <hb.h>

#include <ctype.h>
#include <math.h>

#include "sv_font.h"
#include "sv_import.h"
#include "sv_internal.h"
#include "sv_text.h"

enum { POS_X, POS_Y, POS_DX, POS_DY, POS_ROT, POS_N };
static const char *const pos_attr[POS_N] = {"x", "y", "dx", "dy", "rotate"};

#define MAX_TSPAN_DEPTH 32

/* An element with positioning lists, and how many characters it has given out. */
typedef struct frame {
    double *v[POS_N];
    int n[POS_N];
    int count;
    double letter, word; /* letter-spacing and word-spacing in force */
} frame;

typedef struct ch {
    unsigned long cp;
    int owner; /* index into layout.owners */
    bool has[4];
    double v[4]; /* absolute x, y, then dx, dy */
    double rot;  /* degrees */
    double space; /* added after it: letter-spacing, and word-spacing after a space */
} ch;

typedef struct owner {
    const sv_node *node;
    sv_style style;
    const char *lang;
} owner;

typedef struct layout {
    ch *c;
    int n, cap;
    owner *own;
    int nown, capown;
    frame stack[MAX_TSPAN_DEPTH];
    int depth;
    bool preserve, last_space;
    const sv_css *css;
    double vp_w, vp_h;
    sv_doc *doc;
} layout;

/* A list of lengths (numbers with units or percentages); malloc'd, count returned. */
static int parse_lengths(const char *a, double ref, const sv_style *s, double **out)
{
    int n = 0, cap = 0;
    double *v = NULL;
    const char *p = a;
    for (;;) {
        p = sv_skip_wsp_comma(p);
        if (!*p)
            break;
        const char *e = p;
        while (*e && !isspace((unsigned char)*e) && *e != ',')
            e++;
        char tok[64];
        size_t len = (size_t)(e - p) < sizeof tok - 1 ? (size_t)(e - p) : sizeof tok - 1;
        memcpy(tok, p, len);
        tok[len] = 0;
        double x;
        if (!sv_parse_length(tok, s->font_size, ref, &x) || !isfinite(x))
            break; /* SVG: an error ends the list */
        SV_GROW(v, n, cap);
        v[n++] = x;
        p = e;
    }
    *out = v;
    return n;
}

/*
 * A property of the element itself: its style attribute's declaration, else
 * its presentation attribute (the order CSS gives them). False if neither.
 */
static bool prop(const sv_node *n, const char *name, char *out, size_t len)
{
    const char *st = sv_attr(n, "style"), *v = NULL;
    size_t nl = strlen(name);
    for (const char *p = st; p && (p = strstr(p, name)) != NULL; p += nl) {
        const char *q = p + nl;
        while (*q == ' ' || *q == '\t')
            q++;
        if (*q == ':' && (p == st || p[-1] == ';' || isspace((unsigned char)p[-1]))) {
            v = q + 1;
            break;
        }
    }
    size_t k = 0;
    if (v) {
        while (*v == ' ' || *v == '\t')
            v++;
        while (v[k] && v[k] != ';' && k + 1 < len)
            k++;
    } else if ((v = sv_attr(n, name)) != NULL) {
        k = strnlen(v, len - 1);
    } else {
        return false;
    }
    memcpy(out, v, k);
    while (k > 0 && isspace((unsigned char)out[k - 1]))
        k--;
    out[k] = 0;
    return true;
}

/* Text properties the layout does not honour, when not at their initial value: named in a
 * warning, never silently ignored. */
static void warn_unsupported(layout *L, const sv_node *n)
{
    static const char *const names[][4] = {
        {"baseline-shift", "baseline", "0", NULL},
        {"dominant-baseline", "auto", "alphabetic", NULL},
        {"alignment-baseline", "auto", "baseline", "alphabetic"},
        {"writing-mode", "lr-tb", "lr", "horizontal-tb"},
        {"textLength", NULL},
        {"font-variant", "normal", NULL},
        {"font-stretch", "normal", NULL}};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        char v[64];
        if (!prop(n, names[i][0], v, sizeof v))
            continue;
        bool initial = false;
        for (int k = 1; k < 4 && names[i][k]; k++)
            initial |= !strcmp(v, names[i][k]);
        if (!initial)
            sv_doc_warn(L->doc, "<%s> (line %d): %s \"%s\" not supported, drawn without",
                        n->name, n->line, names[i][0], v);
    }
}

/* letter-spacing or word-spacing (inherited; "normal" is 0), in user units. */
static double spacing(const sv_node *n, const char *name, const sv_style *s, double inherited)
{
    char v[64];
    double x;
    if (!prop(n, name, v, sizeof v) || !strcmp(v, "inherit"))
        return inherited;
    if (!strcmp(v, "normal"))
        return 0;
    return sv_parse_length(v, s->font_size, s->font_size, &x) && isfinite(x) ? x : inherited;
}

static double ancestor_spacing(const sv_node *n, const char *name, const sv_style *s)
{
    for (const sv_node *a = n->parent; a; a = a->parent) {
        double v = spacing(a, name, s, NAN);
        if (!isnan(v))
            return v;
    }
    return 0;
}

static void push_frame(layout *L, const sv_node *n, const sv_style *s)
{
    warn_unsupported(L, n);
    frame *f = &L->stack[L->depth++];
    memset(f, 0, sizeof *f);
    /* inherited: the enclosing tspan's, or for the text the nearest ancestor's */
    f->letter = spacing(n, "letter-spacing", s,
                        L->depth > 1 ? f[-1].letter : ancestor_spacing(n, "letter-spacing", s));
    f->word = spacing(n, "word-spacing", s,
                      L->depth > 1 ? f[-1].word : ancestor_spacing(n, "word-spacing", s));
    for (int a = 0; a < POS_N; a++) {
        const char *v = sv_attr(n, pos_attr[a]);
        if (!v)
            continue;
        double ref = (a == POS_X || a == POS_DX) ? L->vp_w : L->vp_h;
        if (a == POS_ROT) { /* plain numbers; an invalid list is ignored whole */
            int k = 0, cap = 0;
            const char *p = v;
            double x;
            for (p = sv_skip_wsp_comma(p); *p; p = sv_skip_wsp_comma(p)) {
                if (!sv_parse_number(&p, &x) || !isfinite(x)) {
                    k = 0;
                    break;
                }
                SV_GROW(f->v[a], k, cap);
                f->v[a][k++] = x;
            }
            f->n[a] = k;
        } else {
            f->n[a] = parse_lengths(v, ref, s, &f->v[a]);
        }
    }
}

static void pop_frame(layout *L)
{
    frame *f = &L->stack[--L->depth];
    for (int a = 0; a < POS_N; a++)
        free(f->v[a]);
}

static void add_char(layout *L, unsigned long cp, int owner_index)
{
    SV_GROW(L->c, L->n, L->cap);
    ch *c = &L->c[L->n++];
    memset(c, 0, sizeof *c);
    c->cp = cp;
    c->owner = owner_index;
    for (int a = 0; a < 4; a++)
        for (int d = L->depth - 1; d >= 0; d--) {
            const frame *f = &L->stack[d];
            if (f->count < f->n[a]) {
                c->has[a] = true;
                c->v[a] = f->v[a][f->count];
                break;
            }
        }
    for (int d = L->depth - 1; d >= 0; d--) {
        const frame *f = &L->stack[d];
        if (f->n[POS_ROT] > 0) {
            c->rot = f->v[POS_ROT][f->count < f->n[POS_ROT] ? f->count : f->n[POS_ROT] - 1];
            break;
        }
    }
    const frame *in = &L->stack[L->depth - 1];
    c->space = in->letter + (cp == ' ' ? in->word : 0);
    for (int d = 0; d < L->depth; d++)
        L->stack[d].count++;
}

static void add_text(layout *L, const char *raw, size_t len, int owner_index)
{
    const unsigned char *s = (const unsigned char *)raw, *end = s + len;
    while (s < end) {
        unsigned long cp = sv_utf8_next(&s, end);
        if (cp == '\n' || cp == '\r') {
            if (!L->preserve)
                continue; /* SVG 1.1 default: newlines are removed */
            cp = ' ';
        }
        if (cp == '\t')
            cp = ' ';
        if (cp == ' ' && !L->preserve) {
            if (L->last_space)
                continue;
            L->last_space = true;
        } else if (cp != ' ') {
            L->last_space = false;
        }
        add_char(L, cp, owner_index);
    }
}

static int add_owner(layout *L, const sv_node *n, const sv_style *s, const char *lang)
{
    SV_GROW(L->own, L->nown, L->capown);
    L->own[L->nown].node = n;
    L->own[L->nown].style = *s;
    L->own[L->nown].lang = lang;
    return L->nown++;
}

static const char *lang_of(const sv_node *n, const char *inherited)
{
    const char *l = sv_attr(n, "xml:lang");
    if (!l)
        l = sv_attr(n, "lang");
    return l ? l : inherited;
}

static void walk(layout *L, const sv_node *n, const sv_style *s, const char *lang)
{
    int me = -1;
    for (int i = 0; i < n->nkids; i++) {
        const sv_node *k = n->kids[i];
        if (!strcmp(k->name, "#text")) {
            if (me < 0)
                me = add_owner(L, n, s, lang);
            add_text(L, k->text, k->textlen, me);
        } else if (!strcmp(k->name, "tspan") || !strcmp(k->name, "a")) {
            if (L->depth >= MAX_TSPAN_DEPTH) {
                sv_doc_warn(L->doc, "<%s> (line %d): tspans nested deeper than %d, not drawn",
                            k->name, k->line, MAX_TSPAN_DEPTH);
                continue;
            }
            sv_style ks;
            sv_style_compute(&ks, s, k, L->css, sqrt((L->vp_w * L->vp_w + L->vp_h * L->vp_h) / 2),
                             L->doc);
            if (ks.display_none)
                continue;
            push_frame(L, k, &ks);
            walk(L, k, &ks, lang_of(k, lang));
            pop_frame(L);
            me = -1; /* text after the tspan is a new run of this element */
        } else if (strncmp(k->name, "ns:", 3) != 0 && strcmp(k->name, "title") != 0 &&
                   strcmp(k->name, "desc") != 0) {
            sv_doc_warn(L->doc, "<%s> (line %d) in <text>: not supported, not drawn", k->name,
                        k->line);
        }
    }
}

/*
 * Glyph `gi` of the face at the origin with the decoration lines under its
 * advance `adv` (text-decoration follows each glyph, as resvg draws it),
 * turned by `rot` degrees, then at (x, y). The lines turn as the glyph's
 * outer contour does, so that nonzero filling adds them to it.
 */
static void set_glyph(FT_Face face, unsigned gi, double scale, double rot, double x, double y,
                      const double (*lines)[2], int nlines, double adv, sv_path *out)
{
    if (FT_Load_Glyph(face, gi, FT_LOAD_NO_SCALE | FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP))
        return;
    sv_path gp;
    sv_path_init(&gp);
    if (face->glyph->format == FT_GLYPH_FORMAT_OUTLINE)
        sv_text_outline_path((const struct FT_Outline_ *)&face->glyph->outline, scale, 0, 0, &gp);
    double turn = 0;
    for (int i = 0; i < gp.n && nlines > 0; i++) {
        double a = sv_subpath_area(&gp.sub[i]);
        turn = fabs(a) > fabs(turn) ? a : turn;
    }
    for (int i = 0; i < nlines && adv > 0; i++) {
        double top = lines[i][0], bot = top + lines[i][1];
        sv_path_move(&gp, 0, top);
        if (turn >= 0) { /* clockwise on screen */
            sv_path_line(&gp, adv, top);
            sv_path_line(&gp, adv, bot);
            sv_path_line(&gp, 0, bot);
        } else {
            sv_path_line(&gp, 0, bot);
            sv_path_line(&gp, adv, bot);
            sv_path_line(&gp, adv, top);
        }
        sv_path_close(&gp);
    }
    double r = rot * M_PI / 180, cs = cos(r), sn = sin(r);
    sv_affine m = {cs, sn, -sn, cs, x, y};
    sv_path_transform(&gp, m);
    sv_path_append(out, &gp);
    sv_path_free(&gp);
}

typedef struct chunk {
    double start, end; /* pen x where it starts and after its last glyph */
    int anchor;
} chunk;

/*
 * text-decoration on the element or the nearest ancestor up to the <text>
 * that sets it: the lines under, over and through its glyphs (top relative
 * to the baseline and thickness, user units) from the font's own metrics
 * ('post' underline, OS/2 strikeout, the ascender for the overline).
 * Returns how many.
 */
static int deco_lines(const sv_node *n, const sv_node *text, FT_Face face, double size,
                      double lines[3][2])
{
    char v[64] = "";
    for (const sv_node *a = n; a; a = a == text ? NULL : a->parent)
        if (prop(a, "text-decoration", v, sizeof v))
            break;
    double k = size / face->units_per_EM, t = face->underline_thickness * k;
    const TT_OS2 *os2 = FT_Get_Sfnt_Table(face, FT_SFNT_OS2);
    const double all[3][2] = {
        {-face->underline_position * k - t, t}, /* where resvg draws it */
        {-face->ascender * k, t},
        {os2 ? -os2->yStrikeoutPosition * k : -0.3 * size, os2 ? os2->yStrikeoutSize * k : t}};
    static const char *const names[3] = {"underline", "overline", "line-through"};
    int n_lines = 0;
    for (int i = 0; i < 3; i++)
        if (strstr(v, names[i]) && all[i][1] > 0) {
            lines[n_lines][0] = all[i][0];
            lines[n_lines++][1] = all[i][1];
        }
    return n_lines;
}

/* How far text-anchor moves a chunk: half or all of its advance back. */
static double anchor_shift(const chunk *k)
{
    double w = k->end - k->start;
    return k->anchor == 1 ? -w / 2 : k->anchor == 2 ? -w : 0;
}

/*
 * Bidi embedding levels of characters [cs, ce) (UAX #9 through FriBidi, the
 * paragraph's direction the `direction` property's, ltr unless said): even
 * left to right, odd right to left. All 0 if FriBidi refuses.
 */
static void bidi_levels(const layout *L, int cs, int ce, bool rtl, FriBidiLevel *levels)
{
    int n = ce - cs;
    FriBidiChar *str = sv_xrealloc(NULL, (size_t)n * sizeof *str);
    FriBidiCharType *types = sv_xrealloc(NULL, (size_t)n * sizeof *types);
    FriBidiBracketType *br = sv_xrealloc(NULL, (size_t)n * sizeof *br);
    for (int k = 0; k < n; k++)
        str[k] = (FriBidiChar)L->c[cs + k].cp;
    fribidi_get_bidi_types(str, n, types);
    fribidi_get_bracket_types(str, n, types, br);
    FriBidiParType base = rtl ? FRIBIDI_PAR_RTL : FRIBIDI_PAR_LTR;
    if (!fribidi_get_par_embedding_levels_ex(types, br, n, &base, levels))
        memset(levels, 0, (size_t)n * sizeof *levels);
    free(str);
    free(types);
    free(br);
}

/* UAX #9 rule L2 on whole segments: from the highest level down to the lowest odd one,
 * every run of segments at that level or above is reversed. */
static void visual_order(int (*seg)[2], int n, const FriBidiLevel *levels)
{
    int hi = 0, lo_odd = 255;
    for (int k = 0; k < n; k++) {
        int l = levels[seg[k][0]];
        hi = l > hi ? l : hi;
        if (l & 1)
            lo_odd = l < lo_odd ? l : lo_odd;
    }
    for (int l = hi; l >= lo_odd && l > 0; l--)
        for (int a = 0; a < n;) {
            if (levels[seg[a][0]] < l) {
                a++;
                continue;
            }
            int b = a;
            while (b < n && levels[seg[b][0]] >= l)
                b++;
            for (int x = a, y = b - 1; x < y; x++, y--) {
                int t0 = seg[x][0], t1 = seg[x][1];
                seg[x][0] = seg[y][0];
                seg[x][1] = seg[y][1];
                seg[y][0] = t0;
                seg[y][1] = t1;
            }
            a = b;
        }
}

/*
 * Shapes characters [i0, i1) of L (one face and size, no absolute position
 * after i0; they may belong to several elements, as HarfBuzz then kerns
 * across a tspan's edge) and sets each glyph into the path of its
 * character's run, runs[char_run[i]], from the pen, which it advances.
 * Per-character dx, dy and rotate apply to the first glyph of the
 * character's cluster.
 */
static void shape_segment(const layout *L, int i0, int i1, FT_Face face, hb_font_t *font,
                          const sv_node *text, double *penx, double *peny, bool rtl,
                          sv_text_run *runs, const int *char_run, double ylim[2])
{
    const owner *o = &L->own[L->c[i0].owner];
    hb_buffer_t *buf = hb_buffer_create();
    for (int i = i0; i < i1; i++)
        hb_buffer_add(buf, (hb_codepoint_t)L->c[i].cp, (unsigned)(i - i0));
    hb_buffer_set_content_type(buf, HB_BUFFER_CONTENT_TYPE_UNICODE);
    if (o->lang)
        hb_buffer_set_language(buf, hb_language_from_string(o->lang, -1));
    hb_buffer_guess_segment_properties(buf);
    hb_buffer_set_direction(buf, rtl ? HB_DIRECTION_RTL : HB_DIRECTION_LTR);
    hb_shape(font, buf, NULL, 0);
    unsigned n;
    hb_glyph_info_t *info = hb_buffer_get_glyph_infos(buf, &n);
    hb_glyph_position_t *pos = hb_buffer_get_glyph_positions(buf, &n);
    double scale = o->style.font_size / face->units_per_EM;
    hb_font_extents_t ext;
    if (!hb_font_get_h_extents(font, &ext)) {
        ext.ascender = face->ascender;
        ext.descender = face->descender;
    }
    double lines[3][2];
    int nlines = 0, deco_owner = -1;
    unsigned last = (unsigned)-1;
    for (unsigned g = 0; g < n; g++) {
        const ch *c = &L->c[i0 + (int)info[g].cluster];
        if (info[g].cluster != last) {
            if (g > 0) /* the spacing after the cluster before */
                *penx += L->c[i0 + (int)last].space;
            if (c->has[POS_DX])
                *penx += c->v[POS_DX];
            if (c->has[POS_DY])
                *peny += c->v[POS_DY];
            last = info[g].cluster;
        }
        if (c->owner != deco_owner) { /* its element's decoration */
            deco_owner = c->owner;
            nlines = deco_lines(L->own[c->owner].node, text, face, o->style.font_size, lines);
        }
        set_glyph(face, info[g].codepoint, scale, c->rot, *penx + pos[g].x_offset * scale,
                  *peny - pos[g].y_offset * scale, lines, nlines, pos[g].x_advance * scale,
                  &runs[char_run[i0 + (int)info[g].cluster]].path);
        ylim[0] = fmin(ylim[0], *peny - ext.ascender * scale); /* the glyph's cell */
        ylim[1] = fmax(ylim[1], *peny - ext.descender * scale);
        *penx += pos[g].x_advance * scale;
    }
    if (n > 0)
        *penx += L->c[i0 + (int)last].space;
    hb_buffer_destroy(buf);
}

int sv_svg_text_layout(const sv_node *text, const sv_style *style, const sv_css *css,
                       double vp_w, double vp_h, sv_fonts *F, sv_text_run **out, sv_doc *doc)
{
    layout L;
    memset(&L, 0, sizeof L);
    L.css = css;
    L.vp_w = vp_w;
    L.vp_h = vp_h;
    L.doc = doc;
    const char *sp = sv_attr(text, "xml:space");
    L.preserve = sp && !strcmp(sp, "preserve");
    L.last_space = true; /* leading spaces go */
    const char *lang = NULL;
    for (const sv_node *a = text; a && !lang; a = a->parent)
        lang = lang_of(a, NULL);
    push_frame(&L, text, style);
    walk(&L, text, style, lang);
    pop_frame(&L);
    if (!L.preserve) /* trailing spaces go too */
        while (L.n > 0 && L.c[L.n - 1].cp == ' ')
            L.n--;

    size_t cnt = (size_t)(L.n ? L.n : 1);
    FT_Face *faces = sv_xrealloc(NULL, cnt * sizeof *faces);
    for (int i = 0; i < L.n; i++) {
        const owner *o = &L.own[L.c[i].owner];
        char err[300];
        faces[i] = sv_font_face(F, o->style.font_family, o->style.font_weight,
                                o->style.font_italic, o->lang, L.c[i].cp, NULL, err, sizeof err);
        if (!faces[i])
            sv_doc_warn(doc, "<text> (line %d): %s", text->line, err);
    }
    /* text chunks (to the next absolute position), each cut into segments of one face,
       size, language and bidi level, placed in visual order */
    sv_text_run *runs = sv_xrealloc(NULL, cnt * sizeof *runs);
    int *run_chunk = sv_xrealloc(NULL, cnt * sizeof *run_chunk);
    int *char_run = sv_xrealloc(NULL, cnt * sizeof *char_run);
    chunk *chunks = sv_xrealloc(NULL, cnt * sizeof *chunks);
    FriBidiLevel *levels = sv_xrealloc(NULL, cnt * sizeof *levels);
    int (*seg)[2] = sv_xrealloc(NULL, cnt * sizeof *seg);
    int nr = 0, nch = 0;
    double penx = 0, peny = 0, ylim[2] = {INFINITY, -INFINITY};
    char dir[16] = "";
    for (const sv_node *a = text; a && !prop(a, "direction", dir, sizeof dir); a = a->parent)
        ;
    bool rtl = !strcmp(dir, "rtl");
    for (int cs = 0, ce; cs < L.n; cs = ce) {
        for (ce = cs + 1; ce < L.n && !L.c[ce].has[POS_X] && !L.c[ce].has[POS_Y]; ce++)
            ;
        const ch *c0 = &L.c[cs];
        if (c0->has[POS_X])
            penx = c0->v[POS_X];
        if (c0->has[POS_Y])
            peny = c0->v[POS_Y];
        chunks[nch].start = chunks[nch].end = penx;
        int anchor = L.own[c0->owner].style.text_anchor; /* start and end swap under rtl */
        chunks[nch++].anchor = rtl && anchor != 1 ? 2 - anchor : anchor;
        for (int k = cs; k < ce; k++) { /* a run per element within the chunk */
            const owner *ok = &L.own[L.c[k].owner];
            if (nr == 0 || runs[nr - 1].node != ok->node || run_chunk[nr - 1] != nch - 1) {
                runs[nr].node = ok->node;
                runs[nr].style = sv_xrealloc(NULL, sizeof(sv_style));
                *runs[nr].style = ok->style;
                sv_path_init(&runs[nr].path);
                run_chunk[nr++] = nch - 1;
            }
            char_run[k] = nr - 1;
        }
        bidi_levels(&L, cs, ce, rtl, levels + cs);
        int nseg = 0;
        for (int i = cs, j; i < ce; i = j) {
            const owner *o = &L.own[L.c[i].owner];
            for (j = i + 1; j < ce && faces[j] == faces[i] && levels[j] == levels[i] &&
                            L.own[L.c[j].owner].style.font_size == o->style.font_size &&
                            L.own[L.c[j].owner].lang == o->lang;
                 j++)
                ;
            seg[nseg][0] = i;
            seg[nseg++][1] = j;
        }
        visual_order(seg, nseg, levels);
        for (int k = 0; k < nseg; k++) {
            int i = seg[k][0];
            if (faces[i])
                shape_segment(&L, i, seg[k][1], faces[i], sv_font_hb(F, faces[i]), text, &penx,
                              &peny, levels[i] & 1, runs, char_run, ylim);
        }
        chunks[nch - 1].end = penx;
    }
    free(levels);
    free(seg);
    /* text-anchor: each chunk moves by half or all of its advance; the cells' box spans
       the chunks where they end up */
    for (int r = 0; r < nr; r++) {
        sv_affine t = {1, 0, 0, 1, anchor_shift(&chunks[run_chunk[r]]), 0};
        if (t.e != 0)
            sv_path_transform(&runs[r].path, t);
    }
    double box[4] = {INFINITY, ylim[0], -INFINITY, ylim[1]};
    for (int k = 0; k < nch; k++) {
        double shift = anchor_shift(&chunks[k]);
        box[0] = fmin(box[0], fmin(chunks[k].start, chunks[k].end) + shift);
        box[2] = fmax(box[2], fmax(chunks[k].start, chunks[k].end) + shift);
    }
    if (!(box[0] <= box[2] && box[1] <= box[3]))
        box[0] = box[1] = box[2] = box[3] = 0;
    for (int r = 0; r < nr; r++)
        memcpy(runs[r].cell_box, box, sizeof box);
    free(faces);
    free(char_run);
    free(run_chunk);
    free(chunks);
    free(L.c);
    free(L.own);
    *out = runs;
    return nr;
}

void sv_text_runs_free(sv_text_run *runs, int n)
{
    for (int i = 0; i < n; i++) {
        sv_path_free(&runs[i].path);
        free(runs[i].style);
    }
    free(runs);
}
