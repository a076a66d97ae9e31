/*
 * sv_style.c - CSS and presentation attributes to computed styles, plus the
 * transform and length grammars.
 *
 * The cascade is SVG's: a property starts from the parent (inherited ones)
 * or its initial value, then presentation attributes apply, then matching
 * style sheet rules in order of specificity and appearance, then the style
 * attribute. Style sheets are supported for compound selectors (tag, *,
 * .class, #id and their combinations, in comma lists), which is what icon
 * themes and editors write; anything else is skipped with a warning, never
 * ignored silently.
 */
#include <ctype.h>
#include <math.h>
#include <strings.h>

#include "sv_import.h"
#include "sv_internal.h"

/* ------------------------------------------------------------- lengths */

bool sv_parse_length(const char *s, double font_size, double percent_of, double *v)
{
    const char *p = s;
    double x;
    if (!sv_parse_number(&p, &x))
        return false;
    while (*p == ' ')
        p++;
    static const struct {
        const char *unit;
        double scale; /* user units (px at 96 dpi, as CSS and librsvg) */
    } units[] = {{"px", 1}, {"pt", 96.0 / 72}, {"pc", 16}, {"mm", 96 / 25.4},
                 {"cm", 96 / 2.54}, {"in", 96}, {"", 1}};
    if (*p == '%') {
        *v = x / 100 * percent_of;
        return true;
    }
    if (strncmp(p, "em", 2) == 0) {
        *v = x * font_size;
        return true;
    }
    if (strncmp(p, "ex", 2) == 0) {
        *v = x * font_size / 2;
        return true;
    }
    for (size_t i = 0; i < sizeof units / sizeof units[0]; i++) {
        size_t n = strlen(units[i].unit);
        if (strncmp(p, units[i].unit, n) == 0 && (p[n] == 0 || isspace((unsigned char)p[n]))) {
            *v = x * units[i].scale;
            return true;
        }
    }
    return false;
}

/* ---------------------------------------------------------- transforms */

bool sv_parse_transform(const char *s, sv_affine *out)
{
    sv_affine m = sv_affine_identity();
    for (;;) {
        s = sv_skip_wsp_comma(s);
        if (!*s)
            break;
        const char *name = s;
        while (isalpha((unsigned char)*s))
            s++;
        size_t nlen = (size_t)(s - name);
        while (isspace((unsigned char)*s))
            s++;
        if (*s != '(' || nlen == 0)
            return false;
        s++;
        double a[6];
        int n = 0;
        while (n < 6 && sv_parse_number(&s, &a[n]))
            n++;
        s = sv_skip_wsp_comma(s);
        if (*s != ')')
            return false;
        s++;
        sv_affine t = sv_affine_identity();
#define IS(str) (nlen == strlen(str) && strncmp(name, str, nlen) == 0)
        if (IS("matrix") && n == 6) {
            t.a = a[0], t.b = a[1], t.c = a[2], t.d = a[3], t.e = a[4], t.f = a[5];
        } else if (IS("translate") && (n == 1 || n == 2)) {
            t.e = a[0];
            t.f = n == 2 ? a[1] : 0;
        } else if (IS("scale") && (n == 1 || n == 2)) {
            t.a = a[0];
            t.d = n == 2 ? a[1] : a[0];
        } else if (IS("rotate") && (n == 1 || n == 3)) {
            double r = a[0] * M_PI / 180, c = cos(r), sn = sin(r);
            t.a = c, t.b = sn, t.c = -sn, t.d = c;
            if (n == 3) { /* translate(cx,cy) rotate(a) translate(-cx,-cy) */
                t.e = a[1] - c * a[1] + sn * a[2];
                t.f = a[2] - sn * a[1] - c * a[2];
            }
        } else if (IS("skewX") && n == 1) {
            t.c = tan(a[0] * M_PI / 180);
        } else if (IS("skewY") && n == 1) {
            t.b = tan(a[0] * M_PI / 180);
        } else {
            return false;
        }
#undef IS
        m = sv_affine_mul(m, t);
    }
    *out = m;
    return true;
}

/* ---------------------------------------------------------------- CSS */

static char *trim(char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    size_t n = strlen(s);
    while (n > 0 && isspace((unsigned char)s[n - 1]))
        s[--n] = 0;
    return s;
}

