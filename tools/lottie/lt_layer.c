/*
 * lt_layer.c - Lottie layers as cels and cel groups.
 *
 * Every drawn layer (shape, solid) becomes a cel of its own, in the layer
 * list's order (the first layer is in front). Its transform ("ks": anchor,
 * position, scale, rotation, skew, opacity) is a TRS track, its in and out
 * points multiply the track's opacity (0 outside them), and its content is
 * regions (lt_shape.c). Parenting is the core's cel groups: a layer that
 * other layers name as "parent" also gets a group cel carrying its
 * transform alone, since a parent's transform moves its children but its
 * opacity does not; the layer's own content cel then carries only its
 * opacity and sits in that group. Precomp layers are groups over their
 * composition's layers, which are read again for every use, with the
 * composition's time: the layer's frame minus its start time "st", over
 * its stretch "sr", or a plain time-remap track "tm" (rlottie's reading,
 * whole frames). Null layers are groups and draw nothing.
 *
 * Parent chains, precomp nesting and their cycles are bounded by
 * LT_MAX_DEPTH and refused with an error naming the layer.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../svg/sv_internal.h"
#include "lt_internal.h"

static const cJSON *get(const cJSON *o, const char *k)
{
    return cJSON_GetObjectItemCaseSensitive(o, k);
}

typedef struct layer_info {
    const cJSON *j;
    double ind;
    int parent;    /* index into the list, or -1 */
    bool is_parent;
    int xf_cel;    /* group cel with its transform, or -1 */
} layer_info;

/* A TRS sample: scale and opacity are kept in percent, so that one
 * tolerance (0.01) means 0.01 px, 0.01 degree and 0.01 % alike. */
static cJSON *trs_value(const double *pct, int width)
{
    (void)width;
    double v[10];
    memcpy(v, pct, sizeof v);
    v[4] /= 100, v[5] /= 100, v[9] /= 100;
    cJSON *o = cJSON_CreateObject();
    if (v[0] != 0 || v[1] != 0)
        cJSON_AddItemToObject(o, "position", lt_num_array(v, 2));
    if (v[2] != 0 || v[3] != 0)
        cJSON_AddItemToObject(o, "anchor", lt_num_array(v + 2, 2));
    if (v[4] != 1 || v[5] != 1)
        cJSON_AddItemToObject(o, "scale", lt_num_array(v + 4, 2));
    if (v[6] != 0)
        cJSON_AddNumberToObject(o, "rotation", v[6]);
    if (v[7] != 0) {
        cJSON_AddNumberToObject(o, "skew", v[7]);
        cJSON_AddNumberToObject(o, "skew_axis", v[8]);
    }
    if (v[9] != 1)
        cJSON_AddNumberToObject(o, "opacity", fmin(fmax(v[9], 0), 1));
    return o;
}

/* A layer's transform props. */
typedef struct layer_xf {
    lt_prop a, p, s, r, o, sk, sa;
} layer_xf;

static int parse_layer_xf(lt_ctx *c, const cJSON *ks, layer_xf *x)
{
    static const double zero[3] = {0, 0, 0}, hundred[3] = {100, 100, 100}, one[1] = {100};
    const cJSON *r = get(ks, "r");
    if (!r)
        r = get(ks, "rz");
    return lt_prop_parse(c, get(ks, "a"), 2, zero, "layer anchor", &x->a) ||
           lt_prop_parse(c, get(ks, "p"), 2, zero, "layer position", &x->p) ||
           lt_prop_parse(c, get(ks, "s"), 2, hundred, "layer scale", &x->s) ||
           lt_prop_parse(c, r, 1, zero, "layer rotation", &x->r) ||
           lt_prop_parse(c, get(ks, "o"), 1, one, "layer opacity", &x->o) ||
           lt_prop_parse(c, get(ks, "sk"), 1, zero, "layer skew", &x->sk) ||
           lt_prop_parse(c, get(ks, "sa"), 1, zero, "layer skew axis", &x->sa);
}

static void free_layer_xf(layer_xf *x)
{
    lt_prop_free(&x->a), lt_prop_free(&x->p), lt_prop_free(&x->s), lt_prop_free(&x->r);
    lt_prop_free(&x->o), lt_prop_free(&x->sk), lt_prop_free(&x->sa);
}

/*
 * A precomp layer folded into the one layer its composition draws: instead
 * of a group cel of its own, its transform, opacity and in / out points
 * compose onto that layer's TRS track, sample by sample. Taken only where
 * the precomp's transform is a similarity at every sample (uniform scale,
 * no skew), since then P . T(p) R(r) K S(s) T(-a), K the skew, is
 * T(P(p)) R(r + rP) K S(s sP) T(-a) again, one TRS key per sample. Files
 * of many one-layer precomps (1667-firework.json: 104 of them) would
 * otherwise take a group cel each, beyond the store's cels.
 */
struct lt_fold {
    const layer_xf *x;      /* the precomp layer's transform */
    const lt_time *tm;      /* its time (the composition it sits in) */
    const double *visible;  /* its in / out points at each sample */
    int depth;              /* c->depth of the composition folded into it */
    int group;              /* the cel its group cel would have sat in */
};

