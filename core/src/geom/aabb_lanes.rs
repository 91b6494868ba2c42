//! The box tests of four boxes at once ([`Aabb4`]), one SIMD operation per coordinate.
//!
//! Like the one-box tests these only decide what a query visits, with the query's margin of
//! slack, so lane-wise rounding (or a target without SIMD) never changes an answer.

use glam::{Vec3, Vec3A, Vec4};
use wide::f32x8;

use super::SlabRay;
use crate::math::{Aabb4, Aabb8};

/// Relative slack on box distances (ray entry and exit `t`, squared point distances): a box is
/// entered when it might hold an answer within a few thousand ulps of the current best, so
/// rounding in a box test can never cull a triangle whose own rounded answer would win (ties
/// included).
pub(crate) const MARGIN: f32 = 1.0 / 65_536.0;

/// A ray's origin and padded inverse direction (from its [`SlabRay`]) spread over four lanes,
/// computed once per ray, and its interval, with the [`MARGIN`] folded in where it can be.
///
/// For `t_min ≥ 0` no entry distance is negative, and widening `[entry, exit]` by the margin
/// is scaling the entry by `1 − MARGIN` and the exit by `1 + MARGIN`. Scaling by a positive
/// constant commutes with `max` and `min`, so it moves into the terms: each near plane's
/// distance is taken with the inverse direction scaled by `1 − MARGIN`, each far plane's with
/// it scaled by `1 + MARGIN`, and the interval's ends are stored scaled. The same real
/// numbers as scaling the entry and exit, rounded differently by an ulp or two, far inside the
/// margin; one product fewer on each node's path to its verdict. For a negative `t_min` the
/// ends are widened after, as `x ∓ |x|·MARGIN`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LaneRay {
    origin: [Vec4; 3],
    /// The inverse direction for near planes: times `1 − MARGIN` when `t_min ≥ 0`.
    inv_near: [Vec4; 3],
    /// The inverse direction for far planes: times `1 + MARGIN` when `t_min ≥ 0` (kept finite).
    inv_far: [Vec4; 3],
    /// `t_min` and `t_max` in every lane, scaled as the inverse directions are. Kept here as
    /// whole vectors, written whole when a hit shrinks `t_max`: a splat of the scalar read next
    /// to other fields is compiled to one wide load, which waits for a just-stored scalar
    /// instead of forwarding it.
    t_min: Vec4,
    t_max: Vec4,
    /// Whether `t_min ≥ 0` (the margin is folded in).
    from_zero: bool,
    /// Per axis, whether the inverse direction is negative (the near plane is `max`).
    negative: [bool; 3],
}

/// The factors [`LaneRay`] scales near and far distances by: `(1 − MARGIN, 1 + MARGIN)` when
/// the margin is folded in (`from_zero`), else `(1, 1)`.
#[inline(always)]
fn fold_factors(from_zero: bool) -> (f32, f32) {
    if from_zero {
        (1.0 - MARGIN, 1.0 + MARGIN)
    } else {
        (1.0, 1.0)
    }
}

impl LaneRay {
    #[inline(always)]
    pub(crate) fn new(ray: &SlabRay) -> Self {
        let (o, inv) = (ray.origin, ray.inv_dir);
        let from_zero = ray.t_min >= 0.0;
        let (near, far) = fold_factors(from_zero);
        // The padded inverse is at most `f32::MAX` in size: scaled up it stays finite, so a
        // far plane through the origin still gives `0`, never `0 · ∞`.
        let far_inv = (inv * far)
            .max(Vec3A::splat(-f32::MAX))
            .min(Vec3A::splat(f32::MAX));
        let near_inv = inv * near;
        Self {
            origin: [Vec4::splat(o.x), Vec4::splat(o.y), Vec4::splat(o.z)],
            inv_near: [
                Vec4::splat(near_inv.x),
                Vec4::splat(near_inv.y),
                Vec4::splat(near_inv.z),
            ],
            inv_far: [
                Vec4::splat(far_inv.x),
                Vec4::splat(far_inv.y),
                Vec4::splat(far_inv.z),
            ],
            t_min: Vec4::splat(ray.t_min * near),
            t_max: Vec4::splat(ray.t_max * far),
            from_zero,
            negative: [inv.x < 0.0, inv.y < 0.0, inv.z < 0.0],
        }
    }

