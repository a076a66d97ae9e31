/*
 * lt_shape.c - a shape layer's contents as regions, and solid layers.
 *
 * Lottie lists a group's items top to bottom: shapes (sh, el, rc, sr),
 * styles (fl, st, gf, gs), modifiers and nested groups, with the group's
 * transform (tr). A style paints every shape listed before it in its group,
 * nested groups included, and the items before it are drawn above it
 * (lottie-web's and rlottie's reading). So a walk in list order makes the
 * regions front to back: each style becomes one region, holding the paths
 * collected so far.
 *
 * Each region is then sampled at every frame (its contours by lt_geom.c);
 * contours whose layout holds from frame to frame, or is made to hold
 * (lt_layout.c), become points tracks, which lt_track.c turns back into
 * few keys. Paint colour and opacity, times the opacities of the groups
 * above, are a paint track; gradients are paint functions.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../svg/sv_internal.h"
#include "lt_shape.h"

typedef struct sh_tree {
    int nnodes, nnodes_cap;
    sh_node **nodes;
    int npaths_all, npaths_cap;
    sh_path **paths;
    int ntrims, ntrims_cap;
    sh_trim **trims;
    int nstyles, nstyles_cap;
    sh_style **styles;
    int nreps, nreps_cap;
    sh_rep **reps;
} sh_tree;

static const double d_zero[4] = {0, 0, 0, 0};
static const double d_hundred[4] = {100, 100, 100, 100};

static const char *ty_of(const cJSON *item)
{
    const cJSON *ty = cJSON_GetObjectItemCaseSensitive(item, "ty");
    return cJSON_IsString(ty) ? ty->valuestring : "";
}

static const cJSON *get(const cJSON *o, const char *k)
{
    return cJSON_GetObjectItemCaseSensitive(o, k);
}

static bool hidden(const cJSON *item)
{
    const cJSON *hd = get(item, "hd");
    return cJSON_IsTrue(hd);
}

static int parse_xf(lt_ctx *c, const cJSON *tr, sh_node *n)
{
    n->has_xf = tr != NULL;
    double one[1] = {100};
    if (lt_prop_parse(c, get(tr, "a"), 2, d_zero, "transform anchor", &n->a) != 0 ||
        lt_prop_parse(c, get(tr, "p"), 2, d_zero, "transform position", &n->p) != 0 ||
        lt_prop_parse(c, get(tr, "s"), 2, d_hundred, "transform scale", &n->s) != 0 ||
        lt_prop_parse(c, get(tr, "r"), 1, d_zero, "transform rotation", &n->r) != 0 ||
        lt_prop_parse(c, get(tr, "o"), 1, one, "transform opacity", &n->o) != 0 ||
        lt_prop_parse(c, get(tr, "sk"), 1, d_zero, "transform skew", &n->sk) != 0 ||
        lt_prop_parse(c, get(tr, "sa"), 1, d_zero, "transform skew axis", &n->sa) != 0)
        return -1;
    return 0;
}

/* ------------------------------------------------------------- parsing */

#define PUSH(c, arr, n, cap, item)                                                                 \
    do {                                                                                           \
        if ((n) >= (cap)) {                                                                        \
            (cap) = (cap) ? 2 * (cap) : 16;                                                        \
            (arr) = sv_xrealloc((arr), (size_t)(cap) * sizeof *(arr));                             \
        }                                                                                          \
        (arr)[(n)++] = (item);                                                                     \
    } while (0)

typedef struct path_list {
    int n, cap;
    sh_path **v;
} path_list;

