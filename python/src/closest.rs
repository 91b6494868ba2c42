//! Closest points, winding numbers, containment and signed distance, in batches.

use meshq::inside::WindingAccuracy;
use meshq::math::ClosestPoint;
use numpy::PyArray2;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use rayon::prelude::*;

use crate::arrays::{column, rows, vec3s};
use crate::mesh::{Column, Mesh};
use crate::pool::detached;

fn batch_error(e: impl std::fmt::Display) -> PyErr {
    PyRuntimeError::new_err(e.to_string())
}

/// `max_distance`: a number ≥ 0 (`inf`: no limit).
fn limit(max_distance: f64) -> PyResult<f32> {
    if max_distance >= 0.0 {
        Ok(max_distance as f32)
    } else {
        Err(PyValueError::new_err(format!(
            "max_distance must be a number >= 0 (inf: no limit), got {max_distance}"
        )))
    }
}

/// `accuracy`: the far ratio of the fast winding number, ≥ 1 (`inf`: the exact sum).
fn accuracy(x: f64) -> PyResult<WindingAccuracy> {
    WindingAccuracy::new(x as f32).ok_or_else(|| {
        PyValueError::new_err(format!(
            "accuracy must be a number >= 1 (inf: exact), got {x}"
        ))
    })
}

type Closest<'py> = (
    Bound<'py, PyArray2<f32>>,
    Column<'py, f32>,
    Column<'py, i64>,
    Column<'py, f32>,
    Column<'py, f32>,
);

type Signed<'py> = (
    Column<'py, f32>,
    Bound<'py, PyArray2<f32>>,
    Column<'py, i64>,
);

/// The columns of closest points found (`None`: nothing within the limit).
fn closest_columns<'py>(
    py: Python<'py>,
    queries: &[glam::Vec3],
    found: &[Option<ClosestPoint>],
) -> PyResult<Closest<'py>> {
    let n = found.len();
    let (mut p, mut d, mut tri, mut u, mut v) = (
        Vec::with_capacity(3 * n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
    );
    for (c, &q) in found.iter().zip(queries) {
        match c {
            Some(c) => {
                p.extend_from_slice(&c.point.to_array());
                d.push(c.distance_from(q));
                tri.push(i64::from(c.tri));
                u.push(c.u);
                v.push(c.v);
            }
            None => {
                p.extend_from_slice(&[f32::NAN; 3]);
                d.push(f32::INFINITY);
                tri.push(-1);
                u.push(0.0);
                v.push(0.0);
            }
        }
    }
    Ok((
        rows(py, p, 3)?,
        column(py, d),
        column(py, tri),
        column(py, u),
        column(py, v),
    ))
}

impl Mesh {
    /// The winding numbers at `points` (see `winding_numbers`).
    fn winding_values(
        &self,
        py: Python<'_>,
        points: &Bound<'_, PyAny>,
        accuracy: f64,
    ) -> PyResult<Vec<f32>> {
        let accuracy = self::accuracy(accuracy)?;
        let queries = vec3s(points, "points")?;
        let storage = self.with_winding()?;
        let tree = storage
            .winding_tree()
            .ok_or_else(|| PyRuntimeError::new_err("no winding-number tree"))?;
        let mut out = vec![0.0f32; queries.len()];
        detached(py, || {
            meshq::parallel::winding_numbers(&tree, &queries, accuracy, &mut out)
        })?
        .map_err(batch_error)?;
        Ok(out)
    }
}

