#!/usr/bin/env python3
"""Runs the benchmarks and writes docs/benchmarks.md (and the README's summary table) from
their results.

  python3 scripts/benchmarks.py run [SECTION ...]   run sections (all by default), store results
  python3 scripts/benchmarks.py render              rewrite docs/benchmarks.md and the README table
  python3 scripts/benchmarks.py list                the sections and when each was last run

Each run stores bench/results/SECTION.json: the UTC date, the machine (CPU, cores, OS, rustc,
node), the commit, the exact commands and what they measured. `render` only reads those files,
so a table always shows the run that made it, with that run's machine, date and command; a
section never run shows the command to run it. Benchmarks are never part of CI: they take
minutes each and want an otherwise idle machine. Sections that need the benchmark-only peers
(Embree, gpytoolbox) need `scripts/peers-setup.sh` first; `node` needs `scripts/build-web.sh`.
"""
import datetime
import json
import os
import pathlib
import platform
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
RESULTS = ROOT / "bench" / "results"
CRITERION = ROOT / "target" / "criterion"
PEERS_PY = "target/peers-venv/bin/python"
BUILD_CLI = "cargo build --release -p meshq-cli"


def sh(command, env=None):
    """Runs `command` in the repository root, echoing it; returns its stdout."""
    print(f"$ {command}", file=sys.stderr, flush=True)
    merged = dict(os.environ, **(env or {}))
    done = subprocess.run(command, shell=True, cwd=ROOT, env=merged, check=True,
                          stdout=subprocess.PIPE, text=True)
    return done.stdout


def first_line(command):
    try:
        return subprocess.run(command, shell=True, capture_output=True, text=True,
                              cwd=ROOT).stdout.strip().splitlines()[0]
    except (IndexError, OSError):
        return "unknown"


def machine():
    cpu = first_line("lscpu | sed -n 's/^Model name: *//p'")
    return {
        "cpu": cpu,
        "cores": os.cpu_count(),
        "os": f"{platform.system()} {platform.release()}",
        "rustc": first_line("rustc -V"),
        "node": first_line("node -v"),
    }


def criterion_means(prefix):
    """Mean time in ms of every criterion benchmark whose group starts with `prefix`."""
    means = {}
    for estimates in sorted(CRITERION.glob("**/new/estimates.json")):
        parts = estimates.relative_to(CRITERION).parts[:-2]
        group, bench = "/".join(parts[:-1]), parts[-1]
        if group.startswith(prefix):
            ns = json.loads(estimates.read_text())["mean"]["point_estimate"]
            means.setdefault(group, {})[bench] = ns / 1e6
    return means


NUMBER = re.compile(r"^[-+]?[\d.,]+(e[-+]?\d+)?\s*(×|%|°|ms|µs|ns|s)?$|^—$|^$")


def table(header, rows):
    """A Markdown table; columns whose every cell is a number are right-aligned."""
    numeric = [all(NUMBER.match(str(row[i]).strip()) for row in rows) and bool(rows)
               for i in range(len(header))]
    out = ["| " + " | ".join(header) + " |",
           "|" + "|".join("---:" if n else "---" for n in numeric) + "|"]
    out += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(out)


def markdown_tables(text):
    """The markdown table lines a tool printed."""
    return "\n".join(line for line in text.splitlines() if line.startswith("|"))


# --- native: against obvhs, parry3d and the bvh crate ---------------------------------------

NATIVE_ROWS = [
    ("random rays, closest hit", "raycast_random", "meshq_eight_wide_packed_watertight", "obvhs_cwbvh_medium", "obvhs CWBVH `medium_build`"),
    ("random rays, closest hit", "raycast_random", "meshq_eight_wide_packed_watertight", "obvhs_medium", "obvhs BVH2 `medium_build`"),
    ("random rays, closest hit", "raycast_random", "meshq_eight_wide_packed_watertight", "parry3d", "parry3d `TriMesh`"),
    ("random rays, closest hit", "raycast_random", "meshq_eight_wide_packed_watertight", "bvh_crate", "`bvh` crate"),
    ("random rays, closest hit, four-wide", "raycast_random", "meshq_wide_packed_watertight", "obvhs_cwbvh_medium", "obvhs CWBVH `medium_build`"),
    ("camera rays, closest hit", "raycast_camera", "meshq_eight_wide_packed_watertight", "obvhs_medium", "obvhs BVH2 `medium_build`"),
    ("camera rays, closest hit", "raycast_camera", "meshq_eight_wide_packed_watertight", "obvhs_cwbvh_medium", "obvhs CWBVH `medium_build`"),
    ("random rays, any hit, four-wide", "raycast_any_random", "meshq_wide_packed_watertight", "obvhs_medium", "obvhs BVH2 `medium_build`"),
    ("closest points, batch", "closest_point", "meshq_eight_wide_packed_batch", "parry3d", "parry3d `TriMesh`, one call each"),
    ("closest points, one call each", "closest_point", "meshq_eight_wide_packed", "parry3d", "parry3d `TriMesh`"),
    ("build, `balanced` (binned SAH)", "build", "meshq_balanced", "obvhs_medium", "obvhs `medium_build`"),
    ("build, `fast`", "build", "meshq_fast", "obvhs_fast", "obvhs `fast_build`"),
    ("build, `balanced`", "build", "meshq_balanced", "parry3d_trimesh", "parry3d `TriMesh`"),
]


