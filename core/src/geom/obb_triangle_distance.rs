use glam::Vec3;

use super::{
    ClosestPair, closest_point_triangle, closest_points_segment_triangle, overlap_triangle_obb,
};
use crate::math::{Obb, Triangle, dot};

/// The point of `obb` nearest `p`: `p` clamped to the box in its own frame.
#[must_use]
pub(crate) fn closest_point_obb(p: Vec3, obb: &Obb) -> Vec3 {
    let local = obb.to_local(p);
    let h = obb.half_extents;
    let clamped = local.clamp(-h, h);
    let [a, b, c] = obb.axes;
    obb.center + a * clamped.x + b * clamped.y + c * clamped.z
}

/// The closest points between oriented box `obb` (solid) and triangle `tri`: `on_first` in the
/// box, `on_second` on the triangle.
///
/// The candidates are the triangle's three corners against the box, the box's eight corners
/// against the triangle, the box's twelve edges against the triangle (by
/// [`closest_points_segment_triangle`](crate::geom::closest_points_segment_triangle), so an
/// edge piercing the triangle is at 0) and the triangle's three edges clipped to the box (an
/// edge entering it is at 0, at the point where it enters): apart, the closest pair of two
/// convex polyhedra is a corner against the other or an edge against an edge, and when they
/// meet, an edge of one meets the other. The nearest wins, ties to the first in that order.
/// A triangle that shares a point with the box as
/// [`overlap_triangle_obb`](crate::geom::overlap_triangle_obb) decides (touching counts) is at
/// distance exactly 0, with the nearest candidate's points. A box that is not
/// [valid](Obb::is_valid) or a NaN corner gives a NaN distance.
#[must_use]
pub fn closest_points_obb_triangle(obb: &Obb, tri: &Triangle) -> ClosestPair {
    if !obb.is_valid() {
        return ClosestPair {
            on_first: Vec3::NAN,
            on_second: Vec3::NAN,
            distance_squared: f32::NAN,
        };
    }
    let pair = |on_first: Vec3, on_second: Vec3| {
        let gap = on_first - on_second;
        ClosestPair {
            on_first,
            on_second,
            distance_squared: dot(gap, gap),
        }
    };
    let mut best = pair(closest_point_obb(tri.a, obb), tri.a);
    let mut consider = |c: ClosestPair| {
        if c.distance_squared < best.distance_squared {
            best = c;
        }
    };
    consider(pair(closest_point_obb(tri.b, obb), tri.b));
    consider(pair(closest_point_obb(tri.c, obb), tri.c));
    let corners = box_corners(obb);
    for &k in &corners {
        consider(pair(k, closest_point_triangle(k, tri).point));
    }
    for (i, j) in BOX_EDGES {
        let (Some(&p), Some(&q)) = (corners.get(i), corners.get(j)) else {
            continue;
        };
        let c = closest_points_segment_triangle(p, q, tri);
        consider(c);
    }
    for (p, q) in [(tri.a, tri.b), (tri.b, tri.c), (tri.c, tri.a)] {
        if let Some(x) = segment_entry(p, q, obb) {
            consider(pair(x, x));
        }
    }
    if best.distance_squared > 0.0 && overlap_triangle_obb(tri, obb) {
        best.distance_squared = 0.0;
    }
    best
}

/// Where segment `[p, q]` enters `obb` (its first point inside, `p` itself when `p` is in
/// the box), by clipping its parameter to each axis's slab; `None` when it stays outside.
fn segment_entry(p: Vec3, q: Vec3, obb: &Obb) -> Option<Vec3> {
    let (lp, lq) = (obb.to_local(p), obb.to_local(q));
    let (d, h) = (lq - lp, obb.half_extents);
    let (mut lo, mut hi) = (0.0f32, 1.0f32);
    for axis in 0..3 {
        let (start, step, half) = (lp[axis], d[axis], h[axis]);
        if step == 0.0 {
            if start.abs() > half {
                return None;
            }
            continue;
        }
        let (a, b) = ((-half - start) / step, (half - start) / step);
        lo = lo.max(a.min(b));
        hi = hi.min(a.max(b));
    }
    (lo <= hi).then(|| p + (q - p) * lo)
}

