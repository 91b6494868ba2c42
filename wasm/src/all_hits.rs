//! Every hit along a ray (three.js reports all intersections unless `firstHitOnly` is set).

use meshq::geom::{intersect_ray_aabb, intersect_ray_triangle_watertight};
use meshq::math::{Aabb, Ray};
use meshq::query::{LeafTriangleIds, RayOptions, Visitor};
use std::ops::ControlFlow;
use wasm_bindgen::prelude::*;

use crate::MeshBvh;
use crate::mesh_bvh::xyz_ray;
use crate::options::ray_options;
use crate::storage::Storage;

/// Collects every hit in the ray's range: boxes the ray misses are skipped, nothing else (a
/// triangle in several cells is met, and collected, once per cell).
struct AllHits<'v> {
    views: &'v Storage,
    ray: Ray,
    options: RayOptions,
    hits: Vec<[f64; 4]>,
}

impl Visitor for AllHits<'_> {
    fn enter(&mut self, aabb: &Aabb) -> Option<f32> {
        intersect_ray_aabb(&self.ray, aabb).map(|(entry, _)| entry)
    }

    fn leaf(&mut self, tris: LeafTriangleIds<'_>) -> ControlFlow<()> {
        for (_, index) in tris {
            let Some(triangle) = self.views.triangle(index) else {
                continue;
            };
            if let Some(hit) =
                intersect_ray_triangle_watertight(&self.ray, &triangle, self.options.cull)
            {
                self.hits.push([
                    f64::from(hit.t),
                    f64::from(index),
                    f64::from(hit.u),
                    f64::from(hit.v),
                ]);
            }
        }
        ControlFlow::Continue(())
    }
}

#[wasm_bindgen]
impl MeshBvh {
    /// Every hit of the ray `origin + t·direction` with `t` in `[near, far]`, nearest first
    /// (lower triangle index on equal `t`), as 4 numbers per hit: `t, triangle, u, v` (exact:
    /// a `Float64Array` holds every `f32` and `u32`). `side` as in `raycast`.
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
        let views = &self.storage;
        let mut visitor = AllHits {
            views,
            ray,
            options: ray_options(side)?,
            hits: Vec::new(),
        };
        views.traverse(&mut visitor);
        let mut hits = visitor.hits;
        hits.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
        // A cell structure offers a triangle once per cell it lies in: the same hit, repeated.
        hits.dedup();
        Ok(hits.into_iter().flatten().collect())
    }
}
