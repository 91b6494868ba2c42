"""Shared fixtures: the bundled meshes (read by a small OBJ reader, so the tests need no loader)
and f64 brute-force oracles."""

from pathlib import Path

import numpy as np
import pytest

ASSETS = Path(__file__).resolve().parents[2] / "assets"


def read_obj(name: str) -> tuple[np.ndarray, np.ndarray]:
    """Vertices `(n, 3)` float64 and triangles `(m, 3)` int64 of a bundled OBJ (polygons
    fanned), as written: no vertex is merged or dropped."""
    vertices, faces = [], []
    for line in (ASSETS / name).read_text().splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            vertices.append([float(x) for x in parts[1:4]])
        elif parts[0] == "f":
            corners = [int(p.split("/")[0]) for p in parts[1:]]
            corners = [c - 1 if c > 0 else len(vertices) + c for c in corners]
            for k in range(1, len(corners) - 1):
                faces.append([corners[0], corners[k], corners[k + 1]])
    return np.array(vertices, dtype=np.float64), np.array(faces, dtype=np.int64)


@pytest.fixture(scope="session")
def fandisk():
    return read_obj("fandisk.obj")


@pytest.fixture(scope="session")
def spot():
    return read_obj("spot.obj")


@pytest.fixture(scope="session")
def bunny():
    return read_obj("stanford-bunny.obj")


def diagonal(vertices: np.ndarray) -> float:
    return float(np.linalg.norm(vertices.max(axis=0) - vertices.min(axis=0)))


def random_rays(vertices: np.ndarray, count: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """Rays from points around the mesh's box toward points inside it."""
    rng = np.random.default_rng(seed)
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    centre, size = (lo + hi) / 2, hi - lo
    origins = centre + (rng.random((count, 3)) - 0.5) * size * 3
    targets = centre + (rng.random((count, 3)) - 0.5) * size * 0.8
    return origins, targets - origins


def brute_raycast(vertices, faces, origins, directions):
    """First hit per ray in f64 over every triangle (Möller–Trumbore, both faces): `t`
    (inf for a miss), triangle (-1), and the smallest barycentric margin of the hit (how close
    it is to an edge)."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    e1, e2 = b - a, c - a
    ts, tris, margins = [], [], []
    for o, d in zip(origins, directions):
        p = np.cross(d, e2)
        det = np.einsum("ij,ij->i", e1, p)
        with np.errstate(divide="ignore", invalid="ignore"):
            inv = 1.0 / det
            s = o - a
            u = np.einsum("ij,ij->i", s, p) * inv
            q = np.cross(s, e1)
            v = (q @ d) * inv
            t = np.einsum("ij,ij->i", e2, q) * inv
        ok = (np.abs(det) > 0) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t >= 0)
        if not ok.any():
            ts.append(np.inf), tris.append(-1), margins.append(np.inf)
            continue
        t_ok = np.where(ok, t, np.inf)
        i = int(np.argmin(t_ok))
        ts.append(t_ok[i]), tris.append(i)
        margins.append(min(u[i], v[i], 1 - u[i] - v[i]))
    return np.array(ts), np.array(tris), np.array(margins)


def brute_closest(vertices, faces, points):
    """Closest distance per point over every triangle, in f64 (Ericson's regions)."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    out = np.empty(len(points))
    for i, p in enumerate(points):
        out[i] = np.sqrt(np.min(_point_triangle_sq(p, a, b, c)))
    return out


def _point_triangle_sq(p, a, b, c):
    ab, ac = b - a, c - a
    normal = np.cross(ab, ac)
    nn = np.einsum("ij,ij->i", normal, normal)
    ap = p - a
    with np.errstate(divide="ignore", invalid="ignore"):
        # Inside the prism: the plane distance.
        d_plane = np.einsum("ij,ij->i", ap, normal) ** 2 / nn
        inside = np.ones(len(a), dtype=bool)
        for x, y in ((a, b), (b, c), (c, a)):
            inside &= np.einsum("ij,ij->i", np.cross(y - x, p - x), normal) >= 0
    best = np.where(inside & (nn > 0), d_plane, np.inf)
    for x, y in ((a, b), (b, c), (c, a)):
        e = y - x
        ee = np.einsum("ij,ij->i", e, e)
        with np.errstate(divide="ignore", invalid="ignore"):
            s = np.clip(np.einsum("ij,ij->i", p - x, e) / ee, 0, 1)
        s = np.where(ee > 0, s, 0)
        q = x + e * s[:, None]
        best = np.minimum(best, np.einsum("ij,ij->i", p - q, p - q))
    return best


def exact_winding(vertices, faces, points):
    """The winding number by the exact sum of solid angles (Van Oosterom–Strackee), f64."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    out = np.empty(len(points))
    for i, p in enumerate(points):
        x, y, z = a - p, b - p, c - p
        lx, ly, lz = (np.linalg.norm(v, axis=1) for v in (x, y, z))
        det = np.einsum("ij,ij->i", x, np.cross(y, z))
        div = (
            lx * ly * lz
            + np.einsum("ij,ij->i", x, y) * lz
            + np.einsum("ij,ij->i", y, z) * lx
            + np.einsum("ij,ij->i", z, x) * ly
        )
        out[i] = np.sum(2 * np.arctan2(det, div)) / (4 * np.pi)
    return out
