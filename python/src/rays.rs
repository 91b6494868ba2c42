//! Ray casts in batches: the first hit, any hit, every hit.

use glam::Vec3;
use meshq::MeshQuery;
use meshq::geom::CullMode;
use meshq::math::{Ray, RayHit};
use meshq::query::{RayOptions, TriangleTest};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use rayon::prelude::*;

use crate::arrays::{column, count, finite_rows, with_floats};
use crate::mesh::{Column, Mesh, Storage};
use crate::pool::detached;

/// The rays `origins[i] + t·directions[i]`, `t` in `[near, far]`, each direction non-zero,
/// made in one pass over the two arrays (read in place where their layout allows).
fn rays(
    origins: &Bound<'_, PyAny>,
    directions: &Bound<'_, PyAny>,
    near: f64,
    far: f64,
) -> PyResult<Vec<Ray>> {
    if near.is_nan() || far.is_nan() || near > far {
        return Err(PyValueError::new_err(format!(
            "near and far must be numbers with near <= far, got {near} and {far}"
        )));
    }
    let (near, far) = (near as f32, far as f32);
    with_floats(origins, "origins", 3, |o| {
        with_floats(directions, "directions", 3, |d| {
            if o.len() != d.len() {
                return Err(PyValueError::new_err(format!(
                    "origins has {} rows but directions has {}",
                    o.len() / 3,
                    d.len() / 3
                )));
            }
            finite_rows(o, "origins")?;
            finite_rows(d, "directions")?;
            let mut rays = Vec::with_capacity(o.len() / 3);
            for (i, (o, d)) in o.chunks_exact(3).zip(d.chunks_exact(3)).enumerate() {
                let dir = Vec3::new(d[0], d[1], d[2]);
                if dir == Vec3::ZERO {
                    return Err(PyValueError::new_err(format!("directions[{i}] is zero")));
                }
                rays.push(Ray::new(Vec3::new(o[0], o[1], o[2]), dir).with_range(near, far));
            }
            Ok(rays)
        })
    })
}

/// The options of `side` (`"both"`, `"front"`, `"back"`: the faces a ray may hit) and `test`
/// (`"watertight"`, `"moller-trumbore"` or `"two-step"`).
fn options(side: &str, test: &str) -> PyResult<RayOptions> {
    let cull = match side {
        "both" => CullMode::None,
        "front" => CullMode::Back,
        "back" => CullMode::Front,
        other => {
            return Err(PyValueError::new_err(format!(
                "side must be 'both', 'front' or 'back', got {other:?}"
            )));
        }
    };
    let test = TriangleTest::from_name(test).ok_or_else(|| {
        PyValueError::new_err(format!(
            "test must be 'watertight', 'moller-trumbore' or 'two-step', got {test:?}"
        ))
    })?;
    Ok(RayOptions { test, cull })
}

fn batch_error(e: impl std::fmt::Display) -> PyErr {
    PyRuntimeError::new_err(e.to_string())
}

/// Every hit of `ray`, nearest first (the buffer grows until all fit).
fn every_hit(storage: &Storage, ray: &Ray, options: &RayOptions) -> Vec<RayHit> {
    let most = storage.scene.mesh().triangle_count().max(1);
    let empty = RayHit {
        t: 0.0,
        tri: 0,
        u: 0.0,
        v: 0.0,
    };
    let mut hits = vec![empty; most.min(16)];
    loop {
        let found = MeshQuery::raycast_all(&storage.scene, ray, options, &mut hits);
        if found.is_complete() || hits.len() >= most {
            hits.truncate(found.written);
            return hits;
        }
        hits.resize(most.min(hits.len() * 4), empty);
    }
}

/// A hit's triangle as an `int64` index, `-1` for a miss.
fn triangle_of(tri: Option<u32>) -> i64 {
    tri.map_or(-1, i64::from)
}

type Hits<'py> = (
    Column<'py, f32>,
    Column<'py, i64>,
    Column<'py, f32>,
    Column<'py, f32>,
);

type AllHits<'py> = (
    Column<'py, i64>,
    Column<'py, f32>,
    Column<'py, i64>,
    Column<'py, f32>,
    Column<'py, f32>,
);

