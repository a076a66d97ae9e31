#!/usr/bin/env python3
"""Generates scenes/demo.json, the signage demo: python3 tools/gen_demo.py > scenes/demo.json

The JSON is the artefact that tools and tests read; this script is how it was drawn, so
the geometry (exact circles, cubic Bezier banner, rational blob, {7/3} rosette) can be
changed in one place."""
import json, math, re, sys

R2 = 0.70710678  # sqrt(1/2) to float precision: the corner weight of an exact circle

def rnd(v, nd=3):
    v = round(v, nd)
    return int(v) if v == int(v) else v

def fmt_pts(pts):
    out = []
    for p in pts:
        q = [rnd(p[0]), rnd(p[1])]
        if len(p) > 2 and p[2] != 1:
            q.append(rnd(p[2], 8))
        out.append(q)
    return out

def circle(r, cx=0.0, cy=0.0, reverse=False):
    """Exact circle, degree 2, 8 points, intervals [1,0]*4 (DESIGN.md).
    Counter-clockwise in y-up terms; reverse=True for a hole under nonzero."""
    pts = []
    for k in range(8):
        a = k * math.pi / 4
        if k % 2 == 0:
            pts.append([cx + r * math.cos(a), cy + r * math.sin(a)])
        else:
            pts.append([cx + r * math.copysign(1, math.cos(a)), cy + r * math.copysign(1, math.sin(a)), R2])
    if reverse:
        pts = [pts[0]] + pts[:0:-1]   # still on-curve at even indices
    return {"degree": 2, "points": fmt_pts(pts), "intervals": [1, 0] * 4}

def bezier_path(segs):
    """Closed cubic Bezier path: segs = [(P0, C1, C2), ...], segment k ends at P0 of k+1."""
    pts = []
    for p0, c1, c2 in segs:
        pts += [p0, c1, c2]
    return {"degree": 3, "points": fmt_pts(pts), "intervals": [1, 0, 0] * len(segs)}

def rounded_rect(x0, y0, x1, y1, r):
    k = 0.5523 * r
    def line(a, b):
        return (a, (a[0] + (b[0] - a[0]) / 3, a[1] + (b[1] - a[1]) / 3),
                (a[0] + 2 * (b[0] - a[0]) / 3, a[1] + 2 * (b[1] - a[1]) / 3))
    segs = [
        line((x0 + r, y0), (x1 - r, y0)),
        ((x1 - r, y0), (x1 - r + k, y0), (x1, y0 + r - k)),
        line((x1, y0 + r), (x1, y1 - r)),
        ((x1, y1 - r), (x1, y1 - r + k), (x1 - r + k, y1)),
        line((x1 - r, y1), (x0 + r, y1)),
        ((x0 + r, y1), (x0 + r - k, y1), (x0, y1 - r + k)),
        line((x0, y1 - r), (x0, y0 + r)),
        ((x0, y0 + r), (x0, y0 + r - k), (x0 + r - k, y0)),
    ]
    return bezier_path(segs)

def hermite_path(samples):
    """Closed Catmull-Rom spline through samples, as a cubic Bezier path."""
    n = len(samples)
    segs = []
    for i in range(n):
        p0, p1 = samples[i], samples[(i + 1) % n]
        pm, p2 = samples[i - 1], samples[(i + 2) % n]
        c1 = (p0[0] + (p1[0] - pm[0]) / 6, p0[1] + (p1[1] - pm[1]) / 6)
        c2 = (p1[0] - (p2[0] - p0[0]) / 6, p1[1] - (p2[1] - p0[1]) / 6)
        segs.append((p0, c1, c2))
    return bezier_path(segs)

def arc_pts(cx, cy, r, a0, a1):
    """Rational quadratic arc a0 -> a1 (degrees), as [on, ctrl, on, ctrl, ...] without the last on."""
    n = max(1, math.ceil(abs(a1 - a0) / 90 - 1e-9))
    d = (a1 - a0) / n
    w = math.cos(math.radians(d / 2))
    out = []
    for i in range(n):
        s = math.radians(a0 + i * d)
        m = math.radians(a0 + (i + 0.5) * d)
        out.append([cx + r * math.cos(s), cy + r * math.sin(s)])
        out.append([cx + r / w * math.cos(m), cy + r / w * math.sin(m), w])
    return out

