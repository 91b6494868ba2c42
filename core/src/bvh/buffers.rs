//! Every buffer a BVH build needs, in one fixed-capacity value, for code without an allocator.

use super::{BuildConfig, Bvh, BvhNode, PrimRef};
use crate::error::BuildError;
use crate::mesh::ValidMesh;

/// The node, order and scratch buffers of a build over up to `TRIS` triangles, in one value
/// (`TRIS · 100` bytes: 64 for nodes, 4 for the order, 32 for scratch), for code without an
/// allocator. Put it on the stack, in a `static` cell, or wherever the caller keeps memory.
///
/// ```
/// use meshq::prelude::*;
/// let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
/// let mesh = MeshRef::new(&positions, &[[0, 1, 2]]).validate()?;
/// let mut buffers = BvhBuffers::<16>::new();
/// let bvh = buffers.build(&mesh, &BuildConfig::default())?;
/// assert_eq!(bvh.order(), &[0]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct BvhBuffers<const TRIS: usize> {
    /// Two nodes per triangle: at least [`node_capacity`](super::node_capacity)`(TRIS)`.
    nodes: [[BvhNode; 2]; TRIS],
    order: [u32; TRIS],
    scratch: [PrimRef; TRIS],
}

impl<const TRIS: usize> Default for BvhBuffers<TRIS> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const TRIS: usize> BvhBuffers<TRIS> {
    /// Empty buffers.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            nodes: [[BvhNode::EMPTY; 2]; TRIS],
            order: [0; TRIS],
            scratch: [PrimRef::EMPTY; TRIS],
        }
    }

    /// Builds a BVH of `mesh` into these buffers: [`Bvh::build`] with them. Building again
    /// reuses them (the earlier view must be gone by then).
    ///
    /// # Errors
    /// As [`Bvh::build`]: [`BuildError::BufferTooSmall`] when `mesh` has more than `TRIS`
    /// triangles, [`BuildError::TooDeep`] or [`BuildError::InvalidConfig`].
    pub fn build(
        &mut self,
        mesh: &ValidMesh<'_>,
        config: &BuildConfig,
    ) -> Result<Bvh<'_>, BuildError> {
        Bvh::build(
            mesh,
            config,
            self.nodes.as_flattened_mut(),
            &mut self.order,
            &mut self.scratch,
        )
    }
}