/* Composes the fold's transform and opacity at sample n onto a TRS sample v (scale and
 * opacity in percent, as in add_cel). */
static void fold_sample(const struct lt_fold *fd, int n, double *v)
{
    double f = fd->tm->frame[n], a[2], p[2], s[2], r, o;
    lt_prop_eval(&fd->x->a, f, a);
    lt_prop_eval(&fd->x->p, f, p);
    lt_prop_eval(&fd->x->s, f, s);
    lt_prop_eval(&fd->x->r, f, &r);
    lt_prop_eval(&fd->x->o, f, &o);
    double k = s[0] / 100, d = M_PI / 180, cr = cos(r * d), sr = sin(r * d);
    double dx = v[0] - a[0], dy = v[1] - a[1];
    v[0] = p[0] + k * (cr * dx - sr * dy);
    v[1] = p[1] + k * (sr * dx + cr * dy);
    v[4] *= k, v[5] *= k;
    v[6] += r;
    v[9] *= fmin(fmax(o, 0), 100) / 100 * fd->visible[n];
}

/*
 * Appends a cel: regions (NULL: a group), the layer's transform and/or
 * opacity times visibility as a TRS track or a static transform, and its
 * parent cel. Returns the cel's index.
 */
static int add_cel(lt_ctx *c, const char *name, cJSON *regions, const layer_xf *x,
                   bool transform, bool opacity, const double *visible, const lt_time *tm,
                   int parent)
{
    int N = tm->nframes;
    lt_signal sg;
    lt_signal_init(&sg, N, 10, 0.01);
    if (!sg.v || !lt_charge(c, 10.0 * N)) {
        lt_signal_free(&sg);
        return -1;
    }
    const lt_prop *ps[7] = {&x->a, &x->p, &x->s, &x->r, &x->o, &x->sk, &x->sa};
    for (int k = 0; k < 7; k++)
        if (transform || k == 4)
            lt_signal_note_prop(&sg, ps[k], tm->f0, tm->fscale);
    /* The folded precomp's layer: its own TRS with the precomp's after it. */
    const struct lt_fold *fd = c->fold && c->depth == c->fold->depth && parent == c->fold->group &&
                                       transform ? c->fold : NULL;
    if (fd) {
        const layer_xf *fx = fd->x;
        const lt_prop *fp[5] = {&fx->a, &fx->p, &fx->s, &fx->r, &fx->o};
        for (int k = 0; k < 5; k++)
            lt_signal_note_prop(&sg, fp[k], fd->tm->f0, fd->tm->fscale);
        for (int n = 1; n < N; n++)
            if (fd->visible[n] != fd->visible[n - 1])
                lt_signal_break(&sg, n);
    }
    for (int n = 0; n < N; n++) {
        double f = tm->frame[n], *v = sg.v + 10 * (size_t)n;
        double a[2], p[2], s[2], r, o, sk, sa;
        lt_prop_eval(&x->a, f, a);
        lt_prop_eval(&x->p, f, p);
        lt_prop_eval(&x->s, f, s);
        lt_prop_eval(&x->r, f, &r);
        lt_prop_eval(&x->o, f, &o);
        lt_prop_eval(&x->sk, f, &sk);
        lt_prop_eval(&x->sa, f, &sa);
        if (transform) {
            v[0] = p[0], v[1] = p[1], v[2] = a[0], v[3] = a[1];
            v[4] = s[0], v[5] = s[1], v[6] = r;
            v[7] = fmin(fmax(-sk, -85), 85), v[8] = sa;
        } else {
            v[0] = v[1] = v[2] = v[3] = v[6] = v[7] = v[8] = 0;
            v[4] = v[5] = 100;
        }
        v[9] = (opacity ? fmin(fmax(o, 0), 100) : 100) * (visible ? visible[n] : 1);
        if (fd)
            fold_sample(fd, n, v);
    }
    /* Visibility steps on whole frames: breaks there make them holds. */
    if (visible)
        for (int n = 1; n < N; n++)
            if (visible[n] != visible[n - 1])
                lt_signal_break(&sg, n);
    cJSON *cel = cJSON_CreateObject();
    cJSON_AddStringToObject(cel, "name", name);
    cJSON_AddItemToObject(cel, "regions", regions ? regions : cJSON_CreateArray());
    cJSON *track = lt_signal_track(&sg, c->fr, trs_value);
    if (track) {
        cJSON *anim = cJSON_AddObjectToObject(cel, "animate");
        cJSON_AddItemToObject(anim, "trs", track);
    } else if (sg.v[9] != 100) {
        /* Static but faded: a one-key TRS track holds the opacity. */
        cJSON *anim = cJSON_AddObjectToObject(cel, "animate");
        cJSON *t = cJSON_AddObjectToObject(anim, "trs"), *keys = cJSON_AddArrayToObject(t, "keys");
        cJSON *key = cJSON_CreateArray();
        cJSON_AddItemToArray(key, cJSON_CreateNumber(0));
        cJSON_AddItemToArray(key, trs_value(sg.v, 10));
        cJSON_AddItemToArray(keys, key);
    } else {
        double v[10];
        memcpy(v, sg.v, sizeof v);
        v[4] /= 100, v[5] /= 100;
        double d = M_PI / 180, cr = cos(v[6] * d), sr = sin(v[6] * d);
        sv_affine m = {v[4], 0, 0, v[5], -v[4] * v[2], -v[5] * v[3]};
        if (v[7] != 0) {
            double ca = cos(v[8] * d), sn = sin(v[8] * d), t = tan(v[7] * d);
            sv_affine rn = {ca, -sn, sn, ca, 0, 0}, sh = {1, 0, t, 1, 0, 0},
                      rp = {ca, sn, -sn, ca, 0, 0};
            m = sv_affine_mul(rp, sv_affine_mul(sh, sv_affine_mul(rn, m)));
        }
        m = sv_affine_mul((sv_affine){cr, sr, -sr, cr, v[0], v[1]}, m);
        if (m.a != 1 || m.b != 0 || m.c != 0 || m.d != 1 || m.e != 0 || m.f != 0) {
            double mm[6] = {m.a, m.b, m.c, m.d, m.e, m.f};
            cJSON_AddItemToObject(cel, "transform", lt_num_array(mm, 6));
        }
    }
    if (parent >= 0)
        cJSON_AddNumberToObject(cel, "parent", parent);
    lt_signal_free(&sg);
    cJSON_AddItemToArray(c->cels, cel);
    return cJSON_GetArraySize(c->cels) - 1;
}

