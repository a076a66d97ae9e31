/*
 * peer_cairo.c - the scene drawn by cairo, the peer most users would pick.
 *
 * An ARGB32 image surface with cairo's defaults: CAIRO_ANTIALIAS_DEFAULT
 * (in cairo 1.16 the image backend's "tor" scan converter: 15 sub-rows and
 * 256 sub-columns per pixel, coverage per cell) and the default flattening
 * tolerance of 0.1 device pixels unless the caller asks for another (the
 * benchmark also runs a "fine" cairo at 0.01 px, to see what equal quality
 * on curves costs it). Regions are filled back to front with OVER, one
 * cairo_fill per region with the region's fill rule, as an SVG renderer
 * would. Quadratic segments are raised to cubics (exact); rational ones
 * arrive as cubics from outline.c.
 *
 * Path construction (cairo_move_to and friends) is inside the timed frame,
 * as it is for any cairo user; the NURBS-to-Bezier conversion is not.
 */
#include <cairo.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

struct peer_cairo {
    cairo_surface_t *surf, *saved;
    int w, h;
    double tol;
};

peer_cairo *peer_cairo_new(int width, int height, double tolerance)
{
    peer_cairo *p = calloc(1, sizeof *p);
    if (!p)
        return NULL;
    p->w = width;
    p->h = height;
    p->tol = tolerance;
    p->surf = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height);
    if (cairo_surface_status(p->surf) != CAIRO_STATUS_SUCCESS) {
        peer_cairo_free(p);
        return NULL;
    }
    return p;
}

void peer_cairo_free(peer_cairo *p)
{
    if (!p)
        return;
    if (p->surf)
        cairo_surface_destroy(p->surf);
    if (p->saved)
        cairo_surface_destroy(p->saved);
    free(p);
}

static void add_contour(cairo_t *cr, const ol_set *set, const ol_contour *c, double dx, double dy)
{
    double px = c->x0 - dx, py = c->y0 - dy;
    cairo_move_to(cr, px, py);
    for (int i = c->first; i < c->first + c->count; i++) {
        const ol_cmd *m = &set->cmds[i];
        switch (m->op) {
        case OL_LINE:
            px = m->p[0] - dx;
            py = m->p[1] - dy;
            cairo_line_to(cr, px, py);
            break;
        case OL_QUAD: {
            double qx = m->p[0] - dx, qy = m->p[1] - dy, ex = m->p[2] - dx, ey = m->p[3] - dy;
            cairo_curve_to(cr, px + 2.0 / 3.0 * (qx - px), py + 2.0 / 3.0 * (qy - py),
                           ex + 2.0 / 3.0 * (qx - ex), ey + 2.0 / 3.0 * (qy - ey), ex, ey);
            px = ex;
            py = ey;
            break;
        }
        default:
            px = m->p[4] - dx;
            py = m->p[5] - dy;
            cairo_curve_to(cr, m->p[0] - dx, m->p[1] - dy, m->p[2] - dx, m->p[3] - dy, px, py);
            break;
        }
    }
    cairo_close_path(cr);
}

static void fill_region(cairo_t *cr, const ol_set *set, const ol_region *r)
{
    if (!(r->rgba[3] > 0.0))
        return;
    cairo_new_path(cr);
    for (int k = r->first; k < r->first + r->count; k++)
        add_contour(cr, set, &set->contours[k], 0.0, 0.0);
    cairo_set_fill_rule(cr, r->evenodd ? CAIRO_FILL_RULE_EVEN_ODD : CAIRO_FILL_RULE_WINDING);
    cairo_set_source_rgba(cr, r->rgba[0], r->rgba[1], r->rgba[2], r->rgba[3]);
    cairo_fill(cr);
}

void peer_cairo_frame(peer_cairo *p, const ol_set *set, int first, int end, bool over_saved)
{
    cairo_t *cr = cairo_create(p->surf);
    cairo_set_tolerance(cr, p->tol);
    cairo_set_operator(cr, CAIRO_OPERATOR_SOURCE);
    if (over_saved && p->saved)
        cairo_set_source_surface(cr, p->saved, 0, 0);
    else
        cairo_set_source_rgb(cr, set->background[0], set->background[1], set->background[2]);
    cairo_paint(cr);
    cairo_set_operator(cr, CAIRO_OPERATOR_OVER);
    for (int i = end - 1; i >= first; i--)
        fill_region(cr, set, &set->regions[i]);
    cairo_destroy(cr);
    cairo_surface_flush(p->surf);
}

void peer_cairo_save_background(peer_cairo *p)
{
    if (!p->saved)
        p->saved = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, p->w, p->h);
    cairo_t *cr = cairo_create(p->saved);
    cairo_set_operator(cr, CAIRO_OPERATOR_SOURCE);
    cairo_set_source_surface(cr, p->surf, 0, 0);
    cairo_paint(cr);
    cairo_destroy(cr);
    cairo_surface_flush(p->saved);
}

const uint32_t *peer_cairo_pixels(peer_cairo *p, int *stride_bytes)
{
    cairo_surface_flush(p->surf);
    *stride_bytes = cairo_image_surface_get_stride(p->surf);
    return (const uint32_t *)cairo_image_surface_get_data(p->surf);
}

void peer_cairo_coverage(const ol_set *set, const ol_contour *c, bool evenodd, double tolerance,
                         int x0, int y0, int w, int h, double *out)
{
    cairo_surface_t *s = cairo_image_surface_create(CAIRO_FORMAT_A8, w, h);
    cairo_t *cr = cairo_create(s);
    cairo_set_tolerance(cr, tolerance);
    add_contour(cr, set, c, x0, y0);
    cairo_set_fill_rule(cr, evenodd ? CAIRO_FILL_RULE_EVEN_ODD : CAIRO_FILL_RULE_WINDING);
    cairo_set_source_rgba(cr, 1, 1, 1, 1);
    cairo_fill(cr);
    cairo_destroy(cr);
    cairo_surface_flush(s);
    const unsigned char *d = cairo_image_surface_get_data(s);
    int stride = cairo_image_surface_get_stride(s);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            out[(size_t)y * w + x] = d[(size_t)y * stride + x] / 255.0;
    cairo_surface_destroy(s);
}
