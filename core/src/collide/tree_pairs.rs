//! Walking two binary trees at once: every pair of leaves whose boxes overlap, found by
//! descending both trees together from their roots.

use core::ops::ControlFlow;

use super::Affine;
use crate::bvh::{BvhNode, MAX_DEPTH, TreeArrays};
use crate::math::Aabb;

/// Room for the deferred pairs of a walk over two trees of at most [`MAX_DEPTH`] levels:
/// each step descends one tree by a level and defers at most one sibling pair, so at most
/// one pair waits per level of either tree.
const PAIR_STACK: usize = 2 * MAX_DEPTH as usize + 2;

/// Room for the deferred pairs of a walk of one tree against itself: a node paired with
/// itself defers two pairs as it descends (its children with themselves and each other),
/// then each of those walks like [`PAIR_STACK`].
const SELF_STACK: usize = 4 * MAX_DEPTH as usize + 4;

/// What a walk over two trees asks of its caller at each pair of nodes and each pair of
/// leaves.
pub(crate) trait LeafPairVisitor {
    /// The score of a pair of nodes whose boxes are `a` and `b` (placed in `a`'s frame):
    /// `None` skips the pair and everything under it; of two children pairs, the one with
    /// the smaller score is walked first (the first child's on ties).
    fn nodes(&mut self, a: &Aabb, b: &Aabb) -> Option<f32>;

    /// Whether a pair scored `score` when it was deferred is still worth walking now.
    fn still_wanted(&mut self, score: f32) -> bool;

    /// A pair of leaves whose nodes were kept down to here.
    fn leaves(&mut self, a: BvhNode, b: BvhNode) -> ControlFlow<()>;
}

/// Walks two trees together from their roots, `b`'s boxes moved by `b_to_a` (see
/// [`Affine::apply_box`]), handing every pair of leaves that `visitor` keeps to
/// [`LeafPairVisitor::leaves`]. Depth first: of a pair of inner nodes, the one with the larger
/// box (half area, `a`'s on ties) is split; a leaf is split never. Stops when the visitor
/// breaks, and returns whether it did.
///
/// A validated tree is at most [`MAX_DEPTH`] deep, so the fixed stack never fills; on a
/// deeper one (which validation rules out) the walk stops.
pub(crate) fn walk_leaf_pairs<A, B, V>(
    a: &A,
    b: &B,
    b_to_a: Option<&Affine>,
    visitor: &mut V,
) -> ControlFlow<()>
where
    A: TreeArrays + ?Sized,
    B: TreeArrays + ?Sized,
    V: LeafPairVisitor + ?Sized,
{
    let placed = |node: &BvhNode| b_to_a.map_or(node.aabb(), |m| m.apply_box(&node.aabb()));
    let (Some(ra), Some(rb)) = (a.node(0), b.node(0)) else {
        return ControlFlow::Continue(());
    };
    let root_b = placed(&rb);
    let Some(root_score) = visitor.nodes(&ra.aabb(), &root_b) else {
        return ControlFlow::Continue(());
    };
    // Each deferred pair keeps `b`'s node box as placed, so a box is placed once, and the
    // score it was deferred with.
    let mut stack = [(0u32, 0u32, root_b, root_score); PAIR_STACK];
    let mut sp = 1usize;
    while sp > 0 {
        sp -= 1;
        let Some(&(ia, ib, box_b, score)) = stack.get(sp) else {
            break;
        };
        if !visitor.still_wanted(score) {
            continue;
        }
        let (Some(na), Some(nb)) = (a.node(ia as usize), b.node(ib as usize)) else {
            break;
        };
        if na.is_leaf() && nb.is_leaf() {
            visitor.leaves(na, nb)?;
            continue;
        }
        let split_a = !na.is_leaf() && (nb.is_leaf() || na.aabb().half_area() >= box_b.half_area());
        let children = if split_a {
            let Some([l, r]) = a.node_pair(na.first as usize) else {
                break;
            };
            [
                (l.aabb(), na.first, ib, box_b),
                (r.aabb(), na.first.wrapping_add(1), ib, box_b),
            ]
        } else {
            let Some([l, r]) = b.node_pair(nb.first as usize) else {
                break;
            };
            let (bl, br) = (placed(&l), placed(&r));
            [
                (na.aabb(), ia, nb.first, bl),
                (na.aabb(), ia, nb.first.wrapping_add(1), br),
            ]
        };
        let [first, second] = children
            .map(|(box_a, i, j, box_b)| visitor.nodes(&box_a, &box_b).map(|s| (i, j, box_b, s)));
        // The pair walked first is pushed last: the first child's unless the second scores
        // strictly better.
        let (early, late) = match (first, second) {
            (Some(f), Some(s)) if s.3 < f.3 => (Some(s), Some(f)),
            _ => (first, second),
        };
        for pair in [late, early].into_iter().flatten() {
            let Some(slot) = stack.get_mut(sp) else {
                return ControlFlow::Continue(());
            };
            *slot = pair;
            sp += 1;
        }
    }
    ControlFlow::Continue(())
}

