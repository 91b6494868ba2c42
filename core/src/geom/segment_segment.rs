use glam::Vec3;

use crate::math::{cross, dot};

/// The closest points between two segments.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SegmentSegment {
    /// Parameter on the first segment, in `[0, 1]`.
    pub s: f32,
    /// Parameter on the second segment, in `[0, 1]`.
    pub t: f32,
    /// The point `p1 + s·(q1 − p1)`.
    pub on_first: Vec3,
    /// The point `p2 + t·(q2 − p2)`.
    pub on_second: Vec3,
    /// `|on_first − on_second|²`.
    pub distance_squared: f32,
}

#[inline(always)]
fn clamp01(x: f32) -> f32 {
    if x > 0.0 { x.min(1.0) } else { 0.0 }
}

/// The closest points between segments `[p1, q1]` and `[p2, q2]`.
///
/// Solves for the closest points of the two lines, clamps to the segments and re-projects
/// (Ericson, *Real-Time Collision Detection*, §5.1.9), with the lines' determinant taken as
/// `|d1 × d2|²`, so nearly parallel segments are measured to within rounding of their
/// coordinates too. Parallel segments (the cross product exactly zero) give one of the
/// closest pairs (the one with the smaller `s` on the first segment, found by clamping
/// `s = 0`); zero-length segments act as points.
///
/// ```
/// use meshq::{geom::closest_points_segment_segment, math::Vec3};
/// let r = closest_points_segment_segment(
///     Vec3::new(-1.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0),
///     Vec3::new(0.0, -1.0, 2.0), Vec3::new(0.0, 1.0, 2.0));
/// assert_eq!((r.on_first, r.on_second, r.distance_squared), (Vec3::ZERO, Vec3::new(0.0, 0.0, 2.0), 4.0));
/// ```
#[must_use]
pub fn closest_points_segment_segment(p1: Vec3, q1: Vec3, p2: Vec3, q2: Vec3) -> SegmentSegment {
    let d1 = q1 - p1;
    let d2 = q2 - p2;
    let r = p1 - p2;
    let a = dot(d1, d1);
    let e = dot(d2, d2);
    let f = dot(d2, r);
    let (s, t) = if !(a > 0.0) && !(e > 0.0) {
        (0.0, 0.0)
    } else if !(a > 0.0) {
        (0.0, clamp01(f / e))
    } else {
        let c = dot(d1, r);
        if !(e > 0.0) {
            (clamp01(-c / a), 0.0)
        } else {
            let b = dot(d1, d2);
            // The lines' determinant `a·e − b²` and numerator `b·f − c·e` as the cross products
            // they equal (Lagrange's identity): as differences of products they cancel to
            // rounding noise when the segments are nearly parallel, and `s` lands anywhere.
            let n = cross(d1, d2);
            let denom = dot(n, n);
            // Parallel lines (denom = 0): any s works, take s = 0.
            let mut s = if denom > 0.0 {
                clamp01(dot(n, cross(d2, r)) / denom)
            } else {
                0.0
            };
            let mut t = (b * s + f) / e;
            if t < 0.0 {
                t = 0.0;
                s = clamp01(-c / a);
            } else if t > 1.0 {
                t = 1.0;
                s = clamp01((b - c) / a);
            }
            (s, t)
        }
    };
    let on_first = p1 + d1 * s;
    let on_second = p2 + d2 * t;
    let d = on_first - on_second;
    SegmentSegment {
        s,
        t,
        on_first,
        on_second,
        distance_squared: dot(d, d),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_skew_and_clamped() {
        let r = closest_points_segment_segment(
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(4.0, 0.0, 0.0),
            Vec3::new(1.0, -1.0, 0.0),
            Vec3::new(1.0, 3.0, 0.0),
        );
        assert_eq!((r.s, r.t, r.distance_squared), (0.25, 0.25, 0.0));
        // The second segment lies beyond the first's end: clamp s to 1.
        let r = closest_points_segment_segment(
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(3.0, -1.0, 1.0),
            Vec3::new(3.0, 1.0, 1.0),
        );
        assert_eq!((r.s, r.t), (1.0, 0.5));
        assert_eq!(r.distance_squared, 5.0);
    }

    #[test]
    fn parallel_and_zero_length() {
        let r = closest_points_segment_segment(
            Vec3::ZERO,
            Vec3::X * 2.0,
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(5.0, 1.0, 0.0),
        );
        assert_eq!(r.distance_squared, 1.0);
        let r = closest_points_segment_segment(Vec3::ONE, Vec3::ONE, Vec3::ZERO, Vec3::X * 2.0);
        assert_eq!((r.on_second, r.distance_squared), (Vec3::X, 2.0));
        let r = closest_points_segment_segment(Vec3::ZERO, Vec3::X * 2.0, Vec3::ONE, Vec3::ONE);
        assert_eq!((r.on_first, r.distance_squared), (Vec3::X, 2.0));
        let r = closest_points_segment_segment(Vec3::ONE, Vec3::ONE, Vec3::ZERO, Vec3::ZERO);
        assert_eq!(r.distance_squared, 3.0);
    }
}
