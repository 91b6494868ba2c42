#!/usr/bin/env python3
"""meshq against Embree 4, in the same run, on the same meshes and the same ray files.

Embree 4 is driven through the `embreex` package (Embree 4.4 with its own TBB), a benchmark
dependency only. Both sides run on one core: this process pins itself to CPU 0 before
anything starts (`os.sched_setaffinity`), the meshq command inherits that, and so do Embree's
TBB threads, so builds are single-threaded too.

For each mesh:
- the rays are the DESIGN.md workloads written by `meshq workload` (random rays, default
  1,000,000, and the 1024x1024 camera); Embree reads the same float32 files;
- meshq: `meshq raycast MESH --rays FILE --out HITS --json --per-ray` (and `--any`), its own
  `query_seconds` (queries only, one ray per call) and `build_seconds` (MeshBvh::build:
  the binned-SAH tree, packed triangles and the wide collapse queries walk); then the same without
  `--per-ray` (the batch entry point: packets for the camera's rays, which share an origin;
  the random rays sorted by the line they draw through the mesh's box on meshes of 131,072
  triangles or more), whose records must equal the per-ray ones byte for byte;
- Embree: a scene with the robust flag (`RTC_SCENE_FLAG_ROBUST`), one triangle mesh; the build
  is the commit (timed through the first `run` call, with one ray); closest hit is
  `rtcIntersect1` and any hit `rtcOccluded1`, one ray per call, looped in embreex's compiled
  code;
- both answers are compared ray by ray (the same triangle, or a distance within 1e-5 of the
  mesh's size: two triangles meeting where the ray lands);
- times are the best of `--repeat` rounds (default 5); each round runs every meshq command
  and Embree query of the workload once, one after another, so that the machine's slow spells
  fall on both sides alike.

The 1.1M-triangle case is the bunny subdivided twice (each triangle into four, midpoints
shared), written to target/peers/ as a binary PLY at run time; it is never committed.

Set up once: scripts/peers-setup.sh (a virtual environment in target/peers-venv).
Run: target/peers-venv/bin/python bench/peers/embree.py [--meshq BIN] [--rays N]
     [--eight-wide | --four-wide] [--repeat K] [--json] [MESH ...]
     (names of bundled meshes, paths, or `bunny-x16`)
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import time

import numpy as np
from embreex import rtcore_scene as rtcs
from embreex.mesh_construction import TriangleMesh
from meshfiles import read_mesh, read_obj, write_ply

ROOT = pathlib.Path(__file__).resolve().parents[2]
DEFAULT_MESHES = ["stanford-bunny", "fandisk", "spot", "cow", "teapot", "bunny-x16"]


def subdivide(v, f):
    """Each triangle into four, through its edge midpoints (each midpoint made once)."""
    edges = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    keys = np.sort(edges, axis=1)
    unique, inverse = np.unique(keys, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    mids = ((v[unique[:, 0]].astype(np.float64) + v[unique[:, 1]]) / 2).astype(np.float32)
    base = len(v)
    n = len(f)
    m01, m12, m20 = (base + inverse[k * n:(k + 1) * n] for k in range(3))
    a, b, c = f[:, 0], f[:, 1], f[:, 2]
    faces = np.concatenate([
        np.stack([a, m01, m20], 1), np.stack([m01, b, m12], 1),
        np.stack([m20, m12, c], 1), np.stack([m01, m12, m20], 1),
    ])
    return np.concatenate([v, mids]), faces


def mesh_path(name, scratch):
    if name == "bunny-x16":
        path = ROOT / "target/peers/bunny-x16.ply"
        if not path.exists():
            v, f = read_obj(ROOT / "assets/stanford-bunny.obj", np.float32)
            for _ in range(2):
                v, f = subdivide(v, f)
            path.parent.mkdir(parents=True, exist_ok=True)
            write_ply(path, v, f)
        return path
    p = pathlib.Path(name)
    if p.exists():
        return p
    return ROOT / "assets" / f"{name}.obj"


MESHQ_FLAGS = []  # flags every meshq raycast gets (`--eight-wide`, `--four-wide`)


def meshq(binary, mesh, rays, out, *flags):
    result = subprocess.run(
        [binary, "raycast", str(mesh), "--rays", str(rays), "--out", str(out), "--json", *flags,
         *MESHQ_FLAGS],
        check=True, capture_output=True, text=True)
    return json.loads(result.stdout)


def read_rays(path):
    r = np.fromfile(path, dtype="<f4").reshape(-1, 6)
    return np.ascontiguousarray(r[:, :3]), np.ascontiguousarray(r[:, 3:])


def embree_build(v, f):
    """A robust scene with the mesh, committed; returns it and the commit time."""
    scene = rtcs.EmbreeScene(robust=True)
    TriangleMesh(scene, v, f.astype(np.int32))
    o = np.zeros((1, 3), np.float32)
    d = np.ones((1, 3), np.float32)
    start = time.perf_counter()
    scene.run(o, d)  # commits the scene (builds the BVH), then casts one ray
    return scene, time.perf_counter() - start


def timed(f):
    """How long `f` took, and what it returned."""
    start = time.perf_counter()
    result = f()
    return time.perf_counter() - start, result


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("meshes", nargs="*", default=DEFAULT_MESHES)
    parser.add_argument("--meshq", default=str(ROOT / "target/release/meshq"))
    parser.add_argument("--rays", type=int, default=1_000_000)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--json", action="store_true")
    nodes = parser.add_mutually_exclusive_group()
    nodes.add_argument("--eight-wide", action="store_true",
                       help="meshq walks its eight-wide tree (`meshq raycast --eight-wide`)")
    nodes.add_argument("--four-wide", action="store_true",
                       help="meshq walks its four-wide tree (`meshq raycast --four-wide`)")
    args = parser.parse_args()
    if args.eight_wide:
        MESHQ_FLAGS.append("--eight-wide")
    if args.four_wide:
        MESHQ_FLAGS.append("--four-wide")
    os.sched_setaffinity(0, {sorted(os.sched_getaffinity(0))[0]})
    say = (lambda *a: None) if args.json else print
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        s = pathlib.Path(scratch)
        for name in args.meshes:
            path = mesh_path(name, s)
            v, f = read_mesh(path, np.float32)
            label = pathlib.Path(name).stem
            say(f"== {label}: {len(f):,} triangles")
            workloads = {}
            for kind, extra in [("random", ["--kind", "random-rays", "--count", str(args.rays)]),
                                ("camera", ["--kind", "camera-rays"])]:
                file = s / f"{label}-{kind}.bin"
                subprocess.run([args.meshq, "workload", str(path), *extra, "-o", str(file)],
                               check=True, capture_output=True)
                workloads[kind] = file
            builds = [embree_build(v, f) for _ in range(args.repeat)]
            scene, embree_build_s = min(builds, key=lambda b: b[1])
            row = {"mesh": label, "triangles": int(len(f)), "embree_build_s": embree_build_s}
            size = float(np.linalg.norm(v.max(0) - v.min(0)))
            for kind, file in workloads.items():
                o, d = read_rays(file)
                out = s / "hits.bin"
                # Round by round, each meshq run beside the Embree run it is compared with, so
                # that a slow spell of the machine falls on both sides alike.
                runs, em_times, any_runs, em_any_times, batch_runs, batch_any_runs = ([] for _ in range(6))
                per_ray_bytes = any_bytes = None
                for _ in range(args.repeat):
                    runs.append(meshq(args.meshq, path, file, out, "--per-ray"))
                    records = out.read_bytes()
                    if per_ray_bytes not in (None, records):
                        sys.exit(f"{label} {kind}: two runs of the same rays differ")
                    per_ray_bytes = records
                    em_times.append(timed(lambda: scene.run(o, d, output=1)))
                    any_runs.append(meshq(args.meshq, path, file, out, "--any", "--per-ray"))
                    records = out.read_bytes()
                    if any_bytes not in (None, records):
                        sys.exit(f"{label} {kind}: two any-hit runs of the same rays differ")
                    any_bytes = records
                    em_any_times.append(timed(lambda: scene.run(o, d, query="OCCLUDED")))
                    # The batch entry point (packets for rays that share an origin): timed, and
                    # its records checked equal to one ray per call, byte for byte.
                    batch_runs.append(meshq(args.meshq, path, file, out))
                    batch_same = out.read_bytes() == per_ray_bytes
                    batch_any_runs.append(meshq(args.meshq, path, file, out, "--any"))
                    batch_any_same = out.read_bytes() == any_bytes
                    if not (batch_same and batch_any_same):
                        sys.exit(f"{label} {kind}: batched records differ from one ray per call")
                ours = np.frombuffer(per_ray_bytes, dtype=[("t", "<f4"), ("tri", "<u4")])
                ours_any = np.frombuffer(any_bytes, dtype=[("t", "<f4"), ("tri", "<u4")])["tri"] != 0xFFFFFFFF
                mq = min(r["query_seconds"] for r in runs)
                anyq = min(r["query_seconds"] for r in any_runs)
                batch = min(r["query_seconds"] for r in batch_runs)
                batch_any = min(r["query_seconds"] for r in batch_any_runs)
                row["meshq_build_s"] = min(row.get("meshq_build_s", 1e9), *(r["build_seconds"] for r in runs))
                em, theirs = min(em_times, key=lambda x: x[0])
                em_any, occluded = min(em_any_times, key=lambda x: x[0])
                hit = theirs["primID"] >= 0
                same = (ours["tri"] == np.where(hit, theirs["primID"], 0xFFFFFFFF).astype(np.uint32))
                close = np.isfinite(ours["t"]) & hit & (
                    np.abs(ours["t"] * np.linalg.norm(d, axis=1) - theirs["tfar"] * np.linalg.norm(d, axis=1))
                    <= 1e-5 * size)
                agree = int(np.count_nonzero(same | close))
                agree_any = int(np.count_nonzero(ours_any == (occluded >= 0)))
                n = len(o)
                row[kind] = {
                    "rays": n, "hits": int(np.count_nonzero(hit)), "agree": agree, "agree_any": agree_any,
                    "meshq_s": mq, "embree_s": em, "ratio": em / mq,
                    "meshq_any_s": anyq, "embree_any_s": em_any, "ratio_any": em_any / anyq,
                    "meshq_batch_s": batch, "ratio_batch": em / batch,
                    "meshq_batch_any_s": batch_any, "ratio_batch_any": em_any / batch_any,
                }
                say(f"  {kind}: closest hit meshq {n / mq / 1e6:.2f} M rays/s, Embree {n / em / 1e6:.2f} "
                    f"-> {em / mq:.2f}x; any hit {n / anyq / 1e6:.2f} vs {n / em_any / 1e6:.2f} -> "
                    f"{em_any / anyq:.2f}x; answers agree on {agree:,} of {n:,} (any hit {agree_any:,}); "
                    f"meshq batched: {em / batch:.2f}x, any hit {em_any / batch_any:.2f}x (same records)")
            say(f"  build: meshq {row['meshq_build_s'] * 1e3:.1f} ms, Embree commit {embree_build_s * 1e3:.1f} ms "
                f"-> meshq takes {row['meshq_build_s'] / embree_build_s:.2f}x Embree's time")
            rows.append(row)
    if args.json:
        json.dump(rows, sys.stdout, indent=2)
        print()
    else:
        print("\n| mesh | triangles | random rays | random, batch | camera rays | camera, batch | "
              "random any hit | camera any hit | camera any, batch | build time (meshq / Embree) |")
        print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
        for r in rows:
            print(f"| {r['mesh']} | {r['triangles']:,} | {r['random']['ratio']:.2f}x | "
                  f"{r['random']['ratio_batch']:.2f}x | {r['camera']['ratio']:.2f}x | "
                  f"{r['camera']['ratio_batch']:.2f}x | {r['random']['ratio_any']:.2f}x | "
                  f"{r['camera']['ratio_any']:.2f}x | {r['camera']['ratio_batch_any']:.2f}x | "
                  f"{r['meshq_build_s'] / r['embree_build_s']:.2f} |")
        print("\nray columns: meshq's throughput / Embree's (one core, best of "
              f"{args.repeat}; Embree one ray per call; meshq one ray per call, or its batch entry "
              "point where it says batch); build: meshq's time / Embree's commit.")


if __name__ == "__main__":
    main()
