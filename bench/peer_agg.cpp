/*
 * peer_agg.cpp - the scene drawn by Anti-Grain Geometry 2.6 (Debian's
 * libagg-dev), the C++ rasterizer many vector and plotting libraries embed.
 *
 * AGG as its own examples use it, with its defaults: each region's contours
 * go into one agg::path_storage (quadratics and cubics as curve3/curve4),
 * agg::conv_curve flattens them (approximation scale 1, its default),
 * agg::rasterizer_scanline_aa accumulates exact cell areas with the
 * region's fill rule (no gamma), and render_scanlines_aa_solid blends the
 * region's colour into a B,G,R,A buffer with agg::scanline_u8 and the
 * non-premultiplied blender (the frame is opaque, so that is "over").
 * Regions are drawn back to front, as cairo draws them. Path construction is
 * inside the timed frame, as it is for cairo; the NURBS-to-Bezier
 * conversion (outline.c) is not.
 */
#include <cstdlib>
#include <cstring>
#include <new>

#include <agg_basics.h>
#include <agg_conv_curve.h>
#include <agg_path_storage.h>
#include <agg_pixfmt_gray.h>
#include <agg_pixfmt_rgba.h>
#include <agg_rasterizer_scanline_aa.h>
#include <agg_renderer_base.h>
#include <agg_renderer_scanline.h>
#include <agg_rendering_buffer.h>
#include <agg_scanline_u.h>

#include "peer_agg.h"

struct peer_agg {
    int w, h;
    unsigned char *buf, *saved;
    agg::rendering_buffer rbuf;
    agg::path_storage path;
    agg::rasterizer_scanline_aa<> ras;
    agg::scanline_u8 sl;
};

extern "C" peer_agg *peer_agg_new(int width, int height)
{
    peer_agg *p = new (std::nothrow) peer_agg;
    if (!p)
        return NULL;
    p->w = width;
    p->h = height;
    p->saved = NULL;
    p->buf = static_cast<unsigned char *>(std::calloc((size_t)width * (size_t)height, 4));
    if (!p->buf) {
        delete p;
        return NULL;
    }
    p->rbuf.attach(p->buf, (unsigned)width, (unsigned)height, width * 4);
    return p;
}

extern "C" void peer_agg_free(peer_agg *p)
{
    if (!p)
        return;
    std::free(p->buf);
    std::free(p->saved);
    delete p;
}

/* Appends one contour, moved by (-dx, -dy), to the path. */
static void add_contour(agg::path_storage &path, const ol_set *set, const ol_contour *c, double dx,
                        double dy)
{
    path.move_to(c->x0 - dx, c->y0 - dy);
    for (int i = c->first; i < c->first + c->count; i++) {
        const ol_cmd *m = &set->cmds[i];
        switch (m->op) {
        case OL_LINE:
            path.line_to(m->p[0] - dx, m->p[1] - dy);
            break;
        case OL_QUAD:
            path.curve3(m->p[0] - dx, m->p[1] - dy, m->p[2] - dx, m->p[3] - dy);
            break;
        default:
            path.curve4(m->p[0] - dx, m->p[1] - dy, m->p[2] - dx, m->p[3] - dy, m->p[4] - dx,
                        m->p[5] - dy);
            break;
        }
    }
    path.close_polygon();
}

static agg::int8u byte_of(double v)
{
    double b = v * 255.0 + 0.5;
    return (agg::int8u)(b < 0.0 ? 0.0 : b > 255.0 ? 255.0 : b);
}

extern "C" void peer_agg_frame(peer_agg *p, const ol_set *set, int first, int end, bool over_saved)
{
    typedef agg::pixfmt_bgra32 pixfmt;
    pixfmt pf(p->rbuf);
    agg::renderer_base<pixfmt> rb(pf);
    if (over_saved && p->saved)
        std::memcpy(p->buf, p->saved, (size_t)p->w * (size_t)p->h * 4);
    else
        rb.clear(agg::rgba8(byte_of(set->background[0]), byte_of(set->background[1]),
                            byte_of(set->background[2]), 255));
    for (int i = end - 1; i >= first; i--) {
        const ol_region *r = &set->regions[i];
        if (!(r->rgba[3] > 0.0))
            continue;
        p->path.remove_all();
        for (int k = r->first; k < r->first + r->count; k++)
            add_contour(p->path, set, &set->contours[k], 0.0, 0.0);
        agg::conv_curve<agg::path_storage> curves(p->path);
        p->ras.reset();
        p->ras.filling_rule(r->evenodd ? agg::fill_even_odd : agg::fill_non_zero);
        p->ras.add_path(curves);
        agg::render_scanlines_aa_solid(p->ras, p->sl, rb,
                                       agg::rgba8(byte_of(r->rgba[0]), byte_of(r->rgba[1]),
                                                  byte_of(r->rgba[2]), byte_of(r->rgba[3])));
    }
}

extern "C" void peer_agg_save_background(peer_agg *p)
{
    size_t n = (size_t)p->w * (size_t)p->h * 4;
    if (!p->saved)
        p->saved = static_cast<unsigned char *>(std::malloc(n));
    if (p->saved)
        std::memcpy(p->saved, p->buf, n);
}

extern "C" const uint32_t *peer_agg_pixels(peer_agg *p)
{
    return reinterpret_cast<const uint32_t *>(p->buf);
}

extern "C" void peer_agg_coverage(const ol_set *set, const ol_contour *c, bool evenodd, int x0,
                                  int y0, int w, int h, double *out)
{
    unsigned char *g = static_cast<unsigned char *>(std::calloc((size_t)w * (size_t)h, 1));
    if (!g) {
        for (size_t k = 0; k < (size_t)w * (size_t)h; k++)
            out[k] = -1.0; /* shows as a huge error, never silently as right */
        return;
    }
    agg::rendering_buffer rbuf(g, (unsigned)w, (unsigned)h, w);
    agg::pixfmt_gray8 pf(rbuf);
    agg::renderer_base<agg::pixfmt_gray8> rb(pf);
    agg::path_storage path;
    add_contour(path, set, c, x0, y0);
    agg::conv_curve<agg::path_storage> curves(path);
    agg::rasterizer_scanline_aa<> ras;
    agg::scanline_u8 sl;
    ras.filling_rule(evenodd ? agg::fill_even_odd : agg::fill_non_zero);
    ras.add_path(curves);
    agg::render_scanlines_aa_solid(ras, sl, rb, agg::gray8(255, 255));
    for (size_t k = 0; k < (size_t)w * (size_t)h; k++)
        out[k] = g[k] / 255.0;
    std::free(g);
}