/* Whether a region may let what is behind it show through (beta below 1 at
 * some frame, or a function of position). */
static bool see_through(const cJSON *reg)
{
    const cJSON *paint = get(reg, "paint"), *beta = get(paint, "beta");
    if (beta && (!cJSON_IsNumber(beta) || beta->valuedouble < 1))
        return true;
    const cJSON *track = get(get(reg, "animate"), "paint"), *key;
    cJSON_ArrayForEach(key, get(track, "keys"))
    {
        const cJSON *b = get(cJSON_GetArrayItem(key, 1), "beta");
        if (cJSON_IsNumber(b) && b->valuedouble < 1)
            return true;
    }
    return false;
}

/* Grows box (x0 y0 x1 y1) by the control points in a "points" value. */
static void grow_box(const cJSON *pts, double *box)
{
    const cJSON *p;
    cJSON_ArrayForEach(p, pts)
    {
        const cJSON *x = cJSON_GetArrayItem(p, 0), *y = cJSON_GetArrayItem(p, 1);
        if (!cJSON_IsNumber(x) || !cJSON_IsNumber(y))
            continue;
        box[0] = fmin(box[0], x->valuedouble), box[1] = fmin(box[1], y->valuedouble);
        box[2] = fmax(box[2], x->valuedouble), box[3] = fmax(box[3], y->valuedouble);
    }
}

/* The box of a region's control points over every key: the region never
 * paints outside it (positive weights keep curves in their hulls). */
static void region_box(const cJSON *reg, double *box)
{
    box[0] = box[1] = INFINITY;
    box[2] = box[3] = -INFINITY;
    const cJSON *ct, *key;
    cJSON_ArrayForEach(ct, get(reg, "contours"))
    {
        grow_box(get(ct, "points"), box);
        cJSON_ArrayForEach(key, get(get(get(ct, "animate"), "points"), "keys"))
            grow_box(cJSON_GetArrayItem(key, 1), box);
    }
}

static bool boxes_meet(const double *a, const double *b)
{
    return a[0] <= b[2] && b[0] <= a[2] && a[1] <= b[3] && b[1] <= a[3];
}

/*
 * A layer's regions as cels. Regions of one cel do not blend with each
 * other: the front one owns the pixels it covers. That is Lottie's reading
 * where the front shape is opaque, so a region joins the cel of the
 * regions in front of it unless one of them that lets light through (at
 * some frame) may overlap it; then it starts a new cel. One cel takes the
 * layer's TRS track; several become children of a group cel that takes it.
 */
static int add_content(lt_ctx *c, const char *name, cJSON *regions, const layer_xf *x,
                       bool own_xf, const double *visible, const lt_time *tm, int group)
{
    int n = cJSON_GetArraySize(regions);
    int *run_of = calloc((size_t)(n ? n : 1), sizeof *run_of);
    double(*box)[4] = calloc((size_t)(n ? n : 1), sizeof *box);
    bool *clear = calloc((size_t)(n ? n : 1), sizeof *clear);
    if (!run_of || !box || !clear) {
        free(run_of), free(box), free(clear);
        return lt_fail(c, "out of memory");
    }
    int runs = 1, start = 0;
    for (int k = 0; k < n; k++) {
        const cJSON *reg = cJSON_GetArrayItem(regions, k);
        region_box(reg, box[k]);
        clear[k] = see_through(reg);
        bool meets = false;
        for (int j = start; j < k && !meets; j++)
            meets = clear[j] && boxes_meet(box[j], box[k]);
        if (meets) {
            runs++;
            start = k;
        }
        run_of[k] = runs - 1;
    }
    free(box);
    free(clear);
    if (runs == 1) {
        free(run_of);
        return add_cel(c, name, regions, x, own_xf, true, visible, tm, group) < 0 ? -1 : 0;
    }
    int holder = cJSON_GetArraySize(c->cels) + runs;
    for (int r = 0, k = 0; r < runs; r++) {
        cJSON *cel = cJSON_CreateObject(), *run = cJSON_CreateArray();
        cJSON_AddStringToObject(cel, "name", name);
        for (; k < n && run_of[k] == r; k++)
            cJSON_AddItemToArray(run, cJSON_DetachItemFromArray(regions, 0));
        cJSON_AddItemToObject(cel, "regions", run);
        cJSON_AddNumberToObject(cel, "parent", holder);
        cJSON_AddItemToArray(c->cels, cel);
    }
    free(run_of);
    cJSON_Delete(regions);
    return add_cel(c, name, NULL, x, own_xf, true, visible, tm, group) == holder ? 0 : -1;
}

