#!/usr/bin/env python3
"""Interleaved A/B of two builds of the `meshq` command on the same inputs: for each query
path (batched and per-ray random rays, camera rays, any hit, closest points, and the cell
structures built from the mesh), runs A then B, round after round, and prints the best
`query_seconds` of each and the ratio B/A (below 1: B is faster). Checks first that both
builds write the same records, byte for byte.

Usage: python3 bench/ab_cli.py A_BIN B_BIN [MESH] [--rounds N]
"""
import argparse
import filecmp
import json
import pathlib
import subprocess
import tempfile

parser = argparse.ArgumentParser()
parser.add_argument("a")
parser.add_argument("b")
parser.add_argument("mesh", nargs="?", default="assets/stanford-bunny.obj")
parser.add_argument("--rounds", type=int, default=5)
args = parser.parse_args()

work = pathlib.Path(tempfile.mkdtemp(prefix="meshq-ab-"))
run = lambda *cmd: subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
blob = work / "mesh.meshq"
run(args.a, "bake", args.mesh, "-o", str(blob))
blob_b = work / "mesh-b.meshq"
run(args.b, "bake", args.mesh, "-o", str(blob_b))
assert filecmp.cmp(blob, blob_b, shallow=False), "the two builds bake different blobs"
rays = work / "random.rays"
camera = work / "camera.rays"
points = work / "points.bin"
run(args.a, "workload", args.mesh, "--count", "300000", "-o", str(rays))
run(args.a, "workload", args.mesh, "--kind", "camera-rays", "--image", "512x512", "-o", str(camera))
run(args.a, "workload", args.mesh, "--kind", "points", "--count", "100000", "-o", str(points))

cases = {
    "random rays, batch": ["raycast", str(blob), "--rays", str(rays)],
    "random rays, one per call": ["raycast", str(blob), "--rays", str(rays), "--per-ray"],
    "camera rays, batch": ["raycast", str(blob), "--rays", str(camera)],
    "random rays, any hit": ["raycast", str(blob), "--rays", str(rays), "--any"],
    "closest points": ["closest", str(blob), "--points", str(points)],
    "random rays, k-d tree": ["raycast", args.mesh, "--structure", "kdtree", "--rays", str(rays)],
    "random rays, octree": ["raycast", args.mesh, "--structure", "octree", "--rays", str(rays)],
    "closest points, grid": ["closest", args.mesh, "--structure", "grid", "--points", str(points)],
}
print(f"{'case':30} {'A (ms)':>9} {'B (ms)':>9} {'B/A':>6}")
for name, command in cases.items():
    best = {}
    outs = {}
    for _ in range(args.rounds):
        for label, binary in (("a", args.a), ("b", args.b)):
            out = work / f"{label}.bin"
            report = json.loads(run(binary, *command, "--out", str(out), "--json"))
            best[label] = min(best.get(label, float("inf")), report["query_seconds"])
            outs[label] = out
    assert filecmp.cmp(outs["a"], outs["b"], shallow=False), f"{name}: records differ"
    a, b = best["a"] * 1e3, best["b"] * 1e3
    print(f"{name:30} {a:9.2f} {b:9.2f} {b / a:6.3f}")