def run_native():
    command = "cargo bench -p meshq-bench --bench queries"
    sh(command)
    return [command], {"means_ms": criterion_means("")}


def render_native(data):
    means = data["means_ms"]
    rows = []
    for label, group, ours, theirs, peer in NATIVE_ROWS:
        m, p = means.get(group, {}).get(ours), means.get(group, {}).get(theirs)
        if m is None or p is None:
            continue
        rows.append((label, f"`{ours}`", peer, f"{m:.2f}", f"{p:.2f}", f"{p / m:.2f}×"))
    return ("Bunny (69,451 triangles), 200,000 random rays, the 1024×1024 camera, 100,000 "
            "closest points, one thread; criterion means. Ratio: the peer's time over meshq's.\n\n"
            + table(["workload", "meshq", "peer", "meshq ms", "peer ms", "ratio"], rows))


# --- Embree 4 --------------------------------------------------------------------------------

def run_embree():
    commands = [BUILD_CLI, f"{PEERS_PY} bench/peers/embree.py --json"]
    sh(commands[0])
    return commands, {"rows": json.loads(sh(commands[1]))}


def render_embree(data):
    rows = []
    for r in data["rows"]:
        rnd, cam = r["random"], r["camera"]
        rows.append((r["mesh"], f"{r['triangles']:,}", f"{rnd['ratio']:.2f}×",
                     f"{rnd['ratio_batch']:.2f}×", f"{cam['ratio']:.2f}×",
                     f"{cam['ratio_batch']:.2f}×", f"{rnd['ratio_any']:.2f}×",
                     f"{cam['ratio_any']:.2f}×", f"{r['meshq_build_s'] / r['embree_build_s']:.2f}",
                     f"{rnd['agree']:,} / {rnd['rays']:,}"))
    return ("One core each, Embree's robust scene, one ray per call (`rtcIntersect1`, "
            "`rtcOccluded1`) against `meshq raycast --per-ray` and meshq's batch entry point, "
            "best of 5 interleaved rounds. Ray columns: meshq's throughput over Embree's; build: "
            "meshq's time over Embree's commit; the last column counts random rays whose answers "
            "agree.\n\n"
            + table(["mesh", "triangles", "random rays", "random, batch", "camera rays",
                     "camera, batch", "random, any hit", "camera, any hit", "build time",
                     "random rays agreeing"], rows))


# --- the four structures ----------------------------------------------------------------------

def run_structures():
    commands = ["cargo bench -p meshq-bench --bench structures", "python3 scripts/structure_table.py"]
    sh(commands[0])
    return commands, {"table": markdown_tables(sh(commands[1]))}


def render_text_table(data):
    return data["table"]


# --- sweep SAH --------------------------------------------------------------------------------

def run_sweep():
    command = "cargo run --release -p meshq-bench --example sweep_sah"
    out = sh(command, env={"JSON": "1"})
    return [f"JSON=1 {command}"], {"meshes": [json.loads(l) for l in out.splitlines() if l.startswith("{")]}


def render_sweep(data):
    rows = []
    for m in data["meshes"]:
        binned = m["rows"][0]
        for r in m["rows"]:
            rows.append((m["mesh"], f"{m['triangles']:,}", r["build"], f"{r['sah_cost']:.2f}",
                         f"{r['batched_sah_cost']:.2f}", f"{r['nodes']:,}", f"{r['build_ms']:.1f}",
                         f"{r['build_ms'] / binned['build_ms']:.1f}×",
                         f"{r['random_mrays']:.2f}", f"{r['random_mrays'] / binned['random_mrays']:.2f}×",
                         f"{r['camera_mrays']:.2f}", f"{r['camera_mrays'] / binned['camera_mrays']:.2f}×"))
    return ("`BuildConfig::default()` (binned SAH, 32 bins) against `SplitStrategy::Sweep` with a cut "
            "weighed every 32 triangles and at every triangle, the same leaf size and costs; one "
            "thread. SAH cost: `TreeStats::sah_cost` (leaves cost their triangle count); batched: "
            "leaves cost `⌈N/4⌉`, the objective both builders minimise. Build: best of 3 (one build "
            "above 500k triangles). Rays: 200,000 random and a 512×512 camera through the default "
            "query nodes, M rays/s, best of 7 interleaved rounds, every answer checked equal first; "
            "ratios against the binned tree.\n\n"
            + table(["mesh", "triangles", "build", "SAH cost", "batched", "nodes", "build ms",
                     "build time", "random", "random ×", "camera", "camera ×"], rows))


