use glam::{Vec2, Vec3};

use crate::math::{Triangle, dot};

#[inline(always)]
fn edge_function(a: Vec2, b: Vec2, p: Vec2) -> f32 {
    (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)
}

/// True when `p` lies inside the 2D triangle `a, b, c` or on its boundary, for either winding.
///
/// Uses the three half-plane (edge function) tests. A zero-area triangle contains no point.
///
/// ```
/// use meshq::{advanced::point_in_triangle_2d, math::Vec2};
/// let (a, b, c) = (Vec2::ZERO, Vec2::X, Vec2::Y);
/// assert!(point_in_triangle_2d(Vec2::new(0.5, 0.5), a, b, c)); // on the hypotenuse
/// assert!(!point_in_triangle_2d(Vec2::new(0.6, 0.6), a, c, b));
/// ```
#[must_use]
pub fn point_in_triangle_2d(p: Vec2, a: Vec2, b: Vec2, c: Vec2) -> bool {
    let area = edge_function(a, b, c);
    if area == 0.0 || area.is_nan() {
        return false;
    }
    let e0 = edge_function(a, b, p);
    let e1 = edge_function(b, c, p);
    let e2 = edge_function(c, a, p);
    if area > 0.0 {
        e0 >= 0.0 && e1 >= 0.0 && e2 >= 0.0
    } else {
        e0 <= 0.0 && e1 <= 0.0 && e2 <= 0.0
    }
}

/// Barycentric coordinates `(u, v)` of the orthogonal projection of `p` onto the plane of
/// `tri`, such that the projection is `(1 − u − v)·a + u·b + v·c`. `None` for a degenerate
/// triangle or a non-finite result.
#[must_use]
pub fn barycentric_triangle(p: Vec3, tri: &Triangle) -> Option<(f32, f32)> {
    let e0 = tri.b - tri.a;
    let e1 = tri.c - tri.a;
    let ep = p - tri.a;
    let d00 = dot(e0, e0);
    let d01 = dot(e0, e1);
    let d11 = dot(e1, e1);
    let dp0 = dot(ep, e0);
    let dp1 = dot(ep, e1);
    let denom = d00 * d11 - d01 * d01;
    if !(denom > 0.0) || tri.is_degenerate() {
        return None;
    }
    let u = (d11 * dp0 - d01 * dp1) / denom;
    let v = (d00 * dp1 - d01 * dp0) / denom;
    (u.is_finite() && v.is_finite()).then_some((u, v))
}

/// True when the orthogonal projection of `p` onto the plane of `tri` lies inside the triangle
/// or on its boundary (`u ≥ 0`, `v ≥ 0`, `u + v ≤ 1` in [`barycentric_triangle`]).
///
/// The distance from `p` to the plane is ignored; check it separately (for example with
/// [`closest_point_triangle`](super::closest_point_triangle())) when `p` must lie on the
/// triangle. A degenerate triangle contains no point.
#[must_use]
pub fn point_in_triangle(p: Vec3, tri: &Triangle) -> bool {
    barycentric_triangle(p, tri).is_some_and(|(u, v)| u >= 0.0 && v >= 0.0 && u + v <= 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_dimensional_inside_boundary_outside_and_degenerate() {
        let (a, b, c) = (Vec2::ZERO, Vec2::new(4.0, 0.0), Vec2::new(0.0, 4.0));
        assert!(point_in_triangle_2d(Vec2::ONE, a, b, c));
        assert!(point_in_triangle_2d(Vec2::ONE, a, c, b));
        assert!(point_in_triangle_2d(Vec2::new(2.0, 0.0), a, b, c));
        assert!(point_in_triangle_2d(b, a, b, c));
        assert!(!point_in_triangle_2d(Vec2::new(2.5, 2.5), a, b, c));
        assert!(!point_in_triangle_2d(Vec2::new(-0.1, 1.0), a, b, c));
        assert!(!point_in_triangle_2d(
            Vec2::ONE,
            a,
            Vec2::ONE,
            Vec2::splat(2.0)
        ));
        assert!(!point_in_triangle_2d(Vec2::NAN, a, b, c));
    }

    #[test]
    fn three_dimensional_projection_and_barycentrics() {
        let t = Triangle::new(
            Vec3::ZERO,
            Vec3::new(4.0, 0.0, 0.0),
            Vec3::new(0.0, 4.0, 0.0),
        );
        assert_eq!(
            barycentric_triangle(Vec3::new(1.0, 2.0, 9.0), &t),
            Some((0.25, 0.5))
        );
        assert!(point_in_triangle(Vec3::new(1.0, 1.0, -3.0), &t));
        assert!(point_in_triangle(Vec3::new(0.0, 4.0, 0.0), &t));
        assert!(!point_in_triangle(Vec3::new(3.0, 3.0, 0.0), &t));
        let line = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::X * 2.0);
        assert!(!point_in_triangle(Vec3::X, &line));
        assert!(!point_in_triangle(Vec3::NAN, &t));
    }
}
