//! Collapsing a binary BVH into a four- or eight-wide one.

use super::WideNode;
use crate::bvh::{Bvh, BvhNode, MAX_DEPTH, TreeArrays};
use crate::error::{BufferKind, BuildError};
use crate::math::Aabb;

/// Inner binary nodes waiting to become wide nodes. A wide node is no deeper than the binary
/// node it starts from, and each one leaves at most seven siblings pending per level (eight
/// lanes at most), so a valid tree never fills this.
const PENDING: usize = 7 * MAX_DEPTH as usize + 1;

/// Collapses `tree` into wide nodes, handing each to `sink` with its index (in any order), and
/// returns how many there are. The same tree always gives the same nodes.
///
/// Each wide node starts from an inner binary node's two children and repeatedly opens the
/// inner child with the largest surface area (the one a ray is most likely to enter; the
/// earlier lane on ties) until it has four (or eight) children or only leaves. Children of one node get
/// consecutive indices.
pub(super) fn collapse(
    tree: &Bvh<'_>,
    sink: impl FnMut(usize, WideNode),
) -> Result<usize, BuildError> {
    collapse_to::<WideNode, 4>(tree, sink)
}

/// A node a collapse fills lane by lane.
pub(crate) trait CollapsedNode: Sized {
    /// A node with every lane unused.
    const EMPTY: Self;
    /// Writes lane `lane`'s box, child and triangle count (ignored past the last lane).
    fn set_lane(&mut self, lane: usize, aabb: &Aabb, child: u32, count: u32);
    /// Adds `by` (wrapping) to the node index of every inner child lane (used, count 0).
    #[cfg(feature = "parallel")]
    fn shift_inner(&mut self, by: u32);
}

