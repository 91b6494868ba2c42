//! The box test of a packet of rays sharing one origin: four boxes at once, one test for the
//! whole packet.
//!
//! For a shared origin `o`, every ray's slab distance to a plane is `(plane − o) · inv`, the
//! same difference times its own inverse direction. Rounded multiplication is monotone in each
//! factor, so over the packet that distance is smallest at one end of the packet's interval of
//! inverse directions and largest at the other, whichever end the sign of the difference says.
//! Taking those ends gives an entry no later than any ray's own and an exit no earlier, so the
//! packet enters every box that any of its rays would enter on its own (with the same margin),
//! and its key is no larger than any of theirs. Boxes only decide what to visit, so this never
//! changes an answer.

use glam::Vec4;
use wide::f32x8;

use super::SlabRay;
use super::aabb_lanes::{Planes, near_far8, widened_verdict8};
use crate::math::{Aabb, Aabb4, Aabb8, max_f32, min_f32};

/// A packet's shared origin and interval of padded inverse directions, spread over four lanes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PacketLanes {
    origin: [Vec4; 3],
    /// Per axis, the smallest inverse direction in the packet.
    inv_lo: [Vec4; 3],
    /// Per axis, the largest inverse direction in the packet.
    inv_hi: [Vec4; 3],
    /// Per axis, whether the packet's inverse directions are negative (all of them, or none).
    negative: [bool; 3],
    /// The smallest `t_min` in the packet.
    pub(crate) t_min: f32,
}

impl PacketLanes {
    /// The packet of `rays`, or `None` when they do not share an origin (bit for bit) or a
    /// direction sign on some axis, or there are none.
    pub(crate) fn new(rays: &[SlabRay]) -> Option<Self> {
        let first = rays.first()?;
        let origin = first.origin.to_array().map(f32::to_bits);
        let negative = first.inv_dir.to_array().map(|i| i < 0.0);
        let mut lo = first.inv_dir.to_array();
        let mut hi = lo;
        let mut t_min = first.t_min;
        for ray in rays {
            let inv = ray.inv_dir.to_array();
            let same_signs = inv.map(|i| i < 0.0) == negative;
            if ray.origin.to_array().map(f32::to_bits) != origin || !same_signs {
                return None;
            }
            for axis in 0..3 {
                if let (Some(l), Some(h), Some(&i)) =
                    (lo.get_mut(axis), hi.get_mut(axis), inv.get(axis))
                {
                    *l = min_f32(*l, i);
                    *h = max_f32(*h, i);
                }
            }
            t_min = min_f32(t_min, ray.t_min);
        }
        let [ox, oy, oz] = first.origin.to_array();
        Some(Self {
            origin: [Vec4::splat(ox), Vec4::splat(oy), Vec4::splat(oz)],
            inv_lo: lo.map(Vec4::splat),
            inv_hi: hi.map(Vec4::splat),
            negative,
            t_min,
        })
    }

    /// The lanes some ray of the packet may enter within `[self.t_min, t_max]` (`t_max` the
    /// largest of the packet's, in every lane), widened by `margin` as a single ray's test
    /// is, and each lane's entry distance less that margin: no larger than any ray's own.
    /// `planes` picks each axis's planes: by index for stored boxes, among values for
    /// computed ones.
    #[inline(always)]
    pub(crate) fn enter(
        &self,
        node: &Aabb4,
        t_max: Vec4,
        margin: f32,
        planes: Planes,
    ) -> (u32, [f32; 4]) {
        let [ox, oy, oz] = self.origin;
        let [lx, ly, lz] = self.inv_lo;
        let [hx, hy, hz] = self.inv_hi;
        let [neg_x, neg_y, neg_z] = self.negative;
        let (nx, fx) = planes(node, 0, neg_x);
        let (ny, fy) = planes(node, 1, neg_y);
        let (nz, fz) = planes(node, 2, neg_z);
        // The smallest of `d · inv` over the interval (the entry), and the largest (the exit).
        let least = |d: Vec4, lo: Vec4, hi: Vec4| Vec4::select(d.cmpge(Vec4::ZERO), d * lo, d * hi);
        let most = |d: Vec4, lo: Vec4, hi: Vec4| Vec4::select(d.cmpge(Vec4::ZERO), d * hi, d * lo);
        let entry = least(nx - ox, lx, hx)
            .max(least(ny - oy, ly, hy))
            .max(least(nz - oz, lz, hz))
            .max(Vec4::splat(self.t_min));
        let exit = most(fx - ox, lx, hx)
            .min(most(fy - oy, ly, hy))
            .min(most(fz - oz, lz, hz))
            .min(t_max);
        // Widened as a single ray's test is (`LaneRay::enter`, one product for `t_min ≥ 0`);
        // unused lanes are the structure's to ignore.
        let (lo, hi) = if self.t_min >= 0.0 {
            (entry * (1.0 - margin), exit * (1.0 + margin))
        } else {
            (entry - entry.abs() * margin, exit + exit.abs() * margin)
        };
        (lo.cmple(hi).bitmask(), lo.to_array())
    }
}