static int parse_shape(lt_ctx *c, const cJSON *it, const char *ty, sh_node *node, sh_tree *t,
                       path_list *acc)
{
    sh_path *p = calloc(1, sizeof *p);
    if (!p)
        return lt_fail(c, "out of memory");
    PUSH(c, t->paths, t->npaths_all, t->npaths_cap, p);
    p->node = node;
    const cJSON *d = get(it, "d");
    p->reversed = cJSON_IsNumber(d) && d->valuedouble == 3;
    int rc = 0;
    if (!strcmp(ty, "sh")) {
        p->type = SH_PATH;
        rc = lt_prop_parse_path(c, get(it, "ks"), "path", &p->k, &p->nverts);
    } else if (!strcmp(ty, "el")) {
        p->type = SH_ELLIPSE;
        rc = lt_prop_parse(c, get(it, "p"), 2, d_zero, "ellipse position", &p->p) ||
             lt_prop_parse(c, get(it, "s"), 2, d_zero, "ellipse size", &p->s);
    } else if (!strcmp(ty, "rc")) {
        p->type = SH_RECT;
        rc = lt_prop_parse(c, get(it, "p"), 2, d_zero, "rect position", &p->p) ||
             lt_prop_parse(c, get(it, "s"), 2, d_zero, "rect size", &p->s) ||
             lt_prop_parse(c, get(it, "r"), 1, d_zero, "rect roundness", &p->r);
    } else {
        p->type = SH_STAR;
        const cJSON *sy = get(it, "sy");
        p->star = cJSON_IsNumber(sy) && sy->valuedouble == 2 ? 2 : 1;
        rc = lt_prop_parse(c, get(it, "p"), 2, d_zero, "polystar position", &p->p) ||
             lt_prop_parse(c, get(it, "r"), 1, d_zero, "polystar rotation", &p->r) ||
             lt_prop_parse(c, get(it, "pt"), 1, (const double[]){5}, "polystar points", &p->pt) ||
             lt_prop_parse(c, get(it, "ir"), 1, d_zero, "polystar inner radius", &p->ir) ||
             lt_prop_parse(c, get(it, "or"), 1, d_zero, "polystar outer radius", &p->or_);
        /* A refused property holds nothing (lt_prop_parse frees it). */
        if (rc == 0)
            rc = lt_prop_parse(c, get(it, "is"), 1, d_zero, "polystar inner roundness", &p->is) ||
                 lt_prop_parse(c, get(it, "os"), 1, d_zero, "polystar outer roundness", &p->os);
        /* rlottie grows a partial point as the count passes between whole ones, and rounds
         * the sides into cubics; a stroke's outline then changes its layout every frame
         * (polystar_anim.json's took 18.7 M key values), so a polystar whose count is
         * animated is drawn in whole points with sharp corners. */
        p->whole = lt_prop_animated(&p->pt);
        if (rc == 0 && p->whole)
            lt_warn(c, LT_F_STAR_POINTS, "a polystar whose point count is animated is drawn in "
                    "whole points with sharp corners (rlottie grows a partial point and rounds)");
    }
    if (rc)
        return -1;
    PUSH(c, acc->v, acc->n, acc->cap, p);
    return 0;
}

static int parse_gradient(lt_ctx *c, const cJSON *it, sh_style *s)
{
    const cJSON *t = get(it, "t");
    s->gtype = cJSON_IsNumber(t) && t->valuedouble == 2 ? 2 : 1;
    const cJSON *g = get(it, "g");
    const cJSON *pn = get(g, "p");
    if (!cJSON_IsNumber(pn) || pn->valuedouble < 1 || pn->valuedouble > 64)
        return lt_fail(c, "gradient: stop count \"p\" missing or beyond 64");
    s->gstops = (int)pn->valuedouble;
    /* The stop array's length: colour stops (4 each) then alpha stops (2 each). */
    const cJSON *k = get(g, "k"), *kk = get(k, "k");
    int len = 0;
    if (cJSON_IsArray(kk)) {
        const cJSON *first = cJSON_GetArrayItem(kk, 0);
        if (cJSON_IsObject(first)) {
            const cJSON *sv = get(first, "s");
            len = cJSON_GetArraySize(sv);
        } else {
            len = cJSON_GetArraySize(kk);
        }
    }
    if (len < 4 * s->gstops || len > 4 * s->gstops + 2 * 64)
        return lt_fail(c, "gradient: %d numbers for %d stops", len, s->gstops);
    s->gcount = len;
    return lt_prop_parse(c, k, len, NULL, "gradient stops", &s->g) ||
           lt_prop_parse(c, get(it, "s"), 2, d_zero, "gradient start", &s->gs) ||
           lt_prop_parse(c, get(it, "e"), 2, d_zero, "gradient end", &s->ge) ||
           lt_prop_parse(c, get(it, "h"), 1, d_zero, "gradient highlight", &s->gh) ||
           lt_prop_parse(c, get(it, "a"), 1, d_zero, "gradient highlight angle", &s->ga);
}

