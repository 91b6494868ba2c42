#!/usr/bin/env python3
"""meshq's Python package against trimesh (with Embree through embreex), libigl and itself on
a Dask cluster, in the same run.

On one core unless said (the process pins itself to CPU 0 and sets RAYON_NUM_THREADS=1 before
meshq starts; the Dask workers get a core each), on the bundled bunny:
- rays: `--rays` random rays (`meshq workload --kind random-rays`, seed 1), first hits:
  `meshq.Mesh.raycast` (the batch) and `meshq.trimesh.RayMeshIntersector.intersects_first`
  (the drop-in, with its float64 conversion) against trimesh's
  `ray_pyembree.RayMeshIntersector.intersects_first` (Embree 4 through embreex); structures
  built before the clock starts; the first triangles compared;
- closest points: `--points` points (`meshq workload --kind points`, seed 2):
  `Mesh.closest_points` against `trimesh.proximity.closest_point` (trimesh's r-tree built and
  cached by a warm-up call first; called on 10,000 points at a time, since one call of 20,000
  peaks at 9.4 GB) and libigl's `point_mesh_squared_distance` (whose call builds
  its own tree: meshq is timed with its build too, for that row); distances compared;
- call overhead: one-ray `Mesh.raycast` calls on the same rays against the Rust CLI's
  one-call-per-ray time (`meshq raycast --per-ray --json`);
- Dask: `--blobs` blob files (the bundled meshes turned, scaled and moved, written to a
  temporary directory) × `--dask-rays` random rays: `meshq.dask.Blobs(client, paths).raycast`
  on a local cluster of two single-threaded workers (answers gathered into this process, and
  answers written to /dev/shm with `out=` and returned memory-mapped) against one process
  loading and querying each blob in turn and keeping every answer (the job's output; the time
  when each answer is dropped once digested is reported too), and two plain processes (no
  Dask) each doing half, keeping their answers, the machine's own ceiling; every answer
  compared bit for bit (by digest).
Times are the best of `--repeat` rounds (Dask: of `--dask-rounds` rounds of every variant).

Set up: scripts/setup.sh (target/py-venv), then the extension built for speed:
  (cd python && VIRTUAL_ENV=$PWD/../target/py-venv ../target/py-venv/bin/maturin develop --release)
  target/py-venv/bin/pip install libigl==2.6.3
Run: target/py-venv/bin/python bench/python/bench.py [--meshq BIN] [--json]
"""
import argparse
import hashlib
import json
import multiprocessing
import os
import pathlib
import subprocess
import sys
import tempfile
import time

os.environ["RAYON_NUM_THREADS"] = "1"


def set_cpus(cpus):
    """Every thread of this process on `cpus` (a thread made later inherits its maker's)."""
    for tid in os.listdir("/proc/self/task"):
        try:
            os.sched_setaffinity(int(tid), cpus)
        except OSError:
            pass  # the thread ended meanwhile


import numpy as np  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]


def best(repeat, run):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        out = run()
        times.append(time.perf_counter() - start)
    return min(times), out


def read_obj(path):
    vertices, faces = [], []
    for line in pathlib.Path(path).read_text().splitlines():
        parts = line.split()
        if parts and parts[0] == "v":
            vertices.append([float(x) for x in parts[1:4]])
        elif parts and parts[0] == "f":
            c = [int(p.split("/")[0]) - 1 for p in parts[1:]]
            faces.extend([c[0], c[k], c[k + 1]] for k in range(1, len(c) - 1))
    return np.array(vertices), np.array(faces, dtype=np.int64)


def workload(meshq, mesh, kind, count, out):
    subprocess.run([meshq, "workload", mesh, "--kind", kind, "--count", str(count), "-o", out],
                   check=True, stdout=subprocess.DEVNULL)
    return np.fromfile(out, dtype="<f4")


