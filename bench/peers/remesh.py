#!/usr/bin/env python3
"""Remeshing against gpytoolbox's remesh_botsch, in the same run, on the same meshes.

Both remesh each mesh at its mean edge length for 10 iterations (the last case keeps creases
sharper than 45 degrees: `--feature-angle 45` for meshq, `detect_feature_edges` for
gpytoolbox), single-threaded. The quality figures of both outputs are computed here by the
same code: percentage of interior vertices with valence 6, smallest angle of triangles off
the boundary, percentage of triangles with an angle under 30 degrees, edge-length coefficient
of variation, and the two-sided distance to the input sampled at vertices and centroids over
the bounding-box diagonal. Times: best of 3 (meshq's own `remesh_seconds`, gpytoolbox's call).

Set up once: scripts/peers-setup.sh (a virtual environment in target/peers-venv).
Run: target/peers-venv/bin/python bench/peers/remesh.py [meshq binary]
"""
import json
import pathlib
import subprocess
import sys
import tempfile
import time

import gpytoolbox as gpy
import numpy as np
from meshfiles import read_obj, read_ply

ROOT = pathlib.Path(__file__).resolve().parents[2]
MESHQ = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "target/release/meshq")
CASES = [("stanford-bunny", None), ("fandisk", None), ("spot", None), ("fandisk", 45.0)]


def quality(v, f, v_in, f_in):
    e = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    directed = set(map(tuple, e))
    boundary = {x for a, b in directed if (b, a) not in directed for x in (a, b)}
    und = np.unique(np.sort(e, axis=1), axis=0)
    lengths = np.linalg.norm(v[und[:, 0]] - v[und[:, 1]], axis=1)
    valence = np.bincount(und.ravel(), minlength=len(v))
    used = np.zeros(len(v), bool)
    used[f.ravel()] = True
    interior = np.array([used[i] and i not in boundary for i in range(len(v))])
    p = v[f]
    angles = []
    for k in range(3):
        a, b, c = p[:, k], p[:, (k + 1) % 3], p[:, (k + 2) % 3]
        u, w = b - a, c - a
        cos = np.einsum("ij,ij->i", u, w) / (np.linalg.norm(u, axis=1) * np.linalg.norm(w, axis=1))
        angles.append(np.degrees(np.arccos(np.clip(cos, -1, 1))))
    smallest = np.min(np.stack(angles, axis=1), axis=1)
    off = np.array([not any(x in boundary for x in t) for t in f])
    diag = np.linalg.norm(v_in.max(0) - v_in.min(0))

    def one_way(vs, fs, vt, ft):
        samples = np.concatenate([vs, vs[fs].mean(axis=1)])
        d2 = gpy.squared_distance(samples, vt, ft, use_cpp=True)[0]
        return np.sqrt(d2.max())

    dist = max(one_way(v, f, v_in, f_in), one_way(v_in, f_in, v, f)) / diag
    return {
        "triangles": len(f),
        "valence6": 100.0 * np.mean(valence[interior] == 6),
        "min_angle": float(smallest[off].min()) if off.any() else 180.0,
        "under30": 100.0 * np.mean(smallest < 30.0),
        "edge_cv": float(lengths.std() / lengths.mean()),
        "distance": float(dist),
    }


def main():
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, angle in CASES:
            path = ROOT / "assets" / f"{name}.obj"
            v_in, f_in = read_obj(path)
            out = pathlib.Path(tmp) / "out.ply"
            args = [MESHQ, "remesh", str(path), "-o", str(out), "--json"]
            if angle is not None:
                args += ["--feature-angle", str(angle)]
            meshq_s = min(json.loads(subprocess.check_output(args))["remesh_seconds"] for _ in range(3))
            mv, mf = read_ply(out)
            und = np.unique(np.sort(np.concatenate([f_in[:, [0, 1]], f_in[:, [1, 2]], f_in[:, [2, 0]]]), axis=1), axis=0)
            h = float(np.linalg.norm(v_in[und[:, 0]] - v_in[und[:, 1]], axis=1).mean())
            gpy_s, result = float("inf"), None
            for _ in range(3):
                t0 = time.perf_counter()
                result = gpy.remesh_botsch(v_in, f_in.astype(np.int32), i=10, h=h,
                                           detect_feature_edges=angle is not None,
                                           feature_dihedral_threshold=angle or 45.0)
                gpy_s = min(gpy_s, time.perf_counter() - t0)
            gv, gf = result
            label = name + (f", creases {angle:g}°" if angle else "")
            rows.append((label, "meshq", quality(mv, mf, v_in, f_in), meshq_s))
            rows.append((label, "gpytoolbox", quality(gv, gf, v_in, f_in), gpy_s))
    print("| mesh | remesher | triangles | % valence 6 | min angle off boundary | % tri < 30° | edge CV | distance | time (s) |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|")
    for label, who, q, s in rows:
        print(f"| {label} | {who} | {q['triangles']} | {q['valence6']:.2f} | {q['min_angle']:.2f}° | "
              f"{q['under30']:.3f} | {q['edge_cv']:.3f} | {q['distance']:.2e} | {s:.3f} |")


if __name__ == "__main__":
    main()
