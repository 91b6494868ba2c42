//! [`MeshGrid`]: a mesh and its uniform grid, in buffers it owns.

use alloc::vec;
use alloc::vec::Vec;

use super::cell_scene::CellScene;
use crate::cells::CellStats;
use crate::error::BuildError;
use crate::grid::{Grid, GridConfig, GridLayout};
use crate::math::{PackedTriangle, Triangle};
use crate::mesh::ValidMesh;
use crate::query::{LeafTriangles, Traverse, Visitor};

/// A mesh with its [`Grid`], owning every buffer: the mesh copy, the cell offsets and
/// references (sized by [`Grid::measure`]) and the triangles packed per reference, which
/// queries read. Answers every query of [`MeshQuery`](crate::query::MeshQuery), exactly as the
/// grid over the mesh does.
#[derive(Clone, Debug)]
pub struct MeshGrid {
    pub(super) scene: CellScene,
    pub(super) layout: GridLayout,
    pub(super) offsets: Vec<u32>,
    pub(super) items: Vec<u32>,
    pub(super) config: GridConfig,
}

impl MeshGrid {
    /// Copies `mesh` and builds its grid with `config` at full resolution.
    ///
    /// # Errors
    /// [`BuildError::InvalidConfig`] for a config out of range.
    pub fn build(mesh: &ValidMesh<'_>, config: &GridConfig) -> Result<Self, BuildError> {
        let mut scene = CellScene::copy(mesh);
        let sizes = Grid::measure(mesh, config)?;
        let (mut offsets, mut items) = (vec![0u32; sizes.offsets], vec![0u32; sizes.items]);
        let layout = *Grid::build(&scene.mesh(), config, &mut offsets, &mut items)?.layout();
        scene.pack(&items)?;
        Ok(Self {
            scene,
            layout,
            offsets,
            items,
            config: *config,
        })
    }

    /// The grid over [`MeshGrid::mesh`].
    #[must_use]
    pub fn grid(&self) -> Grid<&[u32]> {
        Grid::from_validated(self.layout, &self.offsets, &self.items)
    }

    /// The mesh.
    #[must_use]
    pub fn mesh(&self) -> ValidMesh<'_> {
        self.scene.mesh()
    }

    /// The config it was built with.
    #[must_use]
    pub const fn config(&self) -> &GridConfig {
        &self.config
    }

    /// Cells, references, empty cells.
    #[must_use]
    pub fn stats(&self) -> CellStats {
        self.grid().stats(self.scene.triangles.len())
    }

    /// Bytes of the structure's own arrays (offsets and references; not the mesh or the packed
    /// triangles).
    #[must_use]
    pub fn structure_bytes(&self) -> usize {
        4 * (self.offsets.len() + self.items.len())
    }

    /// Bytes of the packed triangles (36 per reference).
    #[must_use]
    pub fn packed_bytes(&self) -> usize {
        self.scene.packed_bytes()
    }
}

impl Traverse for MeshGrid {
    #[inline(always)]
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        self.grid().traverse(visitor);
    }
}

impl LeafTriangles for MeshGrid {
    #[inline(always)]
    fn corners(&self, slot: usize, tri: u32) -> Option<Triangle> {
        self.scene.corners(slot, tri)
    }

    #[inline(always)]
    fn run(&self, first: usize, count: usize) -> Option<&[PackedTriangle]> {
        self.scene.run(first, count)
    }
}