#[pymethods]
impl Mesh {
    /// The closest surface point to each of `points` (`(n, 3)`) within `max_distance`
    /// (inclusive; `inf`: no limit). Returns `(closest, distance, triangle, u, v)`: `closest`
    /// `(n, 3)` `float32` (NaN where nothing lies within the limit), `distance` Euclidean
    /// (`inf` there), `triangle` `int64` (`-1` there), `u`, `v` barycentric weights of the
    /// triangle's second and third corners. On equal distance the lower triangle wins.
    #[pyo3(signature = (points, *, max_distance = f64::INFINITY))]
    fn closest_points<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
        max_distance: f64,
    ) -> PyResult<Closest<'py>> {
        let max_distance = limit(max_distance)?;
        let queries = vec3s(points, "points")?;
        let storage = self.read()?;
        let mut out = vec![None; queries.len()];
        detached(py, || {
            meshq::parallel::closest_points(&storage.scene, &queries, max_distance, &mut out)
        })?
        .map_err(batch_error)?;
        closest_columns(py, &queries, &out)
    }

    /// The generalized winding number of the mesh at each of `points`: 1 inside a closed mesh
    /// whose triangles face outwards, 0 outside, fractions near holes, so open, non-manifold
    /// and self-intersecting meshes have an inside too. `accuracy` (≥ 1; `inf`: the exact sum
    /// over every triangle) is the far ratio of the fast winding number: a group of triangles
    /// counts by its expansion when the point is farther than `accuracy` times its radius.
    /// The first inside query prepares the expansions.
    #[pyo3(signature = (points, *, accuracy = 2.0))]
    fn winding_numbers<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
        accuracy: f64,
    ) -> PyResult<Column<'py, f32>> {
        Ok(column(py, self.winding_values(py, points, accuracy)?))
    }

    /// Whether each of `points` is inside the mesh: `|winding number| >= 0.5` (a `bool`
    /// array). `accuracy` as for `winding_numbers`.
    #[pyo3(signature = (points, *, accuracy = 2.0))]
    fn contains<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
        accuracy: f64,
    ) -> PyResult<Column<'py, bool>> {
        let w = self.winding_values(py, points, accuracy)?;
        Ok(column(py, w.iter().map(|w| w.abs() >= 0.5).collect()))
    }

    /// The signed distance from each of `points` to the surface within `max_distance`:
    /// negative inside. `sign="winding"` (default) takes the sign from the winding number at
    /// `accuracy` (any mesh); `sign="pseudo-normal"` from the angle-weighted pseudo-normal at
    /// the closest point (closed, manifold, consistently oriented meshes only: a `ValueError`
    /// names an edge otherwise). Returns `(distance, closest, triangle)`: `distance` `float32`
    /// (NaN where nothing lies within the limit), `closest` `(n, 3)` (NaN there), `triangle`
    /// `int64` (`-1` there). The magnitude equals `closest_points`' distance, bit for bit.
    #[pyo3(signature = (points, *, max_distance = f64::INFINITY, sign = "winding", accuracy = 2.0))]
    fn signed_distances<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
        max_distance: f64,
        sign: &str,
        accuracy: f64,
    ) -> PyResult<Signed<'py>> {
        let max_distance = limit(max_distance)?;
        let accuracy = self::accuracy(accuracy)?;
        let queries = vec3s(points, "points")?;
        let n = queries.len();
        let found: Vec<Option<(f32, ClosestPoint)>> = match sign {
            "winding" => {
                let storage = self.with_winding()?;
                let tree = storage
                    .winding_tree()
                    .ok_or_else(|| PyRuntimeError::new_err("no winding-number tree"))?;
                let mut out = vec![None; n];
                detached(py, || {
                    meshq::parallel::signed_distances(
                        &tree,
                        &storage.scene,
                        &queries,
                        max_distance,
                        accuracy,
                        &mut out,
                    )
                })?
                .map_err(batch_error)?;
                out.into_iter()
                    .map(|s| s.map(|s| (s.distance, s.closest)))
                    .collect()
            }
            "pseudo-normal" => {
                let storage = self.with_pseudo_normals()?;
                let normals = storage
                    .pseudo
                    .as_ref()
                    .ok_or_else(|| PyRuntimeError::new_err("no pseudo-normals"))?
                    .view();
                let mut closest = vec![None; n];
                detached(py, || -> PyResult<Vec<Option<(f32, ClosestPoint)>>> {
                    meshq::parallel::closest_points(
                        &storage.scene,
                        &queries,
                        max_distance,
                        &mut closest,
                    )
                    .map_err(batch_error)?;
                    let mesh = storage.scene.mesh();
                    Ok(closest
                        .par_iter()
                        .zip(queries.par_iter())
                        .map(|(found, &p)| {
                            let c = (*found)?;
                            let inside = normals.inside_at(&mesh, p, &c)?;
                            let d = c.distance_from(p);
                            Some((if inside { -d } else { d }, c))
                        })
                        .collect())
                })??
            }
            other => {
                return Err(PyValueError::new_err(format!(
                    "sign must be 'winding' or 'pseudo-normal', got {other:?}"
                )));
            }
        };
        let (mut d, mut p, mut tri) = (
            Vec::with_capacity(n),
            Vec::with_capacity(3 * n),
            Vec::with_capacity(n),
        );
        for f in &found {
            match f {
                Some((distance, c)) => {
                    d.push(*distance);
                    p.extend_from_slice(&c.point.to_array());
                    tri.push(i64::from(c.tri));
                }
                None => {
                    d.push(f32::NAN);
                    p.extend_from_slice(&[f32::NAN; 3]);
                    tri.push(-1);
                }
            }
        }
        Ok((column(py, d), rows(py, p, 3)?, column(py, tri)))
    }
}
