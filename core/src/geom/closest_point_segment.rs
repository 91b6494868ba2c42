use glam::Vec3;

use crate::math::dot;

/// The point of segment `[a, b]` closest to `p`, and its parameter `t ∈ [0, 1]`
/// (the point is `a + t·(b − a)`).
///
/// The unclamped projection parameter is clamped to the segment. A zero-length segment
/// (`a == b`) returns `(a, 0)`.
///
/// ```
/// use meshq::{geom::closest_point_segment, math::Vec3};
/// let (q, t) = closest_point_segment(Vec3::new(3.0, 1.0, 0.0), Vec3::ZERO, Vec3::X * 2.0);
/// assert_eq!((q, t), (Vec3::X * 2.0, 1.0));
/// ```
#[must_use]
pub fn closest_point_segment(p: Vec3, a: Vec3, b: Vec3) -> (Vec3, f32) {
    let ab = b - a;
    let len2 = dot(ab, ab);
    if !(len2 > 0.0) {
        return (a, 0.0);
    }
    let t = dot(p - a, ab) / len2;
    let t = if t > 0.0 { t.min(1.0) } else { 0.0 };
    (a + ab * t, t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interior_and_both_clamped_ends() {
        let (a, b) = (Vec3::new(1.0, 0.0, 0.0), Vec3::new(3.0, 0.0, 0.0));
        assert_eq!(
            closest_point_segment(Vec3::new(2.5, 4.0, -1.0), a, b),
            (Vec3::new(2.5, 0.0, 0.0), 0.75)
        );
        assert_eq!(
            closest_point_segment(Vec3::new(-9.0, 1.0, 0.0), a, b),
            (a, 0.0)
        );
        assert_eq!(
            closest_point_segment(Vec3::new(9.0, 1.0, 0.0), a, b),
            (b, 1.0)
        );
    }

    #[test]
    fn zero_length_segment_and_nan_point() {
        assert_eq!(
            closest_point_segment(Vec3::ONE, Vec3::ZERO, Vec3::ZERO),
            (Vec3::ZERO, 0.0)
        );
        let (q, t) = closest_point_segment(Vec3::splat(f32::NAN), Vec3::ZERO, Vec3::X);
        assert_eq!((q, t), (Vec3::ZERO, 0.0));
    }
}
