//! Shapes against the mesh: which triangles a box or sphere touches, and where a moving
//! sphere, capsule or oriented box first touches the mesh.

use glam::Vec3;
use meshq::MeshQuery;
use meshq::math::{Aabb, Obb};
use meshq::query::{SweepHit, SweepShape};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::{column, floats, point};
use crate::mesh::{Column, Mesh};

/// `radius`: a finite number ≥ 0.
fn radius_of(radius: f64) -> PyResult<f32> {
    let r = radius as f32;
    if r.is_finite() && r >= 0.0 {
        Ok(r)
    } else {
        Err(PyValueError::new_err(format!(
            "radius must be a finite number >= 0, got {radius}"
        )))
    }
}

/// Every triangle `query` reports, in ascending order, as `int64`.
fn sorted_triangles(
    py: Python<'_>,
    query: impl FnOnce(&mut dyn FnMut(u32) -> std::ops::ControlFlow<()>),
) -> Column<'_, i64> {
    let mut found = Vec::new();
    query(&mut |tri| {
        found.push(i64::from(tri));
        std::ops::ControlFlow::Continue(())
    });
    found.sort_unstable();
    found.dedup();
    column(py, found)
}

/// The oriented box of `center`, `axes` (`(3, 3)`: one unit direction per row) and
/// `half_extents`.
fn obb_of(
    center: &Bound<'_, PyAny>,
    axes: &Bound<'_, PyAny>,
    half_extents: &Bound<'_, PyAny>,
) -> PyResult<Obb> {
    let values = floats(axes, "axes", 3)?;
    let [x, y, z] = match values.as_slice() {
        [a, b, c, d, e, f, g, h, i] => [[*a, *b, *c], [*d, *e, *f], [*g, *h, *i]],
        _ => {
            return Err(PyValueError::new_err(
                "axes must be a (3, 3) array: three directions",
            ));
        }
    };
    Ok(Obb::new(
        point(center, "center")?,
        [x, y, z].map(Vec3::from_array),
        point(half_extents, "half_extents")?,
    ))
}

impl Mesh {
    fn sweep_py<'py>(
        &self,
        py: Python<'py>,
        shape: &SweepShape,
        motion: &Bound<'py, PyAny>,
    ) -> PyResult<Option<Bound<'py, PyDict>>> {
        let motion = point(motion, "motion")?;
        let hit = self
            .read()?
            .scene
            .sweep(shape, motion)
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        let Some(SweepHit {
            t,
            point,
            normal,
            tri,
        }) = hit
        else {
            return Ok(None);
        };
        let out = PyDict::new(py);
        out.set_item("t", t)?;
        out.set_item("point", point.to_array())?;
        out.set_item("normal", normal.to_array())?;
        out.set_item("triangle", tri)?;
        Ok(Some(out))
    }
}

#[pymethods]
impl Mesh {
    /// The triangles (ascending `int64` indices) that share a point with the axis-aligned box
    /// from `lower` to `upper` (touching counts).
    fn overlap_box<'py>(
        &self,
        py: Python<'py>,
        lower: &Bound<'py, PyAny>,
        upper: &Bound<'py, PyAny>,
    ) -> PyResult<Column<'py, i64>> {
        let aabb = Aabb::new(point(lower, "lower")?, point(upper, "upper")?);
        let storage = self.read()?;
        Ok(sorted_triangles(py, |report| {
            storage.scene.overlap_aabb(&aabb, report)
        }))
    }

    /// The triangles (ascending `int64` indices) within `radius` (inclusive, ≥ 0) of
    /// `center`.
    fn overlap_sphere<'py>(
        &self,
        py: Python<'py>,
        center: &Bound<'py, PyAny>,
        radius: f64,
    ) -> PyResult<Column<'py, i64>> {
        let (center, radius) = (point(center, "center")?, radius_of(radius)?);
        let storage = self.read()?;
        Ok(sorted_triangles(py, |report| {
            storage.scene.overlap_sphere(center, radius, report)
        }))
    }

    /// The triangles (ascending `int64` indices) that share a point with the oriented box of
    /// `center`, `axes` (`(3, 3)`, one orthonormal direction per row) and `half_extents`.
    fn overlap_oriented_box<'py>(
        &self,
        py: Python<'py>,
        center: &Bound<'py, PyAny>,
        axes: &Bound<'py, PyAny>,
        half_extents: &Bound<'py, PyAny>,
    ) -> PyResult<Column<'py, i64>> {
        let obb = obb_of(center, axes, half_extents)?;
        let storage = self.read()?;
        Ok(sorted_triangles(py, |report| {
            storage.scene.overlap_obb(&obb, report)
        }))
    }

    /// Where the sphere of `center` and `radius` (≥ 0), moved by `motion`, first touches the
    /// mesh: a dict `{t, point, normal, triangle}` (`t` the fraction of the motion done at
    /// contact, 0 to 1; `normal` a unit vector from the mesh toward the sphere) or `None`.
    /// Exact to 2⁻¹⁸ of the sweep's size; of contacts at one `t` the lowest triangle wins.
    fn sweep_sphere<'py>(
        &self,
        py: Python<'py>,
        center: &Bound<'py, PyAny>,
        radius: f64,
        motion: &Bound<'py, PyAny>,
    ) -> PyResult<Option<Bound<'py, PyDict>>> {
        let shape = SweepShape::Sphere {
            center: point(center, "center")?,
            radius: radius_of(radius)?,
        };
        self.sweep_py(py, &shape, motion)
    }

    /// `sweep_sphere` for the capsule around the segment `a`–`b` with `radius` (≥ 0).
    fn sweep_capsule<'py>(
        &self,
        py: Python<'py>,
        a: &Bound<'py, PyAny>,
        b: &Bound<'py, PyAny>,
        radius: f64,
        motion: &Bound<'py, PyAny>,
    ) -> PyResult<Option<Bound<'py, PyDict>>> {
        let shape = SweepShape::Capsule {
            a: point(a, "a")?,
            b: point(b, "b")?,
            radius: radius_of(radius)?,
        };
        self.sweep_py(py, &shape, motion)
    }

    /// `sweep_sphere` for the oriented box of `center`, `axes` and `half_extents` (as
    /// `overlap_oriented_box` takes it).
    fn sweep_box<'py>(
        &self,
        py: Python<'py>,
        center: &Bound<'py, PyAny>,
        axes: &Bound<'py, PyAny>,
        half_extents: &Bound<'py, PyAny>,
        motion: &Bound<'py, PyAny>,
    ) -> PyResult<Option<Bound<'py, PyDict>>> {
        let shape = SweepShape::Box(obb_of(center, axes, half_extents)?);
        self.sweep_py(py, &shape, motion)
    }
}
