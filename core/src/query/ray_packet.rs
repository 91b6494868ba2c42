//! Ray packets: rays that share an origin (a camera's, a light's) walk a BVH together, each box
//! judged once for the whole packet ([`PacketLanes`]) and each leaf tested ray by ray.
//!
//! Every ray's answer is exactly its own query's. The packet enters every box any of its rays
//! would enter alone (its test is conservative for each of them) and revisits a deferred box
//! while any ray still might want it, so each ray's leaf tests include every triangle its own
//! walk would test; the extra triangles it tests can only be hits it would also accept if they
//! won, and a ray query's answer is the minimum under a total order, so it does not change.

use core::ops::ControlFlow;

use glam::{Vec3, Vec4};
use wide::f32x8;

use super::batch_order::query_index;
use super::leaf_batches::for_each_batch;
use super::ray::{
    Goal, Kernel, RayTester, moller_trumbore_kernel, two_step_kernel, walk, watertight,
    within_reach,
};
use super::{
    LeafTriangleIds, LeafTriangles, RayOptions, Traverse, TriangleTest, Visitor, VisitorHints,
};
use crate::geom::SlabRay;
use crate::geom::aabb_lanes::{MARGIN, near_far, near_far_values};
use crate::geom::packet_aabb_lanes::{PACKET_RAYS, PacketLanes, PacketRays};
use crate::math::{Aabb, Aabb4, Aabb8, Ray, max_f32, min_f32};

/// Rays per packet.
pub(super) const PACKET: usize = PACKET_RAYS;

/// `PACKET` rays walking one structure together.
pub(super) struct Packet<'m, S: ?Sized, K, G> {
    source: &'m S,
    pub(super) rays: [RayTester<K, G>; PACKET],
    lanes: PacketLanes,
    /// The same rays lane by lane, for their leaf boxes.
    each: PacketRays,
    /// Bit `i` set: ray `i`'s answer is final (an any-hit query that found one).
    done: u32,
    /// The largest `t_max` of the rays still looking (each shrinks as hits are found).
    t_max: f32,
    /// The same in every lane, written whole (see `LaneRay`: a splat of the scalar could be
    /// one wide load that waits for the scalar's store).
    t_max4: Vec4,
    t_max8: f32x8,
}

/// Every ray of a packet done.
const ALL: u32 = (1 << PACKET) - 1;

impl<'m, S: ?Sized, K: Kernel, G: Goal> Packet<'m, S, K, G> {
    /// The packet of `rays`, or `None` when they do not share an origin and direction signs.
    /// Recomputes [`Self::t_max`] (after a leaf, where rays find hits).
    #[inline(always)]
    fn update_t_max(&mut self) {
        let done = self.done;
        self.t_max = (0u32..)
            .zip(&self.rays)
            .filter(|(i, _)| done & (1 << i) == 0)
            .map(|(_, r)| r.slab.t_max)
            .fold(f32::NEG_INFINITY, max_f32);
        self.t_max4 = Vec4::splat(self.t_max);
        self.t_max8 = f32x8::splat(self.t_max);
        self.each
            .set_t_max(self.rays.each_ref().map(|r| r.slab.t_max));
    }
}

impl<S: LeafTriangles + ?Sized, K: Kernel, G: Goal> Visitor for Packet<'_, S, K, G> {
    /// The smallest key of the rays that enter `aabb`.
    #[inline(always)]
    fn enter(&mut self, aabb: &Aabb) -> Option<f32> {
        let done = self.done;
        (0u32..)
            .zip(&mut self.rays)
            .filter(|(i, _)| done & (1 << i) == 0)
            .filter_map(|(_, r)| r.enter(aabb))
            .reduce(min_f32)
    }

    #[inline(always)]
    fn enter_lanes(&mut self, boxes: &Aabb4) -> (u32, [f32; 4]) {
        self.lanes.enter(boxes, self.t_max4, MARGIN, near_far)
    }

    #[inline(always)]
    fn enter_computed_lanes(&mut self, boxes: &Aabb4) -> (u32, [f32; 4]) {
        self.lanes
            .enter(boxes, self.t_max4, MARGIN, near_far_values)
    }

    #[inline(always)]
    fn enter_lanes8(&mut self, boxes: &Aabb8) -> (u32, [f32; 8]) {
        self.lanes.enter8(boxes, self.t_max8, MARGIN)
    }

    /// Whether any ray still looking would revisit: the one with the largest `t_max` would.
    #[inline(always)]
    fn revisit(&self, key: f32) -> bool {
        !G::PRUNES || within_reach(key, self.t_max)
    }

    #[inline(always)]
    fn leaf(&mut self, tris: LeafTriangleIds<'_>) -> ControlFlow<()> {
        self.leaf_for(None, tris)
    }

    /// Repeats skipped, no cells read; empty lanes never entered (an empty box's near plane is
    /// infinitely far, its far plane infinitely near); the box of each leaf read.
    #[inline(always)]
    fn hints(&self) -> VisitorHints {
        VisitorHints {
            empty_lanes_never_entered: true,
            leaf_boxes: true,
            ..VisitorHints::SKIP_REPEATS
        }
    }

    /// Only the rays that enter `aabb` on their own test the leaf.
    #[inline(always)]
    fn leaf_in(&mut self, aabb: &Aabb, tris: LeafTriangleIds<'_>) -> ControlFlow<()> {
        self.leaf_for(Some(aabb), tris)
    }
}

