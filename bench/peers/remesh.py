#!/usr/bin/env python3
"""Remeshing against gpytoolbox's remesh_botsch, in the same run, on the same meshes.

Both remesh each mesh at its mean edge length for 10 iterations (the last case keeps creases
sharper than 45 degrees: `--feature-angle 45` for meshq, `detect_feature_edges` for
gpytoolbox), single-threaded. The quality figures of both outputs are computed here by the
same code: percentage of interior vertices with valence 6, smallest angle of triangles off
the boundary, percentage of triangles with an angle under 30 degrees, edge-length coefficient
of variation, and the two-sided distance to the input sampled at vertices and centroids over
the bounding-box diagonal. Times: best of 3 (meshq's own `remesh_seconds`, gpytoolbox's call).

With `--corpus DIR`, the meshes of DIR (`cargo run --release -p meshq-bench --example
hard_corpus -- DIR` writes the remeshing tests' hard inputs there) are remeshed too, each at
its own mean edge length times its entry in RATIOS (1 when absent): the cone's mean edge is
dominated by its 1,024 long side edges, a target at which the whole cone is a dozen
triangles, so it is remeshed at a twentieth of it.

A second table refines the bundled meshes (`--target-ratio` 0.5, 0.2 and 0.1; the bunny
at 0.5 and 0.2, whose 0.1 run would make about six million triangles) with meshq alone: the
triangles against the count of equilateral triangles of the target's side that cover the
input's area, the same degenerate/flipped/angle figures, the time per output triangle, and the
resident peak of the command (`--max-distance-tests 0`, so it is the remeshing's: no distance
report) against the output's size (12 bytes per vertex and per triangle).

Set up once: scripts/peers-setup.sh (a virtual environment in target/peers-venv).
Run: target/peers-venv/bin/python bench/peers/remesh.py [meshq binary] [--corpus DIR]
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
ARGS = sys.argv[1:]
CORPUS = pathlib.Path(ARGS[ARGS.index("--corpus") + 1]) if "--corpus" in ARGS else None
POSITIONAL = [a for i, a in enumerate(ARGS) if not a.startswith("--") and (i == 0 or ARGS[i - 1] != "--corpus")]
MESHQ = POSITIONAL[0] if POSITIONAL else str(ROOT / "target/release/meshq")
CASES = [(ROOT / "assets" / f"{name}.obj", angle)
         for name, angle in [("stanford-bunny", None), ("fandisk", None), ("spot", None), ("fandisk", 45.0)]]
if CORPUS is not None:
    CASES += [(path, None) for path in sorted(CORPUS.glob("*.obj"))]
RATIOS = {"cone-1024": 0.05}


def faces_against_all_nearest(t, centroid, d2, normal, nearest, v_in, f_in, n_in):
    """Whether output triangle `t` faces against every input triangle as near its centroid
    as the nearest one (to a part in 10⁶): where the nearest point lies on an edge or corner
    that input triangles facing different ways share, each of them is "the nearest", and a
    triangle facing the way one of them does faces the input. Ties can only be among the
    triangles around the nearest one's corners."""
    around = np.flatnonzero(np.isin(f_in, f_in[nearest]).any(axis=1))
    for s in around:
        ds = gpy.squared_distance(centroid[None], v_in, f_in[s:s + 1], use_cpp=True)[0][0]
        if ds <= d2 * (1 + 1e-6) + 1e-30 and np.dot(normal, n_in[s]) > 0:
            return False
    return True


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
    # Degenerate output: triangles of (relatively) zero area, and used vertices sharing one
    # position; flipped: triangles facing against the input triangle nearest their centroid
    # (against every one of them where several are equally near).
    normals = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    area2 = np.linalg.norm(normals, axis=1)
    zero_area = int(np.count_nonzero(area2 <= 1e-12 * diag * diag))
    coincident = int(np.count_nonzero(used)) - len(np.unique(v[used], axis=0))
    centroids = p.mean(axis=1)
    d2, nearest = gpy.squared_distance(centroids, v_in, f_in, use_cpp=True)[:2]
    q = v_in[f_in]
    n_in = np.cross(q[:, 1] - q[:, 0], q[:, 2] - q[:, 0])
    against = np.flatnonzero(np.einsum("ij,ij->i", normals, n_in[nearest]) < 0)
    flipped = sum(1 for t in against if faces_against_all_nearest(t, centroids[t], d2[t], normals[t], nearest[t], v_in, f_in, n_in))
    return {
        "degenerate": zero_area + coincident,
        "flipped": flipped,
        "triangles": len(f),
        "valence6": 100.0 * np.mean(valence[interior] == 6),
        "min_angle": float(smallest[off].min()) if off.any() else 180.0,
        "under30": 100.0 * np.mean(smallest < 30.0),
        "edge_cv": float(lengths.std() / lengths.mean()),
        "distance": float(dist),
    }


REFINING = [("spot", [0.5, 0.2, 0.1]), ("fandisk", [0.5, 0.2, 0.1]), ("stanford-bunny", [0.5, 0.2])]


