/*
 * sv_ir.c - the intermediate representation's life cycle: initialisation,
 * warnings, counts, freeing. The IR is plain C structs owned by sv_doc, so
 * back ends (scene JSON, cs_scene, later the cel stream) read it directly.
 */
#include <stdarg.h>

#include "sv_internal.h"

void sv_doc_init(sv_doc *doc)
{
    memset(doc, 0, sizeof *doc);
}

void sv_region_free(sv_region *r)
{
    for (int i = 0; i < r->nbands; i++)
        sv_region_free(&r->bands[i]);
    free(r->bands);
    for (int i = 0; i < r->ncontours; i++)
        sv_contour_free(&r->contours[i]);
    free(r->contours);
    free(r->source);
}

void sv_doc_free(sv_doc *doc)
{
    for (int c = 0; c < doc->ncels; c++) {
        for (int r = 0; r < doc->cels[c].nregions; r++)
            sv_region_free(&doc->cels[c].regions[r]);
        free(doc->cels[c].regions);
        free(doc->cels[c].name);
    }
    free(doc->cels);
    for (int g = 0; g < doc->ngradients; g++)
        free(doc->gradients[g].stops);
    free(doc->gradients);
    for (int k = 0; k < doc->nclips; k++) {
        for (int p = 0; p < doc->clips[k].nparts; p++) {
            for (int i = 0; i < doc->clips[k].parts[p].ncontours; i++)
                sv_contour_free(&doc->clips[k].parts[p].contours[i]);
            free(doc->clips[k].parts[p].contours);
        }
        free(doc->clips[k].parts);
    }
    free(doc->clips);
    for (int w = 0; w < doc->nwarnings; w++)
        free(doc->warnings[w]);
    free(doc->warnings);
    sv_doc_init(doc);
}

void sv_doc_warn(sv_doc *doc, const char *fmt, ...)
{
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    /* The same message from a repeated <use> or a loop says nothing new. */
    for (int i = 0; i < doc->nwarnings; i++)
        if (strcmp(doc->warnings[i], buf) == 0)
            return;
    /* A hostile file can make a warning per element; the search above stays bounded. */
    if (doc->nwarnings > SV_MAX_WARNINGS)
        return;
    if (doc->nwarnings == SV_MAX_WARNINGS)
        snprintf(buf, sizeof buf, "more than %d warnings; the rest are not listed",
                 SV_MAX_WARNINGS);
    doc->warnings = sv_xrealloc(doc->warnings, (size_t)(doc->nwarnings + 1) * sizeof(char *));
    doc->warnings[doc->nwarnings++] = sv_xstrdup(buf);
}

size_t sv_doc_point_count(const sv_doc *doc)
{
    size_t n = 0;
    for (int c = 0; c < doc->ncels; c++)
        for (int r = 0; r < doc->cels[c].nregions; r++)
            for (int k = 0; k < doc->cels[c].regions[r].ncontours; k++)
                n += (size_t)doc->cels[c].regions[r].contours[k].count;
    return n;
}

size_t sv_doc_region_count(const sv_doc *doc)
{
    size_t n = 0;
    for (int c = 0; c < doc->ncels; c++)
        n += (size_t)doc->cels[c].nregions;
    return n;
}
