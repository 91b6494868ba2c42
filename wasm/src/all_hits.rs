//! Every hit along a ray (three.js reports all intersections unless `firstHitOnly` is set).

use wasm_bindgen::prelude::*;

use crate::MeshBvh;
use crate::args::side_number;
use crate::mesh_bvh::xyz_ray;

#[wasm_bindgen]
impl MeshBvh {
    /// Every hit of the ray `origin + t·direction` with `t` in `[near, far]`, nearest first
    /// (lower triangle index on equal `t`), each triangle once, as 4 numbers per hit:
    /// `t, triangle, u, v` (exact: a `Float64Array` holds every `f32` and `u32`). Numbers as in
    /// `raycastXyz`, `side` as in `raycast`.
    #[wasm_bindgen(js_name = raycastAll)]
    #[allow(clippy::too_many_arguments)]
    pub fn raycast_all(
        &self,
        ox: f64,
        oy: f64,
        oz: f64,
        dx: f64,
        dy: f64,
        dz: f64,
        near: Option<f64>,
        far: Option<f64>,
        side_in: Option<f64>,
    ) -> Result<Vec<f64>, JsValue> {
        let ray = xyz_ray(ox, oy, oz, dx, dy, dz, near, far)?;
        let hits = self.storage.raycast_all(&ray, &side_number(side_in)?);
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
