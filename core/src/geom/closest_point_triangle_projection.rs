use glam::Vec3;

use super::closest_point_triangle::{at_working_scale, closest_point_on_edges};
use crate::math::{ClosestPoint, Triangle, TriangleFeature, cross, dot};

/// The point of triangle `tri` closest to `p`, by projection and half-plane tests: `p` is
/// dropped perpendicularly onto the triangle's plane; when the foot lies strictly inside all
/// three edges (each tested as `n · (edge × (foot − edge start)) > 0`, `n` the unnormalized
/// normal) it is the answer, otherwise the nearest point of the three edges is.
///
/// The same point, barycentrics, feature and distance as
/// [`closest_point_triangle`](super::closest_point_triangle) up to rounding: a second method for
/// comparison, simpler to follow, slower and less accurate on slivers, where the foot's
/// rounding grows with the triangle's longest edge over its width. The result's `tri` is 0; a
/// foot exactly on an edge is handled by the edge search, so `Face` means strictly inside.
/// Ties between edges go to the first in the order ab, bc, ca. Degenerate triangles and every
/// coordinate size are handled as in `closest_point_triangle`.
///
/// ```
/// use meshq::{geom::closest_point_triangle_projection, math::{Triangle, TriangleFeature, Vec3}};
/// let tri = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
/// let c = closest_point_triangle_projection(Vec3::new(0.25, 0.25, 2.0), &tri);
/// assert_eq!((c.point, c.distance_squared, c.feature), (Vec3::new(0.25, 0.25, 0.0), 4.0, TriangleFeature::Face));
/// ```
#[must_use]
pub fn closest_point_triangle_projection(p: Vec3, tri: &Triangle) -> ClosestPoint {
    at_working_scale(p, tri, project)
}

fn project(p: Vec3, tri: &Triangle) -> ClosestPoint {
    let (a, b, c) = (tri.a, tri.b, tri.c);
    let n = cross(b - a, c - a);
    let nn = dot(n, n);
    if !(nn > 0.0 && nn.is_finite()) {
        return closest_point_on_edges(p, tri);
    }
    let foot = p - n * (dot(n, p - a) / nn);
    // Twice the signed area of the foot with each edge, times |n|: the weight of the opposite
    // corner, positive on the inner side.
    let weight_a = dot(n, cross(c - b, foot - b));
    let weight_b = dot(n, cross(a - c, foot - c));
    let weight_c = dot(n, cross(b - a, foot - a));
    if weight_a > 0.0 && weight_b > 0.0 && weight_c > 0.0 {
        let d = p - foot;
        return ClosestPoint {
            point: foot,
            tri: 0,
            u: weight_b / nn,
            v: weight_c / nn,
            distance_squared: dot(d, d),
            feature: TriangleFeature::Face,
        };
    }
    closest_point_on_edges(p, tri)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::closest_point_triangle;

    #[test]
    fn agrees_with_the_region_walk_on_every_feature() {
        let tri = Triangle::new(
            Vec3::ZERO,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
        );
        for p in [
            Vec3::new(0.5, 0.5, 1.0),
            Vec3::new(-1.0, -1.0, 0.5),
            Vec3::new(3.0, -0.5, 0.0),
            Vec3::new(1.0, -1.0, -2.0),
            Vec3::new(2.0, 2.0, 0.25),
            Vec3::new(-1.0, 1.0, 0.0),
            Vec3::new(0.0, 5.0, 1.0),
        ] {
            let want = closest_point_triangle(p, &tri);
            let got = closest_point_triangle_projection(p, &tri);
            assert_eq!(got.feature, want.feature, "{p}");
            assert!((got.point - want.point).length() < 1e-6, "{p}");
            assert!(
                (got.u - want.u).abs() < 1e-6 && (got.v - want.v).abs() < 1e-6,
                "{p}"
            );
        }
    }

    #[test]
    fn degenerate_and_huge_triangles() {
        let line = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::X * 2.0);
        let c = closest_point_triangle_projection(Vec3::new(1.5, 1.0, 0.0), &line);
        assert_eq!(c.point, Vec3::new(1.5, 0.0, 0.0));
        let big = Triangle::new(Vec3::ZERO, Vec3::X * 1e30, Vec3::Y * 1e30);
        let c = closest_point_triangle_projection(Vec3::new(2.5e29, 2.5e29, 1e30), &big);
        assert_eq!(c.feature, TriangleFeature::Face);
        assert!((c.point - Vec3::new(2.5e29, 2.5e29, 0.0)).length() < 1e24);
    }
}
