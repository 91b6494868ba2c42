//! The watertight ray test on four triangles at once, as a filter: which lanes the scalar test
//! could accept.
//!
//! A ray meets few of the triangles in the leaves it visits, and the scalar test's branches on
//! the edge signs mispredict. Each lane here repeats the scalar test's arithmetic in its
//! order (the same IEEE operations on the same values), so the lanes it rejects are exactly
//! those the scalar test rejects, and the lanes it accepts carry exactly the scalar test's
//! `t`, `u` and `v`. Lanes with an edge function of exactly zero, where the scalar test redoes
//! its sums in `f64`, and lanes whose products left the range of `f32`, where it rescales the
//! triangle, are left to the scalar test.

use glam::Vec4;

use super::triangle_lanes::{Lanes3, TriangleLanes};
use super::{CullMode, WatertightRay};

/// What [`WatertightRay::intersect`] answers for four triangles, as far as the lanes decide.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LaneHits {
    /// Bit `i` set: the scalar test accepts lane `i`, with exactly `t[i]`, `u[i]` and `v[i]`.
    pub(crate) sure: u32,
    /// Bit `i` set: an edge function of lane `i` is exactly zero, where the scalar test redoes
    /// its sums in `f64`, or a product left the range of `f32`, where it rescales the triangle;
    /// only the scalar test decides.
    pub(crate) unsure: u32,
    /// Ray parameter of each sure lane.
    pub(crate) t: [f32; 4],
    /// Weight of corner `b` of each sure lane.
    pub(crate) u: [f32; 4],
    /// Weight of corner `c` of each sure lane.
    pub(crate) v: [f32; 4],
}

