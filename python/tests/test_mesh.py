"""Building, loading and saving: arguments checked by name, blobs and pickles that answer
exactly as the mesh they came from."""

import pickle

import numpy as np
import pytest

import meshq
from conftest import random_rays

TRIANGLE = (np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float), np.array([[0, 1, 2]]))


def test_properties_describe_the_mesh(fandisk):
    v, f = fandisk
    m = meshq.Mesh(v, f)
    assert (m.triangle_count, m.vertex_count, len(m)) == (len(f), len(v), len(f))
    assert m.structure == "bvh"
    np.testing.assert_array_equal(m.vertices, v.astype(np.float32))
    np.testing.assert_array_equal(m.faces, f.astype(np.uint32))
    np.testing.assert_array_equal(m.bounds, [v.min(0).astype(np.float32), v.max(0).astype(np.float32)])
    assert "fandisk" not in repr(m) and f"{len(f)} triangles" in repr(m)


@pytest.mark.parametrize(
    "args, kwargs, error, words",
    [
        ((np.zeros((3, 2)), [[0, 1, 2]]), {}, ValueError, "vertices must have shape (n, 3)"),
        ((TRIANGLE[0], [[0, 1]]), {}, ValueError, "faces must have shape (n, 3)"),
        ((TRIANGLE[0], [[0, 1, 3]]), {}, ValueError, "3"),
        ((TRIANGLE[0], [[0, 1, -2]]), {}, ValueError, "faces must lie in 0..2^32"),
        ((TRIANGLE[0], [[0.5, 1, 2]]), {}, TypeError, "faces must hold integers"),
        ((np.array([[0, 0, np.nan], [1, 0, 0], [0, 1, 0]]), [[0, 1, 2]]), {}, ValueError, "finite"),
        (TRIANGLE, {"structure": "tree"}, ValueError, "structure must be"),
        (TRIANGLE, {"quality": "best"}, ValueError, "quality must be"),
        (TRIANGLE, {"max_leaf_size": 0}, ValueError, "max_leaf_size must be in"),
        (TRIANGLE, {"bins": 1}, ValueError, "bins must be in"),
        (TRIANGLE, {"spatial_splits": 9.0}, ValueError, "spatial_splits must be"),
        (TRIANGLE, {"structure": "grid", "spatial_splits": True}, ValueError, "applies to the BVH"),
        (TRIANGLE, {"nodes": "two-wide"}, ValueError, "nodes must be"),
        (TRIANGLE, {"sweep_sah": 0}, ValueError, "sweep_sah must be True, False, None or a whole number"),
        (TRIANGLE, {"sweep_sah": 2.5}, TypeError, "sweep_sah must be a whole number, got float"),
        (TRIANGLE, {"sweep_sah": True, "spatial_splits": True}, ValueError, "do not go together"),
        (TRIANGLE, {"structure": "kdtree", "sweep_sah": 8}, ValueError, "sweep_sah applies to the BVH"),
        (TRIANGLE, {"bins": -3}, ValueError, "bins must be in 0..=4294967295, got -3"),
        (TRIANGLE, {"max_depth": "deep"}, TypeError, "max_depth must be a whole number, got str"),
        (TRIANGLE, {"max_leaf_size": True}, TypeError, "max_leaf_size must be a whole number, got bool"),
        (TRIANGLE, {"structure": "octree", "nodes": "compact"}, ValueError, "nodes applies to the BVH"),
    ],
)
def test_bad_input_is_refused_by_name(args, kwargs, error, words):
    with pytest.raises(error, match=None) as caught:
        meshq.Mesh(*args, **kwargs)
    assert words in str(caught.value)


def test_query_arguments_are_checked_by_name():
    m = meshq.Mesh(*TRIANGLE)
    with pytest.raises(ValueError, match="directions\\[1\\] is zero"):
        m.raycast([[0, 0, 1], [0, 0, 1]], [[0, 0, -1], [0, 0, 0]])
    with pytest.raises(ValueError, match="origins has 2 rows but directions has 1"):
        m.raycast([[0, 0, 1], [0, 0, 1]], [[0, 0, -1]])
    with pytest.raises(ValueError, match="near and far"):
        m.raycast([[0, 0, 1]], [[0, 0, -1]], near=2.0, far=1.0)
    with pytest.raises(ValueError, match="side must be"):
        m.raycast([[0, 0, 1]], [[0, 0, -1]], side="up")
    with pytest.raises(ValueError, match="test must be 'watertight', 'moller-trumbore' or 'two-step'"):
        m.raycast([[0, 0, 1]], [[0, 0, -1]], test="fast")
    with pytest.raises(ValueError, match="max_distance must be"):
        m.closest_points([[0, 0, 1]], max_distance=-1.0)
    with pytest.raises(ValueError, match="accuracy must be"):
        m.winding_numbers([[0, 0, 1]], accuracy=0.5)
    with pytest.raises(ValueError, match="sign must be"):
        m.signed_distances([[0, 0, 1]], sign="normal")
    with pytest.raises(ValueError, match="points\\[0, 2\\] is not finite"):
        m.closest_points([[0, 0, np.inf]])
    with pytest.raises(ValueError, match="transform"):
        m.intersects(m, transform=np.ones((4, 4)))
    with pytest.raises(ValueError, match="layout must be"):
        m.to_blob("zipped")
    with pytest.raises(ValueError, match="max_hits must be in 0..="):
        m.raycast_all([[0, 0, 1]], [[0, 0, -1]], max_hits=-1)
    with pytest.raises(TypeError, match="max_tests must be a whole number, got float"):
        m.intersects(m, max_tests=1.5)
    with pytest.raises(ValueError, match="max_pairs must be in 0..="):
        m.self_intersections(max_pairs=-1)
    with pytest.raises(ValueError, match="iterations must be in 0..="):
        meshq.remesh(*TRIANGLE, iterations=-2)
    with pytest.raises(TypeError, match="blob must be bytes, bytearray or memoryview, got int"):
        meshq.Mesh.from_blob(123)
    # Whole numbers from numpy count as whole numbers.
    assert m.raycast_all([[0.2, 0.2, 1]], [[0, 0, -1]], max_hits=np.int64(1))[0].tolist() == [0]


