"""Every query against an f64 brute-force oracle; tolerances relative to the mesh's size."""

import numpy as np
import pytest

import meshq
from conftest import brute_closest, brute_raycast, diagonal, exact_winding, random_rays


@pytest.mark.parametrize("test", ["watertight", "moller-trumbore", "two-step"])
def test_raycast_matches_brute_force(fandisk, test):
    v, f = fandisk
    m = meshq.Mesh(v, f)
    origins, directions = random_rays(v, 400, seed=1)
    t, tri, u, w = m.raycast(origins, directions, test=test)
    t_ref, tri_ref, margin = brute_raycast(v, f, origins, directions)
    scale = diagonal(v) / np.linalg.norm(directions, axis=1)
    hit, hit_ref = tri >= 0, tri_ref >= 0
    # A hit and a miss disagree only for a ray grazing an edge.
    assert np.all((hit == hit_ref) | (margin < 1e-5))
    both = hit & hit_ref
    assert both.sum() > 100
    assert np.all(np.abs(t[both] - t_ref[both]) <= 1e-5 * scale[both])
    # The point at t lies on the reported triangle.
    a, b, c = (v[f[tri[both], k]] for k in range(3))
    on = a * (1 - u[both] - w[both])[:, None] + b * u[both][:, None] + c * w[both][:, None]
    along = origins[both] + t[both][:, None] * directions[both]
    assert np.all(np.linalg.norm(on - along, axis=1) <= 1e-5 * diagonal(v))
    assert np.all(t[~hit] == np.inf) and np.all(tri[~hit] == -1)


def test_raycast_any_and_all_agree_with_first_hits(fandisk):
    v, f = fandisk
    m = meshq.Mesh(v, f)
    origins, directions = random_rays(v, 500, seed=2)
    t, tri, _, _ = m.raycast(origins, directions)
    np.testing.assert_array_equal(m.raycast_any(origins, directions), tri >= 0)
    ray, t_all, tri_all, _, _ = m.raycast_all(origins, directions)
    assert np.all(np.diff(ray) >= 0)
    for i in range(len(origins)):
        mine = t_all[ray == i]
        assert np.all(np.diff(mine) >= 0)
        if tri[i] < 0:
            assert len(mine) == 0
        else:
            assert mine[0] == t[i]
    # A closed mesh is entered and left: rays from outside that hit do so an even number of
    # times, up to grazing rays.
    counts = np.bincount(ray, minlength=len(origins))
    assert np.mean(counts[tri >= 0] % 2 == 0) > 0.97
    first_two = m.raycast_all(origins, directions, max_hits=2)[0]
    assert np.bincount(first_two, minlength=len(origins)).max() <= 2


def test_ray_range_and_sides(fandisk):
    v, f = fandisk
    m = meshq.Mesh(v, f)
    origins, directions = random_rays(v, 300, seed=7)
    t, tri, _, _ = m.raycast(origins, directions)
    hit = tri >= 0
    beyond = m.raycast(origins, directions, far=float(np.min(t[hit])) * 0.5)[1]
    assert np.all(beyond == -1)
    front = m.raycast(origins, directions, side="front")[0]
    back = m.raycast(origins, directions, side="back")[0]
    np.testing.assert_array_equal(np.minimum(front, back), t)


def test_closest_points_match_brute_force(spot):
    v, f = spot
    m = meshq.Mesh(v, f)
    rng = np.random.default_rng(11)
    lo, hi = v.min(0), v.max(0)
    points = lo + (rng.random((300, 3)) * 1.6 - 0.3) * (hi - lo)
    closest, distance, tri, u, w = m.closest_points(points)
    ref = brute_closest(v, f, points)
    tol = 1e-5 * diagonal(v)
    assert np.all(np.abs(distance - ref) <= tol)
    np.testing.assert_allclose(np.linalg.norm(closest - points, axis=1), distance, atol=tol)
    a, b, c = (v[f[tri, k]] for k in range(3))
    on = a * (1 - u - w)[:, None] + b * u[:, None] + c * w[:, None]
    assert np.all(np.linalg.norm(on - closest, axis=1) <= tol)
    limited = m.closest_points(points, max_distance=float(np.median(ref)))
    far = ref > np.median(ref) * (1 + 1e-5)
    assert np.all(limited[2][far] == -1) and np.all(np.isnan(limited[0][far]))
    near = ref < np.median(ref) * (1 - 1e-5)
    np.testing.assert_array_equal(limited[1][near], distance[near])


