/*
 * sv_emit.c - the IR's two back ends: a cs_scene built through the core's
 * own validating cs_scene_* calls, and the scene JSON of DESIGN.md and
 * docs/SCENE.md written with cJSON.
 *
 * Both draw what sv_doc_plan decided for each region, through one
 * description per drawn region (`shape`): its geometry (the region, or one
 * of its gradient bands), its paint as constants and paint functions, its
 * CSG program with the clip contours, and the map from canvas units to its
 * cel's space. The two writers only differ in where that goes, so celsim
 * loading the JSON builds the same scene as sv_doc_to_scene (test_svg
 * checks it).
 */
#include <cjson/cJSON.h>
#include <math.h>

#include "sv_gradient.h"
#include "sv_internal.h"

/* One drawn region, in the IR's sRGB-encoded colours. */
typedef struct shape {
    const sv_region *geo;
    int rule;
    double pigment[3], medium[3], beta;
    bool has_func[3]; /* per cs_paint_field */
    cs_paint_func func[3];
    bool has_csg;
    sv_csg csg;
    bool map; /* contours (and clip contours) go through inv */
    sv_affine inv;
} shape;

static void shape_init(const sv_doc *doc, const sv_cel *cel, const sv_region *whole,
                       const sv_region *geo, bool func, shape *s)
{
    memset(s, 0, sizeof *s);
    s->geo = geo;
    s->rule = geo->fill_rule;
    memcpy(s->pigment, geo->paint.pigment, sizeof s->pigment);
    memcpy(s->medium, geo->paint.medium, sizeof s->medium);
    s->beta = geo->paint.beta;
    sv_affine id = sv_affine_identity(), space = cel->has_transform ? cel->transform : id;
    if (func) {
        sv_gradfn fn;
        if (sv_gradient_funcs(&doc->gradients[whole->paint.gradient],
                              whole->paint.gradient_opacity, space, &fn) == SV_FN_OK) {
            s->has_func[CS_FIELD_PIGMENT] = fn.has_pigment;
            s->func[CS_FIELD_PIGMENT] = fn.pigment;
            s->has_func[CS_FIELD_BETA] = fn.has_beta;
            s->func[CS_FIELD_BETA] = fn.beta;
            /* the constants of the fields that stay constant (and valid
             * placeholders for the others) */
            for (int k = 0; k < 3; k++)
                s->pigment[k] = fn.has_pigment ? fn.pigment.stops[0].value[k] : fn.pigment_const[k];
            s->beta = fn.has_beta ? fn.beta.stops[0].value[0] : fn.beta_const;
            s->medium[0] = s->medium[1] = s->medium[2] = 1;
        }
    }
    if (whole->csg_clips > 0 && sv_csg_build(doc, geo, whole->csg_clips, &s->csg)) {
        s->has_csg = true;
        s->rule = s->csg.rule;
    }
    s->map = cel->has_transform && sv_affine_invert(cel->transform, &s->inv);
}

static int shape_ncontours(const shape *s)
{
    return s->has_csg ? s->csg.ncontours : s->geo->ncontours;
}

static const sv_contour *shape_contour(const shape *s, int i, int *op)
{
    *op = s->has_csg ? s->csg.ops[i] : 0;
    return s->has_csg ? s->csg.contours[i] : &s->geo->contours[i];
}

static sv_pt shape_point(const shape *s, const sv_contour *c, int i)
{
    sv_pt p = {c->pts[3 * i], c->pts[3 * i + 1]};
    return s->map ? sv_affine_apply(s->inv, p) : p;
}

/*
 * The shapes of one region, in the order they go into the cel: the region,
 * or its bands. `average` draws gradients in their average colour.
 */
typedef void (*shape_fn)(void *ctx, const shape *s);

static void region_shapes(const sv_doc *doc, const sv_cel *cel, const sv_region *r, bool average,
                          shape_fn fn, void *ctx)
{
    sv_draw draw = average ? SV_DRAW_SOLID : r->draw;
    int n = draw == SV_DRAW_BANDS ? r->nbands : 1;
    for (int b = 0; b < n; b++) {
        shape s;
        shape_init(doc, cel, r, draw == SV_DRAW_BANDS ? &r->bands[b] : r, draw == SV_DRAW_FUNC,
                   &s);
        fn(ctx, &s);
        sv_csg_free(&s.csg);
    }
}

/* ------------------------------------------------------------ cs_scene */

typedef struct emitter {
    cs_scene *scene;
    cs_point *pts;
    float *iv;
    size_t cap;
    cs_status st;
    cs_error e;
} emitter;

/* The IR's sRGB-encoded colours to the core's linear light. */
static float lin(double v)
{
    return (float)sv_srgb_to_linear(v);
}