/* Removes comments in place. */
static void strip_comments(char *s)
{
    char *w = s;
    while (*s) {
        if (s[0] == '/' && s[1] == '*') {
            char *e = strstr(s + 2, "*/");
            s = e ? e + 2 : s + strlen(s);
            continue;
        }
        *w++ = *s++;
    }
    *w = 0;
}

int sv_css_parse_decls(const char *text, sv_decl **out)
{
    char *buf = sv_xstrdup(text);
    strip_comments(buf);
    int n = 0, cap = 0;
    *out = NULL;
    char *p = buf;
    while (*p) {
        /* a declaration ends at ';' outside parentheses and quotes */
        char *start = p;
        int depth = 0;
        char quote = 0;
        while (*p && (depth > 0 || quote || *p != ';')) {
            if (quote) {
                if (*p == quote)
                    quote = 0;
            } else if (*p == '"' || *p == '\'') {
                quote = *p;
            } else if (*p == '(') {
                depth++;
            } else if (*p == ')' && depth > 0) {
                depth--;
            }
            p++;
        }
        if (*p)
            *p++ = 0;
        char *colon = strchr(start, ':');
        if (!colon)
            continue;
        *colon = 0;
        char *name = trim(start), *value = trim(colon + 1);
        char *imp = strstr(value, "!important");
        if (imp) {
            *imp = 0;
            value = trim(value);
        }
        bool important = imp != NULL;
        if (!*name)
            continue;
        for (char *c = name; *c; c++)
            *c = (char)tolower((unsigned char)*c);
        SV_GROW(*out, n, cap);
        (*out)[n].name = sv_xstrdup(name);
        (*out)[n].value = sv_xstrdup(value);
        (*out)[n].important = important;
        n++;
    }
    free(buf);
    return n;
}

void sv_decls_free(sv_decl *d, int n)
{
    for (int i = 0; i < n; i++) {
        free(d[i].name);
        free(d[i].value);
    }
    free(d);
}

static bool ident_char(char c)
{
    return isalnum((unsigned char)c) || c == '-' || c == '_';
}

/* One compound selector at *pp into c (zeroed by the caller); false if it is beyond us. */
static bool parse_compound(const char **pp, sv_css_rule *c)
{
    const char *p = *pp, *begin = p;
    if (*p == '*') {
        p++;
    } else if (isalpha((unsigned char)*p)) {
        const char *s = p;
        while (ident_char(*p))
            p++;
        c->tag = sv_xstrndup(s, (size_t)(p - s));
        c->specificity += 1;
    }
    for (;;) {
        if (*p == '.' || *p == '#') {
            char kind = *p++;
            const char *s = p;
            while (ident_char(*p))
                p++;
            if (p == s || (kind == '#' && c->id))
                return false;
            if (kind == '#') {
                c->id = sv_xstrndup(s, (size_t)(p - s));
                c->specificity += 10000;
            } else {
                c->classes = sv_xrealloc(c->classes, (size_t)(c->nclasses + 1) * sizeof(char *));
                c->classes[c->nclasses++] = sv_xstrndup(s, (size_t)(p - s));
                c->specificity += 100;
            }
        } else if (*p == '[') {
            p++;
            while (isspace((unsigned char)*p))
                p++;
            const char *s = p;
            while (ident_char(*p) || *p == ':')
                p++;
            if (p == s)
                return false;
            sv_css_attr a = {sv_xstrndup(s, (size_t)(p - s)), NULL, 0};
            c->attrs = sv_xrealloc(c->attrs, (size_t)(c->nattrs + 1) * sizeof a);
            c->attrs[c->nattrs++] = a;
            c->specificity += 100;
            while (isspace((unsigned char)*p))
                p++;
            if (*p != ']') {
                if (strchr("~^$*|", *p) && *p && p[1] == '=')
                    c->attrs[c->nattrs - 1].op = *p++;
                else if (*p == '=')
                    c->attrs[c->nattrs - 1].op = '=';
                else
                    return false;
                p++;
                while (isspace((unsigned char)*p))
                    p++;
                char q = *p == '"' || *p == '\'' ? *p++ : 0;
                const char *v = p;
                while (*p && (q ? *p != q : ident_char(*p)))
                    p++;
                c->attrs[c->nattrs - 1].value = sv_xstrndup(v, (size_t)(p - v));
                if (q && *p++ != q)
                    return false;
                while (isspace((unsigned char)*p))
                    p++;
                if (*p != ']')
                    return false;
            }
            p++;
        } else if (!strncmp(p, ":first-child", 12) && !ident_char(p[12])) {
            p += 12;
            c->first_child = true;
            c->specificity += 100;
        } else {
            break;
        }
    }
    *pp = p;
    return p != begin;
}

