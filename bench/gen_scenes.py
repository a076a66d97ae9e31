#!/usr/bin/env python3
"""Generates the benchmark scenes: python3 bench/gen_scenes.py [OUTDIR]  (default scenes/bench)

The reference scenes of BENCHMARKS.md, drawn from fixed seeds so that every run and every
machine measures the same geometry. The signage scene is scenes/demo.json itself (see
tools/gen_demo.py); the others are written here:

  blobs.json     300 overlapping closed cubic Bezier blobs of 8 segments, 30 of them
                 translucent, 1920x1080 (issue 8, "Many-blobs").
  thin.json      1000 specks of 0.5..4 px (triangles, squares, circles), 300 straight hairlines
                 0.3..1.5 px wide and 100 curved cubic hairlines: edges everywhere, little area.
  rational.json  circles (exact, weight sqrt(1/2)), ellipses by cel transform, rings, and
                 periodic NURBS of degree 2 and 3 with weights 0.25..4 and uneven knots.
  anim.json      a static background (sky, hills, a forest of 120 trees) behind 6 animated
                 characters whose transform tracks run over 2 s: 120 frames at 60 Hz.

Paints use a clear medium ([1,1,1]) and the stack's lights, so a region's beta-model map is
exactly premultiplied alpha over (alpha = beta) and cairo or a FreeType span compositor can
draw the same picture. Opaque shapes that follow one another in depth share a cel (within a
cel a front region hides the regions behind it, which for opaque paint is what painting in
order does); every translucent shape gets a cel of its own so that it composites over what
lies behind it, as a peer's painter's algorithm would.
"""
import json
import math
import os
import random
import sys

R2 = 0.70710678  # sqrt(1/2): the corner weight of an exact circle
W, H = 1920, 1080


def rnd(v, nd=3):
    v = round(v, nd)
    return int(v) if v == int(v) else v


def pts_json(pts):
    out = []
    for p in pts:
        q = [rnd(p[0]), rnd(p[1])]
        if len(p) > 2 and p[2] != 1:
            q.append(rnd(p[2], 8))
        out.append(q)
    return out


def colour(rng):
    return "#%02x%02x%02x" % (rng.randrange(40, 256), rng.randrange(40, 256), rng.randrange(40, 256))


def bezier_path(segs):
    """Closed cubic Bezier path: segs = [(P0, C1, C2), ...]; segment k ends at P0 of k+1."""
    pts = []
    for p0, c1, c2 in segs:
        pts += [p0, c1, c2]
    return {"degree": 3, "points": pts_json(pts), "intervals": [1, 0, 0] * len(segs)}


def polygon(pts):
    return {"degree": 1, "points": pts_json(pts)}


def circle(cx, cy, r, reverse=False):
    pts = []
    for k in range(8):
        a = k * math.pi / 4
        if k % 2 == 0:
            pts.append([cx + r * math.cos(a), cy + r * math.sin(a)])
        else:
            pts.append([cx + r * math.copysign(1, math.cos(a)),
                        cy + r * math.copysign(1, math.sin(a)), R2])
    if reverse:
        pts = [pts[0]] + pts[:0:-1]
    return {"degree": 2, "points": pts_json(pts), "intervals": [1, 0] * 4}


def blob(rng, cx, cy, r, nseg=8):
    """A closed cubic Bezier blob: on-curve points at jittered angles and radii, handles
    along the tangent of the circle through them (a smooth, mostly convex outline)."""
    angles = sorted(2 * math.pi * (k + rng.uniform(-0.3, 0.3)) / nseg for k in range(nseg))
    radii = [r * rng.uniform(0.6, 1.3) for _ in range(nseg)]
    on = [(cx + rr * math.cos(a), cy + rr * math.sin(a)) for a, rr in zip(angles, radii)]
    segs = []
    for k in range(nseg):
        a0, a1 = angles[k], angles[(k + 1) % nseg] + (2 * math.pi if k + 1 == nseg else 0)
        h = 4.0 / 3.0 * math.tan((a1 - a0) / 4)
        r0, r1 = radii[k], radii[(k + 1) % nseg]
        p0, p1 = on[k], on[(k + 1) % nseg]
        c1 = (p0[0] - h * r0 * math.sin(a0), p0[1] + h * r0 * math.cos(a0))
        c2 = (p1[0] + h * r1 * math.sin(a1), p1[1] - h * r1 * math.cos(a1))
        segs.append((p0, c1, c2))
    return bezier_path(segs)


def region(contours, pigment, beta=1.0, rule="nonzero"):
    paint = {"pigment": pigment}
    if beta != 1.0:
        paint["beta"] = rnd(beta, 3)
    return {"fill_rule": rule, "paint": paint, "contours": contours}


def cels_by_depth(items, prefix):
    """items: (region, translucent) front to back. Consecutive opaque regions share a cel."""
    cels, run = [], []
    for reg, translucent in items:
        if translucent:
            if run:
                cels.append({"name": "%s-%d" % (prefix, len(cels)), "regions": run})
                run = []
            cels.append({"name": "%s-%d" % (prefix, len(cels)), "regions": [reg]})
        else:
            run.append(reg)
    if run:
        cels.append({"name": "%s-%d" % (prefix, len(cels)), "regions": run})
    return cels