static int parse_style(lt_ctx *c, const cJSON *it, const char *ty, sh_node *node, sh_tree *t,
                       const path_list *acc)
{
    sh_style *s = calloc(1, sizeof *s);
    if (!s)
        return lt_fail(c, "out of memory");
    PUSH(c, t->styles, t->nstyles, t->nstyles_cap, s);
    s->node = node;
    s->type = !strcmp(ty, "fl") ? ST_FILL : !strcmp(ty, "st") ? ST_STROKE
            : !strcmp(ty, "gf") ? ST_GFILL : ST_GSTROKE;
    const cJSON *r = get(it, "r");
    s->rule = cJSON_IsNumber(r) && r->valuedouble == 2 ? CS_FILL_EVENODD : CS_FILL_NONZERO;
    const double white[4] = {1, 1, 1, 1}, one[1] = {100};
    if (lt_prop_parse(c, get(it, "o"), 1, one, "opacity", &s->o) != 0)
        return -1;
    if (s->type == ST_FILL || s->type == ST_STROKE) {
        if (lt_prop_parse(c, get(it, "c"), 3, white, "colour", &s->c) != 0)
            return -1;
    } else if (parse_gradient(c, it, s) != 0) {
        return -1;
    }
    if (s->type == ST_STROKE || s->type == ST_GSTROKE) {
        if (lt_prop_parse(c, get(it, "w"), 1, (const double[]){1}, "stroke width", &s->w) != 0)
            return -1;
        double lc = 2, lj = 2, ml = 4;
        if (lt_num(c, it, "lc", 1, 3, 2, &lc) || lt_num(c, it, "lj", 1, 3, 2, &lj) ||
            lt_num(c, it, "ml", 0, 1e4, 4, &ml))
            return -1;
        s->cap = lc == 1 ? SV_CAP_BUTT : lc == 2 ? SV_CAP_ROUND : SV_CAP_SQUARE;
        s->join = lj == 1 ? SV_JOIN_MITER : lj == 2 ? SV_JOIN_ROUND : SV_JOIN_BEVEL;
        s->miter = ml;
        const cJSON *d = get(it, "d"), *e;
        cJSON_ArrayForEach(e, d)
        {
            const cJSON *n = get(e, "n");
            const char *nm = cJSON_IsString(n) ? n->valuestring : "";
            if (!strcmp(nm, "o")) {
                lt_prop_free(&s->dash_offset);
                if (lt_prop_parse(c, get(e, "v"), 1, d_zero, "dash offset", &s->dash_offset))
                    return -1;
            } else if (s->ndash < 16) {
                if (lt_prop_parse(c, get(e, "v"), 1, d_zero, "dash", &s->dash[s->ndash]))
                    return -1; /* a refused property holds nothing (lt_prop_parse frees it) */
                s->ndash++;
            }
        }
        s->has_dash = s->ndash > 0;
        if (!s->has_dash && lt_prop_parse(c, NULL, 1, d_zero, "dash offset", &s->dash_offset))
            return -1;
    }
    s->npaths = acc->n;
    s->paths = malloc((size_t)(acc->n ? acc->n : 1) * sizeof *s->paths);
    if (!s->paths)
        return lt_fail(c, "out of memory");
    if (acc->n)
        memcpy(s->paths, acc->v, (size_t)acc->n * sizeof *s->paths);
    return 0;
}

static int parse_items(lt_ctx *c, const cJSON *first, int count, sh_node *node, sh_tree *t,
                       path_list *acc);

/*
 * A repeater: the `count` items before it in its group, once per copy,
 * each copy under a node that carries the copy's transform and opacity.
 * rlottie draws copy 0 at the back, so the last copy is walked first (the
 * walk goes front to back). Copies are as many as the largest value the
 * copy count takes; those beyond the count at a frame have opacity 0.
 */
static int parse_repeater(lt_ctx *c, const cJSON *rp, const cJSON *first, int count,
                          sh_node *node, sh_tree *t, path_list *acc)
{
    sh_rep *r = calloc(1, sizeof *r);
    if (!r)
        return lt_fail(c, "out of memory");
    PUSH(c, t->reps, t->nreps, t->nreps_cap, r);
    const cJSON *tr = get(rp, "tr"), *m = get(rp, "m");
    if (cJSON_IsNumber(m) && m->valuedouble == 2)
        lt_warn(c, LT_F_REPEATER, "repeater copies composited below are drawn above (as rlottie does)");
    const double one[1] = {1}, hundred[1] = {100};
    if (lt_prop_parse(c, get(rp, "c"), 1, one, "repeater copies", &r->c) ||
        lt_prop_parse(c, get(rp, "o"), 1, d_zero, "repeater offset", &r->o) ||
        lt_prop_parse(c, get(tr, "a"), 2, d_zero, "repeater anchor", &r->a) ||
        lt_prop_parse(c, get(tr, "p"), 2, d_zero, "repeater position", &r->p) ||
        lt_prop_parse(c, get(tr, "s"), 2, d_hundred, "repeater scale", &r->s) ||
        lt_prop_parse(c, get(tr, "r"), 1, d_zero, "repeater rotation", &r->r) ||
        lt_prop_parse(c, get(tr, "so"), 1, hundred, "repeater start opacity", &r->so) ||
        lt_prop_parse(c, get(tr, "eo"), 1, hundred, "repeater end opacity", &r->eo))
        return -1;
    double most = r->c.nkeys ? 0 : r->c.value[0];
    for (int k = 0; k < r->c.nkeys; k++) {
        most = fmax(most, r->c.keys[k].s[0]);
        if (r->c.keys[k].e)
            most = fmax(most, r->c.keys[k].e[0]);
    }
    if (!(most <= LT_MAX_COPIES)) /* NaN too */
        return lt_fail(c, "repeater: %.0f copies, more than %d", most, LT_MAX_COPIES);
    if (most < 0)
        most = 0; /* no copies; and no cast of a huge negative count */
    for (int k = (int)most - 1; k >= 0; k--) {
        if (t->nnodes + t->npaths_all + t->nstyles > LT_MAX_ITEMS)
            return lt_fail(c, "repeaters make more than %d shape items", LT_MAX_ITEMS);
        sh_node *n = calloc(1, sizeof *n);
        if (!n)
            return lt_fail(c, "out of memory");
        PUSH(c, t->nodes, t->nnodes, t->nnodes_cap, n);
        n->parent = node;
        n->rep = r;
        n->copy = k;
        path_list mine = {0, 0, NULL};
        int rc = parse_items(c, first, count, n, t, &mine);
        for (int i = 0; i < mine.n && rc == 0; i++)
            PUSH(c, acc->v, acc->n, acc->cap, mine.v[i]);
        free(mine.v);
        if (rc)
            return -1;
    }
    return 0;
}

