//! [`MeshGrid`]: a mesh and its uniform grid, in buffers it owns.

use alloc::vec;
use alloc::vec::Vec;

use super::cell_scene::CellScene;
use crate::cells::{CellStats, ReferencePad};
use crate::error::{BufferKind, BuildError};
use crate::grid::{Grid, GridConfig, GridLayout, for_each_cell};
use crate::math::{PackedTriangle, Triangle};
use crate::mesh::ValidMesh;
use crate::query::{LeafTriangles, Traverse, Visitor};

/// A mesh with its [`Grid`], owning every buffer: the mesh copy, the cell offsets and
/// references (exactly what [`Grid::build`] writes into buffers of the lengths
/// [`Grid::measure`] gives) and the triangles packed per reference, which
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
        config.validate()?;
        let mut scene = CellScene::copy(mesh);
        let layout = GridLayout::for_triangles(
            mesh.bounds(),
            mesh.triangle_count(),
            config.cells_per_triangle,
            config.max_resolution,
        );
        let (offsets, items) = fill_in_one_pass(&layout, &scene.mesh())?;
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

/// The cell offsets and references of `layout` over `mesh`: what [`Grid::build`] writes given
/// buffers of exactly the measured lengths, found with one pass of triangle–cell tests instead
/// of three (measure, count, fill) by keeping each reference's cell.
fn fill_in_one_pass(
    layout: &GridLayout,
    mesh: &ValidMesh<'_>,
) -> Result<(Vec<u32>, Vec<u32>), BuildError> {
    // Offsets and references are `u32`s: past that, say which array cannot hold them (a
    // resolution within `MAX_RESOLUTION` never needs that many cells).
    let too_many = |buffer, needed| BuildError::BufferTooSmall {
        buffer,
        needed,
        got: u32::MAX as usize,
    };
    let cells = layout
        .cell_count()
        .filter(|&c| c < u32::MAX as usize)
        .ok_or(too_many(BufferKind::CellOffsets, usize::MAX))?;
    let pad = ReferencePad::of(&layout.bounds);
    // Each reference's cell, triangle by triangle; `ends[t]` is where triangle t's stop.
    let mut cell_of = Vec::with_capacity(mesh.triangle_count() * 2);
    let mut ends = Vec::with_capacity(mesh.triangle_count());
    let mut offsets = vec![0u32; cells + 1];
    for tri in 0..mesh.triangle_count() as u32 {
        for_each_cell(layout, pad, mesh, tri, |c| {
            cell_of.push(c as u32);
            if let Some(o) = offsets.get_mut(c + 1) {
                *o += 1;
            }
        });
        ends.push(cell_of.len());
    }
    if cell_of.len() > u32::MAX as usize {
        return Err(too_many(BufferKind::References, cell_of.len()));
    }
    let mut sum = 0u32;
    for o in &mut offsets {
        sum += *o;
        *o = sum;
    }
    // A counting sort, triangles ascending within each cell: `next[c]` is where cell c's next
    // reference goes.
    let mut next = offsets.clone();
    let mut items = vec![0u32; cell_of.len()];
    let mut start = 0usize;
    for (tri, &end) in (0u32..).zip(&ends) {
        for &c in cell_of.get(start..end).unwrap_or_default() {
            if let Some(at) = next.get_mut(c as usize) {
                if let Some(slot) = items.get_mut(*at as usize) {
                    *slot = tri;
                }
                *at += 1;
            }
        }
        start = end;
    }
    Ok((offsets, items))
}
