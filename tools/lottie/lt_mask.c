/*
 * lt_mask.c - layer masks as CSG over each of the layer's regions.
 *
 * Lottie combines a layer's masks in order, starting from the first: add
 * is a union with what came before, subtract a difference, intersect an
 * intersection; the layer's content shows inside the result. The core's
 * CSG regions (docs/SCENE.md) say exactly that: every region of the layer
 * keeps its own contours as operand 0 and gains one operand per mask, and
 * its program is 0 (masks combined) intersect. Mask paths are in the
 * layer's space, which is the cel's; an animated mask path is a points
 * track like any other. Difference is xor (rlottie's reading); an inverted
 * mask after the first is the region minus it (the same within the final
 * intersection). A static opacity on a single add or intersect mask fades
 * the layer's paints inside it, as rlottie scales the mask's coverage.
 * Feather, expansion, the lighten / darken modes, animated mask opacity and
 * opacity with several masks have no such form: each is warned and the
 * mask drawn as a plain add (or left out, for mode "n") at full opacity.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../svg/sv_internal.h"
#include "lt_internal.h"

typedef struct mask {
    char mode;
    bool inv;
    lt_prop pt;
    int nverts;
    int ncont;
    sv_contour *cont; /* frame 0 */
    lt_signal *sig;   /* per contour */
} mask;

static int mask_geometry(lt_ctx *c, mask *m, const lt_time *tm)
{
    int N = tm->nframes;
    for (int n = 0; n < N; n++) {
        double *vals = malloc((size_t)(1 + 6 * m->nverts) * sizeof *vals);
        if (!vals)
            return lt_fail(c, "out of memory");
        lt_prop_eval(&m->pt, tm->frame[n], vals);
        sv_path p;
        sv_path_init(&p);
        if (m->nverts > 0)
            lt_path_build(vals, m->nverts, &p);
        free(vals);
        sv_contour *cc = NULL;
        int nc = 0;
        lt_fixed_contours(&p, &cc, &nc);
        sv_path_free(&p);
        if (n == 0) {
            m->cont = cc;
            m->ncont = nc;
            m->sig = calloc((size_t)(nc ? nc : 1), sizeof *m->sig);
            if (!m->sig)
                return lt_fail(c, "out of memory");
            for (int i = 0; i < nc; i++) {
                lt_signal_init(&m->sig[i], N, 3 * cc[i].count, 0.01);
                lt_signal_note_prop(&m->sig[i], &m->pt, tm->f0, tm->fscale);
            }
        }
        if (nc != m->ncont) {
            lt_free_contours(cc, n ? nc : 0);
            return lt_fail(c, "a mask path changes its subpaths between frames");
        }
        for (int i = 0; i < nc; i++) {
            if (!lt_charge(c, 3.0 * cc[i].count))
                return -1;
            memcpy(m->sig[i].v + (size_t)n * m->sig[i].width, cc[i].pts,
                   (size_t)m->sig[i].width * sizeof(double));
        }
        if (n > 0)
            lt_free_contours(cc, nc);
    }
    return 0;
}

/* Multiplies a region's beta by f: its constant, its paint track's keys, a beta function's stops. */
static void fade_region(cJSON *reg, double f)
{
    cJSON *paint = cJSON_GetObjectItemCaseSensitive(reg, "paint");
    cJSON *beta = cJSON_GetObjectItemCaseSensitive(paint, "beta"), *x;
    if (cJSON_IsNumber(beta))
        cJSON_SetNumberValue(beta, beta->valuedouble * f);
    else if (!beta)
        cJSON_AddNumberToObject(paint, "beta", f);
    cJSON_ArrayForEach(x, cJSON_GetObjectItemCaseSensitive(beta, "stops"))
    {
        cJSON *v = cJSON_GetArrayItem(x, 1);
        if (cJSON_IsNumber(v))
            cJSON_SetNumberValue(v, v->valuedouble * f);
    }
    cJSON *track = cJSON_GetObjectItemCaseSensitive(
        cJSON_GetObjectItemCaseSensitive(reg, "animate"), "paint");
    cJSON_ArrayForEach(x, cJSON_GetObjectItemCaseSensitive(track, "keys"))
    {
        cJSON *b = cJSON_GetObjectItemCaseSensitive(cJSON_GetArrayItem(x, 1), "beta");
        if (cJSON_IsNumber(b))
            cJSON_SetNumberValue(b, b->valuedouble * f);
    }
}

