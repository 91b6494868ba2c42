//! How far apart two meshes are: the closest pair of points, by a best-first walk down both
//! BVHs that drops every pair of nodes farther apart than the best pair found so far.

use core::ops::ControlFlow;

use glam::Vec3;

use super::budget::Tally;
use super::tree_pairs::{LeafPairVisitor, walk_leaf_pairs};
use super::{Affine, Found, PairBudget};
use crate::bvh::{BvhNode, TreeArrays};
use crate::error::PairBudgetSpent;
use crate::geom::closest_points_triangle_triangle;
use crate::math::{Aabb, Triangle, cross, dot, unit_scale};
use crate::query::{LeafTriangles, With};

/// The closest pair of points of two meshes, as [`mesh_distance`] finds it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshDistance {
    /// The point of the first mesh, in its frame.
    pub on_a: Vec3,
    /// The point of the second mesh, placed in the first mesh's frame (equal to `on_a` when
    /// the meshes meet there).
    pub on_b: Vec3,
    /// `|on_a − on_b|`, in the first mesh's units: exactly 0 when the meshes meet.
    pub distance: f32,
    /// The first mesh's triangle holding `on_a`.
    pub triangle_a: u32,
    /// The second mesh's triangle holding `on_b`.
    pub triangle_b: u32,
}

/// How far [`mesh_distance`] looks, and when it may stop early.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DistanceLimits {
    /// Pairs of points farther apart than this are not reported: when every pair is, the
    /// answer is `None`. Most of the walk is pruned by it, so a small bound answers "are
    /// these within `d`" fast. `f32::INFINITY` (the default) reports the closest pair
    /// however far. NaN or a negative bound finds nothing.
    pub max_distance: f32,
    /// The walk stops at the first pair found at this distance or closer, which is then the
    /// answer though a closer pair may exist (three-mesh-bvh's `minThreshold`). `0.0` (the
    /// default) stops only at a pair that meets, which no pair can beat.
    pub stop_at: f32,
}

impl Default for DistanceLimits {
    fn default() -> Self {
        Self {
            max_distance: f32::INFINITY,
            stop_at: 0.0,
        }
    }
}

/// The closest pair of points of meshes `a` and `b`, with `b` placed in `a`'s frame by
/// `b_to_a` (`None`: as it is), within `limits.max_distance`; `None` when no pair is that
/// close (or either mesh is empty).
///
/// Pairs of triangles are measured by
/// [`closest_points_triangle_triangle`](crate::geom::closest_points_triangle_triangle), so
/// meshes that meet (touching counts) are at distance exactly 0, and the walk stops there.
/// Apart, the distance found is the smallest over all pairs to within a factor `1 + 2⁻¹⁷`
/// (about 8·10⁻⁶): the walk skips pairs of boxes that could beat the best pair by less, so
/// that many equally close triangles (copies of one triangle) are not walked one by one.
/// Distances are in `a`'s frame, so a scaling `b_to_a` is accounted for. Ties between pairs
/// at the same distance go to the first pair the walk measures; the walk's order is fixed, so
/// the answer is the same on every target. Degenerate triangles count as the segments or
/// points they are; triangles with NaN corners are never the answer.
///
/// `a` and `b` are BVHs with their triangles (`bvh.with(&mesh)`, a blob's tree and mesh, or a
/// tree with [`PackedTriangles`](crate::query::PackedTriangles)). The walk is best first:
/// of the two children of a split node, the nearer is walked first, and a pair of nodes
/// whose boxes are farther apart than the best pair so far is dropped. No allocation: a
/// fixed stack of about 5 KiB.
///
/// # Errors
/// [`PairBudgetSpent`] when the leaves the walk could not rule out held more triangle pairs
/// than `budget` allows (see [`PairBudget`]; [`PairBudget::for_triangles`] is the usual
/// choice).
pub fn mesh_distance<A, SA, B, SB>(
    a: With<'_, A, SA>,
    b: With<'_, B, SB>,
    b_to_a: Option<&Affine>,
    limits: DistanceLimits,
    budget: PairBudget,
) -> Result<Option<MeshDistance>, PairBudgetSpent>
where
    A: TreeArrays + ?Sized,
    SA: LeafTriangles + ?Sized,
    B: TreeArrays + ?Sized,
    SB: LeafTriangles + ?Sized,
{
    if !(limits.max_distance >= 0.0) {
        return Ok(None);
    }
    let (tree_a, tree_b) = (a.structure(), b.structure());
    let (Some(root_a), Some(root_b)) = (tree_a.node(0), tree_b.node(0)) else {
        return Ok(None);
    };
    let placed_b = b_to_a.map_or(root_b.aabb(), |m| m.apply_box(&root_b.aabb()));
    let scale = scale_for(&root_a.aabb().union(placed_b));
    let squared = |d: f32| {
        let s = d * scale;
        // Capped: a bound that overflowed would let every pair tie at infinity.
        if s.is_nan() {
            0.0
        } else {
            (s * s).min(f32::MAX)
        }
    };
    let mut walk = Nearest {
        a,
        b,
        b_to_a,
        scale,
        limit: squared(limits.max_distance),
        stop: squared(limits.stop_at.max(0.0)),
        best: None,
        tally: Tally::new(budget),
        tested: 0,
    };
    let _ = walk_leaf_pairs(tree_a, tree_b, b_to_a, &mut walk);
    let found = Found {
        total: usize::from(walk.best.is_some()),
        written: 0,
        tested: walk.tested,
    };
    // Stopping early at `stop` is an answer, not a spent budget: the tally is only marked
    // when it refused a pair of leaves.
    let _ = walk.tally.finish(found)?;
    let up = 1.0 / scale;
    Ok(walk.best.map(|best| MeshDistance {
        on_a: best.on_a * up,
        on_b: best.on_b * up,
        distance: libm::sqrtf(best.distance) * up,
        triangle_a: best.triangle_a,
        triangle_b: best.triangle_b,
    }))
}

