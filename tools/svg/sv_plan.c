/*
 * sv_plan.c - how each region of the IR is drawn, decided once for both
 * back ends, within the capacities of the default scene store.
 *
 * After packing, every region is drawn one of three ways (sv_draw):
 *
 *  - a gradient becomes the core's paint functions when sv_gradient_funcs
 *    can express it in its cel's space (sv_gradfn.c). A scene holds
 *    CS_CFG_MAX_FUNCS functions; beyond that the smallest gradient regions
 *    fall back first, since they show the least.
 *  - otherwise its solid bands of exact geometry (sv_bands.c), and when
 *    the scene's points run out, the regions whose bands cost the most
 *    points fall back to their average colour.
 *
 * A region inside clip paths that are not one convex polygon (those are cut
 * into the geometry at import) is intersected with them by the core's CSG:
 * the region's contours and each clip's parts become operands, and the
 * program is region AND (part OR part ...) AND ... for each clip of the
 * nesting chain, innermost first, as many as CS_CFG_MAX_OPERANDS and
 * CS_CFG_MAX_CSG allow.
 *
 * The core applies one fill rule to every operand. When the region and its
 * clips agree (the usual case: nonzero everywhere), that rule is used; an
 * operand of one simple contour does not care (it winds at most once), but
 * one that crosses itself does (a star: its centre winds twice). Otherwise
 * the program runs under nonzero and each evenodd operand of several
 * contours is split into one operand per contour joined by XOR: parity is
 * additive, and a simple contour's nonzero inside is its parity.
 *
 * Every fallback is warned, naming the element.
 */
#include <limits.h>
#include <math.h>

#include "sv_gradient.h"
#include "sv_internal.h"

/* ------------------------------------------------------------------ CSG */

typedef struct group {
    const sv_contour *c;
    int n;
    int rule;
} group;

static bool push(sv_csg *o, int token)
{
    if (o->nrpn >= CS_CFG_MAX_CSG)
        return false;
    o->rpn[o->nrpn++] = token;
    return true;
}

static void add_contour(sv_csg *o, const sv_contour *c, int op, bool own)
{
    o->contours = sv_xrealloc(o->contours, (size_t)(o->ncontours + 1) * sizeof *o->contours);
    o->ops = sv_xrealloc(o->ops, (size_t)(o->ncontours + 1) * sizeof *o->ops);
    o->contours[o->ncontours] = c;
    o->ops[o->ncontours++] = op;
    if (own)
        o->nown++;
}

/* One group's expression: one operand, or its contours XORed. */
static bool emit_group(sv_csg *o, const group *g, bool split, bool own)
{
    if (!split || g->n <= 1) {
        if (o->nops >= CS_CFG_MAX_OPERANDS)
            return false;
        int op = o->nops++;
        for (int i = 0; i < g->n; i++)
            add_contour(o, &g->c[i], op, own);
        return push(o, op);
    }
    for (int i = 0; i < g->n; i++) {
        if (o->nops >= CS_CFG_MAX_OPERANDS)
            return false;
        int op = o->nops++;
        add_contour(o, &g->c[i], op, own);
        if (!push(o, op) || (i > 0 && !push(o, CS_CSG_XOR)))
            return false;
    }
    return true;
}

static bool edges_cross(sv_pt a, sv_pt b, sv_pt c, sv_pt d)
{
    double d1 = sv_cross(sv_sub(b, a), sv_sub(c, a)), d2 = sv_cross(sv_sub(b, a), sv_sub(d, a));
    double d3 = sv_cross(sv_sub(d, c), sv_sub(a, c)), d4 = sv_cross(sv_sub(d, c), sv_sub(b, c));
    if (d1 == 0 && d2 == 0) /* collinear: overlapping counts as crossing */
        return fmax(a.x, b.x) >= fmin(c.x, d.x) && fmax(c.x, d.x) >= fmin(a.x, b.x) &&
               fmax(a.y, b.y) >= fmin(c.y, d.y) && fmax(c.y, d.y) >= fmin(a.y, b.y);
    return ((d1 <= 0 && d2 >= 0) || (d1 >= 0 && d2 <= 0)) &&
           ((d3 <= 0 && d4 >= 0) || (d3 >= 0 && d4 <= 0));
}

