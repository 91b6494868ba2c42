"""A drop-in for trimesh's ray intersector and closest-point query.

Switching is one line::

    from meshq.trimesh import RayMeshIntersector      # was trimesh.ray.ray_pyembree's
    intersector = RayMeshIntersector(mesh)
    index_tri = intersector.intersects_first(origins, directions)

    from meshq.trimesh import closest_point            # was trimesh.proximity.closest_point
    closest, distance, triangle_id = closest_point(mesh, points)

The methods take and return what trimesh's do (``float64`` positions, ``int64`` indices, ``-1``
for a miss). Differences, by design: hits are found in ``float32`` by meshq's watertight test,
exactly once per triangle and ray, with no ray offsetting, so a ray through a shared edge or
corner reports the triangle with the lower index once, where trimesh's loop may report it on
both sides or skip it; ``intersects_id`` lists hits by ray, nearest first, where trimesh lists
them by depth. The meshq structure is built on first use and kept in the mesh's cache, which
trimesh clears when the vertices or faces change.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from . import Mesh

_CACHE_KEY = "meshq_index"


def index_of(mesh: Any) -> Mesh:
    """The :class:`meshq.Mesh` of a ``trimesh.Trimesh``, built once and kept in its cache."""
    cache = getattr(mesh, "_cache", None)
    if cache is not None:
        found = cache[_CACHE_KEY]  # checks the data first; None when absent or stale
        if found is not None:
            return found
    built = Mesh(np.asarray(mesh.vertices), np.asarray(mesh.faces))
    if cache is not None:
        cache[_CACHE_KEY] = built
    return built


def _rays(ray_origins: Any, ray_directions: Any) -> tuple[np.ndarray, np.ndarray]:
    origins = np.asarray(ray_origins, dtype=np.float64)
    directions = np.asarray(ray_directions, dtype=np.float64)
    if origins.shape != directions.shape:
        raise ValueError("Ray origin and direction don't match!")
    return origins.reshape(-1, 3), directions.reshape(-1, 3)


class RayMeshIntersector:
    """trimesh's ``RayMeshIntersector`` interface over a meshq BVH of ``geometry`` (a
    ``trimesh.Trimesh``)."""

    def __init__(self, geometry: Any) -> None:
        self.mesh = geometry

    @property
    def index(self) -> Mesh:
        """The meshq structure the queries run on."""
        return index_of(self.mesh)

    def _locations(self, index_tri: np.ndarray, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        # On the triangle from its barycentric weights, in float64: on the surface whatever the
        # ray's length.
        corners = np.asarray(self.mesh.vertices, dtype=np.float64)[
            np.asarray(self.mesh.faces)[index_tri]
        ]
        u = u.astype(np.float64)[:, None]
        v = v.astype(np.float64)[:, None]
        return corners[:, 0] * (1.0 - u - v) + corners[:, 1] * u + corners[:, 2] * v

    def intersects_first(self, ray_origins: Any, ray_directions: Any, **kwargs: Any) -> np.ndarray:
        """The index of the first triangle each ray hits, ``-1`` for a miss (``(n,)`` int64)."""
        origins, directions = _rays(ray_origins, ray_directions)
        _, index_tri, _, _ = self.index.raycast(origins, directions)
        return index_tri

    def intersects_any(self, ray_origins: Any, ray_directions: Any, **kwargs: Any) -> np.ndarray:
        """Whether each ray hits the mesh (``(n,)`` bool)."""
        origins, directions = _rays(ray_origins, ray_directions)
        return self.index.raycast_any(origins, directions)

    def intersects_id(
        self,
        ray_origins: Any,
        ray_directions: Any,
        multiple_hits: bool = True,
        max_hits: int = 100,
        return_locations: bool = False,
        **kwargs: Any,
    ) -> tuple[np.ndarray, ...]:
        """``(index_tri, index_ray[, locations])``: every hit (at most ``max_hits`` per ray), or
        the first hit per ray with ``multiple_hits=False``; rays in order, each ray's hits
        nearest first."""
        origins, directions = _rays(ray_origins, ray_directions)
        if multiple_hits:
            index_ray, _, index_tri, u, v = self.index.raycast_all(
                origins, directions, max_hits=max_hits
            )
        else:
            _, index_tri, u, v = self.index.raycast(origins, directions)
            hit = index_tri >= 0
            index_ray = np.flatnonzero(hit).astype(np.int64)
            index_tri, u, v = index_tri[hit], u[hit], v[hit]
        if return_locations:
            return index_tri, index_ray, self._locations(index_tri, u, v)
        return index_tri, index_ray

    def intersects_location(
        self, ray_origins: Any, ray_directions: Any, multiple_hits: bool = True, **kwargs: Any
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(locations, index_ray, index_tri)`` of every hit (or the first, with
        ``multiple_hits=False``)."""
        index_tri, index_ray, locations = self.intersects_id(
            ray_origins, ray_directions, multiple_hits=multiple_hits, return_locations=True
        )
        return locations, index_ray, index_tri

    def contains_points(self, points: Any) -> np.ndarray:
        """Whether each point is inside the mesh, by the generalized winding number (also for
        meshes that are not watertight)."""
        return self.index.contains(np.asarray(points, dtype=np.float64).reshape(-1, 3))


def closest_point(mesh: Any, points: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``trimesh.proximity.closest_point``: ``(closest (m, 3) float64, distance (m,) float64,
    triangle_id (m,) int64)``; on equal distance the lower triangle index wins."""
    query = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    closest, distance, triangle, _, _ = index_of(mesh).closest_points(query)
    return closest.astype(np.float64), distance.astype(np.float64), triangle