# --- primitive methods ------------------------------------------------------------------------

def run_primitives():
    command = "cargo run --release -p meshq-bench --example primitive_methods"
    out = sh(command, env={"JSON": "1"})
    line = next(l for l in out.splitlines() if l.startswith("{"))
    return [f"JSON=1 {command}"], json.loads(line)


def render_primitives(data):
    rows = data["rows"]
    closest = [r for r in rows if r["kind"] == "closest"]
    fair = {r["method"]: r for r in closest if not r["slivers"]}
    thin = {r["method"]: r for r in closest if r["slivers"]}
    first = [(m, f"{fair[m]['mcalls']:.1f}", f"{fair[m]['worst_eps']:.1f}",
              f"{thin[m]['mcalls']:.1f}", f"{thin[m]['worst_eps']:.1f}") for m in fair]
    bunny = {r["method"]: r["mrays"] for r in rows if r["kind"] == "bunny"}
    second = [(r["method"], f"{r['mcalls']:.1f}", f"{r['worst_point_eps']:.1f}",
               f"{r['worst_uv_eps']:.0f}", f"{r['disagree']} of {r['checked']:,}",
               f"{bunny[r['method']]:.2f}") for r in rows if r["kind"] == "ray"]
    return ("One core, 200,000 cases each, best of 7 interleaved rounds (M calls/s). Worst error "
            "against an `f64` reference in units of `f32` rounding of the largest coordinate "
            "involved (ε·scale; for u, v in units of ε). Closest point on a triangle by Ericson's "
            "region walk (`closest_point_triangle`, the one every query uses), by projection "
            "with half-plane tests and by rotation into 2D, on fair random triangles and on "
            "slivers (a corner 10⁻³ of the length off the opposite edge, the point near the "
            "face):\n\n"
            + table(["method", "fair M/s", "fair worst (ε·scale)", "slivers M/s",
                     "slivers worst (ε·scale)"], first)
            + "\n\nRay–triangle tests on rays aimed at random triangles (errors where the "
            "reference hit lies 10⁻³ or more from every edge and the ray meets the plane at a "
            "cosine of 0.1 or more; disagreements: hit against miss there), and random rays per "
            "second through the bunny's BVH with each test (`RayOptions::test`; the watertight "
            "test alone runs four triangles at a time):\n\n"
            + table(["test", "M tests/s", "worst point (ε·scale)", "worst u, v (ε)",
                     "disagreements", "bunny M rays/s"], second))


# --- mesh–mesh intersection -------------------------------------------------------------------

def run_collide():
    # Everything on the bunny; the distance on the other bundled meshes too (their closest
    # pairs sit in few leaves, where fixed costs show).
    commands = ["cargo bench -p meshq-bench --bench collide"] + [
        f"MESHQ_BENCH_MESHES={mesh} cargo bench -p meshq-bench --bench collide -- distance"
        for mesh in ("fandisk", "spot")
    ]
    for command in commands:
        sh(command)
    means = {**criterion_means("collide"), **criterion_means("distance"), **criterion_means("sweep")}
    return commands, {"means_ms": means}


def duration(ms):
    """A time given in ms, in the unit that shows three figures."""
    if ms >= 1.0:
        return f"{ms:.2f} ms"
    if ms >= 1e-3:
        return f"{ms * 1e3:.2f} µs"
    return f"{ms * 1e6:.1f} ns"


def render_collide(data):
    rows = []
    for group, entries in sorted(data["means_ms"].items()):
        case = group.removeprefix("collide_").removeprefix("distance_").removeprefix("sweep_").replace("_", ", ")
        if "meshq_intersects" in entries and "parry3d_intersection_test" in entries:
            m, p = entries["meshq_intersects"], entries["parry3d_intersection_test"]
            rows.append((f"{case}: yes/no", duration(m), duration(p), f"{p / m:.2f}×"))
        if "meshq_all_pairs" in entries:
            rows.append((f"{case}: every pair", duration(entries["meshq_all_pairs"]), "—", ""))
        if "meshq_self_pairs" in entries:
            rows.append((f"{case}-intersection", duration(entries["meshq_self_pairs"]), "—", ""))
        if "meshq_mesh_distance" in entries and "parry3d_distance" in entries:
            m, p = entries["meshq_mesh_distance"], entries["parry3d_distance"]
            rows.append((f"{case}: distance", duration(m), duration(p), f"{p / m:.2f}×"))
        if "meshq_sweep" in entries and "parry3d_cast_shapes" in entries:
            m, p = entries["meshq_sweep"], entries["parry3d_cast_shapes"]
            rows.append((f"{case}: sweeps", duration(m), duration(p), f"{p / m:.2f}×"))
    return ("A mesh against a copy of itself in each placement: meshq's `meshes_intersect` "
            "against parry3d's `intersection_test` (answers checked to agree first); "
            "`mesh_distance` against parry3d's `distance` with the copy 0.01 of the diagonal "
            "apart (distances checked to agree first); 1,000 sweeps of spheres, capsules and "
            "boxes through the mesh, meshq's `sweep` against parry3d's `cast_shapes` (the same "
            "hits, checked first). Criterion means.\n\n"
            + table(["case", "meshq", "parry3d", "ratio"], rows))