/*
 * Whether a contour's control polygon is simple: for polygons exactly
 * whether the contour is; for curves a close stand-in (a self-crossing curve
 * crosses its control polygon too, in any drawing seen). Long contours are
 * taken as not simple, which only costs an operand's rule its freedom.
 */
static bool contour_simple(const sv_contour *c)
{
    enum { MAX_EDGES = 256 };
    int n = c->count;
    if (n > MAX_EDGES)
        return false;
    sv_pt v[MAX_EDGES];
    for (int i = 0; i < n; i++)
        v[i] = sv_pt_make(c->pts[3 * i] / c->pts[3 * i + 2], c->pts[3 * i + 1] / c->pts[3 * i + 2]);
    for (int i = 0; i < n; i++)
        for (int j = i + 2; j < n; j++) {
            if (i == 0 && j == n - 1)
                continue; /* they share v[0] */
            if (edges_cross(v[i], v[(i + 1) % n], v[j], v[(j + 1) % n]))
                return false;
        }
    return true;
}

/* Whether an operand's inside depends on the fill rule. */
static bool rule_matters(const sv_contour *c, int n)
{
    return n > 1 || (n == 1 && !contour_simple(c));
}

void sv_csg_free(sv_csg *o)
{
    free(o->contours);
    free(o->ops);
    memset(o, 0, sizeof *o);
}

/* The rule the operands of `nclips` clips of the chain from ci ask for (and their parts' own). */
static void chain_rules(const sv_doc *doc, int ci, int nclips, int *rule, bool *mixed)
{
    for (int k = 0; k < nclips && ci >= 0; k++, ci = doc->clips[ci].parent)
        for (int p = 0; p < doc->clips[ci].nparts; p++) {
            const struct sv_clip_part *part = &doc->clips[ci].parts[p];
            if (part->clip >= 0) /* earlier clips: this ends */
                chain_rules(doc, part->clip, INT_MAX, rule, mixed);
            if (!rule_matters(part->contours, part->ncontours))
                continue;
            if (*rule < 0)
                *rule = part->fill_rule;
            else if (*rule != part->fill_rule)
                *mixed = true;
        }
}

/*
 * `nclips` clips of the chain from ci, each intersected with what is on the
 * stack: (part [AND its own chain]) OR part ..., AND.
 */
static bool emit_chain(sv_csg *o, const sv_doc *doc, int ci, int nclips, bool mixed)
{
    bool ok = true;
    for (int k = 0; ok && k < nclips && ci >= 0; k++, ci = doc->clips[ci].parent) {
        const sv_clip *clip = &doc->clips[ci];
        if (clip->nparts == 0) { /* an empty clip path: an operand without contours */
            group none = {NULL, 0, o->rule};
            ok = emit_group(o, &none, false, false);
        }
        for (int p = 0; ok && p < clip->nparts; p++) {
            const struct sv_clip_part *part = &clip->parts[p];
            group g = {part->contours, part->ncontours, part->fill_rule};
            ok = emit_group(o, &g, mixed && g.rule == CS_FILL_EVENODD, false) &&
                 (part->clip < 0 || emit_chain(o, doc, part->clip, INT_MAX, mixed)) &&
                 (p == 0 || push(o, CS_CSG_UNION));
        }
        ok = ok && push(o, CS_CSG_INTERSECT);
    }
    return ok;
}

bool sv_csg_build(const sv_doc *doc, const sv_region *r, int nclips, sv_csg *o)
{
    memset(o, 0, sizeof *o);
    /* the rule: the one every operand whose rule matters shares, else nonzero */
    int rule = -1;
    bool mixed = false;
    group rg = {r->contours, r->ncontours, r->fill_rule};
    if (rule_matters(rg.c, rg.n))
        rule = rg.rule;
    chain_rules(doc, r->clip, nclips, &rule, &mixed);
    o->rule = mixed ? CS_FILL_NONZERO : rule >= 0 ? rule : r->fill_rule;
    bool ok = emit_group(o, &rg, mixed && rg.rule == CS_FILL_EVENODD, true) &&
              emit_chain(o, doc, r->clip, nclips, mixed);
    if (!ok)
        sv_csg_free(o);
    return ok;
}

