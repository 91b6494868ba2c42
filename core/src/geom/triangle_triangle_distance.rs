use glam::Vec3;

use super::{
    ClosestPair, TriangleTriangle, closest_point_triangle, closest_points_segment_segment,
    closest_points_segment_triangle, intersect_triangle_triangle,
};
use crate::math::{Triangle, dot};

/// The closest points between triangles `t1` and `t2`.
///
/// Triangles that meet (as [`intersect_triangle_triangle`] decides, touching included) are at
/// distance exactly 0: crossing triangles report the first end of their common segment as
/// both points; coplanar overlapping ones the nearest pair of the features below, pulled
/// onto one point. Apart, the closest pair of two triangles is between a corner of one and
/// the other triangle, or between two edges (the closest features of two disjoint convex
/// polygons), so the answer is the nearest of the six corner–triangle pairs (by
/// [`closest_point_triangle`]) and nine edge–edge pairs (by
/// [`closest_points_segment_segment`]).
///
/// Ties go to the first candidate in this order: `t1`'s corners `a, b, c` against `t2`,
/// `t2`'s corners against `t1`, then `t1`'s edges `ab, bc, ca` each against `t2`'s edges in
/// the same order. A degenerate triangle (a segment or a point) is measured as the union of its
/// edges, each by
/// [`closest_points_segment_triangle`](crate::geom::closest_points_segment_triangle) against a
/// proper triangle, so one that pierces it is at 0. A NaN corner gives a NaN distance.
///
/// ```
/// use meshq::{geom::closest_points_triangle_triangle, math::{Triangle, Vec3}};
/// let floor = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
/// let above = Triangle::new(Vec3::new(0.0, 0.0, 2.0), Vec3::new(1.0, 0.0, 3.0), Vec3::new(0.0, 1.0, 3.0));
/// let c = closest_points_triangle_triangle(&floor, &above);
/// assert_eq!((c.on_first, c.on_second, c.distance_squared), (Vec3::ZERO, Vec3::new(0.0, 0.0, 2.0), 4.0));
/// ```
#[must_use]
pub fn closest_points_triangle_triangle(t1: &Triangle, t2: &Triangle) -> ClosestPair {
    // A segment (or point) against a proper triangle may pierce its face, which no pair of
    // features below sees: measure its edges as segments instead.
    match (t1.is_degenerate(), t2.is_degenerate()) {
        (true, false) => return degenerate_against(t1, t2, false),
        (false, true) => return degenerate_against(t2, t1, true),
        _ => {}
    }
    // Triangles whose boxes are apart cannot meet: the plane tests are skipped for them.
    let meet = if t1.bounds().overlaps(&t2.bounds()) {
        intersect_triangle_triangle(t1, t2)
    } else {
        TriangleTriangle::Disjoint
    };
    if let TriangleTriangle::Segment { a, .. } = meet {
        return ClosestPair {
            on_first: a,
            on_second: a,
            distance_squared: 0.0,
        };
    }
    let mut best = corner_to_triangle(t1.a, t2, false);
    let mut consider = |c: ClosestPair| {
        if c.distance_squared < best.distance_squared {
            best = c;
        }
    };
    consider(corner_to_triangle(t1.b, t2, false));
    consider(corner_to_triangle(t1.c, t2, false));
    for corner in [t2.a, t2.b, t2.c] {
        consider(corner_to_triangle(corner, t1, true));
    }
    let edges = |t: &Triangle| [(t.a, t.b), (t.b, t.c), (t.c, t.a)];
    for (p1, q1) in edges(t1) {
        for (p2, q2) in edges(t2) {
            let s = closest_points_segment_segment(p1, q1, p2, q2);
            consider(ClosestPair {
                on_first: s.on_first,
                on_second: s.on_second,
                distance_squared: s.distance_squared,
            });
        }
    }
    if meet == TriangleTriangle::Coplanar {
        // The overlap's nearest features are apart only by rounding: they touch.
        best.on_second = best.on_first;
        best.distance_squared = 0.0;
    }
    best
}

/// The edges of degenerate triangle `d` against proper triangle `t`, nearest first (ties to
/// the first edge); `d_is_second` puts `d`'s points in `on_second`.
fn degenerate_against(d: &Triangle, t: &Triangle, d_is_second: bool) -> ClosestPair {
    let mut best = closest_points_segment_triangle(d.a, d.b, t);
    for (p, q) in [(d.b, d.c), (d.c, d.a)] {
        let c = closest_points_segment_triangle(p, q, t);
        if c.distance_squared < best.distance_squared {
            best = c;
        }
    }
    if d_is_second {
        core::mem::swap(&mut best.on_first, &mut best.on_second);
    }
    best
}