# --- Node: WebAssembly against three-mesh-bvh -------------------------------------------------

def run_node():
    command = "node bench/node/bench.mjs --json"
    return [command], json.loads(sh(command))


def render_node(data):
    peers = [r for r in data["results"] if "three_mesh_bvh_ms" in r]
    pool = [r for r in data["results"] if "workers" in r]
    rows = [(r["workload"], f"{r['meshq_ms']:.1f}", f"{r['three_mesh_bvh_ms']:.1f}", f"{r['ratio']:.2f}×")
            for r in peers]
    text = (f"The npm package's Node build against three-mesh-bvh in one process, the bunny "
            f"({data['triangles']:,} triangles), the same rays and points for both. Ratio: "
            f"three-mesh-bvh's time over meshq's.\n\n"
            + table(["workload", "meshq ms", "three-mesh-bvh ms", "ratio"], rows))
    if pool:
        rows = [(r["workload"], r["workers"], f"{r['one_worker_ms']:.1f}", f"{r['all_workers_ms']:.1f}",
                 f"{r['ratio']:.2f}×") for r in pool]
        text += ("\n\nThe worker pool (`meshq-wasm/pool`) against one worker on the same batch:\n\n"
                 + table(["workload", "workers", "one worker ms", "pool ms", "speed-up"], rows))
    return text


# --- remeshing against gpytoolbox -------------------------------------------------------------

def run_remesh():
    corpus = "target/hard-corpus"
    commands = [BUILD_CLI,
                f"cargo run --release -p meshq-bench --example hard_corpus -- {corpus}",
                f"{PEERS_PY} bench/peers/remesh.py --corpus {corpus}"]
    sh(commands[0])
    sh(commands[1])
    # Two tables, a blank line apart: the corpus against gpytoolbox, then meshq refining.
    blocks = [markdown_tables(block) for block in sh(commands[2]).split("\n\n")]
    tables = [b for b in blocks if b]
    return commands, {"table": tables[0] if tables else "", "refining": "\n".join(tables[1:])}


def render_remesh(data):
    return ("meshq and gpytoolbox's `remesh_botsch` on the same meshes at each mesh's mean edge "
            "length (the cone at a twentieth of it), 10 iterations, best of 3: the bundled meshes (the creases row keeps "
            "dihedral angles sharper than 45°) and the remeshing tests' hard inputs (capsules "
            "with long side strips and high-valence poles, a closed cone of 1,024 needle-thin side facets, an open tube of strips, boxes, "
            "slivers, stretched spheres, and `scan-224`: an open range scan of 99,458 triangles with upright slivers across a jump edge). Both outputs are measured by the same code: "
            "degenerate (zero-area triangles and coincident vertices), flipped (facing against "
            "the nearest input triangle, and against every other one as near), the distance two ways over the bounding-box "
            "diagonal.\n\n" + data["table"]
            + ("\n\nRefining the bundled meshes (meshq alone; the bunny's 0.1 run would make about six "
               "million triangles): the triangles against the count of equilateral triangles of the "
               "target's side that cover the input's area, the time per output triangle, and the "
               "command's resident peak without the distance report (`--max-distance-tests 0`) over "
               "the output's size (12 bytes per vertex and per triangle); the same code measures "
               "degenerate and flipped triangles.\n\n" + data["refining"] if data.get("refining") else ""))


# --- inside and signed distance against libigl -----------------------------------------------

def run_inside():
    commands = [BUILD_CLI, f"{PEERS_PY} bench/peers/inside.py --json"]
    sh(commands[0])
    return commands, json.loads(sh(commands[1]))