static void rule_free(sv_css_rule *r)
{
    free(r->tag);
    free(r->id);
    for (int i = 0; i < r->nclasses; i++)
        free(r->classes[i]);
    free(r->classes);
    for (int i = 0; i < r->nattrs; i++) {
        free(r->attrs[i].name);
        free(r->attrs[i].value);
    }
    free(r->attrs);
    if (r->left) {
        rule_free(r->left);
        free(r->left);
    }
}

/*
 * A selector into rule r: compounds joined by combinators, the subject (the
 * rightmost) in r and the others chained through `left`. False if it is
 * beyond what we match (r then holds what was parsed, for rule_free).
 */
static bool parse_selector(const char *sel, sv_css_rule *r)
{
    const char *p = sel;
    memset(r, 0, sizeof *r);
    for (int n = 0;; n++) {
        if (n == 32 || !parse_compound(&p, r))
            return false;
        const char *after = p;
        while (isspace((unsigned char)*p))
            p++;
        if (!*p)
            return true;
        char comb = ' ';
        if (*p == '>' || *p == '+' || *p == '~') {
            comb = *p++;
            while (isspace((unsigned char)*p))
                p++;
        } else if (p == after) {
            return false; /* a pseudo-class or other syntax we do not match */
        }
        /* what was parsed becomes the left side of the next compound */
        sv_css_rule *left = sv_xrealloc(NULL, sizeof *left);
        *left = *r;
        memset(r, 0, sizeof *r);
        r->left = left;
        r->comb = comb;
        r->specificity = left->specificity;
    }
}

void sv_css_parse_sheet(sv_css *css, const char *text, sv_doc *doc)
{
    char *buf = sv_xstrdup(text);
    strip_comments(buf);
    char *p = buf;
    for (;;) {
        while (isspace((unsigned char)*p))
            p++;
        if (!*p)
            break;
        if (p[0] == '<' && strncmp(p, "<!--", 4) == 0) { /* CDO/CDC tokens are allowed */
            p += 4;
            continue;
        }
        if (strncmp(p, "-->", 3) == 0) {
            p += 3;
            continue;
        }
        char *open = strchr(p, '{');
        if (*p == '@') {
            char *semi = strchr(p, ';');
            char word[32];
            snprintf(word, sizeof word, "%.*s", (int)strcspn(p, " \t\n{;"), p);
            sv_doc_warn(doc, "<style>: CSS at-rule %s ignored", word);
            if (semi && (!open || semi < open)) {
                p = semi + 1;
                continue;
            }
        }
        if (!open)
            break;
        /* the block runs to the matching brace */
        char *q = open + 1;
        int depth = 1;
        while (*q && depth > 0) {
            if (*q == '{')
                depth++;
            else if (*q == '}')
                depth--;
            q++;
        }
        char *close = q - 1;
        *open = 0;
        if (*close == '}')
            *close = 0;
        if (*p == '@') {
            p = q;
            continue;
        }
        sv_decl *decls;
        int nd = sv_css_parse_decls(open + 1, &decls);
        int used = 0;
        char *sels = p;
        for (char *tok = strtok(sels, ","); tok; tok = strtok(NULL, ",")) {
            char *sel = trim(tok);
            sv_css_rule r;
            if (!parse_selector(sel, &r)) {
                sv_doc_warn(doc, "<style>: CSS selector '%s' not supported, rule ignored", sel);
                rule_free(&r);
                continue;
            }
            r.order = css->n;
            /* each rule owns a copy of the declarations */
            r.decls = sv_xrealloc(NULL, (size_t)(nd ? nd : 1) * sizeof *r.decls);
            for (int i = 0; i < nd; i++) {
                r.decls[i].name = sv_xstrdup(decls[i].name);
                r.decls[i].value = sv_xstrdup(decls[i].value);
                r.decls[i].important = decls[i].important;
            }
            r.ndecls = nd;
            SV_GROW(css->rules, css->n, css->cap);
            css->rules[css->n++] = r;
            used++;
        }
        sv_decls_free(decls, nd);
        p = q;
    }
    free(buf);
}