int lt_masks(lt_ctx *c, const cJSON *masks, const lt_time *tm, cJSON *regions)
{
    int nm = cJSON_GetArraySize(masks);
    mask *M = calloc((size_t)(nm ? nm : 1), sizeof *M);
    if (!M)
        return lt_fail(c, "out of memory");
    int used = 0, rc = 0, tokens = 1, faded = 0;
    double fade = 1;
    const cJSON *mj;
    cJSON_ArrayForEach(mj, masks)
    {
        const cJSON *mode = cJSON_GetObjectItemCaseSensitive(mj, "mode");
        char md = cJSON_IsString(mode) && mode->valuestring[0] ? mode->valuestring[0] : 'a';
        if (md == 'n')
            continue;
        if (md != 'a' && md != 's' && md != 'i' && md != 'f') {
            lt_warn(c, LT_F_MASK, "mask mode \"%c\" is drawn as add", md);
            md = 'a';
        }
        lt_prop o;
        double ov = 100;
        if (lt_prop_parse(c, cJSON_GetObjectItemCaseSensitive(mj, "o"), 1, (const double[]){100},
                          "mask opacity", &o) != 0) {
            rc = -1;
            break;
        }
        lt_prop_eval(&o, tm->frame[0], &ov);
        if (lt_prop_animated(&o))
            lt_warn(c, LT_F_MASK, "animated mask opacity is drawn as 100%%");
        else if (ov < 100)
            fade = ov < 0 ? 0 : ov / 100, faded++;
        lt_prop_free(&o);
        bool inv = cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(mj, "inv"));
        int need = used == 0 ? 3 : 2 + (inv ? 3 : 0);
        if (used >= CS_CFG_MAX_OPERANDS - 1 || tokens + need + 1 > CS_CFG_MAX_CSG) {
            lt_warn(c, LT_F_MASK, "more masks than the core's CSG holds: the first %d are used",
                    used);
            break;
        }
        tokens += need;
        mask *m = &M[used];
        m->mode = md;
        m->inv = inv;
        if (lt_prop_parse_path(c, cJSON_GetObjectItemCaseSensitive(mj, "pt"), "mask path", &m->pt,
                               &m->nverts) != 0 ||
            mask_geometry(c, m, tm) != 0) {
            used++;
            rc = -1;
            break;
        }
        used++;
    }
    /* A mask's opacity scales its coverage (rlottie): for one mask that adds or
     * intersects, that is the layer's paints' beta times it inside the mask. */
    if (faded && !(faded == 1 && used == 1 && !M[0].inv && M[0].mode != 's')) {
        lt_warn(c, LT_F_MASK, "mask opacity below 100%% is drawn as 100%% (beyond one add mask)");
        faded = 0;
    }
    if (rc == 0 && faded) {
        cJSON *reg;
        cJSON_ArrayForEach(reg, regions)
            fade_region(reg, fade);
    }
    if (rc == 0 && used > 0) {
        /* RPN: 0, the masks combined in order, intersect. */
        int rpn[CS_CFG_MAX_CSG], nr = 0;
        rpn[nr++] = 0;
        for (int k = 0; k < used; k++) {
            int op = k + 1;
            if (k == 0) {
                if (M[k].mode == 's' || M[k].inv) {
                    if (M[k].inv && M[k].mode == 's')
                        rpn[nr++] = op; /* everything minus not-m: m */
                    else {
                        rpn[nr++] = 0;
                        rpn[nr++] = op;
                        rpn[nr++] = CS_CSG_DIFFERENCE;
                    }
                } else {
                    rpn[nr++] = op;
                }
                continue;
            }
            /* An inverted mask is the region's own shape minus it: the same, within the
             * final intersection with the region. */
            if (M[k].inv)
                rpn[nr++] = 0;
            rpn[nr++] = op;
            if (M[k].inv)
                rpn[nr++] = CS_CSG_DIFFERENCE;
            rpn[nr++] = M[k].mode == 'a' ? CS_CSG_UNION
                        : M[k].mode == 's' ? CS_CSG_DIFFERENCE
                        : M[k].mode == 'f' ? CS_CSG_XOR : CS_CSG_INTERSECT;
        }
        rpn[nr++] = CS_CSG_INTERSECT;
        static const char *const names[] = {"", "union", "intersect", "difference", "xor"};
        cJSON *reg;
        cJSON_ArrayForEach(reg, regions)
        {
            cJSON *csg = cJSON_CreateArray();
            for (int k = 0; k < nr; k++)
                cJSON_AddItemToArray(csg, rpn[k] >= 0 ? cJSON_CreateNumber(rpn[k])
                                                      : cJSON_CreateString(names[-rpn[k]]));
            cJSON *cts = cJSON_GetObjectItemCaseSensitive(reg, "contours");
            cJSON *ops = cJSON_CreateArray();
            for (int k = cJSON_GetArraySize(cts); k > 0; k--)
                cJSON_AddItemToArray(ops, cJSON_CreateNumber(0));
            for (int k = 0; k < used; k++)
                for (int i = 0; i < M[k].ncont; i++) {
                    cJSON *ct = lt_contour_json(&M[k].cont[i]);
                    cJSON *track = lt_signal_track(&M[k].sig[i], c->fr, lt_points_value);
                    if (track)
                        cJSON_AddItemToObject(cJSON_AddObjectToObject(ct, "animate"), "points",
                                              track);
                    cJSON_AddItemToArray(cts, ct);
                    cJSON_AddItemToArray(ops, cJSON_CreateNumber(k + 1));
                }
            cJSON_AddItemToObject(reg, "csg", csg);
            cJSON_AddItemToObject(reg, "operands", ops);
        }
    }
    for (int k = 0; k < used; k++) {
        lt_prop_free(&M[k].pt);
        for (int i = 0; i < M[k].ncont; i++)
            lt_signal_free(&M[k].sig[i]);
        free(M[k].sig);
        lt_free_contours(M[k].cont, M[k].ncont);
    }
    free(M);
    return rc;
}

