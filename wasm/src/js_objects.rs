//! Result objects made on the JavaScript side: Rust passes plain numbers to small functions
//! defined in JavaScript, which is much cheaper than setting properties one by one across the
//! boundary.
//!
//! One word, one meaning, in every result: `t` is the ray parameter (the hit is at
//! `origin + t·direction`), `distance` a Euclidean distance in the mesh's units.

use wasm_bindgen::prelude::*;

#[wasm_bindgen(inline_js = "
export function meshq_ray_hit(t, distance, px, py, pz, triangle, u, v, nx, ny, nz) {
  return { t, distance, point: { x: px, y: py, z: pz }, triangle, u, v, normal: { x: nx, y: ny, z: nz } };
}
export function meshq_closest_point(distance, px, py, pz, triangle, u, v, nx, ny, nz) {
  return { distance, point: { x: px, y: py, z: pz }, triangle, u, v, normal: { x: nx, y: ny, z: nz } };
}
export function meshq_mesh_distance(distance, ax, ay, az, bx, by, bz, triangleA, triangleB) {
  return { distance, pointA: { x: ax, y: ay, z: az }, pointB: { x: bx, y: by, z: bz }, triangleA, triangleB };
}
export function meshq_sweep_hit(t, px, py, pz, nx, ny, nz, triangle) {
  return { t, point: { x: px, y: py, z: pz }, normal: { x: nx, y: ny, z: nz }, triangle };
}
export function meshq_signed_distance(distance, px, py, pz, triangle, u, v, nx, ny, nz, windingNumber) {
  return { distance, point: { x: px, y: py, z: pz }, triangle, u, v, normal: { x: nx, y: ny, z: nz }, windingNumber };
}
")]
extern "C" {
    /// A `RayHit`: `{ t, distance, point: {x, y, z}, triangle, u, v, normal: {x, y, z} }`.
    #[allow(clippy::too_many_arguments)]
    pub fn meshq_ray_hit(
        t: f32,
        distance: f64,
        px: f32,
        py: f32,
        pz: f32,
        triangle: u32,
        u: f32,
        v: f32,
        nx: f32,
        ny: f32,
        nz: f32,
    ) -> JsValue;

    /// A `ClosestPoint`: `{ distance, point: {x, y, z}, triangle, u, v, normal: {x, y, z} }`.
    #[allow(clippy::too_many_arguments)]
    pub fn meshq_closest_point(
        distance: f32,
        px: f32,
        py: f32,
        pz: f32,
        triangle: u32,
        u: f32,
        v: f32,
        nx: f32,
        ny: f32,
        nz: f32,
    ) -> JsValue;

    /// A `MeshDistance`: `{ distance, pointA: {x, y, z}, pointB: {x, y, z}, triangleA,
    /// triangleB }`.
    #[allow(clippy::too_many_arguments)]
    pub fn meshq_mesh_distance(
        distance: f32,
        ax: f32,
        ay: f32,
        az: f32,
        bx: f32,
        by: f32,
        bz: f32,
        triangle_a: u32,
        triangle_b: u32,
    ) -> JsValue;

    /// A `SweepHit`: `{ t, point: {x, y, z}, normal: {x, y, z}, triangle }`.
    #[allow(clippy::too_many_arguments)]
    pub fn meshq_sweep_hit(
        t: f32,
        px: f32,
        py: f32,
        pz: f32,
        nx: f32,
        ny: f32,
        nz: f32,
        triangle: u32,
    ) -> JsValue;

    /// A `SignedDistance`: a `ClosestPoint` whose `distance` is negative inside, with the
    /// `windingNumber` that gave the sign.
    #[allow(clippy::too_many_arguments)]
    pub fn meshq_signed_distance(
        distance: f32,
        px: f32,
        py: f32,
        pz: f32,
        triangle: u32,
        u: f32,
        v: f32,
        nx: f32,
        ny: f32,
        nz: f32,
        winding_number: f32,
    ) -> JsValue;
}

/// Sets `object[key] = value`.
pub fn set(object: &js_sys::Object, key: &str, value: impl Into<JsValue>) -> Result<(), JsError> {
    js_sys::Reflect::set(object, &JsValue::from_str(key), &value.into())
        .map(|_| ())
        .map_err(|_| JsError::new("cannot build the result object"))
}
