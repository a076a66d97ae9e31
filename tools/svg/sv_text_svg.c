/*
 * sv_text_svg.c - layout of SVG <text>: runs of glyph outlines in user space.
 *
 * Character data and <tspan>s are taken in document order (the element tree
 * keeps character data as "#text" children for this). Each run is set with
 * FreeType (sv_text.c) in the font its style maps to, at the pen position,
 * and the pen advances by the run's advance. x or y on the element or a
 * tspan starts a new text chunk at that absolute position; dx/dy shift the
 * pen; text-anchor then moves each chunk by half or all of its width. Only
 * the first value of each of x/y/dx/dy is used (per-glyph lists are warned).
 * White space follows xml:space: by default newlines and tabs become spaces,
 * runs of spaces collapse across tspans, and the text is trimmed at both
 * ends; "preserve" keeps every space.
 *
 * Font families map to the DejaVu faces installed by fonts-dejavu-core
 * (sans, serif, mono; bold; italic/oblique), which is also what librsvg's
 * fontconfig picks here for the generic families.
 */
#include <ctype.h>
#include <math.h>

#include "sv_import.h"
#include "sv_internal.h"
#include "sv_text.h"

typedef struct pending {
    const sv_node *node;
    sv_style style;
    char *text;
    bool set_x, set_y;
    double x, y, dx, dy;
    bool new_chunk;
} pending;

typedef struct layout {
    pending *p;
    int n, cap;
    bool preserve, last_space;
    const sv_css *css;
    double vp_w, vp_h;
    sv_doc *doc;
} layout;

static const char *family_font(const sv_style *s, bool *mapped)
{
    const char *f = s->font_family;
    bool mono = strstr(f, "ono") != NULL, serif = strstr(f, "erif") && !strstr(f, "ans");
    bool bold = s->font_weight >= 600, it = s->font_italic;
    *mapped = !(strstr(f, "DejaVu") || strstr(f, "sans") || strstr(f, "Sans") || serif || mono);
    if (mono)
        return bold ? (it ? "DejaVuSansMono-BoldOblique.ttf" : "DejaVuSansMono-Bold.ttf")
                    : (it ? "DejaVuSansMono-Oblique.ttf" : "DejaVuSansMono.ttf");
    if (serif)
        return bold ? (it ? "DejaVuSerif-BoldItalic.ttf" : "DejaVuSerif-Bold.ttf")
                    : (it ? "DejaVuSerif-Italic.ttf" : "DejaVuSerif.ttf");
    return bold ? (it ? "DejaVuSans-BoldOblique.ttf" : "DejaVuSans-Bold.ttf")
                : (it ? "DejaVuSans-Oblique.ttf" : "DejaVuSans.ttf");
}

/* Reads the first length of an attribute list; warns if there are more. */
static bool first_len(layout *L, const sv_node *n, const char *name, double ref,
                      const sv_style *s, double *v)
{
    const char *a = sv_attr(n, name);
    if (!a)
        return false;
    double vals[2];
    int k = sv_parse_numbers(a, vals, 2);
    if (k == 0)
        return false;
    if (k > 1)
        sv_doc_warn(L->doc, "<%s> (line %d): per-glyph %s positions not supported, first used",
                    n->name, n->line, name);
    if (!sv_parse_length(a, s->font_size, ref, v))
        *v = vals[0];
    return true;
}

static void add_run(layout *L, const sv_node *owner, const sv_style *s, const char *raw,
                    size_t len, pending *pos)
{
    char *t = sv_xrealloc(NULL, len + 1);
    size_t k = 0;
    for (size_t i = 0; i < len; i++) {
        char ch = raw[i];
        if (ch == '\n' || ch == '\r') {
            if (!L->preserve)
                continue; /* SVG 1.1 default: newlines are removed */
            ch = ' ';
        }
        if (ch == '\t')
            ch = ' ';
        if (ch == ' ' && !L->preserve) {
            if (L->last_space)
                continue;
            L->last_space = true;
        } else if (ch != ' ') {
            L->last_space = false;
        }
        t[k++] = ch;
    }
    t[k] = 0;
    if (k == 0 && !pos->set_x && !pos->set_y && !pos->dx && !pos->dy) {
        free(t);
        return;
    }
    SV_GROW(L->p, L->n, L->cap);
    pending *r = &L->p[L->n++];
    *r = *pos;
    r->node = owner;
    r->style = *s;
    r->text = t;
    memset(pos, 0, sizeof *pos); /* positions apply once, to the next run */
}

