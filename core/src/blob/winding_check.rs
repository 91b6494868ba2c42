//! The check at load that a blob's stored winding-number expansions are its tree's.

use super::{BlobMesh, BlobTree};
use crate::error::BlobError;
use crate::inside::WindingTree;

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
