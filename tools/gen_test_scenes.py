#!/usr/bin/env python3
"""Generates the test scenes next to the demo: python3 tools/gen_test_scenes.py scenes/

  beta-csg.json  the beta model's paints as authoring JSON: linear and radial gradients, a
                 feathered matte (a radial beta), a four-corner colour map on a gel, a CSG
                 emblem (ring minus bar, plus dot) with operands, a soft hold-out matte;
                 animated stack lights and background, a sliding gel, and a paint track
                 on a region whose pigment and beta are functions (it animates the medium).
  motion.json    one track of every kind: a spinning star (transform), a morphing contour
                 (points), a lamp (cel lights), a colour-changing tile (paint), the stack
                 lights and the background.

Every scene in scenes/ is compiled to a stream and compared with its JSON by the tests
(tests/test_scenes.c, tests/cli_stream.sh), so these exist to put every record and track
kind of the cel stream through that comparison. The JSON is the artefact; this script is
how it was drawn."""
import json, math, os, re, sys

R2 = 0.70710678  # sqrt(1/2) to float precision: the corner weight of an exact circle


def rnd(v, nd=3):
    v = round(v, nd)
    return int(v) if v == int(v) else v


def circle(r, cx=0.0, cy=0.0):
    pts = []
    for k in range(8):
        a = k * math.pi / 4
        if k % 2 == 0:
            pts.append([rnd(cx + r * math.cos(a)), rnd(cy + r * math.sin(a))])
        else:
            pts.append([rnd(cx + r * math.copysign(1, math.cos(a))),
                        rnd(cy + r * math.copysign(1, math.sin(a))), R2])
    return {"degree": 2, "points": pts, "intervals": [1, 0] * 4}


def polygon(pts):
    return {"degree": 1, "points": [[rnd(x), rnd(y)] for x, y in pts]}


def rounded_rect(x0, y0, x1, y1, r):
    k = 0.5523 * r
    def line(a, b):
        return [a, (a[0] + (b[0] - a[0]) / 3, a[1] + (b[1] - a[1]) / 3),
                (a[0] + 2 * (b[0] - a[0]) / 3, a[1] + 2 * (b[1] - a[1]) / 3)]
    segs = [line((x0 + r, y0), (x1 - r, y0)), [(x1 - r, y0), (x1 - r + k, y0), (x1, y0 + r - k)],
            line((x1, y0 + r), (x1, y1 - r)), [(x1, y1 - r), (x1, y1 - r + k), (x1 - r + k, y1)],
            line((x1 - r, y1), (x0 + r, y1)), [(x0 + r, y1), (x0 + r - k, y1), (x0, y1 - r + k)],
            line((x0, y1 - r), (x0, y0 + r)), [(x0, y0 + r), (x0, y0 + r - k), (x0 + r - k, y0)]]
    pts = [[rnd(x), rnd(y)] for seg in segs for x, y in seg]
    return {"degree": 3, "points": pts, "intervals": [1, 0, 0] * 8}


def star(n, r_out, r_in, cx=0.0, cy=0.0, phase=-90):
    pts = []
    for k in range(2 * n):
        a = math.radians(phase + k * 180 / n)
        r = r_out if k % 2 == 0 else r_in
        pts.append((cx + r * math.cos(a), cy + r * math.sin(a)))
    return pts


def rot(deg, cx, cy, s=1.0):
    a = math.radians(deg)
    c, si = s * math.cos(a), s * math.sin(a)
    return [rnd(c, 5), rnd(si, 5), rnd(-si, 5), rnd(c, 5), cx, cy]


def beta_csg():
    cels = []
    # Front to back. A gel slides across everything, lit from behind.
    cels.append({
        "name": "gel",
        "transform": [1, 0, 0, 1, 20, 120],
        "lights": {"back": [0.9, 0.9, 0.9]},
        "animate": {"transform": {"keys": [[0, [1, 0, 0, 1, 20, 120]], [3, [1, 0, 0, 1, 220, 120]]],
                                  "ease": "smooth"}},
        "regions": [{"paint": {"pigment": "#000000", "beta": 0,
                               "medium": {"map": [0, 0, 80, 0, 0, 60], "cols": 2,
                                          "values": ["#ff6060", "#60ff60", "#6060ff", "#ffff80"]}},
                     "contours": [rounded_rect(0, 0, 80, 60, 12)]}],
    })
    # A CSG emblem: a ring (two circles in operand 0, evenodd) minus a bar, plus a dot.
    cels.append({
        "name": "emblem",
        "transform": [1, 0, 0, 1, 250, 60],
        "regions": [{"fill_rule": "evenodd", "paint": {"pigment": "#f2f2f2"},
                     "csg": [0, 1, "difference", 2, "union"], "operands": [0, 0, 1, 2],
                     "contours": [circle(40), circle(26), polygon([(-50, -6), (50, -6), (50, 6), (-50, 6)]),
                                  circle(9)]}],
    })
    # A sun: radial pigment, and a radial beta that feathers its edge into the sky.
    cels.append({
        "name": "sun",
        "transform": [1, 0, 0, 1, 90, 70],
        "regions": [{"paint": {"pigment": {"radial": [0, 0, 50, -12, -12],
                                           "stops": [[0, "#fff6c0"], [0.6, "#ffb040"], [1, "#ff6020"]]},
                               "medium": "#ff8040",
                               "beta": {"radial": [0, 0, 50], "stops": [[0, 1], [0.7, 1], [1, 0]]}},
                     "animate": {"paint": {"keys": [[0, {"medium": "#ff8040"}], [3, {"medium": "#4060ff"}]]}},
                     "contours": [circle(50)]}],
    })
    # A soft hold-out matte: 60% of what is behind is held out.
    cels.append({
        "name": "matte",
        "regions": [{"paint": {"pigment": "#000000", "beta": 0.6},
                     "contours": [rounded_rect(150, 130, 310, 170, 8)]}],
    })
    # A hill with a linear gradient, reflected.
    cels.append({
        "name": "hill",
        "regions": [{"paint": {"pigment": {"linear": [0, 110, 0, 200], "spread": "reflect",
                                           "stops": [[0, "#2a7f62"], [0.5, "#5fbf7f"], [1, "#1b4d3e"]]}},
                     "contours": [{"degree": 3, "points": [[-10, 140], [60, 100], [140, 100], [200, 135],
                                                           [240, 160], [300, 110], [330, 130],
                                                           [340, 180], [340, 210], [170, 210],
                                                           [-10, 210], [-10, 180]],
                                   "intervals": [1, 0, 0] * 4}]}],
    })
    return {
        "note": "generated by tools/gen_test_scenes.py",
        "canvas": {"width": 320, "height": 200, "background": "#1a1a30"},
        "lights": {"front": [1, 1, 1], "back": [0, 0, 0]},
        "animate": {"lights": {"keys": [[0, {"front": [1, 1, 1]}], [3, {"front": [0.7, 0.7, 0.95]}]],
                               "ease": "smooth"},
                    "background": {"keys": [[0, "#1a1a30"], [3, "#402040"]]}},
        "cels": cels,
    }


