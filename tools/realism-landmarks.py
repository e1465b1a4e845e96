#!/usr/bin/python3
"""Landmark statistics of two datasets, for calibrating the synthetic generator (issue 16,
docs/realism.md): the proportions part of `facesketch eval realism`.

For each dataset: the mean landmark positions over every sample (skin landmarks of the
manifest) and, per sex-free population, the mean and SD of the Farkas distances
(face_params.cpp's list) and of a few profile depths. The DATA mean landmarks are moved onto
the REFERENCE's by the least-squares similarity (Umeyama) on the shared central landmarks, as
`eval realism` does (obs_l/_r left out), and each landmark's residual (reference minus data,
in the reference's frame and mm: x to the face's left, y up, z forward) is printed.

Only statistics are printed (a few dozen numbers: means and SDs of landmark positions and
distances); nothing is written. These numbers are what the generator's parameters may be set
from (issue 16 forbids committing anything derived from ICT vertex by vertex).

usage: tools/realism-landmarks.py DATA REFERENCE [--json OUT]
"""
import argparse, json, re
from pathlib import Path

import numpy as np

FARKAS = [("ex-ex", "ex_r", "ex_l"), ("en-en", "en_r", "en_l"), ("al-al", "al_r", "al_l"), ("ch-ch", "ch_r", "ch_l"),
          ("n-gn", "n", "gn"), ("n-sn", "n", "sn"), ("sn-sto", "sn", "sto"), ("sto-gn", "sto", "gn"), ("ps-pi", "ps_r", "pi_r"),
          ("os-ex (brow)", "os_r", "ex_r"), ("g-n", "g", "n"), ("n-prn", "n", "prn"), ("sn-prn", "sn", "prn"), ("ls-li", "ls", "li")]


def read_vertices(path, count):
    data = Path(path).read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode()
    assert "binary_little_endian" in header and "property float x" in header, path
    nv = int(re.search(r"element vertex (\d+)", header).group(1))
    assert nv >= count, path
    return np.frombuffer(data, dtype="<f4", count=3 * nv, offset=end).reshape(nv, 3)[:count].astype(np.float64)


def load(folder):
    folder = Path(folder)
    m = json.loads((folder / "manifest.json").read_text())
    units = {"mm": 1.0, "cm": 10.0, "m": 1000.0}[m.get("units", "mm")]
    skin_begin, skin_end = m["components"]["skin"]
    names = sorted(k for k, v in m["landmarks"].items() if skin_begin <= v < skin_end)
    idx = [m["landmarks"][k] for k in names]
    L = np.stack([read_vertices(folder / s["file"], skin_end)[idx] for s in m["samples"]]) * units
    return names, L  # samples x landmarks x 3


def load_mean(folder):
    folder = Path(folder)
    m = json.loads((folder / "manifest.json").read_text())
    units = {"mm": 1.0, "cm": 10.0, "m": 1000.0}[m.get("units", "mm")]
    skin_end = m["components"]["skin"][1]
    mean = sum(read_vertices(folder / s["file"], skin_end) for s in m["samples"]) / len(m["samples"]) * units
    F = np.array([t for t in m["topology"] if max(t) < skin_end])
    return mean, F


def vertex_normals(V, F):
    n = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    N = np.zeros_like(V)
    for k in range(3):
        np.add.at(N, F[:, k], n)
    return N / np.maximum(np.linalg.norm(N, axis=1, keepdims=True), 1e-12)


