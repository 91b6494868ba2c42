//! The tree of a blob, read in place from its bytes.

use super::format::{NODE_BYTES, ORDER_BYTES, WINDING_BYTES, node_from_bytes};
use crate::advanced::CollapseRoles;
use crate::bvh::{BvhNode, TreeArrays};
use crate::query::LeafTriangleIds;
use crate::query::SplitRefs;
#[cfg(feature = "blob-spatial")]
use crate::query::split_refs::SPLIT_REF_BYTES;

/// A BVH whose nodes and order are read straight out of a validated blob's bytes (in RAM or in
/// flash): no copy, 32 bytes decoded per node visited.
///
/// Obtained from [`BlobView::tree`](super::BlobView::tree), so it is always valid. Answers every
/// query exactly as the [`Bvh`](crate::bvh::Bvh) it was encoded from, bit for bit.
#[derive(Clone, Copy, Debug)]
pub struct BlobTree<'a> {
    pub(super) nodes: &'a [[u8; NODE_BYTES]],
    pub(super) order: &'a [[u8; ORDER_BYTES]],
    pub(super) depth: u32,
    /// Split reference records (a tree with spatial splits; empty otherwise). Not kept
    /// without the feature, where no blob read has any.
    #[cfg(feature = "blob-spatial")]
    pub(super) splits: &'a [[u8; SPLIT_REF_BYTES]],
    /// The collapse roles (version 5 or 6; empty before, or when not stored).
    pub(super) roles: &'a [u8],
    /// The winding-number expansions (version 6, when stored and read with the
    /// `blob-winding` feature; empty otherwise).
    #[cfg_attr(not(feature = "blob-winding"), allow(dead_code))]
    pub(super) winding: &'a [[u8; WINDING_BYTES]],
}

impl<'a> BlobTree<'a> {
    /// Levels in the tree (0 when empty).
    #[must_use]
    pub const fn depth(&self) -> u32 {
        self.depth
    }

    /// The roles of the tree's nodes in its eight-wide collapse, checked against the tree
    /// (format version 5; `None` for an older blob, whose loaders plan the collapse
    /// themselves): [`CollapsePlan::from_roles`](crate::advanced::CollapsePlan::from_roles)
    /// collapses the tree with them.
    #[must_use]
    pub fn collapse_roles(&self) -> Option<CollapseRoles<'a>> {
        (!self.roles.is_empty()).then_some(CollapseRoles::new(self.roles))
    }

    /// The split references, for as long as the bytes live.
    pub(super) fn split_table(&self) -> SplitRefs<'a> {
        #[cfg(feature = "blob-spatial")]
        return SplitRefs::from_records(self.splits);
        // Without the feature no blob read has any: the constant lets checks fold away.
        #[cfg(not(feature = "blob-spatial"))]
        SplitRefs::NONE
    }

    /// The order's entries (triangle indices, one per leaf slot).
    pub(super) fn order_entries(&self) -> impl Iterator<Item = u32> + '_ {
        self.order.iter().map(|e| u32::from_le_bytes(*e))
    }
}

impl TreeArrays for BlobTree<'_> {
    #[inline(always)]
    fn node_count(&self) -> usize {
        self.nodes.len()
    }

    #[inline(always)]
    fn slot_count(&self) -> usize {
        self.order.len()
    }

    #[inline(always)]
    fn node(&self, index: usize) -> Option<BvhNode> {
        self.nodes.get(index).map(node_from_bytes)
    }

    #[inline(always)]
    fn node_pair(&self, first: usize) -> Option<[BvhNode; 2]> {
        match self.nodes.get(first..first.wrapping_add(2))? {
            [left, right] => Some([node_from_bytes(left), node_from_bytes(right)]),
            _ => None,
        }
    }

    #[inline(always)]
    fn leaf_triangles(&self, first: usize, count: usize) -> Option<LeafTriangleIds<'_>> {
        let ids = self.order.get(first..first.checked_add(count)?)?;
        Some(LeafTriangleIds::from_le_bytes(first, ids))
    }

    #[inline(always)]
    fn split_refs(&self) -> SplitRefs<'_> {
        self.split_table()
    }
}