def motion():
    cels = []
    star_pts = star(5, 40, 17)
    cels.append({
        "name": "spinner",
        "transform": rot(0, 70, 60),
        # A key every 30 degrees: transforms blend entry by entry, so a turn needs
        # keys close enough that the blend of two rotations is nearly one (cos 15°).
        "animate": {"transform": {"keys": [[rnd(k / 4), rot(30 * k, 70, 60, 1 + 0.2 * math.sin(k * math.pi / 6))]
                                           for k in range(13)]}},
        "regions": [{"paint": {"pigment": "#ffd166"}, "contours": [polygon(star_pts)]}],
    })
    octagon = [(34 * math.cos(math.radians(k * 45)), 34 * math.sin(math.radians(k * 45))) for k in range(8)]
    spiky = star(4, 44, 14, phase=0)
    cels.append({
        "name": "morph",
        "transform": [1, 0, 0, 1, 170, 60],
        "regions": [{"paint": {"pigment": "#ef476f", "beta": 0.85, "medium": "#ffd0dc"},
                     "contours": [{"degree": 2, "points": [[rnd(x), rnd(y)] for x, y in octagon],
                                   "animate": {"points": {"ease": "smooth", "keys": [
                                       [0, [[rnd(x), rnd(y)] for x, y in octagon]],
                                       [1.5, [[rnd(x), rnd(y), 1 + (k % 2)] for k, (x, y) in enumerate(spiky)]],
                                       [3, [[rnd(x), rnd(y)] for x, y in octagon]]]}}}]}],
    })
    cels.append({
        "name": "lamp",
        "transform": [1, 0, 0, 1, 260, 60],
        "lights": {"front": [1, 1, 1], "back": [0.2, 0.2, 0.2]},
        "animate": {"lights": {"ease": "smooth", "keys": [
            [0, {"front": [1, 1, 1], "back": [0.2, 0.2, 0.2]}],
            [1, {"front": [1.6, 1.3, 0.6]}],
            [2.5, {"front": [0.3, 0.4, 1.2], "back": [1, 0.9, 0.5]}]]}},
        "regions": [{"paint": {"pigment": "#06d6a0", "beta": 0.5, "medium": "#d0fff0"},
                     "contours": [circle(36)]}],
    })
    cels.append({
        "name": "tile",
        "regions": [{"paint": {"pigment": "#e63946", "beta": 1},
                     "animate": {"paint": {"keys": [[0, {"pigment": "#e63946"}],
                                                    [1.5, {"pigment": "#2a9d8f", "beta": 0.4}],
                                                    [3, {"pigment": "#457b9d", "beta": 1}]]}},
                     "contours": [rounded_rect(40, 115, 280, 165, 14)]}],
    })
    return {
        "note": "generated by tools/gen_test_scenes.py",
        "canvas": {"width": 320, "height": 180, "background": "#101820"},
        "lights": {"front": [1, 1, 1], "back": [0, 0, 0]},
        "animate": {"lights": {"keys": [[0, {"front": [1, 1, 1]}], [1.5, {"front": [0.6, 0.6, 0.6]}],
                                        [3, {"front": [1, 1, 1]}]]},
                    "background": {"ease": "smooth", "keys": [[0, "#101820"], [3, "#283850"]]}},
        "cels": cels,
    }


def dump(scene):
    text = json.dumps(scene, indent=2)
    # One line per numeric array and per array of points or keys.
    num_arr = r"\[[\s\d.,\-e]*\]"
    text = re.sub(num_arr, lambda m: re.sub(r"\s+", " ", m.group(0)).replace("[ ", "[").replace(" ]", "]"), text)
    text = re.sub(r"\[(\s*\[[\d.,\- e]*\],?)+\s*\]",
                  lambda m: re.sub(r"\s+", " ", m.group(0)).replace("[ ", "[").replace(" ]", "]"), text)
    return text + "\n"


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes"
    for name, scene in (("beta-csg.json", beta_csg()), ("motion.json", motion())):
        with open(os.path.join(out, name), "w") as f:
            f.write(dump(scene))
