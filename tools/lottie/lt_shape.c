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
 * Each region is then sampled at every frame: its paths are built in their
 * own group's space, carried up by the group transforms to the style's
 * group, stroked there (the SVG importer's stroker, dashes included), and
 * carried up to the layer; fills keep one cubic, conic or line contour per
 * subpath with a fixed control-point layout, so an animated path, group
 * transform or stroke whose outline keeps its layout becomes a points track
 * (lt_track.c turns the frames back into keys). Paint colour and opacity,
 * times the opacities of the groups above, are a paint track.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../svg/sv_internal.h"
#include "lt_internal.h"

enum { SH_PATH, SH_ELLIPSE, SH_RECT, SH_STAR };
enum { ST_FILL, ST_STROKE, ST_GFILL, ST_GSTROKE };

typedef struct sh_node {
    struct sh_node *parent;
    bool has_xf;
    lt_prop a, p, s, r, o, sk, sa;
} sh_node;

typedef struct sh_trim {
    lt_prop s, e, o;
} sh_trim;

typedef struct sh_path {
    int type;
    bool reversed;
    int nverts;
    lt_prop k, p, s, r;             /* sh: k; el: p s; rc: p s r; sr: p r (rotation) */
    lt_prop pt, ir, or_;            /* sr */
    int star;                       /* sr: 1 star, 2 polygon */
    sh_node *node;
    int ntrims;
    sh_trim *trims[8];
} sh_path;

typedef struct sh_style {
    int type;
    sh_node *node;
    int rule;
    lt_prop c, o, w, gs, ge, gh, ga, g;
    int gtype, gstops, gcount;
    sv_cap cap;
    sv_join join;
    double miter;
    int ndash;
    lt_prop dash[16];
    lt_prop dash_offset;
    bool has_dash;
    int npaths;
    sh_path **paths;
} sh_style;

typedef struct sh_tree {
    int nnodes, nnodes_cap;
    sh_node **nodes;
    int npaths_all, npaths_cap;
    sh_path **paths;
    int ntrims, ntrims_cap;
    sh_trim **trims;
    int nstyles, nstyles_cap;
    sh_style **styles;
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

/* A transform's matrix and opacity at frame f (the After Effects order). */
void lt_xf_eval(const lt_prop *a, const lt_prop *p, const lt_prop *s, const lt_prop *r,
                const lt_prop *sk, const lt_prop *sa, double f, sv_affine *m)
{
    double av[2], pv[2], sv[2], rv, kv, kav;
    lt_prop_eval(a, f, av);
    lt_prop_eval(p, f, pv);
    lt_prop_eval(s, f, sv);
    lt_prop_eval(r, f, &rv);
    lt_prop_eval(sk, f, &kv);
    lt_prop_eval(sa, f, &kav);
    double d = M_PI / 180;
    sv_affine acc = {sv[0] / 100, 0, 0, sv[1] / 100, -sv[0] / 100 * av[0], -sv[1] / 100 * av[1]};
    if (kv != 0) {
        double ca = cos(kav * d), sn = sin(kav * d), t = tan(-kv * d);
        sv_affine rn = {ca, -sn, sn, ca, 0, 0}, sh = {1, 0, t, 1, 0, 0}, rp = {ca, sn, -sn, ca, 0, 0};
        acc = sv_affine_mul(rp, sv_affine_mul(sh, sv_affine_mul(rn, acc)));
    }
    double cr = cos(rv * d), sr = sin(rv * d);
    sv_affine rot = {cr, sr, -sr, cr, pv[0], pv[1]};
    *m = sv_affine_mul(rot, acc);
}

static sv_affine node_matrix(const sh_node *n, double f)
{
    sv_affine m = sv_affine_identity();
    if (n->has_xf)
        lt_xf_eval(&n->a, &n->p, &n->s, &n->r, &n->sk, &n->sa, f, &m);
    return m;
}

static double node_opacity(const sh_node *n, double f)
{
    double o = 100;
    if (n->has_xf)
        lt_prop_eval(&n->o, f, &o);
    return o / 100;
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
        double is = 0, os = 0;
        lt_prop q;
        if (lt_prop_parse(c, get(it, "is"), 1, d_zero, "polystar roundness", &q) == 0) {
            lt_prop_eval(&q, 0, &is);
            lt_prop_free(&q);
        }
        if (lt_prop_parse(c, get(it, "os"), 1, d_zero, "polystar roundness", &q) == 0) {
            lt_prop_eval(&q, 0, &os);
            lt_prop_free(&q);
        }
        if (is != 0 || os != 0)
            lt_warn(c, LT_F_STAR_ROUND, "polystar roundness is drawn as sharp corners");
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
                    return -1;
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

/* One group's items in list order; `acc` collects its paths for the caller. */
static int parse_group(lt_ctx *c, const cJSON *items, sh_node *node, sh_tree *t, path_list *acc)
{
    if (++c->depth > LT_MAX_DEPTH)
        return lt_fail(c, "shape groups nested deeper than %d", LT_MAX_DEPTH);
    if (!cJSON_IsArray(items))
        return lt_fail(c, "a group's items (\"it\" or \"shapes\") are not an array");
    const cJSON *it;
    cJSON_ArrayForEach(it, items)
    {
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
        } else if (!strcmp(ty, "rp")) {
            lt_warn(c, LT_F_REPEATER, "repeaters are not supported: one copy is drawn");
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
    free(t->trims);
    free(t->styles);
}

/* ------------------------------------------------------------ geometry */

void lt_path_build(const double *vals, int n, sv_path *out)
{
    lt_path lp;
    lt_path_from_values(vals, n, &lp);
    sv_path_move(out, lp.v[0], lp.v[1]);
    int segs = lp.closed ? n : n - 1;
    for (int k = 0; k < segs; k++) {
        int j = (k + 1) % n;
        sv_path_cubic(out, lp.v[2 * k] + lp.out[2 * k], lp.v[2 * k + 1] + lp.out[2 * k + 1],
                      lp.v[2 * j] + lp.in[2 * j], lp.v[2 * j + 1] + lp.in[2 * j + 1],
                      lp.v[2 * j], lp.v[2 * j + 1]);
    }
    if (lp.closed)
        sv_path_close(out);
}

/* A path item at frame f in its group's space. */
static void build_path(const sh_path *p, double f, sv_path *out)
{
    if (p->type == SH_PATH) {
        int n = p->nverts;
        if (n < 1)
            return;
        double *vals = malloc((size_t)(1 + 6 * n) * sizeof *vals);
        if (!vals)
            return;
        lt_prop_eval(&p->k, f, vals);
        lt_path_build(vals, n, out);
        free(vals);
        return;
    }
    double pv[2], sv[2];
    lt_prop_eval(&p->p, f, pv);
    if (p->type == SH_ELLIPSE) {
        lt_prop_eval(&p->s, f, sv);
        double rx = fabs(sv[0]) / 2, ry = fabs(sv[1]) / 2, k = sqrt(0.5);
        /* From the top, clockwise on screen (rlottie's start point). */
        double cx = pv[0], cy = pv[1];
        sv_path_move(out, cx, cy - ry);
        if (!p->reversed) {
            sv_path_conic(out, cx + rx, cy - ry, k, cx + rx, cy);
            sv_path_conic(out, cx + rx, cy + ry, k, cx, cy + ry);
            sv_path_conic(out, cx - rx, cy + ry, k, cx - rx, cy);
            sv_path_conic(out, cx - rx, cy - ry, k, cx, cy - ry);
        } else {
            sv_path_conic(out, cx - rx, cy - ry, k, cx - rx, cy);
            sv_path_conic(out, cx - rx, cy + ry, k, cx, cy + ry);
            sv_path_conic(out, cx + rx, cy + ry, k, cx + rx, cy);
            sv_path_conic(out, cx + rx, cy - ry, k, cx, cy - ry);
        }
        sv_path_close(out);
        return;
    }
    if (p->type == SH_RECT) {
        double rr;
        lt_prop_eval(&p->s, f, sv);
        lt_prop_eval(&p->r, f, &rr);
        double w = fabs(sv[0]) / 2, h = fabs(sv[1]) / 2;
        double r = fmin(fmax(rr, 0), fmin(w, h)), k = sqrt(0.5);
        double x0 = pv[0] - w, x1 = pv[0] + w, y0 = pv[1] - h, y1 = pv[1] + h;
        /* Clockwise from the top right, as rlottie; corners as quarter conics. */
        double pts[8][2] = {{x1, y0 + r}, {x1, y1 - r}, {x1 - r, y1}, {x0 + r, y1},
                            {x0, y1 - r}, {x0, y0 + r}, {x0 + r, y0}, {x1 - r, y0}};
        double corner[4][2] = {{x1, y1}, {x0, y1}, {x0, y0}, {x1, y0}};
        if (p->reversed) {
            sv_path_move(out, pts[0][0], pts[0][1]);
            for (int i = 7; i >= 0; i--) {
                if (i % 2 == 1)
                    sv_path_line(out, pts[i][0], pts[i][1]);
                else if (r > 0)
                    sv_path_conic(out, corner[(i / 2 + 3) % 4][0], corner[(i / 2 + 3) % 4][1], k,
                                  pts[i][0], pts[i][1]);
                else
                    sv_path_line(out, pts[i][0], pts[i][1]);
            }
        } else {
            sv_path_move(out, pts[0][0], pts[0][1]);
            for (int i = 1; i <= 8; i++) {
                int j = i % 8;
                if (i % 2 == 1)
                    sv_path_line(out, pts[j][0], pts[j][1]);
                else if (r > 0)
                    sv_path_conic(out, corner[i / 2 - 1][0], corner[i / 2 - 1][1], k, pts[j][0],
                                  pts[j][1]);
                else
                    sv_path_line(out, pts[j][0], pts[j][1]);
            }
        }
        sv_path_close(out);
        return;
    }
    /* Polystar: from the top (rotation 0), clockwise. */
    double npt, rot, ir, orr;
    lt_prop_eval(&p->pt, f, &npt);
    lt_prop_eval(&p->r, f, &rot);
    lt_prop_eval(&p->ir, f, &ir);
    lt_prop_eval(&p->or_, f, &orr);
    int n = (int)floor(npt);
    if (n < 2 || n > 1000)
        return;
    int m = p->star == 1 ? 2 * n : n;
    for (int i = 0; i < m; i++) {
        int k = p->reversed ? (m - i) % m : i;
        double ang = (rot - 90) * M_PI / 180 + 2 * M_PI * k / m;
        double rad = p->star == 1 && k % 2 ? ir : orr;
        double x = pv[0] + rad * cos(ang), y = pv[1] + rad * sin(ang);
        if (i == 0)
            sv_path_move(out, x, y);
        else
            sv_path_line(out, x, y);
    }
    sv_path_close(out);
}

/* Trims `path` to [s, e] of each subpath's length, shifted by o (rlottie's simultaneous mode). */
static void trim_path(const sh_trim *tm, double f, sv_path *path)
{
    double s, e, o;
    lt_prop_eval(&tm->s, f, &s);
    lt_prop_eval(&tm->e, f, &e);
    lt_prop_eval(&tm->o, f, &o);
    s /= 100, e /= 100, o /= 360;
    if (s > e) {
        double t = s;
        s = e, e = t;
    }
    s += o, e += o;
    double sh = floor(s);
    s -= sh, e -= sh;
    if (e - s >= 1 - 1e-9)
        return;
    sv_path out;
    sv_path_init(&out);
    for (int i = 0; i < path->n; i++) {
        sv_path one;
        sv_path_init(&one);
        one.sub = &path->sub[i];
        one.n = 1;
        /* The subpath's length, by flattening. */
        sv_pt *pts = NULL;
        int np = 0;
        sv_subpath_flatten(&path->sub[i], 32, &pts, &np);
        double len = 0;
        int last = path->sub[i].closed ? np : np - 1;
        for (int k = 0; k < last; k++)
            len += sv_hypot(pts[(k + 1) % np].x - pts[k].x, pts[(k + 1) % np].y - pts[k].y);
        free(pts);
        if (len <= 0 || e - s <= 0)
            continue;
        /* Visible [s, e], wrapping past 1 as two pieces: each one dash
         * followed by a gap longer than the path, so that the flattened
         * length's small shortfall never starts a second dash (a dot under
         * round caps) at the path's end. */
        double big = 4 * len + 1;
        double first[2] = {(fmin(e, 1) - s) * len, big};
        sv_path_dash(&one, first, 2, -s * len, &out);
        if (e > 1) {
            double wrap[2] = {(e - 1) * len, big};
            sv_path_dash(&one, wrap, 2, 0, &out);
        }
    }
    sv_path_free(path);
    *path = out;
}

/* The chain of group transforms from node `from` up to (not including) `to`. */
static sv_affine chain(const sh_node *from, const sh_node *to, double f)
{
    sv_affine m = sv_affine_identity();
    for (const sh_node *n = from; n && n != to; n = n->parent)
        m = sv_affine_mul(node_matrix(n, f), m);
    return m;
}

/* Closed contours of a path with a fixed layout: one per subpath, every
 * segment elevated to the subpath's highest degree, a closing line added. */
void lt_fixed_contours(const sv_path *p, sv_contour **out, int *n)
{
    for (int i = 0; i < p->n; i++) {
        const sv_subpath *sp = &p->sub[i];
        if (sp->n < 1)
            continue;
        int k = sp->n, degree = 1;
        for (int j = 0; j < sp->n; j++)
            degree = sp->seg[j].degree > degree ? sp->seg[j].degree : degree;
        sv_pt first = sp->seg[0].p[0], last = sp->seg[k - 1].p[sp->seg[k - 1].degree];
        bool close = first.x != last.x || first.y != last.y || k == 1;
        int nseg = k + (close ? 1 : 0);
        *out = sv_xrealloc(*out, (size_t)(*n + 1) * sizeof **out);
        sv_contour *c = &(*out)[(*n)++];
        c->degree = degree;
        c->count = nseg * degree;
        c->pts = sv_xrealloc(NULL, (size_t)c->count * 3 * sizeof(double));
        c->intervals = sv_xrealloc(NULL, (size_t)c->count * sizeof(double));
        for (int j = 0; j < nseg; j++) {
            sv_seg s = j < k ? sp->seg[j] : (sv_seg){1, {last, first}, 1};
            double h[4][3];
            sv_seg_elevate(&s, degree, h);
            for (int m = 0; m < degree; m++) {
                double *q = &c->pts[3 * (j * degree + m)];
                q[0] = h[m][0] / h[m][2];
                q[1] = h[m][1] / h[m][2];
                q[2] = h[m][2];
                c->intervals[j * degree + m] = m == 0 ? 1.0 : 0.0;
            }
        }
    }
}

/* A region's contours at frame f, in the layer's space. */
static void region_contours(lt_ctx *c, const sh_style *s, double f, sv_contour **out, int *n)
{
    sv_path all;
    sv_path_init(&all);
    for (int i = 0; i < s->npaths; i++) {
        const sh_path *p = s->paths[i];
        sv_path one;
        sv_path_init(&one);
        build_path(p, f, &one);
        for (int k = 0; k < p->ntrims; k++)
            trim_path(p->trims[k], f, &one);
        sv_path_transform(&one, chain(p->node, s->node, f));
        sv_path_append(&all, &one);
        sv_path_free(&one);
    }
    sv_affine up = chain(s->node, NULL, f);
    /* Outlining costs about a few dozen floats per segment: charged first. */
    int nseg = 0;
    for (int i = 0; i < all.n; i++)
        nseg += all.sub[i].n;
    if (!lt_charge(c, (s->type == ST_STROKE || s->type == ST_GSTROKE ? 64.0 : 4.0) * nseg)) {
        sv_path_free(&all);
        return;
    }
    if (s->type == ST_STROKE || s->type == ST_GSTROKE) {
        double w;
        lt_prop_eval(&s->w, f, &w);
        sv_path src = all;
        sv_path dashed;
        sv_path_init(&dashed);
        if (s->has_dash) {
            double d[16], off, sum = 0;
            for (int k = 0; k < s->ndash; k++) {
                lt_prop_eval(&s->dash[k], f, &d[k]);
                d[k] = fmax(d[k], 0);
                sum += d[k];
            }
            lt_prop_eval(&s->dash_offset, f, &off);
            if (sum > 0) {
                sv_path_dash(&all, d, s->ndash, off, &dashed);
                src = dashed;
            }
        }
        sv_path outline;
        sv_path_init(&outline);
        if (w > 0) {
            /* Tolerance in the style's space: the canvas one over the scale above. */
            double scale = sv_affine_max_scale(up);
            sv_stroke_style st = {w, s->cap, s->join, s->miter,
                                  c->tolerance / (scale > 1e-9 ? scale : 1)};
            sv_stroke_path(&src, &st, &outline);
        }
        sv_path_transform(&outline, up);
        sv_path_to_contours(&outline, out, n);
        sv_path_free(&outline);
        sv_path_free(&dashed);
    } else {
        sv_path_transform(&all, up);
        lt_fixed_contours(&all, out, n);
    }
    sv_path_free(&all);
}

static bool same_layout(const sv_contour *a, int na, const sv_contour *b, int nb)
{
    if (na != nb)
        return false;
    for (int i = 0; i < na; i++)
        if (a[i].degree != b[i].degree || a[i].count != b[i].count ||
            memcmp(a[i].intervals, b[i].intervals, (size_t)a[i].count * sizeof(double)) != 0)
            return false;
    return true;
}

void lt_free_contours(sv_contour *c, int n)
{
    for (int i = 0; i < n; i++)
        sv_contour_free(&c[i]);
    free(c);
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
        o *= node_opacity(n, f);
    return o;
}

static void note_node_chain(lt_signal *sg, const sh_node *n, const lt_time *tm)
{
    for (; n; n = n->parent)
        if (n->has_xf) {
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
    sv_affine up = chain(s->node, NULL, f);
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
        region_contours(c, s, tm->frame[n], &fc[n], &fn[n]);
        any = any || fn[n] > 0;
        uniform = uniform && same_layout(fc[0], fn[0], fc[n], fn[n]);
        double w = 0;
        for (int i = 0; i < fn[n]; i++)
            w += 3.0 * fc[n][i].count;
        if (!lt_charge(c, w + 64)) {
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
            const lt_prop *ps[8] = {&(*p)->k, &(*p)->p, &(*p)->s, &(*p)->r,
                                    &(*p)->pt, &(*p)->ir, &(*p)->or_, NULL};
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
    double rgb[3] = {0, 0, 0};
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