def render_inside(data):
    wn, sd = [], []
    for r in data["rows"]:
        lib = r["libigl"]
        wn.append((r["mesh"], "libigl `fast_winding_number` (β 2)", f"{lib['seconds']:.3f}", "",
                   f"{lib['largest_error']:.1e}", f"{lib['mean_error']:.1e}", ""))
        for ratio, m in r["meshq"].items():
            mark = " (equal accuracy)" if ratio == r["equal_accuracy_ratio"] else ""
            wn.append((r["mesh"], f"meshq `inside --accuracy {ratio}`{mark}", f"{m['seconds']:.3f}",
                       f"{m['build_seconds']:.3f}", f"{m['largest_error']:.1e}", f"{m['mean_error']:.1e}",
                       f"{m['ratio']:.2f}×"))
        s = r["signed"]
        sd.append((r["mesh"], "libigl `signed_distance` (fast winding number)", f"{s['libigl_seconds']:.3f}",
                   str(s["libigl_wrong_signs"]), f"{s['libigl_magnitude_difference_over_diagonal']:.1e}", ""))
        for ratio, m in s["meshq"].items():
            sd.append((r["mesh"], f"meshq `closest --signed --accuracy {ratio}`", f"{m['seconds']:.3f}",
                       str(m["wrong_signs"]), f"{m['magnitude_difference_over_diagonal']:.1e}", f"{m['ratio']:.2f}×"))
    points = data["rows"][0]["points"] if data["rows"] else 0
    exact = data["rows"][0]["exact_points"] if data["rows"] else 0
    return (f"{points:,} query points per mesh (the closest-point workload), one core. Times include "
            "building the tree and its expansions (libigl's call builds its own); the error is the "
            f"largest and mean difference from the exact winding number (`igl.winding_number`, f64) on "
            f"the first {exact:,} points; β is the accuracy ratio ([inside.md](inside.md)).\n\n"
            + table(["mesh", "winding numbers", "time (s)", "of which build (s)", "largest error",
                     "mean error", "speed-up"], wn)
            + "\n\nSigned distance: wrong signs against the exact winding number (points whose number "
            "is within 0.01 of 1/2 left out); the largest difference of the magnitude from libigl's "
            "unsigned distance, over the diagonal.\n\n"
            + table(["mesh", "signed distance", "time (s)", "wrong signs", "magnitude difference",
                     "speed-up"], sd)
            + grid_text(data.get("grid")))


def grid_text(grid):
    if not grid:
        return ""
    c = grid["counts"]
    return (f"\n\nA signed-distance volume of {grid['mesh']}, {c[0]}×{c[1]}×{c[2]} samples (`meshq sdf "
            f"--resolution {max(c)}`), on every core ({grid['threads']}): meshq "
            f"{grid['meshq_seconds']:.2f} s, libigl `signed_distance` on the same points "
            f"{grid['libigl_seconds']:.2f} s: **{grid['ratio']:.2f}×**; the signs differ at "
            f"{grid['sign_disagreements']} samples.")


# --- python -----------------------------------------------------------------------------------

PY = "target/py-venv/bin/python"


BUILD_EXTENSION = ("(cd python && VIRTUAL_ENV=$PWD/../target/py-venv ../target/py-venv/bin/maturin develop "
                   "--release --quiet)")


def run_python():
    commands = [BUILD_CLI, BUILD_EXTENSION,
                f"{PY} -m pip install --quiet libigl==2.6.3",
                f"{PY} bench/python/bench.py --only rays,closest,overhead --json"]
    for command in commands[:-1]:
        sh(command)
    return commands, json.loads(sh(commands[-1]))


def run_dask():
    commands = [BUILD_EXTENSION, f"{PY} bench/python/bench.py --only dask --json"]
    sh(commands[0])
    return commands, json.loads(sh(commands[-1]))


def render_python(data):
    rows = []
    r = data.get("rays")
    if r:
        rows.append((f"{r['rays']:,} random rays, first hit", "`Mesh.raycast`", "trimesh + embreex `intersects_first`",
                     f"{r['meshq_seconds']:.3f}", f"{r['embree_seconds']:.3f}", f"{r['ratio']:.2f}×"))
        rows.append((f"{r['rays']:,} random rays, first hit", "`meshq.trimesh` drop-in `intersects_first`",
                     "trimesh + embreex `intersects_first`", f"{r['dropin_seconds']:.3f}", f"{r['embree_seconds']:.3f}",
                     f"{r['dropin_ratio']:.2f}×"))
    c = data.get("closest")
    if c:
        rows.append((f"{c['points']:,} closest points", "`Mesh.closest_points`", f"`trimesh.proximity.closest_point` ({c.get('trimesh_chunk', 0):,} points per call)",
                     f"{c['meshq_seconds']:.3f}", f"{c['trimesh_seconds']:.1f}", f"{c['trimesh_ratio']:.0f}×"))
        if "libigl_seconds" in c:
            rows.append((f"{c['points']:,} closest points, tree built in the call", "`Mesh(...)` + `closest_points`",
                         "libigl `point_mesh_squared_distance`", f"{c['meshq_with_build_seconds']:.3f}",
                         f"{c['libigl_seconds']:.3f}", f"{c['libigl_ratio']:.2f}×"))
    text = (f"One core (the script pins itself to one CPU and sets `RAYON_NUM_THREADS=1`), the bundled bunny "
            f"({data.get('triangles', 0):,} triangles), structures built before the clock starts unless said; best of 3.\n\n"
            + table(["workload", "meshq", "peer", "meshq (s)", "peer (s)", "ratio"], rows))
    if r:
        text += (f"\n\nFirst triangles equal to Embree's: {r['same_first_triangle'] * 100:.2f}% of rays; the drop-in's "
                 f"equal to `Mesh.raycast`'s: {'yes' if r['dropin_equal'] else 'no'}.")
    if c:
        text += (f" Closest distances: largest difference from trimesh's {c['trimesh_largest_difference_over_diagonal']:.1e}"
                 + (f", from libigl's {c['libigl_largest_difference_over_diagonal']:.1e}" if "libigl_seconds" in c else "")
                 + " of the diagonal.")
    o = data.get("overhead")
    if o:
        text += (f"\n\nCall overhead: a one-ray `Mesh.raycast` call takes {o['python_microseconds_per_call']:.1f} µs "
                 f"({o['calls']:,} calls), the Rust call {o['rust_microseconds_per_call']:.2f} µs "
                 f"(`meshq raycast --per-ray` on the same rays): {o['overhead_microseconds']:.1f} µs of Python per call.")
    return text


