//! Batched queries: a frame's worth of rays or points crosses the JavaScript ↔ WebAssembly
//! boundary once, in one typed array, and the answers come back in caller-owned arrays.
//!
//! Output arrays must be of the exact type and length named; anything else throws a
//! `TypeError` or `RangeError` before any work, and leaves the arrays untouched.

use glam::Vec3;
use js_sys::Float32Array;
use meshq::math::Ray;
use meshq::query::sorts_ray_batches_of;
use wasm_bindgen::prelude::*;

use crate::MeshBvh;
use crate::args::{
    float_array, floats, max_distance, output_f32, output_u8, output_u32, range, range_error, side,
};

/// The `t` a ray batch writes for a ray that hits nothing (`MeshBvh.MISS_T`).
pub const MISS_T: f32 = f32::INFINITY;
/// The distance a closest-point batch writes for a point that finds nothing
/// (`MeshBvh.MISS_DISTANCE`).
pub const MISS_DISTANCE: f32 = f32::INFINITY;
/// Triangle index written for a ray that hits nothing, or a point that finds nothing
/// (`0xFFFFFFFF`, `MeshBvh.MISS_TRIANGLE`).
pub const MISS_TRIANGLE: u32 = u32::MAX;

/// Rays a ray batch answers per pass. A batch reads its rays, and writes their answers, a chunk
/// at a time through buffers of this many rays (under 1 MB), whatever its length: a
/// WebAssembly module's memory, once grown, is never given back, so buffers sized by the whole
/// batch (about 76 bytes per ray) would keep a large batch's peak for the page's life. A
/// multiple of 8, so that runs of eight rays from one origin stay in one chunk. (On a large
/// mesh, a large batch from many origins goes in passes of [`SORTED_PASS`].)
pub const RAY_CHUNK: usize = 8_192;

/// Rays per pass of a batch of at least 65,536 rays from many origins on a structure of at
/// least 131,072 triangles: passes this long are answered sorted by the line each ray draws
/// through the mesh's box (`meshq::query::sorts_ray_batches_of`), where rays crossing the same
/// region meet while its nodes and triangles are in cache. Their buffers keep about 19 MB of
/// the module's memory, against the mesh's own 50 bytes or more per triangle. A multiple of
/// [`RAY_CHUNK`].
pub const SORTED_PASS: usize = 1 << 18;

/// The rays of a `Float32Array` of 6 numbers per ray, with `t` in `[near, far]`: checked, and
/// read a chunk at a time by [`RayInput::for_each_chunk`].
struct RayInput {
    values: Float32Array,
    /// The rays' numbers copied whole, when an output shares their memory (see
    /// [`RayInput::read_before_writing`]); `None`: read a chunk at a time from `values`.
    whole: Option<Vec<f32>>,
    count: usize,
    near: f32,
    far: f32,
}

impl RayInput {
    /// The rays of `rays`, or the error a wrong type, length or range throws.
    fn new(rays: &JsValue, near: &JsValue, far: &JsValue) -> Result<Self, JsValue> {
        let values = float_array(rays, "rays")?;
        let len = values.length() as usize;
        if !len.is_multiple_of(6) {
            return Err(range_error(&format!(
                "rays hold {len} numbers, not a multiple of 6 (origin x, y, z, direction x, y, z)"
            )));
        }
        let (near, far) = range(near, far)?;
        Ok(Self {
            values,
            whole: None,
            count: len / 6,
            near,
            far,
        })
    }

    /// Copies the rays whole when any of `outputs` (typed arrays) overlaps their bytes, so
    /// that writing a chunk's answers never changes rays not yet read: the answers are those
    /// of separate arrays, whatever the caller shares.
    fn read_before_writing(&mut self, outputs: &[&js_sys::Object]) {
        let (buffer, start, end) = byte_span(self.values.unchecked_ref());
        let shared = outputs.iter().any(|o| {
            let (b, s, e) = byte_span(o);
            js_sys::Object::is(&b, &buffer) && s < end && start < e
        });
        if shared {
            self.whole = Some(self.values.to_vec());
        }
    }

    /// Whether the first [`RAY_CHUNK`] rays' origins are not all one point (bit for bit).
    fn origins_vary(&self) -> bool {
        let len = 6 * RAY_CHUNK.min(self.count);
        let numbers = match &self.whole {
            Some(whole) => whole.get(..len).map(<[f32]>::to_vec).unwrap_or_default(),
            None => self.values.subarray(0, len as u32).to_vec(),
        };
        let origin = |r: &[f32]| [r[0], r[1], r[2]].map(f32::to_bits);
        let mut rays = numbers.chunks_exact(6);
        let first = rays.next().map(origin);
        rays.any(|r| Some(origin(r)) != first)
    }

