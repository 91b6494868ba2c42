use glam::Vec3;

use super::{
    ClosestPair, CullMode, closest_point_triangle, closest_points_segment_segment,
    intersect_ray_triangle,
};
use crate::math::{Ray, Triangle, dot};

/// The closest points between segment `[p, q]` and triangle `tri`: `on_first` on the segment,
/// `on_second` on the triangle.
///
/// A segment that crosses or touches the triangle is at distance exactly 0, both points at the
/// crossing. Apart, the closest pair is an end of the segment against the triangle, or the
/// segment against an edge: the nearest of those five candidates, ties to the first in the
/// order `p`, `q`, edges `ab`, `bc`, `ca`. A zero-length segment is the point `p`; a
/// degenerate triangle is measured as its edges. A NaN coordinate gives a NaN distance.
///
/// ```
/// use meshq::{geom::closest_points_segment_triangle, math::{Triangle, Vec3}};
/// let floor = Triangle::new(Vec3::ZERO, Vec3::new(4.0, 0.0, 0.0), Vec3::new(0.0, 4.0, 0.0));
/// let c = closest_points_segment_triangle(Vec3::new(1.0, 1.0, 1.0), Vec3::new(2.0, 1.0, 3.0), &floor);
/// assert_eq!((c.on_first, c.on_second, c.distance_squared), (Vec3::new(1.0, 1.0, 1.0), Vec3::new(1.0, 1.0, 0.0), 1.0));
/// ```
#[must_use]
pub fn closest_points_segment_triangle(p: Vec3, q: Vec3, tri: &Triangle) -> ClosestPair {
    let d = q - p;
    if d != Vec3::ZERO && !tri.is_degenerate() {
        let mut ray = Ray::new(p, d);
        ray.t_max = 1.0;
        if let Some(hit) = intersect_ray_triangle(&ray, tri, CullMode::None) {
            let x = tri.a * (1.0 - hit.u - hit.v) + tri.b * hit.u + tri.c * hit.v;
            return ClosestPair {
                on_first: x,
                on_second: x,
                distance_squared: 0.0,
            };
        }
    }
    let end = |e: Vec3| {
        let c = closest_point_triangle(e, tri);
        ClosestPair {
            on_first: e,
            on_second: c.point,
            distance_squared: c.distance_squared,
        }
    };
    let mut best = end(p);
    if d == Vec3::ZERO {
        return best;
    }
    let mut consider = |c: ClosestPair| {
        if c.distance_squared < best.distance_squared {
            best = c;
        }
    };
    consider(end(q));
    for (a, b) in [(tri.a, tri.b), (tri.b, tri.c), (tri.c, tri.a)] {
        let s = closest_points_segment_segment(p, q, a, b);
        let gap = s.on_first - s.on_second;
        consider(ClosestPair {
            on_first: s.on_first,
            on_second: s.on_second,
            distance_squared: dot(gap, gap),
        });
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_floats::floats;

    /// Against dense sampling of the segment, each sample measured to the triangle: an upper
    /// bound within half a step of the true distance.
    #[test]
    fn agrees_with_sampling_the_segment() {
        let f = floats(0x5e9_7a1, 15 * 400);
        let steps = 4000;
        for (k, c) in f.chunks_exact(15).enumerate() {
            let off = (k % 4) as f32 * 0.5;
            let (p, q) = (
                Vec3::new(c[0], c[1], c[2] + off),
                Vec3::new(c[3], c[4], c[5] + off),
            );
            let tri = Triangle::new(
                Vec3::new(c[6], c[7], c[8]),
                Vec3::new(c[9], c[10], c[11]),
                Vec3::new(c[12], c[13], c[14]),
            );
            let got = closest_points_segment_triangle(p, q, &tri);
            let sampled = (0..=steps)
                .map(|i| p + (q - p) * (i as f32 / steps as f32))
                .map(|x| closest_point_triangle(x, &tri).distance_squared.sqrt())
                .fold(f32::INFINITY, f32::min);
            let step = (q - p).length() / steps as f32;
            let g = got.distance_squared.sqrt();
            assert!(
                g <= sampled + 1e-5,
                "case {k}: {g} above the sampled {sampled}"
            );
            assert!(
                g >= sampled - step,
                "case {k}: {g} far below the sampled {sampled}"
            );
            let gap = got.on_first - got.on_second;
            assert!((dot(gap, gap) - got.distance_squared).abs() <= 1e-5);
            assert!(closest_point_triangle(got.on_second, &tri).distance_squared <= 1e-10);
        }
    }

    #[test]
    fn crossing_and_point_segments() {
        let floor = Triangle::new(
            Vec3::ZERO,
            Vec3::new(4.0, 0.0, 0.0),
            Vec3::new(0.0, 4.0, 0.0),
        );
        let c = closest_points_segment_triangle(
            Vec3::new(1.0, 1.0, -1.0),
            Vec3::new(1.0, 1.0, 1.0),
            &floor,
        );
        assert_eq!(
            (c.on_first, c.distance_squared),
            (Vec3::new(1.0, 1.0, 0.0), 0.0)
        );
        let p = Vec3::new(1.0, 1.0, 2.0);
        let c = closest_points_segment_triangle(p, p, &floor);
        assert_eq!(
            (c.on_first, c.on_second, c.distance_squared),
            (p, Vec3::new(1.0, 1.0, 0.0), 4.0)
        );
    }
}