    /// Lowers the interval's end to `t_max` (a hit was found).
    #[inline(always)]
    pub(crate) fn set_t_max(&mut self, t_max: f32) {
        self.t_max = Vec4::splat(t_max * fold_factors(self.from_zero).1);
    }

    /// The lanes this ray enters within its interval, widened by [`MARGIN`] (relative), and
    /// each lane's entry distance less that margin.
    ///
    /// Each axis reads its near plane first (`min` for a positive inverse direction), which
    /// gives the same interval as ordering the two slab distances, and sends an unused lane's
    /// empty box to an empty interval. `planes` picks them: [`near_far`] for boxes read where
    /// they are stored, [`near_far_values`] for boxes just computed.
    #[inline(always)]
    pub(crate) fn enter(&self, node: &Aabb4, planes: Planes) -> (u32, [f32; 4]) {
        let [neg_x, neg_y, neg_z] = self.negative;
        let planes = [
            planes(node, 0, neg_x),
            planes(node, 1, neg_y),
            planes(node, 2, neg_z),
        ];
        self.verdict(planes)
    }

    /// The verdict and keys from each axis's (near, far) planes.
    #[inline(always)]
    fn verdict(&self, [(nx, fx), (ny, fy), (nz, fz)]: [(Vec4, Vec4); 3]) -> (u32, [f32; 4]) {
        let [ox, oy, oz] = self.origin;
        let [ix, iy, iz] = self.inv_near;
        let [jx, jy, jz] = self.inv_far;
        let entry = ((nx - ox) * ix)
            .max((ny - oy) * iy)
            .max((nz - oz) * iz)
            .max(self.t_min);
        let exit = ((fx - ox) * jx)
            .min((fy - oy) * jy)
            .min((fz - oz) * jz)
            .min(self.t_max);
        let (lo, hi) = if self.from_zero {
            (entry, exit)
        } else {
            (entry - entry.abs() * MARGIN, exit + exit.abs() * MARGIN)
        };
        // Unused lanes need no mask here: their empty boxes give an empty interval (or NaN),
        // and the structure ignores their verdict anyway.
        (lo.cmple(hi).bitmask(), lo.to_array())
    }
}

/// Picks axis `axis`'s (near, far) planes of four boxes for a ray whose inverse direction on
/// that axis is `negative` or not.
pub(crate) type Planes = fn(&Aabb4, usize, bool) -> (Vec4, Vec4);

/// The indices ([`Aabb4::plane`], [`Aabb8::plane`]) of axis `axis`'s near and far planes for
/// a ray whose inverse direction on that axis is `negative` or not: the near plane is the
/// smaller coordinate for a positive direction.
#[inline(always)]
pub(crate) fn plane_indices(axis: usize, negative: bool) -> (usize, usize) {
    if negative {
        (axis + 3, axis)
    } else {
        (axis, axis + 3)
    }
}

/// [`Planes`] for boxes read where they are stored: each plane picked by its index. A ray's
/// indices are the same at every node, so the compiler keeps each as an offset for the whole
/// walk and loads the plane directly (a pick among loaded values branched on the sign at
/// every node, and a random ray's signs mispredict; a pick between addresses cost selects).
#[inline(always)]
pub(crate) fn near_far(node: &Aabb4, axis: usize, negative: bool) -> (Vec4, Vec4) {
    let (near, far) = plane_indices(axis, negative);
    (
        Vec4::from_array(*node.plane(near)),
        Vec4::from_array(*node.plane(far)),
    )
}