/* Whether a precomp layer (transform x, at the samples of tm) folds into its composition
 * `layers`: they draw one shape or solid layer, with no parenting or track mattes among
 * them (null layers aside), and the precomp's scale is uniform and unskewed throughout. */
static bool foldable(const cJSON *layers, const layer_xf *x, const lt_time *tm)
{
    int drawn = 0;
    const cJSON *l;
    cJSON_ArrayForEach(l, layers)
    {
        if (!cJSON_IsObject(l))
            return false;
        const cJSON *ty = get(l, "ty"), *hd = get(l, "hd"), *td = get(l, "td"), *tt = get(l, "tt");
        if (get(l, "parent") || (tt && !(cJSON_IsNumber(tt) && tt->valuedouble == 0)) ||
            (td && !(cJSON_IsNumber(td) && td->valuedouble == 0)) || (ty && !cJSON_IsNumber(ty)))
            return false;
        if (cJSON_IsTrue(hd))
            continue;
        double tyd = ty ? ty->valuedouble : 4;
        if (!(tyd >= 0 && tyd <= 100))
            return false; /* not a layer type (and no int: the cast would be undefined) */
        int t = (int)tyd;
        if (t == 4 || t == 1)
            drawn++;
        else if (t != 3)
            return false;
    }
    for (int n = 0; n < tm->nframes && drawn == 1; n++) {
        double s[2], sk;
        lt_prop_eval(&x->s, tm->frame[n], s);
        lt_prop_eval(&x->sk, tm->frame[n], &sk);
        if (s[0] != s[1] || sk != 0)
            return false;
    }
    return drawn == 1;
}

/* Whether a precomp layer's masks are one add or subtract mask (inverted or not) whose
 * opacity is 100 and expansion 0: returns the matte type it is (1 alpha, 2 inverted) with
 * *src the shapes of an opaque fill of its path, else 0. */
static int precomp_mask(const cJSON *masks, cJSON **src)
{
    const cJSON *m = cJSON_GetArrayItem(masks, 0), *mode = get(m, "mode"), *pt = get(m, "pt");
    const cJSON *o = get(m, "o"), *x = get(m, "x");
    if (cJSON_GetArraySize(masks) != 1 || !cJSON_IsString(mode) || !cJSON_IsObject(pt))
        return 0;
    const cJSON *oa = get(o, "a"), *ok = get(o, "k"), *xa = get(x, "a"), *xk = get(x, "k");
    if ((o && !(cJSON_IsNumber(oa) && oa->valuedouble == 0 && cJSON_IsNumber(ok) &&
                ok->valuedouble == 100)) ||
        (x && !(cJSON_IsNumber(xa) && xa->valuedouble == 0 && cJSON_IsNumber(xk) &&
                xk->valuedouble == 0)))
        return 0;
    int tt = !strcmp(mode->valuestring, "a") ? 1 : !strcmp(mode->valuestring, "s") ? 2 : 0;
    if (tt && cJSON_IsTrue(get(m, "inv")))
        tt = 3 - tt;
    if (!tt)
        return 0;
    cJSON *shapes = cJSON_CreateArray(), *gr = cJSON_CreateObject(), *it = cJSON_CreateArray();
    cJSON *sh = cJSON_CreateObject(), *fl = cJSON_CreateObject(), *tr = cJSON_CreateObject();
    cJSON_AddStringToObject(sh, "ty", "sh");
    cJSON_AddItemToObject(sh, "ks", cJSON_Duplicate(pt, 1));
    cJSON_AddStringToObject(fl, "ty", "fl");
    cJSON *col = cJSON_AddObjectToObject(fl, "c"), *op = cJSON_AddObjectToObject(fl, "o");
    cJSON_AddNumberToObject(col, "a", 0);
    cJSON_AddItemToObject(col, "k", cJSON_CreateDoubleArray((const double[]){0, 0, 0, 1}, 4));
    cJSON_AddNumberToObject(op, "a", 0);
    cJSON_AddNumberToObject(op, "k", 100);
    cJSON_AddStringToObject(tr, "ty", "tr");
    cJSON_AddItemToArray(it, sh);
    cJSON_AddItemToArray(it, fl);
    cJSON_AddItemToArray(it, tr);
    cJSON_AddStringToObject(gr, "ty", "gr");
    cJSON_AddItemToObject(gr, "it", it);
    cJSON_AddItemToArray(shapes, gr);
    *src = shapes;
    return tt;
}