void sv_css_free(sv_css *css)
{
    for (int i = 0; i < css->n; i++) {
        rule_free(&css->rules[i]);
        sv_decls_free(css->rules[i].decls, css->rules[i].ndecls);
    }
    free(css->rules);
    memset(css, 0, sizeof *css);
}

static bool has_class(const char *list, const char *cls)
{
    size_t n = strlen(cls);
    const char *p = list;
    while (*p) {
        while (isspace((unsigned char)*p))
            p++;
        const char *s = p;
        while (*p && !isspace((unsigned char)*p))
            p++;
        if ((size_t)(p - s) == n && strncmp(s, cls, n) == 0)
            return true;
    }
    return false;
}

/* Element siblings only: character data and foreign elements do not count. */
static bool is_element(const sv_node *n)
{
    return n->name[0] != '#';
}

static const sv_node *prev_element(const sv_node *n)
{
    if (!n->parent)
        return NULL;
    for (int i = n->index - 1; i >= 0; i--)
        if (is_element(n->parent->kids[i]))
            return n->parent->kids[i];
    return NULL;
}

static bool attr_matches(const sv_css_attr *a, const sv_node *n)
{
    const char *v = sv_attr(n, a->name);
    if (!v)
        return false;
    size_t vl = strlen(v), al = a->value ? strlen(a->value) : 0;
    switch (a->op) {
    case '=':
        return !strcmp(v, a->value);
    case '~':
        return al > 0 && has_class(v, a->value); /* a word of a space-separated list */
    case '^':
        return al > 0 && !strncmp(v, a->value, al);
    case '$':
        return al > 0 && vl >= al && !strcmp(v + vl - al, a->value);
    case '*':
        return al > 0 && strstr(v, a->value) != NULL;
    case '|':
        return !strncmp(v, a->value, al) && (v[al] == 0 || v[al] == '-');
    default:
        return true;
    }
}

static bool compound_matches(const sv_css_rule *r, const sv_node *n)
{
    if (!is_element(n) || (r->tag && strcmp(r->tag, n->name) != 0))
        return false;
    if (r->id) {
        const char *id = sv_attr(n, "id");
        if (!id || strcmp(id, r->id) != 0)
            return false;
    }
    if (r->nclasses) {
        const char *cl = sv_attr(n, "class");
        if (!cl)
            return false;
        for (int i = 0; i < r->nclasses; i++)
            if (!has_class(cl, r->classes[i]))
                return false;
    }
    for (int i = 0; i < r->nattrs; i++)
        if (!attr_matches(&r->attrs[i], n))
            return false;
    return !r->first_child || (n->parent && !prev_element(n));
}

/*
 * The subject's compound, then the chain to the left. The ancestor and
 * earlier-sibling combinators take the nearest element that matches
 * (greedy, no backtracking): exact for chains of one combinator kind, the
 * usual case, and linear in the depth, which a hostile sheet cannot blow up.
 */
bool sv_css_matches(const sv_css_rule *r, const sv_node *n)
{
    if (!compound_matches(r, n))
        return false;
    if (!r->left)
        return true;
    const sv_node *m = NULL;
    switch (r->comb) {
    case '>':
        m = n->parent && compound_matches(r->left, n->parent) ? n->parent : NULL;
        break;
    case '+':
        m = prev_element(n);
        m = m && compound_matches(r->left, m) ? m : NULL;
        break;
    case '~':
        for (const sv_node *k = prev_element(n); k && !m; k = prev_element(k))
            m = compound_matches(r->left, k) ? k : NULL;
        break;
    default:
        for (const sv_node *k = n->parent; k && !m; k = k->parent)
            m = compound_matches(r->left, k) ? k : NULL;
        break;
    }
    return m && sv_css_matches(r->left, m);
}

/* -------------------------------------------------------------- styles */