/// The box's corners: bit 0 of the index picks the sign along the first axis, bit 1 the
/// second, bit 2 the third.
fn box_corners(obb: &Obb) -> [Vec3; 8] {
    let [a, b, c] = obb.axes;
    let h = obb.half_extents;
    core::array::from_fn(|i| {
        let s = |bit: usize| if i & bit != 0 { 1.0 } else { -1.0 };
        obb.center + a * (s(1) * h.x) + b * (s(2) * h.y) + c * (s(4) * h.z)
    })
}

/// The twelve edges of [`box_corners`], as pairs of corner indices differing in one bit.
const BOX_EDGES: [(usize, usize); 12] = [
    (0, 1),
    (2, 3),
    (4, 5),
    (6, 7),
    (0, 2),
    (1, 3),
    (4, 6),
    (5, 7),
    (0, 4),
    (1, 5),
    (2, 6),
    (3, 7),
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::closest_points_triangle_triangle;
    use crate::test_floats::floats;

    /// Apart, the distance is that of the nearest of the box's twelve face triangles.
    #[test]
    fn agrees_with_the_box_surface_when_apart() {
        let f = floats(0xb0c5, 16 * 300);
        let mut apart = 0;
        for (k, c) in f.chunks_exact(16).enumerate() {
            let q = glam::Quat::from_euler(glam::EulerRot::XYZ, c[0] * 3.0, c[1] * 3.0, c[2] * 3.0);
            let axes = [q * Vec3::X, q * Vec3::Y, q * Vec3::Z];
            let h = Vec3::new(
                c[3].abs() + 0.05,
                c[4].abs() * 0.5 + 0.05,
                c[5].abs() * 0.2 + 0.01,
            );
            let obb = Obb::new(Vec3::new(c[6], c[7], c[8]) * 0.5, axes, h);
            let off = Vec3::new((k % 3) as f32 * 0.6, 0.0, 0.0);
            let tri = Triangle::new(
                Vec3::new(c[9], c[10], c[11]) + off,
                Vec3::new(c[12], c[13], c[14]) + off,
                Vec3::new(c[15], c[9], c[12]) + off,
            );
            let got = closest_points_obb_triangle(&obb, &tri);
            let corners = box_corners(&obb);
            let faces = [
                [0, 1, 3, 2],
                [4, 5, 7, 6],
                [0, 1, 5, 4],
                [2, 3, 7, 6],
                [0, 2, 6, 4],
                [1, 3, 7, 5],
            ];
            let surface = faces
                .iter()
                .flat_map(|f| [[f[0], f[1], f[2]], [f[0], f[2], f[3]]])
                .map(|[i, j, l]| Triangle::new(corners[i], corners[j], corners[l]))
                .map(|face| closest_points_triangle_triangle(&face, &tri).distance_squared)
                .fold(f32::INFINITY, f32::min);
            if got.distance_squared > 0.0 || surface > 1e-10 {
                apart += 1;
                assert!(
                    (got.distance_squared.sqrt() - surface.sqrt()).abs() <= 1e-5,
                    "case {k}"
                );
                let gap = got.on_first - got.on_second;
                assert!((dot(gap, gap) - got.distance_squared).abs() <= 1e-5);
            } else {
                // Meeting: the triangle touches the surface, or lies inside the box.
                let inside = [tri.a, tri.b, tri.c].iter().all(|&p| {
                    let l = obb.to_local(p);
                    l.abs().cmple(h + Vec3::splat(1e-5)).all()
                });
                assert!(surface <= 1e-10 || inside, "case {k}: {surface}");
            }
        }
        assert!(apart > 100, "{apart} apart");
    }
}
