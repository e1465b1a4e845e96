#!/usr/bin/env python3
"""The realistic check of issue 15 (docs/registration.md): ICT-FaceKit faces become "scans" of
another topology (the shared-topology simplification of `import ict-facekit --vertices`), with a
hole cut in the left cheek, 0.2 mm Gaussian noise on every vertex and feature points at ICT's
landmarks (the ears' too: the scans have ears; --mask leaves them out, as for a face mask); the synthetic high-resolution template is registered onto each,
and the distance to the true (full-resolution, noise-free) ICT surface is measured by
`facesketch register --truth`.

With --train, the scans are instead written to WORK/scans-in (no truth, no per-scan registration),
imported by `facesketch import scans` onto the template, trained, and `eval observe --fraction 0.15`
is run on the result and on the direct ICT import at about 6,000 vertices, for the issue's
"within 1.5x of the direct import" comparison.

--args passes options to `register` (per scan) or `import scans` (with --train), e.g.
--args="--blend 40 --smooth-displacement 1". --mask leaves the ear points (obs_l, obs_r) out, as a
face mask's points file would (the 6th session's check); --ears, the default, gives them.

usage: tools/registration-check.py FACESKETCH ICT_DIR WORK [--faces N] [--noise MM] [--train] [--args "..."] [--mask]
"""
import argparse, json, math, random, re, struct, subprocess, sys
from pathlib import Path


def read_ply(path):
    data = Path(path).read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode()
    nv = int(re.search(r"element vertex (\d+)", header).group(1))
    nf = int(re.search(r"element face (\d+)", header).group(1))
    V = [struct.unpack_from("<3f", data, end + 12 * i) for i in range(nv)]
    F, o = [], end + 12 * nv
    for _ in range(nf):
        n = data[o]
        F.append(struct.unpack_from("<%di" % n, data, o + 1))
        o += 1 + 4 * n
    return V, F


def write_obj(path, V, F):
    with open(path, "w") as out:
        out.writelines("v %.6f %.6f %.6f\n" % tuple(v) for v in V)
        out.writelines("f %d %d %d\n" % tuple(i + 1 for i in f) for f in F)


def run(*args):
    return subprocess.run([str(a) for a in args], check=True, capture_output=True, text=True).stdout


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("facesketch")
    ap.add_argument("ict")
    ap.add_argument("work", type=Path)
    ap.add_argument("--faces", type=int, default=4)
    ap.add_argument("--noise", type=float, default=0.2)
    ap.add_argument("--train", action="store_true")
    ap.add_argument("--args", default="", help="extra options of register / import scans")
    ap.add_argument("--ears", action="store_true", help="give the scans' ear points (obs_l, obs_r): the default")
    ap.add_argument("--mask", action="store_true", help="leave the ear points out, as a face mask's points file would")
    a = ap.parse_args()
    a.work.mkdir(parents=True, exist_ok=True)
    run(a.facesketch, "synth", "-o", a.work / "template", "--identities", 20, "--resolution", "high")
    if not a.train:
        run(a.facesketch, "import", "ict-facekit", a.ict, "-o", a.work / "truth", "--identities", a.faces)
    run(a.facesketch, "import", "ict-facekit", a.ict, "-o", a.work / "scans", "--identities", a.faces, "--vertices", 3000)
    manifest = json.loads((a.work / "scans" / "manifest.json").read_text())
    rows = []
    if a.train:
        (a.work / "scans-in").mkdir(exist_ok=True)
    for sample in manifest["samples"]:
        name = sample["name"]
        V, F = read_ply(a.work / "scans" / sample["file"])
        rng = random.Random(name)
        # A hole of 7 mm radius on the left cheek, beside the mouth corner.
        c = V[manifest["landmarks"]["ch_l"]]
        centre = (c[0] + 18, c[1] + 18, c[2] - 8)
        F = [f for f in F if min(math.dist(V[i], centre) for i in f) > 7]
        where = a.work / "scans-in" if a.train else a.work
        write_obj(where / (name + ".obj"), [[x + rng.gauss(0, a.noise) for x in v] for v in V], F)
        points = {k: list(V[i]) for k, i in manifest["landmarks"].items() if not a.mask or not k.startswith("obs")}
        (where / (name + ".points.json")).write_text(json.dumps(points))
        if a.train:
            continue
        TV, TF = read_ply(a.work / "truth" / sample["file"])
        write_obj(a.work / (name + ".truth.obj"), TV, TF)
        for method in ("depth", "projection"):
            out = run(a.facesketch, "register", a.work / "template", a.work / (name + ".obj"), "--points", a.work / (name + ".points.json"),
                      "-o", a.work / ("%s.%s.ply" % (name, method)), "--truth", a.work / (name + ".truth.obj"), "--method", method,
                      "--error-map", a.work / ("%s.%s.png" % (name, method)), *a.args.split())
            t = re.search(r"truth.obj: mean ([\d.]+) mm, p95 ([\d.]+) mm, max ([\d.]+) mm \((\d+) vertices", out)
            rbf = re.search(r"RBF approximation to scan: mean ([\d.]+) mm, p95 ([\d.]+)", out)
            secs = re.search(r"in ([\d.]+) s", out)
            rows.append((name, method, rbf.group(1), rbf.group(2), *t.groups(), secs.group(1)))
    if a.train:
        print(run(a.facesketch, "import", "scans", a.work / "scans-in", "--template", a.work / "template", "-o", a.work / "registered", "-q", *a.args.split()))
        run(a.facesketch, "import", "ict-facekit", a.ict, "-o", a.work / "direct", "--identities", a.faces, "--vertices", 6000)
        for name in ("registered", "direct"):
            run(a.facesketch, "train", a.work / name, "-o", a.work / (name + ".model"), "-q")
            print(name, run(a.facesketch, "eval", "observe", a.work / (name + ".model"), a.work / name, "--fraction", 0.15))
        return 0
    print("| scan | method | RBF to scan mean / p95 mm | registered to truth mean / p95 / max mm | vertices measured | s |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        print("| %s | %s | %s / %s | %s / %s / %s | %s | %s |" % r)


if __name__ == "__main__":
    sys.exit(main())
