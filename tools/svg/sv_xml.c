/*
 * sv_xml.c - an element tree from expat.
 *
 * SVG needs a tree, not a stream: <use>, gradients and clip paths refer to
 * elements by id, often ones defined later in the file. expat is run in
 * namespace mode so that prefixes mean what the document declares: elements
 * in the SVG namespace (or none, for files that forget it) keep their local
 * name, editor metadata (sodipodi:, inkscape:, rdf:) gets an "ns:" prefix
 * and is skipped by the importer as non-drawing; xlink:href becomes the
 * attribute "xlink:href" whatever prefix the file bound to it. Nesting
 * deeper than SV_MAX_DEPTH stops the parse with an error: the tree is walked
 * recursively afterwards, and no drawing needs that depth.
 */
#include <expat.h>
#include <iconv.h>
#include <limits.h>

#include "sv_import.h"
#include "sv_internal.h"

#define NS_SVG "http://www.w3.org/2000/svg"
#define NS_XLINK "http://www.w3.org/1999/xlink"
#define NS_XML "http://www.w3.org/XML/1998/namespace"

typedef struct builder {
    XML_Parser parser;
    sv_node *root, *cur;
    int depth;
    bool too_deep;  /* stopped at SV_MAX_DEPTH: every later step may recurse */
    int text_depth; /* open <text> elements */
} builder;

/* "uri local" (expat's NS form, separator ' ') to the name we keep. */
static char *element_name(const char *qname)
{
    const char *sp = strchr(qname, ' ');
    if (!sp)
        return sv_xstrdup(qname);
    size_t ulen = (size_t)(sp - qname);
    if (ulen == strlen(NS_SVG) && strncmp(qname, NS_SVG, ulen) == 0)
        return sv_xstrdup(sp + 1);
    size_t n = strlen(sp + 1) + 4;
    char *s = sv_xrealloc(NULL, n);
    snprintf(s, n, "ns:%s", sp + 1);
    return s;
}

static char *attr_name(const char *qname)
{
    const char *sp = strchr(qname, ' ');
    if (!sp)
        return sv_xstrdup(qname);
    size_t ulen = (size_t)(sp - qname);
    const char *prefix = "ns:";
    if (ulen == strlen(NS_XLINK) && strncmp(qname, NS_XLINK, ulen) == 0)
        prefix = "xlink:";
    else if (ulen == strlen(NS_XML) && strncmp(qname, NS_XML, ulen) == 0)
        prefix = "xml:";
    size_t n = strlen(sp + 1) + strlen(prefix) + 1;
    char *s = sv_xrealloc(NULL, n);
    snprintf(s, n, "%s%s", prefix, sp + 1);
    return s;
}

static void XMLCALL on_start(void *ud, const XML_Char *name, const XML_Char **atts)
{
    builder *b = ud;
    if (++b->depth > SV_MAX_DEPTH) {
        b->too_deep = true;
        XML_StopParser(b->parser, XML_FALSE);
        return;
    }
    sv_node *n = sv_xrealloc(NULL, sizeof *n);
    memset(n, 0, sizeof *n);
    n->name = element_name(name);
    n->line = (int)XML_GetCurrentLineNumber(b->parser);
    int na = 0;
    while (atts[na])
        na++;
    n->attrs = sv_xrealloc(NULL, (size_t)(na + 1) * sizeof *n->attrs);
    for (int i = 0; i < na; i += 2) {
        n->attrs[i] = attr_name(atts[i]);
        n->attrs[i + 1] = sv_xstrdup(atts[i + 1]);
    }
    n->attrs[na] = NULL;
    n->parent = b->cur;
    b->text_depth += strcmp(n->name, "text") == 0;
    if (b->cur) {
        SV_GROW(b->cur->kids, b->cur->nkids, b->cur->capkids);
        n->index = b->cur->nkids;
        b->cur->kids[b->cur->nkids++] = n;
    } else if (!b->root) {
        b->root = n;
    }
    b->cur = n;
}

static void XMLCALL on_end(void *ud, const XML_Char *name)
{
    (void)name;
    builder *b = ud;
    b->depth--;
    if (b->cur) {
        b->text_depth -= strcmp(b->cur->name, "text") == 0;
        b->cur = b->cur->parent;
    }
}

static void append_text(sv_node *n, const char *s, size_t len)
{
    n->text = sv_xrealloc(n->text, n->textlen + len + 1);
    memcpy(n->text + n->textlen, s, len);
    n->textlen += len;
    n->text[n->textlen] = 0;
}

/*
 * Character data goes to the element's `text` (all of it, for <style>) and,
 * so that <text> can interleave it with <tspan>s in order, to "#text"
 * children as well. Elsewhere it draws nothing and is not kept: the white
 * space between elements would otherwise cost a node each.
 */
