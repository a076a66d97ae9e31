/*
 * peer_ft.c - the scene drawn by FreeType's smooth rasterizer.
 *
 * FreeType rasterizes; it does not composite. Each region becomes one
 * FT_Outline (26.6 fixed point, y up, so y' = height - y; quadratics stay
 * conics, cubics stay cubics, rational spans arrive as cubics from
 * outline.c), rendered by FT_Outline_Render with FT_RASTER_FLAG_AA |
 * FT_RASTER_FLAG_DIRECT: the smooth rasterizer computes exact area coverage
 * of its flattened outline per cell and hands each row to a spans callback.
 * The callback here is the compositor a FreeType user has to write: 8-bit
 * premultiplied OVER into an ARGB32 buffer (cairo's pixel format), with a
 * straight store for full coverage of an opaque paint. It is plain C;
 * cairo's pixman compositor is SIMD, so FreeType's column measures the
 * rasterizer plus a simple compositor.
 *
 * The 26.6 conversion happens once per frame outside the timing
 * (peer_ft_prepare), like the NURBS-to-Bezier conversion.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_OUTLINE_H

#include "bench.h"

struct peer_ft {
    FT_Library lib;
    int w, h;
    uint32_t *pix, *saved;
    FT_Outline *outlines;
    int outline_count;
};

/* What the span callback needs for one region. */
typedef struct span_ctx {
    uint32_t *pix;
    int w, h;
    uint32_t sa, sr, sg, sb; /* premultiplied source, 0..255 */
    double *cov;             /* coverage mode: 0..1 per pixel, w x h */
} span_ctx;

static inline uint32_t div255(uint32_t x)
{
    x += 128;
    return (x + (x >> 8)) >> 8;
}

static void spans_over(int y, int count, const FT_Span *spans, void *user)
{
    span_ctx *c = user;
    uint32_t *row = c->pix + (size_t)(c->h - 1 - y) * c->w;
    uint32_t solid = (c->sa << 24) | (c->sr << 16) | (c->sg << 8) | c->sb;
    for (int i = 0; i < count; i++) {
        uint32_t *d = row + spans[i].x;
        int n = spans[i].len;
        uint32_t cov = spans[i].coverage;
        if (cov == 255 && c->sa == 255) {
            for (int k = 0; k < n; k++)
                d[k] = solid;
            continue;
        }
        uint32_t a = div255(cov * c->sa), r = div255(cov * c->sr), g = div255(cov * c->sg),
                 b = div255(cov * c->sb), ia = 255 - a;
        for (int k = 0; k < n; k++) {
            uint32_t p = d[k];
            uint32_t pa = p >> 24, pr = (p >> 16) & 255, pg = (p >> 8) & 255, pb = p & 255;
            d[k] = ((a + div255(pa * ia)) << 24) | ((r + div255(pr * ia)) << 16) |
                   ((g + div255(pg * ia)) << 8) | (b + div255(pb * ia));
        }
    }
}

static void spans_cov(int y, int count, const FT_Span *spans, void *user)
{
    span_ctx *c = user;
    double *row = c->cov + (size_t)(c->h - 1 - y) * c->w;
    for (int i = 0; i < count; i++)
        for (int k = 0; k < spans[i].len; k++)
            row[spans[i].x + k] = spans[i].coverage / 255.0;
}

peer_ft *peer_ft_new(int width, int height)
{
    peer_ft *p = calloc(1, sizeof *p);
    if (!p)
        return NULL;
    p->w = width;
    p->h = height;
    p->pix = malloc((size_t)width * height * sizeof *p->pix);
    if (!p->pix || FT_Init_FreeType(&p->lib) != 0) {
        free(p->pix);
        free(p);
        return NULL;
    }
    return p;
}

static void free_outlines(peer_ft *p)
{
    for (int i = 0; i < p->outline_count; i++)
        FT_Outline_Done(p->lib, &p->outlines[i]);
    free(p->outlines);
    p->outlines = NULL;
    p->outline_count = 0;
}

void peer_ft_free(peer_ft *p)
{
    if (!p)
        return;
    free_outlines(p);
    FT_Done_FreeType(p->lib);
    free(p->pix);
    free(p->saved);
    free(p);
}

static FT_Pos fx(double v)
{
    return (FT_Pos)lround(v * 64.0);
}

/* Points one contour adds: the start, then every command's points, less the
 * closing end point (FreeType closes a contour onto its first point). */
static int contour_points(const ol_set *set, const ol_contour *c)
{
    int n = 1;
    for (int i = c->first; i < c->first + c->count; i++)
        n += set->cmds[i].op;
    return c->count > 0 ? n - 1 : n;
}

