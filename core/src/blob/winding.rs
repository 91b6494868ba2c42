//! A blob's winding-number expansions (format version 6), read in place.

use super::format::{WINDING_BYTES, winding_from_bytes};
use super::{BlobMesh, BlobTree, BlobView};
use crate::error::BlobError;
use crate::inside::{WindingNode, WindingNodes, WindingTree};

/// The winding-number expansions stored in a blob, one 112-byte record per tree node, decoded
/// as a query reaches them (no copy).
#[derive(Clone, Copy, Debug)]
pub struct BlobWindingNodes<'a> {
    pub(super) records: &'a [[u8; WINDING_BYTES]],
}

impl WindingNodes for BlobWindingNodes<'_> {
    #[inline(always)]
    fn count(&self) -> usize {
        self.records.len()
    }

    #[inline(always)]
    fn expansion(&self, index: usize) -> Option<WindingNode> {
        self.records.get(index).map(winding_from_bytes)
    }
}

/// A [`WindingTree`] read straight out of a blob: its tree, triangles and expansions.
pub type BlobWindingTree<'a> = WindingTree<'a, BlobTree<'a>, BlobMesh<'a>, BlobWindingNodes<'a>>;

impl<'a> BlobView<'a> {
    /// Winding numbers, containment and signed distance straight from the blob (a geofence in
    /// flash): the stored expansions (format version 6, baked with
    /// [`EncodeOptions::winding`](super::EncodeOptions::winding)) over the stored tree and
    /// triangles, all read in place. Answers as the [`WindingTree`] built in memory from the
    /// same tree and mesh does, bit for bit (the load checked that the expansions are that
    /// tree's). `None` for a blob without expansions or of another structure.
    #[must_use]
    pub fn winding_tree(&self) -> Option<BlobWindingTree<'a>> {
        let tree = *self.tree()?;
        let nodes = tree.winding_nodes()?;
        Some(WindingTree::over(tree, self.mesh, nodes))
    }
}

impl<'a> BlobTree<'a> {
    /// The stored expansions, or `None` when the blob has none.
    #[must_use]
    pub fn winding_nodes(&self) -> Option<BlobWindingNodes<'a>> {
        (!self.winding.is_empty()).then_some(BlobWindingNodes {
            records: self.winding,
        })
    }
}

/// Refuses stored expansions that are not exactly the ones `tree` and `mesh` give (the tree's
/// topology and boxes were checked).
pub(super) fn check_winding(tree: &BlobTree<'_>, mesh: &BlobMesh<'_>) -> Result<(), BlobError> {
    match tree.winding_nodes() {
        Some(nodes) if !WindingTree::expansions_match(tree, mesh, &nodes) => {
            Err(BlobError::BadWindingNodes)
        }
        _ => Ok(()),
    }
}