impl PacketLanes {
    /// [`PacketLanes::enter`] for eight boxes, in eight-lane vectors: the same arithmetic lane
    /// for lane.
    #[inline(always)]
    pub(crate) fn enter8(&self, node: &Aabb8, t_max: f32x8, margin: f32) -> (u32, [f32; 8]) {
        let splat = |v: &[Vec4; 3]| v.map(|x| f32x8::splat(x.x));
        let [ox, oy, oz] = splat(&self.origin);
        let [lx, ly, lz] = splat(&self.inv_lo);
        let [hx, hy, hz] = splat(&self.inv_hi);
        let [neg_x, neg_y, neg_z] = self.negative;
        let (nx, fx) = near_far8(node, 0, neg_x);
        let (ny, fy) = near_far8(node, 1, neg_y);
        let (nz, fz) = near_far8(node, 2, neg_z);
        let zero = f32x8::ZERO;
        let least = |d: f32x8, lo: f32x8, hi: f32x8| d.simd_ge(zero).select(d * lo, d * hi);
        let most = |d: f32x8, lo: f32x8, hi: f32x8| d.simd_ge(zero).select(d * hi, d * lo);
        let entry = least(nx - ox, lx, hx)
            .fast_max(least(ny - oy, ly, hy))
            .fast_max(least(nz - oz, lz, hz))
            .fast_max(f32x8::splat(self.t_min));
        let exit = most(fx - ox, lx, hx)
            .fast_min(most(fy - oy, ly, hy))
            .fast_min(most(fz - oz, lz, hz))
            .fast_min(t_max);
        widened_verdict8(entry, exit, self.t_min >= 0.0, margin)
    }
}

/// Rays per [`PacketRays`]: two groups of four lanes.
pub(crate) const PACKET_RAYS: usize = 8;

/// Eight rays sharing an origin, each in a lane, for judging one box for all of them at once
/// (a leaf's, before its triangles are tested): the single-ray slab test, ray by ray, in SIMD.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PacketRays {
    origin: [f32; 3],
    /// Per axis, the rays' padded inverse directions, rays 0–3 then 4–7.
    inv: [[Vec4; 2]; 3],
    t_min: [Vec4; 2],
    t_max: [Vec4; 2],
}

impl PacketRays {
    /// The lanes of `rays` (which share the origin of the first).
    pub(crate) fn new(rays: &[SlabRay; PACKET_RAYS]) -> Self {
        let group = |f: &dyn Fn(&SlabRay) -> f32, half: usize| {
            Vec4::from_array(core::array::from_fn(|k| {
                rays.get(4 * half + k).map_or(0.0, f)
            }))
        };
        let both = |f: &dyn Fn(&SlabRay) -> f32| [group(f, 0), group(f, 1)];
        Self {
            origin: rays[0].origin.to_array(),
            inv: [
                both(&|r| r.inv_dir.x),
                both(&|r| r.inv_dir.y),
                both(&|r| r.inv_dir.z),
            ],
            t_min: both(&|r| r.t_min),
            t_max: both(&|r| r.t_max),
        }
    }

    /// Sets each ray's `t_max` (it shrinks as the ray finds hits).
    pub(crate) fn set_t_max(&mut self, t_max: [f32; PACKET_RAYS]) {
        let [a, b, c, d, e, f, g, h] = t_max;
        self.t_max = [Vec4::new(a, b, c, d), Vec4::new(e, f, g, h)];
    }

    /// Bit `i` set for each ray `i` that enters `aabb` within its `[t_min, t_max]`, widened by
    /// `margin` (relative): the one-box slab test of a single ray, eight rays at a time.
    #[inline(always)]
    pub(crate) fn entering(&self, aabb: &Aabb, margin: f32) -> u32 {
        let [ox, oy, oz] = self.origin;
        let (lo, hi) = (aabb.min, aabb.max);
        let mut mask = 0;
        for half in 0..2 {
            let slab = |min: f32, max: f32, o: f32, inv: &[Vec4; 2]| {
                let inv = inv.get(half).copied().unwrap_or(Vec4::ZERO);
                let t0 = Vec4::splat(min - o) * inv;
                let t1 = Vec4::splat(max - o) * inv;
                (t0.min(t1), t0.max(t1))
            };
            let [ix, iy, iz] = &self.inv;
            let (nx, fx) = slab(lo.x, hi.x, ox, ix);
            let (ny, fy) = slab(lo.y, hi.y, oy, iy);
            let (nz, fz) = slab(lo.z, hi.z, oz, iz);
            let t_min = self.t_min.get(half).copied().unwrap_or(Vec4::INFINITY);
            let t_max = self.t_max.get(half).copied().unwrap_or(Vec4::NEG_INFINITY);
            let entry = nx.max(ny).max(nz).max(t_min);
            let exit = fx.min(fy).min(fz).min(t_max);
            let lo = entry - entry.abs() * margin;
            let hi = exit + exit.abs() * margin;
            mask |= lo.cmple(hi).bitmask() << (4 * half);
        }
        mask
    }
}