int sv_clip_chain_length(const sv_doc *doc, const sv_region *r)
{
    int n = 0;
    for (int ci = r->clip; ci >= 0 && n < 1000; ci = doc->clips[ci].parent)
        n++;
    return n;
}

/* --------------------------------------------------------------- costs */

typedef struct cost {
    size_t points, regions, contours;
} cost;

static void add_chain_cost(cost *c, const sv_doc *doc, int ci, int nclips)
{
    for (int k = 0; k < nclips && ci >= 0; k++, ci = doc->clips[ci].parent)
        for (int p = 0; p < doc->clips[ci].nparts; p++) {
            const struct sv_clip_part *part = &doc->clips[ci].parts[p];
            for (int i = 0; i < part->ncontours; i++) {
                c->contours++;
                c->points += (size_t)part->contours[i].count;
            }
            if (part->clip >= 0)
                add_chain_cost(c, doc, part->clip, INT_MAX);
        }
}

static void add_cost(cost *c, const sv_doc *doc, const sv_region *geo, int nclips)
{
    c->regions++;
    c->contours += (size_t)geo->ncontours;
    for (int k = 0; k < geo->ncontours; k++)
        c->points += (size_t)geo->contours[k].count;
    add_chain_cost(c, doc, geo->clip, nclips);
}

static cost region_cost(const sv_doc *doc, const sv_region *r, sv_draw draw)
{
    cost c = {0, 0, 0};
    if (draw == SV_DRAW_BANDS)
        for (int b = 0; b < r->nbands; b++)
            add_cost(&c, doc, &r->bands[b], r->csg_clips);
    else
        add_cost(&c, doc, r, r->csg_clips);
    return c;
}

static bool over(cost c)
{
    return c.points > CS_CFG_MAX_POINTS || c.regions > CS_CFG_MAX_REGIONS ||
           c.contours > CS_CFG_MAX_CONTOURS;
}

/* ---------------------------------------------------------------- plan */

static sv_affine cel_space(const sv_cel *cel)
{
    return cel->has_transform ? cel->transform : sv_affine_identity();
}

static int func_count(const sv_doc *doc, const sv_cel *cel, const sv_region *r)
{
    sv_gradfn fn;
    if (sv_gradient_funcs(&doc->gradients[r->paint.gradient], r->paint.gradient_opacity,
                          cel_space(cel), &fn) != SV_FN_OK)
        return 0;
    return fn.has_pigment + fn.has_beta;
}

/* A gradient region that cannot be functions: its bands, or one colour. */
static void fall_back(sv_doc *doc, sv_region *r, const char *why)
{
    r->draw = r->nbands > 0 ? SV_DRAW_BANDS : SV_DRAW_SOLID;
    if (r->nbands > 0)
        sv_doc_warn(doc, "%s: gradient approximated by %d solid bands (%s)", r->source, r->nbands,
                    why);
    else
        sv_doc_warn(doc, "%s: gradient approximated by one colour (%s)", r->source, why);
}

typedef struct ref {
    sv_region *r;
    const sv_cel *cel;
    double key;
} ref;

static int by_key(const void *a, const void *b)
{
    double x = ((const ref *)a)->key, y = ((const ref *)b)->key;
    return x < y ? -1 : x > y;
}