def rays_section(args, v, f, rays):
    import meshq
    import trimesh
    from meshq.trimesh import RayMeshIntersector
    from trimesh.ray import ray_pyembree

    origins, directions = rays[:, :3].astype(np.float64), rays[:, 3:].astype(np.float64)
    mesh = meshq.Mesh(v, f)
    tm = trimesh.Trimesh(v, f, process=False)
    embree = ray_pyembree.RayMeshIntersector(tm)
    embree.intersects_first(origins[:10], directions[:10])  # builds Embree's scene
    ours = RayMeshIntersector(tm)
    ours.intersects_first(origins[:10], directions[:10])  # builds meshq's BVH
    o32, d32 = rays[:, :3].copy(), rays[:, 3:].copy()
    t_batch, (_, tri, _, _) = best(args.repeat, lambda: mesh.raycast(o32, d32))
    t_drop, tri_drop = best(args.repeat, lambda: ours.intersects_first(origins, directions))
    t_embree, tri_embree = best(args.repeat, lambda: embree.intersects_first(origins, directions))
    return {
        "rays": len(rays),
        "meshq_seconds": t_batch,
        "dropin_seconds": t_drop,
        "embree_seconds": t_embree,
        "ratio": t_embree / t_batch,
        "dropin_ratio": t_embree / t_drop,
        "hits": int((tri >= 0).sum()),
        "same_first_triangle": float(np.mean(tri == tri_embree)),
        "dropin_equal": bool(np.array_equal(tri, tri_drop)),
    }


TRIMESH_CHUNK = 10_000


def closest_section(args, v, f, points):
    import meshq
    import trimesh

    mesh = meshq.Mesh(v, f)
    t_meshq, (_, d, _, _, _) = best(args.repeat, lambda: mesh.closest_points(points))
    t_built, _ = best(args.repeat, lambda: meshq.Mesh(v, f).closest_points(points))
    tm = trimesh.Trimesh(v, f, process=False)
    trimesh.proximity.closest_point(tm, points[:10])  # builds and caches its r-tree
    p64 = points.astype(np.float64)

    def trimesh_chunks():
        # In chunks: one call of 20,000 points peaks at 9.4 GB (its candidate arrays), so 100,000
        # in one call exhaust this machine's 24 GB.
        return np.concatenate([trimesh.proximity.closest_point(tm, p64[i:i + TRIMESH_CHUNK])[1]
                               for i in range(0, len(p64), TRIMESH_CHUNK)])

    t_trimesh, d_trimesh = best(1, trimesh_chunks)
    out = {
        "points": len(points),
        "meshq_seconds": t_meshq,
        "meshq_with_build_seconds": t_built,
        "trimesh_seconds": t_trimesh,
        "trimesh_chunk": TRIMESH_CHUNK,
        "trimesh_ratio": t_trimesh / t_meshq,
        "trimesh_largest_difference_over_diagonal": float(
            np.max(np.abs(d - d_trimesh)) / np.linalg.norm(v.max(0) - v.min(0))),
    }
    try:
        import igl
    except ImportError:
        out["libigl"] = "not installed (pip install libigl==2.6.3)"
        return out
    vf, ff = v.astype(np.float64), f.astype(np.int64)
    t_igl, result = best(args.repeat, lambda: igl.point_mesh_squared_distance(p64, vf, ff))
    d_igl = np.sqrt(result[0])
    out.update({
        "libigl_seconds": t_igl,
        "libigl_ratio": t_igl / t_built,
        "libigl_ratio_query_only": t_igl / t_meshq,
        "libigl_largest_difference_over_diagonal": float(
            np.max(np.abs(d - d_igl)) / np.linalg.norm(v.max(0) - v.min(0))),
    })
    return out