def render_dask(data):
    text = ""
    d = data.get("dask")
    if d:
        text += (f"Dask: {d['blobs']:,} blobs ({d['blob_megabytes']:.0f} MB; the bundled meshes turned, scaled and moved) × "
                 f"{d['rays_per_blob']:,} random rays each, a local cluster of two single-threaded workers against one process "
                 f"loading and querying each blob in turn and keeping every answer, the job's output "
                 f"({d['one_process_seconds']:.1f} s"
                 + (f"; {d['one_process_dropping_seconds']:.1f} s when each answer is dropped once digested, "
                    "so that the next blob's answers reuse its memory" if "one_process_dropping_seconds" in d else "")
                 + "):\n\n"
                 + table(["run", "time (s)", "ratio"], [
                     ("`Blobs(client, paths).raycast(o, d)`: answers gathered through the cluster", f"{d['dask_seconds']:.1f}", f"{d['ratio']:.2f}×"),
                     (f"`Blobs(client, paths).raycast(o, d, out=...)`: answers written to {d.get('shared_folder', '')}, returned memory-mapped",
                      f"{d['dask_shared_seconds']:.1f}", f"{d['shared_ratio']:.2f}×"),
                     ("two plain processes (no Dask), each half the blobs, answers kept in each: the machine's ceiling",
                      f"{d['two_processes_seconds']:.1f}", f"{d['two_processes_ratio']:.2f}×"),
                 ])
                 + (f"\n\nAgainst the run that drops each answer: {d['one_process_dropping_seconds'] / d['dask_seconds']:.2f}× "
                    f"gathered, {d['one_process_dropping_seconds'] / d['dask_shared_seconds']:.2f}× through "
                    f"{d.get('shared_folder', '')}." if "one_process_dropping_seconds" in d else "")
                 + f"\n\nAnswers {'identical, bit for bit, in every run' if d['identical'] else 'DIFFERENT'}; best of "
                 f"{d.get('rounds', 1)} rounds of every variant.")
    return text


# --- threads ----------------------------------------------------------------------------------

def run_threads():
    command = "cargo run --release -p meshq-bench --example scaling"
    return [command], {"lines": [l for l in sh(command).splitlines() if l.strip()]}


def render_lines(data):
    return "\n".join(f"- {line}" for line in data["lines"])


# --- firmware ---------------------------------------------------------------------------------

# The summary the script prints last (each run before it prints its own stack marks).
FIRMWARE_LINE = re.compile(r"^(flash,|static RAM|stack high-water mark,|remeshing \(|heap:)")


def run_firmware():
    command = "./scripts/firmware.sh"
    out = sh(command)
    return [command], {"lines": [l for l in out.splitlines() if FIRMWARE_LINE.match(l)]}


def render_firmware(data):
    return ("The example firmware (`firmware/`, release profile, `opt-level = \"s\"`, fat LTO) "
            "on QEMU's `mps2-an386`, reading blobs from flash; details in "
            "[firmware.md](firmware.md).\n\n"
            + render_lines({"lines": [l for l in data["lines"] if FIRMWARE_LINE.match(l)]}))


SECTIONS = {
    "native": ("Native: against obvhs, parry3d and the `bvh` crate", run_native, render_native),
    "embree": ("Native: against Embree 4", run_embree, render_embree),
    "structures": ("Native: the four structures", run_structures, render_text_table),
    "sweep": ("BVH builds: sweep SAH against binned SAH", run_sweep, render_sweep),
    "primitives": ("Primitive methods: closest point and ray–triangle", run_primitives, render_primitives),
    "collide": ("Mesh–mesh intersection, distance and sweeps against parry3d", run_collide, render_collide),
    "threads": ("Threads", run_threads, render_lines),
    "node": ("Node: WebAssembly against three-mesh-bvh", run_node, render_node),
    "remesh": ("Remeshing against gpytoolbox", run_remesh, render_remesh),
    "inside": ("Inside and signed distance against libigl", run_inside, render_inside),
    "python": ("Python: trimesh, Embree and libigl", run_python, render_python),
    "dask": ("Python on Dask: many blobs on a local cluster", run_dask, render_dask),
    "firmware": ("Firmware: Cortex-M4F in QEMU", run_firmware, render_firmware),
}