void sv_style_initial(sv_style *s)
{
    memset(s, 0, sizeof *s);
    s->fill.kind = SV_PAINT_COLOR; /* black */
    s->fill.alpha = 1;
    s->stroke.kind = SV_PAINT_NONE;
    s->stroke.alpha = 1;
    s->fill_opacity = s->stroke_opacity = 1;
    s->fill_rule = s->clip_rule = CS_FILL_NONZERO;
    s->stroke_width = 1;
    s->cap = SV_CAP_BUTT;
    s->join = SV_JOIN_MITER;
    s->miter_limit = 4;
    s->visible = true;
    s->font_size = 12; /* librsvg's default medium size */
    strcpy(s->font_family, "sans-serif");
    s->font_weight = 400;
    s->opacity = 1;
    s->stop_opacity = 1;
    strcpy(s->paint_order, "FSM");
}

/*
 * paint-order (SVG 2): "normal", or fill, stroke and markers, each at most
 * once, the ones left out following in their normal order. False for
 * anything else (the declaration is then invalid and ignored).
 */
static bool parse_paint_order(const char *v, char order[4])
{
    char out[4] = "";
    int n = 0;
    const char *p = v;
    while (*p) {
        while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r')
            p++;
        size_t len = strcspn(p, " \t\n\r");
        if (len == 0)
            break;
        char k = len == 6 && !strncmp(p, "normal", 6) && n == 0 && !p[len] ? 'N'
                 : len == 4 && !strncmp(p, "fill", 4)                      ? 'F'
                 : len == 6 && !strncmp(p, "stroke", 6)                    ? 'S'
                 : len == 7 && !strncmp(p, "markers", 7)                   ? 'M'
                                                                           : 0;
        if (!k || (k != 'N' && strchr(out, k)) || n >= 3)
            return false;
        if (k == 'N') {
            strcpy(order, "FSM");
            return true;
        }
        out[n++] = k;
        out[n] = 0;
        p += len;
    }
    if (n == 0)
        return false;
    for (const char *d = "FSM"; *d; d++)
        if (!strchr(out, *d)) {
            out[n++] = *d;
            out[n] = 0;
        }
    memcpy(order, out, 4);
    return true;
}

void sv_style_inherit(sv_style *c, const sv_style *p)
{
    *c = *p;
    c->opacity = 1;
    c->has_transform = false;
    c->display_none = false;
    c->clip_path[0] = c->mask[0] = c->filter[0] = 0;
    c->stop_color[0] = c->stop_color[1] = c->stop_color[2] = 0;
    c->stop_opacity = 1;
}

/* A number, or a percentage when `percent` is given, and nothing after it but white space. */
static bool parse_number_only(const char *v, bool percent, double *x)
{
    const char *p = v;
    if (!sv_parse_number(&p, x))
        return false;
    if (percent && *p == '%') {
        *x /= 100;
        p++;
    }
    while (isspace((unsigned char)*p))
        p++;
    return *p == 0;
}

/* "0.5", "50%"; anything else ("0.1mm") is invalid and leaves `dflt`. */
static double parse_opacity(const char *v, double dflt)
{
    double x;
    if (!parse_number_only(v, true, &x))
        return dflt;
    return x < 0 ? 0 : (x > 1 ? 1 : x);
}

/* "url(#id)" into id; returns pointer past ')' or NULL. */
static const char *parse_url(const char *v, char *id, size_t idlen)
{
    while (isspace((unsigned char)*v))
        v++;
    if (strncmp(v, "url(", 4) != 0)
        return NULL;
    v += 4;
    while (isspace((unsigned char)*v) || *v == '"' || *v == '\'')
        v++;
    const char *e = strchr(v, ')');
    if (!e)
        return NULL;
    const char *end = e;
    while (end > v && (isspace((unsigned char)end[-1]) || end[-1] == '"' || end[-1] == '\''))
        end--;
    if (*v == '#')
        v++;
    snprintf(id, idlen, "%.*s", (int)(end - v), v);
    return e + 1;
}