/* ------------------------------------------------------------ track mattes */

/* A region's beta when it is one constant at every frame (no beta function;
 * for a luma matte, also white): then its alpha (and luma) is its coverage
 * times that; else -1. */
static double matte_beta(const cJSON *reg, bool luma)
{
    const cJSON *paint = cJSON_GetObjectItemCaseSensitive(reg, "paint");
    const cJSON *beta = cJSON_GetObjectItemCaseSensitive(paint, "beta");
    const cJSON *pig = cJSON_GetObjectItemCaseSensitive(paint, "pigment");
    if (!cJSON_IsNumber(beta) || cJSON_GetObjectItemCaseSensitive(reg, "csg"))
        return -1;
    if (luma) {
        if (cJSON_GetArraySize(pig) != 3)
            return -1;
        for (int k = 0; k < 3; k++)
            if (cJSON_GetArrayItem(pig, k)->valuedouble < 1)
                return -1;
    }
    const cJSON *track = cJSON_GetObjectItemCaseSensitive(
        cJSON_GetObjectItemCaseSensitive(reg, "animate"), "paint");
    const cJSON *key;
    cJSON_ArrayForEach(key, cJSON_GetObjectItemCaseSensitive(track, "keys"))
    {
        const cJSON *v = cJSON_GetArrayItem(key, 1);
        const cJSON *b = cJSON_GetObjectItemCaseSensitive(v, "beta");
        const cJSON *pg = cJSON_GetObjectItemCaseSensitive(v, "pigment");
        if (!cJSON_IsNumber(b) || b->valuedouble != beta->valuedouble)
            return -1;
        for (int k = 0; luma && k < 3; k++)
            if (cJSON_GetArrayItem(pg, k)->valuedouble < 1)
                return -1;
    }
    return beta->valuedouble;
}

static const char *rule_of(const cJSON *reg)
{
    const cJSON *r = cJSON_GetObjectItemCaseSensitive(reg, "fill_rule");
    return cJSON_IsString(r) ? r->valuestring : "nonzero";
}

/*
 * The matte's coverage is the union of its source's regions when each is
 * opaque (and white, for luma): then alpha matting is an intersection with
 * that union, and inverted matting a difference, which the core's CSG
 * evaluates exactly on the scanline. Each source region is one operand
 * (its contours wind together under the matted region's fill rule, so the
 * rules must agree where a region has several contours).
 */
