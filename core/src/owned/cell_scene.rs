//! What the owned cell structures share: the mesh copy, the packed references, and sizing a
//! tree by measuring until complete.

use alloc::vec;
use alloc::vec::Vec;

use crate::cells::pack::pack_references;
use crate::cells::{REFERENCES_PER_TRIANGLE, TreeSizes};
use crate::error::BuildError;
use crate::math::{PackedTriangle, Triangle};
use crate::mesh::ValidMesh;
use crate::query::LeafTriangles;

/// A mesh copy and its triangles packed in a cell structure's reference order.
#[derive(Clone, Debug)]
pub(super) struct CellScene {
    pub(super) positions: Vec<[f32; 3]>,
    pub(super) triangles: Vec<[u32; 3]>,
    pub(super) packed: Vec<PackedTriangle>,
}

impl CellScene {
    /// Copies `mesh` (packing comes later, once the references are known).
    pub(super) fn copy(mesh: &ValidMesh<'_>) -> Self {
        Self {
            positions: mesh.positions().to_vec(),
            triangles: mesh.triangles().to_vec(),
            packed: Vec::new(),
        }
    }

    /// The mesh copy.
    pub(super) fn mesh(&self) -> ValidMesh<'_> {
        // Copied from a validated mesh and never changed.
        ValidMesh::new_unchecked_by_validate(&self.positions, &self.triangles)
    }

    /// Bytes of the packed triangles.
    pub(super) fn packed_bytes(&self) -> usize {
        core::mem::size_of_val(self.packed.as_slice())
    }

    /// Packs the triangles of `items`, in their order.
    pub(super) fn pack(&mut self, items: &[u32]) -> Result<(), BuildError> {
        let mut packed = vec![PackedTriangle::EMPTY; items.len()];
        pack_references(&self.mesh(), items, &mut packed)?;
        self.packed = packed;
        Ok(())
    }
}

impl LeafTriangles for CellScene {
    #[inline(always)]
    fn corners(&self, slot: usize, tri: u32) -> Option<Triangle> {
        self.packed.as_slice().corners(slot, tri)
    }

    #[inline(always)]
    fn run(&self, first: usize, count: usize) -> Option<&[PackedTriangle]> {
        self.packed.as_slice().run(first, count)
    }
}

/// Measures a tree with a work buffer of [`REFERENCES_PER_TRIANGLE`] references per
/// triangle: the tree the config describes when that is room enough (as every ordinary mesh
/// needs), else the tree that room allows, whose remaining cells stay leaves. One pass, whose
/// buffer is freed before the build.
pub(super) fn measure_fully(
    triangles: usize,
    measure: impl Fn(&mut [u32]) -> Result<TreeSizes, BuildError>,
) -> Result<TreeSizes, BuildError> {
    measure(&mut vec![0; work_room(triangles)])
}

/// The references buffer a tree over `triangles` triangles is measured and built with:
/// [`REFERENCES_PER_TRIANGLE`] per triangle (at most what `u32` addresses).
pub(super) fn work_room(triangles: usize) -> usize {
    triangles
        .max(1)
        .saturating_mul(REFERENCES_PER_TRIANGLE)
        .min(u32::MAX as usize)
}

/// The nodes a tree over `triangles` triangles is first built into: eight per triangle, where
/// the bundled meshes' k-d trees take up to 4.7 (fandisk's); a build that needs more is
/// measured first.
pub(super) fn node_room(triangles: usize) -> usize {
    triangles.saturating_mul(8).saturating_add(64)
}
