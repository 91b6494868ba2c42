//! Squared distances from one point to four triangles at once, one triangle per SIMD lane.
//!
//! A closest-point query spends most of its time in leaves, walking the Voronoi regions of
//! triangles that mostly lose. The scalar walk branches on data (which region a point falls
//! in is close to random), so it mispredicts; here every lane evaluates every region and keeps
//! the first that applies, without branches. Each lane performs exactly the operations of
//! [`closest_point_regions`](super::closest_point_regions), in the same order, so its squared
//! distance has the same bits; the query still re-derives a winner with the scalar walk.

use glam::{Vec3, Vec4};

use super::closest_point_triangle::{
    MAX_REACH_SQUARED, MAX_SQUARED, MIN_SQUARED, SLIVER, closest_point_regions,
};
use super::triangle_lanes::{Lanes3, TriangleLanes};
use crate::math::dot;

impl TriangleLanes {
    /// Per lane, the squared distance from `p` to the closest point of that lane's triangle
    /// as the scalar region walk computes it (bit for bit, for a non-degenerate triangle; a
    /// degenerate one gives whatever the walk's arithmetic gives, NaN included, and callers
    /// discard it as the scalar query does).
    #[inline(always)]
    pub(crate) fn closest_distance_squared(&self, p: Vec3) -> Vec4 {
        let (a, b, c) = (self.a, self.b, self.c);
        let p = Lanes3::splat(p);
        let zero = Vec4::ZERO;
        let ab = b.sub(a);
        let ac = c.sub(a);
        let ap = p.sub(a);
        let d1 = ab.dot(ap);
        let d2 = ac.dot(ap);
        let bp = p.sub(b);
        let d3 = ab.dot(bp);
        let d4 = ac.dot(bp);
        let cp = p.sub(c);
        let d5 = ab.dot(cp);
        let d6 = ac.dot(cp);
        let bc = c.sub(b);
        let e = d4 - d3;
        let f = d5 - d6;
        // A fair triangle's signed areas as the walk's differences of products, and its face
        // point from the barycentrics; a sliver's (the walk's `sliver_normal`) as triple
        // products and the foot of the perpendicular, worked out only when a lane holds one.
        let mut vc = d1 * d4 - d3 * d2;
        let mut vb = d5 * d2 - d1 * d6;
        let mut va = d3 * d6 - d5 * d4;
        let inv = Vec4::ONE / (va + vb + vc);
        let mut on_face = a.add_scaled(ab, vb * inv).add_scaled(ac, vc * inv);
        let plain = ab.cross(ac);
        let longest = (d1 - d3).max(d2 - d6).max(e + f);
        let reach = ap.dot(ap);
        // Lanes whose products would leave `f32` (the walk's `in_range`): the scalar walk,
        // which rescales them, answers those at the end.
        let wild = (longest.cmpgt(Vec4::splat(MAX_SQUARED))
            | (longest.cmplt(Vec4::splat(MIN_SQUARED)) & longest.cmpgt(zero))
            | reach.cmpgt(Vec4::splat(MAX_REACH_SQUARED)))
        .bitmask();
        let bound = longest * Vec4::splat(SLIVER);
        let sliver = plain.dot(plain).cmplt(bound * bound);
        if sliver.any() {
            // As the walk's `normal_across`: `ac − ab·t` is `ac + ab·(−t)`, rounded the same.
            let n = ab.cross(ac.add_scaled(ab, -(ab.dot(ac) / ab.dot(ab))));
            vc = Vec4::select(sliver, n.dot(ab.cross(ap)), vc);
            vb = Vec4::select(sliver, n.dot(ap.cross(ac)), vb);
            va = Vec4::select(sliver, n.dot(bc.cross(bp)), va);
            // `p − n·t` as the walk computes it (adding `n·(−t)` rounds the same: negation
            // is exact).
            let foot = p.add_scaled(n, -(n.dot(ap) / n.dot(n)));
            on_face = Lanes3::select(sliver, foot, on_face);
        }

        // The scalar walk's tests, in its order: the first that holds decides the region.
        let in_a = d1.cmple(zero) & d2.cmple(zero);
        let in_b = d3.cmpge(zero) & d4.cmple(d3);
        let in_ab = vc.cmple(zero) & d1.cmpge(zero) & d3.cmple(zero);
        let in_c = d6.cmpge(zero) & d5.cmple(d6);
        let in_ac = vb.cmple(zero) & d2.cmpge(zero) & d6.cmple(zero);
        let in_bc = va.cmple(zero) & e.cmpge(zero) & f.cmpge(zero);

        // One division serves the three edges: each lane takes the first edge test that holds
        // (ab, then ac, then bc), which is the edge its region is whenever it is an edge.
        let edge_ab_or_ac = in_ab | in_ac;
        let num = Vec4::select(in_ab, d1, Vec4::select(in_ac, d2, e));
        let den = Vec4::select(in_ab, d1 - d3, Vec4::select(in_ac, d2 - d6, e + f));
        let s = num / den;
        let base = Lanes3::select(edge_ab_or_ac, a, b);
        let along = Lanes3::select(in_ab, ab, Lanes3::select(in_ac, ac, bc));
        let on_edge = base.add_scaled(along, s);

        // Squared distances to each candidate, then the region's: a corner's offset is the
        // walk's `p − corner` already. Later regions first, so each earlier test overrides them,
        // as the walk's early returns do.
        let to_edge = p.sub(on_edge);
        let to_face = p.sub(on_face);
        let d = Vec4::select(in_ac | in_bc, to_edge.dot(to_edge), to_face.dot(to_face));
        let d = Vec4::select(in_c, cp.dot(cp), d);
        let d = Vec4::select(in_ab, to_edge.dot(to_edge), d);
        let d = Vec4::select(in_b, bp.dot(bp), d);
        let d = Vec4::select(in_a, reach, d);
        if wild == 0 {
            return d;
        }
        self.rescaled_lanes(wild, p, d)
    }

