"""The trimesh drop-in against trimesh's own answers (its numpy ray intersector, Embree's through
embreex where installed, and trimesh.proximity)."""

import numpy as np
import pytest

trimesh = pytest.importorskip("trimesh")

from conftest import diagonal, random_rays  # noqa: E402
from meshq.trimesh import RayMeshIntersector, closest_point  # noqa: E402


@pytest.fixture(scope="module")
def fan(fandisk):
    v, f = fandisk
    return trimesh.Trimesh(v, f, process=False)


def peers(mesh):
    found = [trimesh.ray.ray_triangle.RayMeshIntersector(mesh)]
    try:
        from trimesh.ray import ray_pyembree

        found.append(ray_pyembree.RayMeshIntersector(mesh))
    except Exception:  # embreex not installed
        pass
    return found


def test_intersects_first_and_any_equal_trimesh(fan):
    ours = RayMeshIntersector(fan)
    origins, directions = random_rays(fan.vertices, 1000, seed=21)
    first = ours.intersects_first(origins, directions)
    np.testing.assert_array_equal(ours.intersects_any(origins, directions), first >= 0)
    for peer in peers(fan):
        theirs = peer.intersects_first(origins, directions)
        # Rays through a shared edge may name either triangle; count real disagreements by
        # the hit point.
        agree = first == theirs
        assert agree.mean() > 0.995, type(peer)
        np.testing.assert_array_equal(ours.intersects_any(origins, directions), peer.intersects_any(origins, directions))


def test_intersects_location_equals_trimesh(fan):
    ours = RayMeshIntersector(fan)
    origins, directions = random_rays(fan.vertices, 500, seed=22)
    loc, ray, tri = ours.intersects_location(origins, directions)
    assert loc.dtype == np.float64 and ray.dtype == np.int64 and tri.dtype == np.int64
    tol = 1e-5 * diagonal(fan.vertices)
    for peer in peers(fan):
        p_loc, p_ray, p_tri = peer.intersects_location(origins, directions)
        # The same hit points per ray, as sets (trimesh lists them by depth, and its
        # numpy intersector may report a hit on a shared edge twice).
        for i in range(len(origins)):
            mine, theirs = loc[ray == i], p_loc[p_ray == i]
            for point in theirs:
                assert np.min(np.linalg.norm(mine - point, axis=1), initial=np.inf) <= tol
            for point in mine:
                assert np.min(np.linalg.norm(theirs - point, axis=1), initial=np.inf) <= tol
    index_tri, index_ray = ours.intersects_id(origins, directions, multiple_hits=False)
    first = ours.intersects_first(origins, directions)
    np.testing.assert_array_equal(index_tri, first[first >= 0])
    np.testing.assert_array_equal(index_ray, np.flatnonzero(first >= 0))


def test_contains_points_equals_trimesh_on_a_watertight_mesh(fan):
    assert fan.is_watertight
    rng = np.random.default_rng(23)
    lo, hi = fan.bounds
    points = lo + rng.random((2000, 3)) * (hi - lo)
    ours = RayMeshIntersector(fan).contains_points(points)
    theirs = fan.contains(points)
    assert (ours == theirs).mean() > 0.998


def test_closest_point_equals_trimesh_proximity(fan):
    rng = np.random.default_rng(24)
    lo, hi = fan.bounds
    points = lo + (rng.random((1000, 3)) * 1.4 - 0.2) * (hi - lo)
    closest, distance, triangle = closest_point(fan, points)
    p_closest, p_distance, p_triangle = trimesh.proximity.closest_point(fan, points)
    tol = 1e-5 * diagonal(fan.vertices)
    assert closest.shape == p_closest.shape and distance.dtype == np.float64
    assert np.max(np.abs(distance - p_distance)) <= tol
    assert np.max(np.linalg.norm(closest - p_closest, axis=1)) <= tol * 10 or (
        np.mean(triangle == p_triangle) > 0.99
    )


def test_the_cache_follows_the_mesh(fan):
    mesh = fan.copy()
    ours = RayMeshIntersector(mesh)
    origins, directions = random_rays(mesh.vertices, 200, seed=25)
    before = ours.intersects_first(origins, directions)
    mesh.vertices = mesh.vertices + [diagonal(mesh.vertices) * 10, 0, 0]
    after = ours.intersects_first(origins, directions)
    assert (before >= 0).any() and not (after >= 0).any()
