/*
 * sv_emit.c - the IR's two back ends: a cs_scene built through the core's
 * own validating cs_scene_add_* calls, and the scene JSON of DESIGN.md
 * written with cJSON.
 *
 * Both write what the core draws today: solid paints (a gradient's area
 * average, see sv_gradient.c) and no clip paths beyond those already applied
 * exactly to the geometry. The IR keeps gradients and CSG clips; the JSON
 * writer has one place (paint_json) where gradient paints will be written
 * once their syntax is settled.
 */
#include <cjson/cJSON.h>
#include <math.h>

#include "sv_internal.h"

typedef struct emitter {
    cs_scene *scene;
    bool srgb;
    cs_point *pts;
    float *iv;
    size_t cap;
} emitter;

static size_t region_points(const sv_region *r)
{
    size_t n = 0;
    for (int k = 0; k < r->ncontours; k++)
        n += (size_t)r->contours[k].count;
    return n;
}

static cs_status add_region(emitter *em, const sv_region *reg, cs_error *e)
{
    cs_paint p;
    for (int k = 0; k < 3; k++) {
        double v = reg->paint.pigment[k], m = reg->paint.medium[k];
        p.pigment[k] = (float)(em->srgb ? v : sv_srgb_to_linear(v));
        p.medium[k] = (float)(em->srgb ? m : sv_srgb_to_linear(m));
    }
    p.beta = (float)reg->paint.beta;
    cs_status st = cs_scene_add_region(em->scene, (cs_fill_rule)reg->fill_rule, &p, e);
    for (int k = 0; st == CS_OK && k < reg->ncontours; k++) {
        const sv_contour *ct = &reg->contours[k];
        if ((size_t)ct->count > em->cap) {
            em->cap = (size_t)ct->count;
            em->pts = sv_xrealloc(em->pts, em->cap * sizeof *em->pts);
            em->iv = sv_xrealloc(em->iv, em->cap * sizeof *em->iv);
        }
        for (int i = 0; i < ct->count; i++) {
            em->pts[i].x = (float)ct->pts[3 * i];
            em->pts[i].y = (float)ct->pts[3 * i + 1];
            em->pts[i].w = (float)ct->pts[3 * i + 2];
            em->iv[i] = (float)ct->intervals[i];
        }
        st = cs_scene_add_contour(em->scene, ct->degree, ct->count, em->pts, em->iv, e);
    }
    return st;
}

/*
 * Which gradient regions keep their bands: all of them, unless the scene
 * store would overflow; then the regions whose bands cost the most points
 * fall back to their average colour first.
 */
static bool *choose_bands(const sv_doc *doc, bool average)
{
    size_t nreg = sv_doc_region_count(doc), k = 0;
    bool *use = sv_xrealloc(NULL, (nreg ? nreg : 1) * sizeof *use);
    size_t points = 0, regions = 0, contours = 0;
    for (int c = 0; c < doc->ncels; c++)
        for (int r = 0; r < doc->cels[c].nregions; r++, k++) {
            const sv_region *reg = &doc->cels[c].regions[r];
            use[k] = reg->nbands > 0 && !average;
            points += region_points(reg);
            regions++;
            contours += (size_t)reg->ncontours;
            for (int b = 0; use[k] && b < reg->nbands; b++) {
                points += region_points(&reg->bands[b]);
                regions++;
                contours += (size_t)reg->bands[b].ncontours;
            }
        }
    while (points > CS_CFG_MAX_POINTS || regions > CS_CFG_MAX_REGIONS ||
           contours > CS_CFG_MAX_CONTOURS) {
        size_t best = 0, bi = 0, i = 0;
        const sv_region *br = NULL;
        for (int c = 0; c < doc->ncels; c++)
            for (int r = 0; r < doc->cels[c].nregions; r++, i++) {
                const sv_region *reg = &doc->cels[c].regions[r];
                size_t cost = 0;
                for (int b = 0; use[i] && b < reg->nbands; b++)
                    cost += region_points(&reg->bands[b]);
                if (cost > best) {
                    best = cost;
                    bi = i;
                    br = reg;
                }
            }
        if (!br)
            break; /* no bands left to drop: the scene is simply too big */
        use[bi] = false;
        points -= best;
        regions -= (size_t)br->nbands;
        for (int b = 0; b < br->nbands; b++)
            contours -= (size_t)br->bands[b].ncontours;
    }
    return use;
}

int sv_doc_to_scene(const sv_doc *doc, const sv_scene_opts *opts, cs_scene *scene, char *err,
                    size_t errlen)
{
    sv_scene_opts o = {0};
    if (opts)
        o = *opts;
    cs_status st = cs_scene_init(scene, (float)doc->width, (float)doc->height);
    if (st != CS_OK) {
        snprintf(err, errlen, "canvas %gx%g: %s", doc->width, doc->height, cs_status_str(st));
        return -1;
    }
    if (o.has_background) {
        float bg[3];
        for (int k = 0; k < 3; k++)
            bg[k] = (float)(o.srgb_blend ? o.background[k] : sv_srgb_to_linear(o.background[k]));
        cs_scene_set_background(scene, bg);
    }
    cs_affine id = {1, 0, 0, 1, 0, 0};
    cs_error e;
    emitter em = {scene, o.srgb_blend, NULL, NULL, 0};
    bool *bands = choose_bands(doc, o.gradient_average);
    size_t k = 0;
    int rc = 0;
    for (int c = 0; c < doc->ncels && rc == 0; c++) {
        st = cs_scene_add_cel(scene, &id, NULL, NULL, &e);
        if (st != CS_OK) {
            snprintf(err, errlen, "cel %d of %d: %s", c, doc->ncels, cs_status_str(st));
            rc = -1;
            break;
        }
        const sv_cel *cel = &doc->cels[c];
        for (int r = 0; r < cel->nregions && rc == 0; r++, k++) {
            const sv_region *reg = &cel->regions[r];
            if (bands[k]) {
                for (int b = 0; b < reg->nbands && st == CS_OK; b++)
                    st = add_region(&em, &reg->bands[b], &e);
            } else {
                st = add_region(&em, reg, &e);
            }
            if (st != CS_OK) {
                snprintf(err, errlen, "%s (cel %d region %d, item %d): %s", reg->source, c, r,
                         (int)e.item, cs_status_str(st));
                rc = -1;
            }
        }
    }
    free(bands);
    free(em.pts);
    free(em.iv);
    return rc;
}