    /// Per lane, the squared distance from `p` to the box around that lane's triangle: never
    /// more than the distance to the triangle itself, except by rounding (callers allow a
    /// margin), so a search can pass over four triangles whose boxes all lie beyond its bound
    /// without walking their regions. NaN for a lane with a coordinate that is not a number.
    #[inline(always)]
    pub(crate) fn box_distance_squared(&self, p: Vec3) -> Vec4 {
        let gap = |a: Vec4, b: Vec4, c: Vec4, q: f32| {
            let q = Vec4::splat(q);
            (a.min(b).min(c) - q)
                .max(q - a.max(b).max(c))
                .max(Vec4::ZERO)
        };
        let ([ax, ay, az], [bx, by, bz], [cx, cy, cz]) = (self.a.rows, self.b.rows, self.c.rows);
        let (x, y, z) = (
            gap(ax, bx, cx, p.x),
            gap(ay, by, cy, p.y),
            gap(az, bz, cz, p.z),
        );
        x * x + y * y + z * z
    }

    /// `d` with each lane set in `wild` replaced by the scalar walk's squared distance.
    #[cold]
    #[inline(never)]
    fn rescaled_lanes(&self, wild: u32, p: Lanes3, d: Vec4) -> Vec4 {
        let lane = |rows: &Lanes3, i: usize| {
            let [x, y, z] = rows
                .rows
                .map(|r| r.to_array().get(i).copied().unwrap_or(0.0));
            Vec3::new(x, y, z)
        };
        let mut out = d.to_array();
        for (i, slot) in out.iter_mut().enumerate() {
            if wild & (1 << i) != 0 {
                let p = lane(&p, i);
                let (q, ..) =
                    closest_point_regions(p, lane(&self.a, i), lane(&self.b, i), lane(&self.c, i));
                let to = p - q;
                *slot = dot(to, to);
            }
        }
        Vec4::from_array(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::test_support::Rng;
    use crate::math::Triangle;

    fn scalar_distance_squared(p: Vec3, t: &Triangle) -> f32 {
        let (q, ..) = closest_point_regions(p, t.a, t.b, t.c);
        let d = p - q;
        dot(d, d)
    }

    #[test]
    fn every_lane_matches_the_scalar_walk_bit_for_bit() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let mut checked = 0;
        for round in 0..50_000 {
            // Sizes where the walk's products leave `f32` too (it rescales those lanes).
            let scale = [1e-6, 1.0, 1e6, 1e-14, 1e12][round % 5];
            let mut tris = [Triangle::new(Vec3::ZERO, Vec3::ZERO, Vec3::ZERO); 4];
            for t in &mut tris {
                let a = rng.vec(scale);
                // Slivers and near-degenerate shapes now and then, where rounding is touchiest.
                let b = if round % 7 == 0 {
                    a + rng.vec(scale * 1e-4)
                } else {
                    rng.vec(scale)
                };
                let c = if round % 11 == 0 {
                    a + (b - a) * 0.5 + rng.vec(scale * 1e-5)
                } else {
                    rng.vec(scale)
                };
                *t = Triangle::new(a, b, c);
            }
            let p = rng.vec(scale * 2.0);
            let lanes = TriangleLanes::new(&tris).closest_distance_squared(p);
            for (t, got) in tris.iter().zip(lanes.to_array()) {
                if t.is_degenerate() {
                    continue;
                }
                let want = scalar_distance_squared(p, t);
                assert_eq!(got.to_bits(), want.to_bits(), "{t:?} from {p}");
                checked += 1;
            }
        }
        assert!(checked > 190_000, "only {checked} lanes were comparable");
    }

    #[test]
    fn each_region_is_chosen_as_the_scalar_walk_chooses_it() {
        // The same triangle in every lane, probed from each Voronoi region in turn.
        let t = Triangle::new(
            Vec3::ZERO,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
        );
        let lanes = TriangleLanes::new(&[t; 4]);
        for p in [
            Vec3::new(-1.0, -1.0, 1.0),
            Vec3::new(3.0, -1.0, 0.0),
            Vec3::new(-1.0, 3.0, 0.0),
            Vec3::new(1.0, -3.0, 0.0),
            Vec3::new(2.0, 2.0, 0.0),
            Vec3::new(-3.0, 1.0, 5.0),
            Vec3::new(0.5, 0.5, -3.0),
        ] {
            let want = scalar_distance_squared(p, &t);
            assert_eq!(lanes.closest_distance_squared(p), Vec4::splat(want), "{p}");
        }
    }
}