def scene(cels, background):
    assert len(cels) <= 64, len(cels)
    return {"canvas": {"width": W, "height": H, "background": background},
            "lights": {"front": [1, 1, 1], "back": [0, 0, 0]}, "cels": cels}


def gen_blobs():
    rng = random.Random(8001)
    translucent = set(rng.sample(range(300), 30))
    items = []
    for i in range(300):
        r = math.exp(rng.uniform(math.log(18), math.log(150)))
        cx, cy = rng.uniform(-0.05 * W, 1.05 * W), rng.uniform(-0.05 * H, 1.05 * H)
        t = i in translucent
        items.append((region([blob(rng, cx, cy, r)], colour(rng),
                             rng.uniform(0.3, 0.7) if t else 1.0), t))
    return scene(cels_by_depth(items, "blobs"), "#202830")


def gen_thin():
    rng = random.Random(8002)
    cels = []
    # Specks: 10 regions of 100 tiny shapes each.
    regs = []
    for g in range(10):
        cs = []
        for _ in range(100):
            x, y = rng.uniform(2, W - 2), rng.uniform(2, H - 2)
            s = rng.uniform(0.5, 4.0)
            kind = rng.randrange(3)
            if kind == 0:
                a = rng.uniform(0, 2 * math.pi)
                cs.append(polygon([(x + s * math.cos(a + k * 2.0944), y + s * math.sin(a + k * 2.0944))
                                   for k in range(3)]))
            elif kind == 1:
                a = rng.uniform(0, math.pi / 2)
                c, d = s * math.cos(a) / 2, s * math.sin(a) / 2
                cs.append(polygon([(x - c + d, y - d - c), (x + c + d, y + d - c),
                                   (x + c - d, y + d + c), (x - c - d, y - d + c)]))
            else:
                cs.append(circle(x, y, s / 2))
        regs.append(region(cs, colour(rng)))
    cels.append({"name": "specks", "regions": regs})
    # Straight hairlines: 6 regions of 50, two of them translucent (own cels).
    for g in range(6):
        cs = []
        for _ in range(50):
            x, y = rng.uniform(0, W), rng.uniform(0, H)
            length, w = rng.uniform(50, 600), rng.uniform(0.3, 1.5)
            a = rng.uniform(0, math.pi)
            dx, dy = math.cos(a), math.sin(a)
            nx, ny = -dy * w / 2, dx * w / 2
            x1, y1 = x + dx * length, y + dy * length
            cs.append(polygon([(x + nx, y + ny), (x1 + nx, y1 + ny), (x1 - nx, y1 - ny),
                               (x - nx, y - ny)]))
        t = g >= 4
        cels.append({"name": "hairlines-%d" % g,
                     "regions": [region(cs, colour(rng), 0.6 if t else 1.0)]})
    # Curved hairlines: a cubic centre line offset by +-w/2 along its end normals, closed by
    # straight caps written as cubics (12 points, degree 3).
    cs = []
    for _ in range(100):
        p = [(rng.uniform(0, W), rng.uniform(0, H))]
        for _k in range(3):
            p.append((p[-1][0] + rng.uniform(-200, 200), p[-1][1] + rng.uniform(-200, 200)))
        w = rng.uniform(0.5, 2.0)

        def normal(a, b):
            dx, dy = b[0] - a[0], b[1] - a[1]
            n = math.hypot(dx, dy) or 1.0
            return -dy / n * w / 2, dx / n * w / 2
        n0, n3 = normal(p[0], p[1]), normal(p[2], p[3])
        n1 = n2 = ((n0[0] + n3[0]) / 2, (n0[1] + n3[1]) / 2)
        up = [(q[0] + n[0], q[1] + n[1]) for q, n in zip(p, (n0, n1, n2, n3))]
        dn = [(q[0] - n[0], q[1] - n[1]) for q, n in zip(p, (n0, n1, n2, n3))]

        def line(a, b):
            return (a, (a[0] + (b[0] - a[0]) / 3, a[1] + (b[1] - a[1]) / 3),
                    (a[0] + 2 * (b[0] - a[0]) / 3, a[1] + 2 * (b[1] - a[1]) / 3))
        segs = [(up[0], up[1], up[2]), line(up[3], dn[3]), (dn[3], dn[2], dn[1]), line(dn[0], up[0])]
        cs.append(bezier_path(segs))
    cels.append({"name": "curves", "regions": [region(cs, "#f0f0f0")]})
    return scene(cels, "#101418")