/// [`Planes`] for boxes just computed (in registers): picked among the values, as picking by
/// index would first store them.
#[inline(always)]
pub(crate) fn near_far_values(node: &Aabb4, axis: usize, negative: bool) -> (Vec4, Vec4) {
    let min = Vec4::from_array(*node.plane(axis));
    let max = Vec4::from_array(*node.plane(axis + 3));
    if negative { (max, min) } else { (min, max) }
}

/// [`near_far`] for eight boxes.
#[inline(always)]
pub(crate) fn near_far8(node: &Aabb8, axis: usize, negative: bool) -> (f32x8, f32x8) {
    let (near, far) = plane_indices(axis, negative);
    (f32x8::new(*node.plane(near)), f32x8::new(*node.plane(far)))
}

/// The lanes whose box lies within squared distance `limit` of `point`, after shrinking each
/// squared distance by `margin` (relative), and those shrunk squared distances.
#[inline(always)]
pub(crate) fn enter_point(node: &Aabb4, point: Vec3, limit: f32, margin: f32) -> (u32, [f32; 4]) {
    let axis = |p: f32, min: [f32; 4], max: [f32; 4]| {
        let p = Vec4::splat(p);
        let d = (Vec4::from_array(min) - p)
            .max(p - Vec4::from_array(max))
            .max(Vec4::ZERO);
        d * d
    };
    let d2 = axis(point.x, node.min_x, node.max_x)
        + axis(point.y, node.min_y, node.max_y)
        + axis(point.z, node.min_z, node.max_z);
    // A product, not `d2 − d2·margin`: an overflowed (infinite) distance stays comparable.
    let lo = d2 * (1.0 - margin);
    (
        lo.cmple(Vec4::splat(limit)).bitmask() & node.used_mask(),
        lo.to_array(),
    )
}

/// A ray's origin, padded inverse direction and interval spread over eight lanes
/// ([`LaneRay`] for eight boxes). Made from the ray's [`LaneRay`] for each node
/// ([`LaneRay8::from_lanes`]) rather than kept beside it: on a target without 256-bit
/// vectors an eight-lane vector is two four-lane ones, so the copy is free there, and a
/// second stored copy of the ray cost every four-wide walk its stores.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LaneRay8 {
    origin: [f32x8; 3],
    inv_near: [f32x8; 3],
    inv_far: [f32x8; 3],
    t_min: f32x8,
    t_max: f32x8,
    /// Whether `t_min ≥ 0`.
    from_zero: bool,
    /// Per axis, whether the inverse direction is negative (the near plane is `max`).
    negative: [bool; 3],
}

impl LaneRay8 {
    /// The same ray's eight lanes from its four: each vector twice over.
    #[inline(always)]
    pub(crate) fn from_lanes(four: &LaneRay) -> Self {
        let twice = |v: Vec4| {
            let a = v.to_array();
            f32x8::new([a[0], a[1], a[2], a[3], a[0], a[1], a[2], a[3]])
        };
        Self {
            origin: four.origin.map(twice),
            inv_near: four.inv_near.map(twice),
            inv_far: four.inv_far.map(twice),
            t_min: twice(four.t_min),
            t_max: twice(four.t_max),
            from_zero: four.from_zero,
            negative: four.negative,
        }
    }