static void add_shape(void *ctx, const shape *s)
{
    emitter *em = ctx;
    if (em->st != CS_OK)
        return;
    cs_paint p;
    for (int k = 0; k < 3; k++) {
        p.pigment[k] = lin(s->pigment[k]);
        p.medium[k] = lin(s->medium[k]);
    }
    p.beta = (float)s->beta;
    cs_status st = cs_scene_add_region(em->scene, (cs_fill_rule)s->rule, &p, &em->e);
    for (int f = 0; st == CS_OK && f < 3; f++) {
        if (!s->has_func[f])
            continue;
        cs_paint_func fn = s->func[f];
        if (f != CS_FIELD_BETA)
            for (int i = 0; i < fn.stop_count; i++)
                for (int k = 0; k < 3; k++)
                    fn.stops[i].value[k] = lin(fn.stops[i].value[k]);
        st = cs_scene_set_region_func(em->scene, (cs_paint_field)f, &fn, &em->e);
    }
    int nc = shape_ncontours(s);
    for (int k = 0; st == CS_OK && k < nc; k++) {
        int op;
        const sv_contour *ct = shape_contour(s, k, &op);
        if ((size_t)ct->count > em->cap) {
            em->cap = (size_t)ct->count;
            em->pts = sv_xrealloc(em->pts, em->cap * sizeof *em->pts);
            em->iv = sv_xrealloc(em->iv, em->cap * sizeof *em->iv);
        }
        for (int i = 0; i < ct->count; i++) {
            sv_pt q = shape_point(s, ct, i);
            em->pts[i].x = (float)q.x;
            em->pts[i].y = (float)q.y;
            em->pts[i].w = (float)ct->pts[3 * i + 2];
            em->iv[i] = (float)ct->intervals[i];
        }
        st = cs_scene_add_contour(em->scene, ct->degree, ct->count, em->pts, em->iv, &em->e);
        if (st == CS_OK && s->has_csg && op != 0)
            st = cs_scene_set_contour_operand(em->scene, op, &em->e);
    }
    if (st == CS_OK && s->has_csg)
        st = cs_scene_set_region_csg(em->scene, s->csg.rpn, s->csg.nrpn, &em->e);
    em->st = st;
}

static cs_affine cel_affine(const sv_cel *cel)
{
    sv_affine m = cel->has_transform ? cel->transform : sv_affine_identity();
    cs_affine a = {(float)m.a, (float)m.b, (float)m.c, (float)m.d, (float)m.e, (float)m.f};
    return a;
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
    emitter em = {scene, NULL, NULL, 0, CS_OK, {0}};
    if (o.has_background) {
        float bg[3];
        for (int k = 0; k < 3; k++)
            bg[k] = lin(o.background[k]);
        cs_scene_set_background(scene, bg);
    }
    int rc = 0;
    for (int c = 0; c < doc->ncels && rc == 0; c++) {
        const sv_cel *cel = &doc->cels[c];
        cs_affine m = cel_affine(cel);
        cs_error e;
        st = cs_scene_add_cel(scene, &m, NULL, NULL, &e);
        if (st != CS_OK) {
            snprintf(err, errlen, "cel %d of %d: %s", c, doc->ncels, cs_status_str(st));
            rc = -1;
            break;
        }
        for (int r = 0; r < cel->nregions && rc == 0; r++) {
            const sv_region *reg = &cel->regions[r];
            region_shapes(doc, cel, reg, o.gradient_average, add_shape, &em);
            if (em.st != CS_OK) {
                snprintf(err, errlen, "%s (cel %d region %d, item %d): %s", reg->source, c, r,
                         (int)em.e.item, cs_status_str(em.st));
                rc = -1;
            }
        }
    }
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

/* A paint function in the docs/SCENE.md syntax; colour stops are sRGB. */
static cJSON *func_json(const cs_paint_func *f, bool scalar)
{
    cJSON *o = cJSON_CreateObject();
    cJSON *g = cJSON_CreateArray();
    int ng = f->kind == CS_FUNC_LINEAR ? 4 : 5;
    for (int i = 0; i < ng; i++)
        cJSON_AddItemToArray(g, num(f->geom[i]));
    cJSON_AddItemToObject(o, f->kind == CS_FUNC_LINEAR ? "linear" : "radial", g);
    cJSON *stops = cJSON_AddArrayToObject(o, "stops");
    for (int i = 0; i < f->stop_count; i++) {
        cJSON *st = cJSON_CreateArray();
        cJSON_AddItemToArray(st, num(f->stops[i].offset));
        if (scalar) {
            cJSON_AddItemToArray(st, num(f->stops[i].value[0]));
        } else {
            double c[3] = {f->stops[i].value[0], f->stops[i].value[1], f->stops[i].value[2]};
            cJSON_AddItemToArray(st, rgb_json(c));
        }
        cJSON_AddItemToArray(stops, st);
    }
    if (f->spread != CS_SPREAD_PAD)
        cJSON_AddStringToObject(o, "spread", f->spread == CS_SPREAD_REFLECT ? "reflect" : "repeat");
    return o;
}

static cJSON *paint_json(const shape *s)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddItemToObject(o, "pigment",
                          s->has_func[CS_FIELD_PIGMENT] ? func_json(&s->func[CS_FIELD_PIGMENT], false)
                                                        : rgb_json(s->pigment));
    cJSON_AddItemToObject(o, "medium",
                          s->has_func[CS_FIELD_MEDIUM] ? func_json(&s->func[CS_FIELD_MEDIUM], false)
                                                       : rgb_json(s->medium));
    cJSON_AddItemToObject(o, "beta", s->has_func[CS_FIELD_BETA]
                                         ? func_json(&s->func[CS_FIELD_BETA], true)
                                         : num(s->beta));
    return o;
}