def test_winding_numbers_match_the_exact_sum(fandisk):
    v, f = fandisk
    m = meshq.Mesh(v, f)
    rng = np.random.default_rng(12)
    lo, hi = v.min(0), v.max(0)
    points = lo + (rng.random((200, 3)) * 1.4 - 0.2) * (hi - lo)
    ref = exact_winding(v, f, points)
    exact = m.winding_numbers(points, accuracy=np.inf)
    assert np.max(np.abs(exact - ref)) < 1e-3
    fast = m.winding_numbers(points)
    # Far from the surface the expansions are close; contains agrees with the exact sum away
    # from the 0.5 threshold.
    assert np.max(np.abs(fast - ref)) < 2e-2
    clear = np.abs(np.abs(ref) - 0.5) > 0.05
    np.testing.assert_array_equal(m.contains(points)[clear], (np.abs(ref) >= 0.5)[clear])


def test_winding_numbers_on_an_open_mesh(fandisk):
    v, f = fandisk
    open_faces = f[: len(f) * 3 // 4]
    m = meshq.Mesh(v, open_faces, structure="kdtree")
    rng = np.random.default_rng(13)
    points = v.min(0) + rng.random((100, 3)) * (v.max(0) - v.min(0))
    ref = exact_winding(v, open_faces, points)
    assert np.max(np.abs(m.winding_numbers(points, accuracy=np.inf) - ref)) < 1e-3


def test_signed_distances(spot):
    v, f = spot
    m = meshq.Mesh(v, f)
    rng = np.random.default_rng(14)
    lo, hi = v.min(0), v.max(0)
    points = lo + rng.random((300, 3)) * (hi - lo)
    d, closest, tri = m.signed_distances(points)
    _, unsigned, tri_c, _, _ = m.closest_points(points)
    np.testing.assert_array_equal(np.abs(d), unsigned)
    np.testing.assert_array_equal(tri, tri_c)
    ref = exact_winding(v, f, points)
    clear = (np.abs(np.abs(ref) - 0.5) > 0.05) & (unsigned > 1e-3 * diagonal(v))
    np.testing.assert_array_equal((d < 0)[clear], (np.abs(ref) >= 0.5)[clear])
    pseudo = m.signed_distances(points, sign="pseudo-normal")[0]
    np.testing.assert_array_equal(np.abs(pseudo), unsigned)
    np.testing.assert_array_equal((pseudo < 0)[clear], (np.abs(ref) >= 0.5)[clear])


def test_pseudo_normals_need_a_closed_mesh(fandisk):
    v, f = fandisk
    m = meshq.Mesh(v, f[:-10])
    with pytest.raises(ValueError):
        m.signed_distances([[0.0, 0.0, 0.0]], sign="pseudo-normal")


def test_mesh_mesh_queries(fandisk):
    v, f = fandisk
    a = meshq.Mesh(v, f)
    size = diagonal(v)
    apart = np.eye(4)
    apart[0, 3] = size * 2
    assert not a.intersects(a, transform=apart)
    assert a.intersecting_pairs(a, transform=apart).shape == (0, 2)
    found = a.distance_to(a, transform=apart)
    # The gap along x between the copy's lowest x and the mesh's highest.
    gap = size * 2 - (v[:, 0].max() - v[:, 0].min())
    assert abs(found["distance"] - gap) <= 1e-5 * size
    assert a.distance_to(a, transform=apart, max_distance=gap * 0.5) is None
    shifted = np.eye(4)
    shifted[:3, 3] = size * 0.05
    assert a.intersects(a, transform=shifted)
    pairs = a.intersecting_pairs(a, transform=shifted)
    assert len(pairs) > 0 and pairs.min() >= 0 and pairs[:, 0].max() < len(f)
    assert a.distance_to(a, transform=shifted)["distance"] == 0.0
    assert len(a.self_intersections()) == 0
    # Each crossing segment lies on both of its triangles (the second one moved).
    segments, on = a.intersection_segments(a, transform=shifted)
    assert segments.shape == (len(on), 2, 3) and len(on) > 0
    assert set(map(tuple, on)) <= set(map(tuple, pairs))
    moved = v + shifted[:3, 3]
    ends = segments.reshape(-1, 3)
    first = np.repeat(on[:, 0], 2)
    second = np.repeat(on[:, 1], 2)
    tol = 1e-5 * size
    for mesh_v, tris in ((v, first), (moved, second)):
        gaps = [np.sqrt(_gap(p, mesh_v[f[t]])) for p, t in zip(ends, tris)]
        assert max(gaps) <= tol


def _gap(p, corners):
    from conftest import _point_triangle_sq

    a, b, c = (corners[None, k] for k in range(3))
    return float(_point_triangle_sq(p, a, b, c)[0])


def test_overlaps_match_brute_force(spot):
    v, f = spot
    m = meshq.Mesh(v, f)
    centre = v.mean(0)
    radius = diagonal(v) * 0.1
    got = m.overlap_sphere(centre, radius)
    ref = brute_closest(v, f[got], [centre])[0]
    assert ref <= radius * (1 + 1e-5)
    # Every triangle within the radius is reported: check those a little inside it.
    a, b, c = (v[f[:, k]] for k in range(3))
    near = np.flatnonzero(np.linalg.norm((a + b + c) / 3 - centre, axis=1) < radius * 0.9)
    assert set(near) <= set(got)
    lower, upper = centre - radius, centre + radius
    boxed = set(m.overlap_box(lower, upper))
    inside = np.flatnonzero(np.all((a >= lower) & (a <= upper), axis=1))
    assert set(inside) <= boxed
    axes = np.eye(3)
    assert set(m.overlap_oriented_box(centre, axes, [radius] * 3)) == boxed


def test_sweeps_touch_where_the_mesh_is(fandisk):
    v, f = fandisk
    m = meshq.Mesh(v, f)
    size = diagonal(v)
    start = v.mean(0) + np.array([0, 0, size * 2])
    motion = np.array([0, 0, -size * 4])
    r = size * 0.01
    hit = m.sweep_sphere(start, r, motion)
    assert hit is not None and 0 < hit["t"] < 1
    centre = start + hit["t"] * motion
    d = m.closest_points([centre])[1][0]
    assert abs(d - r) <= 1e-4 * size
    assert m.sweep_sphere(start, r, [size, 0, 0]) is None
    assert m.sweep_capsule(start, start + [0, size * 0.01, 0], r, motion) is not None
    assert m.sweep_box(start, np.eye(3), [r] * 3, motion)["t"] <= hit["t"] + 1e-4


def test_remesh_reaches_its_target(fandisk):
    v, f = fandisk
    size = diagonal(v)
    edges = np.linalg.norm(v[f[:, 0]] - v[f[:, 1]], axis=1)
    target = float(edges.mean())
    out_v, out_f, report = meshq.remesh(v, f, target_length=target)
    assert out_v.dtype == np.float32 and out_f.dtype == np.uint32
    out_edges = np.linalg.norm(out_v[out_f[:, 0]] - out_v[out_f[:, 1]], axis=1)
    assert abs(out_edges.mean() / target - 1) < 0.15
    assert report["after"]["triangles"] == len(out_f)
    assert report["after"]["min_angle_off_boundary"] > 25
    assert report["distance"] < 0.01
    # The output's vertices lie near the input surface (relative to its size).
    assert meshq.Mesh(v, f).closest_points(out_v)[1].max() < 0.01 * size
    with pytest.raises(ValueError, match="not both"):
        meshq.remesh(v, f, target_length=1.0, target_ratio=1.0)
    with pytest.raises(ValueError, match="target_ratio must be"):
        meshq.remesh(v, f, target_ratio=-1.0)
