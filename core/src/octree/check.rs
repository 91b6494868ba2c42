//! Checking that arrays form an octree.

use super::tree::STACK;
use super::{Octree, OctreeConfig};
use crate::cells::{Visits, Words, first_bad_reference};
use crate::error::StructureError;
use crate::math::Aabb;

/// Checks `tree` (see [`Octree::from_parts`]). The walk counts visits and stops past the node
/// count, so arrays that name the same children twice are refused in bounded time.
fn check<N: Words, W: Words>(
    tree: &Octree<N, W>,
    triangle_count: usize,
) -> Result<(), StructureError> {
    let count = tree.node_count();
    if count == 0 || !tree.nodes.len().is_multiple_of(2) {
        return Err(StructureError::EmptyMismatch);
    }
    let single_empty_leaf = count == 1 && tree.items.is_empty();
    if !single_empty_leaf && (!tree.root.is_finite() || tree.root.is_empty()) {
        return Err(StructureError::BadBounds { node: 0 });
    }
    let mut stack = [(0u32, 0u32); STACK];
    let mut top = 1usize;
    let mut visits = Visits::new(count);
    while let Some((node, depth)) = top.checked_sub(1).and_then(|i| stack.get(i).copied()) {
        top -= 1;
        visits.visit()?;
        let Some(n) = tree.node(node as usize) else {
            return Err(StructureError::ChildOutOfRange { node });
        };
        match n.first_child() {
            None => {
                if n.a as usize + n.b as usize > tree.items.len() {
                    return Err(StructureError::LeafRangeOutOfBounds { node });
                }
            }
            Some(first) => {
                if depth >= OctreeConfig::MAX_DEPTH {
                    return Err(StructureError::TooDeep { node });
                }
                if first <= node {
                    return Err(StructureError::ChildNotAfterParent { node });
                }
                if first as usize + 8 > count {
                    return Err(StructureError::ChildOutOfRange { node });
                }
                for k in 0..8 {
                    if let Some(slot) = stack.get_mut(top) {
                        *slot = (first + k, depth + 1);
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

impl<N: Words, W: Words> Octree<N, W> {
    /// An octree over arrays written earlier by [`Octree::build`] (kept, copied or stored),
    /// with root cube `root`, for a mesh of `triangle_count` triangles, after checking they form
    /// one: every node reachable exactly once, children after their parent, depth at most
    /// [`OctreeConfig::MAX_DEPTH`], leaf ranges inside `items`, references naming triangles of
    /// the mesh. It does not check that each leaf lists exactly the triangles touching it: one
    /// that lists others answers wrongly, never panics.
    ///
    /// # Errors
    /// The first [`StructureError`] found.
    pub fn from_parts(
        root: Aabb,
        nodes: N,
        items: W,
        triangle_count: usize,
    ) -> Result<Self, StructureError> {
        let tree = Self { root, nodes, items };
        check(&tree, triangle_count)?;
        Ok(tree)
    }
}