/// Calls `visit(leaf of a, leaf of b)` on every pair of leaves whose boxes overlap, with
/// `b`'s boxes moved by `b_to_a`, in [`walk_leaf_pairs`]'s order. Stops when `visit` breaks,
/// and returns whether it did.
pub(crate) fn for_each_leaf_pair<A, B>(
    a: &A,
    b: &B,
    b_to_a: Option<&Affine>,
    visit: impl FnMut(BvhNode, BvhNode) -> ControlFlow<()>,
) -> ControlFlow<()>
where
    A: TreeArrays + ?Sized,
    B: TreeArrays + ?Sized,
{
    /// Keeps the pairs whose boxes overlap, all scored alike.
    struct Overlapping<F>(F);
    impl<F: FnMut(BvhNode, BvhNode) -> ControlFlow<()>> LeafPairVisitor for Overlapping<F> {
        fn nodes(&mut self, a: &Aabb, b: &Aabb) -> Option<f32> {
            a.overlaps(b).then_some(0.0)
        }
        fn still_wanted(&mut self, _: f32) -> bool {
            true
        }
        fn leaves(&mut self, a: BvhNode, b: BvhNode) -> ControlFlow<()> {
            (self.0)(a, b)
        }
    }
    walk_leaf_pairs(a, b, b_to_a, &mut Overlapping(visit))
}

/// Calls `visit(leaf, leaf)` on every unordered pair of leaves of `tree` whose boxes overlap,
/// each leaf with itself included (then both arguments are the same leaf). Depth first; of
/// two different inner nodes the one with the larger box is split. Stops when `visit`
/// breaks, and returns whether it did.
pub(crate) fn for_each_self_leaf_pair<A>(
    tree: &A,
    mut visit: impl FnMut(BvhNode, BvhNode) -> ControlFlow<()>,
) -> ControlFlow<()>
where
    A: TreeArrays + ?Sized,
{
    let mut stack = [(0u32, 0u32); SELF_STACK];
    let mut sp = usize::from(tree.node(0).is_some());
    let push = |stack: &mut [(u32, u32)], sp: &mut usize, pair: (u32, u32)| {
        if let Some(slot) = stack.get_mut(*sp) {
            *slot = pair;
            *sp += 1;
            true
        } else {
            false
        }
    };
    while sp > 0 {
        sp -= 1;
        let Some(&(i, j)) = stack.get(sp) else {
            break;
        };
        let (Some(ni), Some(nj)) = (tree.node(i as usize), tree.node(j as usize)) else {
            break;
        };
        if ni.is_leaf() && nj.is_leaf() {
            visit(ni, nj)?;
            continue;
        }
        let pushed = if i == j {
            // A node against itself: its children each against itself, and against each other.
            let (l, r) = (ni.first, ni.first.wrapping_add(1));
            let Some([left, right]) = tree.node_pair(l as usize) else {
                break;
            };
            let mut ok = push(&mut stack, &mut sp, (r, r));
            if left.aabb().overlaps(&right.aabb()) {
                ok &= push(&mut stack, &mut sp, (l, r));
            }
            ok && push(&mut stack, &mut sp, (l, l))
        } else {
            let split_i =
                !ni.is_leaf() && (nj.is_leaf() || ni.aabb().half_area() >= nj.aabb().half_area());
            let (split, keep, keep_box) = if split_i {
                (ni, j, nj.aabb())
            } else {
                (nj, i, ni.aabb())
            };
            let Some(pair) = tree.node_pair(split.first as usize) else {
                break;
            };
            let mut ok = true;
            for (child, index) in pair
                .iter()
                .zip([split.first, split.first.wrapping_add(1)])
                .rev()
            {
                if child.aabb().overlaps(&keep_box) {
                    ok &= push(&mut stack, &mut sp, (index, keep));
                }
            }
            ok
        };
        if !pushed {
            return ControlFlow::Continue(());
        }
    }
    ControlFlow::Continue(())
}