/* One group's items in list order; `acc` collects its paths for the caller. */
static int parse_group(lt_ctx *c, const cJSON *items, sh_node *node, sh_tree *t, path_list *acc)
{
    if (!cJSON_IsArray(items))
        return lt_fail(c, "a group's items (\"it\" or \"shapes\") are not an array");
    return parse_items(c, items->child, cJSON_GetArraySize(items), node, t, acc);
}

/* `count` items from `first` on, in list order. A repeater takes the items
 * before it (the last repeater first; it meets the earlier ones in them). */
static int parse_items(lt_ctx *c, const cJSON *first, int count, sh_node *node, sh_tree *t,
                       path_list *acc)
{
    if (++c->depth > LT_MAX_DEPTH)
        return lt_fail(c, "shape groups or repeaters nested deeper than %d", LT_MAX_DEPTH);
    const cJSON *it = first, *rp = NULL;
    int at = -1, pos = 0;
    for (; it && pos < count; it = it->next, pos++)
        if (cJSON_IsObject(it) && !hidden(it) && !strcmp(ty_of(it), "rp"))
            rp = it, at = pos;
    if (rp) {
        if (parse_repeater(c, rp, first, at, node, t, acc) != 0)
            return -1;
        first = rp->next;
        count -= at + 1;
    }
    for (it = first, pos = 0; it && pos < count; it = it->next, pos++) {
        if (!cJSON_IsObject(it))
            return lt_fail(c, "a shape item is not an object");
        const char *ty = ty_of(it);
        if (hidden(it) || !strcmp(ty, "tr"))
            continue;
        if (!strcmp(ty, "gr")) {
            sh_node *n = calloc(1, sizeof *n);
            if (!n)
                return lt_fail(c, "out of memory");
            PUSH(c, t->nodes, t->nnodes, t->nnodes_cap, n);
            n->parent = node;
            const cJSON *sub = get(it, "it"), *x, *tr = NULL;
            cJSON_ArrayForEach(x, sub)
            {
                if (!strcmp(ty_of(x), "tr"))
                    tr = x;
            }
            if (parse_xf(c, tr, n) != 0)
                return -1;
            path_list mine = {0, 0, NULL};
            int rc = parse_group(c, sub, n, t, &mine);
            for (int i = 0; i < mine.n && rc == 0; i++)
                PUSH(c, acc->v, acc->n, acc->cap, mine.v[i]);
            free(mine.v);
            if (rc)
                return -1;
        } else if (!strcmp(ty, "sh") || !strcmp(ty, "el") || !strcmp(ty, "rc") ||
                   !strcmp(ty, "sr")) {
            if (parse_shape(c, it, ty, node, t, acc) != 0)
                return -1;
        } else if (!strcmp(ty, "fl") || !strcmp(ty, "st") || !strcmp(ty, "gf") ||
                   !strcmp(ty, "gs")) {
            if (parse_style(c, it, ty, node, t, acc) != 0)
                return -1;
        } else if (!strcmp(ty, "tm")) {
            sh_trim *tm = calloc(1, sizeof *tm);
            if (!tm)
                return lt_fail(c, "out of memory");
            PUSH(c, t->trims, t->ntrims, t->ntrims_cap, tm);
            if (lt_prop_parse(c, get(it, "s"), 1, d_zero, "trim start", &tm->s) ||
                lt_prop_parse(c, get(it, "e"), 1, d_hundred, "trim end", &tm->e) ||
                lt_prop_parse(c, get(it, "o"), 1, d_zero, "trim offset", &tm->o))
                return -1;
            for (int i = 0; i < acc->n; i++)
                if (acc->v[i]->ntrims < 8)
                    acc->v[i]->trims[acc->v[i]->ntrims++] = tm;
        } else if (!strcmp(ty, "mm")) {
            lt_warn(c, LT_F_MERGE, "merge paths are not supported: the paths are drawn unmerged");
        } else if (!strcmp(ty, "rd")) {
            lt_warn(c, LT_F_ROUND, "round corners are not supported: corners stay sharp");
        } else {
            lt_warn(c, LT_F_OTHER, "shape item \"%.8s\" is not supported and not drawn", ty);
        }
    }
    c->depth--;
    return 0;
}

