#!/usr/bin/python3
"""A front view of a face's mean curvature, as a grey image: the diagnostic that shows where a
surface bends (issue 16, docs/realism.md "Curvature maps").

Shading hides much of a surface's shape and shows some of it too strongly (a lit crease reads as
a line); mean curvature shows every fold, ridge and plateau edge with the same weight, whatever
the light. Two surfaces that are close in millimetres can still bend very differently: this is
where the synthetic faces' grid-aligned structure (straight bands of curvature along the
generator's rows and columns) shows, while `facesketch eval realism` sees it only as a few
tenths of a millimetre.

Mean curvature H per vertex: the cotangent Laplacian of the positions along the vertex normal,
over the vertex's mixed Voronoi area (Meyer et al. 2003), so it does not depend on how densely or
evenly the mesh is sampled. Convex (a ridge, the nose's dorsum) is H > 0 and drawn dark;
concave (a valley, the eye's inner corner) is H < 0 and drawn light; grey is flat. The grey
levels saturate at +-CLIP (1/mm).

The image is an orthographic view, each triangle filled with its corners' values interpolated,
nearest surface in front; only triangles whose normal has a component towards the viewer above
0.2 are drawn (the rest are seen edge-on). --view names it as `facesketch` does (front,
profile, 34, or AZ,EL in degrees: the eye at (sin AZ cos EL, sin EL, cos AZ cos EL), y up), so
e.g. 0,-60 shows a nose's underside; the default is the front view (x right, y up, looking
along -z).

DATASET is a dataset folder (its `faces/*.ply`, binary little-endian as `facesketch` writes
them); the image is of the mean of its first N faces (default 1: the first face itself, in
file-name order), or of one sample with --sample.

usage: tools/curvature-map.py DATASET -o OUT.png [--faces N | --sample NAME] [--view V] [--clip C] [--size PX]
"""
import argparse, re, struct, sys, zlib
from pathlib import Path

import numpy as np


def read_ply(path):
    """Vertices (n, 3) and triangles (m, 3) of a binary little-endian PLY as facesketch writes it."""
    data = Path(path).read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode()
    if "binary_little_endian" not in header:
        sys.exit(f"{path}: not a binary little-endian PLY")
    nv = int(re.search(r"element vertex (\d+)", header).group(1))
    nf = int(re.search(r"element face (\d+)", header).group(1))
    vertex_part = header[header.index("element vertex"):header.index("element face")]
    props = len(re.findall(r"^property float ", vertex_part, re.M))
    if props != len(re.findall(r"^property ", vertex_part, re.M)):
        sys.exit(f"{path}: vertex properties other than float")
    if not re.search(r"property list uchar (int|uint) vertex_indices", header):
        sys.exit(f"{path}: faces are not lists of uchar count and int indices")
    V = np.frombuffer(data, dtype="<f4", count=props * nv, offset=end).reshape(nv, props)[:, :3].astype(np.float64)
    raw = np.frombuffer(data, dtype=np.uint8, count=13 * nf, offset=end + 4 * props * nv).reshape(nf, 13)
    if (raw[:, 0] != 3).any():
        sys.exit(f"{path}: a face that is not a triangle")
    F = raw[:, 1:].copy().view("<i4").reshape(nf, 3)
    return V, F


def mean_curvature(V, F):
    """Per vertex: H (1/mm, convex positive) and the unit normal (area-weighted, outward for
    counter-clockwise triangles)."""
    n = len(V)
    face_normal = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    N = np.zeros_like(V)
    for k in range(3):
        np.add.at(N, F[:, k], face_normal)
    N /= np.linalg.norm(N, axis=1)[:, None] + 1e-12
    laplacian = np.zeros_like(V)
    triangle_area = np.linalg.norm(face_normal, axis=1) / 2
    cots, edges2, obtuse = [], [], np.zeros((len(F), 3), bool)
    for c, (i, j, k) in enumerate([(0, 1, 2), (1, 2, 0), (2, 0, 1)]):
        u, w = V[F[:, j]] - V[F[:, i]], V[F[:, k]] - V[F[:, i]]
        cot = (u * w).sum(1) / (np.linalg.norm(np.cross(u, w), axis=1) + 1e-12)  # angle at i, opposite edge j-k
        obtuse[:, c] = cot < 0
        cots.append(cot)
        edges2.append(((u * u).sum(1), (w * w).sum(1)))  # squared lengths of corner i's edges to j and k
        d = V[F[:, k]] - V[F[:, j]]
        np.add.at(laplacian, F[:, j], cot[:, None] * d)
        np.add.at(laplacian, F[:, k], -cot[:, None] * d)
    # The mixed Voronoi area of each vertex (Meyer et al. 2003): with one third of the triangles'
    # areas instead, a sphere's H is off by up to 15% at the vertices of valence 5.
    area = np.zeros(n)
    any_obtuse = obtuse.any(1)
    for c in range(3):
        # Corner c's Voronoi part: its two edges, each times the cotangent of the angle opposite.
        to_j, to_k = edges2[c]
        voronoi = to_j * cots[(c + 2) % 3] + to_k * cots[(c + 1) % 3]
        part = np.where(any_obtuse, np.where(obtuse[:, c], triangle_area / 2, triangle_area / 4), voronoi / 8)
        np.add.at(area, F[:, c], part)
    # Summed over a vertex's edges, the cotangent weights give -4 H n A (A: the vertex's area;
    # outward n, convex H > 0), since the Laplace-Beltrami operator of the position is -2 H n.
    H = -(laplacian * N).sum(1) / (4 * np.maximum(area, 1e-12))
    return H, N


