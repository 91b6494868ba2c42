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

/// The power of two `s` that brings `length` into `[1, 2)` (`length · s`), within the normal
/// range; 1 for zero, subnormal, negative or non-finite `length`. Multiplying by it is exact,
/// keeps every order and tie, and brings a shape to a size where products of up to four
/// lengths neither overflow nor underflow `f32`.
#[must_use]
pub(crate) fn unit_scale(length: f32) -> f32 {
    if !(length > 0.0 && length.is_finite()) {
        return 1.0;
    }
    // The biased exponent e puts length in [2^(e−127), 2^(e−126)); 2^(127−e) is its inverse's
    // power of two, kept within the normal range.
    let biased = (length.to_bits() >> 23) & 0xff;
    f32::from_bits(254u32.saturating_sub(biased).clamp(1, 254) << 23)
}

/// The power of two `s` that brings the product `a · b` of two squared lengths (a length to
/// the fourth) near 1 (`a · b · s⁴` in `[1, 32)`), with `s` and `1 / s` normal; 1 when either is
/// zero, subnormal, negative or NaN. `b` may be `+inf` (a squared length past `f32`): it then
/// counts as 2¹²⁸. Used to rescale a computation whose products of four lengths would leave
/// the range of `f32` — exactly, since multiplying by a power of two rounds nothing.
#[must_use]
pub(crate) fn unit_scale_of_squares(a: f32, b: f32) -> f32 {
    if !(a.is_normal() && a > 0.0 && b >= f32::MIN_POSITIVE) {
        return 1.0;
    }
    // Unbiased exponents: a in [2^ea, 2^(ea+1)), b likewise (+inf reads as 2^128).
    let exponent = |x: f32| ((x.to_bits() >> 23) & 0xff) as i32 - 127;
    let quarter = (exponent(a) + exponent(b)).div_euclid(4);
    f32::from_bits(((127 - quarter).clamp(2, 252) as u32) << 23)
}
