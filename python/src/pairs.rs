//! Two meshes (the second placed by an affine map), and a mesh against itself: whether they
//! meet, which triangle pairs meet, how far apart they are.

use std::borrow::Cow;

use meshq::Traverse;
use meshq::bvh::{BuildConfig, Bvh};
use meshq::collide::{
    Affine, CrossingSegment, DistanceLimits, Found, PairBudget, TrianglePair, intersecting_pairs,
    intersection_segments, mesh_distance, meshes_intersect, self_intersecting_pairs,
};
use meshq::error::PairBudgetSpent;
use meshq::owned::{MeshBvh, MeshIndex};
use meshq::query::{PackedTriangles, With};
use numpy::{PyArray1, PyArray2, PyArray3, PyArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::{count, floats, rows};
use crate::mesh::{Mesh, Storage};

/// Pairs returned when `max_pairs` is not given: 2²⁰.
const DEFAULT_MAX_PAIRS: usize = 1 << 20;

/// The BVH the checks walk: the structure itself when it is one, else one built over the same
/// mesh (a k-d tree, octree or grid is not a tree of boxes).
fn bvh_of(storage: &Storage) -> PyResult<Cow<'_, MeshBvh>> {
    match &storage.scene {
        MeshIndex::Bvh(bvh) => Ok(Cow::Borrowed(bvh)),
        other => MeshBvh::build(&other.mesh(), &BuildConfig::default())
            .map(Cow::Owned)
            .map_err(|e| PyValueError::new_err(e.to_string())),
    }
}

/// `transform`: `None` (as it is) or a `(4, 4)` affine matrix (numpy's row-major layout, the
/// translation in the last column, the bottom row `0, 0, 0, 1`) placing `other` in this mesh's
/// frame.
fn placement(transform: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Affine>> {
    let Some(transform) = transform.filter(|t| !t.is_none()) else {
        return Ok(None);
    };
    let m = floats(transform, "transform", 4)?;
    let rows_of: [[f32; 4]; 4] = match m.as_slice() {
        [a, b, c, d, e, f, g, h, i, j, k, l, mm, n, o, p] => [
            [*a, *b, *c, *d],
            [*e, *f, *g, *h],
            [*i, *j, *k, *l],
            [*mm, *n, *o, *p],
        ],
        _ => {
            return Err(PyValueError::new_err(format!(
                "transform must be a (4, 4) matrix, got {} numbers",
                m.len()
            )));
        }
    };
    let mut columns = [0.0f32; 16];
    for (c, column) in columns.chunks_exact_mut(4).enumerate() {
        for (r, value) in column.iter_mut().enumerate() {
            *value = rows_of[r][c];
        }
    }
    Affine::from_cols_4x4(&columns)
        .map(Some)
        .map_err(|e| PyValueError::new_err(format!("transform: {e}")))
}

/// `max_tests`: `None` → [`PairBudget::for_triangles`] of the two meshes.
fn budget(max_tests: Option<usize>, a: usize, b: usize) -> PairBudget {
    max_tests.map_or_else(
        || PairBudget::for_triangles(a, b),
        |max_tests| PairBudget { max_tests },
    )
}

fn spent(error: PairBudgetSpent) -> PyErr {
    PyRuntimeError::new_err(format!("{error} (max_tests)"))
}

type Walked<'a> = With<'a, Bvh<'a>, PackedTriangles<'a>>;

/// Runs `query` on the trees of `one` and `other`, the GIL released.
fn on_both<R: Send>(
    py: Python<'_>,
    one: &Mesh,
    other: &Mesh,
    query: impl FnOnce(Walked<'_>, Walked<'_>, usize, usize) -> R + Send,
) -> PyResult<R> {
    let (sa, sb) = (one.read()?, other.read()?);
    let (a, b) = (bvh_of(&sa)?, bvh_of(&sb)?);
    let (na, nb) = (a.mesh().triangle_count(), b.mesh().triangle_count());
    Ok(py.detach(|| {
        let (ta, tb, pa, pb) = (a.bvh(), b.bvh(), a.packed(), b.packed());
        query(ta.with(&pa), tb.with(&pb), na, nb)
    }))
}

/// Pairs found as an `(k, 2)` `int64` array.
fn pair_rows<'py>(
    py: Python<'py>,
    pairs: &[TrianglePair],
    found: Found,
) -> PyResult<Bound<'py, PyArray2<i64>>> {
    let flat: Vec<i64> = pairs
        .iter()
        .take(found.written)
        .flat_map(|p| [i64::from(p.a), i64::from(p.b)])
        .collect();
    rows(py, flat, 2)
}

