use glam::Vec3;

use crate::math::{cross, dot};

/// How two infinite lines `p1 + s·d1` and `p2 + t·d2` relate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LineLine {
    /// The lines meet (their closest points are within the tolerance); `point` is the midpoint
    /// of the two closest points.
    Intersect {
        /// Where they meet.
        point: Vec3,
        /// Parameter on the first line.
        s: f32,
        /// Parameter on the second line.
        t: f32,
    },
    /// The lines are skew: the closest points are farther apart than the tolerance.
    Skew {
        /// Closest point on the first line, `p1 + s·d1`.
        on_first: Vec3,
        /// Closest point on the second line, `p2 + t·d2`.
        on_second: Vec3,
        /// Parameter on the first line.
        s: f32,
        /// Parameter on the second line.
        t: f32,
    },
    /// The lines are parallel and apart by more than the tolerance.
    Parallel,
    /// The lines are parallel and within the tolerance of each other: the same line.
    Coincident,
    /// A direction is zero or a value is not finite: no line.
    Degenerate,
}

/// Intersects the lines `p1 + s·d1` and `p2 + t·d2` (directions need not be unit length).
///
/// Lines count as parallel when the squared sine of their angle is at most `f32::EPSILON`
/// (about 2·10⁻⁴ rad); they count as meeting when their closest points are within
/// `tolerance` (a distance, inclusive).
///
/// ```
/// use meshq::{advanced::{intersect_line_line, LineLine}, math::Vec3};
/// let r = intersect_line_line(Vec3::ZERO, Vec3::X, Vec3::new(2.0, -1.0, 0.0), Vec3::Y, 1e-6);
/// assert_eq!(r, LineLine::Intersect { point: Vec3::new(2.0, 0.0, 0.0), s: 2.0, t: 1.0 });
/// ```
#[must_use]
pub fn intersect_line_line(p1: Vec3, d1: Vec3, p2: Vec3, d2: Vec3, tolerance: f32) -> LineLine {
    if !(p1.is_finite() && d1.is_finite() && p2.is_finite() && d2.is_finite()) {
        return LineLine::Degenerate;
    }
    let a = dot(d1, d1);
    let e = dot(d2, d2);
    if !(a > 0.0 && e > 0.0) {
        return LineLine::Degenerate;
    }
    let tol2 = tolerance * tolerance;
    let r = p1 - p2;
    let b = dot(d1, d2);
    let c = dot(d1, r);
    let f = dot(d2, r);
    let denom = a * e - b * b;
    if denom <= f32::EPSILON * a * e {
        // Distance from p1 to the second line: |r × d2|² / |d2|².
        let n = cross(r, d2);
        return if dot(n, n) / e <= tol2 {
            LineLine::Coincident
        } else {
            LineLine::Parallel
        };
    }
    let s = (b * f - c * e) / denom;
    let t = (a * f - b * c) / denom;
    let on_first = p1 + d1 * s;
    let on_second = p2 + d2 * t;
    let gap = on_first - on_second;
    if dot(gap, gap) <= tol2 {
        LineLine::Intersect {
            point: (on_first + on_second) * 0.5,
            s,
            t,
        }
    } else {
        LineLine::Skew {
            on_first,
            on_second,
            s,
            t,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn skew_parallel_coincident_degenerate() {
        let r = intersect_line_line(Vec3::ZERO, Vec3::X, Vec3::new(1.0, 0.0, 1.0), Vec3::Y, 1e-6);
        assert_eq!(
            r,
            LineLine::Skew {
                on_first: Vec3::X,
                on_second: Vec3::new(1.0, 0.0, 1.0),
                s: 1.0,
                t: 0.0
            }
        );
        assert_eq!(
            intersect_line_line(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::X * -3.0, 1e-6),
            LineLine::Parallel
        );
        assert_eq!(
            intersect_line_line(Vec3::ZERO, Vec3::X, Vec3::X * 5.0, Vec3::X * 2.0, 1e-6),
            LineLine::Coincident
        );
        assert_eq!(
            intersect_line_line(Vec3::ZERO, Vec3::ZERO, Vec3::Y, Vec3::X, 1e-6),
            LineLine::Degenerate
        );
        assert_eq!(
            intersect_line_line(Vec3::NAN, Vec3::X, Vec3::Y, Vec3::X, 1e-6),
            LineLine::Degenerate
        );
    }

    #[test]
    fn tolerance_turns_near_misses_into_intersections() {
        let r = intersect_line_line(
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(1.0, 0.0, 1e-3),
            Vec3::Y,
            1e-2,
        );
        assert!(matches!(r, LineLine::Intersect { s, t, .. } if s == 1.0 && t == 0.0));
    }
}
