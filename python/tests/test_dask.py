"""meshq.dask on a two-worker local cluster: bakes and queries equal the single-process
answers bit for bit, in input order, also when a worker is killed in the middle of a job."""

import os
import signal
import time

import numpy as np
import pytest

distributed = pytest.importorskip("distributed")

import meshq  # noqa: E402
from conftest import random_rays, read_obj  # noqa: E402
from meshq.dask import Blobs, bake_directory  # noqa: E402


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(
        n_workers=2,
        threads_per_worker=1,
        processes=True,
        dashboard_address=None,
        env={"RAYON_NUM_THREADS": "1"},
    )
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()


def placed_copies(count, seed):
    """`count` different meshes: the bundled fandisk and spot, each turned, scaled and moved."""
    rng = np.random.default_rng(seed)
    sources = [read_obj("fandisk.obj"), read_obj("spot.obj")]
    meshes = []
    for i in range(count):
        v, f = sources[i % 2]
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        centred = v - v.mean(0)
        scaled = centred / np.abs(centred).max()
        meshes.append((scaled @ q.T * rng.uniform(0.5, 1.5) + rng.normal(size=3) * 0.1, f))
    return meshes


def write_obj(path, v, f):
    with open(path, "w") as out:
        out.writelines(f"v {x:.17g} {y:.17g} {z:.17g}\n" for x, y, z in v)
        out.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in f)