#[pymethods]
impl Mesh {
    /// Whether this mesh meets `other` placed in this mesh's frame by `transform` (see
    /// `distance_to`). Touching counts. `max_tests` bounds the triangle pairs considered (by
    /// default 2²⁰ + 256 per triangle of the two meshes); a `RuntimeError` says when it is
    /// spent before an answer, instead of working for minutes on degenerate input.
    #[pyo3(signature = (other, *, transform = None, max_tests = None))]
    fn intersects(
        &self,
        py: Python<'_>,
        other: &Mesh,
        transform: Option<&Bound<'_, PyAny>>,
        max_tests: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<bool> {
        let max_tests = count(max_tests, "max_tests")?;
        let place = placement(transform)?;
        on_both(py, self, other, |a, b, na, nb| {
            meshes_intersect(a, b, place.as_ref(), budget(max_tests, na, nb))
        })?
        .map_err(spent)
    }

    /// The pairs of triangles (this mesh's, `other`'s) that meet, as a `(k, 2)` `int64` array,
    /// at most `max_pairs` (default 2²⁰) of them; `transform` and `max_tests` as for
    /// `intersects`.
    #[pyo3(signature = (other, *, transform = None, max_pairs = None, max_tests = None))]
    fn intersecting_pairs<'py>(
        &self,
        py: Python<'py>,
        other: &Mesh,
        transform: Option<&Bound<'_, PyAny>>,
        max_pairs: Option<&Bound<'_, PyAny>>,
        max_tests: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let max_tests = count(max_tests, "max_tests")?;
        let max_pairs = count(max_pairs, "max_pairs")?.unwrap_or(DEFAULT_MAX_PAIRS);
        let place = placement(transform)?;
        let (pairs, found) = on_both(py, self, other, |a, b, na, nb| {
            let budget = budget(max_tests, na, nb);
            let counted = intersecting_pairs(a, b, place.as_ref(), budget, &mut [])?;
            let mut pairs = vec![TrianglePair::default(); counted.total.min(max_pairs)];
            let found = intersecting_pairs(a, b, place.as_ref(), budget, &mut pairs)?;
            Ok((pairs, found))
        })?
        .map_err(spent)?;
        pair_rows(py, &pairs, found)
    }

    /// Where this mesh and `other` (placed by `transform`) cross: one segment per pair of
    /// crossing triangles (coplanar overlaps have none), at most `max_segments` (default 2²⁰).
    /// Returns `(segments, pairs)`: `(k, 2, 3)` `float32` end points in this mesh's frame and
    /// the `(k, 2)` `int64` triangle pairs they lie on. `max_tests` as for `intersects`.
    #[pyo3(signature = (other, *, transform = None, max_segments = None, max_tests = None))]
    #[allow(clippy::type_complexity)]
    fn intersection_segments<'py>(
        &self,
        py: Python<'py>,
        other: &Mesh,
        transform: Option<&Bound<'_, PyAny>>,
        max_segments: Option<&Bound<'_, PyAny>>,
        max_tests: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<(Bound<'py, PyArray3<f32>>, Bound<'py, PyArray2<i64>>)> {
        let max_tests = count(max_tests, "max_tests")?;
        let max_segments = count(max_segments, "max_segments")?.unwrap_or(DEFAULT_MAX_PAIRS);
        let place = placement(transform)?;
        let segments = on_both(py, self, other, |a, b, na, nb| {
            let budget = budget(max_tests, na, nb);
            let counted = intersection_segments(a, b, place.as_ref(), budget, &mut [])?;
            let empty = CrossingSegment {
                pair: TrianglePair::default(),
                start: glam::Vec3::ZERO,
                end: glam::Vec3::ZERO,
            };
            let mut segments = vec![empty; counted.total.min(max_segments)];
            let found = intersection_segments(a, b, place.as_ref(), budget, &mut segments)?;
            segments.truncate(found.written);
            Ok(segments)
        })?
        .map_err(spent)?;
        let ends: Vec<f32> = segments
            .iter()
            .flat_map(|s| [s.start.to_array(), s.end.to_array()])
            .flatten()
            .collect();
        let pairs: Vec<i64> = segments
            .iter()
            .flat_map(|s| [i64::from(s.pair.a), i64::from(s.pair.b)])
            .collect();
        let k = segments.len();
        Ok((
            PyArray1::from_vec(py, ends).reshape([k, 2, 3])?,
            rows(py, pairs, 2)?,
        ))
    }

