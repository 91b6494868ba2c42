//! Winding numbers, containment and signed distance on a [`MeshBvh`].

use alloc::vec;

use super::MeshBvh;
use crate::error::BuildError;
use crate::inside::{WindingNode, WindingTree};

impl MeshBvh {
    /// This structure with its winding-number expansions worked out (one
    /// [`WindingNode`] per binary node, 112 bytes each), so that [`MeshBvh::winding`] answers
    /// winding numbers, containment and signed distance. Already prepared: unchanged.
    ///
    /// # Errors
    /// Never for a structure built or loaded by this crate.
    pub fn with_winding_numbers(mut self) -> Result<Self, BuildError> {
        self.prepare_winding_numbers()?;
        Ok(self)
    }

    /// [`MeshBvh::with_winding_numbers`] in place. On error nothing changes.
    ///
    /// # Errors
    /// As [`MeshBvh::with_winding_numbers`].
    pub fn prepare_winding_numbers(&mut self) -> Result<(), BuildError> {
        if self.winding.is_some() {
            return Ok(());
        }
        let mut nodes = vec![WindingNode::EMPTY; self.nodes.len()];
        WindingTree::build(self.bvh(), self.mesh(), &mut nodes)?;
        self.winding = Some(nodes);
        Ok(())
    }

    /// The winding-number tree over this structure's binary tree and mesh
    /// ([`WindingTree`]: winding numbers, `contains`, signed distance), once
    /// [`MeshBvh::with_winding_numbers`] has prepared it; `None` before.
    #[must_use]
    pub fn winding(&self) -> Option<WindingTree<'_>> {
        let nodes = self.winding.as_deref()?;
        WindingTree::from_parts(self.bvh(), self.mesh(), nodes).ok()
    }
}