impl<S: LeafTriangles + ?Sized, K: Kernel, G: Goal> Packet<'_, S, K, G> {
    /// Each ray still looking (and, given a box, entering it) tests the leaf.
    #[inline(always)]
    fn leaf_for(&mut self, aabb: Option<&Aabb>, tris: LeafTriangleIds<'_>) -> ControlFlow<()> {
        let entering = aabb.map_or(ALL, |b| self.each.entering(b, MARGIN));
        let mut testing = entering & !self.done & ALL;
        if testing == 0 {
            return ControlFlow::Continue(());
        }
        if K::LANES {
            // Each batch of four triangles is loaded into lanes once, for all the rays.
            let (rays, done) = (&mut self.rays, &mut self.done);
            let _ = for_each_batch(self.source, tris, |batch| {
                for (i, ray) in (0u32..).zip(rays.iter_mut()) {
                    if testing & (1 << i) != 0 && ray.offer_batch(batch).is_break() {
                        testing &= !(1 << i);
                        *done |= 1 << i;
                    }
                }
                if testing == 0 {
                    ControlFlow::Break(())
                } else {
                    ControlFlow::Continue(())
                }
            });
        } else {
            for (i, ray) in (0u32..).zip(&mut self.rays) {
                if testing & (1 << i) != 0 && ray.leaf(self.source, tris.clone()).is_break() {
                    self.done |= 1 << i;
                }
            }
        }
        self.update_t_max();
        if self.done == ALL {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }
}

/// What a batch keeps of each ray: one goal for a ray in a packet, another for a ray walked
/// alone (which may keep its answer in a form its caller reads back faster), and the answer
/// each one gives.
pub(super) trait BatchGoal {
    /// What the batch's output holds per ray.
    type Answer;
    /// The goal of each ray of a packet.
    type InPacket: Goal;
    /// The goal of a ray walked alone.
    type Alone: Goal;
    /// An empty goal for a ray of a packet.
    fn in_packet() -> Self::InPacket;
    /// An empty goal for a ray alone.
    fn alone() -> Self::Alone;
    /// The answer of a finished packet goal.
    fn of_packet(goal: &Self::InPacket) -> Self::Answer;
    /// The answer of a finished goal of a ray alone.
    fn of_alone(goal: &Self::Alone) -> Self::Answer;
}

/// Rays a sorted batch gathers before answering them, and answers it holds before scattering
/// them: four packets' worth.
const GATHER: usize = 4 * PACKET;

/// Answers `rays` in their order, `out[i]` for `rays[i]`: each run of [`PACKET`] (or, at the
/// end, fewer) valid rays that share an origin and direction signs as one packet, any other
/// ray alone. `packets` is cleared at the first packet the structure declines, which then
/// answers one ray at a time.
pub(super) fn answer_in_runs<A, S, B>(
    tree: &A,
    source: &S,
    rays: &[Ray],
    options: &RayOptions,
    out: &mut [B::Answer],
    packets: &mut bool,
) where
    A: Traverse + ?Sized,
    S: LeafTriangles + ?Sized,
    B: BatchGoal,
{
    for (group, found) in rays.chunks(PACKET).zip(out.chunks_mut(PACKET)) {
        let [first, ..] = group else {
            continue;
        };
        let together =
            *packets && group.len() >= 2 && group.iter().all(|r| r.is_valid() && alike(r, first));
        if together {
            // A short run is padded with its last ray, whose extra answers are dropped.
            let last = group.len() - 1;
            let padded: [Ray; PACKET] =
                core::array::from_fn(|k| group.get(k.min(last)).copied().unwrap_or(*first));
            *packets = walk_packet(tree, source, &padded, options, &B::in_packet, |k, g| {
                if let Some(slot) = found.get_mut(k) {
                    *slot = B::of_packet(g);
                }
            });
            if *packets {
                continue;
            }
        }
        for (ray, slot) in group.iter().zip(found.iter_mut()) {
            let g = if ray.is_valid() {
                walk(tree, source, ray, options, B::alone())
            } else {
                B::alone()
            };
            *slot = B::of_alone(&g);
        }
    }
}

