//! Scalar helpers with a fixed evaluation order.
//!
//! glam's own `dot`/`cross` are written in the same order today, but the kernels call these so
//! that the order is stated here, once, and cannot change with a dependency update.

use glam::Vec3;

/// `a · b` evaluated as `(a.x*b.x + a.y*b.y) + a.z*b.z`, never fused.
#[inline(always)]
#[must_use]
pub fn dot(a: Vec3, b: Vec3) -> f32 {
    a.x * b.x + a.y * b.y + a.z * b.z
}

/// `a × b`, each component evaluated as `p*q - r*s`, never fused.
#[inline(always)]
#[must_use]
pub fn cross(a: Vec3, b: Vec3) -> Vec3 {
    Vec3::new(
        a.y * b.z - a.z * b.y,
        a.z * b.x - a.x * b.z,
        a.x * b.y - a.y * b.x,
    )
}

/// The smaller of `a` and `b`; returns `b` when the comparison fails (either is NaN).
///
/// Written as a comparison so it compiles to a single `minss` on x86 and so that NaN handling is
/// explicit rather than the "ignore NaN" rule of `f32::min`.
#[inline(always)]
#[must_use]
pub fn min_f32(a: f32, b: f32) -> f32 {
    if a < b { a } else { b }
}

/// The larger of `a` and `b`; returns `b` when the comparison fails (either is NaN).
#[inline(always)]
#[must_use]
pub fn max_f32(a: f32, b: f32) -> f32 {
    if a > b { a } else { b }
}
