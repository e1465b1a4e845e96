#!/usr/bin/python3
"""Checks tools/curvature-map.py: mean curvature on surfaces with a known answer, the sign
convention, and the image it writes.

usage: tests/tools/curvature_map.py TOOL WORKDIR
"""
import importlib.util, struct, sys, zlib
from pathlib import Path

import numpy as np

spec = importlib.util.spec_from_file_location("curvature_map", sys.argv[1])
tool = importlib.util.module_from_spec(spec)
spec.loader.exec_module(tool)
work = Path(sys.argv[2])
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def icosphere(radius, levels):
    t = (1 + 5 ** 0.5) / 2
    V = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    V = [np.array(v, float) / np.linalg.norm(v) for v in V]
    F = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8),
         (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        mid = {}

        def middle(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                m = V[a] + V[b]
                V.append(m / np.linalg.norm(m))
                mid[key] = len(V) - 1
            return mid[key]
        F = [f for a, b, c in F for f in ((a, middle(a, b), middle(c, a)), (b, middle(b, c), middle(a, b)),
                                           (c, middle(c, a), middle(b, c)), (middle(a, b), middle(b, c), middle(c, a)))]
    return radius * np.array(V), np.array(F, dtype=np.int32)


def grey_rows(png, size):
    """The grey levels of the tool's size-by-size 8-bit PNG (one IDAT chunk, filter byte 0)."""
    idat = png[png.index(b"IDAT") + 4:png.index(b"IEND") - 8]
    return np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(size, size + 1)[:, 1:]


def write_ply(path, V, F):
    header = (f"ply\nformat binary_little_endian 1.0\nelement vertex {len(V)}\nproperty float x\nproperty float y\n"
              f"property float z\nelement face {len(F)}\nproperty list uchar int vertex_indices\nend_header\n")
    body = V.astype("<f4").tobytes() + b"".join(struct.pack("<B3i", 3, *map(int, f)) for f in F)
    path.write_bytes(header.encode() + body)


# A sphere of radius 40 mm, outward (counter-clockwise) triangles: H = 1/40 everywhere, convex.
V, F = icosphere(40.0, 4)
H, N = tool.mean_curvature(V, F)
check(np.allclose(np.linalg.norm(N, axis=1), 1) and (np.einsum("ij,ij->i", N, V) > 0).all(), "sphere: unit outward normals")
check(np.abs(H - 1 / 40).max() < 0.02 / 40, f"sphere r 40: H within 2% of 1/40 (worst {np.abs(H - 1 / 40).max() * 40:.4f} of it)")
H_in, _ = tool.mean_curvature(V, F[:, ::-1])
check(np.abs(H_in + 1 / 40).max() < 0.02 / 40, "sphere seen from inside (triangles reversed): H = -1/40, concave")

# A plane, unevenly sampled: H = 0 at every interior vertex.
xs = np.cumsum(np.r_[0, np.linspace(0.5, 3, 19)])
gx, gy = np.meshgrid(xs, xs)
P = np.stack([gx.ravel(), gy.ravel(), np.zeros(gx.size)], 1)
n = len(xs)
quads = [(i * n + j, i * n + j + 1, (i + 1) * n + j + 1, (i + 1) * n + j) for i in range(n - 1) for j in range(n - 1)]
T = np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))], dtype=np.int32)
Hp, _ = tool.mean_curvature(P, T)
interior = np.array([0 < k // n < n - 1 and 0 < k % n < n - 1 for k in range(len(P))])
check(np.abs(Hp[interior]).max() < 1e-9, "uneven plane: H = 0 inside")

# The tool end to end: a dataset folder of two spheres; the mean of both is the sphere of 40 mm.
faces = work / "spheres" / "faces"
faces.mkdir(parents=True, exist_ok=True)
write_ply(faces / "a.ply", V * 0.75, F)
write_ply(faces / "b.ply", V * 1.25, F)
out = work / "spheres.png"
sys.argv = ["curvature-map.py", str(work / "spheres"), "-o", str(out), "--faces", "2", "--size", "64", "--clip", "0.05"]
tool.main()
data = out.read_bytes()
check(data[:8] == b"\x89PNG\r\n\x1a\n", "writes a PNG")
w, h, depth, colour = struct.unpack(">IIBB", data[16:26])
check((w, h, depth, colour) == (64, 64, 8, 0), f"64 by 64, 8-bit grey (found {w} by {h}, {depth} bits, colour type {colour})")
rows = grey_rows(data, 64)
# H = 1/40 over a clip of 0.05: 128 - 127 * 0.5 = 64.5 at the centre; the background stays 128.
check(abs(int(rows[32, 32]) - 64) <= 1, f"the sphere's centre is drawn at H / clip (grey {rows[32, 32]}, expected 64)")
check(rows[0, 0] == 128, "the background is grey 128")

# Views as `facesketch` names them: the eye goes onto +z, world y stays up in the image.
for view, eye in (("profile", (1, 0, 0)), ("34", (0.5 ** 0.5, 0, 0.5 ** 0.5)), ("0,-60", (0, -(0.75 ** 0.5), 0.5)), ("front", (0, 0, 1))):
    R = tool.view_rotation(view)
    check(np.allclose(R @ np.array(eye), (0, 0, 1)) and (R @ np.array((0, 1, 0)))[1] > 0, f"view {view}: the eye onto +z, y up")
for bad in ("sideways", "1,2,3", "0,95", "nan,0", ""):
    try:
        tool.view_rotation(bad)
        check(False, f"view '{bad}' refused")
    except SystemExit as e:
        check("expected front, profile, 34 or AZ,EL" in str(e), f"view '{bad}' refused with a message naming the forms")

# A sphere looks the same from every side: its centre keeps H / clip from the profile too.
sys.argv = ["curvature-map.py", str(work / "spheres"), "-o", str(out), "--faces", "2", "--size", "64", "--clip", "0.05", "--view", "profile"]
tool.main()
rows = grey_rows(out.read_bytes(), 64)
check(abs(int(rows[32, 32]) - 64) <= 1, f"from the profile the sphere's centre is drawn at H / clip (grey {rows[32, 32]})")

# A plane facing +z has no triangle facing the profile view: a clear error, no image.
plane = work / "plane" / "faces"
plane.mkdir(parents=True, exist_ok=True)
write_ply(plane / "p.ply", P, T)
side = work / "plane-side.png"
sys.argv = ["curvature-map.py", str(work / "plane"), "-o", str(side), "--view", "profile"]
try:
    tool.main()
    check(False, "a plane seen edge-on is refused")
except SystemExit as e:
    check("no triangle faces the view" in str(e) and not side.exists(), "a plane seen edge-on is refused, no image written")

sys.exit(1 if failures else 0)