static void tree_free(sh_tree *t)
{
    for (int i = 0; i < t->nnodes; i++) {
        sh_node *n = t->nodes[i];
        lt_prop_free(&n->a), lt_prop_free(&n->p), lt_prop_free(&n->s), lt_prop_free(&n->r);
        lt_prop_free(&n->o), lt_prop_free(&n->sk), lt_prop_free(&n->sa);
        free(n);
    }
    for (int i = 0; i < t->npaths_all; i++) {
        sh_path *p = t->paths[i];
        lt_prop_free(&p->k), lt_prop_free(&p->p), lt_prop_free(&p->s), lt_prop_free(&p->r);
        lt_prop_free(&p->pt), lt_prop_free(&p->ir), lt_prop_free(&p->or_);
        lt_prop_free(&p->is), lt_prop_free(&p->os);
        free(p);
    }
    for (int i = 0; i < t->ntrims; i++) {
        lt_prop_free(&t->trims[i]->s), lt_prop_free(&t->trims[i]->e), lt_prop_free(&t->trims[i]->o);
        free(t->trims[i]);
    }
    for (int i = 0; i < t->nstyles; i++) {
        sh_style *s = t->styles[i];
        lt_prop_free(&s->c), lt_prop_free(&s->o), lt_prop_free(&s->w), lt_prop_free(&s->g);
        lt_prop_free(&s->gs), lt_prop_free(&s->ge), lt_prop_free(&s->gh), lt_prop_free(&s->ga);
        for (int k = 0; k < s->ndash; k++)
            lt_prop_free(&s->dash[k]);
        lt_prop_free(&s->dash_offset);
        free(s->paths);
        free(s);
    }
    free(t->nodes);
    free(t->paths);
    for (int i = 0; i < t->nreps; i++) {
        sh_rep *r = t->reps[i];
        lt_prop_free(&r->c), lt_prop_free(&r->o), lt_prop_free(&r->a), lt_prop_free(&r->p);
        lt_prop_free(&r->s), lt_prop_free(&r->r), lt_prop_free(&r->so), lt_prop_free(&r->eo);
        free(r);
    }
    free(t->trims);
    free(t->styles);
    free(t->reps);
}


/* ----------------------------------------------------------------- JSON */

cJSON *lt_num_array(const double *v, int n)
{
    cJSON *a = cJSON_CreateArray();
    for (int i = 0; i < n; i++)
        cJSON_AddItemToArray(a, cJSON_CreateNumber(v[i]));
    return a;
}

cJSON *lt_points_value(const double *v, int width)
{
    cJSON *a = cJSON_CreateArray();
    for (int i = 0; i + 2 < width; i += 3)
        cJSON_AddItemToArray(a, v[i + 2] == 1 ? lt_num_array(v + i, 2) : lt_num_array(v + i, 3));
    return a;
}

static cJSON *paint_value(const double *v, int width)
{
    (void)width;
    cJSON *o = cJSON_CreateObject();
    double rgb[3];
    for (int k = 0; k < 3; k++)
        rgb[k] = fmin(fmax(v[k], 0), 1);
    cJSON_AddItemToObject(o, "pigment", lt_num_array(rgb, 3));
    cJSON_AddNumberToObject(o, "beta", fmin(fmax(v[3], 0), 1));
    return o;
}

cJSON *lt_contour_json(const sv_contour *ct)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "degree", ct->degree);
    cJSON_AddItemToObject(o, "points", lt_points_value(ct->pts, 3 * ct->count));
    bool uniform = true;
    for (int i = 0; i < ct->count; i++)
        uniform = uniform && ct->intervals[i] == 1;
    if (!uniform)
        cJSON_AddItemToObject(o, "intervals", lt_num_array(ct->intervals, ct->count));
    return o;
}

/* Opacity of the style's groups at frame f, times its own. */
static double style_opacity(const sh_style *s, double f)
{
    double o;
    lt_prop_eval(&s->o, f, &o);
    o /= 100;
    for (const sh_node *n = s->node; n; n = n->parent)
        o *= lt_node_opacity(n, f);
    return o;
}

