//! [`MeshOctree`]: a mesh and its octree, in buffers it owns.

use alloc::vec;
use alloc::vec::Vec;

use super::cell_scene::{CellScene, measure_fully};
use crate::cells::CellStats;
use crate::error::BuildError;
use crate::math::{Aabb, PackedTriangle, Triangle};
use crate::mesh::ValidMesh;
use crate::octree::{Octree, OctreeConfig, OctreeNode};
use crate::query::{LeafTriangles, Traverse, Visitor};

/// A mesh with its [`Octree`], owning every buffer: the mesh copy, the nodes and references
/// (sized by measuring until complete, then trimmed) and the triangles packed per reference,
/// which queries read. Answers every query of [`MeshQuery`](crate::query::MeshQuery), exactly
/// as the tree over the mesh does.
#[derive(Clone, Debug)]
pub struct MeshOctree {
    pub(super) scene: CellScene,
    pub(super) root: Aabb,
    pub(super) nodes: Vec<OctreeNode>,
    pub(super) items: Vec<u32>,
    pub(super) config: OctreeConfig,
}

impl MeshOctree {
    /// Copies `mesh` and builds its full octree with `config`.
    ///
    /// # Errors
    /// [`BuildError::InvalidConfig`] for a config out of range.
    pub fn build(mesh: &ValidMesh<'_>, config: &OctreeConfig) -> Result<Self, BuildError> {
        let mut scene = CellScene::copy(mesh);
        let sizes = measure_fully(mesh.triangle_count(), |w| Octree::measure(mesh, config, w))?;
        let (mut nodes, mut items) = (
            vec![OctreeNode::default(); sizes.nodes],
            vec![0u32; sizes.work],
        );
        let root = *Octree::build(&scene.mesh(), config, &mut nodes, &mut items)?.root();
        items.truncate(sizes.items);
        items.shrink_to_fit();
        scene.pack(&items)?;
        Ok(Self {
            scene,
            root,
            nodes,
            items,
            config: *config,
        })
    }

    /// The tree over [`MeshOctree::mesh`].
    #[must_use]
    pub fn tree(&self) -> Octree<&[OctreeNode], &[u32]> {
        Octree::from_validated(self.root, &self.nodes, &self.items)
    }

    /// The mesh.
    #[must_use]
    pub fn mesh(&self) -> ValidMesh<'_> {
        self.scene.mesh()
    }

    /// The config it was built with.
    #[must_use]
    pub const fn config(&self) -> &OctreeConfig {
        &self.config
    }

    /// Nodes, cells, references, depth.
    #[must_use]
    pub fn stats(&self) -> CellStats {
        self.tree().stats(self.scene.triangles.len())
    }

    /// Bytes of the structure's own arrays (nodes and references).
    #[must_use]
    pub fn structure_bytes(&self) -> usize {
        8 * self.nodes.len() + 4 * self.items.len()
    }

    /// Bytes of the packed triangles (36 per reference).
    #[must_use]
    pub fn packed_bytes(&self) -> usize {
        self.scene.packed_bytes()
    }
}

impl Traverse for MeshOctree {
    #[inline(always)]
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        self.tree().traverse(visitor);
    }
}

impl LeafTriangles for MeshOctree {
    #[inline(always)]
    fn corners(&self, slot: usize, tri: u32) -> Option<Triangle> {
        self.scene.corners(slot, tri)
    }

    #[inline(always)]
    fn run(&self, first: usize, count: usize) -> Option<&[PackedTriangle]> {
        self.scene.run(first, count)
    }
}