    /// [`LaneRay::enter`] for eight boxes: the lanes this ray enters within its interval,
    /// widened by [`MARGIN`] (relative), and each lane's entry distance less that margin. The
    /// same arithmetic lane for lane, in eight-lane vectors (one AVX instruction where the
    /// target has it, two four-lane ones elsewhere).
    #[inline(always)]
    pub(crate) fn enter(&self, node: &Aabb8) -> (u32, [f32; 8]) {
        let [ox, oy, oz] = self.origin;
        let [ix, iy, iz] = self.inv_near;
        let [jx, jy, jz] = self.inv_far;
        let [neg_x, neg_y, neg_z] = self.negative;
        let (nx, fx) = near_far8(node, 0, neg_x);
        let (ny, fy) = near_far8(node, 1, neg_y);
        let (nz, fz) = near_far8(node, 2, neg_z);
        let entry = ((nx - ox) * ix)
            .fast_max((ny - oy) * iy)
            .fast_max((nz - oz) * iz)
            .fast_max(self.t_min);
        let exit = ((fx - ox) * jx)
            .fast_min((fy - oy) * jy)
            .fast_min((fz - oz) * jz)
            .fast_min(self.t_max);
        let (lo, hi) = if self.from_zero {
            (entry, exit)
        } else {
            let m = f32x8::splat(MARGIN);
            (entry - entry.abs() * m, exit + exit.abs() * m)
        };
        (lo.simd_le(hi).to_bitmask(), lo.to_array())
    }
}

/// The lanes whose interval `[entry, exit]`, widened by `margin` (relative), is not empty, and
/// each lane's widened entry: the end of every eight-lane ray test. As in `LaneRay::enter`, one
/// product widens when `from_zero` (`t_min ≥ 0`: no entry is negative then).
#[inline(always)]
pub(crate) fn widened_verdict8(
    entry: f32x8,
    exit: f32x8,
    from_zero: bool,
    margin: f32,
) -> (u32, [f32; 8]) {
    let (lo, hi) = if from_zero {
        (
            entry * f32x8::splat(1.0 - margin),
            exit * f32x8::splat(1.0 + margin),
        )
    } else {
        (
            entry - entry.abs() * f32x8::splat(margin),
            exit + exit.abs() * f32x8::splat(margin),
        )
    };
    (lo.simd_le(hi).to_bitmask(), lo.to_array())
}

