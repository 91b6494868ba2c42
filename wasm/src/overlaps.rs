//! Whether a shape touches the mesh: a sphere, an oriented box, a triangle.

use std::ops::ControlFlow;

use meshq::MeshQuery;
use meshq::math::{Obb, Triangle};
use wasm_bindgen::prelude::*;

use crate::MeshBvh;
use crate::mesh_bvh::vec3;

/// Whether `query` reports anything, stopping at the first report.
fn any(query: impl FnOnce(&mut dyn FnMut(u32) -> ControlFlow<()>)) -> bool {
    let mut found = false;
    query(&mut |_| {
        found = true;
        ControlFlow::Break(())
    });
    found
}

#[wasm_bindgen]
impl MeshBvh {
    /// Whether a triangle of the mesh comes within `radius` of `center` (`[x, y, z]`),
    /// touching included. A negative or NaN radius touches nothing.
    #[wasm_bindgen(js_name = overlapsSphere)]
    pub fn overlaps_sphere(&self, center: &[f32], radius: f32) -> Result<bool, JsError> {
        let c = vec3(center, "center")?;
        Ok(any(|f| self.storage.scene.overlap_sphere(c, radius, f)))
    }

    /// Whether a triangle of the mesh shares a point with the oriented box of centre `center`
    /// (`[x, y, z]`), axes `axes` (9 numbers: three orthonormal directions one after the
    /// other) and half extents `halfExtents` (`[x, y, z]` along those axes, each ≥ 0).
    #[wasm_bindgen(js_name = overlapsOrientedBox)]
    pub fn overlaps_oriented_box(
        &self,
        center: &[f32],
        axes: &[f32],
        half_extents: &[f32],
    ) -> Result<bool, JsError> {
        let [x, y, z] = match axes {
            [a, b, c, d, e, f, g, h, i] => [[*a, *b, *c], [*d, *e, *f], [*g, *h, *i]],
            _ => {
                return Err(JsError::new(&format!(
                    "axes must hold 9 numbers (three directions), got {}",
                    axes.len()
                )));
            }
        };
        let obb = Obb::new(
            vec3(center, "center")?,
            [x, y, z].map(glam::Vec3::from_array),
            vec3(half_extents, "halfExtents")?,
        );
        Ok(any(|f| self.storage.scene.overlap_obb(&obb, f)))
    }

    /// Whether a triangle of the mesh meets the triangle with corners `a`, `b`, `c` (each
    /// `[x, y, z]`): touching and coplanar overlap count; a degenerate triangle meets nothing.
    #[wasm_bindgen(js_name = overlapsTriangle)]
    pub fn overlaps_triangle(&self, a: &[f32], b: &[f32], c: &[f32]) -> Result<bool, JsError> {
        let t = Triangle::new(vec3(a, "a")?, vec3(b, "b")?, vec3(c, "c")?);
        Ok(any(|f| self.storage.scene.overlap_triangle(&t, f)))
    }
}