static void XMLCALL on_text(void *ud, const XML_Char *s, int len)
{
    builder *b = ud;
    sv_node *n = b->cur;
    if (!n || len <= 0 || (b->text_depth == 0 && strcmp(n->name, "style") != 0))
        return;
    append_text(n, s, (size_t)len);
    sv_node *last = n->nkids ? n->kids[n->nkids - 1] : NULL;
    if (!last || strcmp(last->name, "#text") != 0) {
        last = sv_xrealloc(NULL, sizeof *last);
        memset(last, 0, sizeof *last);
        last->name = sv_xstrdup("#text");
        last->attrs = sv_xrealloc(NULL, sizeof *last->attrs);
        last->attrs[0] = NULL;
        last->parent = n;
        last->line = (int)XML_GetCurrentLineNumber(b->parser);
        SV_GROW(n->kids, n->nkids, n->capkids);
        last->index = n->nkids;
        n->kids[n->nkids++] = last;
    }
    append_text(last, s, (size_t)len);
}

/*
 * Encodings expat does not know itself (it knows UTF-8, UTF-16, ISO-8859-1
 * and US-ASCII): a single-byte one that iconv knows (windows-1251, KOI8-R,
 * ISO-8859-5, ...) becomes expat's byte-to-code-point map. Multi-byte ones
 * stay unknown, and the parse ends with expat's "unknown encoding".
 */
static int XMLCALL on_unknown_encoding(void *ud, const XML_Char *name, XML_Encoding *info)
{
    (void)ud;
    iconv_t cd = iconv_open("UTF-32LE", name);
    if (cd == (iconv_t)-1)
        return XML_STATUS_ERROR;
    int ok = XML_STATUS_OK;
    for (int b = 0; b < 256; b++) {
        char in = (char)b;
        unsigned char out[4];
        char *ip = &in, *op = (char *)out;
        size_t il = 1, ol = sizeof out;
        iconv(cd, NULL, NULL, NULL, NULL);
        if (iconv(cd, &ip, &il, &op, &ol) == (size_t)-1 || ol != 0) {
            if (b < 128) { /* not ASCII-compatible (or multi-byte): not ours to map */
                ok = XML_STATUS_ERROR;
                break;
            }
            info->map[b] = -1; /* a byte the encoding leaves undefined */
            continue;
        }
        info->map[b] = out[0] | out[1] << 8 | out[2] << 16 | out[3] << 24;
    }
    iconv_close(cd);
    info->data = NULL;
    info->convert = NULL;
    info->release = NULL;
    return ok;
}

sv_node *sv_xml_parse(const char *data, size_t len, char *err, size_t errlen)
{
    builder b = {0};
    b.parser = XML_ParserCreateNS(NULL, ' ');
    if (!b.parser) {
        snprintf(err, errlen, "cannot create the XML parser");
        return NULL;
    }
    XML_SetUserData(b.parser, &b);
    XML_SetElementHandler(b.parser, on_start, on_end);
    XML_SetCharacterDataHandler(b.parser, on_text);
    XML_SetUnknownEncodingHandler(b.parser, on_unknown_encoding, NULL);
    if (len > INT_MAX) {
        snprintf(err, errlen, "file of %zu bytes is over the XML parser's %d", len, INT_MAX);
        XML_ParserFree(b.parser);
        return NULL;
    }
    if (XML_Parse(b.parser, data, (int)len, 1) == XML_STATUS_ERROR) {
        if (b.too_deep)
            snprintf(err, errlen, "elements nested deeper than " SV_STR(SV_MAX_DEPTH)
                     " (SV_MAX_DEPTH) at line %lu",
                     (unsigned long)XML_GetCurrentLineNumber(b.parser));
        else
            snprintf(err, errlen, "XML error at line %lu column %lu: %s",
                     (unsigned long)XML_GetCurrentLineNumber(b.parser),
                     (unsigned long)XML_GetCurrentColumnNumber(b.parser),
                     XML_ErrorString(XML_GetErrorCode(b.parser)));
        XML_ParserFree(b.parser);
        sv_xml_free(b.root);
        return NULL;
    }
    XML_ParserFree(b.parser);
    if (!b.root)
        snprintf(err, errlen, "no root element");
    return b.root;
}

void sv_xml_free(sv_node *n)
{
    if (!n)
        return;
    for (int i = 0; i < n->nkids; i++)
        sv_xml_free(n->kids[i]);
    for (int i = 0; n->attrs && n->attrs[i]; i++)
        free(n->attrs[i]);
    free(n->attrs);
    free(n->kids);
    free(n->text);
    free(n->name);
    free(n);
}

const char *sv_attr(const sv_node *n, const char *name)
{
    for (int i = 0; n->attrs[i]; i += 2)
        if (strcmp(n->attrs[i], name) == 0)
            return n->attrs[i + 1];
    return NULL;
}