    /// Hands `each` consecutive runs of at most `chunk` rays, in order, with the index of each
    /// run's first ray; stops at its first error.
    fn for_each_chunk(
        &self,
        chunk: usize,
        mut each: impl FnMut(u32, &[Ray]) -> Result<(), JsValue>,
    ) -> Result<(), JsValue> {
        let most = chunk.min(self.count);
        let mut numbers = vec![0.0f32; 6 * most];
        let mut rays = Vec::with_capacity(most);
        for first in (0..self.count).step_by(chunk) {
            let len = chunk.min(self.count - first);
            let numbers = &mut numbers[..6 * len];
            match &self.whole {
                Some(whole) => numbers.copy_from_slice(&whole[6 * first..6 * (first + len)]),
                None => self
                    .values
                    .subarray((6 * first) as u32, (6 * (first + len)) as u32)
                    .copy_to(numbers),
            }
            rays.clear();
            rays.extend(numbers.chunks_exact(6).map(|r| {
                Ray::new(Vec3::new(r[0], r[1], r[2]), Vec3::new(r[3], r[4], r[5]))
                    .with_range(self.near, self.far)
            }));
            each(first as u32, &rays)?;
        }
        Ok(())
    }
}

/// The elements `first..first + part.len()` of `values` set to `part` (a run of a batch's
/// answers).
/// The bytes a typed array covers: its buffer and the range in it.
fn byte_span(a: &js_sys::Object) -> (js_sys::ArrayBuffer, f64, f64) {
    let view = a.unchecked_ref::<js_sys::Uint8Array>();
    let start = f64::from(view.byte_offset());
    (view.buffer(), start, start + f64::from(view.byte_length()))
}

/// A `RangeError` when two of the `outputs` (typed arrays, with their argument names) share
/// bytes: one answer would overwrite another, so the call refuses before writing anything.
pub(crate) fn outputs_apart(outputs: &[(&js_sys::Object, &str)]) -> Result<(), JsValue> {
    for (i, (a, name_a)) in outputs.iter().enumerate() {
        let (buffer_a, start_a, end_a) = byte_span(a);
        for (b, name_b) in outputs.iter().skip(i + 1) {
            let (buffer_b, start_b, end_b) = byte_span(b);
            if js_sys::Object::is(&buffer_a, &buffer_b) && start_a < end_b && start_b < end_a {
                return Err(range_error(&format!(
                    "{name_a} and {name_b} share memory: pass separate arrays"
                )));
            }
        }
    }
    Ok(())
}

fn write_f32(values: &Float32Array, first: u32, part: &[f32]) {
    values
        .subarray(first, first + part.len() as u32)
        .copy_from(part);
}

#[wasm_bindgen]
impl MeshBvh {
    /// `Infinity`: the `t` a ray batch writes for a ray that hits nothing
    /// (`MeshBvh.MISS_T`).
    #[wasm_bindgen(getter = MISS_T)]
    pub fn miss_t() -> f32 {
        MISS_T
    }

    /// `Infinity`: the distance `closestPointBatch` writes for a point that finds nothing
    /// (`MeshBvh.MISS_DISTANCE`).
    #[wasm_bindgen(getter = MISS_DISTANCE)]
    pub fn miss_distance() -> f32 {
        MISS_DISTANCE
    }

    /// `0xFFFFFFFF`: the triangle a batch writes for a ray or point that finds nothing
    /// (`MeshBvh.MISS_TRIANGLE`).
    #[wasm_bindgen(getter = MISS_TRIANGLE)]
    pub fn miss_triangle() -> u32 {
        MISS_TRIANGLE
    }

    /// `8192`: how many rays a ray batch reads and answers per pass (`MeshBvh.RAY_CHUNK`).
    /// Answers do not depend on it; an output array may even share the rays' buffer.
    #[wasm_bindgen(getter = RAY_CHUNK)]
    pub fn ray_chunk() -> u32 {
        RAY_CHUNK as u32
    }

