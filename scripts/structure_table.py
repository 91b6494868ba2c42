#!/usr/bin/env python3
"""Prints the README table of the structures benchmark from criterion's JSON output.

Run `cargo bench -p meshq-bench --bench structures` first (MESHQ_BENCH_MESHES picks the meshes).
For each scene: build time, random-ray and camera-ray throughput (million rays per second),
closest points per second (thousands), and each structure's random-ray ratio to the BVH's.
"""
import json
import pathlib
import sys

root = pathlib.Path(__file__).resolve().parent.parent / "target" / "criterion"
if not root.is_dir():
    sys.exit("no target/criterion: run `cargo bench -p meshq-bench --bench structures` first")

KINDS = ["bvh", "kdtree", "octree", "grid"]


def mean_ns(group, kind):
    f = root / group / kind / "new" / "estimates.json"
    if not f.is_file():
        return None
    return json.loads(f.read_text())["mean"]["point_estimate"]


def elements(group, kind):
    f = root / group / kind / "new" / "benchmark.json"
    if not f.is_file():
        return None
    t = json.loads(f.read_text()).get("throughput") or {}
    return t.get("Elements")


scenes = sorted({p.name.split("_", 1)[1] for p in root.iterdir() if p.name.startswith("build_")})
print("| scene | structure | build (ms) | random rays (M/s) | × BVH | camera rays (M/s) | closest points (k/s) |")
print("|---|---|---:|---:|---:|---:|---:|")
for scene in scenes:
    base = None
    for kind in KINDS:
        row = [scene, kind]
        b = mean_ns(f"build_{scene}", kind)
        row.append(f"{b / 1e6:.1f}" if b else "–")
        rates = {}
        for what in ["random", "camera", "closest"]:
            g = f"{what}_{scene}"
            t, n = mean_ns(g, kind), elements(g, kind)
            rates[what] = n / (t / 1e9) if t and n else None
        if kind == "bvh":
            base = rates["random"]
        r = rates["random"]
        row.append(f"{r / 1e6:.2f}" if r else "–")
        row.append(f"{r / base:.2f}" if r and base else "–")
        c = rates["camera"]
        row.append(f"{c / 1e6:.2f}" if c else "–")
        p = rates["closest"]
        row.append(f"{p / 1e3:.0f}" if p else "–")
        print("| " + " | ".join(row) + " |")