/* ---------------------------------------------------------------- JSON */

/* Numbers as %.9g: canvas precision far beyond a pixel, compact text. */
static cJSON *num(double v)
{
    char b[32];
    if (v == 0)
        v = 0; /* no "-0" */
    snprintf(b, sizeof b, "%.9g", v);
    return cJSON_CreateRaw(b);
}

static cJSON *rgb_json(const double *c)
{
    cJSON *a = cJSON_CreateArray();
    for (int k = 0; k < 3; k++) {
        char b[32];
        snprintf(b, sizeof b, "%.6g", c[k]);
        cJSON_AddItemToArray(a, cJSON_CreateRaw(b));
    }
    return a;
}

static cJSON *paint_json(const sv_doc *doc, const sv_paint *p)
{
    (void)doc;
    cJSON *o = cJSON_CreateObject();
    cJSON_AddItemToObject(o, "pigment", rgb_json(p->pigment));
    cJSON_AddItemToObject(o, "medium", rgb_json(p->medium));
    cJSON_AddItemToObject(o, "beta", num(p->beta));
    /*
     * Gradient hook: when p->gradient >= 0, doc->gradients[p->gradient] holds
     * the resolved gradient (stops, geometry, transform to canvas units). It
     * is written here as soon as the scene JSON has a gradient syntax; the
     * pigment/beta above are its area average and stay as the fallback.
     */
    return o;
}

char *sv_doc_to_json(const sv_doc *doc, const double *background)
{
    cJSON *root = cJSON_CreateObject();
    cJSON *canvas = cJSON_AddObjectToObject(root, "canvas");
    cJSON_AddItemToObject(canvas, "width", num(doc->width));
    cJSON_AddItemToObject(canvas, "height", num(doc->height));
    if (background)
        cJSON_AddItemToObject(canvas, "background", rgb_json(background));
    /*
     * Blend hook: imported artwork was designed for sRGB blending. Once the
     * scene JSON can ask for it (`--blend srgb` from the beta work), write
     * that request here so celsim shows what the designer's tool showed.
     */
    cJSON *cels = cJSON_AddArrayToObject(root, "cels");
    bool *use_bands = choose_bands(doc, false); /* what fits the default scene store */
    size_t idx = 0;
    for (int c = 0; c < doc->ncels; c++) {
        const sv_cel *cel = &doc->cels[c];
        cJSON *jc = cJSON_CreateObject();
        cJSON_AddStringToObject(jc, "name", cel->name);
        cJSON *regions = cJSON_AddArrayToObject(jc, "regions");
        for (int r = 0; r < cel->nregions; r++, idx++) {
            const sv_region *whole = &cel->regions[r];
            int nb = use_bands[idx] ? whole->nbands : 0;
            for (int b = 0; b < (nb ? nb : 1); b++) {
            const sv_region *reg = nb ? &whole->bands[b] : whole;
            cJSON *jr = cJSON_CreateObject();
            cJSON_AddStringToObject(jr, "fill_rule",
                                    reg->fill_rule == CS_FILL_EVENODD ? "evenodd" : "nonzero");
            cJSON_AddItemToObject(jr, "paint", paint_json(doc, &reg->paint));
            cJSON *contours = cJSON_AddArrayToObject(jr, "contours");
            for (int k = 0; k < reg->ncontours; k++) {
                const sv_contour *ct = &reg->contours[k];
                cJSON *jk = cJSON_CreateObject();
                cJSON_AddNumberToObject(jk, "degree", ct->degree);
                cJSON *points = cJSON_AddArrayToObject(jk, "points");
                cJSON *iv = cJSON_AddArrayToObject(jk, "intervals");
                for (int i = 0; i < ct->count; i++) {
                    cJSON *pt = cJSON_CreateArray();
                    cJSON_AddItemToArray(pt, num(ct->pts[3 * i]));
                    cJSON_AddItemToArray(pt, num(ct->pts[3 * i + 1]));
                    if (ct->pts[3 * i + 2] != 1)
                        cJSON_AddItemToArray(pt, num(ct->pts[3 * i + 2]));
                    cJSON_AddItemToArray(points, pt);
                    cJSON_AddItemToArray(iv, num(ct->intervals[i]));
                }
                cJSON_AddItemToArray(contours, jk);
            }
            cJSON_AddItemToArray(regions, jr);
            }
        }
        cJSON_AddItemToArray(cels, jc);
    }
    free(use_bands);
    char *s = cJSON_PrintUnformatted(root);
    cJSON_Delete(root);
    return s;
}
