//! The generic walk over two trees: the caller's rule orders and prunes pairs of nodes, and
//! the caller's callback sees pairs of triangles (three-mesh-bvh's `bvhcast`). Mesh distance
//! and the mesh–mesh intersection queries run on the same walk.

use core::ops::ControlFlow;

use super::budget::Tally;
use super::tree_pairs::{LeafPairVisitor, walk_leaf_pairs};
use super::{Affine, Found, PairBudget};
use crate::bvh::{BvhNode, TreeArrays};
use crate::error::PairBudgetSpent;
use crate::math::{Aabb, Triangle};
use crate::query::{LeafTriangles, With};

/// A triangle handed to [`PairVisitor::triangles`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WalkedTriangle {
    /// The triangle's index in its mesh.
    pub index: u32,
    /// Its corners; the second mesh's placed in the first one's frame.
    pub corners: Triangle,
    /// The box of the leaf that holds it (placed likewise): with spatial splits a triangle
    /// sits in several leaves, and the box tells which reference this is.
    pub leaf: Aabb,
}

/// The caller's side of [`walk_pairs`]: which pairs of nodes to descend, in which order, and
/// what to do with a pair of triangles.
pub trait PairVisitor {
    /// The score of a pair of nodes whose boxes are `a` (the first tree's) and `b` (the
    /// second's, placed in the first one's frame and grown to hold the placement's rounding):
    /// `None` skips the pair and everything under it. Of the two children pairs of a split,
    /// the one with the smaller score is walked first (the first child's on ties), so a
    /// distance makes the walk best-first; a constant keeps the plain depth-first order.
    fn nodes(&mut self, a: &Aabb, b: &Aabb) -> Option<f32>;

    /// Whether a pair of nodes scored `score` when it was deferred is still worth walking
    /// when its turn comes (a distance query drops pairs farther than the best found since).
    /// The default keeps every pair.
    fn still_wanted(&mut self, score: f32) -> bool {
        let _ = score;
        true
    }

    /// A triangle of the first mesh and one of the second, from a pair of leaves whose nodes
    /// were kept. Breaking stops the walk.
    fn triangles(&mut self, a: &WalkedTriangle, b: &WalkedTriangle) -> ControlFlow<()>;
}

/// Walks the trees of `a` and `b` together from their roots, `b` placed in `a`'s frame by
/// `b_to_a` (`None`: as it is), and hands `visitor` every pair of triangles under the pairs of
/// nodes it keeps: `b`'s triangles in the outer loop, each placed once per pair of leaves,
/// `a`'s in the inner one. Of two inner nodes the one with the larger box is split; the
/// order is deterministic, the same on every target.
///
/// A triangle that spatial splits put in several leaves can come up once per pair of leaves
/// that holds it ([`WalkedTriangle::leaf`] tells them apart). No allocation: a fixed stack of
/// about 5 KiB.
///
/// Returns `Break` when the visitor stopped the walk and `Continue` when it went to its end.
///
/// # Errors
/// [`PairBudgetSpent`] when the leaves of the kept pairs held more triangle pairs than
/// `budget` allows (counted per pair of leaves, before the pairs are handed over; see
/// [`PairBudget`]).
pub fn walk_pairs<A, SA, B, SB, V>(
    a: With<'_, A, SA>,
    b: With<'_, B, SB>,
    b_to_a: Option<&Affine>,
    budget: PairBudget,
    visitor: &mut V,
) -> Result<ControlFlow<()>, PairBudgetSpent>
where
    A: TreeArrays + ?Sized,
    SA: LeafTriangles + ?Sized,
    B: TreeArrays + ?Sized,
    SB: LeafTriangles + ?Sized,
    V: PairVisitor + ?Sized,
{
    let mut walk = TrianglePairs {
        a,
        b,
        b_to_a,
        tally: Tally::new(budget),
        tested: 0,
        visitor,
    };
    let flow = walk_leaf_pairs(a.structure(), b.structure(), b_to_a, &mut walk);
    let found = Found {
        total: 0,
        written: 0,
        tested: walk.tested,
    };
    walk.tally.finish(found).map(|_| flow)
}

/// [`walk_pairs`]'s leaf-level side: loads the triangles of each pair of leaves.
struct TrianglePairs<'w, A: ?Sized, SA: ?Sized, B: ?Sized, SB: ?Sized, V: ?Sized> {
    a: With<'w, A, SA>,
    b: With<'w, B, SB>,
    b_to_a: Option<&'w Affine>,
    tally: Tally,
    tested: usize,
    visitor: &'w mut V,
}

impl<A, SA, B, SB, V> LeafPairVisitor for TrianglePairs<'_, A, SA, B, SB, V>
where
    A: TreeArrays + ?Sized,
    SA: LeafTriangles + ?Sized,
    B: TreeArrays + ?Sized,
    SB: LeafTriangles + ?Sized,
    V: PairVisitor + ?Sized,
{
    fn nodes(&mut self, a: &Aabb, b: &Aabb) -> Option<f32> {
        self.visitor.nodes(a, b)
    }

    fn still_wanted(&mut self, score: f32) -> bool {
        self.visitor.still_wanted(score)
    }

    fn leaves(&mut self, leaf_a: BvhNode, leaf_b: BvhNode) -> ControlFlow<()> {
        let Some((ids_a, ids_b)) =
            self.tally
                .take_leaves(self.a.structure(), self.b.structure(), &leaf_a, &leaf_b)?
        else {
            return ControlFlow::Continue(());
        };
        let placed_leaf_b = self
            .b_to_a
            .map_or(leaf_b.aabb(), |m| m.apply_box(&leaf_b.aabb()));
        for (slot_b, id_b) in ids_b {
            let Some(tb) = self.b.triangles().corners(slot_b, id_b) else {
                continue;
            };
            let walked_b = WalkedTriangle {
                index: id_b,
                corners: self.b_to_a.map_or(tb, |m| m.apply_triangle(&tb)),
                leaf: placed_leaf_b,
            };
            for (slot_a, id_a) in ids_a.clone() {
                let Some(ta) = self.a.triangles().corners(slot_a, id_a) else {
                    continue;
                };
                self.tested += 1;
                let walked_a = WalkedTriangle {
                    index: id_a,
                    corners: ta,
                    leaf: leaf_a.aabb(),
                };
                self.visitor.triangles(&walked_a, &walked_b)?;
            }
        }
        ControlFlow::Continue(())
    }
}
