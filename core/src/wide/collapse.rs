//! Collapsing a binary BVH into a four- or eight-wide one.

use super::WideNode;
use super::plan::CollapsePlan;
use crate::bvh::{BvhNode, TreeArrays};
use crate::error::{BufferKind, BuildError};
use crate::math::Aabb;

/// A node of `W` lanes that a collapse fills lane by lane (public in a private module: the
/// bound of [`WideBvh::build`](super::WideBvh::build), not nameable outside).
pub trait CollapsedNode<const W: usize>: Sized {
    /// A node with every lane unused.
    const EMPTY: Self;
    /// True when every field of both nodes has the same bits (so `0.0` and `-0.0` differ).
    fn same_bits(&self, other: &Self) -> bool;
    /// Writes lane `lane`'s box, child and triangle count (ignored past the last lane).
    fn set_lane(&mut self, lane: usize, aabb: &Aabb, child: u32, count: u32);
    /// Adds `by` (wrapping) to the node index of every inner child lane (used, count 0).
    #[cfg(feature = "parallel")]
    fn shift_inner(&mut self, by: u32);
}

impl CollapsedNode<4> for WideNode {
    const EMPTY: Self = WideNode::EMPTY;
    fn same_bits(&self, other: &Self) -> bool {
        WideNode::same_bits(self, other)
    }
    fn set_lane(&mut self, lane: usize, aabb: &Aabb, child: u32, count: u32) {
        WideNode::set_lane(self, lane, aabb, child, count);
    }
    #[cfg(feature = "parallel")]
    fn shift_inner(&mut self, by: u32) {
        shift_inner_lanes(&mut self.child, &self.count, by);
    }
}

/// [`CollapsedNode::shift_inner`] over a node's `child` and `count` lanes: inner children are
/// the lanes with a count of 0 and a child other than 0 (no inner child is the root, 0, and
/// unused lanes hold 0).
#[cfg(feature = "parallel")]
pub(super) fn shift_inner_lanes(child: &mut [u32], count: &[u32], by: u32) {
    for (c, &n) in child.iter_mut().zip(count) {
        if n == 0 && *c != 0 {
            *c = c.wrapping_add(by);
        }
    }
}

/// Collapses `plan`'s tree into `out` with nodes of `W` lanes and returns how many it wrote.
///
/// # Errors
/// [`BuildError::BufferTooSmall`] when `out` holds fewer than [`CollapsePlan::node_count`]
/// nodes (nothing is written then), or the collapse's own errors.
pub(super) fn collapse_into<N: CollapsedNode<W>, const W: usize>(
    plan: &CollapsePlan<'_, '_, W>,
    out: &mut [N],
) -> Result<usize, BuildError> {
    let too_small = |needed: usize, got: usize| BuildError::BufferTooSmall {
        buffer: BufferKind::WideNodes,
        needed,
        got,
    };
    if out.len() < plan.node_count() {
        return Err(too_small(plan.node_count(), out.len()));
    }
    let needed = collapse_to::<N, W>(plan, |index, node| {
        if let Some(slot) = out.get_mut(index) {
            *slot = node;
        }
    })?;
    if needed > out.len() {
        // Unreachable (the plan counted these very nodes), but never hand out a short view.
        return Err(too_small(needed, out.len()));
    }
    Ok(needed)
}

/// Plans the collapse of `tree` in a vector of its own and collapses it into nodes of `W`
/// lanes (the owned types' collapse).
#[cfg(feature = "alloc")]
pub(crate) fn collapse_vec<N: CollapsedNode<W> + Clone, const W: usize>(
    tree: &crate::bvh::Bvh<'_>,
) -> Result<alloc::vec::Vec<N>, BuildError> {
    let mut entries = alloc::vec![super::plan::PlanEntry::EMPTY; super::plan::plan_capacity(tree)];
    let plan = CollapsePlan::<W>::solved(tree, &mut entries)?;
    collapse_planned_vec(&plan)
}

/// The roles of `tree`'s nodes in its eight-wide collapse, planned here
/// ([`CollapsePlan::write_roles`]), for a blob to store.
#[cfg(all(feature = "alloc", feature = "blob"))]
pub(crate) fn eight_wide_roles(
    tree: &crate::bvh::Bvh<'_>,
) -> Result<alloc::vec::Vec<u8>, BuildError> {
    let mut entries = alloc::vec![super::plan::PlanEntry::EMPTY; super::plan::plan_capacity(tree)];
    let plan = CollapsePlan::<8>::solved(tree, &mut entries)?;
    let mut roles = alloc::vec![0u8; super::roles::CollapseRoles::len_for(tree.nodes().len())];
    plan.write_roles(&mut roles)?;
    Ok(roles)
}