def test_bake_directory_writes_the_blobs_one_process_would(client, tmp_path):
    trimesh = pytest.importorskip("trimesh")
    source = tmp_path / "meshes"
    source.mkdir()
    for i, (v, f) in enumerate(placed_copies(4, seed=1)):
        write_obj(source / f"part-{i}.obj", v, f)
    paths = bake_directory(client, source, tmp_path / "blobs", structure="octree")
    assert [p.name for p in paths] == [f"part-{i}.meshq" for i in range(4)]
    for i, path in enumerate(paths):
        loaded = trimesh.load(source / f"part-{i}.obj", force="mesh", process=False)
        want = meshq.Mesh(loaded.vertices, loaded.faces, structure="octree").to_blob()
        assert path.read_bytes() == want
    assert not list((tmp_path / "blobs").glob(".bake-*"))
    (source / "broken.obj").write_text("v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    with pytest.raises(RuntimeError, match="broken.obj"):
        bake_directory(client, source, tmp_path / "blobs")


def test_queries_over_blobs_equal_one_process(client, tmp_path):
    meshes = [meshq.Mesh(v, f) for v, f in placed_copies(6, seed=2)]
    blobs = [m.to_blob() for m in meshes]
    paths = []
    for i, blob in enumerate(blobs):
        paths.append(tmp_path / f"{i}.meshq")
        paths[-1].write_bytes(blob)
    origins, directions = random_rays(np.array([[-1.5, -1.5, -1.5], [1.5, 1.5, 1.5]]), 5000, seed=3)
    points = origins * 0.5
    for placed in (Blobs(client, blobs), Blobs(client, paths), Blobs(client, blobs, group=4)):
        assert len(placed) == len(meshes)
        got_rays = placed.raycast(origins, directions)
        got_closest = placed.closest_points(points)
        got_signed = placed.signed_distances(points[:500])
        for m, rays, closest, signed in zip(meshes, got_rays, got_closest, got_signed):
            for a, b in zip(m.raycast(origins, directions), rays):
                np.testing.assert_array_equal(a, b)
            for a, b in zip(m.closest_points(points), closest):
                np.testing.assert_array_equal(a, b)
            for a, b in zip(m.signed_distances(points[:500]), signed):
                np.testing.assert_array_equal(a, b)
    per_blob = Blobs(client, blobs).map("closest_points", [points[i::6] for i in range(6)], per_blob=True)
    for i, (m, answer) in enumerate(zip(meshes, per_blob)):
        np.testing.assert_array_equal(m.closest_points(points[i::6])[1], answer[1])
    with pytest.raises(ValueError, match="group must be"):
        Blobs(client, blobs, group=0)
    with pytest.raises(FileNotFoundError, match="blobs\\[0\\]"):
        Blobs(client, [tmp_path / "missing.meshq"])


def test_a_killed_worker_loses_and_repeats_nothing(client):
    meshes = [meshq.Mesh(v, f) for v, f in placed_copies(16, seed=4)]
    placed = Blobs(client, [m.to_blob() for m in meshes], group=2)
    origins, directions = random_rays(np.array([[-1.5, -1.5, -1.5], [1.5, 1.5, 1.5]]), 200_000, seed=5)
    want = [m.raycast(origins, directions) for m in meshes]
    futures = placed.submit("raycast", origins, directions)
    distributed.wait(futures, return_when="FIRST_COMPLETED")
    pending = sum(not f.done() for f in futures)
    pids = client.run(os.getpid)
    victim = sorted(pids)[0]
    os.kill(pids[victim], signal.SIGKILL)
    # The kill must land while work is left, or the test proves nothing.
    assert pending >= 4, "the job finished before the worker was killed"
    got = placed.gather(futures)
    assert len(got) == len(meshes)
    for a, b in zip(want, got):
        for x, y in zip(a, b):
            np.testing.assert_array_equal(x, y)
    # The cluster is whole again (the nanny restarted the worker).
    deadline = time.time() + 60
    while len(client.scheduler_info()["workers"]) < 2 and time.time() < deadline:
        time.sleep(0.2)
    assert len(client.scheduler_info()["workers"]) == 2


def test_answers_written_to_shared_storage_equal_one_process(client, tmp_path):
    meshes = [meshq.Mesh(v, f) for v, f in placed_copies(5, seed=6)]
    placed = Blobs(client, [m.to_blob() for m in meshes], group=2)
    origins, directions = random_rays(np.array([[-1.5, -1.5, -1.5], [1.5, 1.5, 1.5]]), 3000, seed=7)
    points = origins * 0.5
    got_rays = placed.raycast(origins, directions, out=tmp_path / "rays")
    got_winding = placed.map("winding_numbers", points, out=tmp_path / "winding")
    got_closest = placed.map("closest_points", [points[i::5] for i in range(5)], per_blob=True, out=tmp_path / "closest")
    for i, m in enumerate(meshes):
        for a, b in zip(m.raycast(origins, directions), got_rays[i]):
            assert isinstance(b, np.memmap)
            np.testing.assert_array_equal(a, b)
        np.testing.assert_array_equal(m.winding_numbers(points), got_winding[i])
        for a, b in zip(m.closest_points(points[i::5]), got_closest[i]):
            np.testing.assert_array_equal(a, b)
    assert not list((tmp_path / "rays").glob(".part-*"))
    with pytest.raises(TypeError, match="out= needs a method that returns arrays"):
        placed.map("distance_to", meshes[0], out=tmp_path / "pairs")


def test_the_client_may_be_an_address_or_the_current_one(client, tmp_path):
    from meshq.dask import _client

    assert _client(client) is client
    assert _client(None) is client  # the client this process already has
    address = client.scheduler.address
    other = _client(address)
    try:
        assert other.scheduler.address == address
        blobs = [meshq.Mesh(v, f).to_blob() for v, f in placed_copies(2, seed=8)]
        points = np.zeros((10, 3))
        placed = Blobs(address, blobs)
        try:
            assert len(placed.closest_points(points)) == 2
        finally:
            placed.client.close()
    finally:
        other.close()


def test_groups_are_even_in_bytes_and_dealt_to_every_thread(client):
    from meshq.dask import _even_bounds

    # Consecutive runs, none empty, each within one item of its share of the total.
    rng = np.random.default_rng(8)
    for count in (1, 3, 8, 13):
        sizes = [int(s) for s in rng.integers(1, 100, size=40)]
        bounds = _even_bounds(sizes, count)
        assert bounds[0] == 0 and bounds[-1] == len(sizes) and len(bounds) == count + 1
        runs = [sum(sizes[a:b]) for a, b in zip(bounds, bounds[1:])]
        assert all(b > a for a, b in zip(bounds, bounds[1:]))
        assert max(runs) - sum(sizes) / count <= max(sizes)
    assert _even_bounds([5, 5], 4) == [0, 1, 2] and _even_bounds([], 4) == [0]
    # Small and large meshes mixed: as many groups on each worker, about as many bytes each.
    meshes = [meshq.Mesh(v, f) for v, f in placed_copies(12, seed=9)]
    blobs = [m.to_blob() for m in meshes] + [meshes[0].to_blob()] * 30
    placed = Blobs(client, blobs)
    assert len(placed._groups) % 2 == 0 and len(placed._groups) >= 8
    distributed.wait(placed._groups)
    holders = client.who_has(placed._groups)
    per_worker = {}
    for future in placed._groups:
        (worker,) = holders[future.key]
        per_worker[worker] = per_worker.get(worker, 0) + 1
    assert sorted(per_worker.values()) == [len(placed._groups) // 2] * 2
    # A map's answers leave the workers as they arrive: only the decoded groups stay.
    origins, directions = random_rays(np.array([[-1.5, -1.5, -1.5], [1.5, 1.5, 1.5]]), 1000, seed=10)

    def held():
        return {key for keys in client.has_what().values() for key in keys}

    before = held()
    assert {future.key for future in placed._groups} <= before
    # (The futures stay referenced here: only the release as each group arrives frees them.)
    futures = placed.submit("raycast", origins, directions)
    assert len(placed._collect(futures, release=True)) == len(blobs)
    deadline = time.time() + 30
    while not held() <= before and time.time() < deadline:
        time.sleep(0.1)
    assert held() <= before, f"answers left on the workers: {held() - before}"
