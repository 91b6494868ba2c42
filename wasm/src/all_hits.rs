//! Every hit along a ray (three.js reports all intersections unless `firstHitOnly` is set).

use wasm_bindgen::prelude::*;

use crate::MeshBvh;
use crate::mesh_bvh::ray_side;
use crate::mesh_bvh::{hit_object, js_ray};

#[wasm_bindgen]
impl MeshBvh {
    /// Every hit of the ray `origin + t·direction` with `t` in `[near, far]`, as an array of
    /// `RayHit`s (the objects `raycast` returns), nearest first (lower triangle index on equal
    /// `t`), each triangle once. Arguments as for `raycast`.
    #[wasm_bindgen(js_name = raycastAll, unchecked_return_type = "RayHit[]")]
    pub fn raycast_all(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] origin: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] direction: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number | null")] near: Option<JsValue>,
        #[wasm_bindgen(unchecked_param_type = "number | null")] far: Option<JsValue>,
        #[wasm_bindgen(unchecked_param_type = "Side | RayOptions | null")] side: Option<JsValue>,
    ) -> Result<js_sys::Array, JsValue> {
        let ray = js_ray(origin, direction, near, far)?;
        let hits = self.storage.raycast_all(&ray, &ray_side(side)?);
        Ok(hits
            .into_iter()
            .map(|h| hit_object(&self.storage, &ray, h))
            .collect())
    }
}
