//! [`MeshBvh`] to and from blobs (features `alloc` and `blob`).

use alloc::vec;
use alloc::vec::Vec;

use super::MeshBvh;
use crate::blob::{self, BlobView, EncodeOptions, MeshLayout};
use crate::bvh::BvhNode;
use crate::error::{BlobError, BlobSection};
use crate::math::PackedTriangle;
use crate::mesh::ValidMesh;

impl MeshBvh {
    /// Validates a self-contained blob once ([`BlobView::parse`]) and decodes it into owned
    /// buffers, so it queries as a built one does and answers the same, bit for bit. The
    /// config is the one the blob records.
    ///
    /// A blob baked with [`MeshLayout::Packed`] stores corners, not the indexed mesh: the mesh
    /// becomes three vertices of its own per triangle, in triangle order (same triangles,
    /// same indices, same answers).
    ///
    /// # Errors
    /// What [`BlobView::parse`] reports ([`BlobError::MeshNotIncluded`] for a blob baked
    /// without its mesh: use [`MeshBvh::from_blob_with_mesh`]), and
    /// [`BlobError::RepeatedTriangle`] for an order that names a triangle twice.
    pub fn from_blob(bytes: &[u8]) -> Result<Self, BlobError> {
        Self::decode(&BlobView::parse(bytes)?)
    }

    /// [`MeshBvh::from_blob`] for any blob, with the mesh it was baked from
    /// ([`BlobView::parse_with_mesh`]): needed for a blob baked without its mesh.
    ///
    /// # Errors
    /// What [`BlobView::parse_with_mesh`] reports, and [`BlobError::RepeatedTriangle`].
    pub fn from_blob_with_mesh(bytes: &[u8], mesh: &ValidMesh<'_>) -> Result<Self, BlobError> {
        Self::decode(&BlobView::parse_with_mesh(bytes, *mesh)?)
    }

    pub(super) fn decode(view: &BlobView<'_>) -> Result<Self, BlobError> {
        let header = *view.header();
        let config = *header.config.bvh().ok_or(BlobError::UnsupportedStructure {
            kind: header.kind.tag(),
        })?;
        let (n, v) = (header.triangle_count as usize, header.vertex_count as usize);
        let mut nodes = vec![BvhNode::EMPTY; header.node_count as usize];
        let mut order = vec![0u32; n];
        let depth = view.decode_tree(&mut nodes, &mut order)?.depth();
        check_permutation(&order)?;
        let (positions, triangles) = if header.mesh == MeshLayout::Packed {
            // Three vertices of its own per triangle: their indices must fit in `u32`.
            if header.triangle_count > u32::MAX / 3 {
                return Err(BlobError::TooLarge);
            }
            let mut packed = vec![PackedTriangle::EMPTY; n];
            view.decode_packed(&mut packed)?;
            unshared_mesh(n, &order, &packed)
        } else {
            let mut positions = vec![[0.0f32; 3]; v];
            let mut triangles = vec![[0u32; 3]; n];
            view.decode_mesh(&mut positions, &mut triangles)?;
            (positions, triangles)
        };
        Self::assemble(positions, triangles, nodes, order, depth, config).map_err(|_| {
            // Unreachable: the buffers are sized from the validated blob's own counts.
            BlobError::BufferTooSmall {
                section: BlobSection::PackedTriangles,
                needed: n,
                got: 0,
            }
        })
    }

    /// The exact size of [`MeshBvh::to_blob`]'s output for `layout`.
    ///
    /// # Errors
    /// [`BlobError::TooLarge`] when a count does not fit the format.
    pub fn encoded_len(&self, layout: MeshLayout) -> Result<usize, BlobError> {
        blob::encoded_len(&self.bvh(), &self.mesh(), &self.encode_options(layout))
    }

    /// Encodes the tree and (as `layout` says) the mesh as a blob, with this tree's config in
    /// its header: the bytes [`blob::encode_into`] writes, which depend only on the mesh, the
    /// tree and the layout, on every target.
    ///
    /// # Errors
    /// What [`blob::encode_into`] reports.
    pub fn to_blob(&self, layout: MeshLayout) -> Result<Vec<u8>, BlobError> {
        let options = self.encode_options(layout);
        let (bvh, mesh) = (self.bvh(), self.mesh());
        let mut out = vec![0u8; blob::encoded_len(&bvh, &mesh, &options)?];
        let n = blob::encode_into(&bvh, &mesh, &options, &mut out)?;
        out.truncate(n);
        Ok(out)
    }

    fn encode_options(&self, layout: MeshLayout) -> EncodeOptions {
        EncodeOptions {
            mesh: layout,
            config: self.config,
        }
    }
}

/// Refuses an order that names a triangle twice (the validated view bounds every entry by the
/// triangle count, so with as many slots as triangles each one then appears exactly once).
fn check_permutation(order: &[u32]) -> Result<(), BlobError> {
    let mut seen = vec![false; order.len()];
    for (slot, &tri) in (0u32..).zip(order) {
        match seen.get_mut(tri as usize) {
            Some(s) if !*s => *s = true,
            _ => return Err(BlobError::RepeatedTriangle { slot, tri }),
        }
    }
    Ok(())
}

/// Positions and triangles of `triangles` triangles given by slot (`packed[slot]` is triangle
/// `order[slot]`; a BVH's leaf order, or a cell structure's references, where a triangle may
/// appear several times with the same corners): three vertices of their own per triangle, in
/// triangle order. A triangle no slot names (none does in a validated structure) sits at the
/// origin. The caller makes sure `3 · triangles` fits in `u32`.
pub(super) fn unshared_mesh(
    triangles: usize,
    order: &[u32],
    packed: &[PackedTriangle],
) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let mut positions = vec![[0.0f32; 3]; 3 * triangles];
    for (&tri, corners) in order.iter().zip(packed) {
        let at = 3 * tri as usize;
        if let Some(out) = positions.get_mut(at..at + 3) {
            out.copy_from_slice(&[corners.a, corners.b, corners.c]);
        }
    }
    let triangles = (0u32..)
        .step_by(3)
        .take(triangles)
        .map(|v| [v, v + 1, v + 2])
        .collect();
    (positions, triangles)
}