def view_rotation(text):
    """The rotation that turns the view `text` (front, profile, 34 or AZ,EL in degrees, as
    `facesketch` parses it) into the front view: the eye onto +z, world y up in the image."""
    named = {"front": (0.0, 0.0), "profile": (90.0, 0.0), "34": (45.0, 0.0)}
    try:
        az, el = named[text] if text in named else (float(a) for a in text.split(","))
    except ValueError:
        az, el = np.nan, 0.0
    if not (np.isfinite(az) and np.isfinite(el) and abs(el) <= 90):
        sys.exit(f"view '{text}': expected front, profile, 34 or AZ,EL in degrees with |EL| <= 90")
    a, e = np.radians(az), np.radians(el)
    turn = np.array([[np.cos(a), 0, -np.sin(a)], [0, 1, 0], [np.sin(a), 0, np.cos(a)]])  # about y by -AZ
    tilt = np.array([[1, 0, 0], [0, np.cos(e), -np.sin(e)], [0, np.sin(e), np.cos(e)]])  # about x by EL
    return tilt @ turn


def raster(V, F, values, facing, size):
    """Grey levels (size by size) of `values` over the front view, nearest surface in front."""
    drawn = facing[F].all(1)
    if not drawn.any():
        sys.exit("no triangle faces the view")
    x, y = V[:, 0], V[:, 1]
    used = np.unique(F[drawn])
    x0, x1, y0, y1 = x[used].min(), x[used].max(), y[used].min(), y[used].max()
    scale = (size - 20) / max(x1 - x0, y1 - y0)
    P = np.stack([(x - x0) * scale + 10 + ((size - 20) - (x1 - x0) * scale) / 2, (y1 - y) * scale + 10], 1)
    image = np.full((size, size), 128.0)
    depth = np.full((size, size), -np.inf)
    for t in F[drawn]:
        a, b, c = P[t]
        lo = np.floor(np.minimum(np.minimum(a, b), c)).astype(int).clip(0, size - 1)
        hi = np.ceil(np.maximum(np.maximum(a, b), c)).astype(int).clip(0, size - 1)
        det = (b[1] - c[1]) * (a[0] - c[0]) + (c[0] - b[0]) * (a[1] - c[1])
        if abs(det) < 1e-12:
            continue
        gx, gy = np.meshgrid(np.arange(lo[0], hi[0] + 1) + 0.5, np.arange(lo[1], hi[1] + 1) + 0.5)
        l0 = ((b[1] - c[1]) * (gx - c[0]) + (c[0] - b[0]) * (gy - c[1])) / det
        l1 = ((c[1] - a[1]) * (gx - c[0]) + (a[0] - c[0]) * (gy - c[1])) / det
        l2 = 1 - l0 - l1
        inside = (l0 >= -1e-9) & (l1 >= -1e-9) & (l2 >= -1e-9)
        z = l0 * V[t[0], 2] + l1 * V[t[1], 2] + l2 * V[t[2], 2]
        v = l0 * values[t[0]] + l1 * values[t[1]] + l2 * values[t[2]]
        d = depth[lo[1]:hi[1] + 1, lo[0]:hi[0] + 1]
        im = image[lo[1]:hi[1] + 1, lo[0]:hi[0] + 1]
        inside &= z > d
        d[inside] = z[inside]
        im[inside] = v[inside]
    return image


def write_png(path, grey):
    """An 8-bit greyscale PNG (zlib and the PNG chunk layout only; no imaging library needed)."""
    rows = b"".join(b"\x00" + row.tobytes() for row in grey.astype(np.uint8))
    h, w = grey.shape

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    Path(path).write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0))
                           + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("dataset")
    ap.add_argument("-o", "--output", required=True, help="PNG to write")
    ap.add_argument("--faces", type=int, default=1, help="mean of the first N faces (default 1)")
    ap.add_argument("--sample", help="one sample by name (faces/NAME.ply) instead")
    ap.add_argument("--view", default="front", help="front, profile, 34 or AZ,EL in degrees (default front)")
    ap.add_argument("--clip", type=float, default=0.06, help="|H| (1/mm) drawn black or white (default 0.06)")
    ap.add_argument("--size", type=int, default=600, help="image width and height, pixels (default 600)")
    args = ap.parse_args()
    if args.faces < 1 or args.clip <= 0 or args.size < 32:
        sys.exit("--faces must be >= 1, --clip > 0 and --size >= 32")
    R = view_rotation(args.view)
    folder = Path(args.dataset) / "faces"
    files = [folder / f"{args.sample}.ply"] if args.sample else sorted(folder.glob("*.ply"))[:args.faces]
    if not files or not files[0].exists():
        sys.exit(f"{folder}: no such face ({args.sample or '*.ply'})")
    V, F = read_ply(files[0])
    for f in files[1:]:
        W, G = read_ply(f)
        if W.shape != V.shape or not np.array_equal(G, F):
            sys.exit(f"{f}: not the topology of {files[0]}")
        V = V + W
    V /= len(files)
    if not np.isfinite(V).all():
        sys.exit(f"{folder}: a non-finite coordinate")
    H, N = mean_curvature(V, F)
    grey = 128 - 127 * np.clip(H / args.clip, -1, 1)
    write_png(args.output, raster(V @ R.T, F, grey, (N @ R.T)[:, 2] > 0.2, args.size))
    print(f"{args.output}: {len(files)} face(s) of {folder}, {len(V)} vertices, view {args.view}; H in 1/mm, clipped at +-{args.clip}")


if __name__ == "__main__":
    main()