impl WatertightRay {
    /// The scalar test's answers for the four lanes of `tris` with `cull`: those it accepts
    /// (and their hits, bit for bit) and those only it can decide.
    #[inline(always)]
    pub(crate) fn hits(&self, tris: &TriangleLanes, cull: CullMode) -> LaneHits {
        // `(a − o)` picked at axis `k` is `a[k] − o[k]`: the same subtraction, so each row is
        // picked first (by address) and only the three rows the frame uses are subtracted.
        let [okx, oky, okz] = self.origin_k.map(Vec4::splat);
        let (sx, sy, sz) = (
            Vec4::splat(self.sx),
            Vec4::splat(self.sy),
            Vec4::splat(self.sz),
        );
        let frame = |p: &Lanes3| {
            (
                *p.axis_ref(self.kx) - okx,
                *p.axis_ref(self.ky) - oky,
                *p.axis_ref(self.kz) - okz,
            )
        };
        let ((pax, pay, az), (pbx, pby, bz), (pcx, pcy, cz)) =
            (frame(&tris.a), frame(&tris.b), frame(&tris.c));
        let ax = pax - sx * az;
        let ay = pay - sy * az;
        let bx = pbx - sx * bz;
        let by = pby - sy * bz;
        let cx = pcx - sx * cz;
        let cy = pcy - sy * cz;
        let u = cx * by - cy * bx;
        let v = ax * cy - ay * cx;
        let w = bx * ay - by * ax;
        let zero = Vec4::ZERO;
        let redone_in_f64 = u.cmpeq(zero) | v.cmpeq(zero) | w.cmpeq(zero);
        let inside = match cull {
            CullMode::None => {
                let any_negative = u.cmplt(zero) | v.cmplt(zero) | w.cmplt(zero);
                let any_positive = u.cmpgt(zero) | v.cmpgt(zero) | w.cmpgt(zero);
                !(any_negative & any_positive)
            }
            // As in the scalar test: "none on the wrong side", so that a NaN (an overflow)
            // passes and reaches the determinant's check.
            CullMode::Back => !(u.cmplt(zero) | v.cmplt(zero) | w.cmplt(zero)),
            CullMode::Front => !(u.cmpgt(zero) | v.cmpgt(zero) | w.cmpgt(zero)),
        };
        let unsure = redone_in_f64.bitmask();
        if inside.bitmask() | unsure == 0 {
            // Most batches a ray visits hold no triangle it crosses: the distances and the
            // division are skipped (the scalar test would reject every lane here too).
            return LaneHits {
                sure: 0,
                unsure: 0,
                t: [0.0; 4],
                u: [0.0; 4],
                v: [0.0; 4],
            };
        }
        let det = u + v + w;
        // `det == det` is false for NaN: the scalar test's `det.is_nan()`.
        let det_usable = det.cmpne(zero) & det.cmpeq(det);
        let t_scaled = u * (sz * az) + v * (sz * bz) + w * (sz * cz);
        let inv_det = Vec4::ONE / det;
        let t = t_scaled * inv_det;
        let in_range = t.cmpge(Vec4::splat(self.t_min)) & t.cmple(Vec4::splat(self.t_max));
        // Lanes whose products left f32's range go to the scalar test, which rescales them.
        let finite = |x: Vec4| x.abs().cmplt(Vec4::INFINITY);
        let out_of_range = inside & det.cmpne(zero) & !(finite(det) & finite(t));
        let unsure = unsure | out_of_range.bitmask();
        LaneHits {
            sure: (inside & det_usable & in_range).bitmask() & !unsure,
            unsure,
            t: t.to_array(),
            u: (v * inv_det).to_array(),
            v: (w * inv_det).to_array(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::TriangleHit;
    use crate::geom::test_support::Rng;
    use crate::math::{Ray, Triangle};

    /// Every lane the scalar test accepts is sure with exactly its hit, or unsure; a sure lane
    /// is always one the scalar test accepts; and few lanes are unsure: on random rays through
    /// random small triangles, with every cull mode and ray direction. The same at 2⁴⁵ and 2⁶²
    /// times the size, where the products overflow `f32` (the rescaled lanes are unsure), and
    /// there the scalar test answers as at size 1, bit for bit: the ray's origin and the
    /// triangles scaled by a power of two leave `u` and `v` as they are and scale `t`.
    #[test]
    fn sure_lanes_are_the_scalar_hits_bit_for_bit() {
        for scale in [1.0, 2f32.powi(45), 2f32.powi(62)] {
            let mut rng = Rng(0x2545_f491_4f6c_dd1d);
            let (mut hits, mut lanes) = (0, 0);
            // Passes beyond hits, outside the rounds aimed at a shared corner.
            let mut extra_off_corner = 0;
            for round in 0..40_000 {
                let centre = rng.vec(1.0);
                let tris: [Triangle; 4] = core::array::from_fn(|i| {
                    let a = centre + rng.vec(1.0) * 0.3;
                    // A shared edge now and then: rays through it stress the zero-edge case.
                    let b = if i % 2 == 1 && round % 3 == 0 {
                        centre
                    } else {
                        a + rng.vec(1.0) * 0.3
                    };
                    Triangle::new(a, b, a + rng.vec(1.0) * 0.3)
                });
                let origin = rng.vec(1.0) * 3.0;
                let target = if round % 4 == 0 {
                    centre
                } else {
                    centre + rng.vec(1.0) * 0.2
                };
                let mut unit_ray = Ray::new(origin, target - origin);
                unit_ray.t_max = if round % 5 == 0 { 0.9 } else { f32::INFINITY };
                // The direction stays as it is: `t` grows with the scale, and its products
                // overflow.
                let mut ray = Ray::new(origin * scale, target - origin);
                ray.t_max = unit_ray.t_max * scale;
                let (unit, wt) = (WatertightRay::new(&unit_ray), WatertightRay::new(&ray));
                let cull = [CullMode::None, CullMode::Back, CullMode::Front][round % 3];
                let big = tris.map(|t| Triangle::new(t.a * scale, t.b * scale, t.c * scale));
                let lanes_say = wt.hits(&TriangleLanes::new(&big), cull);
                let mask = lanes_say.sure | lanes_say.unsure;
                let bits = |h: TriangleHit| [h.t, h.u, h.v].map(f32::to_bits);
                for (i, (t, b)) in tris.iter().zip(&big).enumerate() {
                    let scalar = wt.intersect(b.a, b.b, b.c, cull);
                    let unit_hit = unit.intersect(t.a, t.b, t.c, cull);
                    assert_eq!(
                        scalar.map(bits),
                        unit_hit.map(|h| bits(TriangleHit {
                            t: h.t * scale,
                            ..h
                        })),
                        "scale {scale}: {t:?} {unit_ray:?} {cull:?}"
                    );
                    let hit = scalar.is_some();
                    let pass = mask & (1 << i) != 0;
                    assert!(
                        pass || !hit,
                        "lane {i} rejected a hit: {b:?} {ray:?} {cull:?}"
                    );
                    if lanes_say.sure & (1 << i) != 0 {
                        let lane = TriangleHit {
                            t: lanes_say.t[i],
                            u: lanes_say.u[i],
                            v: lanes_say.v[i],
                        };
                        assert_eq!(
                            scalar.map(bits),
                            Some(bits(lane)),
                            "lane {i} is sure of another hit: {b:?} {ray:?} {cull:?}"
                        );
                    }
                    hits += usize::from(hit);
                    lanes += 1;
                    let aimed_at_corner = round % 12 == 0;
                    extra_off_corner += usize::from(pass && !hit && !aimed_at_corner);
                }
            }
            assert!(
                hits > 5_000,
                "scale {scale}: only {hits} hits in {lanes} lanes"
            );
            // Exact arithmetic: the only extra passes are edge functions of exactly zero, which
            // rays aimed at a shared corner produce on purpose and random rays almost never.
            if scale == 1.0 {
                assert!(
                    extra_off_corner <= 2,
                    "{extra_off_corner} passes without a hit"
                );
            }
        }
    }
}
