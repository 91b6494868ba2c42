//! Batched queries: a frame's worth of rays or points crosses the JavaScript ↔ WebAssembly
//! boundary once, in one typed array, and the answers come back in caller-owned arrays.

use glam::Vec3;
use meshq::math::Ray;
use wasm_bindgen::prelude::*;

use crate::MeshBvh;
use crate::options::ray_options;

/// Distance written for a ray that hits nothing.
pub const MISS_DISTANCE: f32 = f32::INFINITY;
/// Triangle index written for a ray that hits nothing (`0xFFFFFFFF`).
pub const MISS_TRIANGLE: u32 = u32::MAX;

fn check_len(what: &str, got: usize, needed: usize) -> Result<(), JsError> {
    if got < needed {
        return Err(JsError::new(&format!(
            "{what} holds {got} numbers; {needed} are needed"
        )));
    }
    Ok(())
}

fn rays(rays: &[f32], near: f32, far: f32) -> Result<impl Iterator<Item = Ray> + '_, JsError> {
    if !rays.len().is_multiple_of(6) {
        return Err(JsError::new(&format!(
            "rays hold {} numbers, not a multiple of 6 (origin x, y, z, direction x, y, z)",
            rays.len()
        )));
    }
    Ok(rays.chunks_exact(6).map(move |r| {
        Ray::new(Vec3::new(r[0], r[1], r[2]), Vec3::new(r[3], r[4], r[5])).with_range(near, far)
    }))
}

#[wasm_bindgen]
impl MeshBvh {
    /// Casts every ray of `rays` (6 numbers per ray: origin, then direction) with `t` in
    /// `[near, far]`, writing ray `i`'s hit distance to `distances[i]` and its triangle to
    /// `triangles[i]` (a miss writes `Infinity` and `0xFFFFFFFF`). `side` as in `raycast`.
    /// Returns the number of hits.
    #[wasm_bindgen(js_name = raycastBatch)]
    pub fn raycast_batch(
        &self,
        rays_in: &[f32],
        near: f32,
        far: f32,
        distances: &mut [f32],
        triangles: &mut [u32],
        side: Option<u8>,
    ) -> Result<u32, JsError> {
        self.batch(rays_in, near, far, distances, triangles, None, side)
    }

    /// [`MeshBvh::raycast_batch`] that also writes each hit's barycentric weights `u, v` to
    /// `barycentrics[2i..2i+2]` (`NaN` on a miss).
    #[wasm_bindgen(js_name = raycastBatchBarycentric)]
    #[allow(clippy::too_many_arguments)]
    pub fn raycast_batch_barycentric(
        &self,
        rays_in: &[f32],
        near: f32,
        far: f32,
        distances: &mut [f32],
        triangles: &mut [u32],
        barycentrics: &mut [f32],
        side: Option<u8>,
    ) -> Result<u32, JsError> {
        self.batch(
            rays_in,
            near,
            far,
            distances,
            triangles,
            Some(barycentrics),
            side,
        )
    }

    /// Any-hit for every ray of `rays` (6 numbers per ray): `hits[i]` becomes 1 when ray `i`
    /// hits something in `[near, far]`, else 0. Returns the number of rays that hit.
    #[wasm_bindgen(js_name = raycastAnyBatch)]
    pub fn raycast_any_batch(
        &self,
        rays_in: &[f32],
        near: f32,
        far: f32,
        hits: &mut [u8],
        side: Option<u8>,
    ) -> Result<u32, JsError> {
        let options = ray_options(side)?;
        check_len("hits", hits.len(), rays_in.len() / 6)?;
        let views = &self.storage;
        let rays: Vec<Ray> = rays(rays_in, near, far)?.collect();
        let mut answers = vec![false; rays.len()];
        views.raycast_any_batch(&rays, &options, &mut answers)?;
        let mut count = 0;
        for (hit, out) in answers.into_iter().zip(hits.iter_mut()) {
            count += u32::from(hit);
            *out = u8::from(hit);
        }
        Ok(count)
    }

    /// The closest surface point of every point of `points` (3 numbers per point) within
    /// `maxDistance`: `closest[3i..3i+3]` receives the point, `triangles[i]` its triangle and
    /// `distances[i]` the distance (not found: `NaN` coordinates, `0xFFFFFFFF`, `Infinity`).
    /// Returns the number of points found.
    #[wasm_bindgen(js_name = closestPointBatch)]
    pub fn closest_point_batch(
        &self,
        points: &[f32],
        max_distance: f32,
        closest: &mut [f32],
        triangles: &mut [u32],
        distances: &mut [f32],
    ) -> Result<u32, JsError> {
        if !points.len().is_multiple_of(3) {
            return Err(JsError::new("points must hold 3 numbers per point"));
        }
        let n = points.len() / 3;
        check_len("closest", closest.len(), 3 * n)?;
        check_len("triangles", triangles.len(), n)?;
        check_len("distances", distances.len(), n)?;
        let views = &self.storage;
        let queries: Vec<Vec3> = points
            .chunks_exact(3)
            .map(|p| Vec3::new(p[0], p[1], p[2]))
            .collect();
        // Answered in Morton order with seeded searches (the core's batch call): the same
        // answers as one call per point, about 1.8 times as fast on the bunny's workload.
        let mut answers = vec![None; n];
        views.closest_points(&queries, max_distance, &mut answers)?;
        let mut found = 0;
        let outputs = closest
            .chunks_exact_mut(3)
            .zip(triangles.iter_mut())
            .zip(distances.iter_mut());
        for (answer, ((c, t), d)) in answers.into_iter().zip(outputs) {
            match answer {
                Some(hit) => {
                    found += 1;
                    c.copy_from_slice(&hit.point.to_array());
                    *t = hit.tri;
                    *d = hit.distance_squared.sqrt();
                }
                None => {
                    c.fill(f32::NAN);
                    *t = MISS_TRIANGLE;
                    *d = f32::INFINITY;
                }
            }
        }
        Ok(found)
    }
}

impl MeshBvh {
    #[allow(clippy::too_many_arguments)]
    fn batch(
        &self,
        rays_in: &[f32],
        near: f32,
        far: f32,
        distances: &mut [f32],
        triangles: &mut [u32],
        mut barycentrics: Option<&mut [f32]>,
        side: Option<u8>,
    ) -> Result<u32, JsError> {
        let options = ray_options(side)?;
        let n = rays_in.len() / 6;
        check_len("distances", distances.len(), n)?;
        check_len("triangles", triangles.len(), n)?;
        if let Some(uv) = &barycentrics {
            check_len("barycentrics", uv.len(), 2 * n)?;
        }
        let views = &self.storage;
        let rays: Vec<Ray> = rays(rays_in, near, far)?.collect();
        let mut answers = vec![None; rays.len()];
        views.raycast_batch(&rays, &options, &mut answers)?;
        let mut hits = 0;
        let outputs = distances.iter_mut().zip(triangles.iter_mut());
        for (i, (hit, (d, t))) in answers.into_iter().zip(outputs).enumerate() {
            hits += u32::from(hit.is_some());
            (*d, *t) = hit.map_or((MISS_DISTANCE, MISS_TRIANGLE), |h| (h.t, h.tri));
            if let Some(uv) = barycentrics.as_deref_mut() {
                let pair = hit.map_or([f32::NAN; 2], |h| [h.u, h.v]);
                if let Some(out) = uv.get_mut(2 * i..2 * i + 2) {
                    out.copy_from_slice(&pair);
                }
            }
        }
        Ok(hits)
    }
}