def overhead_section(args, v, f, rays, rays_file):
    import meshq

    mesh = meshq.Mesh(v, f)
    count = min(len(rays), args.single)
    o, d = rays[:count, :3].copy(), rays[:count, 3:].copy()
    one = [(o[i:i + 1], d[i:i + 1]) for i in range(count)]

    def calls():
        for a, b in one:
            mesh.raycast(a, b)

    t_python, _ = best(args.repeat, calls)
    small = pathlib.Path(rays_file).with_suffix(".single.rays")
    rays[:count].astype("<f4").tofile(small)
    rust = []
    for _ in range(args.repeat):
        report = subprocess.run([args.meshq, "raycast", str(ROOT / "assets/stanford-bunny.obj"),
                                 "--rays", str(small), "--out", os.devnull, "--per-ray", "--json"],
                                check=True, capture_output=True, text=True)
        rust.append(json.loads(report.stdout)["query_seconds"])
    return {
        "calls": count,
        "python_microseconds_per_call": t_python / count * 1e6,
        "rust_microseconds_per_call": min(rust) / count * 1e6,
        "overhead_microseconds": (t_python - min(rust)) / count * 1e6,
    }


def placed_meshes(count, seed):
    rng = np.random.default_rng(seed)
    sources = [read_obj(ROOT / "assets" / n) for n in
               ("fandisk.obj", "spot.obj", "cow.obj", "teapot.obj", "uv-sphere.obj")]
    for i in range(count):
        v, f = sources[i % len(sources)]
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        centred = v - v.mean(0)
        yield (centred / np.abs(centred).max()) @ q.T * rng.uniform(0.5, 1.5) + rng.normal(size=3) * 0.1, f


def digest(arrays):
    h = hashlib.sha256()
    for a in arrays:
        h.update(np.ascontiguousarray(a).tobytes())
    return h.hexdigest()


def _query_blobs(paths, origins, directions):
    """One of the two plain processes: the digests of its blobs' answers, every answer kept
    until the last is made, as the job's output."""
    import meshq

    answers = [meshq.Mesh.from_blob(pathlib.Path(p).read_bytes()).raycast(origins, directions)
               for p in paths]
    return [digest(a) for a in answers]