    /// Casts every ray of `rays` (a `Float32Array`, 6 numbers per ray: origin, then
    /// direction) with `t` in `[near, far]` (`undefined` or `null`: `0`, `Infinity`), writing
    /// ray `i`'s hit parameter to `t[i]` (a `Float32Array` of exactly one number per ray) and
    /// its triangle to `triangles[i]` (a `Uint32Array`, one per ray); a miss writes `MISS_T`
    /// and `MISS_TRIANGLE`. `side` as in `raycast`. Returns the number of hits. Each answer is
    /// exactly `raycast`'s; rays are cast in the given order, and runs of eight consecutive
    /// rays from one origin (a camera's: give them in rows or small tiles) walk the tree
    /// together. Rays are read, and answers written, 8,192 at a time: a batch of any length
    /// needs under 1 MB of the module's memory. On a mesh of 131,072 triangles or more, a batch
    /// of 65,536 rays or more whose first rays come from more than one origin goes in passes of
    /// 262,144 rays instead, each answered sorted by the line each ray draws through the mesh's
    /// box (about 19 MB of the module's memory, kept); the answers are the same.
    #[wasm_bindgen(js_name = raycastBatch)]
    pub fn raycast_batch(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Float32Array")] rays: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number | null | undefined")] near: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number | null | undefined")] far: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Float32Array")] t: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Uint32Array")] triangles: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Side | RayOptions | null")] side: Option<JsValue>,
    ) -> Result<u32, JsValue> {
        let side = side.unwrap_or(JsValue::UNDEFINED);
        self.batch(rays, near, far, t, triangles, None, &side)
    }

    /// [`MeshBvh::raycast_batch`] that also writes each hit's barycentric weights `u, v` to
    /// `barycentrics[2i..2i+2]` (a `Float32Array` of two numbers per ray; `NaN` on a miss).
    #[wasm_bindgen(js_name = raycastBatchBarycentric)]
    #[allow(clippy::too_many_arguments)]
    pub fn raycast_batch_barycentric(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Float32Array")] rays: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number | null | undefined")] near: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number | null | undefined")] far: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Float32Array")] t: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Uint32Array")] triangles: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Float32Array")] barycentrics: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Side | RayOptions | null")] side: Option<JsValue>,
    ) -> Result<u32, JsValue> {
        let side = side.unwrap_or(JsValue::UNDEFINED);
        self.batch(rays, near, far, t, triangles, Some(barycentrics), &side)
    }

    /// Any-hit for every ray of `rays` (a `Float32Array`, 6 numbers per ray): `hits[i]` (a
    /// `Uint8Array`, one per ray) becomes 1 when ray `i` hits something in `[near, far]`
    /// (omitted: `0`, `Infinity`), else 0. Returns the number of rays that hit. Read and
    /// answered in passes as `raycastBatch`.
    #[wasm_bindgen(js_name = raycastAnyBatch)]
    pub fn raycast_any_batch(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Float32Array")] rays: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number | null | undefined")] near: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number | null | undefined")] far: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Uint8Array")] hits: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Side | RayOptions | null")] side: Option<JsValue>,
    ) -> Result<u32, JsValue> {
        let options = crate::args::side(&side.unwrap_or(JsValue::UNDEFINED))?;
        let mut input = RayInput::new(rays, near, far)?;
        let hits = output_u8(hits, "hits", input.count, " (one per ray)")?;
        input.read_before_writing(&[&hits]);
        let (mut answers, mut flags, mut found) = (Vec::new(), Vec::new(), 0u32);
        input.for_each_chunk(self.rays_per_pass(&input), |first, rays| {
            answers.clear();
            answers.resize(rays.len(), false);
            self.storage
                .raycast_any_batch(rays, &options, &mut answers)?;
            flags.clear();
            flags.extend(answers.iter().map(|&a| u8::from(a)));
            hits.subarray(first, first + flags.len() as u32)
                .copy_from(&flags);
            found += answers.iter().map(|&a| u32::from(a)).sum::<u32>();
            Ok(())
        })?;
        Ok(found)
    }

    /// The closest surface point of every point of `points` (a `Float32Array`, 3 numbers per
    /// point) within `maxDistance` (omitted: any distance; otherwise a number ≥ 0):
    /// `closest[3i..3i+3]` (a `Float32Array`, 3 per point) receives the point, `triangles[i]`
    /// (a `Uint32Array`) its triangle and `distances[i]` (a `Float32Array`) the Euclidean
    /// distance; a point that finds nothing writes `NaN` coordinates, `MISS_TRIANGLE` and
    /// `MISS_DISTANCE`. Returns the number of points found.
    #[wasm_bindgen(js_name = closestPointBatch)]
    pub fn closest_point_batch(
        &self,
        #[wasm_bindgen(unchecked_param_type = "Float32Array")] points: &JsValue,
        #[wasm_bindgen(js_name = maxDistance, unchecked_param_type = "number | null | undefined")]
        max_distance_in: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Float32Array")] closest: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Uint32Array")] triangles: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Float32Array")] distances: &JsValue,
    ) -> Result<u32, JsValue> {
        let values = floats(points, "points")?;
        if !values.len().is_multiple_of(3) {
            return Err(range_error(&format!(
                "points hold {} numbers, not a multiple of 3",
                values.len()
            )));
        }
        let n = values.len() / 3;
        let limit = max_distance(max_distance_in)?;
        let closest = output_f32(closest, "closest", 3 * n, " (3 per point)")?;
        let triangles = output_u32(triangles, "triangles", n, " (one per point)")?;
        let distances = output_f32(distances, "distances", n, " (one per point)")?;
        outputs_apart(&[
            (&closest, "closest"),
            (&triangles, "triangles"),
            (&distances, "distances"),
        ])?;
        let queries: Vec<Vec3> = values
            .chunks_exact(3)
            .map(|p| Vec3::new(p[0], p[1], p[2]))
            .collect();
        // Answered in Morton order with seeded searches (the core's batch call): the same
        // answers as one call per point.
        let mut answers = vec![None; n];
        self.storage.closest_points(&queries, limit, &mut answers)?;
        let mut points_out = Vec::with_capacity(3 * n);
        let mut tris = Vec::with_capacity(n);
        let mut dists = Vec::with_capacity(n);
        for (answer, &query) in answers.iter().zip(&queries) {
            match answer {
                Some(hit) => {
                    points_out.extend_from_slice(&hit.point.to_array());
                    tris.push(hit.tri);
                    dists.push(hit.distance_from(query));
                }
                None => {
                    points_out.extend_from_slice(&[f32::NAN; 3]);
                    tris.push(MISS_TRIANGLE);
                    dists.push(MISS_DISTANCE);
                }
            }
        }
        closest.copy_from(&points_out);
        triangles.copy_from(&tris);
        distances.copy_from(&dists);
        Ok(answers.iter().filter(|a| a.is_some()).count() as u32)
    }
}