# --- the README's summary ---------------------------------------------------------------------

def summary_rows(results):
    """(workload, peer, ratio) rows for the README, each from a stored result."""
    rows = []
    if "embree" in results:
        rows_e = results["embree"]["data"]["rows"]
        bundled = [r for r in rows_e if r["triangles"] < 500_000]
        big = [r for r in rows_e if r["triangles"] >= 500_000]
        span = lambda key, kind: (min(r[kind][key] for r in bundled), max(r[kind][key] for r in bundled))
        if bundled:
            lo, hi = span("ratio", "random")
            rows.append(("random rays, closest hit, one call per ray, bundled meshes", "Embree 4, robust", f"{lo:.2f}–{hi:.2f}×"))
            lo, hi = span("ratio", "camera")
            rows.append(("camera rays, closest hit, one call per ray", "Embree 4", f"{lo:.2f}–{hi:.2f}×"))
            lo, hi = span("ratio_batch", "camera")
            rows.append(("camera rays, batch (packets)", "Embree 4, one call per ray", f"{lo:.2f}–{hi:.2f}×"))
        for r in big:
            rows.append((f"random rays, {r['mesh']} ({r['triangles']:,} triangles)", "Embree 4", f"{r['random']['ratio']:.2f}×"))
    if "native" in results:
        means = results["native"]["data"]["means_ms"]
        for label, group, ours, theirs, peer in NATIVE_ROWS[:1] + NATIVE_ROWS[8:9] + NATIVE_ROWS[10:11]:
            m, p = means.get(group, {}).get(ours), means.get(group, {}).get(theirs)
            if m and p:
                rows.append((f"{label}, bunny", peer, f"{p / m:.2f}×"))
    if "node" in results:
        wanted = {"random rays, batched vs raycastFirst": "random rays, batch",
                  "random rays, one call each: raycastXyz": "random rays, one call each",
                  "closest point, batched vs closestPointToPoint": "closest points, batch"}
        for r in results["node"]["data"]["results"]:
            if r["workload"] in wanted:
                peer = "three-mesh-bvh " + ("`closestPointToPoint`" if "closest" in r["workload"] else "`raycastFirst`")
                rows.append((f"Node (WebAssembly), bunny: {wanted[r['workload']]}", peer, f"{r['ratio']:.2f}×"))
    if "collide" in results:
        for group, e in sorted(results["collide"]["data"]["means_ms"].items()):
            if group.endswith("overlapping") and "meshq_intersects" in e and "parry3d_intersection_test" in e:
                rows.append(("mesh–mesh yes/no, two overlapping bunnies", "parry3d `intersection_test`",
                             f"{e['parry3d_intersection_test'] / e['meshq_intersects']:.1f}×"))
            if "stanford-bunny" in group and "meshq_mesh_distance" in e and "parry3d_distance" in e:
                rows.append(("mesh–mesh distance, two bunnies 0.01 diagonal apart", "parry3d `distance`",
                             f"{e['parry3d_distance'] / e['meshq_mesh_distance']:.1f}×"))
            if "stanford-bunny" in group and "meshq_sweep" in e and "parry3d_cast_shapes" in e:
                rows.append(("1,000 sphere, capsule and box sweeps at the bunny", "parry3d `cast_shapes`",
                             f"{e['parry3d_cast_shapes'] / e['meshq_sweep']:.2f}×"))
    if "inside" in results:
        for r in results["inside"]["data"].get("rows", []):
            if r["mesh"] == "stanford-bunny" and r["equal_accuracy_ratio"]:
                m = r["meshq"][r["equal_accuracy_ratio"]]
                rows.append(("winding numbers, bunny, 100k points, equal accuracy", "libigl `fast_winding_number`", f"{m['ratio']:.2f}×"))
                sd = r["signed"]["meshq"][r["equal_accuracy_ratio"]]
                rows.append(("signed distance, bunny, 100k points", "libigl `signed_distance`", f"{sd['ratio']:.2f}×"))
    if "python" in results:
        p = results["python"]["data"]
        if "rays" in p:
            rows.append(("Python, bunny: 1M random rays, `Mesh.raycast`", "trimesh + embreex `intersects_first`", f"{p['rays']['ratio']:.2f}×"))
        if "closest" in p:
            rows.append(("Python, bunny: 100k closest points", "`trimesh.proximity.closest_point`", f"{p['closest']['trimesh_ratio']:.0f}×"))
            if "libigl_ratio" in p["closest"]:
                rows.append(("Python, bunny: 100k closest points, build included", "libigl `point_mesh_squared_distance`", f"{p['closest']['libigl_ratio']:.2f}×"))
    if "dask" in results:
        d = results["dask"]["data"]["dask"]
        rows.append(("Python: 1,000 blobs × 100k rays, two Dask workers, answers via `/dev/shm`", "one process", f"{d['shared_ratio']:.2f}×"))
    if "remesh" in results:
        times = {}
        lines = results["remesh"]["data"]["table"].splitlines()
        header = [c.strip() for c in lines[0].strip("|").split("|")] if lines else []
        for line in lines[2:]:
            cells = [c.strip() for c in line.strip("|").split("|")]
            if len(cells) == len(header) and cells[0] == "stanford-bunny" and cells[-1]:
                times[cells[1]] = float(cells[-1])
        if "meshq" in times and "gpytoolbox" in times:
            rows.append(("remeshing the bunny, 10 iterations", "gpytoolbox `remesh_botsch`", f"{times['gpytoolbox'] / times['meshq']:.1f}×"))
    return rows