/// [`collapse_to`] into a vector grown as nodes come (reserved up front when the plan bounds
/// their count): one pass.
#[cfg(feature = "alloc")]
pub(crate) fn collapse_planned_vec<N: CollapsedNode<W> + Clone, const W: usize>(
    plan: &CollapsePlan<'_, '_, W>,
) -> Result<alloc::vec::Vec<N>, BuildError> {
    let mut nodes = alloc::vec::Vec::with_capacity(plan.node_bound());
    let count = collapse_to::<N, W>(plan, |index, node| {
        if index >= nodes.len() {
            nodes.resize(index + 1, N::EMPTY);
        }
        if let Some(slot) = nodes.get_mut(index) {
            *slot = node;
        }
    })?;
    // Every index below the count is written once, so the vector is exactly the nodes.
    nodes.truncate(count);
    nodes.shrink_to_fit();
    Ok(nodes)
}

/// Collapses `plan`'s tree into wide nodes of `W` lanes, handing each to `sink` with its index
/// (in any order), and returns how many there are. The same plan always gives the same nodes.
///
/// Each wide node covers an inner binary node's subtree with the lanes the plan chose for it
/// ([`CollapsePlan::lanes`]), inner children in its first lanes ([`wide_node`]). Inner children
/// of one node get consecutive indices, in lane order; the nodes are numbered depth first, the
/// last inner child's subtree first.
pub(super) fn collapse_to<N: CollapsedNode<W>, const W: usize>(
    plan: &CollapsePlan<'_, '_, W>,
    mut sink: impl FnMut(usize, N),
) -> Result<usize, BuildError> {
    if plan.is_stored() {
        // The walk of stored roles checks them, an empty tree's and a lone leaf's included.
        return collapse_from::<N, W>(plan, 0, sink);
    }
    let tree = plan.tree();
    let Some(root) = tree.node(0) else {
        return Ok(0);
    };
    if root.is_leaf() {
        let mut node = N::EMPTY;
        node.set_lane(0, &root.aabb(), root.first, root.count);
        sink(0, node);
        return Ok(1);
    }
    collapse_from::<N, W>(plan, 0, sink)
}

/// The collapse of the subtree under the inner binary node `root` alone: its wide node is
/// index 0 and its descendants are numbered from 1, as the whole collapse numbers them from
/// where it reaches that node (so the parallel collapse can lay a subtree collapsed on its
/// own down in place). Returns how many nodes it made.
pub(super) fn collapse_from<N: CollapsedNode<W>, const W: usize>(
    plan: &CollapsePlan<'_, '_, W>,
    root: u32,
    mut sink: impl FnMut(usize, N),
) -> Result<usize, BuildError> {
    plan.for_each_node(root, |wide, lanes, first_inner| {
        sink(wide as usize, wide_node::<N, W>(lanes, first_inner));
    })
}

/// The wide node of `children` (an [`open`]ed node's lanes, left to right): the inner
/// children first, in their order, numbered `first, first + 1, …`, then the leaves in theirs.
///
/// Inner lane `i` therefore holds node `first + i`, which the walk computes from lane 0's
/// child word instead of reading lane `i`'s after the box test
/// ([`LaneNode::first_inner`](super::traverse::LaneNode::first_inner)). Lane order only
/// breaks ties between equal keys in the walk, and no answer depends on the walk's order.
pub(super) fn wide_node<N: CollapsedNode<W>, const W: usize>(
    children: &[(u32, BvhNode)],
    first: u32,
) -> N {
    let mut node = N::EMPTY;
    let mut next = first;
    let inner = children.iter().filter(|(_, c)| !c.is_leaf());
    let leaves = children.iter().filter(|(_, c)| c.is_leaf());
    for (lane, (_, child)) in inner.chain(leaves).enumerate() {
        if child.is_leaf() {
            node.set_lane(lane, &child.aabb(), child.first, child.count);
        } else {
            node.set_lane(lane, &child.aabb(), next, 0);
            next = next.wrapping_add(1);
        }
    }
    node
}
