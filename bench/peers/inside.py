#!/usr/bin/env python3
"""meshq's winding numbers and signed distance against libigl's, in the same run, on the same
points.

For each mesh, 100,000 query points (the DESIGN.md closest-point workload, written by
`meshq workload --kind points`), on one core (this process pins itself to CPU 0 before
anything starts; the meshq command inherits that):
- libigl (the `libigl` package): `igl.fast_winding_number(V, F, Q)` (Barill et al.'s fast
  winding number over the triangle soup, its default expansion order 2 and beta 2: the tree and
  expansions are built inside the call, so its time includes them), and `igl.signed_distance`
  with the fast-winding-number sign;
- meshq: `meshq inside MESH --points Q --accuracy R --json` and
  `meshq closest MESH --points Q --signed --accuracy R --json`, whose `build_seconds` (the BVH
  and its expansions, file reading excluded) and `query_seconds` are added: the same work as
  libigl's call;
- the error of each against the exact winding number (`igl.winding_number`, double precision,
  a brute-force sum over every triangle) on the first `--exact` points: the largest and the
  mean difference. "Equal accuracy" compares meshq at the ratio whose largest error is at most
  libigl's;
- signed distances: the magnitudes compared point by point with libigl's unsigned distances
  (`SIGNED_DISTANCE_TYPE_UNSIGNED`; largest difference over the mesh's diagonal: libigl's
  fast-winding-number mode returns other magnitudes near the surface, also reported), and the
  signs with the exact winding number's (points where they differ, among those whose exact
  number is not within 0.01 of 1/2).
- a signed-distance volume of the first mesh, `--grid` samples along its longest axis
  (default 128), on every core: `meshq sdf MESH --resolution N --threads 0` against
  `igl.signed_distance` (fast-winding-number sign; libigl spreads it over every core itself)
  at the volume's sample points read back from meshq's NRRD header, once each; the signs
  compared.
Times are the best of `--repeat` rounds (default 3).

Set up once: scripts/peers-setup.sh (a virtual environment in target/peers-venv).
Run: target/peers-venv/bin/python bench/peers/inside.py [--meshq BIN] [--points N]
     [--ratios 2,2.5,3] [--repeat K] [--json] [MESH ...]
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import time

import igl
import numpy as np
from meshfiles import read_mesh

ROOT = pathlib.Path(__file__).resolve().parents[2]
DEFAULT_MESHES = ["stanford-bunny", "fandisk", "spot"]


def best_of(repeat, f):
    best, value = float("inf"), None
    for _ in range(repeat):
        start = time.perf_counter()
        value = f()
        best = min(best, time.perf_counter() - start)
    return best, value


def meshq_run(meshq, args, repeat):
    """The best build + query time of a meshq command, and its last JSON summary."""
    best, summary = float("inf"), None
    for _ in range(repeat):
        out = subprocess.run([meshq, *args, "--json"], check=True, capture_output=True, text=True)
        summary = json.loads(out.stdout)
        best = min(best, summary["build_seconds"] + summary["query_seconds"])
    return best, summary


def errors(numbers, exact):
    d = np.abs(np.asarray(numbers[: len(exact)], dtype=np.float64) - exact)
    return float(d.max()), float(d.mean())


def run_mesh(name, args, work):
    path = ROOT / "assets" / f"{name}.obj" if not name.endswith((".obj", ".ply")) else pathlib.Path(name)
    v, f = read_mesh(path)
    v = np.ascontiguousarray(v, dtype=np.float64)
    f = np.ascontiguousarray(f, dtype=np.int64)
    diagonal = float(np.linalg.norm(v.max(0) - v.min(0)))
    points_file = work / f"{path.stem}.points"
    subprocess.run(
        [args.meshq, "workload", str(path), "--kind", "points", "--count", str(args.points), "-o", str(points_file)],
        check=True,
        capture_output=True,
    )
    q = np.fromfile(points_file, dtype="<f4").reshape(-1, 3).astype(np.float64)
    exact = igl.winding_number(v, f, q[: args.exact])
    row = {"mesh": path.stem, "triangles": int(len(f)), "points": int(len(q)), "exact_points": int(len(exact))}

    igl_time, w = best_of(args.repeat, lambda: igl.fast_winding_number(v, f, q))
    row["libigl"] = {"seconds": igl_time, "largest_error": errors(w, exact)[0], "mean_error": errors(w, exact)[1]}
    row["meshq"] = {}
    out = work / "inside.bin"
    for ratio in args.ratios:
        t, summary = meshq_run(
            args.meshq, ["inside", str(path), "--points", str(points_file), "--out", str(out), "--accuracy", ratio], args.repeat
        )
        numbers = np.fromfile(out, dtype=[("w", "<f4"), ("inside", "<u4")])["w"]
        largest, mean = errors(numbers, exact)
        row["meshq"][ratio] = {
            "seconds": t,
            "build_seconds": summary["build_seconds"],
            "query_seconds": summary["query_seconds"],
            "largest_error": largest,
            "mean_error": mean,
            "ratio": igl_time / t,
        }
    equal = [r for r, m in row["meshq"].items() if m["largest_error"] <= row["libigl"]["largest_error"]]
    row["equal_accuracy_ratio"] = equal[0] if equal else None

    kind = igl.SIGNED_DISTANCE_TYPE_FAST_WINDING_NUMBER
    sd_time, (s, _i, _c, _n) = best_of(args.repeat, lambda: igl.signed_distance(q, v, f, kind))
    unsigned = igl.signed_distance(q, v, f, igl.SIGNED_DISTANCE_TYPE_UNSIGNED)[0]
    row["signed"] = {
        "libigl_seconds": sd_time,
        "libigl_magnitude_difference_over_diagonal": float(np.abs(np.abs(s) - unsigned).max() / diagonal),
        "meshq": {},
    }
    decided = np.abs(np.abs(exact) - 0.5) > 0.01
    for ratio in args.ratios:
        t, _ = meshq_run(
            args.meshq,
            ["closest", str(path), "--points", str(points_file), "--out", str(out), "--signed", "--accuracy", ratio],
            args.repeat,
        )
        ours = np.fromfile(out, dtype=[("d", "<f4"), ("tri", "<u4")])["d"].astype(np.float64)
        magnitude = float(np.abs(np.abs(ours) - unsigned).max() / diagonal)
        n = len(exact)
        truth = np.where(np.abs(exact) >= 0.5, -1.0, 1.0)
        wrong_sign = int(np.sum((np.sign(ours[:n]) != truth) & decided))
        igl_wrong = int(np.sum((np.sign(s[:n]) != truth) & decided))
        row["signed"]["meshq"][ratio] = {
            "seconds": t,
            "ratio": sd_time / t,
            "magnitude_difference_over_diagonal": magnitude,
            "wrong_signs": wrong_sign,
        }
        row["signed"]["libigl_wrong_signs"] = igl_wrong
    return row


def run_grid(name, args, work):
    path = ROOT / "assets" / f"{name}.obj" if not name.endswith((".obj", ".ply")) else pathlib.Path(name)
    v, f = read_mesh(path)
    v = np.ascontiguousarray(v, dtype=np.float64)
    f = np.ascontiguousarray(f, dtype=np.int64)
    volume = work / "volume.nrrd"
    os.sched_setaffinity(0, set(range(os.cpu_count())))
    try:
        t, summary = meshq_run(
            args.meshq, ["sdf", str(path), "-o", str(volume), "--resolution", str(args.grid), "--threads", "0"], 1
        )
        data = volume.read_bytes()
        end = data.index(b"\n\n") + 2
        ours = np.frombuffer(data[end:], dtype="<f4")
        nx, ny, nz = summary["counts"]
        o = np.array(summary["origin"], dtype=np.float32)
        h = np.array(summary["spacing"], dtype=np.float32)
        k, j, i = np.meshgrid(np.arange(nz), np.arange(ny), np.arange(nx), indexing="ij")
        index = np.stack([i.ravel(), j.ravel(), k.ravel()], 1).astype(np.float32)
        points = (o + index * h).astype(np.float64)
        start = time.perf_counter()
        s, _i, _c, _n = igl.signed_distance(points, v, f, igl.SIGNED_DISTANCE_TYPE_FAST_WINDING_NUMBER)
        igl_time = time.perf_counter() - start
    finally:
        os.sched_setaffinity(0, {0})
    return {
        "mesh": path.stem,
        "counts": summary["counts"],
        "threads": summary["threads"],
        "meshq_seconds": t,
        "libigl_seconds": igl_time,
        "ratio": igl_time / t,
        "sign_disagreements": int(np.sum(np.sign(ours) != np.sign(s))),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("meshes", nargs="*", default=DEFAULT_MESHES)
    parser.add_argument("--meshq", default=str(ROOT / "target/release/meshq"))
    parser.add_argument("--points", type=int, default=100_000)
    parser.add_argument("--exact", type=int, default=5_000, help="points checked against the exact number")
    parser.add_argument("--ratios", default="2,2.5,3", help="meshq --accuracy values, comma-separated")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--grid", type=int, default=128, help="volume samples along the longest axis (0: none)")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    args.ratios = args.ratios.split(",")
    os.sched_setaffinity(0, {0})
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name in args.meshes:
            rows.append(run_mesh(name, args, pathlib.Path(tmp)))
        grid = run_grid(args.meshes[0], args, pathlib.Path(tmp)) if args.grid else None
    if args.json:
        print(json.dumps({"rows": rows, "grid": grid}, indent=1))
        return
    if grid:
        c = grid["counts"]
        print(
            f"{grid['mesh']} volume {c[0]}x{c[1]}x{c[2]} on {grid['threads']} threads: meshq sdf {grid['meshq_seconds']:.2f} s,"
            f" libigl signed_distance {grid['libigl_seconds']:.2f} s: {grid['ratio']:.2f}x; signs differ at {grid['sign_disagreements']} samples"
        )
    for row in rows:
        lib = row["libigl"]
        print(f"{row['mesh']} ({row['triangles']} triangles, {row['points']} points; errors on {row['exact_points']})")
        print(f"  libigl fast_winding_number: {lib['seconds']:.3f} s, largest error {lib['largest_error']:.2e}, mean {lib['mean_error']:.2e}")
        for ratio, m in row["meshq"].items():
            print(
                f"  meshq inside --accuracy {ratio}: {m['seconds']:.3f} s (build {m['build_seconds']:.3f}, queries {m['query_seconds']:.3f}),"
                f" largest error {m['largest_error']:.2e}, mean {m['mean_error']:.2e}: {m['ratio']:.2f}x libigl"
            )
        print(f"  at equal or better accuracy: --accuracy {row['equal_accuracy_ratio']}")
        sd = row["signed"]
        print(
            f"  libigl signed_distance (fast winding number sign): {sd['libigl_seconds']:.3f} s, wrong signs {sd['libigl_wrong_signs']};"
            f" |distance| differs from its unsigned one by {sd['libigl_magnitude_difference_over_diagonal']:.1e} of the diagonal"
        )
        for ratio, m in sd["meshq"].items():
            print(
                f"  meshq closest --signed --accuracy {ratio}: {m['seconds']:.3f} s: {m['ratio']:.2f}x libigl;"
                f" |distance| differs from libigl's unsigned one by {m['magnitude_difference_over_diagonal']:.1e} of the diagonal; wrong signs {m['wrong_signs']}"
            )


if __name__ == "__main__":
    sys.exit(main())
