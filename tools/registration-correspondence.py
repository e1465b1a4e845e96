#!/usr/bin/env python3
"""Correspondence of registered ICT scans against the truth (docs/registration.md, "Where the
gap was"): for a dataset made by `facesketch import scans` from the scans of
tools/registration-check.py --train (WORK/registered) and the direct ICT import of the same
identities (WORK/direct, noise-free, ICT's own correspondence), maps every template skin vertex
of the registered faces' mean onto the direct faces' mean surface (closest point, as a triangle
and barycentric coordinates: the template vertex's "true" correspondent), carries that point to
every face, and splits each registered vertex's deviation from it (less its mean over the faces)
into the component along the true surface's normal and the tangential one (sliding), per region
(within 15 mm of the landmarks of the nose, lips, eyes, chin and brows, else "other"). Vertices
whose mean lies more than 2 mm from the truth's mean surface (off the scanned part) are left out.

usage: tools/registration-correspondence.py REGISTERED DIRECT [--n FACES] [--save OUT.npz]
Needs numpy (analysis only).
"""
import json, re, sys

try:
    import numpy as np
except ImportError:  # Debian's python3-numpy, when python3 is not Debian's
    sys.path.append("/usr/lib/python3/dist-packages")
    import numpy as np
def load(d, n=None):
    m = json.load(open(d + '/manifest.json'))
    S = m['samples'] if n is None else m['samples'][:n]
    def read(p):
        b = open(p, 'rb').read(); e = b.index(b'end_header\n') + 11; h = b[:e].decode()
        nv = int(re.search(r'element vertex (\d+)', h).group(1))
        return np.frombuffer(b[e:e + 12 * nv], dtype='<f4').reshape(nv, 3).astype(float)
    X = np.stack([read(d + '/' + s['file']) for s in S])
    return m, [s['name'] for s in S], X

def closest_on_tris(P, A, B, C):
    # P (k,3), A/B/C (k,3): closest point on triangle, returns point and barycentrics (k,3)
    e0 = B - A; e1 = C - A; v = P - A
    d00 = (e0*e0).sum(1); d01 = (e0*e1).sum(1); d11 = (e1*e1).sum(1)
    d20 = (v*e0).sum(1); d21 = (v*e1).sum(1)
    den = d00*d11 - d01*d01; den[den == 0] = 1e-30
    b1 = (d11*d20 - d01*d21)/den; b2 = (d00*d21 - d01*d20)/den
    bary = np.stack([1-b1-b2, b1, b2], 1)
    inside = (bary >= 0).all(1)
    best = np.where(inside[:, None], bary, 0.0)
    bestd = np.where(inside, np.linalg.norm(P - (bary[:, :1]*A + bary[:, 1:2]*B + bary[:, 2:]*C), axis=1), np.inf)
    for (i, j) in ((0, 1), (1, 2), (2, 0)):
        Q = [A, B, C]; X0, X1 = Q[i], Q[j]
        e = X1 - X0; t = np.clip(((P - X0)*e).sum(1)/np.maximum((e*e).sum(1), 1e-30), 0, 1)
        pt = X0 + t[:, None]*e; d = np.linalg.norm(P - pt, axis=1)
        bb = np.zeros_like(bary); bb[:, i] = 1 - t; bb[:, j] = t
        better = (~inside) & (d < bestd)
        best[better] = bb[better]; bestd[better] = d[better]
    return best, bestd

def map_to_mesh(P, V, F, k=12):
    # for each P find closest point on mesh V,F among triangles touching the k nearest vertices
    vt = [[] for _ in range(len(V))]
    for t, f in enumerate(F):
        for a in f: vt[a].append(t)
    tri = np.zeros(len(P), int); bar = np.zeros((len(P), 3)); dist = np.full(len(P), np.inf)
    for s in range(0, len(P), 500):
        Q = P[s:s+500]
        d2 = ((Q[:, None, :] - V[None])**2).sum(2)
        nn = np.argsort(d2, 1)[:, :k]
        for qi in range(len(Q)):
            cand = sorted({t for a in nn[qi] for t in vt[a]})
            c = np.array(cand); f = F[c]
            b, d = closest_on_tris(np.repeat(Q[qi:qi+1], len(c), 0), V[f[:, 0]], V[f[:, 1]], V[f[:, 2]])
            j = np.argmin(d); tri[s+qi] = c[j]; bar[s+qi] = b[j]; dist[s+qi] = d[j]
    return tri, bar, dist

def main():
    rd, dd = sys.argv[1], sys.argv[2]
    n = int(sys.argv[sys.argv.index('--n')+1]) if '--n' in sys.argv else None
    mr, namesr, R = load(rd, n)
    md, namesd, D = load(dd)
    idx = [namesd.index(x) for x in namesr]; D = D[idx]
    nskin = mr['components']['skin'][1]
    FD = np.array(md['topology'])
    R = R[:, :nskin]
    MR, MD = R.mean(0), D.mean(0)
    tri, bar, dist = map_to_mesh(MR, MD, FD)
    f = FD[tri]
    T = (bar[None, :, 0:1]*D[:, f[:, 0]] + bar[None, :, 1:2]*D[:, f[:, 1]] + bar[None, :, 2:3]*D[:, f[:, 2]])
    Nf = np.cross(D[:, f[:, 1]] - D[:, f[:, 0]], D[:, f[:, 2]] - D[:, f[:, 0]])
    Nf /= np.linalg.norm(Nf, axis=2, keepdims=True)
    E = R - T  # (faces, verts, 3)
    E = E - E.mean(0, keepdims=True)   # inconsistency: remove the per-vertex mean offset
    en = (E*Nf).sum(2); et = np.linalg.norm(E - en[..., None]*Nf, axis=2)
    lm = mr['landmarks']
    groups = {'nose': ['prn', 'al_l', 'al_r', 'sbal_l', 'sbal_r', 'sn', 'cs1'], 'lips': ['ls', 'li', 'ch_l', 'ch_r', 'sto', 'cph_l', 'cph_r', 'sl'],
              'eyes': ['en_l', 'en_r', 'ex_l', 'ex_r', 'ps_l', 'ps_r', 'pi_l', 'pi_r'], 'chin/jaw': ['pg', 'gn'], 'brow': ['g', 'os_l', 'os_r', 'n', 's']}
    names = [k for k in groups for _ in groups[k]]; pts = np.array([MR[lm[x]] for k in groups for x in groups[k]])
    dl = np.linalg.norm(MR[:, None] - pts[None], axis=2); near = dl.argmin(1)
    region = np.array([names[i] if dl[v, i] < 15 else 'other' for v, i in enumerate(near)])
    face = dist < 2.0
    print('faces', len(R), 'skin vertices', nskin, 'on truth surface (mean map < 2 mm)', face.sum())
    print('%-10s %6s %10s %10s %10s %10s' % ('region', 'verts', 'rms normal', 'rms tang', 'mean |E|', 'p95 tang'))
    for rg in ['nose', 'lips', 'eyes', 'chin/jaw', 'brow', 'other', 'all']:
        sel = face & ((region == rg) if rg != 'all' else True)
        a, b = en[:, sel], et[:, sel]
        print('%-10s %6d %10.3f %10.3f %10.3f %10.3f' % (rg, sel.sum(), np.sqrt((a**2).mean()), np.sqrt((b**2).mean()), np.sqrt(a**2+b**2).mean(), np.percentile(b, 95)))
    if '--save' in sys.argv: np.savez(sys.argv[sys.argv.index('--save') + 1], en=en, et=et, region=region, face=face, tri=tri, bar=bar)

if __name__ == '__main__':
    main()
