//! Isotropic remeshing of numpy arrays.

use meshq::collide::PairBudget;
use meshq::mesh::MeshRef;
use meshq::owned::Remeshed;
use meshq::remesh::{EdgeTarget, MeshQuality, RemeshConfig};
use numpy::PyArray2;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::{count, floats, indices, rows, setting};

fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// A positive finite number, or a `ValueError` naming `name`.
fn positive(x: Option<f64>, name: &str) -> PyResult<Option<f32>> {
    match x {
        Some(v) if !(v > 0.0 && (v as f32).is_finite()) => Err(PyValueError::new_err(format!(
            "{name} must be a positive finite number, got {v}"
        ))),
        v => Ok(v.map(|v| v as f32)),
    }
}

fn quality<'py>(py: Python<'py>, q: &MeshQuality) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("triangles", q.triangles)?;
    d.set_item("vertices", q.vertices)?;
    d.set_item("valence_6_percent", q.valence_6_percent)?;
    d.set_item("min_angle_off_boundary", q.min_angle_off_boundary)?;
    d.set_item("under_30_percent", q.under_30_percent)?;
    d.set_item("mean_edge", q.mean_edge)?;
    d.set_item("edge_cv", q.edge_cv)?;
    Ok(d)
}

type Remeshing<'py> = (
    Bound<'py, PyArray2<f32>>,
    Bound<'py, PyArray2<u32>>,
    Bound<'py, PyDict>,
);

/// Remeshes the triangle mesh `vertices` (`(n, 3)`) / `faces` (`(m, 3)`) towards equal edges
/// of `target_length` (world units) or `target_ratio` times the input's mean edge (not both;
/// default: the mean edge), in `iterations` rounds of split, collapse, flip and smoothing,
/// keeping creases sharper than `feature_angle` degrees (default: none kept). Returns
/// `(vertices, faces, report)`: `float32` and `uint32` arrays and a dict of the run's figures
/// (operations, peaks, the quality `before` and `after`, and `distance`, the Hausdorff
/// distance to the input sampled at most `max_distance_tests` triangle pairs, relative to the
/// input's bounding-box diagonal; 0 tests skips it). Raises `ValueError` naming a bad argument
/// or what is wrong with the mesh, and when the output would exceed the remesher's bounds.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (vertices, faces, *, target_length = None, target_ratio = None, iterations = None, feature_angle = None, max_distance_tests = None))]
pub fn remesh<'py>(
    py: Python<'py>,
    vertices: &Bound<'py, PyAny>,
    faces: &Bound<'py, PyAny>,
    target_length: Option<f64>,
    target_ratio: Option<f64>,
    iterations: Option<&Bound<'py, PyAny>>,
    feature_angle: Option<f64>,
    max_distance_tests: Option<&Bound<'py, PyAny>>,
) -> PyResult<Remeshing<'py>> {
    let iterations = setting(iterations, "iterations")?;
    let max_distance_tests = count(max_distance_tests, "max_distance_tests")?;
    let mut config = RemeshConfig::default();
    match (
        positive(target_length, "target_length")?,
        positive(target_ratio, "target_ratio")?,
    ) {
        (Some(_), Some(_)) => {
            return Err(PyValueError::new_err(
                "give target_length or target_ratio, not both",
            ));
        }
        (Some(l), None) => config.target = EdgeTarget::Length(l),
        (None, Some(r)) => config.target = EdgeTarget::MeanEdgeTimes(r),
        (None, None) => {}
    }
    if let Some(n) = iterations {
        config.iterations = n;
    }
    config.feature_angle = feature_angle.map(|a| a as f32);
    config.validate().map_err(value_error)?;
    let positions = floats(vertices, "vertices", 3)?;
    let corners = indices(faces, "faces", 3)?;
    let (out, distance) = py
        .detach(|| -> Result<_, String> {
            let mesh = MeshRef::from_flat(&positions, &corners)
                .and_then(MeshRef::validate)
                .map_err(|e| e.to_string())?;
            let out = Remeshed::of(&mesh, &config).map_err(|e| e.to_string())?;
            let budget = max_distance_tests.map_or_else(
                || PairBudget::for_triangles(mesh.triangle_count(), out.triangles.len()),
                |max_tests| PairBudget { max_tests },
            );
            let distance = out.distance_to(&mesh, budget).map_err(|e| e.to_string())?;
            Ok((out, distance))
        })
        .map_err(PyValueError::new_err)?;
    let report = PyDict::new(py);
    let r = &out.report;
    report.set_item("iterations", r.iterations)?;
    report.set_item("splits", r.splits)?;
    report.set_item("collapses", r.collapses)?;
    report.set_item("flips", r.flips)?;
    report.set_item("relaxed", r.relaxed)?;
    report.set_item("creases", r.creases)?;
    report.set_item("peak_vertices", r.peak_vertices)?;
    report.set_item("peak_triangles", r.peak_triangles)?;
    report.set_item("distance", distance.relative)?;
    report.set_item("distance_samples", distance.samples)?;
    report.set_item("distance_samples_measured", distance.measured)?;
    report.set_item("before", quality(py, &out.before)?)?;
    report.set_item("after", quality(py, &out.after)?)?;
    let flat_positions = out.positions.as_flattened().to_vec();
    let flat_faces = out.triangles.as_flattened().to_vec();
    Ok((
        rows(py, flat_positions, 3)?,
        rows(py, flat_faces, 3)?,
        report,
    ))
}