int lt_matte(lt_ctx *c, int tt, const cJSON *src_regions, cJSON *regions)
{
    bool luma = tt >= 3, inv = tt == 2 || tt == 4;
    int ns = cJSON_GetArraySize(src_regions);
    const cJSON *sr;
    double fade = 1;
    cJSON_ArrayForEach(sr, src_regions)
    {
        /* One source region of constant beta b mattes by b inside it (a plain
         * matte, not inverted): the matted paints' beta times b. */
        double b = matte_beta(sr, luma);
        if (ns == 1 && !inv && b >= 0)
            fade = b;
        else if (b != 1) {
            lt_warn(c, LT_F_MATTE, "a %s track matte whose source is not opaque%s at every frame "
                    "is drawn unmatted", luma ? "luma" : "alpha", luma ? " white" : "");
            return 0;
        }
    }
    /* Check every region first, so that a layer is matted whole or not at all. */
    cJSON *reg;
    cJSON_ArrayForEach(reg, regions)
    {
        const cJSON *csg = cJSON_GetObjectItemCaseSensitive(reg, "csg");
        int len = csg ? cJSON_GetArraySize(csg) : 1, ops = 1;
        const cJSON *o;
        cJSON_ArrayForEach(o, cJSON_GetObjectItemCaseSensitive(reg, "operands"))
            ops = o->valueint + 1 > ops ? o->valueint + 1 : ops;
        if (ns > 0 && (len + 2 * ns > CS_CFG_MAX_CSG || ops + ns > CS_CFG_MAX_OPERANDS)) {
            lt_warn(c, LT_F_MATTE, "a track matte of %d regions is more than the core's CSG "
                    "holds: drawn unmatted", ns);
            return 0;
        }
        cJSON_ArrayForEach(sr, src_regions)
        {
            if (strcmp(rule_of(sr), rule_of(reg)) != 0 &&
                cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(sr, "contours")) > 1) {
                lt_warn(c, LT_F_MATTE, "a track matte whose fill rule differs from its layer's "
                        "is drawn unmatted");
                return 0;
            }
        }
    }
    if (ns == 0) {
        /* An empty matte: nothing shows through it, everything through its inverse. */
        if (!inv)
            while (cJSON_GetArraySize(regions) > 0)
                cJSON_DeleteItemFromArray(regions, 0);
        return 1;
    }
    cJSON_ArrayForEach(reg, regions)
    {
        cJSON *cts = cJSON_GetObjectItemCaseSensitive(reg, "contours");
        cJSON *csg = cJSON_GetObjectItemCaseSensitive(reg, "csg");
        cJSON *ops = cJSON_GetObjectItemCaseSensitive(reg, "operands");
        if (!csg) {
            csg = cJSON_AddArrayToObject(reg, "csg");
            cJSON_AddItemToArray(csg, cJSON_CreateNumber(0));
            ops = cJSON_AddArrayToObject(reg, "operands");
            for (int k = cJSON_GetArraySize(cts); k > 0; k--)
                cJSON_AddItemToArray(ops, cJSON_CreateNumber(0));
        }
        int next = 0;
        const cJSON *o;
        cJSON_ArrayForEach(o, ops)
            next = o->valueint + 1 > next ? o->valueint + 1 : next;
        int j = 0;
        cJSON_ArrayForEach(sr, src_regions)
        {
            const cJSON *ct;
            cJSON_ArrayForEach(ct, cJSON_GetObjectItemCaseSensitive(sr, "contours"))
            {
                cJSON_AddItemToArray(cts, cJSON_Duplicate(ct, true));
                cJSON_AddItemToArray(ops, cJSON_CreateNumber(next + j));
            }
            cJSON_AddItemToArray(csg, cJSON_CreateNumber(next + j));
            if (j > 0)
                cJSON_AddItemToArray(csg, cJSON_CreateString("union"));
            j++;
        }
        cJSON_AddItemToArray(csg, cJSON_CreateString(inv ? "difference" : "intersect"));
        if (fade != 1)
            fade_region(reg, fade);
    }
    return 1;
}