def refining(tmp):
    rows = []
    for name, ratios in REFINING:
        path = ROOT / "assets" / f"{name}.obj"
        v_in, f_in = read_obj(path)
        q = v_in[f_in]
        area = 0.5 * np.linalg.norm(np.cross(q[:, 1] - q[:, 0], q[:, 2] - q[:, 0]), axis=1).sum()
        for ratio in ratios:
            out = pathlib.Path(tmp) / "refined.ply"
            args = [MESHQ, "remesh", str(path), "-o", str(out), "--json", "--target-ratio", str(ratio),
                    "--max-distance-tests", "0"]
            # GNU time reports its child's resident peak (KiB). A child forked from this
            # process would count this process's pages, mapped in it until exec.
            peak_file = pathlib.Path(tmp) / "peak"
            done = subprocess.run(["/usr/bin/time", "-f", "%M", "-o", str(peak_file)] + args,
                                  capture_output=True, text=True)
            if done.returncode != 0:
                rows.append((name, ratio, f"failed: {done.stderr.strip().splitlines()[-1:]}"))
                continue
            report = json.loads(done.stdout)
            mv, mf = read_ply(out)
            length = report["target_length"]
            expected = area / (np.sqrt(3) / 4 * length * length)
            peak = int(peak_file.read_text().split()[-1]) * 1024
            size = 12 * len(mv) + 12 * len(mf)
            rows.append((name, ratio, quality(mv, mf, v_in, f_in), expected, report["remesh_seconds"], peak, size))
    print("| mesh | target ratio | triangles | of expected | degenerate | flipped | min angle off boundary | % tri < 30° | time (s) | µs per triangle | peak (MB) | peak / output |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for row in rows:
        if isinstance(row[2], str):
            print(f"| {row[0]} | {row[1]:g} | {row[2]} | | | | | | | | | |")
            continue
        name, ratio, q, expected, seconds, peak, size = row
        print(f"| {name} | {ratio:g} | {q['triangles']} | {q['triangles'] / expected:.3f} | {q['degenerate']} | "
              f"{q['flipped']} | {q['min_angle']:.2f}° | {q['under30']:.3f} | {seconds:.2f} | "
              f"{1e6 * seconds / q['triangles']:.1f} | {peak / 1e6:.0f} | {peak / size:.1f}× |")


def main():
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for path, angle in CASES:
            name = path.stem
            v_in, f_in = read_obj(path)
            out = pathlib.Path(tmp) / "out.ply"
            ratio = RATIOS.get(name, 1.0)
            args = [MESHQ, "remesh", str(path), "-o", str(out), "--json", "--target-ratio", str(ratio)]
            if angle is not None:
                args += ["--feature-angle", str(angle)]
            label = name + (f", creases {angle:g}°" if angle else "") + (f", {ratio:g} × mean edge" if ratio != 1.0 else "")
            try:
                meshq_s = min(json.loads(subprocess.run(args, check=True, capture_output=True, text=True).stdout)["remesh_seconds"]
                              for _ in range(3))
                mv, mf = read_ply(out)
                rows.append((label, "meshq", quality(mv, mf, v_in, f_in), meshq_s))
            except subprocess.CalledProcessError as failure:
                rows.append((label, "meshq", failure.stderr.strip().splitlines()[-1], None))
            und = np.unique(np.sort(np.concatenate([f_in[:, [0, 1]], f_in[:, [1, 2]], f_in[:, [2, 0]]]), axis=1), axis=0)
            h = ratio * float(np.linalg.norm(v_in[und[:, 0]] - v_in[und[:, 1]], axis=1).mean())
            gpy_s, result = float("inf"), None
            try:
                for _ in range(3):
                    t0 = time.perf_counter()
                    result = gpy.remesh_botsch(v_in, f_in.astype(np.int32), i=10, h=h,
                                               detect_feature_edges=angle is not None,
                                               feature_dihedral_threshold=angle or 45.0)
                    gpy_s = min(gpy_s, time.perf_counter() - t0)
                gv, gf = result
                rows.append((label, "gpytoolbox", quality(gv, gf, v_in, f_in), gpy_s))
            except Exception as failure:  # the peer's own refusal, reported as such
                rows.append((label, "gpytoolbox", f"failed: {failure}", None))
    print("| mesh | remesher | triangles | degenerate | flipped | % valence 6 | min angle off boundary | % tri < 30° | edge CV | distance | time (s) |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for label, who, q, s in rows:
        if isinstance(q, str):
            print(f"| {label} | {who} | {q} | | | | | | | | |")
            continue
        print(f"| {label} | {who} | {q['triangles']} | {q['degenerate']} | {q['flipped']} | {q['valence6']:.2f} | "
              f"{q['min_angle']:.2f}° | {q['under30']:.3f} | {q['edge_cv']:.3f} | {q['distance']:.2e} | {s:.3f} |")
    if "--no-refining" not in ARGS:
        print()
        with tempfile.TemporaryDirectory() as tmp:
            refining(tmp)


if __name__ == "__main__":
    main()