@pytest.mark.parametrize("structure", ["bvh", "kdtree", "octree", "grid"])
def test_blob_and_pickle_answer_bit_for_bit(fandisk, structure):
    v, f = fandisk
    built = meshq.Mesh(v, f, structure=structure)
    blob = built.to_blob()
    loaded = meshq.Mesh.from_blob(blob)
    assert loaded.structure == structure
    for other_kind in (bytearray(blob), memoryview(blob)):
        assert meshq.Mesh.from_blob(other_kind).to_blob() == blob
    assert loaded.to_blob() == blob
    unpickled = pickle.loads(pickle.dumps(built))
    origins, directions = random_rays(v, 2000, seed=5)
    want = built.raycast(origins, directions)
    for other in (loaded, unpickled):
        for a, b in zip(want, other.raycast(origins, directions)):
            np.testing.assert_array_equal(a, b)


def test_every_structure_gives_the_same_answers(fandisk):
    v, f = fandisk
    origins, directions = random_rays(v, 3000, seed=9)
    points = origins * 0.4
    answers = []
    builds = [{"structure": s} for s in ["bvh", "kdtree", "octree", "grid"]] + [
        {"nodes": n} for n in ["eight-wide", "four-wide", "compact"]
    ] + [{"spatial_splits": True}, {"quality": "high"}, {"quality": "fast", "max_leaf_size": 2}] + [
        {"sweep_sah": True},
        {"sweep_sah": 1, "quality": "high"},
    ]
    for options in builds:
        m = meshq.Mesh(v, f, **options)
        answers.append((m.raycast(origins, directions), m.closest_points(points)))
    for rays, closest in answers[1:]:
        for a, b in zip(answers[0][0], rays):
            np.testing.assert_array_equal(a, b)
        for a, b in zip(answers[0][1], closest):
            np.testing.assert_array_equal(a, b)


def test_damaged_blobs_are_refused():
    blob = bytearray(meshq.Mesh(*TRIANGLE).to_blob())
    blob[len(blob) // 2] ^= 0xFF
    with pytest.raises(ValueError):
        meshq.Mesh.from_blob(bytes(blob))
    with pytest.raises(ValueError):
        meshq.Mesh.from_blob(b"not a blob")


def test_winding_blob_round_trip(fandisk):
    v, f = fandisk
    m = meshq.Mesh(v, f)
    plain = m.to_blob()
    blob = m.to_blob(winding=True)
    assert len(blob) > len(plain)
    # Once prepared, the expansions are stored whether asked for or not.
    assert m.to_blob() == blob
    points = random_rays(v, 500, seed=3)[0] * 0.3
    np.testing.assert_array_equal(
        meshq.Mesh.from_blob(blob).winding_numbers(points), m.winding_numbers(points)
    )
    with pytest.raises(ValueError, match="applies to a BVH"):
        meshq.Mesh(v, f, structure="grid").to_blob(winding=True)


def test_threads_share_one_mesh(fandisk):
    from concurrent.futures import ThreadPoolExecutor

    v, f = fandisk
    m = meshq.Mesh(v, f, structure="octree")
    points = random_rays(v, 300, seed=4)[0] * 0.3
    want = m.signed_distances(points)[0]
    fresh = meshq.Mesh(v, f, structure="octree")
    with ThreadPoolExecutor(4) as pool:
        got = list(pool.map(lambda _: fresh.signed_distances(points)[0], range(8)))
    for g in got:
        np.testing.assert_array_equal(g, want)


def _child_answers(mesh, origins, directions, pipe):
    pipe.send([a.tolist() for a in mesh.raycast(origins, directions)])


def test_a_forked_child_answers_as_its_parent(fandisk):
    """multiprocessing forks on Linux: the child has none of the parent's batch threads and
    must still answer (not wait forever for them), and answer the same."""
    import multiprocessing

    v, f = fandisk
    m = meshq.Mesh(v, f)
    origins, directions = random_rays(v, 20_000, seed=8)
    want = m.raycast(origins, directions)  # starts the parent's threads
    context = multiprocessing.get_context("fork")
    for _ in range(2):
        receive, send = context.Pipe(duplex=False)
        child = context.Process(target=_child_answers, args=(m, origins, directions, send))
        child.start()
        assert receive.poll(60), "the forked child did not answer within a minute"
        got = receive.recv()
        child.join(10)
        for a, b in zip(want, got):
            np.testing.assert_array_equal(a, np.array(b, dtype=a.dtype))
