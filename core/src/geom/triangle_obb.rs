use crate::math::{Aabb, Obb, Triangle};

use super::overlap_triangle_aabb;

/// True when triangle `tri` and oriented box `obb` share a point (touching counts, up to the
/// rounding of moving the triangle into the box's frame).
///
/// The triangle's corners are expressed in the box's frame (`Obb` axes, rotated about its centre), where the box
/// is axis-aligned, and tested with [`overlap_triangle_aabb`]. Degenerate triangles (segments
/// and points) are tested as what they are; an invalid box ([`Obb::is_valid`]) or a
/// non-finite corner overlaps nothing.
///
/// ```
/// use meshq::{geom::overlap_triangle_obb, math::{Obb, Triangle, Vec3}};
/// let (s, c) = (0.5f32.sqrt(), 0.5f32.sqrt());
/// // A cube of half-size 1 turned 45° about z: its corner reaches x = √2 ≈ 1.41.
/// let obb = Obb::new(Vec3::ZERO, [Vec3::new(c, s, 0.0), Vec3::new(-s, c, 0.0), Vec3::Z], Vec3::ONE);
/// let near = Triangle::new(Vec3::new(1.3, -0.1, 0.0), Vec3::new(2.0, 0.0, 0.0), Vec3::new(1.3, 0.1, 0.5));
/// assert!(overlap_triangle_obb(&near, &obb));
/// ```
#[must_use]
pub fn overlap_triangle_obb(tri: &Triangle, obb: &Obb) -> bool {
    if !obb.is_valid() {
        return false;
    }
    let local = Triangle::new(
        obb.to_local(tri.a),
        obb.to_local(tri.b),
        obb.to_local(tri.c),
    );
    overlap_triangle_aabb(&local, &Aabb::new(-obb.half_extents, obb.half_extents))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// A cube of half-size 1 about the origin, turned 45° about z.
    fn turned_cube() -> Obb {
        let h = core::f32::consts::FRAC_1_SQRT_2;
        Obb::new(
            Vec3::ZERO,
            [Vec3::new(h, h, 0.0), Vec3::new(-h, h, 0.0), Vec3::Z],
            Vec3::ONE,
        )
    }

    fn tri(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> Triangle {
        Triangle::new(Vec3::from(a), Vec3::from(b), Vec3::from(c))
    }

    #[test]
    fn inside_crossing_and_beyond_a_turned_face() {
        let obb = turned_cube();
        assert!(overlap_triangle_obb(
            &tri([0.1, 0.0, 0.0], [0.0, 0.1, 0.0], [0.0, 0.0, 0.1]),
            &obb
        ));
        assert!(overlap_triangle_obb(
            &tri([0.0, 0.0, 0.0], [3.0, 0.0, 0.0], [0.0, 0.0, 3.0]),
            &obb
        ));
        // Near the corner of the box's bounds at (1.41, 1.41), outside the turned face
        // x + y = √2: inside the bounds, outside the box.
        assert!(!overlap_triangle_obb(
            &tri([1.2, 1.2, 0.0], [1.4, 1.2, 0.0], [1.2, 1.4, 0.5]),
            &obb
        ));
        // Touching the box's corner at (√2, 0) counts.
        let corner = core::f32::consts::SQRT_2;
        assert!(overlap_triangle_obb(
            &tri([corner, 0.0, 0.0], [2.0, 1.0, 0.0], [2.0, -1.0, 0.0]),
            &obb
        ));
    }

    #[test]
    fn an_invalid_box_touches_nothing() {
        let t = tri([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        let mut obb = turned_cube();
        obb.half_extents.x = -1.0;
        assert!(!overlap_triangle_obb(&t, &obb));
        obb = turned_cube();
        obb.center.y = f32::NAN;
        assert!(!overlap_triangle_obb(&t, &obb));
    }
}
