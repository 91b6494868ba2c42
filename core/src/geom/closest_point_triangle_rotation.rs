use glam::{Vec2, Vec3};

use super::closest_point_triangle::{
    at_working_scale, closest_point_on_edges, closest_point_triangle_2d,
};
use crate::math::{ClosestPoint, Triangle, cross, dot};

/// The point of triangle `tri` closest to `p`, by rotation into 2D: the triangle is moved so
/// that `a` is the origin and turned onto the plane `x = 0` (its unit normal onto the x axis,
/// its first edge along y), the 2D question is solved there by
/// [`closest_point_triangle_2d`](crate::advanced::closest_point_triangle_2d), and the 2D answer
/// is turned and moved back. The distance to the plane is the point's dropped x coordinate.
///
/// The same point, barycentrics, feature and distance as
/// [`closest_point_triangle`](super::closest_point_triangle) up to rounding of the rotation: a
/// third method for comparison (the rotation's square roots and extra products make it the
/// slowest). The result's `tri` is 0. Degenerate triangles and every coordinate size are
/// handled as in `closest_point_triangle`.
///
/// ```
/// use meshq::{geom::closest_point_triangle_rotation, math::{Triangle, TriangleFeature, Vec3}};
/// let tri = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
/// let c = closest_point_triangle_rotation(Vec3::new(0.25, 0.25, 2.0), &tri);
/// assert_eq!((c.point, c.distance_squared, c.feature), (Vec3::new(0.25, 0.25, 0.0), 4.0, TriangleFeature::Face));
/// ```
#[must_use]
pub fn closest_point_triangle_rotation(p: Vec3, tri: &Triangle) -> ClosestPoint {
    at_working_scale(p, tri, rotate)
}

fn rotate(p: Vec3, tri: &Triangle) -> ClosestPoint {
    let ab = tri.b - tri.a;
    let ac = tri.c - tri.a;
    let n = cross(ab, ac);
    let (n_length, ab_length) = (length(n), length(ab));
    if !(n_length > 0.0 && ab_length > 0.0 && n_length.is_finite()) {
        return closest_point_on_edges(p, tri);
    }
    // The rotation's rows: the unit normal (to x), the first edge's direction (to y), and their
    // cross product (to z), a right-handed orthonormal frame.
    let y_axis = ab * (1.0 / ab_length);
    let x_axis = n * (1.0 / n_length);
    let z_axis = cross(x_axis, y_axis);
    let in_plane = |v: Vec3| Vec2::new(dot(y_axis, v), dot(z_axis, v));
    let (q, u, v, feature) = closest_point_triangle_2d(
        in_plane(p - tri.a),
        Vec2::ZERO,
        Vec2::new(ab_length, 0.0),
        in_plane(ac),
    );
    let point = tri.a + y_axis * q.x + z_axis * q.y;
    let d = p - point;
    ClosestPoint {
        point,
        tri: 0,
        u,
        v,
        distance_squared: dot(d, d),
        feature,
    }
}

fn length(v: Vec3) -> f32 {
    libm::sqrtf(dot(v, v))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::closest_point_triangle;
    use crate::math::TriangleFeature;

    #[test]
    fn agrees_with_the_region_walk_on_every_feature() {
        let tri = Triangle::new(
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 2.0, 0.5),
            Vec3::new(-1.0, 0.0, 1.0),
        );
        for p in [
            Vec3::new(0.0, 0.5, 0.5),
            Vec3::new(3.0, -1.0, 0.5),
            Vec3::new(0.0, 4.0, 0.0),
            Vec3::new(-3.0, 0.0, 2.0),
            Vec3::new(0.0, -1.0, 0.5),
            Vec3::new(0.5, 1.5, 3.0),
        ] {
            let want = closest_point_triangle(p, &tri);
            let got = closest_point_triangle_rotation(p, &tri);
            assert_eq!(got.feature, want.feature, "{p}");
            assert!((got.point - want.point).length() < 1e-5, "{p}");
            assert!(
                (got.u - want.u).abs() < 1e-5 && (got.v - want.v).abs() < 1e-5,
                "{p}"
            );
        }
        let line = Triangle::new(Vec3::ZERO, Vec3::ZERO, Vec3::X);
        let c = closest_point_triangle_rotation(Vec3::new(0.5, 1.0, 0.0), &line);
        assert_eq!(
            (c.point, c.feature),
            (Vec3::new(0.5, 0.0, 0.0), TriangleFeature::Edge(1))
        );
    }
}
