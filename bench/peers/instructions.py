#!/usr/bin/env python3
"""Instructions per ray, meshq against Embree 4, counted by Valgrind (callgrind).

Wall-clock ratios on a shared machine move by ±10% or more from run to run; instruction
counts do not. This script counts the instructions each library executes inside its one-ray
entry point, on the same meshes and the same ray files as `embree.py`:
- meshq: `meshq raycast --per-ray`, counting inside `meshq::query::ray::walk` (ray set-up, the
  walk, the triangle tests, the answer), nothing of the command around it;
- Embree: `rtcIntersect1` on a robust scene (`RTC_SCENE_FLAG_ROBUST`), driven by embreex,
  counting inside `rtcIntersect1` only (not the Python loop around it).
Under Valgrind, Embree picks its AVX2 code (Valgrind has no AVX-512), and meshq runs as built
(`--meshq BIN` for another build, such as `RUSTFLAGS="-C target-cpu=native"`). Instruction
counts are not times: a cache miss or a mispredicted branch costs many instructions' worth,
so the counts show where the work is, and the timed ratios stay in `embree.py`.

Needs `valgrind` and the peers environment (scripts/peers-setup.sh).
Run: target/peers-venv/bin/python bench/peers/instructions.py [--meshq BIN] [--rays N]
     [--image WxH] [--json] [MESH ...]   (names of bundled meshes, paths, or `bunny-x16`)
"""
import argparse
import json
import pathlib
import re
import subprocess
import sys
import tempfile

from embree import DEFAULT_MESHES, ROOT, mesh_path, read_rays

# bunny-x16 under Valgrind takes minutes to build on both sides: opt in by name.
MESHES = [m for m in DEFAULT_MESHES if m != "bunny-x16"]


def embree_child(mesh, rays):
    """Casts every ray of `rays` at `mesh` with Embree, one `rtcIntersect1` each."""
    import numpy as np
    from embreex import rtcore_scene as rtcs
    from embreex.mesh_construction import TriangleMesh
    from meshfiles import read_mesh

    v, f = read_mesh(mesh, np.float32)
    scene = rtcs.EmbreeScene(robust=True)
    TriangleMesh(scene, v, f.astype(np.int32))
    o, d = read_rays(rays)
    scene.run(o[:1], d[:1])  # the commit, and one ray (counted: one ray in the total)
    scene.run(o, d, output=1)


def callgrind(command, function):
    """Instructions executed inside `function` (and what it calls) by `command`."""
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(tmp) / "callgrind.out"
        result = subprocess.run(
            ["valgrind", "--tool=callgrind", f"--toggle-collect={function}",
             f"--callgrind-out-file={out}", *command],
            check=True, capture_output=True, text=True)
    found = re.search(r"Collected\s*:\s*(\d+)", result.stderr)
    if not found:
        sys.exit(f"no instruction count from valgrind:\n{result.stderr}")
    return int(found.group(1))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("meshes", nargs="*", default=MESHES)
    parser.add_argument("--meshq", default=str(ROOT / "target/release/meshq"))
    parser.add_argument("--rays", type=int, default=20_000, help="random rays per mesh")
    parser.add_argument("--image", default="160x120", help="camera image, WIDTHxHEIGHT")
    parser.add_argument("--json", action="store_true")
    parser.add_argument("--embree-child", nargs=2, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.embree_child:
        embree_child(*args.embree_child)
        return
    say = (lambda *a: None) if args.json else print
    rows = []
    say(f"{'mesh':16} {'rays':8} {'meshq':>8} {'Embree':>8} {'ratio':>6}  (instructions per ray)")
    with tempfile.TemporaryDirectory() as tmp:
        for name in args.meshes:
            mesh = mesh_path(name, tmp)
            for kind, extra in [("random", ["--count", str(args.rays)]),
                                ("camera", ["--kind", "camera-rays", "--image", args.image])]:
                rays = pathlib.Path(tmp) / f"{kind}.bin"
                subprocess.run([args.meshq, "workload", str(mesh), *extra, "-o", str(rays)],
                               check=True, capture_output=True)
                count = rays.stat().st_size // 24
                ours = callgrind(
                    [args.meshq, "raycast", str(mesh), "--rays", str(rays),
                     "--out", str(pathlib.Path(tmp) / "hits.bin"), "--per-ray"],
                    "meshq::query::ray::walk*")
                theirs = callgrind(
                    [sys.executable, __file__, "--embree-child", str(mesh), str(rays)],
                    "rtcIntersect1")
                row = {
                    "mesh": name, "rays": kind, "count": count,
                    "meshq_per_ray": ours / count, "embree_per_ray": theirs / (count + 1),
                }
                row["ratio"] = row["meshq_per_ray"] / row["embree_per_ray"]
                rows.append(row)
                say(f"{name:16} {kind:8} {row['meshq_per_ray']:8.0f} "
                    f"{row['embree_per_ray']:8.0f} {row['ratio']:5.2f}×")
    if args.json:
        print(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