/// `corner` against triangle `t`; `corner_on_second` says that the corner belongs to the
/// second triangle, so the points land in the right fields.
fn corner_to_triangle(corner: Vec3, t: &Triangle, corner_on_second: bool) -> ClosestPair {
    let c = closest_point_triangle(corner, t);
    let d = corner - c.point;
    let (on_first, on_second) = if corner_on_second {
        (c.point, corner)
    } else {
        (corner, c.point)
    };
    ClosestPair {
        on_first,
        on_second,
        distance_squared: dot(d, d),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_floats::floats;

    fn tri(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> Triangle {
        Triangle::new(Vec3::from(a), Vec3::from(b), Vec3::from(c))
    }

    /// The distance by dense sampling of both triangles in `f64`: an upper bound within
    /// the sampling step of the true one.
    fn sampled_distance(t1: &Triangle, t2: &Triangle, steps: usize) -> f64 {
        let point = |t: &Triangle, i: usize, j: usize| {
            let (u, v) = (i as f64 / steps as f64, j as f64 / steps as f64);
            let w = 1.0 - u - v;
            let f = |a: f32, b: f32, c: f32| w * f64::from(a) + u * f64::from(b) + v * f64::from(c);
            [
                f(t.a.x, t.b.x, t.c.x),
                f(t.a.y, t.b.y, t.c.y),
                f(t.a.z, t.b.z, t.c.z),
            ]
        };
        let samples = |t: &Triangle| {
            let mut out = std::vec::Vec::new();
            for i in 0..=steps {
                for j in 0..=steps - i {
                    out.push(point(t, i, j));
                }
            }
            out
        };
        let (s1, s2) = (samples(t1), samples(t2));
        let mut best = f64::INFINITY;
        for p in &s1 {
            for q in &s2 {
                let d = (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2);
                best = best.min(d);
            }
        }
        best.sqrt()
    }

    #[test]
    fn corner_over_face_and_crossing_edges() {
        let floor = tri([0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [0.0, 4.0, 0.0]);
        let above = tri([1.0, 1.0, 2.0], [2.0, 1.0, 5.0], [1.0, 2.0, 5.0]);
        let c = closest_points_triangle_triangle(&floor, &above);
        assert_eq!(c.on_second, Vec3::new(1.0, 1.0, 2.0));
        assert_eq!(c.on_first, Vec3::new(1.0, 1.0, 0.0));
        assert_eq!(c.distance_squared, 4.0);
        // Two edges crossing over each other, one unit apart.
        let a = tri([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, -1.0, -1.0]);
        let b = tri([0.0, -1.0, 1.0], [0.0, 1.0, 1.0], [1.0, 0.0, 2.0]);
        let c = closest_points_triangle_triangle(&a, &b);
        assert_eq!(c.distance_squared, 1.0);
        assert_eq!(c.on_first, Vec3::ZERO);
        assert_eq!(c.on_second, Vec3::new(0.0, 0.0, 1.0));
        // Swapping the arguments swaps the points.
        let d = closest_points_triangle_triangle(&b, &a);
        assert_eq!((d.on_first, d.on_second), (c.on_second, c.on_first));
    }

    #[test]
    fn meeting_triangles_are_at_zero() {
        let floor = tri([-2.0, 0.0, -2.0], [2.0, 0.0, -2.0], [0.0, 0.0, 3.0]);
        let wall = tri([-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [0.0, 1.0, 0.0]);
        let c = closest_points_triangle_triangle(&floor, &wall);
        assert_eq!(c.distance_squared, 0.0);
        assert_eq!(c.on_first, c.on_second);
        assert_eq!(c.on_first.y, 0.0);
        let shifted = tri([0.5, 0.0, 0.0], [3.0, 0.0, 0.0], [0.5, 3.0, 0.0]);
        let flat = tri([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
        let c = closest_points_triangle_triangle(&flat, &shifted);
        assert_eq!(c.distance_squared, 0.0);
    }

    #[test]
    fn nan_corner_gives_nan() {
        let t = tri([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        let bad = tri([f32::NAN, 0.0, 5.0], [1.0, 0.0, 5.0], [0.0, 1.0, 5.0]);
        assert!(
            closest_points_triangle_triangle(&t, &bad)
                .distance_squared
                .is_nan()
        );
    }

    #[test]
    fn matches_dense_sampling_on_random_pairs() {
        let f = floats(0x5eed_7717, 18 * 300);
        let steps = 60;
        for (k, c) in f.chunks_exact(18).enumerate() {
            let t1 = tri([c[0], c[1], c[2]], [c[3], c[4], c[5]], [c[6], c[7], c[8]]);
            // Second triangle moved off by a varying amount so some pairs meet.
            let off = (k % 5) as f32 * 0.4;
            let t2 = tri(
                [c[9] + off, c[10], c[11]],
                [c[12] + off, c[13], c[14]],
                [c[15] + off, c[16], c[17]],
            );
            let got = closest_points_triangle_triangle(&t1, &t2);
            let d = f64::from(got.distance_squared).sqrt();
            let gap = got.on_first - got.on_second;
            assert!((f64::from(dot(gap, gap)) - f64::from(got.distance_squared)).abs() <= 1e-5);
            // The points lie on their triangles.
            assert!(closest_point_triangle(got.on_first, &t1).distance_squared <= 1e-10);
            assert!(closest_point_triangle(got.on_second, &t2).distance_squared <= 1e-10);
            // Sampling bounds the true distance from above, within its step of the true one.
            let sampled = sampled_distance(&t1, &t2, steps);
            let longest = [t1, t2]
                .iter()
                .flat_map(|t| [t.b - t.a, t.c - t.b, t.a - t.c])
                .map(|e| f64::from(e.length()))
                .fold(0.0f64, f64::max);
            let step = longest / steps as f64;
            assert!(
                d <= sampled + 1e-5,
                "pair {k}: {d} above the sampled {sampled}"
            );
            assert!(
                d >= sampled - step,
                "pair {k}: {d} far below the sampled {sampled}"
            );
        }
    }
}