impl MeshBvh {
    /// Rays per pass of a ray batch on this mesh: [`SORTED_PASS`] when the core sorts a pass
    /// that long on this structure and the batch's first rays do not all share one origin (a
    /// camera's batch then keeps small passes, which stay in cache), else [`RAY_CHUNK`].
    fn rays_per_pass(&self, input: &RayInput) -> usize {
        let pass = SORTED_PASS.min(input.count);
        if sorts_ray_batches_of(&self.storage.scene, pass) && input.origins_vary() {
            SORTED_PASS
        } else {
            RAY_CHUNK
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn batch(
        &self,
        rays: &JsValue,
        near: &JsValue,
        far: &JsValue,
        t_out: &JsValue,
        triangles: &JsValue,
        barycentrics: Option<&JsValue>,
        side_in: &JsValue,
    ) -> Result<u32, JsValue> {
        let options = side(side_in)?;
        let mut input = RayInput::new(rays, near, far)?;
        let n = input.count;
        let t_out = output_f32(t_out, "t", n, " (one per ray)")?;
        let triangles = output_u32(triangles, "triangles", n, " (one per ray)")?;
        let barycentrics: Option<Float32Array> = barycentrics
            .map(|b| output_f32(b, "barycentrics", 2 * n, " (two per ray)"))
            .transpose()?;
        match &barycentrics {
            Some(uv) => {
                outputs_apart(&[
                    (&t_out, "t"),
                    (&triangles, "triangles"),
                    (uv, "barycentrics"),
                ])?;
                input.read_before_writing(&[&t_out, &triangles, uv]);
            }
            None => {
                outputs_apart(&[(&t_out, "t"), (&triangles, "triangles")])?;
                input.read_before_writing(&[&t_out, &triangles]);
            }
        }
        let (mut answers, mut ts, mut tris, mut uvs) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let mut found = 0u32;
        input.for_each_chunk(self.rays_per_pass(&input), |first, rays| {
            answers.clear();
            answers.resize(rays.len(), None);
            self.storage.raycast_batch(rays, &options, &mut answers)?;
            ts.clear();
            ts.extend(answers.iter().map(|h| h.map_or(MISS_T, |h| h.t)));
            write_f32(&t_out, first, &ts);
            tris.clear();
            tris.extend(answers.iter().map(|h| h.map_or(MISS_TRIANGLE, |h| h.tri)));
            triangles
                .subarray(first, first + tris.len() as u32)
                .copy_from(&tris);
            if let Some(uv) = &barycentrics {
                uvs.clear();
                uvs.extend(
                    answers
                        .iter()
                        .flat_map(|h| h.map_or([f32::NAN; 2], |h| [h.u, h.v])),
                );
                write_f32(uv, 2 * first, &uvs);
            }
            found += answers.iter().flatten().count() as u32;
            Ok(())
        })?;
        Ok(found)
    }
}
