//! Measures of a triangle's shape that the remeshing guards share: its normal, how flat it
//! is, and its smallest angle.

use glam::Vec3;

use crate::math::{cross, dot};

/// How flat a triangle may get from a projection: its height over its longest edge, as a
/// fraction of that edge (about the sine of its smallest angle; 0.05 is about 3°).
pub(super) const FLATTEST: f32 = 0.05;

/// The normal of corners `p` (length: twice the area).
pub(super) fn normal_of(p: [Vec3; 3]) -> Vec3 {
    cross(p[1] - p[0], p[2] - p[0])
}

/// How flat corners `p` are, squared: (height over the longest edge / that edge)², about the
/// sine of the smallest angle squared; 0 for a degenerate triangle.
pub(super) fn flatness(p: [Vec3; 3]) -> f32 {
    let n = normal_of(p);
    let longest = [p[1] - p[0], p[2] - p[1], p[0] - p[2]]
        .iter()
        .map(|&e| dot(e, e))
        .fold(0.0f32, f32::max);
    if longest > 0.0 {
        dot(n, n) / (longest * longest)
    } else {
        0.0
    }
}

/// Whether an edit that replaces triangles as flat as `was()` (the flattest of them) with
/// ones as flat as `now` is allowed: not below [`FLATTEST`] unless no worse than before.
/// `was` is worked out only when `now` is below.
pub(super) fn flat_enough(now: f32, was: impl FnOnce() -> f32) -> bool {
    now >= FLATTEST * FLATTEST || now >= was()
}

/// The sine of the smallest angle of corners `p` (the angle between the two longest edges;
/// at most 60°, where the sine grows with the angle); 0 for a degenerate triangle.
pub(super) fn smallest_angle_sine(p: [Vec3; 3]) -> f32 {
    let [x, y, z] = [p[1] - p[0], p[2] - p[1], p[0] - p[2]].map(|e| libm::sqrtf(dot(e, e)));
    let n = normal_of(p);
    // The two longest edges' product is the largest pairwise product.
    let product = (x * y).max(y * z).max(z * x);
    if product > 0.0 {
        libm::sqrtf(dot(n, n)) / product
    } else {
        0.0
    }
}