static bool parse_paint(const char *v, sv_paint_spec *ps)
{
    while (isspace((unsigned char)*v))
        v++;
    sv_paint_spec p;
    memset(&p, 0, sizeof p);
    p.alpha = 1;
    const char *rest = parse_url(v, p.url, sizeof p.url);
    if (rest) {
        p.kind = SV_PAINT_URL;
        while (isspace((unsigned char)*rest))
            rest++;
        double a;
        if (*rest && strcmp(rest, "none") != 0) {
            sv_color_kind k = sv_parse_color(rest, p.fallback_rgb, &a);
            if (k == SV_COLOR_INVALID)
                return false; /* "url(#g) green icc-color(...)": the whole value is invalid */
            p.fallback_kind = k == SV_COLOR_RGB ? SV_PAINT_COLOR : SV_PAINT_CURRENT;
        }
        *ps = p;
        return true;
    }
    if (strcmp(v, "none") == 0) {
        p.kind = SV_PAINT_NONE;
        *ps = p;
        return true;
    }
    sv_color_kind k = sv_parse_color(v, p.rgb, &p.alpha);
    if (k == SV_COLOR_INVALID)
        return false; /* an invalid value leaves the property as it was */
    p.kind = k == SV_COLOR_CURRENT ? SV_PAINT_CURRENT : SV_PAINT_COLOR;
    *ps = p;
    return true;
}