#[pymethods]
impl Mesh {
    /// The first hit of each ray `origins[i] + t·directions[i]` (`(n, 3)` arrays), `t` in
    /// `[near, far]` in units of the direction's length (world units for unit directions).
    /// Returns `(t, triangle, u, v)`: `t` `float32` (`inf` for a miss), `triangle` `int64`
    /// (`-1` for a miss), `u`, `v` the hit's barycentric weights of the triangle's second and
    /// third corners (0 for a miss). `side` picks the faces that count (`"both"`, `"front"`,
    /// `"back"`; counter-clockwise is front), `test` the triangle test (`"watertight"`, no ray
    /// slips between triangles, `"moller-trumbore"` or `"two-step"`). Ties in `t` go to the lower triangle.
    #[pyo3(signature = (origins, directions, *, near = 0.0, far = f64::INFINITY, side = "both", test = "watertight"))]
    #[allow(clippy::too_many_arguments)]
    fn raycast<'py>(
        &self,
        py: Python<'py>,
        origins: &Bound<'py, PyAny>,
        directions: &Bound<'py, PyAny>,
        near: f64,
        far: f64,
        side: &str,
        test: &str,
    ) -> PyResult<Hits<'py>> {
        let options = options(side, test)?;
        let rays = rays(origins, directions, near, far)?;
        let storage = self.read()?;
        let mut out = vec![None; rays.len()];
        detached(py, || {
            meshq::parallel::raycast_batch(&storage.scene, &rays, &options, &mut out)
        })?
        .map_err(batch_error)?;
        let n = out.len();
        let (mut t, mut tri, mut u, mut v) = (
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
        );
        for hit in &out {
            t.push(hit.map_or(f32::INFINITY, |h| h.t));
            tri.push(triangle_of(hit.map(|h| h.tri)));
            u.push(hit.map_or(0.0, |h| h.u));
            v.push(hit.map_or(0.0, |h| h.v));
        }
        Ok((column(py, t), column(py, tri), column(py, u), column(py, v)))
    }

    /// Whether each ray hits anything in `[near, far]` (a `bool` array); arguments as for
    /// `raycast`. Faster than `raycast`: it stops at the first triangle found.
    #[pyo3(signature = (origins, directions, *, near = 0.0, far = f64::INFINITY, side = "both", test = "watertight"))]
    #[allow(clippy::too_many_arguments)]
    fn raycast_any<'py>(
        &self,
        py: Python<'py>,
        origins: &Bound<'py, PyAny>,
        directions: &Bound<'py, PyAny>,
        near: f64,
        far: f64,
        side: &str,
        test: &str,
    ) -> PyResult<Column<'py, bool>> {
        let options = options(side, test)?;
        let rays = rays(origins, directions, near, far)?;
        let storage = self.read()?;
        let mut out = vec![false; rays.len()];
        detached(py, || {
            meshq::parallel::raycast_any_batch(&storage.scene, &rays, &options, &mut out)
        })?
        .map_err(batch_error)?;
        Ok(column(py, out))
    }

    /// Every hit of each ray, rays in input order and each ray's hits nearest first (at most
    /// `max_hits` per ray when given). Returns `(ray, t, triangle, u, v)`, one entry per hit:
    /// `ray` the `int64` index of the ray. Arguments as for `raycast`.
    #[pyo3(signature = (origins, directions, *, near = 0.0, far = f64::INFINITY, side = "both", test = "watertight", max_hits = None))]
    #[allow(clippy::too_many_arguments)]
    fn raycast_all<'py>(
        &self,
        py: Python<'py>,
        origins: &Bound<'py, PyAny>,
        directions: &Bound<'py, PyAny>,
        near: f64,
        far: f64,
        side: &str,
        test: &str,
        max_hits: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<AllHits<'py>> {
        let max_hits = count(max_hits, "max_hits")?;
        let options = options(side, test)?;
        let rays = rays(origins, directions, near, far)?;
        let storage = self.read()?;
        let per_ray: Vec<Vec<RayHit>> = detached(py, || {
            rays.par_iter()
                .map(|ray| {
                    let mut hits = every_hit(&storage, ray, &options);
                    hits.truncate(max_hits.unwrap_or(usize::MAX));
                    hits
                })
                .collect()
        })?;
        let total: usize = per_ray.iter().map(Vec::len).sum();
        let (mut ray, mut t, mut tri, mut u, mut v) = (
            Vec::with_capacity(total),
            Vec::with_capacity(total),
            Vec::with_capacity(total),
            Vec::with_capacity(total),
            Vec::with_capacity(total),
        );
        for (i, hits) in (0i64..).zip(&per_ray) {
            for h in hits {
                ray.push(i);
                t.push(h.t);
                tri.push(i64::from(h.tri));
                u.push(h.u);
                v.push(h.v);
            }
        }
        Ok((
            column(py, ray),
            column(py, t),
            column(py, tri),
            column(py, u),
            column(py, v),
        ))
    }
}
