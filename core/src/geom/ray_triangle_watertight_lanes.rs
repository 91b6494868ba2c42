//! The watertight ray test on four triangles at once, as a filter: which lanes the scalar test
//! could accept.
//!
//! A ray meets few of the triangles in the leaves it visits, and the scalar test's branches on
//! the edge signs mispredict. Each lane here repeats the scalar test's arithmetic in its
//! order, so the lanes it rejects are exactly those the scalar test rejects; the query runs
//! the scalar test on the rest, which decides and supplies `t`, `u` and `v`. Lanes with an
//! edge function of exactly zero, where the scalar test redoes its sums in `f64`, always pass.

use glam::Vec4;

use super::triangle_lanes::{Lanes3, TriangleLanes};
use super::{CullMode, WatertightRay};

impl WatertightRay {
    /// The lanes of `tris` that [`intersect`](WatertightRay::intersect) might accept with
    /// `cull`, as a bit mask (bit `i` for lane `i`): never fewer than it accepts.
    #[inline(always)]
    pub(crate) fn may_hit(&self, tris: &TriangleLanes, cull: CullMode) -> u32 {
        let o = Lanes3::splat(self.origin);
        let (pa, pb, pc) = (tris.a.sub(o), tris.b.sub(o), tris.c.sub(o));
        let (sx, sy, sz) = (
            Vec4::splat(self.sx),
            Vec4::splat(self.sy),
            Vec4::splat(self.sz),
        );
        let (az, bz, cz) = (pa.axis(self.kz), pb.axis(self.kz), pc.axis(self.kz));
        let ax = pa.axis(self.kx) - sx * az;
        let ay = pa.axis(self.ky) - sy * az;
        let bx = pb.axis(self.kx) - sx * bz;
        let by = pb.axis(self.ky) - sy * bz;
        let cx = pc.axis(self.kx) - sx * cz;
        let cy = pc.axis(self.ky) - sy * cz;
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
            CullMode::Back => u.cmpge(zero) & v.cmpge(zero) & w.cmpge(zero),
            CullMode::Front => u.cmple(zero) & v.cmple(zero) & w.cmple(zero),
        };
        let det = u + v + w;
        // `det == det` is false for NaN: the scalar test's `det.is_nan()`.
        let det_usable = det.cmpne(zero) & det.cmpeq(det);
        let t_scaled = u * (sz * az) + v * (sz * bz) + w * (sz * cz);
        let t = t_scaled * (Vec4::ONE / det);
        let in_range = t.cmpge(Vec4::splat(self.t_min)) & t.cmple(Vec4::splat(self.t_max));
        (redone_in_f64 | (inside & det_usable & in_range)).bitmask()
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::math::{Ray, Triangle};

    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> f32 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            ((self.0 >> 40) as f32 / (1u64 << 24) as f32) * 2.0 - 1.0
        }

        fn vec(&mut self) -> Vec3 {
            Vec3::new(self.next(), self.next(), self.next())
        }
    }

    /// Every lane the scalar test accepts passes the filter, and the filter passes few others:
    /// on random rays through random small triangles, with every cull mode and ray direction.
    #[test]
    fn passes_every_scalar_hit_and_little_else() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        let (mut hits, mut lanes) = (0, 0);
        // Passes beyond hits, outside the rounds aimed at a shared corner.
        let mut extra_off_corner = 0;
        for round in 0..40_000 {
            let centre = rng.vec();
            let tris: [Triangle; 4] = core::array::from_fn(|i| {
                let a = centre + rng.vec() * 0.3;
                // A shared edge now and then: rays through it stress the zero-edge case.
                let b = if i % 2 == 1 && round % 3 == 0 {
                    centre
                } else {
                    a + rng.vec() * 0.3
                };
                Triangle::new(a, b, a + rng.vec() * 0.3)
            });
            let origin = rng.vec() * 3.0;
            let target = if round % 4 == 0 {
                centre
            } else {
                centre + rng.vec() * 0.2
            };
            let mut ray = Ray::new(origin, target - origin);
            ray.t_max = if round % 5 == 0 { 0.9 } else { f32::INFINITY };
            let wt = WatertightRay::new(&ray);
            let cull = [CullMode::None, CullMode::Back, CullMode::Front][round % 3];
            let mask = wt.may_hit(&TriangleLanes::new(&tris), cull);
            for (i, t) in tris.iter().enumerate() {
                let hit = wt.intersect(t.a, t.b, t.c, cull).is_some();
                let pass = mask & (1 << i) != 0;
                assert!(
                    pass || !hit,
                    "lane {i} rejected a hit: {t:?} {ray:?} {cull:?}"
                );
                hits += usize::from(hit);
                lanes += 1;
                let aimed_at_corner = round % 12 == 0;
                extra_off_corner += usize::from(pass && !hit && !aimed_at_corner);
            }
        }
        assert!(hits > 5_000, "only {hits} hits in {lanes} lanes");
        // Exact arithmetic: the only extra passes are edge functions of exactly zero, which
        // rays aimed at a shared corner produce on purpose and random rays almost never.
        assert!(
            extra_off_corner <= 2,
            "{extra_off_corner} passes without a hit"
        );
    }
}