static void json_shape(void *ctx, const shape *s)
{
    cJSON *regions = ctx;
    cJSON *jr = cJSON_CreateObject();
    cJSON_AddStringToObject(jr, "fill_rule", s->rule == CS_FILL_EVENODD ? "evenodd" : "nonzero");
    cJSON_AddItemToObject(jr, "paint", paint_json(s));
    cJSON *ops = NULL;
    if (s->has_csg) {
        static const char *const names[] = {"", "union", "intersect", "difference", "xor"};
        cJSON *prog = cJSON_AddArrayToObject(jr, "csg");
        for (int i = 0; i < s->csg.nrpn; i++) {
            int t = s->csg.rpn[i];
            cJSON_AddItemToArray(prog, t >= 0 ? cJSON_CreateNumber(t) : cJSON_CreateString(names[-t]));
        }
        ops = cJSON_AddArrayToObject(jr, "operands");
    }
    cJSON *contours = cJSON_AddArrayToObject(jr, "contours");
    int nc = shape_ncontours(s);
    for (int k = 0; k < nc; k++) {
        int op;
        const sv_contour *ct = shape_contour(s, k, &op);
        if (ops)
            cJSON_AddItemToArray(ops, cJSON_CreateNumber(op));
        cJSON *jk = cJSON_CreateObject();
        cJSON_AddNumberToObject(jk, "degree", ct->degree);
        cJSON *points = cJSON_AddArrayToObject(jk, "points");
        cJSON *iv = cJSON_AddArrayToObject(jk, "intervals");
        for (int i = 0; i < ct->count; i++) {
            sv_pt q = shape_point(s, ct, i);
            cJSON *pt = cJSON_CreateArray();
            cJSON_AddItemToArray(pt, num(q.x));
            cJSON_AddItemToArray(pt, num(q.y));
            if (ct->pts[3 * i + 2] != 1)
                cJSON_AddItemToArray(pt, num(ct->pts[3 * i + 2]));
            cJSON_AddItemToArray(points, pt);
            cJSON_AddItemToArray(iv, num(ct->intervals[i]));
        }
        cJSON_AddItemToArray(contours, jk);
    }
    cJSON_AddItemToArray(regions, jr);
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
     * Imported artwork was designed for sRGB blending: ask for it, so that
     * a loader that honours the key (docs/SCENE.md, "Blending space") shows
     * what the designer's tool showed. Colours stay as written (sRGB).
     */
    if (doc->blend_srgb)
        cJSON_AddStringToObject(canvas, "blend", "srgb");
    cJSON *cels = cJSON_AddArrayToObject(root, "cels");
    for (int c = 0; c < doc->ncels; c++) {
        const sv_cel *cel = &doc->cels[c];
        cJSON *jc = cJSON_CreateObject();
        cJSON_AddStringToObject(jc, "name", cel->name);
        if (cel->has_transform) {
            const sv_affine *m = &cel->transform;
            const double v[6] = {m->a, m->b, m->c, m->d, m->e, m->f};
            cJSON *t = cJSON_AddArrayToObject(jc, "transform");
            for (int i = 0; i < 6; i++)
                cJSON_AddItemToArray(t, num(v[i]));
        }
        cJSON *regions = cJSON_AddArrayToObject(jc, "regions");
        for (int r = 0; r < cel->nregions; r++)
            region_shapes(doc, cel, &cel->regions[r], false, json_shape, regions);
        cJSON_AddItemToArray(cels, jc);
    }
    char *s = cJSON_PrintUnformatted(root);
    cJSON_Delete(root);
    return s;
}
