use glam::Vec3;

use super::closest_point_segment;
use crate::math::dot;

/// True when `p` is within `tolerance` (a distance, inclusive) of segment `[a, b]`.
///
/// A zero-length segment is the point `a`. A negative or NaN tolerance accepts nothing.
///
/// ```
/// use meshq::{geom::point_on_segment, math::Vec3};
/// assert!(point_on_segment(Vec3::new(1.0, 1e-4, 0.0), Vec3::ZERO, Vec3::X * 2.0, 1e-3));
/// assert!(!point_on_segment(Vec3::new(3.0, 0.0, 0.0), Vec3::ZERO, Vec3::X * 2.0, 0.5));
/// ```
#[must_use]
pub fn point_on_segment(p: Vec3, a: Vec3, b: Vec3, tolerance: f32) -> bool {
    if !(tolerance >= 0.0) {
        return false;
    }
    let (q, _) = closest_point_segment(p, a, b);
    let d = p - q;
    dot(d, d) <= tolerance * tolerance
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tolerance_is_inclusive_and_ends_are_rounded() {
        let (a, b) = (Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0));
        assert!(point_on_segment(Vec3::new(1.0, 0.0, 0.0), a, b, 0.0));
        assert!(point_on_segment(Vec3::new(1.0, 0.5, 0.0), a, b, 0.5));
        assert!(!point_on_segment(Vec3::new(1.0, 0.5, 0.0), a, b, 0.49));
        assert!(point_on_segment(Vec3::new(2.3, 0.4, 0.0), a, b, 0.5));
        assert!(!point_on_segment(Vec3::ONE, a, b, -1.0));
        assert!(!point_on_segment(Vec3::ONE, a, b, f32::NAN));
        assert!(point_on_segment(Vec3::ZERO, Vec3::ZERO, Vec3::ZERO, 0.0));
    }
}