static void note_node_chain(lt_signal *sg, const sh_node *n, const lt_time *tm)
{
    for (; n; n = n->parent)
        if (n->rep) {
            const sh_rep *r = n->rep;
            const lt_prop *ps[8] = {&r->c, &r->o, &r->a, &r->p, &r->s, &r->r, &r->so, &r->eo};
            for (int k = 0; k < 8; k++)
                lt_signal_note_prop(sg, ps[k], tm->f0, tm->fscale);
        } else if (n->has_xf) {
            const lt_prop *ps[7] = {&n->a, &n->p, &n->s, &n->r, &n->o, &n->sk, &n->sa};
            for (int k = 0; k < 7; k++)
                lt_signal_note_prop(sg, ps[k], tm->f0, tm->fscale);
        }
}

/* A gradient as paint functions at frame 0 (sRGB stops, in the layer's space). */
static void gradient_paint(lt_ctx *c, const sh_style *s, const lt_time *tm, cJSON *paint,
                           double opacity)
{
    double f = tm->frame[0];
    double *g = malloc((size_t)s->gcount * sizeof *g);
    if (!g)
        return;
    lt_prop_eval(&s->g, f, g);
    double sp[2], ep[2];
    lt_prop_eval(&s->gs, f, sp);
    lt_prop_eval(&s->ge, f, ep);
    sv_affine up = lt_chain(s->node, NULL, f);
    sv_pt a = sv_affine_apply(up, sv_pt_make(sp[0], sp[1]));
    sv_pt b = sv_affine_apply(up, sv_pt_make(ep[0], ep[1]));
    if (lt_prop_animated(&s->g) || lt_prop_animated(&s->gs) || lt_prop_animated(&s->ge))
        lt_warn(c, LT_F_GRADIENT, "animated gradients are drawn as at the layer's first frame");
    int n = s->gstops > CS_CFG_MAX_STOPS ? CS_CFG_MAX_STOPS : s->gstops;
    cJSON *pig = cJSON_CreateObject();
    double geo[5];
    if (s->gtype == 1) {
        geo[0] = a.x, geo[1] = a.y, geo[2] = b.x, geo[3] = b.y;
        if (a.x == b.x && a.y == b.y)
            geo[2] += 1e-3;
        cJSON_AddItemToObject(pig, "linear", lt_num_array(geo, 4));
    } else {
        double r = sv_hypot(b.x - a.x, b.y - a.y), h;
        lt_prop_eval(&s->gh, f, &h);
        h = fmin(fmax(h / 100, -0.99), 0.99);
        double ang = atan2(b.y - a.y, b.x - a.x);
        double ha;
        lt_prop_eval(&s->ga, f, &ha);
        ang += ha * M_PI / 180;
        geo[0] = a.x, geo[1] = a.y, geo[2] = r > 1e-6 ? r : 1e-3;
        geo[3] = a.x + h * r * cos(ang), geo[4] = a.y + h * r * sin(ang);
        cJSON_AddItemToObject(pig, "radial", lt_num_array(geo, 5));
    }
    cJSON *stops = cJSON_AddArrayToObject(pig, "stops");
    double prev = 0;
    for (int i = 0; i < n; i++) {
        double off = fmin(fmax(g[4 * i], prev), 1), rgb[3];
        prev = off;
        for (int k = 0; k < 3; k++)
            rgb[k] = fmin(fmax(g[4 * i + 1 + k], 0), 1);
        cJSON *st = cJSON_CreateArray();
        cJSON_AddItemToArray(st, cJSON_CreateNumber(off));
        cJSON_AddItemToArray(st, lt_num_array(rgb, 3));
        cJSON_AddItemToArray(stops, st);
    }
    int na = (s->gcount - 4 * s->gstops) / 2;
    bool varying = false;
    for (int i = 0; i < na; i++)
        varying = varying || g[4 * s->gstops + 2 * i + 1] != 1;
    cJSON_AddItemToObject(paint, "pigment", pig);
    if (varying) {
        cJSON *beta = cJSON_CreateObject();
        cJSON_AddItemToObject(beta, s->gtype == 1 ? "linear" : "radial",
                              lt_num_array(geo, s->gtype == 1 ? 4 : 5));
        cJSON *bs = cJSON_AddArrayToObject(beta, "stops");
        int m = na > CS_CFG_MAX_STOPS ? CS_CFG_MAX_STOPS : na;
        prev = 0;
        for (int i = 0; i < m; i++) {
            double off = fmin(fmax(g[4 * s->gstops + 2 * i], prev), 1);
            prev = off;
            double al = fmin(fmax(g[4 * s->gstops + 2 * i + 1], 0), 1) * opacity;
            cJSON *st = cJSON_CreateArray();
            cJSON_AddItemToArray(st, cJSON_CreateNumber(off));
            cJSON_AddItemToArray(st, cJSON_CreateNumber(al));
            cJSON_AddItemToArray(bs, st);
        }
        cJSON_AddItemToObject(paint, "beta", beta);
    } else {
        cJSON_AddNumberToObject(paint, "beta", fmin(fmax(opacity, 0), 1));
    }
    free(g);
}