impl CollapsedNode for WideNode {
    const EMPTY: Self = WideNode::EMPTY;
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

/// Collapses `tree` into `out` with nodes of `W` lanes and returns how many it wrote. When
/// `out` is shorter than [`wide_node_capacity`](super::wide_node_capacity) of the triangle
/// count, a counting pass first makes sure the nodes fit.
///
/// # Errors
/// [`BuildError::BufferTooSmall`] when `out` is too small (nothing is written then), or the
/// collapse's own errors.
pub(super) fn collapse_into<N: CollapsedNode, const W: usize>(
    tree: &Bvh<'_>,
    out: &mut [N],
) -> Result<usize, BuildError> {
    let too_small = |needed: usize, got: usize| BuildError::BufferTooSmall {
        buffer: BufferKind::WideNodes,
        needed,
        got,
    };
    if out.len() < super::wide_node_capacity(tree.order().len()) {
        let needed = collapse_to::<N, W>(tree, |_, _| {})?;
        if out.len() < needed {
            return Err(too_small(needed, out.len()));
        }
    }
    let needed = collapse_to::<N, W>(tree, |index, node| {
        if let Some(slot) = out.get_mut(index) {
            *slot = node;
        }
    })?;
    if needed > out.len() {
        // Unreachable for a valid tree (the bound holds), but never hand out a short view.
        return Err(too_small(needed, out.len()));
    }
    Ok(needed)
}

/// [`collapse_to`] into a vector grown as nodes come: one pass, no counting, and no more
/// memory than the nodes need (the owned types' collapse).
#[cfg(feature = "alloc")]
pub(crate) fn collapse_vec<N: CollapsedNode + Clone, const W: usize>(
    tree: &Bvh<'_>,
) -> Result<alloc::vec::Vec<N>, BuildError> {
    let mut nodes = alloc::vec::Vec::new();
    let count = collapse_to::<N, W>(tree, |index, node| {
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

/// [`collapse`] into nodes of `W` lanes (`2..=8`).
pub(super) fn collapse_to<N: CollapsedNode, const W: usize>(
    tree: &Bvh<'_>,
    mut sink: impl FnMut(usize, N),
) -> Result<usize, BuildError> {
    let Some(root) = tree.node(0) else {
        return Ok(0);
    };
    if root.is_leaf() {
        let mut node = N::EMPTY;
        node.set_lane(0, &root.aabb(), root.first, root.count);
        sink(0, node);
        return Ok(1);
    }
    collapse_from::<N, W>(tree, 0, sink)
}

/// The collapse of the subtree under the inner binary node `root` alone: its wide node is
/// index 0 and its descendants are numbered from 1, as the whole collapse numbers them from
/// where it reaches that node (so the parallel collapse can lay a subtree collapsed on its
/// own down in place). Returns how many nodes it made.
pub(super) fn collapse_from<N: CollapsedNode, const W: usize>(
    tree: &Bvh<'_>,
    root: u32,
    mut sink: impl FnMut(usize, N),
) -> Result<usize, BuildError> {
    let too_deep = BuildError::TooDeep {
        max_depth: MAX_DEPTH,
        triangles: tree.slot_count(),
    };
    let mut pending = [(root, 0u32); PENDING];
    let mut len = 1usize;
    let mut next = 1u32;
    while let Some(at) = len.checked_sub(1) {
        len = at;
        let Some(&(binary, wide)) = pending.get(at) else {
            return Err(too_deep);
        };
        let Some(inner) = tree.node(binary as usize) else {
            return Err(too_deep);
        };
        let (children, lanes) = open::<W>(tree, &inner);
        let node = wide_node::<N>(children.get(..lanes).unwrap_or_default(), next);
        for &(index, child) in children.iter().take(lanes) {
            if !child.is_leaf() {
                let slot = pending.get_mut(len).ok_or(too_deep)?;
                *slot = (index, next);
                len += 1;
                next = next.checked_add(1).ok_or(too_deep)?;
            }
        }
        sink(wide as usize, node);
    }
    Ok(next as usize)
}

/// The wide node of `children` (an [`open`]ed node's lanes), its inner children numbered
/// `first, first + 1, …` in lane order.
pub(super) fn wide_node<N: CollapsedNode>(children: &[(u32, BvhNode)], first: u32) -> N {
    let mut node = N::EMPTY;
    let mut next = first;
    for (lane, (_, child)) in children.iter().enumerate() {
        if child.is_leaf() {
            node.set_lane(lane, &child.aabb(), child.first, child.count);
        } else {
            node.set_lane(lane, &child.aabb(), next, 0);
            next = next.wrapping_add(1);
        }
    }
    node
}

/// The up to `W` binary descendants of `inner` that become one wide node's children, as
/// `(binary index, node)`, and how many there are. An opened child's left half takes its
/// lane and its right half goes last (lane order carries no meaning: queries sort lanes by
/// distance).
pub(super) fn open<const W: usize>(
    tree: &Bvh<'_>,
    inner: &BvhNode,
) -> ([(u32, BvhNode); W], usize) {
    let mut lanes = [(0u32, BvhNode::EMPTY); W];
    let Some([left, right]) = tree.node_pair(inner.first as usize) else {
        return (lanes, 0);
    };
    lanes[0] = (inner.first, left);
    lanes[1] = (inner.first.wrapping_add(1), right);
    let mut len = 2usize;
    while len < W {
        let Some((lane, first)) = widest_inner(lanes.get(..len).unwrap_or_default()) else {
            break;
        };
        let Some([left, right]) = tree.node_pair(first as usize) else {
            break;
        };
        if let Some(l) = lanes.get_mut(lane) {
            *l = (first, left);
        }
        if let Some(r) = lanes.get_mut(len) {
            *r = (first.wrapping_add(1), right);
        }
        len += 1;
    }
    (lanes, len)
}

/// The lane of the inner node with the largest surface area (the first on ties) and that
/// node's first child index, or `None` when every lane is a leaf.
fn widest_inner(lanes: &[(u32, BvhNode)]) -> Option<(usize, u32)> {
    let mut best: Option<(usize, u32, f32)> = None;
    for (lane, (_, node)) in lanes.iter().enumerate() {
        if node.is_leaf() {
            continue;
        }
        let area = node.aabb().half_area();
        if best.is_none_or(|(_, _, a)| area > a) {
            best = Some((lane, node.first, area));
        }
    }
    best.map(|(lane, first, _)| (lane, first))
}