def arc_stroke(cx, cy, r_in, r_out, a0, a1):
    """A thick circular arc with square ends: degree 2, exact arcs, straight caps."""
    def on(r, a):
        return [cx + r * math.cos(math.radians(a)), cy + r * math.sin(math.radians(a))]
    def mid(p, q):
        return [(p[0] + q[0]) / 2, (p[1] + q[1]) / 2]
    pts = arc_pts(cx, cy, r_out, a0, a1)
    pts.append(on(r_out, a1)); pts.append(mid(on(r_out, a1), on(r_in, a1)))
    pts += arc_pts(cx, cy, r_in, a1, a0)
    pts.append(on(r_in, a0)); pts.append(mid(on(r_in, a0), on(r_out, a0)))
    return {"degree": 2, "points": pts, "intervals": [1, 0] * (len(pts) // 2)}

def polygon(pts):
    return {"degree": 1, "points": [list(p) for p in pts]}

def area(c):
    p = c["points"]
    return sum(p[i][0] * p[(i + 1) % len(p)][1] - p[(i + 1) % len(p)][0] * p[i][1] for i in range(len(p))) / 2

def oriented(c, sign):
    """Orient a contour (area sign of its control polygon) for nonzero filling.
    Only for contours whose intervals survive reversal: none, or the [1,0] pattern."""
    if (area(c) > 0) != (sign > 0):
        assert c.get("intervals") in (None, [1, 0] * (len(c["points"]) // 2))
        c = dict(c)
        c["points"] = [c["points"][0]] + c["points"][:0:-1]
    return c

def moved(c, dx, dy):
    c = dict(c)
    c["points"] = [[p[0] + dx, p[1] + dy] + p[2:] for p in c["points"]]
    return c

# ---- glyphs for the title, in a 28-unit-high cell; each returns (contours, advance)
T = 6.0   # stroke
def g_C():
    return [arc_stroke(14, 14, 14 - T, 14, 40, 320)], 25.5
def g_E():
    return [polygon([(0, 0), (20, 0), (20, T), (T, T), (T, 11), (17, 11), (17, 17), (T, 17), (T, 22), (20, 22), (20, 28), (0, 28)])], 20
def g_L():
    return [polygon([(0, 0), (T, 0), (T, 22), (19, 22), (19, 28), (0, 28)])], 19
def g_S():
    rc = (28 - T) / 4
    top = arc_stroke(9, T / 2 + rc, rc - T / 2, rc + T / 2, 85, 330)
    bot = arc_stroke(9, T / 2 + 3 * rc, rc - T / 2, rc + T / 2, -95, 150)
    return [top, bot], 18
def g_A():
    outer = polygon([(0, 28), (10, 0), (18, 0), (28, 28), (21.6, 28), (19.6, 22), (8.4, 22), (6.4, 28)])
    hole = polygon([(10.4, 16.5), (17.6, 16.5), (14, 6)])
    return [outer, ("hole", hole)], 28
def g_N():
    return [polygon([(0, 0), (T, 0), (16, 16.5), (16, 0), (22, 0), (22, 28), (16, 28), (T, 11.5), (T, 28), (0, 28)])], 22

def title(word, gap=4.5):
    glyphs = {"C": g_C, "E": g_E, "L": g_L, "S": g_S, "A": g_A, "N": g_N}
    x = 0.0
    contours = []
    for ch in word:
        cs, adv = glyphs[ch]()
        for c in cs:
            hole = isinstance(c, tuple)
            if hole:
                c = c[1]
            contours.append(oriented(moved(c, x, 0), -1 if hole else 1))
        x += adv + gap
    for c in contours:
        c["points"] = fmt_pts(c["points"])
    return contours, x - gap

def rot(deg, s=1.0, tx=0.0, ty=0.0):
    a = math.radians(deg)
    return [rnd(s * math.cos(a), 5), rnd(s * math.sin(a), 5), rnd(-s * math.sin(a), 5), rnd(s * math.cos(a), 5), rnd(tx), rnd(ty)]

def paint(pig, beta=None, medium=None):
    p = {"pigment": pig}
    if medium is not None: p["medium"] = medium
    if beta is not None: p["beta"] = beta
    return p

cels = []

# --- front: a magenta gel lens (beta 0: pure filter), lit from behind so it glows
cels.append({
    "name": "gel-lens",
    "transform": [1, 0, 0, 1, 250, 152],
    "lights": {"back": [0.22, 0.22, 0.22]},
    "regions": [
        {"fill_rule": "nonzero", "paint": paint("#000000", 0.0, "#ff6fb5"), "contours": [circle(44)]},
    ],
    "animate": {"transform": {"keys": [[0, [1, 0, 0, 1, 250, 152]], [2, [1, 0, 0, 1, 420, 152]]], "ease": "smooth"}},
})

# --- title lettering, scaled by its cel transform into the banner's window
words, width = title("CELSCAN")
sc = 1.3
cels.append({
    "name": "title",
    "transform": [sc, 0, 0, sc, rnd(414 - sc * width / 2), rnd(60 - sc * 14)],
    "regions": [{"fill_rule": "nonzero", "paint": paint("#fff1d6"), "contours": words}],
})

# --- star flourish: a smooth self-intersecting {7/3} rosette; evenodd leaves the
#     overlaps hollow. Rotated by its cel transform, and animated to spin.
star = []
for k in range(7):
    a = math.radians(-90 + k * 3 * 360 / 7)
    star.append([150 * math.cos(a), 150 * math.sin(a)])
cels.append({
    "name": "star",
    "transform": rot(0, 1.0, 330, 222),
    "regions": [
        {"fill_rule": "evenodd", "paint": paint("#ffd166"),
         "contours": [{"degree": 3, "points": fmt_pts(star)}]},
    ],
    "animate": {"transform": {"keys": [[0, rot(0, 1.0, 330, 222)], [1, rot(-25.714, 1.08, 330, 222)],
                                       [2, rot(-51.429, 1.0, 330, 222)]], "ease": "linear"}},
})

# --- ring with a hole (outer and inner circles of opposite orientation, nonzero),
#     with twelve hour ticks in front of it, like a station clock
ticks = []
for k in range(12):
    a = math.radians(k * 30)
    ticks.append(circle(3.2 if k % 3 else 4.6, 78 * math.cos(a), 78 * math.sin(a)))
cels.append({
    "name": "ring",
    "transform": [1, 0, 0, 1, 330, 222],
    "regions": [
        {"fill_rule": "nonzero", "paint": paint("#1b2333"), "contours": ticks},
        {"fill_rule": "nonzero", "paint": paint("#ff6b6b"), "contours": [circle(90), circle(66, reverse=True)]},
    ],
})

# --- three translucent discs on three cels: where they overlap, light passes
#     through one cel's medium into the next. A back light makes them glow.
for i, (name, col, med) in enumerate([("disc-red", "#ff4d6d", "#ffc2cf"),
                                      ("disc-blue", "#4cc9f0", "#c4ecf9"),
                                      ("disc-green", "#a7e163", "#e1f5c8")]):
    a = math.radians(-90 + i * 120)
    cel = {
        "name": name,
        "transform": [1, 0, 0, 1, rnd(532 + 26 * math.cos(a)), rnd(228 + 26 * math.sin(a))],
        "lights": {"back": [0.3, 0.3, 0.3]},
        "regions": [{"fill_rule": "nonzero", "paint": paint(col, 0.5, med), "contours": [circle(44)]}],
    }
    if i == 0:
        cel["animate"] = {"lights": {"keys": [[0, {"front": [1, 1, 1], "back": [0.3, 0.3, 0.3]}],
                                              [2, {"front": [0.5, 0.5, 0.9], "back": [0.9, 0.8, 0.6]}]],
                                     "ease": "smooth"}}
    cels.append(cel)

# --- rational blob: degree 3 NURBS, varied weights, non-uniform knot intervals,
#     with a translucent halo (same curve, scaled) behind it in the same cel
radii = [62, 40, 70, 48, 66, 36, 58]
weights = [1, 2.5, 0.6, 1.6, 1, 3, 0.8]
blob = []
for k in range(7):
    a = math.radians(k * 360 / 7)
    blob.append([radii[k] * math.cos(a), radii[k] * math.sin(a), weights[k]])
ivals = [1, 0.5, 2, 1, 0.7, 1.5, 1]
cels.append({
    "name": "blob",
    "transform": rot(-20, 1.1, 122, 228),
    "regions": [
        {"fill_rule": "nonzero", "paint": paint("#2ec4b6"),
         "contours": [{"degree": 3, "points": fmt_pts(blob), "intervals": ivals}]},
        {"fill_rule": "nonzero", "paint": paint("#2ec4b6", 0.3, "#a8f0e8"),
         "contours": [{"degree": 3, "points": fmt_pts([[1.2 * x, 1.2 * y, w] for x, y, w in blob]),
                       "intervals": ivals}]},
    ],
})

# --- banner: pictograms, a title plate with a window (evenodd), dark glass in the window
arrow = polygon([(56, 52), (84, 52), (84, 40), (108, 60), (84, 80), (84, 68), (56, 68)])
dots = [circle(6.5, 136 + 24 * i, 60) for i in range(3)]
cels.append({
    "name": "banner",
    "regions": [
        {"fill_rule": "nonzero", "paint": paint("#1b2333"), "contours": [arrow] + dots},
        {"fill_rule": "evenodd", "paint": paint("#f4a259"),
         "contours": [rounded_rect(32, 22, 608, 98, 24), rounded_rect(216, 34, 596, 86, 16)]},
        {"fill_rule": "nonzero", "paint": paint("#141b2b", 0.8, "#f4a259"),
         "contours": [rounded_rect(216, 34, 596, 86, 16)]},
    ],
})

# --- ribbons: tapered brush strokes (elongated regions) along the bottom
def ribbon(y0, amp, phase, thick, n=16):
    top, bot = [], []
    for i in range(n + 1):
        s = i / n
        x = -12 + 664 * s
        y = y0 + amp * math.sin(2 * math.pi * (1.5 * s + phase))
        half = 1.2 + thick * math.sin(math.pi * s)
        top.append((x, y - half))
        bot.append((x, y + half))
    return hermite_path(top + bot[::-1][1:-1])
cels.append({
    "name": "ribbons",
    "regions": [
        {"fill_rule": "nonzero", "paint": paint("#5e60ce", 0.8, "#b8b9ff"), "contours": [ribbon(330, 10, 0.0, 8)]},
        {"fill_rule": "nonzero", "paint": paint("#48bfe3", 0.6, "#c0ecf8"), "contours": [ribbon(334, 12, 0.3, 5)]},
    ],
})

scene = {
    "canvas": {"width": 640, "height": 360, "background": "#0b1320"},
    "lights": {"front": [1, 1, 1], "back": [0, 0, 0]},
    "cels": cels,
}

text = json.dumps(scene, indent=2)
# One line per numeric array and per array of points or keys.
num_arr = r"\[[\s\d.,\-e]*\]"
text = re.sub(num_arr, lambda m: re.sub(r"\s+", "", m.group(0)).replace(",", ", "), text)
text = re.sub(r"\[\s*(\[[\d.,\- e]*\],?\s*)+\]",
              lambda m: "[" + ", ".join(re.findall(r"\[[\d.,\- e]*\]", m.group(0))) + "]", text)
text = re.sub(r"\{\s*(\"\w+\": \[[\d., \-e]*\],?\s*)+\}",
              lambda m: "{ " + ", ".join(re.findall(r"\"\w+\": \[[\d., \-e]*\]", m.group(0))) + " }", text)
text = re.sub(r"\[\s*([\d.\-]+),\s*(\[[^\[\]]*\]|\{[^{}]*\})\s*\]", r"[\1, \2]", text)
text = re.sub(r"\[\s*(\[[\d.\-]+, (?:\[[^\[\]]*\]|\{[^{}]*\})\],?\s*)+\]",
              lambda m: "[" + ", ".join(re.findall(r"\[[\d.\-]+, (?:\[[^\[\]]*\]|\{[^{}]*\})\]", m.group(0))) + "]", text)
text = re.sub(r"\{\s*(\"\w+\": (?:\"[^\"]*\"|[\d.\-]+|\[[\d., \-e]*\]),?\s*)+\}",
              lambda m: "{ " + ", ".join(re.findall(r"\"\w+\": (?:\"[^\"]*\"|[\d.\-]+|\[[\d., \-e]*\])", m.group(0))) + " }", text)
sys.stdout.write(text + "\n")
