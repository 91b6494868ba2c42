use glam::Vec3;

use crate::math::{Aabb, Triangle, cross, dot, max_f32, min_f32};

/// True when the projections of the triangle (corners `v`) and of the box (half extents `h`,
/// centred at the origin) on `axis` are disjoint. A zero axis separates nothing.
#[inline(always)]
fn separates(axis: Vec3, v: [Vec3; 3], h: Vec3) -> bool {
    let p0 = dot(axis, v[0]);
    let p1 = dot(axis, v[1]);
    let p2 = dot(axis, v[2]);
    let r = h.x * axis.x.abs() + h.y * axis.y.abs() + h.z * axis.z.abs();
    min_f32(min_f32(p0, p1), p2) > r || max_f32(max_f32(p0, p1), p2) < -r
}

/// True when triangle `tri` and box `aabb` share at least one point (touching counts).
///
/// Separating-axis test over the 13 candidate axes: the three box axes, the triangle normal and
/// the nine cross products of box axes with triangle edges (Akenine-Möller 2001, "Fast 3D
/// Triangle-Box Overlap Testing"). Works for degenerate triangles (segments and points). An
/// empty box, or any non-finite input, overlaps nothing.
///
/// ```
/// use meshq::{geom::overlap_triangle_aabb, math::{Aabb, Triangle, Vec3}};
/// let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
/// let tri = Triangle::new(Vec3::new(0.5, 0.5, 2.0), Vec3::new(3.0, 0.5, -1.0), Vec3::new(0.5, 3.0, -1.0));
/// assert!(overlap_triangle_aabb(&tri, &unit));
/// ```
#[must_use]
pub fn overlap_triangle_aabb(tri: &Triangle, aabb: &Aabb) -> bool {
    if aabb.is_empty()
        || !aabb.is_finite()
        || !(tri.a.is_finite() && tri.b.is_finite() && tri.c.is_finite())
    {
        return false;
    }
    // Box axes first: the cheap rejection, equivalent to a bounds overlap.
    if !tri.bounds().overlaps(aabb) {
        return false;
    }
    let center = aabb.center();
    let h = aabb.max - center;
    let v = [tri.a - center, tri.b - center, tri.c - center];
    let edges = [v[1] - v[0], v[2] - v[1], v[0] - v[2]];
    if separates(cross(edges[0], edges[1]), v, h) {
        return false;
    }
    for e in edges {
        for axis in [Vec3::X, Vec3::Y, Vec3::Z] {
            if separates(cross(axis, e), v, h) {
                return false;
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    const UNIT: Aabb = Aabb::new(Vec3::ZERO, Vec3::ONE);

    #[test]
    fn overlapping_touching_and_separated_by_each_axis_kind() {
        let inside = Triangle::new(Vec3::splat(0.2), Vec3::splat(0.3), Vec3::new(0.2, 0.4, 0.3));
        assert!(overlap_triangle_aabb(&inside, &UNIT));
        let touching_corner = Triangle::new(Vec3::ONE, Vec3::splat(2.0), Vec3::new(1.0, 2.0, 3.0));
        assert!(overlap_triangle_aabb(&touching_corner, &UNIT));
        // Separated by a box axis.
        let beside = Triangle::new(
            Vec3::new(1.1, 0.0, 0.0),
            Vec3::new(2.0, 1.0, 0.0),
            Vec3::new(1.5, 0.0, 1.0),
        );
        assert!(!overlap_triangle_aabb(&beside, &UNIT));
        // Separated by the triangle's plane only: a big triangle cutting past the corner.
        let past_corner = Triangle::new(
            Vec3::new(3.2, 0.0, 0.0),
            Vec3::new(0.0, 3.2, 0.0),
            Vec3::new(0.0, 0.0, 3.2),
        );
        assert!(!overlap_triangle_aabb(&past_corner, &UNIT));
        let through_corner = Triangle::new(
            Vec3::new(2.9, 0.0, 0.0),
            Vec3::new(0.0, 2.9, 0.0),
            Vec3::new(0.0, 0.0, 2.9),
        );
        assert!(overlap_triangle_aabb(&through_corner, &UNIT));
        // Edge-cross axes are covered by the property test against polygon clipping.
    }

    #[test]
    fn degenerate_triangles_and_bad_boxes() {
        let segment_through = Triangle::new(Vec3::splat(-1.0), Vec3::splat(2.0), Vec3::splat(2.0));
        assert!(overlap_triangle_aabb(&segment_through, &UNIT));
        let point_outside = Triangle::new(Vec3::splat(2.0), Vec3::splat(2.0), Vec3::splat(2.0));
        assert!(!overlap_triangle_aabb(&point_outside, &UNIT));
        let inside = Triangle::new(Vec3::splat(0.2), Vec3::splat(0.3), Vec3::new(0.2, 0.4, 0.3));
        assert!(!overlap_triangle_aabb(&inside, &Aabb::EMPTY));
        let nan = Triangle::new(Vec3::NAN, Vec3::splat(0.3), Vec3::splat(0.4));
        assert!(!overlap_triangle_aabb(&nan, &UNIT));
    }
}