def nurbs(rng, cx, cy, r, degree):
    n = rng.randrange(8, 13)
    pts = []
    for k in range(n):
        a = 2 * math.pi * (k + rng.uniform(-0.25, 0.25)) / n
        rr = r * rng.uniform(0.5, 1.4)
        w = math.exp(rng.uniform(math.log(0.25), math.log(4.0)))
        pts.append((cx + rr * math.cos(a), cy + rr * math.sin(a), w))
    iv = [rnd(rng.uniform(0.5, 2.0), 3) for _ in range(n)]
    return {"degree": degree, "points": pts_json(pts), "intervals": iv}


def gen_rational():
    rng = random.Random(8003)
    items = []
    for i in range(160):
        kind = rng.randrange(4)
        r = math.exp(rng.uniform(math.log(8), math.log(160)))
        cx, cy = rng.uniform(0, W), rng.uniform(0, H)
        t = rng.random() < 0.12
        beta = rng.uniform(0.35, 0.75) if t else 1.0
        if kind == 0:
            reg = region([circle(cx, cy, r)], colour(rng), beta)
        elif kind == 1:
            reg = region([circle(cx, cy, r), circle(cx, cy, r * rng.uniform(0.4, 0.85))],
                         colour(rng), beta, "evenodd")
        else:
            reg = region([nurbs(rng, cx, cy, r, 2 if kind == 2 else 3)], colour(rng), beta)
        items.append((reg, t))
    cels = cels_by_depth(items, "rational")
    # Ellipses: circles on cels that scale and turn them.
    for k in range(6):
        a = rng.uniform(0, math.pi)
        sx, sy = rng.uniform(1.5, 3.0), rng.uniform(0.3, 0.8)
        ca, sa = math.cos(a), math.sin(a)
        m = [sx * ca, sx * sa, -sy * sa, sy * ca, rng.uniform(200, W - 200), rng.uniform(150, H - 150)]
        cels.insert(2 * k, {"name": "ellipse-%d" % k, "transform": [rnd(v, 6) for v in m],
                            "regions": [region([circle(0, 0, rng.uniform(20, 80))], colour(rng),
                                               0.6 if k % 2 else 1.0)]})
    return scene(cels, "#182028")


def gen_anim():
    rng = random.Random(8004)
    cels = []
    # Six characters in front, each a body blob, a head circle and two eyes (evenodd rings),
    # moving along keyframed paths over 2 s.
    for k in range(6):
        body = blob(rng, 0, 40, 60)
        head = circle(0, -40, 35)
        eyes = [circle(-12, -45, 8), circle(-12, -45, 4), circle(12, -45, 8), circle(12, -45, 4)]
        keys = []
        x0, y0 = rng.uniform(100, W - 100), rng.uniform(200, H - 200)
        for j in range(5):
            t = j * 0.5
            a = rng.uniform(-0.4, 0.4)
            s = rng.uniform(0.8, 1.3)
            keys.append([t, [rnd(s * math.cos(a), 5), rnd(s * math.sin(a), 5), rnd(-s * math.sin(a), 5),
                             rnd(s * math.cos(a), 5), rnd(x0 + rng.uniform(-300, 300), 2),
                             rnd(y0 + rng.uniform(-150, 150), 2)]])
        cels.append({"name": "character-%d" % k, "transform": keys[0][1],
                     "regions": [region(eyes, "#101010", 1.0, "evenodd"),
                                 region([head], colour(rng)),
                                 region([body], colour(rng), 0.85 if k % 2 else 1.0)],
                     "animate": {"transform": {"keys": keys,
                                               "ease": "smooth" if k % 2 else "linear"}}})
    # Static background, front to back: mist band, forest, hills, sky.
    cels.append({"name": "mist", "regions": [region([bezier_path([
        ((0, 560), (640, 520), (1280, 600)), ((W, 560), (W, 600), (W, 640)),
        ((W, 680), (1280, 720), (640, 640)), ((0, 680), (0, 640), (0, 600))])], "#e8eef0", 0.35)]})
    trees = []
    for _ in range(120):
        x, y = rng.uniform(0, W), rng.uniform(600, H)
        s = rng.uniform(15, 45)
        trees.append(polygon([(x, y - 2.2 * s), (x + s, y), (x - s, y)]))
        trees.append(circle(x, y - 2.6 * s, 0.5 * s))
    cels.append({"name": "forest", "regions": [region(trees, "#1f5f3a")]})
    hills = []
    for k in range(4):
        hills.append(blob(rng, rng.uniform(0, W), H + 100, rng.uniform(300, 600)))
    cels.append({"name": "hills", "regions": [region(hills, "#3d7a4a")]})
    cels.append({"name": "sky", "regions": [region([polygon([(0, 0), (W, 0), (W, H), (0, H)])],
                                                   "#6fa8dc")]})
    return scene(cels, "#000000")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/bench"
    os.makedirs(out, exist_ok=True)
    for name, fn in (("blobs", gen_blobs), ("thin", gen_thin), ("rational", gen_rational),
                     ("anim", gen_anim)):
        path = os.path.join(out, name + ".json")
        with open(path, "w") as f:
            json.dump(fn(), f, separators=(",", ":"))
            f.write("\n")


if __name__ == "__main__":
    main()
