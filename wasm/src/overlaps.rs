//! Whether a shape touches the mesh: a sphere, an oriented box, a triangle.

use std::ops::ControlFlow;

use meshq::MeshQuery;
use meshq::math::{Obb, Triangle};
use wasm_bindgen::prelude::*;

use crate::MeshBvh;
use crate::args::{JsNumber, finite, range_error, vector};
use crate::fields::finite_numbers;

/// Whether `query` reports anything, stopping at the first report.
fn any(query: impl FnOnce(&mut dyn FnMut(u32) -> ControlFlow<()>)) -> bool {
    let mut found = false;
    query(&mut |_| {
        found = true;
        ControlFlow::Break(())
    });
    found
}

/// `radius`: a finite number ≥ 0, or a `TypeError` / `RangeError` naming it.
pub(crate) fn radius_of(radius: &JsValue) -> Result<f32, JsValue> {
    let radius = finite(radius, "radius")?;
    if radius < 0.0 {
        return Err(range_error(&format!(
            "radius must be a finite number >= 0, got {}",
            JsNumber(f64::from(radius))
        )));
    }
    Ok(radius)
}

/// The oriented box of `center` (`Vec3Like`), `axes` (9 numbers: three directions one after
/// the other) and `halfExtents` (`Vec3Like`).
pub(crate) fn obb_of(
    center: &JsValue,
    axes: &JsValue,
    half_extents: &JsValue,
) -> Result<Obb, JsValue> {
    let values = finite_numbers(axes, "axes", Some(9))?;
    let [x, y, z] = match values.as_slice() {
        [a, b, c, d, e, f, g, h, i] => [[*a, *b, *c], [*d, *e, *f], [*g, *h, *i]],
        _ => return Err(range_error("axes must hold 9 numbers (three directions)")),
    };
    Ok(Obb::new(
        vector(center, "center")?,
        [x, y, z].map(glam::Vec3::from_array),
        vector(half_extents, "halfExtents")?,
    ))
}

#[wasm_bindgen]
impl MeshBvh {
    /// Whether a triangle of the mesh comes within `radius` (a finite number ≥ 0) of `center`
    /// (`Vec3Like`), touching included. A negative radius is a `RangeError`.
    #[wasm_bindgen(js_name = overlapsSphere)]
    pub fn overlaps_sphere(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] center: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number")] radius: &JsValue,
    ) -> Result<bool, JsValue> {
        let c = vector(center, "center")?;
        let radius = radius_of(radius)?;
        Ok(any(|f| self.storage.scene.overlap_sphere(c, radius, f)))
    }

    /// Whether a triangle of the mesh shares a point with the oriented box of centre `center`
    /// (`[x, y, z]` or `{x, y, z}`), axes `axes` (9 numbers: three orthonormal directions one after the
    /// other) and half extents `halfExtents` (`[x, y, z]` along those axes, each ≥ 0).
    #[wasm_bindgen(js_name = overlapsOrientedBox)]
    pub fn overlaps_oriented_box(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] center: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "ArrayLike<number>")] axes: &JsValue,
        #[wasm_bindgen(js_name = halfExtents, unchecked_param_type = "Vec3Like")]
        half_extents: &JsValue,
    ) -> Result<bool, JsValue> {
        let obb = obb_of(center, axes, half_extents)?;
        Ok(any(|f| self.storage.scene.overlap_obb(&obb, f)))
    }

    /// Whether a triangle of the mesh meets the triangle with corners `a`, `b`, `c` (each
    /// `[x, y, z]`): touching and coplanar overlap count; a degenerate triangle meets nothing.
    #[wasm_bindgen(js_name = overlapsTriangle)]
    pub fn overlaps_triangle(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] a: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] b: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] c: &JsValue,
    ) -> Result<bool, JsValue> {
        let t = Triangle::new(vector(a, "a")?, vector(b, "b")?, vector(c, "c")?);
        Ok(any(|f| self.storage.scene.overlap_triangle(&t, f)))
    }
}