/// What the walk multiplies coordinates by: the power of two that brings the two meshes'
/// reach (largest coordinate magnitude) into `[1, 2)`. The closest-point arithmetic multiplies
/// up to four lengths together, which overflows `f32` for triangles beyond about 10⁹ and
/// underflows for tiny ones; at unit size it does neither. A power of two keeps the order and
/// ties of the distances, and is undone exactly.
fn scale_for(bounds: &Aabb) -> f32 {
    unit_scale(bounds.min.abs().max(bounds.max.abs()).max_element())
}

/// The squared gap between the plane of `t` and the nearest corner of `other` when all of
/// `other` lies on one side (0 when it touches or crosses the plane): a lower bound of the
/// distance between the triangles, cheaper than measuring it, and tight for the facing,
/// nearly parallel triangles that boxes cannot tell apart. 0 for a degenerate `t`.
#[inline(always)]
fn plane_gap_squared(t: &Triangle, other: &Triangle) -> f32 {
    // The normal is brought to unit length through its largest component first, so neither
    // its square nor the gap's overflows on large or far triangles.
    let n = cross(t.b - t.a, t.c - t.a);
    let largest = n.abs().max_element();
    if !(largest > 0.0) || !largest.is_finite() {
        return 0.0;
    }
    let n = n / largest;
    let n = n / libm::sqrtf(dot(n, n));
    let h = dot(n, t.a);
    let [x, y, z] = [other.a, other.b, other.c].map(|p| dot(n, p) - h);
    let (lo, hi) = (x.min(y).min(z), x.max(y).max(z));
    let gap = if lo > 0.0 {
        lo
    } else if hi < 0.0 {
        -hi
    } else {
        0.0
    };
    gap * gap
}

/// How much closer (relatively, in squared distance) a pair of nodes must be able to come
/// than the best pair so far to be walked: 2⁻¹⁶, so the distance found is at most a factor
/// `1 + 2⁻¹⁷` (about 8·10⁻⁶) above the smallest.
const CLOSER_BY: f32 = 1.0 / 65_536.0;

/// The best-first walk's state; distances are squared and scaled.
struct Nearest<'w, A: ?Sized, SA: ?Sized, B: ?Sized, SB: ?Sized> {
    a: With<'w, A, SA>,
    b: With<'w, B, SB>,
    b_to_a: Option<&'w Affine>,
    scale: f32,
    /// `max_distance²`: the bound until a pair is found.
    limit: f32,
    /// `stop_at²`: a pair this close ends the walk.
    stop: f32,
    /// The best pair, its `distance` field holding the squared scaled distance until the end.
    best: Option<MeshDistance>,
    tally: Tally,
    tested: usize,
}