static const cJSON *find_asset(lt_ctx *c, const char *id)
{
    const cJSON *a;
    cJSON_ArrayForEach(a, c->assets)
    {
        const cJSON *aid = get(a, "id");
        if (cJSON_IsString(aid) && !strcmp(aid->valuestring, id))
            return a;
    }
    return NULL;
}

static void warn_unsupported(lt_ctx *c, const cJSON *l)
{
    const cJSON *ef = get(l, "ef");
    if (cJSON_IsArray(ef) && cJSON_GetArraySize(ef) > 0)
        lt_warn(c, LT_F_EFFECT, "layer effects are not supported and not drawn");
    const cJSON *ddd = get(l, "ddd");
    if (cJSON_IsNumber(ddd) && ddd->valuedouble != 0)
        lt_warn(c, LT_F_3D, "3D layers are drawn flat");
    const cJSON *ao = get(l, "ao");
    if (cJSON_IsNumber(ao) && ao->valuedouble != 0)
        lt_warn(c, LT_F_AUTO_ORIENT, "auto-orient along the motion path is not supported");
}

/* Layer i's matrix at frame f with its parents', in the composition's space. */
static sv_affine layer_matrix(const layer_info *L, const layer_xf *X, int i, double f)
{
    sv_affine m = sv_affine_identity();
    for (int k = i, d = 0; k >= 0 && d <= LT_MAX_DEPTH; k = L[k].parent, d++) {
        sv_affine local;
        lt_xf_eval(&X[k].a, &X[k].p, &X[k].s, &X[k].r, &X[k].sk, &X[k].sa, f, &local);
        m = sv_affine_mul(local, m);
    }
    return m;
}

/* The inverse of an affine map, or false when it is (nearly) singular: scaled
 * below 1/1000, a layer covers no pixel, and a matte carried into its space
 * would be beyond the core's coordinates. */
static bool invert(sv_affine m, sv_affine *out)
{
    double det = m.a * m.d - m.b * m.c;
    if (!(fabs(det) >= 1e-6))
        return false;
    sv_affine v = {m.d / det, -m.b / det, -m.c / det, m.a / det, 0, 0};
    v.e = -(v.a * m.e + v.c * m.f);
    v.f = -(v.b * m.e + v.d * m.f);
    *out = v;
    return true;
}

/*
 * to[n] = space[n]^-1 * from[n] for every sample. Where space[n] cannot be
 * inverted, the nearest sample's result stands in (what it maps is drawn
 * nowhere). Returns a malloc'd array, or NULL (error set).
 */
static sv_affine *carry(lt_ctx *c, const sv_affine *space, const sv_affine *from, int N)
{
    sv_affine *to = malloc((size_t)N * sizeof *to);
    bool *ok = malloc((size_t)N * sizeof *ok);
    if (!to || !ok || !lt_charge(c, 6.0 * N)) {
        free(to), free(ok);
        if (!c->failed)
            lt_fail(c, "out of memory");
        return NULL;
    }
    int good = -1;
    for (int n = 0; n < N; n++) {
        sv_affine inv;
        ok[n] = invert(space[n], &inv);
        if (ok[n]) {
            to[n] = sv_affine_mul(inv, from[n]);
            good = n;
        }
    }
    for (int n = N - 1, next = -1; n >= 0; n--) {
        if (ok[n])
            next = n;
        else
            to[n] = next >= 0 ? to[next] : good >= 0 ? to[good] : sv_affine_identity();
    }
    free(ok);
    return to;
}

/* Layer i's matrices (with its parents') at every sample. */
static sv_affine *layer_matrices(lt_ctx *c, const layer_info *L, const layer_xf *X, int i,
                                 const lt_time *tm)
{
    sv_affine *m = malloc((size_t)tm->nframes * sizeof *m);
    if (!m || !lt_charge(c, 6.0 * tm->nframes)) {
        free(m);
        if (!c->failed)
            lt_fail(c, "out of memory");
        return NULL;
    }
    for (int n = 0; n < tm->nframes; n++)
        m[n] = layer_matrix(L, X, i, tm->frame[n]);
    return m;
}

/*
 * Whether layer s can be a track matte's source as CSG: a shape layer
 * without masks whose opacity is 100 % while it is within its in and out
 * points (out of them the matted layer is hidden, as rlottie draws it).
 * Else warned (0).
 */