/* One style as a region over every frame; appended to `regions` (or nothing if empty). */
static int emit_region(lt_ctx *c, const sh_style *s, const lt_time *tm, cJSON *regions)
{
    int N = tm->nframes;
    /* Every frame's contours; frames whose layouts differ are unified. */
    sv_contour **fc = calloc((size_t)N, sizeof *fc);
    int *fn = calloc((size_t)N, sizeof *fn);
    if (!fc || !fn) {
        free(fc), free(fn);
        return lt_fail(c, "out of memory");
    }
    bool any = false, uniform = true;
    for (int n = 0; n < N; n++) {
        lt_region_contours(c, s, tm->frame[n], &fc[n], &fn[n]);
        for (int i = 0; tm->xf && i < fn[n]; i++)
            for (int k = 0; k < fc[n][i].count; k++) {
                double *q = fc[n][i].pts + 3 * k;
                sv_pt m = sv_affine_apply(tm->xf[n], sv_pt_make(q[0], q[1]));
                q[0] = m.x, q[1] = m.y; /* control points are Euclidean: an affine map keeps
                                           the rational curve */
            }
        any = any || fn[n] > 0;
        uniform = uniform && lt_same_layout(fc[0], fn[0], fc[n], fn[n]);
        double w = 0;
        for (int i = 0; i < fn[n]; i++)
            w += 3.0 * fc[n][i].count;
        if (c->failed || !lt_charge(c, w + 64)) { /* failed: a refused dash pattern */
            for (int k = 0; k <= n; k++)
                lt_free_contours(fc[k], fn[k]);
            free(fc), free(fn);
            return -1;
        }
    }
    if (!any) {
        for (int n = 0; n < N; n++)
            lt_free_contours(fc[n], fn[n]);
        free(fc), free(fn);
        return 0;
    }
    if (!uniform)
        lt_unify_layout(fc, fn, N);
    sv_contour *first = fc[0];
    int nfirst = fn[0];
    /* Geometry signals, one per contour. */
    lt_signal *geo = calloc((size_t)(nfirst ? nfirst : 1), sizeof *geo);
    if (!geo)
        return lt_fail(c, "out of memory");
    for (int i = 0; i < nfirst; i++) {
        lt_signal_init(&geo[i], N, 3 * first[i].count, 0.01);
        for (const sh_path *const *p = (const sh_path *const *)s->paths;
             p < (const sh_path *const *)s->paths + s->npaths; p++) {
            const lt_prop *ps[10] = {&(*p)->k,  &(*p)->p,   &(*p)->s,  &(*p)->r,  &(*p)->pt,
                                     &(*p)->ir, &(*p)->or_, &(*p)->is, &(*p)->os, NULL};
            for (int k = 0; ps[k]; k++)
                lt_signal_note_prop(&geo[i], ps[k], tm->f0, tm->fscale);
            note_node_chain(&geo[i], (*p)->node, tm);
        }
        for (int n = 0; n < N; n++)
            memcpy(geo[i].v + (size_t)n * geo[i].width, fc[n][i].pts,
                   (size_t)geo[i].width * sizeof(double));
    }
    for (int n = 1; n < N; n++)
        lt_free_contours(fc[n], fn[n]);
    free(fc);
    free(fn);
    /* Paint: colour and opacity over the frames. */
    lt_signal pt;
    lt_signal_init(&pt, N, 4, 1e-3);
    lt_signal_note_prop(&pt, &s->o, tm->f0, tm->fscale);
    if (s->type == ST_FILL || s->type == ST_STROKE)
        lt_signal_note_prop(&pt, &s->c, tm->f0, tm->fscale);
    note_node_chain(&pt, s->node, tm);
    for (int n = 0; n < N; n++) {
        double f = tm->frame[n], *v = pt.v + 4 * (size_t)n;
        if (s->type == ST_FILL || s->type == ST_STROKE)
            lt_prop_eval(&s->c, f, v);
        v[3] = style_opacity(s, f);
    }
    bool shown = false;
    for (int n = 0; n < N && !shown; n++)
        shown = pt.v[4 * (size_t)n + 3] > 0;
    if (!shown) { /* a repeater's copy beyond its count at every frame, or faded out */
        for (int i = 0; i < nfirst; i++)
            lt_signal_free(&geo[i]);
        free(geo);
        lt_signal_free(&pt);
        lt_free_contours(first, nfirst);
        return 0;
    }
    cJSON *reg = cJSON_CreateObject();
    cJSON_AddStringToObject(reg, "fill_rule",
                            s->rule == CS_FILL_EVENODD && (s->type == ST_FILL || s->type == ST_GFILL)
                                ? "evenodd" : "nonzero");
    cJSON *paint = cJSON_AddObjectToObject(reg, "paint");
    if (s->type == ST_FILL || s->type == ST_STROKE) {
        cJSON *p0 = paint_value(pt.v, 4);
        cJSON_AddItemToObject(paint, "pigment", cJSON_DetachItemFromObject(p0, "pigment"));
        cJSON_AddItemToObject(paint, "beta", cJSON_DetachItemFromObject(p0, "beta"));
        cJSON_Delete(p0);
        cJSON *track = lt_signal_track(&pt, c->fr, paint_value);
        if (track) {
            cJSON *anim = cJSON_AddObjectToObject(reg, "animate");
            cJSON_AddItemToObject(anim, "paint", track);
        }
    } else {
        gradient_paint(c, s, tm, paint, pt.v[3]);
        bool opacity_moves = false;
        for (int n = 1; n < N; n++)
            opacity_moves = opacity_moves || fabs(pt.v[4 * n + 3] - pt.v[3]) > 1e-4;
        if (opacity_moves)
            lt_warn(c, LT_F_GRADIENT, "animated opacity of a gradient is drawn as at the first frame");
    }
    cJSON *cts = cJSON_AddArrayToObject(reg, "contours");
    for (int i = 0; i < nfirst; i++) {
        cJSON *ct = lt_contour_json(&first[i]);
        /* The static points are the first frame's, as the track's first key. */
        cJSON_ReplaceItemInObject(ct, "points", lt_points_value(geo[i].v, geo[i].width));
        cJSON *track = lt_signal_track(&geo[i], c->fr, lt_points_value);
        if (track) {
            cJSON *anim = cJSON_AddObjectToObject(ct, "animate");
            cJSON_AddItemToObject(anim, "points", track);
        }
        cJSON_AddItemToArray(cts, ct);
    }
    cJSON_AddItemToArray(regions, reg);
    for (int i = 0; i < nfirst; i++)
        lt_signal_free(&geo[i]);
    free(geo);
    lt_signal_free(&pt);
    lt_free_contours(first, nfirst);
    return 0;
}

