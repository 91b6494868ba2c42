"""Typed stubs of the extension module (see the docstrings at run time for the full text)."""

from typing import Any, Literal, TypedDict

import numpy as np
from numpy.typing import ArrayLike, NDArray

Structure = Literal["bvh", "kdtree", "octree", "grid"]
Quality = Literal["fast", "balanced", "high"]
Side = Literal["both", "front", "back"]
Test = Literal["watertight", "moller-trumbore", "two-step"]

class MeshDistance(TypedDict):
    distance: float
    point_a: list[float]
    point_b: list[float]
    triangle_a: int
    triangle_b: int

class SweepHit(TypedDict):
    t: float
    point: list[float]
    normal: list[float]
    triangle: int

class Mesh:
    def __init__(
        self,
        vertices: ArrayLike,
        faces: ArrayLike,
        *,
        structure: Structure = "bvh",
        quality: Quality = "balanced",
        max_leaf_size: int | None = None,
        bins: int | None = None,
        max_depth: int | None = None,
        spatial_splits: bool | float | None = None,
        sweep_sah: bool | int | None = None,
        nodes: Literal["eight-wide", "four-wide", "compact"] | None = None,
    ) -> None: ...
    @staticmethod
    def from_blob(blob: bytes | bytearray | memoryview) -> Mesh: ...
    def to_blob(
        self, layout: Literal["indexed", "packed", "omitted"] | None = None, *, winding: bool = False
    ) -> bytes: ...
    def __reduce__(self) -> tuple[Any, tuple[bytes]]: ...
    def __len__(self) -> int: ...
    @property
    def structure(self) -> Structure: ...
    @property
    def triangle_count(self) -> int: ...
    @property
    def vertex_count(self) -> int: ...
    @property
    def vertices(self) -> NDArray[np.float32]: ...
    @property
    def faces(self) -> NDArray[np.uint32]: ...
    @property
    def bounds(self) -> NDArray[np.float32]: ...
    def raycast(
        self,
        origins: ArrayLike,
        directions: ArrayLike,
        *,
        near: float = 0.0,
        far: float = ...,
        side: Side = "both",
        test: Test = "watertight",
    ) -> tuple[NDArray[np.float32], NDArray[np.int64], NDArray[np.float32], NDArray[np.float32]]: ...
    def raycast_any(
        self,
        origins: ArrayLike,
        directions: ArrayLike,
        *,
        near: float = 0.0,
        far: float = ...,
        side: Side = "both",
        test: Test = "watertight",
    ) -> NDArray[np.bool_]: ...
    def raycast_all(
        self,
        origins: ArrayLike,
        directions: ArrayLike,
        *,
        near: float = 0.0,
        far: float = ...,
        side: Side = "both",
        test: Test = "watertight",
        max_hits: int | None = None,
    ) -> tuple[
        NDArray[np.int64], NDArray[np.float32], NDArray[np.int64], NDArray[np.float32], NDArray[np.float32]
    ]: ...
    def closest_points(
        self, points: ArrayLike, *, max_distance: float = ...
    ) -> tuple[
        NDArray[np.float32], NDArray[np.float32], NDArray[np.int64], NDArray[np.float32], NDArray[np.float32]
    ]: ...
    def winding_numbers(self, points: ArrayLike, *, accuracy: float = 2.0) -> NDArray[np.float32]: ...
    def contains(self, points: ArrayLike, *, accuracy: float = 2.0) -> NDArray[np.bool_]: ...
    def signed_distances(
        self,
        points: ArrayLike,
        *,
        max_distance: float = ...,
        sign: Literal["winding", "pseudo-normal"] = "winding",
        accuracy: float = 2.0,
    ) -> tuple[NDArray[np.float32], NDArray[np.float32], NDArray[np.int64]]: ...
    def intersects(
        self, other: Mesh, *, transform: ArrayLike | None = None, max_tests: int | None = None
    ) -> bool: ...
    def intersecting_pairs(
        self,
        other: Mesh,
        *,
        transform: ArrayLike | None = None,
        max_pairs: int | None = None,
        max_tests: int | None = None,
    ) -> NDArray[np.int64]: ...
    def intersection_segments(
        self,
        other: Mesh,
        *,
        transform: ArrayLike | None = None,
        max_segments: int | None = None,
        max_tests: int | None = None,
    ) -> tuple[NDArray[np.float32], NDArray[np.int64]]: ...
    def distance_to(
        self,
        other: Mesh,
        *,
        transform: ArrayLike | None = None,
        max_distance: float = ...,
        stop_at: float = 0.0,
        max_tests: int | None = None,
    ) -> MeshDistance | None: ...
    def self_intersections(
        self, *, max_pairs: int | None = None, max_tests: int | None = None
    ) -> NDArray[np.int64]: ...
    def overlap_box(self, lower: ArrayLike, upper: ArrayLike) -> NDArray[np.int64]: ...
    def overlap_sphere(self, center: ArrayLike, radius: float) -> NDArray[np.int64]: ...
    def overlap_oriented_box(
        self, center: ArrayLike, axes: ArrayLike, half_extents: ArrayLike
    ) -> NDArray[np.int64]: ...
    def sweep_sphere(self, center: ArrayLike, radius: float, motion: ArrayLike) -> SweepHit | None: ...
    def sweep_capsule(
        self, a: ArrayLike, b: ArrayLike, radius: float, motion: ArrayLike
    ) -> SweepHit | None: ...
    def sweep_box(
        self, center: ArrayLike, axes: ArrayLike, half_extents: ArrayLike, motion: ArrayLike
    ) -> SweepHit | None: ...

def remesh(
    vertices: ArrayLike,
    faces: ArrayLike,
    *,
    target_length: float | None = None,
    target_ratio: float | None = None,
    iterations: int | None = None,
    feature_angle: float | None = None,
    max_distance_tests: int | None = None,
) -> tuple[NDArray[np.float32], NDArray[np.uint32], dict[str, Any]]: ...

def after_fork_in_child() -> None: ...