bool sv_style_set(sv_style *s, const sv_style *parent, const char *name, const char *v,
                  double diag)
{
    bool inherit = strcmp(v, "inherit") == 0;
#define INH(field)                                                                               \
    if (inherit) {                                                                               \
        memcpy(&s->field, &parent->field, sizeof s->field);                                     \
        return true;                                                                             \
    }
    if (!strcmp(name, "fill")) {
        INH(fill);
        return parse_paint(v, &s->fill); /* invalid (context-fill, ...): kept as it was, warned */
    } else if (!strcmp(name, "stroke")) {
        INH(stroke);
        return parse_paint(v, &s->stroke);
    } else if (!strcmp(name, "fill-opacity")) {
        INH(fill_opacity);
        s->fill_opacity = parse_opacity(v, s->fill_opacity);
    } else if (!strcmp(name, "stroke-opacity")) {
        INH(stroke_opacity);
        s->stroke_opacity = parse_opacity(v, s->stroke_opacity);
    } else if (!strcmp(name, "opacity")) {
        INH(opacity);
        s->opacity = parse_opacity(v, 1);
    } else if (!strcmp(name, "stop-opacity")) {
        INH(stop_opacity);
        s->stop_opacity = parse_opacity(v, 1);
    } else if (!strcmp(name, "fill-rule") || !strcmp(name, "clip-rule")) {
        int *rule = name[0] == 'f' ? &s->fill_rule : &s->clip_rule;
        if (inherit)
            *rule = name[0] == 'f' ? parent->fill_rule : parent->clip_rule;
        else if (!strcmp(v, "evenodd"))
            *rule = CS_FILL_EVENODD;
        else if (!strcmp(v, "nonzero"))
            *rule = CS_FILL_NONZERO;
    } else if (!strcmp(name, "stroke-width")) {
        INH(stroke_width);
        double w;
        if (sv_parse_length(v, s->font_size, diag, &w))
            s->stroke_width = w > 0 ? w : 0; /* negative: no stroke, as resvg draws it */
    } else if (!strcmp(name, "stroke-linecap")) {
        INH(cap);
        s->cap = !strcmp(v, "round") ? SV_CAP_ROUND : !strcmp(v, "square") ? SV_CAP_SQUARE
                                                                           : SV_CAP_BUTT;
    } else if (!strcmp(name, "stroke-linejoin")) {
        INH(join);
        if (!strcmp(v, "round"))
            s->join = SV_JOIN_ROUND;
        else if (!strcmp(v, "bevel"))
            s->join = SV_JOIN_BEVEL;
        else if (!strcmp(v, "miter"))
            s->join = SV_JOIN_MITER;
        else
            return false; /* miter-clip, arcs (SVG 2) */
    } else if (!strcmp(name, "stroke-miterlimit")) {
        INH(miter_limit);
        double m; /* a number, not a length: "5mm" is invalid */
        if (parse_number_only(v, false, &m) && m >= 1)
            s->miter_limit = m;
    } else if (!strcmp(name, "stroke-dasharray")) {
        if (inherit) {
            s->has_dash = parent->has_dash;
            s->ndash = parent->ndash;
            memcpy(s->dash, parent->dash, sizeof s->dash);
            return true;
        }
        /* lengths with units, percentages of the viewport's diagonal; "none" is solid */
        double dash[16];
        int n = 0;
        const char *p = v;
        char tok[64];
        while (*(p = sv_skip_wsp_comma(p)) && strcmp(p, "none") != 0) {
            size_t len = strcspn(p, " \t\r\n,");
            snprintf(tok, sizeof tok, "%.*s", (int)len, p);
            if (n == 16 || !sv_parse_length(tok, s->font_size, diag, &dash[n]))
                return false; /* invalid: the property keeps its value */
            n++;
            p += len;
        }
        s->ndash = n;
        memcpy(s->dash, dash, sizeof dash);
        double sum = 0;
        for (int i = 0; i < n; i++)
            sum += dash[i] > 0 ? dash[i] : 0;
        s->has_dash = n > 0 && sum > 0;
    } else if (!strcmp(name, "stroke-dashoffset")) {
        INH(dash_offset);
        sv_parse_length(v, s->font_size, diag, &s->dash_offset);
    } else if (!strcmp(name, "color")) {
        INH(color);
        double a, rgb[3];
        if (sv_parse_color(v, rgb, &a) == SV_COLOR_RGB)
            memcpy(s->color, rgb, sizeof rgb);
    } else if (!strcmp(name, "stop-color")) {
        INH(stop_color);
        double a, rgb[3];
        sv_color_kind k = sv_parse_color(v, rgb, &a);
        if (k == SV_COLOR_RGB) {
            memcpy(s->stop_color, rgb, sizeof rgb);
            s->stop_opacity *= a;
        } else if (k == SV_COLOR_CURRENT) {
            memcpy(s->stop_color, s->color, sizeof rgb);
        }
    } else if (!strcmp(name, "visibility")) {
        INH(visible);
        s->visible = strcmp(v, "hidden") != 0 && strcmp(v, "collapse") != 0;
    } else if (!strcmp(name, "display")) {
        s->display_none = !strcmp(v, "none");
    } else if (!strcmp(name, "clip-path") || !strcmp(name, "mask") || !strcmp(name, "filter")) {
        char *dst = name[0] == 'c' ? s->clip_path : name[0] == 'm' ? s->mask : s->filter;
        dst[0] = 0;
        if (strcmp(v, "none") != 0 && !parse_url(v, dst, 128))
            return false;
    } else if (!strcmp(name, "font-size")) {
        INH(font_size);
        double fs;
        if (sv_parse_length(v, parent->font_size, parent->font_size, &fs) && fs > 0)
            s->font_size = fs;
    } else if (!strcmp(name, "font-family")) {
        INH(font_family);
        snprintf(s->font_family, sizeof s->font_family, "%s", v);
    } else if (!strcmp(name, "font-weight")) {
        INH(font_weight);
        /* a number (1..1000) or a keyword; strtod, since atoi's overflow is undefined */
        double w = strtod(v, NULL);
        if (!strcmp(v, "bold"))
            s->font_weight = 700;
        else if (!strcmp(v, "bolder")) /* CSS Fonts 4's table, in short */
            s->font_weight = parent->font_weight < 600 ? 700 : 900;
        else if (!strcmp(v, "lighter"))
            s->font_weight = parent->font_weight < 600 ? 100 : 400;
        else if (w >= 1 && w <= 1000)
            s->font_weight = (int)w;
        else
            s->font_weight = 400;
    } else if (!strcmp(name, "font-style")) {
        INH(font_italic);
        s->font_italic = !strcmp(v, "italic") || !strcmp(v, "oblique");
    } else if (!strcmp(name, "text-anchor")) {
        INH(text_anchor);
        s->text_anchor = !strcmp(v, "middle") ? 1 : !strcmp(v, "end") ? 2 : 0;
    } else if (!strcmp(name, "marker-start") || !strcmp(name, "marker-mid") ||
               !strcmp(name, "marker-end") || !strcmp(name, "marker")) {
        char which = name[6] ? name[7] : 0; /* 's', 'm', 'e', or the shorthand for all three */
        int first = which == 'm' ? 1 : which == 'e' ? 2 : 0, last = which ? first : 2;
        for (int i = first; i <= last; i++) {
            if (inherit) {
                memcpy(s->marker[i], parent->marker[i], sizeof s->marker[i]);
                continue;
            }
            s->marker[i][0] = 0;
            if (strcmp(v, "none") != 0 && !parse_url(v, s->marker[i], sizeof s->marker[i]))
                return false;
        }
    } else if (!strcmp(name, "mix-blend-mode")) {
        return strcmp(v, "normal") == 0;
    } else if (!strcmp(name, "transform")) {
        /* the property (CSS, style attribute; not the attribute, which the walk reads) */
        sv_affine m;
        if (inherit || !sv_parse_transform(v, &m))
            return inherit;
        s->has_transform = true;
        s->transform = m;
    } else if (!strcmp(name, "paint-order")) {
        INH(paint_order);
        parse_paint_order(v, s->paint_order); /* an invalid value is ignored */
    }
#undef INH
    return true;
}

