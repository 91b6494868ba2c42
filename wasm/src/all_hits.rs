//! Every hit along a ray (three.js reports all intersections unless `firstHitOnly` is set).

use wasm_bindgen::prelude::*;

use crate::MeshBvh;
use crate::mesh_bvh::xyz_ray;
use crate::options::ray_options;

#[wasm_bindgen]
impl MeshBvh {
    /// Every hit of the ray `origin + t·direction` with `t` in `[near, far]`, nearest first
    /// (lower triangle index on equal `t`), each triangle once, as 4 numbers per hit:
    /// `t, triangle, u, v` (exact: a `Float64Array` holds every `f32` and `u32`). `side` as in
    /// `raycast`.
    #[wasm_bindgen(js_name = raycastAll)]
    #[allow(clippy::too_many_arguments)]
    pub fn raycast_all(
        &self,
        ox: f32,
        oy: f32,
        oz: f32,
        dx: f32,
        dy: f32,
        dz: f32,
        near: f32,
        far: f32,
        side: Option<u8>,
    ) -> Result<Vec<f64>, JsError> {
        let ray = xyz_ray(ox, oy, oz, dx, dy, dz, near, far);
        let hits = self.storage.raycast_all(&ray, &ray_options(side)?);
        Ok(hits
            .into_iter()
            .flat_map(|h| {
                [
                    f64::from(h.t),
                    f64::from(h.tri),
                    f64::from(h.u),
                    f64::from(h.v),
                ]
            })
            .collect())
    }
}