impl<A: ?Sized, SA: ?Sized, B: ?Sized, SB: ?Sized> Nearest<'_, A, SA, B, SB> {
    /// Whether a pair of triangles at squared distance `d` beats what was found: within the
    /// limit before the first pair, strictly closer than the best after it (ties go to the
    /// pair found first).
    #[inline(always)]
    fn wanted(&self, d: f32) -> bool {
        match &self.best {
            None => d <= self.limit,
            Some(best) => d < best.distance,
        }
    }

    /// Whether boxes at squared distance `d` could hold a pair that beats what was found by
    /// more than [`CLOSER_BY`]: boxes are padded against rounding, so pairs at the best
    /// distance sit in boxes a hair closer, and without the margin a mesh of many equally
    /// close triangles (copies of one triangle) would be walked pair by pair.
    #[inline(always)]
    fn boxes_wanted(&self, d: f32) -> bool {
        match &self.best {
            None => d <= self.limit,
            Some(best) => d < best.distance * (1.0 - CLOSER_BY),
        }
    }

    fn scaled_box(&self, b: &Aabb) -> Aabb {
        Aabb::new(b.min * self.scale, b.max * self.scale)
    }

    fn scaled(&self, t: &Triangle) -> Triangle {
        Triangle::new(t.a * self.scale, t.b * self.scale, t.c * self.scale)
    }
}

impl<A, SA, B, SB> LeafPairVisitor for Nearest<'_, A, SA, B, SB>
where
    A: TreeArrays + ?Sized,
    SA: LeafTriangles + ?Sized,
    B: TreeArrays + ?Sized,
    SB: LeafTriangles + ?Sized,
{
    #[inline]
    fn nodes(&mut self, a: &Aabb, b: &Aabb) -> Option<f32> {
        let d = self
            .scaled_box(a)
            .distance_squared_to_aabb(&self.scaled_box(b));
        self.boxes_wanted(d).then_some(d)
    }

    #[inline]
    fn still_wanted(&mut self, score: f32) -> bool {
        self.boxes_wanted(score)
    }

    fn leaves(&mut self, leaf_a: BvhNode, leaf_b: BvhNode) -> ControlFlow<()> {
        let Some((ids_a, ids_b)) =
            self.tally
                .take_leaves(self.a.structure(), self.b.structure(), &leaf_a, &leaf_b)?
        else {
            return ControlFlow::Continue(());
        };
        let box_a = self.scaled_box(&leaf_a.aabb());
        for (slot_b, id_b) in ids_b {
            let Some(tb) = self.b.triangles().corners(slot_b, id_b) else {
                continue;
            };
            let tb = self.scaled(&self.b_to_a.map_or(tb, |m| m.apply_triangle(&tb)));
            let bounds_b = tb.bounds();
            // A triangle of `b` whose box is already too far from the leaf's box cannot win.
            if !self.boxes_wanted(box_a.distance_squared_to_aabb(&bounds_b)) {
                continue;
            }
            for (slot_a, id_a) in ids_a.clone() {
                let Some(ta) = self.a.triangles().corners(slot_a, id_a) else {
                    continue;
                };
                let ta = self.scaled(&ta);
                if !self.boxes_wanted(ta.bounds().distance_squared_to_aabb(&bounds_b))
                    || !self.boxes_wanted(plane_gap_squared(&ta, &tb))
                    || !self.boxes_wanted(plane_gap_squared(&tb, &ta))
                {
                    continue;
                }
                self.tested += 1;
                let c = closest_points_triangle_triangle(&ta, &tb);
                if self.wanted(c.distance_squared) {
                    self.best = Some(MeshDistance {
                        on_a: c.on_first,
                        on_b: c.on_second,
                        distance: c.distance_squared,
                        triangle_a: id_a,
                        triangle_b: id_b,
                    });
                    if c.distance_squared <= self.stop {
                        return ControlFlow::Break(());
                    }
                }
            }
        }
        ControlFlow::Continue(())
    }
}
