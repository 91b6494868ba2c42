//! The closest point for a query point so far from the mesh that squared distances overflow
//! `f32` (beyond about 1.8e19): the same walk ([`super::closest`]), in coordinates scaled
//! down by a power of two.
//!
//! Scaling every coordinate by `2⁻ᵏ` is exact in floating point (short of values that become
//! subnormal), and so is squaring a scaled difference against squaring the original, up to
//! the same factor: the distances keep their order and their ties, so the nearest triangle is
//! the one an unbounded float would find.

/// How far the coordinates are scaled down: `2⁻⁶⁴`, which brings the largest finite `f32`
/// (3.4e38) to 1.8e19, whose square still fits, while leaving coordinates above about 1e-19
/// normal numbers.
pub(super) const SCALE: f32 = 1.0 / 18_446_744_073_709_551_616.0;