/* Appends contour c, shifted by (-dx, -dy) and flipped in a box of height h. */
static void put_contour(FT_Outline *o, const ol_set *set, const ol_contour *c, double dx, double dy,
                        int h)
{
    int n = o->n_points;
    o->points[n].x = fx(c->x0 - dx);
    o->points[n].y = fx(h - (c->y0 - dy));
    o->tags[n++] = FT_CURVE_TAG_ON;
    for (int i = c->first; i < c->first + c->count; i++) {
        const ol_cmd *m = &set->cmds[i];
        bool last = i + 1 == c->first + c->count;
        char off = m->op == OL_QUAD ? FT_CURVE_TAG_CONIC : FT_CURVE_TAG_CUBIC;
        for (int q = 0; q < m->op; q++) {
            bool end = q + 1 == m->op;
            if (end && last)
                break;
            o->points[n].x = fx(m->p[2 * q] - dx);
            o->points[n].y = fx(h - (m->p[2 * q + 1] - dy));
            o->tags[n++] = end ? FT_CURVE_TAG_ON : off;
        }
    }
    o->n_points = (short)n;
    o->contours[o->n_contours++] = (short)(n - 1);
}

int peer_ft_prepare(peer_ft *p, const ol_set *set)
{
    free_outlines(p);
    p->outlines = calloc((size_t)set->region_count + 1, sizeof *p->outlines);
    if (!p->outlines)
        return -1;
    for (int i = 0; i < set->region_count; i++) {
        const ol_region *r = &set->regions[i];
        long pts = 0;
        for (int k = r->first; k < r->first + r->count; k++)
            pts += contour_points(set, &set->contours[k]);
        if (pts > 32767 || r->count > 32767)
            return -1; /* FT_Outline counts in shorts */
        FT_Outline *o = &p->outlines[p->outline_count];
        if (FT_Outline_New(p->lib, (FT_UInt)pts, r->count, o) != 0)
            return -1;
        p->outline_count++;
        o->n_points = 0;
        o->n_contours = 0;
        for (int k = r->first; k < r->first + r->count; k++)
            put_contour(o, set, &set->contours[k], 0.0, 0.0, set->height);
        o->flags = r->evenodd ? FT_OUTLINE_EVEN_ODD_FILL : FT_OUTLINE_NONE;
    }
    return 0;
}

static void render(peer_ft *p, FT_Outline *o, FT_SpanFunc fn, span_ctx *ctx, int w, int h)
{
    FT_Raster_Params params;
    memset(&params, 0, sizeof params);
    params.source = o;
    params.flags = FT_RASTER_FLAG_AA | FT_RASTER_FLAG_DIRECT | FT_RASTER_FLAG_CLIP;
    params.gray_spans = fn;
    params.user = ctx;
    params.clip_box.xMin = 0;
    params.clip_box.yMin = 0;
    params.clip_box.xMax = w;
    params.clip_box.yMax = h;
    FT_Outline_Render(p->lib, o, &params);
}

void peer_ft_frame(peer_ft *p, const ol_set *set, int first, int end, bool over_saved)
{
    size_t n = (size_t)p->w * p->h;
    if (over_saved && p->saved) {
        memcpy(p->pix, p->saved, n * sizeof *p->pix);
    } else {
        uint32_t bg = 0xFF000000u | ((uint32_t)lround(set->background[0] * 255) << 16) |
                      ((uint32_t)lround(set->background[1] * 255) << 8) |
                      (uint32_t)lround(set->background[2] * 255);
        for (size_t i = 0; i < n; i++)
            p->pix[i] = bg;
    }
    span_ctx ctx = {.pix = p->pix, .w = p->w, .h = p->h};
    for (int i = end - 1; i >= first; i--) {
        const ol_region *r = &set->regions[i];
        if (!(r->rgba[3] > 0.0))
            continue;
        double a = r->rgba[3];
        ctx.sa = (uint32_t)lround(a * 255);
        ctx.sr = (uint32_t)lround(r->rgba[0] * a * 255);
        ctx.sg = (uint32_t)lround(r->rgba[1] * a * 255);
        ctx.sb = (uint32_t)lround(r->rgba[2] * a * 255);
        render(p, &p->outlines[i], spans_over, &ctx, p->w, p->h);
    }
}

void peer_ft_save_background(peer_ft *p)
{
    size_t n = (size_t)p->w * p->h;
    if (!p->saved)
        p->saved = malloc(n * sizeof *p->saved);
    if (p->saved)
        memcpy(p->saved, p->pix, n * sizeof *p->saved);
}

const uint32_t *peer_ft_pixels(peer_ft *p)
{
    return p->pix;
}

int peer_ft_coverage(peer_ft *p, const ol_set *set, const ol_contour *c, bool evenodd, int x0,
                     int y0, int w, int h, double *out)
{
    FT_Outline o;
    int pts = contour_points(set, c);
    if (pts > 32767 || FT_Outline_New(p->lib, (FT_UInt)pts, 1, &o) != 0)
        return -1;
    o.n_points = 0;
    o.n_contours = 0;
    put_contour(&o, set, c, x0, y0, h);
    o.flags = evenodd ? FT_OUTLINE_EVEN_ODD_FILL : FT_OUTLINE_NONE;
    memset(out, 0, (size_t)w * h * sizeof *out);
    span_ctx ctx = {.w = w, .h = h, .cov = out};
    render(p, &o, spans_cov, &ctx, w, h);
    FT_Outline_Done(p->lib, &o);
    return 0;
}
