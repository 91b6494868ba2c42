//! Winding numbers, containment and signed distance from a blob's view, in place.

use super::{BlobMesh, BlobTree, BlobView, BlobWindingNodes};
use crate::inside::WindingTree;

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