    /// The closest pair of points of this mesh and `other`, placed in this mesh's frame by
    /// `transform` (a `(4, 4)` affine matrix, numpy layout: translation in the last column;
    /// `None`: as it is). Returns a dict `{distance, point_a, point_b, triangle_a,
    /// triangle_b}` (both points in this mesh's frame; distance exactly 0 where the meshes
    /// meet), or `None` when no pair is within `max_distance`. `stop_at` ends the search at the
    /// first pair found that close. Apart, the distance is the smallest to within a factor
    /// 1 + 2⁻¹⁷. `max_tests` as for `intersects`.
    #[pyo3(signature = (other, *, transform = None, max_distance = f64::INFINITY, stop_at = 0.0, max_tests = None))]
    fn distance_to<'py>(
        &self,
        py: Python<'py>,
        other: &Mesh,
        transform: Option<&Bound<'_, PyAny>>,
        max_distance: f64,
        stop_at: f64,
        max_tests: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Option<Bound<'py, PyDict>>> {
        let max_tests = count(max_tests, "max_tests")?;
        if !(max_distance >= 0.0) || !(stop_at >= 0.0) {
            return Err(PyValueError::new_err(format!(
                "max_distance and stop_at must be numbers >= 0, got {max_distance} and {stop_at}"
            )));
        }
        let place = placement(transform)?;
        let limits = DistanceLimits {
            max_distance: max_distance as f32,
            stop_at: stop_at as f32,
        };
        let found = on_both(py, self, other, |a, b, na, nb| {
            mesh_distance(a, b, place.as_ref(), limits, budget(max_tests, na, nb))
        })?
        .map_err(spent)?;
        let Some(f) = found else {
            return Ok(None);
        };
        let out = PyDict::new(py);
        out.set_item("distance", f.distance)?;
        out.set_item("point_a", f.on_a.to_array())?;
        out.set_item("point_b", f.on_b.to_array())?;
        out.set_item("triangle_a", f.triangle_a)?;
        out.set_item("triangle_b", f.triangle_b)?;
        Ok(Some(out))
    }

    /// Where this mesh meets itself: pairs of its triangles (lower index first, `(k, 2)`
    /// `int64`) that meet beyond the corner or edge they share; corners shared by index or by
    /// position count as shared. `max_pairs` and `max_tests` as for `intersecting_pairs`.
    #[pyo3(signature = (*, max_pairs = None, max_tests = None))]
    fn self_intersections<'py>(
        &self,
        py: Python<'py>,
        max_pairs: Option<&Bound<'_, PyAny>>,
        max_tests: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let max_tests = count(max_tests, "max_tests")?;
        let max_pairs = count(max_pairs, "max_pairs")?.unwrap_or(DEFAULT_MAX_PAIRS);
        let storage = self.read()?;
        let bvh = bvh_of(&storage)?;
        let (pairs, found) = py
            .detach(|| {
                let (tree, mesh) = (bvh.bvh(), bvh.mesh());
                let n = mesh.triangle_count();
                let budget = budget(max_tests, n, n);
                let counted = self_intersecting_pairs(&tree, &mesh, budget, &mut [])?;
                let mut pairs = vec![TrianglePair::default(); counted.total.min(max_pairs)];
                let found = self_intersecting_pairs(&tree, &mesh, budget, &mut pairs)?;
                Ok((pairs, found))
            })
            .map_err(spent)?;
        pair_rows(py, &pairs, found)
    }
}