def stamp(result):
    m = result["machine"]
    commands = "; ".join(f"`{c}`" for c in result["commands"])
    return (f"*Run {result['date']} at `{result['commit']}` on {m['cpu']} ({m['cores']} cores), "
            f"{m['os']}, {m['rustc']}, node {m['node']}: {commands}.*")


def load_results():
    results = {}
    for name in SECTIONS:
        f = RESULTS / f"{name}.json"
        if f.is_file():
            results[name] = json.loads(f.read_text())
    return results


def render():
    results = load_results()
    out = ["# Benchmarks", "",
           "The current result of every benchmark, written by `python3 scripts/benchmarks.py render` "
           "from the results `python3 scripts/benchmarks.py run` stored in `bench/results/`; each "
           "table names the run, machine and commands that made it. Peers run in the same process "
           "or script on the same inputs, so each table compares meshq with its peer in one run. "
           "Earlier runs, what moved the numbers and the probes that were dropped are in "
           "[`log/`](log/benchmarks-2026-12-02.md).", ""]
    for name, (title, _, draw) in SECTIONS.items():
        out += [f"## {title}", ""]
        if name in results:
            out += [stamp(results[name]), "", draw(results[name]["data"]), ""]
        else:
            out += [f"Not run yet: `python3 scripts/benchmarks.py run {name}`.", ""]
    out += ["## Probes run by hand", "",
            "These compare meshq's own paths or need a set-up the script does not make; their "
            "last results, with their commands, are in the "
            "[log](log/benchmarks-2026-12-02.md): instructions per ray under callgrind, "
            "profile-guided and `target-cpu=native` builds against Embree, packets, compact and "
            "eight-wide nodes (`--example ab`), sorted ray batches, spatial splits "
            "(`--example spatial`), the worker pool's balance, and Chromium against "
            "three-mesh-bvh (`bench/browser`).", ""]
    (ROOT / "docs" / "benchmarks.md").write_text("\n".join(out))
    rows = summary_rows(results)
    readme = ROOT / "README.md"
    text = readme.read_text()
    start, end = "<!-- benchmarks:summary -->", "<!-- /benchmarks:summary -->"
    if start in text and end in text:
        head, rest = text.split(start, 1)
        _, tail = rest.split(end, 1)
        text = head + start + "\n" + table(["workload", "peer", "ratio"], rows) + "\n" + end + tail
        readme.write_text(text)
    print(f"wrote docs/benchmarks.md ({len(results)} of {len(SECTIONS)} sections) and {len(rows)} README rows")


def run(names):
    RESULTS.mkdir(parents=True, exist_ok=True)
    commit = first_line("git rev-parse --short HEAD")
    # Only changes to what is built and run count: docs and results do not move a number.
    code = ["core", "cli", "wasm", "web", "bench", "workload", "firmware", "tests", "python", "Cargo.lock"]
    changed = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no", "--", *code], cwd=ROOT,
                             capture_output=True, text=True).stdout.strip()
    if changed:
        commit += " with uncommitted changes"
    for name in names:
        title, go, _ = SECTIONS[name]
        print(f"== {name}: {title}", file=sys.stderr, flush=True)
        date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
        commands, data = go()
        result = {"section": name, "date": date, "commit": commit, "machine": machine(),
                  "commands": commands, "data": data}
        (RESULTS / f"{name}.json").write_text(json.dumps(result, indent=1) + "\n")


def main():
    args = sys.argv[1:]
    if not args or args[0] not in ("run", "render", "list"):
        sys.exit(__doc__)
    if args[0] == "list":
        results = load_results()
        for name, (title, _, _) in SECTIONS.items():
            print(f"{name:12} {results.get(name, {}).get('date', 'never run'):22} {title}")
    elif args[0] == "render":
        render()
    else:
        names = args[1:] or list(SECTIONS)
        unknown = [n for n in names if n not in SECTIONS]
        if unknown:
            sys.exit(f"unknown sections {unknown}; known: {', '.join(SECTIONS)}")
        run(names)
        render()


if __name__ == "__main__":
    main()