def dask_section(args):
    import distributed
    import meshq
    from meshq.dask import Blobs

    rng = np.random.default_rng(7)
    origins = (rng.random((args.dask_rays, 3)) - 0.5) * 6
    targets = (rng.random((args.dask_rays, 3)) - 0.5) * 1.6
    o32, d32 = origins.astype(np.float32), (targets - origins).astype(np.float32)
    with tempfile.TemporaryDirectory(prefix="meshq-dask-") as folder:
        paths, size = [], 0
        for i, (v, f) in enumerate(placed_meshes(args.blobs, seed=3)):
            path = pathlib.Path(folder) / f"{i:04}.meshq"
            path.write_bytes(meshq.Mesh(v, f).to_blob())
            size += path.stat().st_size
            paths.append(path)

        def one_process(keep):
            # Loading and querying each blob is timed; the digest of its answers is not. The
            # job's output is every answer (`keep`), as the cluster's is; dropping each once
            # digested lets the allocator hand the next blob the same, already mapped memory.
            seconds, digests, kept = 0.0, [], []
            for p in paths:
                start = time.perf_counter()
                answers = meshq.Mesh.from_blob(p.read_bytes()).raycast(o32, d32)
                seconds += time.perf_counter() - start
                digests.append(digest(answers))
                if keep:
                    kept.append(answers)
            return seconds, digests

        # Rounds of every variant one after the other, best of each: this machine's speed drifts
        # by a fifth over minutes.
        t_one, t_dropped, t_two, t_dask, t_shared = (float("inf"),) * 5
        shm = "/dev/shm" if os.path.isdir("/dev/shm") else None
        set_cpus(set(range(os.cpu_count())))
        cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                           dashboard_address=None, silence_logs=40,
                                           env={"RAYON_NUM_THREADS": "1"})
        with distributed.Client(cluster) as client:
            cpus = client.run(lambda: len(os.sched_getaffinity(0)))
            # Workers import meshq and numpy once, as the process measured alone already has.
            Blobs(client, paths[:2]).raycast(o32[:10], d32[:10])
            for _ in range(args.dask_rounds):
                set_cpus({0})
                seconds, want = one_process(keep=True)
                t_one = min(t_one, seconds)
                seconds, _ = one_process(keep=False)
                t_dropped = min(t_dropped, seconds)
                set_cpus(set(range(os.cpu_count())))
                # The machine's own ceiling: two plain processes, each loading and querying
                # half the blobs (no Dask).
                with multiprocessing.get_context("spawn").Pool(2) as pool:
                    start = time.perf_counter()
                    halves = pool.starmap(_query_blobs, [([str(p) for p in paths[k::2]], o32, d32) for k in (0, 1)])
                    t_two = min(t_two, time.perf_counter() - start)
                two = [None] * len(paths)
                two[0::2], two[1::2] = halves
                start = time.perf_counter()
                answers = Blobs(client, paths).raycast(o32, d32)
                t_dask = min(t_dask, time.perf_counter() - start)
                got = [digest(a) for a in answers]
                del answers
                with tempfile.TemporaryDirectory(prefix="meshq-answers-", dir=shm) as out:
                    start = time.perf_counter()
                    answers = Blobs(client, paths).raycast(o32, d32, out=out)
                    t_shared = min(t_shared, time.perf_counter() - start)
                    got_shared = [digest(a) for a in answers]
                    del answers
        cluster.close()
        set_cpus({0})
    return {
        "blobs": args.blobs,
        "blob_megabytes": size / 1e6,
        "rays_per_blob": args.dask_rays,
        "one_process_seconds": t_one,
        "one_process_dropping_seconds": t_dropped,
        "dask_seconds": t_dask,
        "ratio": t_one / t_dask,
        "dask_shared_seconds": t_shared,
        "shared_ratio": t_one / t_shared,
        "shared_folder": shm or tempfile.gettempdir(),
        "two_processes_seconds": t_two,
        "two_processes_ratio": t_one / t_two,
        "identical": got == want and got_shared == want and two == want,
        "rounds": args.dask_rounds,
        "worker_cpus": sorted(cpus.values()),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--meshq", default=str(ROOT / "target/release/meshq"))
    parser.add_argument("--rays", type=int, default=1_000_000)
    parser.add_argument("--points", type=int, default=100_000)
    parser.add_argument("--single", type=int, default=100_000)
    parser.add_argument("--blobs", type=int, default=1000)
    parser.add_argument("--dask-rays", type=int, default=100_000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--dask-rounds", type=int, default=2)
    parser.add_argument("--only", default="rays,closest,overhead,dask")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    # Pinned here, not on import: Dask's workers start by importing this module again.
    set_cpus({0})
    only = set(args.only.split(","))
    bunny = str(ROOT / "assets/stanford-bunny.obj")
    v, f = read_obj(bunny)
    result = {"mesh": "stanford-bunny", "triangles": len(f)}
    with tempfile.TemporaryDirectory(prefix="meshq-py-bench-") as folder:
        rays_file = os.path.join(folder, "random.rays")
        rays = workload(args.meshq, bunny, "random-rays", args.rays, rays_file).reshape(-1, 6)
        points = workload(args.meshq, bunny, "points", args.points,
                          os.path.join(folder, "points.bin")).reshape(-1, 3)
        if "rays" in only:
            result["rays"] = rays_section(args, v, f, rays)
        if "closest" in only:
            result["closest"] = closest_section(args, v, f, points)
        if "overhead" in only:
            result["overhead"] = overhead_section(args, v, f, rays, rays_file)
    if "dask" in only:
        result["dask"] = dask_section(args)
    print(json.dumps(result, indent=1) if args.json else result)


if __name__ == "__main__":
    sys.exit(main())