static void node_desc(const sv_node *n, char *buf, size_t len)
{
    const char *id = sv_attr(n, "id");
    if (id)
        snprintf(buf, len, "<%s id=\"%s\"> (line %d)", n->name, id, n->line);
    else
        snprintf(buf, len, "<%s> (line %d)", n->name, n->line);
}

static void apply(sv_style *s, const sv_style *parent, const sv_node *n, const char *name,
                  const char *value, double diag, sv_doc *doc)
{
    if (!sv_style_set(s, parent, name, value, diag) && doc) {
        char d[160];
        node_desc(n, d, sizeof d);
        sv_doc_warn(doc, "%s: %s: %s not supported, ignored", d, name, value);
    }
}

/* The declarations of one importance, `color` first. */
static void apply_decls(sv_style *s, const sv_style *parent, const sv_node *n, const sv_decl *d,
                        int nd, bool important, double diag, sv_doc *doc)
{
    for (int k = 0; k < nd; k++)
        if (d[k].important == important && !strcmp(d[k].name, "color"))
            apply(s, parent, n, "color", d[k].value, diag, doc);
    for (int k = 0; k < nd; k++)
        if (d[k].important == important && strcmp(d[k].name, "color") != 0)
            apply(s, parent, n, d[k].name, d[k].value, diag, doc);
}

static int cmp_rules(const void *a, const void *b)
{
    const sv_css_rule *x = *(const sv_css_rule *const *)a, *y = *(const sv_css_rule *const *)b;
    if (x->specificity != y->specificity)
        return x->specificity < y->specificity ? -1 : 1;
    return x->order < y->order ? -1 : (x->order > y->order);
}

void sv_style_compute(sv_style *s, const sv_style *parent, const sv_node *n, const sv_css *css,
                      double diag, sv_doc *doc)
{
    sv_style_inherit(s, parent);
    /* `color` first: currentColor anywhere on the element refers to it. */
    const char *color = sv_attr(n, "color");
    if (color)
        apply(s, parent, n, "color", color, diag, doc);
    for (int i = 0; n->attrs[i]; i += 2)
        if (strcmp(n->attrs[i], "style") != 0 && strcmp(n->attrs[i], "color") != 0 &&
            strcmp(n->attrs[i], "class") != 0 && strcmp(n->attrs[i], "id") != 0 &&
            strcmp(n->attrs[i], "transform") != 0)
            apply(s, parent, n, n->attrs[i], n->attrs[i + 1], diag, doc);
    /*
     * The cascade: matching rules by specificity and order, then the style
     * attribute, then the !important declarations of the rules, then those
     * of the style attribute. `color` goes first at each step.
     */
    const sv_css_rule **match = NULL;
    int nm = 0;
    if (css && css->n) {
        match = sv_xrealloc(NULL, (size_t)css->n * sizeof *match);
        for (int i = 0; i < css->n; i++)
            if (sv_css_matches(&css->rules[i], n))
                match[nm++] = &css->rules[i];
        qsort(match, (size_t)nm, sizeof *match, cmp_rules);
    }
    const char *st = sv_attr(n, "style");
    sv_decl *sd = NULL;
    int nsd = st ? sv_css_parse_decls(st, &sd) : 0;
    for (int important = 0; important < 2; important++) {
        for (int i = 0; i < nm; i++)
            apply_decls(s, parent, n, match[i]->decls, match[i]->ndecls, important, diag, doc);
        apply_decls(s, parent, n, sd, nsd, important, diag, doc);
    }
    sv_decls_free(sd, nsd);
    free(match);
}