void sv_doc_plan(sv_doc *doc)
{
    size_t nreg = sv_doc_region_count(doc), nr = 0;
    ref *refs = sv_xrealloc(NULL, (nreg ? nreg : 1) * sizeof *refs);
    int funcs = 0;
    /* gradients: functions where the core can draw them */
    for (int c = 0; c < doc->ncels; c++)
        for (int i = 0; i < doc->cels[c].nregions; i++) {
            sv_region *r = &doc->cels[c].regions[i];
            r->draw = SV_DRAW_SOLID;
            r->csg_clips = 0;
            if (r->paint.gradient < 0)
                continue;
            const sv_gradient *g = &doc->gradients[r->paint.gradient];
            sv_gradfn fn;
            sv_fn_status st = sv_gradient_funcs(g, r->paint.gradient_opacity,
                                                cel_space(&doc->cels[c]), &fn);
            if (st == SV_FN_OK) {
                r->draw = SV_DRAW_FUNC;
                funcs += fn.has_pigment + fn.has_beta;
                double w = r->bbox[2] - r->bbox[0], h = r->bbox[3] - r->bbox[1];
                refs[nr++] = (ref){r, &doc->cels[c], w * h};
            } else if (st == SV_FN_SOLID) { /* exactly one colour */
                memcpy(r->paint.pigment, fn.pigment_const, sizeof fn.pigment_const);
                r->paint.beta = fn.beta_const;
            } else {
                fall_back(doc, r, sv_fn_status_str(st));
            }
        }
    /* too many functions: the smallest regions give theirs up first */
    qsort(refs, nr, sizeof *refs, by_key);
    for (size_t k = 0; k < nr && funcs > CS_CFG_MAX_FUNCS; k++) {
        funcs -= func_count(doc, refs[k].cel, refs[k].r);
        fall_back(doc, refs[k].r,
                  "the scene's " SV_STR(CS_CFG_MAX_FUNCS) " paint functions are taken");
    }
    /* clip paths: as many of the chain as the CSG capacity takes */
    for (int c = 0; c < doc->ncels; c++)
        for (int i = 0; i < doc->cels[c].nregions; i++) {
            sv_region *r = &doc->cels[c].regions[i];
            int chain = sv_clip_chain_length(doc, r), k = chain;
            for (; k > 0; k--) {
                sv_csg o;
                bool ok = sv_csg_build(doc, r, k, &o);
                sv_csg_free(&o);
                for (int b = 0; ok && r->draw == SV_DRAW_BANDS && b < r->nbands; b++) {
                    ok = sv_csg_build(doc, &r->bands[b], k, &o);
                    sv_csg_free(&o);
                }
                if (ok)
                    break;
            }
            r->csg_clips = k;
            if (k == 0 && chain > 0)
                sv_doc_warn(doc, "%s: clip path beyond the core's CSG capacity (%d operands, %d "
                                 "tokens), drawn unclipped",
                            r->source, CS_CFG_MAX_OPERANDS, CS_CFG_MAX_CSG);
            else if (k < chain)
                sv_doc_warn(doc, "%s: %d of %d nested clip paths applied, the outer ones beyond "
                                 "the core's CSG capacity (%d operands, %d tokens)",
                            r->source, k, chain, CS_CFG_MAX_OPERANDS, CS_CFG_MAX_CSG);
        }
    /* the scene store: bands that cost the most points fall back first */
    cost total = {0, 0, 0};
    nr = 0;
    for (int c = 0; c < doc->ncels; c++)
        for (int i = 0; i < doc->cels[c].nregions; i++) {
            sv_region *r = &doc->cels[c].regions[i];
            cost rc = region_cost(doc, r, r->draw);
            total.points += rc.points;
            total.regions += rc.regions;
            total.contours += rc.contours;
            if (r->draw == SV_DRAW_BANDS)
                refs[nr++] = (ref){r, &doc->cels[c], -(double)rc.points};
        }
    qsort(refs, nr, sizeof *refs, by_key);
    for (size_t k = 0; k < nr && over(total); k++) {
        sv_region *r = refs[k].r;
        cost was = region_cost(doc, r, SV_DRAW_BANDS), now = region_cost(doc, r, SV_DRAW_SOLID);
        r->draw = SV_DRAW_SOLID;
        total.points = total.points - was.points + now.points;
        total.regions = total.regions - was.regions + now.regions;
        total.contours = total.contours - was.contours + now.contours;
        sv_doc_warn(doc, "%s: gradient approximated by one colour (its bands exceed the scene's "
                         "capacity)",
                    r->source);
    }
    free(refs);
}