def signed_map(args, s, R, t):
    """Signed distance from each reference mean skin vertex to the nearest data mean vertex, along
    the reference normal (+: the data is in front), averaged in 10 mm cells of the front view."""
    DV, _ = load_mean(args.data)
    RV, RF = load_mean(args.reference)
    DV = (s * (R @ DV.T)).T + t
    N = vertex_normals(RV, RF)
    d = np.empty(len(RV))
    for a in range(0, len(RV), 500):
        q = RV[a:a + 500]
        k = np.argmin(((q[:, None, :] - DV[None, :, :]) ** 2).sum(2), axis=1)
        d[a:a + 500] = ((DV[k] - q) * N[a:a + 500]).sum(1)
    print("\nsigned distance, data minus reference along the reference normal (mm), mean per 10 mm cell; rows y, columns x")
    xs = np.arange(-55, 56, 10)
    print("   y\\x " + "".join(f"{x:6d}" for x in xs))
    for y in range(85, -86, -10):
        row = []
        for x in xs:
            sel = (np.abs(RV[:, 0] - x) <= 5) & (np.abs(RV[:, 1] - y) <= 5) & (N[:, 2] > 0.2)
            row.append(f"{d[sel].mean():6.1f}" if sel.sum() >= 3 else "     .")
        print(f"{y:6d} " + "".join(row))
    print("\nmidline profile (|x| < 1.5 mm), signed distance by height:")
    for y in range(80, -86, -5):
        sel = (np.abs(RV[:, 0]) < 1.5) & (np.abs(RV[:, 1] - y) <= 2.5) & (N[:, 2] > 0)
        if sel.sum():
            print(f"  y {y:4d}: {d[sel].mean():6.2f}  (reference z {RV[sel, 2].mean():6.1f})")


def umeyama(src, dst):
    ms, md = src.mean(0), dst.mean(0)
    a, b = src - ms, dst - md
    U, S, Vt = np.linalg.svd(b.T @ a / len(src))
    D = np.eye(3)
    if np.linalg.det(U) * np.linalg.det(Vt) < 0:
        D[2, 2] = -1
    R = U @ D @ Vt
    s = np.trace(np.diag(S) @ D) / (a ** 2).sum(1).mean()
    return s, R, md - s * R @ ms


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("data")
    ap.add_argument("reference")
    ap.add_argument("--json")
    ap.add_argument("--map", action="store_true", help="also print a signed distance map of the mean skins")
    args = ap.parse_args()
    dn, DL = load(args.data)
    rn, RL = load(args.reference)
    shared = [n for n in dn if n in rn and not n.startswith("obs")]
    di = [dn.index(n) for n in shared]
    ri = [rn.index(n) for n in shared]
    dm, rm = DL.mean(0)[di], RL.mean(0)[ri]
    s, R, t = umeyama(dm, rm)
    moved = (s * (R @ dm.T)).T + t
    res = rm - moved
    out = {"scale": s, "landmark_rms_mm": float(np.sqrt((res ** 2).sum(1).mean())), "residual_mm": {}, "distances": {}}
    print(f"similarity scale {s:.4f}, landmark RMS {out['landmark_rms_mm']:.2f} mm over {len(shared)} landmarks")
    print(f"{'landmark':8} {'dx':>6} {'dy':>6} {'dz':>6}   (reference - data, mm, reference frame)")
    for k, n in enumerate(shared):
        print(f"{n:8} {res[k, 0]:6.2f} {res[k, 1]:6.2f} {res[k, 2]:6.2f}")
        out["residual_mm"][n] = res[k].tolist()
    print(f"\n{'distance':14} {'data mean':>9} {'sd':>5} {'ref mean':>9} {'sd':>5}   (each set in its own mm)")
    for name, a, b in FARKAS:
        if a in dn and b in dn and a in rn and b in rn:
            d = np.linalg.norm(DL[:, dn.index(a)] - DL[:, dn.index(b)], axis=1)
            r = np.linalg.norm(RL[:, rn.index(a)] - RL[:, rn.index(b)], axis=1)
            print(f"{name:14} {d.mean():9.2f} {d.std():5.2f} {r.mean():9.2f} {r.std():5.2f}")
            out["distances"][name] = {"data": [d.mean(), d.std()], "reference": [r.mean(), r.std()]}
    if args.map:
        signed_map(args, s, R, t)
    if args.json:
        Path(args.json).write_text(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