static void walk(layout *L, const sv_node *n, const sv_style *s, pending *pos)
{
    for (int i = 0; i < n->nkids; i++) {
        const sv_node *k = n->kids[i];
        if (!strcmp(k->name, "#text")) {
            add_run(L, n, s, k->text, k->textlen, pos);
        } else if (!strcmp(k->name, "tspan") || !strcmp(k->name, "a")) {
            sv_style ks;
            sv_style_compute(&ks, s, k, L->css, sqrt((L->vp_w * L->vp_w + L->vp_h * L->vp_h) / 2),
                             L->doc);
            if (ks.display_none)
                continue;
            double v;
            if (first_len(L, k, "x", L->vp_w, &ks, &v)) {
                pos->set_x = pos->new_chunk = true;
                pos->x = v;
            }
            if (first_len(L, k, "y", L->vp_h, &ks, &v)) {
                pos->set_y = pos->new_chunk = true;
                pos->y = v;
            }
            if (first_len(L, k, "dx", L->vp_w, &ks, &v))
                pos->dx += v;
            if (first_len(L, k, "dy", L->vp_h, &ks, &v))
                pos->dy += v;
            walk(L, k, &ks, pos);
        } else if (strncmp(k->name, "ns:", 3) != 0 && strcmp(k->name, "title") != 0 &&
                   strcmp(k->name, "desc") != 0) {
            sv_doc_warn(L->doc, "<%s> (line %d) in <text>: not supported, not drawn", k->name,
                        k->line);
        }
    }
}

int sv_svg_text_layout(const sv_node *text, const sv_style *style, const sv_css *css,
                       double vp_w, double vp_h, const char *font_path, sv_text_run **out,
                       sv_doc *doc)
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
    pending pos;
    memset(&pos, 0, sizeof pos);
    double v;
    pos.new_chunk = true;
    pos.set_x = pos.set_y = true;
    if (first_len(&L, text, "x", vp_w, style, &v))
        pos.x = v;
    if (first_len(&L, text, "y", vp_h, style, &v))
        pos.y = v;
    if (first_len(&L, text, "dx", vp_w, style, &v))
        pos.dx = v;
    if (first_len(&L, text, "dy", vp_h, style, &v))
        pos.dy = v;
    walk(&L, text, style, &pos);
    if (!L.preserve) /* trailing spaces go too */
        for (int i = L.n - 1; i >= 0; i--) {
            size_t k = strlen(L.p[i].text);
            while (k > 0 && L.p[i].text[k - 1] == ' ')
                L.p[i].text[--k] = 0;
            if (k > 0)
                break;
        }
    sv_text_run *runs = sv_xrealloc(NULL, (size_t)(L.n ? L.n : 1) * sizeof *runs);
    double *adv = sv_xrealloc(NULL, (size_t)(L.n ? L.n : 1) * sizeof *adv);
    double *px = sv_xrealloc(NULL, (size_t)(L.n ? L.n : 1) * sizeof *px);
    double penx = 0, peny = 0;
    int chunk_start = 0;
    for (int i = 0; i <= L.n; i++) {
        /* close the chunk before an absolutely positioned run: apply text-anchor */
        if (i == L.n || (i > 0 && L.p[i].new_chunk)) {
            int anchor = chunk_start < L.n ? L.p[chunk_start].style.text_anchor : 0;
            double w = 0;
            for (int k = chunk_start; k < i; k++)
                w += adv[k];
            double shift = anchor == 1 ? -w / 2 : anchor == 2 ? -w : 0;
            for (int k = chunk_start; k < i; k++) {
                sv_affine t = {1, 0, 0, 1, px[k] + shift, 0};
                sv_path_transform(&runs[k].path, t);
            }
            chunk_start = i;
        }
        if (i == L.n)
            break;
        pending *r = &L.p[i];
        if (r->set_x)
            penx = r->x;
        if (r->set_y)
            peny = r->y;
        penx += r->dx;
        peny += r->dy;
        runs[i].node = r->node;
        runs[i].style = sv_xrealloc(NULL, sizeof(sv_style));
        *runs[i].style = r->style;
        sv_path_init(&runs[i].path);
        char path[512];
        bool mapped = false;
        if (font_path)
            snprintf(path, sizeof path, "%s", font_path);
        else
            snprintf(path, sizeof path, "/usr/share/fonts/truetype/dejavu/%s",
                     family_font(&r->style, &mapped));
        if (mapped)
            sv_doc_warn(doc, "<text> (line %d): font-family '%s' set in %s", text->line,
                        r->style.font_family, path);
        sv_text_metrics m;
        char err[300];
        adv[i] = 0;
        /* the run at the pen's y; x is placed with the chunk's anchor */
        if (sv_text_path(r->text, path, r->style.font_size, 0, peny, &runs[i].path, NULL, &m, err,
                         sizeof err) < 0)
            sv_doc_warn(doc, "<text> (line %d): %s", text->line, err);
        else
            adv[i] = m.advance;
        px[i] = penx;
        penx += adv[i];
        free(r->text);
    }
    free(adv);
    free(px);
    free(L.p);
    *out = runs;
    return L.n;
}

void sv_text_runs_free(sv_text_run *runs, int n)
{
    for (int i = 0; i < n; i++) {
        sv_path_free(&runs[i].path);
        free(runs[i].style);
    }
    free(runs);
}