static int matte_source_ok(lt_ctx *c, const layer_info *L, const layer_xf *X, int s,
                           const lt_time *tm, double *ip, double *op)
{
    const cJSON *sj = L[s].j;
    double ty = 4;
    if (lt_num(c, sj, "ty", 0, 100, 4, &ty) || lt_num(c, sj, "ip", -1e7, 1e7, -1e7, ip) ||
        lt_num(c, sj, "op", -1e7, 1e7, 1e7, op))
        return -1;
    *ip = round(*ip), *op = round(*op); /* whole frames, as a layer's own (lt_layers) */
    const cJSON *masks = get(sj, "masksProperties");
    if ((int)ty != 4 || (cJSON_IsArray(masks) && cJSON_GetArraySize(masks) > 0)) {
        lt_warn(c, LT_F_MATTE, "a track matte whose source is not a shape layer, or has masks, is "
                "drawn unmatted");
        return 0;
    }
    for (int n = 0; n < tm->nframes; n++) {
        double o;
        lt_prop_eval(&X[s].o, tm->frame[n], &o);
        if (o < 100 && tm->frame[n] >= *ip && tm->frame[n] < *op) {
            lt_warn(c, LT_F_MATTE, "a track matte whose source layer fades is drawn unmatted");
            return 0;
        }
    }
    return 1;
}

/*
 * A matte (source shapes, type, and the source's space in this
 * composition's at every sample) over the regions of layer i: the source's
 * shapes are built again in layer i's space and become CSG operands of its
 * regions (lt_matte). Returns -1 on error, 1 when matted, 0 when warned.
 */
static int apply_matte(lt_ctx *c, const cJSON *shapes, int tt, const sv_affine *src_space,
                       const layer_info *L, const layer_xf *X, int i, const lt_time *tm,
                       cJSON *regions)
{
    sv_affine *mi = layer_matrices(c, L, X, i, tm);
    sv_affine *xf = mi ? carry(c, mi, src_space, tm->nframes) : NULL;
    free(mi);
    if (!xf)
        return -1;
    lt_time stm = *tm;
    stm.xf = xf;
    cJSON *src = cJSON_CreateArray();
    int rc = lt_shapes(c, shapes, &stm, src);
    free(xf);
    if (rc == 0)
        rc = lt_matte(c, tt, src, regions);
    cJSON_Delete(src);
    return rc;
}

/*
 * Layer i's own track matte (tt) from layer i - 1, rlottie's source: the
 * layer listed just before, drawn only as the matte. For a shape or solid
 * layer it is applied to its regions here; for a precomp layer it becomes
 * the context matte of the composition's layers (c->matte), carried into
 * the precomp's space. Layer i shows only while the source is within its
 * in and out points. Returns -1 on error, else 0.
 */
static int own_matte(lt_ctx *c, const layer_info *L, const layer_xf *X, int i, int tt,
                     const lt_time *tm, double *visible, cJSON *regions, lt_matte_ctx *inner)
{
    double ip, op;
    int ok = matte_source_ok(c, L, X, i - 1, tm, &ip, &op);
    if (ok <= 0)
        return ok;
    sv_affine *ms = layer_matrices(c, L, X, i - 1, tm);
    if (!ms)
        return -1;
    int rc;
    if (regions) {
        rc = apply_matte(c, get(L[i - 1].j, "shapes"), tt, ms, L, X, i, tm, regions);
        free(ms);
    } else {
        /* A precomp: the source in the precomp's space, for its layers. */
        sv_affine *mi = layer_matrices(c, L, X, i, tm);
        inner->xf = mi ? carry(c, mi, ms, tm->nframes) : NULL;
        free(mi);
        free(ms);
        inner->shapes = get(L[i - 1].j, "shapes");
        inner->tt = tt;
        rc = inner->xf ? 1 : -1;
    }
    if (rc == 1)
        for (int n = 0; n < tm->nframes; n++)
            if (!(tm->frame[n] >= ip && tm->frame[n] < op))
                visible[n] = 0;
    return rc < 0 ? -1 : 0;
}