/// [`enter_point`] for eight boxes: the lanes within squared distance `limit` of `point`
/// after shrinking each squared distance by `margin` (relative), and those distances.
#[inline(always)]
pub(crate) fn enter_point8(node: &Aabb8, point: Vec3, limit: f32, margin: f32) -> (u32, [f32; 8]) {
    let axis = |p: f32, min: &[f32; 8], max: &[f32; 8]| {
        let p = f32x8::splat(p);
        let d = (f32x8::new(*min) - p)
            .fast_max(p - f32x8::new(*max))
            .fast_max(f32x8::ZERO);
        d * d
    };
    let d2 = axis(point.x, &node.min_x, &node.max_x)
        + axis(point.y, &node.min_y, &node.max_y)
        + axis(point.z, &node.min_z, &node.max_z);
    let lo = d2 * f32x8::splat(1.0 - margin);
    (
        lo.simd_le(f32x8::splat(limit)).to_bitmask() & node.used_mask(),
        lo.to_array(),
    )
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::math::{Aabb, Ray};

    /// Numbers in `[-1, 1)` from an xorshift generator seeded with `state` (non-zero).
    fn uniform(mut state: u64) -> impl FnMut() -> f32 {
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            ((state >> 40) as f32 / (1u64 << 24) as f32) * 2.0 - 1.0
        }
    }

    /// An unused lane (an empty box, `min = +∞`, `max = −∞`) is never entered by the ray
    /// lane tests, one ray or a packet, four lanes or eight, whatever the ray: directions
    /// with zero components (the padded inverse), negative `t_min`, shrunk `t_max`. The ray
    /// visitors rely on it (`VisitorHints::empty_lanes_never_entered`), so structures keep such lanes in the
    /// mask.
    #[test]
    fn empty_lanes_are_never_entered() {
        let mut next = uniform(0x2545_f491_4f6c_dd1d);
        let mut used_entered = 0;
        for round in 0..20_000 {
            let origin = Vec3::new(next(), next(), next()) * 3.0;
            // Most rays aim at the used boxes' region, so that used lanes are entered.
            let mut dir = Vec3::new(next(), next(), next()) * 0.5 - origin;
            // Zero, negative-zero and tiny components: the padded inverse directions.
            match round % 7 {
                0 => dir.x = 0.0,
                1 => dir.y = -0.0,
                2 => dir = Vec3::new(0.0, 0.0, dir.z.signum()),
                3 => dir.z = 1e-39,
                _ => {}
            }
            let mut ray = Ray::new(origin, dir);
            ray.t_min = if round % 4 == 0 { -2.0 } else { 0.0 };
            let mut boxes = Aabb4::EMPTY;
            for lane in 0..2 {
                let (a, b) = (
                    Vec3::new(next(), next(), next()),
                    Vec3::new(next(), next(), next()),
                );
                boxes.set_lane(lane, &Aabb::new(a.min(b), a.max(b)));
            }
            let mut lanes = LaneRay::new(&SlabRay::new(&ray));
            if round % 3 == 0 {
                lanes.set_t_max(next().abs() * 4.0);
            }
            for planes in [near_far as Planes, near_far_values] {
                let (mask, _) = lanes.enter(&boxes, planes);
                assert_eq!(mask & 0b1100, 0, "round {round}: {mask:04b}");
                used_entered += (mask & 0b11).count_ones();
            }
            let mut boxes8 = Aabb8::EMPTY;
            for lane in 0..2 {
                boxes8.set_lane(lane, &boxes.lane(lane));
            }
            let (mask8, _) = LaneRay8::from_lanes(&lanes).enter(&boxes8);
            assert_eq!(mask8 & 0xFC, 0, "round {round}: {mask8:08b}");
            // A packet of rays from the same origin, with directions of the same signs.
            let slabs: [SlabRay; crate::geom::packet_aabb_lanes::PACKET_RAYS] =
                core::array::from_fn(|k| {
                    let mut r = ray;
                    r.dir *= 1.0 + k as f32 * 0.125;
                    SlabRay::new(&r)
                });
            if let Some(packet) = crate::geom::packet_aabb_lanes::PacketLanes::new(&slabs) {
                let t_max = Vec4::splat(ray.t_max);
                let (mask, _) = packet.enter(&boxes, t_max, MARGIN, near_far);
                assert_eq!(mask & 0b1100, 0, "round {round}: packet {mask:04b}");
                let (mask8, _) = packet.enter8(&boxes8, f32x8::splat(ray.t_max), MARGIN);
                assert_eq!(mask8 & 0xFC, 0, "round {round}: packet {mask8:08b}");
            }
        }
        // Not vacuous: the used lanes are entered often.
        assert!(used_entered > 10_000, "{used_entered} used lanes entered");
    }

    /// The lane tests never cull a box the ray meets within its interval, and never key it
    /// beyond its true entry: against each box's interval computed exactly (in `f64`, where
    /// the slab arithmetic of `f32` inputs loses far less than the margin), for random rays
    /// and boxes, thin and grazed boxes among them, `t_min` zero or negative, `t_max` cut
    /// short or not, four lanes and eight.
    #[test]
    fn the_margin_never_culls_a_box_the_ray_meets() {
        let mut next = uniform(0x5851_f42d_4c95_7f2d);
        let mut met = 0;
        let mut v = move || {
            let (x, y, z) = (next(), next(), next());
            (Vec3::new(x, y, z), next())
        };
        for round in 0..20_000 {
            let (origin, scalar) = v();
            let origin = origin * 2.0;
            // Aimed at the boxes' region, so that most rays meet some of them.
            let (target, _) = v();
            let dir = target * 0.5 - origin;
            if dir.abs().min_element() < 1e-3 {
                continue;
            }
            let mut ray = Ray::new(origin, dir);
            ray.t_min = if round % 4 == 0 { -0.5 } else { 0.0 };
            if round % 3 == 0 {
                ray.t_max = scalar.abs() * 3.0 + 0.01;
            }
            let mut boxes = Aabb4::EMPTY;
            let mut boxes8 = Aabb8::EMPTY;
            for lane in 0..4 {
                let ((a, along), (b, _)) = (v(), v());
                let (mut lo, mut hi) = (a.min(b), a.max(b));
                // Thin boxes, and boxes whose face the ray grazes at a chosen distance.
                if lane == 1 {
                    hi.y = lo.y;
                }
                if lane == 2 {
                    let p = ray.at(along.abs() * 2.0);
                    lo = lo.min(p);
                    hi.x = p.x;
                }
                boxes.set_lane(lane, &Aabb::new(lo, hi));
                boxes8.set_lane(lane, &Aabb::new(lo, hi));
                boxes8.set_lane(lane + 4, &Aabb::new(lo, hi));
            }
            let lanes = LaneRay::new(&SlabRay::new(&ray));
            let (mask, keys) = lanes.enter(&boxes, near_far);
            let (mask8, keys8) = LaneRay8::from_lanes(&lanes).enter(&boxes8);
            for lane in 0..4 {
                let b = boxes.lane(lane);
                let (mut entry, mut exit) = (f64::from(ray.t_min), f64::from(ray.t_max));
                for axis in 0..3 {
                    let o = f64::from(ray.origin[axis]);
                    let d = f64::from(ray.dir[axis]);
                    let t0 = (f64::from(b.min[axis]) - o) / d;
                    let t1 = (f64::from(b.max[axis]) - o) / d;
                    entry = entry.max(t0.min(t1));
                    exit = exit.min(t0.max(t1));
                }
                if entry <= exit {
                    met += 1;
                    for (m, k, l) in [(mask, keys[lane], lane), (mask8, keys8[lane], lane)]
                        .into_iter()
                        .chain([(mask8, keys8[lane + 4], lane + 4)])
                    {
                        assert!(m & (1 << l) != 0, "round {round} lane {l}: culled");
                        assert!(
                            f64::from(k) <= entry,
                            "round {round} lane {l}: key {k} beyond entry {entry}"
                        );
                    }
                }
            }
        }
        // Not vacuous: many boxes are met.
        assert!(met > 10_000, "{met} boxes met");
    }

    /// Both plane pickers give the same verdict and keys, bit for bit, and a box around the
    /// ray's start is always entered: random rays of every direction sign against random
    /// boxes, with an empty lane, for `t_min` zero and negative.
    #[test]
    fn planes_picked_by_index_or_by_value_agree() {
        let mut next = uniform(0x9e37_79b9_7f4a_7c15);
        let mut entered = 0;
        for round in 0..20_000 {
            let mut v = || Vec3::new(next(), next(), next());
            let origin = v();
            let mut ray = Ray::new(origin, v());
            ray.t_min = if round % 4 == 0 { -0.5 } else { 0.0 };
            let lanes = LaneRay::new(&SlabRay::new(&ray));
            let mut boxes = Aabb4::EMPTY;
            for lane in 0..3 {
                let (a, b) = (v() * 2.0, v() * 2.0);
                boxes.set_lane(lane, &Aabb::new(a.min(b), a.max(b)));
            }
            if round % 3 == 0 {
                boxes.set_lane(1, &Aabb::new(origin - 0.01, origin + 0.01));
            }
            let by_index = lanes.enter(&boxes, near_far);
            let by_value = lanes.enter(&boxes, near_far_values);
            assert_eq!(by_index.0, by_value.0, "round {round}");
            assert_eq!(
                by_index.1.map(f32::to_bits),
                by_value.1.map(f32::to_bits),
                "round {round}"
            );
            if round % 3 == 0 {
                assert!(
                    by_index.0 & 2 != 0,
                    "round {round}: the box around the start"
                );
            }
            entered += (by_index.0 & 0b101).count_ones();
        }
        // Not a vacuous agreement: many random boxes are entered, many are not.
        assert!(
            (5_000..35_000).contains(&entered),
            "{entered} lanes entered"
        );
    }
}
