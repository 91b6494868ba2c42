//! [`WindingNodes`]: where a [`WindingTree`](super::WindingTree) reads its expansions from.

use super::WindingNode;

/// Read access to one [`WindingNode`] per tree node, wherever they are stored: in a slice
/// ([`WindingTree::build`](super::WindingTree::build) fills one) or in a blob's bytes, read in
/// place (`BlobView::winding_tree`, feature `blob-winding`).
/// Implementations return `None` past the end; they never panic.
pub trait WindingNodes {
    /// How many expansions there are (one per tree node).
    fn count(&self) -> usize;

    /// The expansion of node `index` (the root is 0), or `None` past the end.
    fn expansion(&self, index: usize) -> Option<WindingNode>;
}

impl WindingNodes for &[WindingNode] {
    #[inline(always)]
    fn count(&self) -> usize {
        self.len()
    }

    #[inline(always)]
    fn expansion(&self, index: usize) -> Option<WindingNode> {
        self.get(index).copied()
    }
}
