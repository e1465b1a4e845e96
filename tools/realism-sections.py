#!/usr/bin/python3
"""Cross-sections of mean faces through the lower nose, for calibrating the synthetic
generator's nose (issue 16, docs/realism.md "v20").

Each DATA set's mean skin is moved onto the REFERENCE's by the similarity on their shared
landmarks, as tools/realism-landmarks.py does, and the mean skins are cut by planes placed
relative to the reference's sn: three sagittal planes (x = 0.7, 8 and 16 mm: the midline beside
the columella, the nostril, the ala) and two horizontal ones (6 and 10 mm above sn). The figure
draws the reference in red and the data sets in grey, blue and green, in that order, on a 5 mm
grid. The table prints, for the sagittal planes x = 10, 13, 16 and 19 mm, how far forward of sn
each mean skin reaches at heights from 4 mm below sn to 20 mm above it: the numbers the alar
lobule's constants were set from (face_shape.cpp).

A section of a mean face is a picture of it, as the renders in docs/images are; nothing is
written but the PNG.

usage: tools/realism-sections.py REFERENCE DATA [DATA ...] -o OUT.png [--table]
"""
import argparse, importlib.util
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw

_spec = importlib.util.spec_from_file_location("realism_landmarks", Path(__file__).with_name("realism-landmarks.py"))
rl = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(rl)

COLOURS = [(210, 0, 0), (150, 150, 150), (0, 0, 210), (0, 150, 0)]
PANEL, SPAN = 360, 44.0  # pixels and mm per panel


def aligned_mean(folder, ref_names, ref_landmarks):
    """The mean skin of `folder` moved onto the reference's landmarks, and its triangles."""
    names, L = rl.load(folder)
    V, F = rl.load_mean(folder)
    shared = [n for n in names if n in ref_names and not n.startswith("obs")]
    s, R, t = rl.umeyama(L.mean(0)[[names.index(n) for n in shared]], ref_landmarks[[ref_names.index(n) for n in shared]])
    return (s * (R @ V.T)).T + t, F


def section(V, F, axis, value):
    """Segments where the plane coordinate[axis] = value cuts the triangles."""
    T = V[F]
    c = T[:, :, axis] - value
    crossing = ~((c > 0).all(1) | (c < 0).all(1))
    segments = []
    for t, cc in zip(T[crossing], c[crossing]):
        points = [t[i] + cc[i] / (cc[i] - cc[(i + 1) % 3]) * (t[(i + 1) % 3] - t[i]) for i in range(3) if (cc[i] > 0) != (cc[(i + 1) % 3] > 0)]
        if len(points) == 2:
            segments.append(points)
    return segments


def reach(V, F, x, y):
    """The largest z of the sagittal section x at height y (the skin's front)."""
    best = -np.inf
    for a, b in section(V, F, 0, x):
        if (a[1] - y) * (b[1] - y) <= 0 and a[1] != b[1]:
            best = max(best, a[2] + (y - a[1]) / (b[1] - a[1]) * (b[2] - a[2]))
    return best


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("reference")
    ap.add_argument("data", nargs="+")
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--table", action="store_true", help="also print how far forward of sn each skin reaches")
    args = ap.parse_args()
    if len(args.data) > len(COLOURS) - 1:
        ap.error(f"at most {len(COLOURS) - 1} data sets")
    ref_names, ref_L = rl.load(args.reference)
    ref_landmarks = ref_L.mean(0)
    sets = [rl.load_mean(args.reference)] + [aligned_mean(d, ref_names, ref_landmarks) for d in args.data]
    sn = ref_landmarks[ref_names.index("sn")]

    planes = [(0, 0.7, "x = 0.7 mm"), (0, 8.0, "x = 8 mm"), (0, 16.0, "x = 16 mm"), (1, sn[1] + 6, "y = sn + 6 mm"), (1, sn[1] + 10, "y = sn + 10 mm")]
    scale = PANEL / SPAN
    out = Image.new("RGB", (PANEL * len(planes), PANEL), "white")
    for k, (axis, value, label) in enumerate(planes):
        img = Image.new("RGB", (PANEL, PANEL), "white")
        d = ImageDraw.Draw(img)
        u, v = (2, 1) if axis == 0 else (0, 2)  # sagittal: z right, y up; horizontal: x right, z up
        cu, cv = sn[u], sn[v] if axis == 0 else sn[v] - 8
        for g in range(-20, 21, 5):
            d.line((PANEL / 2 + scale * g, 0, PANEL / 2 + scale * g, PANEL), fill=(232, 232, 232))
            d.line((0, PANEL / 2 - scale * g, PANEL, PANEL / 2 - scale * g), fill=(232, 232, 232))
        for (V, F), colour in zip(sets, COLOURS):
            for a, b in section(V, F, axis, value):
                d.line((PANEL / 2 + scale * (a[u] - cu), PANEL / 2 - scale * (a[v] - cv), PANEL / 2 + scale * (b[u] - cu),
                        PANEL / 2 - scale * (b[v] - cv)), fill=colour, width=2)
        d.text((6, 6), label, fill="black")
        out.paste(img, (k * PANEL, 0))
    out.save(args.output, optimize=True)

    if args.table:
        heights = np.arange(-4, 21, 2.0)
        print("forward of the reference's sn (mm) at heights above it; rows: reference, then each data set")
        print("        y " + "".join(f"{h:6.0f}" for h in heights))
        for x in (10, 13, 16, 19):
            for k, (V, F) in enumerate(sets):
                row = [reach(V, F, x, sn[1] + h) - sn[2] for h in heights]
                print(f"x {x:2d} {'ref' if k == 0 else 'd' + str(k):>4} " + "".join(f"{z:6.1f}" for z in row))


if __name__ == "__main__":
    main()
