//! Sweeps: a sphere, a capsule or an oriented box moved along a segment, and where it first
//! touches the mesh.

use meshq::MeshQuery;
use meshq::query::{SweepHit, SweepShape};
use wasm_bindgen::prelude::*;

use crate::MeshBvh;
use crate::args::{range_error, vector};
use crate::js_objects::meshq_sweep_hit;
use crate::overlaps::{obb_of, radius_of};

impl MeshBvh {
    /// The first contact of `shape` moved by `motion` (`Vec3Like`), as a `SweepHit` or `null`.
    fn sweep_js(&self, shape: &SweepShape, motion: &JsValue) -> Result<JsValue, JsValue> {
        let motion = vector(motion, "motion")?;
        let hit = self
            .storage
            .scene
            .sweep(shape, motion)
            .map_err(|e| range_error(&e.to_string()))?;
        Ok(hit.map_or(JsValue::NULL, |h: SweepHit| {
            meshq_sweep_hit(
                h.t, h.point.x, h.point.y, h.point.z, h.normal.x, h.normal.y, h.normal.z, h.tri,
            )
        }))
    }
}

#[wasm_bindgen]
impl MeshBvh {
    /// Where the sphere of `center` (`Vec3Like`) and `radius` (≥ 0; 0 sweeps a point, a ray),
    /// moved by `motion` (`Vec3Like`), first touches the mesh: `{ t, point, normal, triangle }`
    /// (`SweepHit`: `t` the fraction of the motion done at contact, 0 to 1; `point` on the
    /// mesh; `normal` a unit vector from the mesh toward the sphere) or `null` when it touches
    /// nothing along the way. A sphere touching the mesh at the start gives `t = 0`. Exact to
    /// 2⁻¹⁸ of the sweep's size; of contacts at the same `t` the lowest triangle wins.
    #[wasm_bindgen(js_name = sweepSphere, unchecked_return_type = "SweepHit | null")]
    pub fn sweep_sphere(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] center: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number")] radius: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] motion: &JsValue,
    ) -> Result<JsValue, JsValue> {
        let shape = SweepShape::Sphere {
            center: vector(center, "center")?,
            radius: radius_of(radius)?,
        };
        self.sweep_js(&shape, motion)
    }

    /// `sweepSphere` for the capsule around the segment `[a, b]` (each `Vec3Like`) with
    /// `radius` (≥ 0): a character controller's body.
    #[wasm_bindgen(js_name = sweepCapsule, unchecked_return_type = "SweepHit | null")]
    pub fn sweep_capsule(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] a: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] b: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number")] radius: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] motion: &JsValue,
    ) -> Result<JsValue, JsValue> {
        let shape = SweepShape::Capsule {
            a: vector(a, "a")?,
            b: vector(b, "b")?,
            radius: radius_of(radius)?,
        };
        self.sweep_js(&shape, motion)
    }

    /// `sweepSphere` for the oriented box of `center`, `axes` (9 numbers: three orthonormal
    /// directions one after the other) and `halfExtents` (along those axes, each ≥ 0), as
    /// `overlapsOrientedBox` takes it.
    #[wasm_bindgen(js_name = sweepBox, unchecked_return_type = "SweepHit | null")]
    pub fn sweep_box(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] center: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "ArrayLike<number>")] axes: &JsValue,
        #[wasm_bindgen(js_name = halfExtents, unchecked_param_type = "Vec3Like")]
        half_extents: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] motion: &JsValue,
    ) -> Result<JsValue, JsValue> {
        let shape = SweepShape::Box(obb_of(center, axes, half_extents)?);
        self.sweep_js(&shape, motion)
    }
}
