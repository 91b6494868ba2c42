//! Checking that arrays form a k-d tree.

use super::{KdConfig, KdKind, KdTree};
use crate::cells::{Visits, Words, first_bad_reference};
use crate::error::StructureError;
use crate::math::Aabb;
use crate::query::Cell;

/// Checks `tree` (see [`KdTree::from_parts`]). The walk counts visits and stops past the node
/// count, so arrays that name the same children twice are refused in bounded time (and every
/// later traversal is bounded by the node count).
fn check<N: Words, W: Words>(
    tree: &KdTree<N, W>,
    triangle_count: usize,
) -> Result<(), StructureError> {
    let count = tree.node_count();
    if count == 0 || !tree.nodes.len().is_multiple_of(2) {
        return Err(StructureError::EmptyMismatch);
    }
    let single_empty_leaf = count == 1 && tree.items.is_empty();
    if !single_empty_leaf && (!tree.bounds.is_finite() || tree.bounds.is_empty()) {
        return Err(StructureError::BadBounds { node: 0 });
    }
    let mut stack = [(0u32, Cell::root(tree.bounds), 0u32); KdConfig::MAX_DEPTH as usize + 2];
    let mut top = 1usize;
    let mut visits = Visits::new(count);
    while let Some((node, cell, depth)) = top.checked_sub(1).and_then(|i| stack.get(i).copied()) {
        top -= 1;
        visits.visit()?;
        let Some(n) = tree.node(node as usize) else {
            return Err(StructureError::ChildOutOfRange { node });
        };
        match n.kind() {
            KdKind::Leaf { first, count: len } => {
                let end = first as usize + len as usize;
                if end > tree.items.len() {
                    return Err(StructureError::LeafRangeOutOfBounds { node });
                }
            }
            KdKind::Inner {
                axis,
                split,
                first_child,
            } => {
                if depth >= KdConfig::MAX_DEPTH {
                    return Err(StructureError::TooDeep { node });
                }
                let (lo, hi) = (cell.aabb().min.to_array(), cell.aabb().max.to_array());
                let inside = matches!((lo.get(axis), hi.get(axis)), (Some(&l), Some(&h)) if split >= l && split <= h);
                if !split.is_finite() || !inside {
                    return Err(StructureError::BadNode { node });
                }
                if first_child <= node {
                    return Err(StructureError::ChildNotAfterParent { node });
                }
                if first_child as usize + 1 >= count {
                    return Err(StructureError::ChildOutOfRange { node });
                }
                let (below, above) = cell.split(axis, split);
                for (k, c) in [(1, above), (0, below)] {
                    if let Some(slot) = stack.get_mut(top) {
                        *slot = (first_child + k, c, depth + 1);
                        top += 1;
                    }
                }
            }
        }
    }
    visits.finish()?;
    match first_bad_reference(tree.items, triangle_count) {
        Some((_, tri)) => Err(StructureError::TriangleOutOfRange { node: 0, tri }),
        None => Ok(()),
    }
}

impl<N: Words, W: Words> KdTree<N, W> {
    /// A k-d tree over arrays written earlier by [`KdTree::build`] (kept, copied or stored)
    /// for a mesh of `triangle_count` triangles with bounds `bounds`, after checking they form
    /// one: every node reachable exactly once, children after their parent, planes finite and
    /// inside their cell, depth at most [`KdConfig::MAX_DEPTH`], leaf ranges inside `items`,
    /// references naming triangles of the mesh. It does not check that each leaf lists exactly
    /// the triangles touching it: one that lists others answers wrongly, never panics.
    ///
    /// # Errors
    /// The first [`StructureError`] found.
    pub fn from_parts(
        bounds: Aabb,
        nodes: N,
        items: W,
        triangle_count: usize,
    ) -> Result<Self, StructureError> {
        let tree = Self {
            bounds,
            nodes,
            items,
        };
        check(&tree, triangle_count)?;
        Ok(tree)
    }
}