int lt_layers(lt_ctx *c, const cJSON *layers, const lt_time *tm, int parent_cel)
{
    if (++c->depth > LT_MAX_DEPTH)
        return lt_fail(c, "precomps nested deeper than %d (or a precomp that contains itself)",
                       LT_MAX_DEPTH);
    if (!cJSON_IsArray(layers))
        return lt_fail(c, "\"layers\" is not an array");
    int n = cJSON_GetArraySize(layers);
    if (n > 10000)
        return lt_fail(c, "%d layers, more than 10000", n);
    layer_info *L = calloc((size_t)(n ? n : 1), sizeof *L);
    if (!L)
        return lt_fail(c, "out of memory");
    int i = 0;
    const cJSON *l;
    cJSON_ArrayForEach(l, layers)
    {
        if (!cJSON_IsObject(l)) {
            free(L);
            return lt_fail(c, "layer %d is not an object", i);
        }
        L[i].j = l;
        L[i].xf_cel = -1;
        L[i].parent = -1;
        if (lt_num(c, l, "ind", -1e9, 1e9, -1e10 - i, &L[i].ind)) {
            free(L);
            return -1;
        }
        i++;
    }
    for (i = 0; i < n; i++) {
        const cJSON *pj = get(L[i].j, "parent");
        if (!cJSON_IsNumber(pj))
            continue;
        for (int k = 0; k < n; k++)
            if (L[k].ind == pj->valuedouble && k != i)
                L[i].parent = k;
        if (L[i].parent >= 0)
            L[L[i].parent].is_parent = true;
    }
    /* Parent chains: bounded, acyclic. */
    for (i = 0; i < n; i++) {
        int d = 0;
        for (int k = L[i].parent; k >= 0; k = L[k].parent)
            if (++d > LT_MAX_DEPTH) {
                free(L);
                return lt_fail(c, "layer %d: parent chain longer than %d or a cycle of parents", i,
                               LT_MAX_DEPTH);
            }
    }
    int rc = 0;
    double *visible = malloc((size_t)tm->nframes * sizeof *visible);
    if (!visible) {
        free(L);
        return lt_fail(c, "out of memory");
    }
    layer_xf *X = calloc((size_t)(n ? n : 1), sizeof *X);
    if (!X) {
        free(L), free(visible);
        return lt_fail(c, "out of memory");
    }
    for (i = 0; i < n && rc == 0; i++)
        rc = parse_layer_xf(c, get(L[i].j, "ks"), &X[i]);
    /* Group cels of parents, parents before children so indices are known. */
    for (int pass = 0; pass <= LT_MAX_DEPTH && rc == 0; pass++)
        for (i = 0; i < n && rc == 0; i++) {
            if (!L[i].is_parent || L[i].xf_cel >= 0)
                continue;
            int p = L[i].parent;
            if (p >= 0 && L[p].xf_cel < 0)
                continue;
            char name[64];
            snprintf(name, sizeof name, "layer %.0f (parent)", L[i].ind);
            L[i].xf_cel = add_cel(c, name, NULL, &X[i], true, false, NULL, tm,
                                  p >= 0 ? L[p].xf_cel : parent_cel);
            if (L[i].xf_cel < 0)
                rc = -1;
        }
    for (i = 0; i < n && rc == 0; i++) {
        const cJSON *lj = L[i].j;
        const cJSON *hd = get(lj, "hd"), *td = get(lj, "td");
        if (cJSON_IsTrue(hd) || (cJSON_IsNumber(td) && td->valuedouble != 0))
            continue; /* hidden, or a matte source (not drawn itself) */
        double ty, ip, op, st, sr;
        if (lt_num(c, lj, "ty", 0, 100, 4, &ty) || lt_num(c, lj, "ip", -1e7, 1e7, -1e7, &ip) ||
            lt_num(c, lj, "op", -1e7, 1e7, 1e7, &op) || lt_num(c, lj, "st", -1e7, 1e7, 0, &st) ||
            lt_num(c, lj, "sr", -1e4, 1e4, 1, &sr)) {
            rc = -1;
            break;
        }
        /* rlottie keeps a layer's in and out points as whole frames, rounded
         * (1667-firework.json's layers start at 4.00000016: shown from frame 4). */
        ip = round(ip), op = round(op);
        warn_unsupported(c, lj);
        const cJSON *ttj = get(lj, "tt");
        double ttd = cJSON_IsNumber(ttj) ? ttj->valuedouble : 0;
        /* Only a small value becomes an int (the cast of 1e48 or NaN is undefined); others are -1. */
        int ttv = ttd >= -100 && ttd <= 100 ? (int)ttd : -1;
        if (ttv != 0 && !(ttv >= 1 && ttv <= 4 && i > 0))
            lt_warn(c, LT_F_MATTE, "track matte type %g without a source layer is drawn unmatted",
                    ttd);
        bool any = false;
        for (int k = 0; k < tm->nframes; k++) {
            visible[k] = tm->frame[k] >= ip && tm->frame[k] < op ? 1 : 0;
            any = any || visible[k] != 0;
        }
        if (!any)
            continue;
        const cJSON *bm = get(lj, "bm");
        if (cJSON_IsNumber(bm) && bm->valuedouble != 0)
            lt_warn(c, LT_F_BLEND, "layer blend modes are drawn as normal (rlottie does too)");
        int p = L[i].parent;
        int group = L[i].xf_cel >= 0 ? L[i].xf_cel : p >= 0 ? L[p].xf_cel : parent_cel;
        bool own_xf = L[i].xf_cel < 0;
        char name[64];
        snprintf(name, sizeof name, "layer %.0f", L[i].ind);
        const cJSON *masks = get(lj, "masksProperties");
        int t = (int)ty;
        if (t == 4 || t == 1) {
            cJSON *regions = cJSON_CreateArray();
            double *lf = malloc((size_t)tm->nframes * sizeof *lf);
            if (!lf) {
                rc = lt_fail(c, "out of memory");
                cJSON_Delete(regions);
                break;
            }
            for (int k = 0; k < tm->nframes; k++)
                lf[k] = tm->frame[k];
            lt_time ltm = {tm->nframes, lf, tm->f0, tm->fscale, NULL};
            rc = t == 4 ? lt_shapes(c, get(lj, "shapes"), &ltm, regions) : lt_solid(c, lj, &ltm, regions);
            free(lf);
            if (rc == 0 && cJSON_IsArray(masks) && cJSON_GetArraySize(masks) > 0)
                rc = lt_masks(c, masks, tm, regions);
            if (rc == 0 && ttv >= 1 && ttv <= 4 && i > 0)
                rc = own_matte(c, L, X, i, ttv, tm, visible, regions, NULL);
            if (rc == 0 && c->matte && c->matte->shapes &&
                apply_matte(c, c->matte->shapes, c->matte->tt, c->matte->xf, L, X, i, tm,
                            regions) < 0)
                rc = -1;
            if (rc == 0 && cJSON_GetArraySize(regions) > 0)
                rc = add_content(c, name, regions, &X[i], own_xf, visible, tm, group);
            else
                cJSON_Delete(regions);
        } else if (t == 0) {
            const cJSON *ref = get(lj, "refId");
            const cJSON *asset = cJSON_IsString(ref) ? find_asset(c, ref->valuestring) : NULL;
            if (!asset || !cJSON_IsArray(get(asset, "layers"))) {
                lt_warn(c, LT_F_OTHER, "a precomp layer names no composition with layers");
                continue;
            }
            /* The matte its layers take: its own, or the one it is in, carried into its
             * space (one level: a matted precomp within a matted precomp is warned). */
            lt_matte_ctx inner = {NULL, 0, NULL};
            const lt_matte_ctx *outer = c->matte;
            if (ttv >= 1 && ttv <= 4 && i > 0 && outer && outer->shapes)
                lt_warn(c, LT_F_MATTE, "a matted precomp within a matted precomp is drawn with "
                        "the outer matte only");
            else if (ttv >= 1 && ttv <= 4 && i > 0 &&
                     own_matte(c, L, X, i, ttv, tm, visible, NULL, &inner) < 0) {
                rc = -1;
                break;
            }
            if (!inner.shapes && outer && outer->shapes) {
                sv_affine *mi = layer_matrices(c, L, X, i, tm);
                inner = *outer;
                inner.xf = mi ? carry(c, mi, outer->xf, tm->nframes) : NULL;
                free(mi);
                if (!inner.xf) {
                    rc = -1;
                    break;
                }
            }
            /* A mask on the precomp: one add or subtract mask at full opacity is a matte
             * of its layers, the mask's path an opaque source in the precomp's space. */
            cJSON *mask_src = NULL;
            if (cJSON_IsArray(masks) && cJSON_GetArraySize(masks) > 0) {
                int mtt = inner.shapes ? 0 : precomp_mask(masks, &mask_src);
                sv_affine *id = mtt ? malloc((size_t)tm->nframes * sizeof *id) : NULL;
                if (id) {
                    for (int k = 0; k < tm->nframes; k++)
                        id[k] = sv_affine_identity();
                    inner = (lt_matte_ctx){mask_src, mtt, id};
                } else {
                    cJSON_Delete(mask_src);
                    mask_src = NULL;
                    lt_warn(c, LT_F_MASK, "masks on precomp layers are drawn only as one add or "
                            "subtract mask at full opacity, not under a track matte");
                }
            }
            /* Folded into its one layer, or a group cel over its layers. */
            bool fold = own_xf && !inner.shapes && !c->fold && ttv == 0 &&
                        foldable(get(asset, "layers"), &X[i], tm);
            struct lt_fold fd = {&X[i], tm, visible, c->depth + 1, group};
            int g = fold ? group : add_cel(c, name, NULL, &X[i], own_xf, true, visible, tm, group);
            /* The composition's own frames at each sample. */
            bool failed = !fold && g < 0;
            double *fr = failed ? NULL : malloc((size_t)tm->nframes * sizeof *fr);
            if (!fr) {
                free(inner.xf);
                cJSON_Delete(mask_src);
                rc = failed ? -1 : lt_fail(c, "out of memory");
                break;
            }
            lt_prop remap;
            const cJSON *tmj = get(lj, "tm");
            rc = lt_prop_parse(c, tmj, 1, (const double[]){0}, "time remap", &remap);
            for (int k = 0; k < tm->nframes && rc == 0; k++) {
                if (tmj) {
                    double secs;
                    lt_prop_eval(&remap, tm->frame[k], &secs);
                    fr[k] = floor(secs * c->fr);
                } else {
                    fr[k] = trunc((tm->frame[k] - trunc(st)) / (sr != 0 ? sr : 1));
                }
            }
            lt_prop_free(&remap);
            lt_time sub = {tm->nframes, fr, (tm->f0 - st) / (sr != 0 ? sr : 1),
                           tm->fscale / (sr != 0 ? sr : 1), NULL};
            c->matte = inner.shapes ? &inner : NULL;
            c->fold = fold ? &fd : NULL;
            if (rc == 0)
                rc = lt_layers(c, get(asset, "layers"), &sub, g);
            c->fold = NULL;
            c->matte = outer;
            free(inner.xf);
            cJSON_Delete(mask_src);
            free(fr);
        } else if (t == 3) {
            /* A null layer draws nothing; as a parent it is a group already. */
        } else if (t == 2) {
            lt_warn(c, LT_F_IMAGE, "image layers are not supported and not drawn");
        } else if (t == 5) {
            lt_warn(c, LT_F_TEXT, "text layers are not supported and not drawn");
        } else {
            lt_warn(c, LT_F_OTHER, "layer type %d is not supported and not drawn", t);
        }
    }
    for (i = 0; i < n; i++)
        free_layer_xf(&X[i]);
    free(X);
    free(visible);
    free(L);
    c->depth--;
    return rc;
}
