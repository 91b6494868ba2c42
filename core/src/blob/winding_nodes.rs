//! A blob's winding-number expansions (format version 6), read in place record by record.

use super::BlobTree;
use super::format::{WINDING_BYTES, winding_from_bytes};
use crate::inside::{WindingNode, WindingNodes};

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

impl<'a> BlobTree<'a> {
    /// The stored expansions, or `None` when the blob has none.
    #[must_use]
    pub fn winding_nodes(&self) -> Option<BlobWindingNodes<'a>> {
        (!self.winding.is_empty()).then_some(BlobWindingNodes {
            records: self.winding,
        })
    }
}