int lt_shapes(lt_ctx *c, const cJSON *shapes, const lt_time *tm, cJSON *regions)
{
    sh_tree t;
    memset(&t, 0, sizeof t);
    path_list acc = {0, 0, NULL};
    int depth = c->depth;
    int rc = parse_group(c, shapes, NULL, &t, &acc);
    c->depth = depth;
    free(acc.v);
    /* Styles in list order are front to back. */
    for (int i = 0; i < t.nstyles && rc == 0; i++)
        rc = emit_region(c, t.styles[i], tm, regions);
    tree_free(&t);
    return rc;
}

int lt_solid(lt_ctx *c, const cJSON *layer, const lt_time *tm, cJSON *regions)
{
    (void)tm;
    double w, h;
    if (lt_num(c, layer, "sw", 0, 1e6, 0, &w) || lt_num(c, layer, "sh", 0, 1e6, 0, &h))
        return -1;
    const cJSON *sc = get(layer, "sc");
    /* A colour that is not #rrggbb (some files have "") is white, as rlottie reads it. */
    double rgb[3] = {1, 1, 1};
    if (cJSON_IsString(sc)) {
        unsigned r, g, b;
        if (sscanf(sc->valuestring, "#%2x%2x%2x", &r, &g, &b) == 3) {
            rgb[0] = r / 255.0, rgb[1] = g / 255.0, rgb[2] = b / 255.0;
        }
    }
    if (w <= 0 || h <= 0)
        return 0;
    cJSON *reg = cJSON_CreateObject();
    cJSON *paint = cJSON_AddObjectToObject(reg, "paint");
    cJSON_AddItemToObject(paint, "pigment", lt_num_array(rgb, 3));
    cJSON *cts = cJSON_AddArrayToObject(reg, "contours");
    cJSON *ct = cJSON_CreateObject();
    cJSON_AddNumberToObject(ct, "degree", 1);
    double pts[4][2] = {{0, 0}, {w, 0}, {w, h}, {0, h}};
    cJSON *pa = cJSON_AddArrayToObject(ct, "points");
    for (int i = 0; i < 4; i++)
        cJSON_AddItemToArray(pa, lt_num_array(pts[i], 2));
    cJSON_AddItemToArray(cts, ct);
    cJSON_AddItemToArray(regions, reg);
    return 0;
}