/// Answers `rays` in the order of `order` (sorted keys from
/// [`ray_order`](super::ray_order::ray_order)) as [`answer_in_runs`] answers them in theirs,
/// writing each answer to `out` at its ray's index.
///
/// The rays are copied out [`GATHER`] at a time, and their answers written back as many at a
/// time: in a sorted order each ray's read is a cache miss, and a loop of nothing but those
/// reads overlaps them, where a read before each walk would wait alone.
pub(super) fn answer_in_order<A, S, B>(
    tree: &A,
    source: &S,
    rays: &[Ray],
    options: &RayOptions,
    order: &[u64],
    out: &mut [B::Answer],
) where
    A: Traverse + ?Sized,
    S: LeafTriangles + ?Sized,
    B: BatchGoal,
    B::Answer: Copy,
{
    let Some(&placeholder) = rays.first() else {
        return;
    };
    let mut gathered = [placeholder; GATHER];
    let mut answers = [B::of_alone(&B::alone()); GATHER];
    let mut packets = true;
    for block in order.chunks(GATHER) {
        for (ray, &key) in gathered.iter_mut().zip(block) {
            *ray = rays.get(query_index(key)).copied().unwrap_or(placeholder);
        }
        let (Some(gathered), Some(answers)) =
            (gathered.get(..block.len()), answers.get_mut(..block.len()))
        else {
            continue;
        };
        answer_in_runs::<_, _, B>(tree, source, gathered, options, answers, &mut packets);
        for (&answer, &key) in answers.iter().zip(block) {
            let i = query_index(key);
            if i < rays.len()
                && let Some(slot) = out.get_mut(i)
            {
                *slot = answer;
            }
        }
    }
}

/// Whether two rays may share a packet: the same origin, bit for bit, and the same direction
/// sign on every axis (the sign of the padded inverse direction, `−0` negative).
#[inline(always)]
fn alike(a: &Ray, b: &Ray) -> bool {
    let bits = |v: Vec3| v.to_array().map(f32::to_bits);
    let signs = |v: Vec3| v.to_array().map(f32::is_sign_negative);
    bits(a.origin) == bits(b.origin) && signs(a.dir) == signs(b.dir)
}

/// Walks `rays` as one packet with the kernel `options` names and hands each ray's goal to
/// `take` with its place in the packet; `false` (nothing handed) when they cannot form one or
/// the structure declines packets.
fn walk_packet<A, S, G>(
    tree: &A,
    source: &S,
    rays: &[Ray; PACKET],
    options: &RayOptions,
    goal: &impl Fn() -> G,
    take: impl FnMut(usize, &G),
) -> bool
where
    A: Traverse + ?Sized,
    S: LeafTriangles + ?Sized,
    G: Goal,
{
    match options.test {
        TriangleTest::Watertight => walk_packet_with(
            tree,
            source,
            rays,
            |r| RayTester::new(r, watertight(r, options), goal()),
            take,
        ),
        TriangleTest::MollerTrumbore => walk_packet_with(
            tree,
            source,
            rays,
            |r| RayTester::new(r, moller_trumbore_kernel(r, options), goal()),
            take,
        ),
        TriangleTest::TwoStep => walk_packet_with(
            tree,
            source,
            rays,
            |r| RayTester::new(r, two_step_kernel(r, options), goal()),
            take,
        ),
    }
}

fn walk_packet_with<'m, A, S, K, G>(
    tree: &A,
    source: &'m S,
    rays: &[Ray; PACKET],
    tester: impl FnMut(&Ray) -> RayTester<K, G>,
    mut take: impl FnMut(usize, &G),
) -> bool
where
    A: Traverse + ?Sized,
    S: LeafTriangles + ?Sized + 'm,
    K: Kernel,
    G: Goal,
{
    if !tree.walks_packets() {
        return false;
    }
    // Built here, in place: a packet is a few kilobytes, and moving it cost more than the
    // walk of a small mesh.
    let slabs: [SlabRay; PACKET] = rays.each_ref().map(SlabRay::new);
    let Some(lanes) = PacketLanes::new(&slabs) else {
        return false;
    };
    let mut packet = Packet {
        source,
        lanes,
        each: PacketRays::new(&slabs),
        rays: rays.each_ref().map(tester),
        done: 0,
        t_max: f32::NEG_INFINITY,
        t_max4: Vec4::NEG_INFINITY,
        t_max8: f32x8::splat(f32::NEG_INFINITY),
    };
    packet.update_t_max();
    tree.traverse(&mut packet);
    for (k, ray) in packet.rays.iter().enumerate() {
        take(k, &ray.goal);
    }
    true
}
