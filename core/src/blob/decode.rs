//! Copying a validated blob's arrays into caller slices, for the fastest queries from RAM.

use super::format::{f32x3_from_bytes, node_from_bytes, u32x3_from_bytes};
use super::{BlobMesh, BlobView};
use crate::bvh::{Bvh, BvhNode, TreeArrays};
use crate::error::{BlobError, BlobSection};
use crate::math::PackedTriangle;
use crate::mesh::{MeshRef, ValidMesh};
use crate::query::{LeafTriangles, PackedTriangles};

/// The BVH of a BVH view; other kinds have no order to decode.
fn bvh_tree<'v, 'a>(view: &'v BlobView<'a>) -> Result<&'v super::BlobTree<'a>, BlobError> {
    view.tree().ok_or(BlobError::UnsupportedStructure {
        kind: view.header.kind.tag(),
    })
}

fn too_small(section: BlobSection, needed: usize, got: usize) -> BlobError {
    BlobError::BufferTooSmall {
        section,
        needed,
        got,
    }
}

impl<'a> BlobView<'a> {
    /// Copies the tree into `nodes` (at least [`BlobHeader::node_count`](super::BlobHeader)
    /// entries) and `order` (at least [`BlobHeader::reference_count`](super::BlobHeader)
    /// entries: the triangle count, more with spatial splits) and returns the in-memory
    /// [`Bvh`], which answers exactly as the view does, usually faster; a tree with spatial
    /// splits reads its split references from the blob's bytes. No re-validation: the view
    /// was validated at load and the copy is exact.
    ///
    /// # Errors
    /// [`BlobError::BufferTooSmall`] (nothing written); [`BlobError::UnsupportedStructure`]
    /// for a blob of another kind.
    pub fn decode_tree<'n>(
        &self,
        nodes: &'n mut [BvhNode],
        order: &'n mut [u32],
    ) -> Result<Bvh<'n>, BlobError>
    where
        'a: 'n,
    {
        let tree = bvh_tree(self)?;
        let (n, m) = (tree.nodes.len(), tree.order.len());
        if nodes.len() < n {
            return Err(too_small(BlobSection::Nodes, n, nodes.len()));
        }
        if order.len() < m {
            return Err(too_small(BlobSection::Order, m, order.len()));
        }
        for (out, b) in nodes.iter_mut().zip(tree.nodes) {
            *out = node_from_bytes(b);
        }
        for (out, b) in order.iter_mut().zip(tree.order) {
            *out = u32::from_le_bytes(*b);
        }
        let nodes: &'n [BvhNode] = nodes;
        let order: &'n [u32] = order;
        Ok(Bvh::from_validated(
            nodes.get(..n).unwrap_or_default(),
            order.get(..m).unwrap_or_default(),
            tree.depth,
        )
        .with_split_refs(tree.split_table()))
    }

    /// Copies an indexed mesh (stored, or the caller's) into `positions` and `triangles` and
    /// returns it validated.
    ///
    /// # Errors
    /// [`BlobError::MeshNotIncluded`] for a packed blob (it stores corners, not the indexed
    /// mesh); [`BlobError::BufferTooSmall`] (nothing written).
    pub fn decode_mesh<'m>(
        &self,
        positions: &'m mut [[f32; 3]],
        triangles: &'m mut [[u32; 3]],
    ) -> Result<ValidMesh<'m>, BlobError> {
        let (nv, nt) = self.copy_mesh(positions, triangles)?;
        let positions: &'m [[f32; 3]] = positions;
        let triangles: &'m [[u32; 3]] = triangles;
        Ok(MeshRef::new(
            positions.get(..nv).unwrap_or_default(),
            triangles.get(..nt).unwrap_or_default(),
        )
        .validate()?)
    }

    /// [`decode_mesh`](Self::decode_mesh)'s copy alone, for a loader that keeps the arrays:
    /// the view checked the mesh already. Returns the vertex and triangle counts.
    pub(crate) fn copy_mesh(
        &self,
        positions: &mut [[f32; 3]],
        triangles: &mut [[u32; 3]],
    ) -> Result<(usize, usize), BlobError> {
        let (nv, nt) = (
            self.header.vertex_count as usize,
            self.header.triangle_count as usize,
        );
        if matches!(self.mesh, BlobMesh::Packed { .. }) {
            return Err(BlobError::MeshNotIncluded);
        }
        if positions.len() < nv {
            return Err(too_small(BlobSection::Positions, nv, positions.len()));
        }
        if triangles.len() < nt {
            return Err(too_small(BlobSection::Triangles, nt, triangles.len()));
        }
        match self.mesh {
            BlobMesh::Indexed {
                positions: p,
                triangles: t,
            } => {
                for (out, b) in positions.iter_mut().zip(p) {
                    *out = f32x3_from_bytes(b);
                }
                for (out, b) in triangles.iter_mut().zip(t) {
                    *out = u32x3_from_bytes(b);
                }
            }
            BlobMesh::External(m) => {
                for (out, p) in positions.iter_mut().zip(m.positions()) {
                    *out = *p;
                }
                for (out, t) in triangles.iter_mut().zip(m.triangles()) {
                    *out = *t;
                }
            }
            BlobMesh::Packed { .. } => return Err(BlobError::MeshNotIncluded),
        }
        Ok((nv, nt))
    }

    /// Copies every triangle's corners in leaf order into `out` (from the packed copy, or
    /// gathered from an indexed mesh) and returns them for queries on the
    /// [`decode_tree`](Self::decode_tree) result.
    ///
    /// # Errors
    /// [`BlobError::BufferTooSmall`] (nothing written); [`BlobError::UnsupportedStructure`]
    /// for a blob of another kind.
    pub fn decode_packed<'p>(
        &self,
        out: &'p mut [PackedTriangle],
    ) -> Result<PackedTriangles<'p>, BlobError> {
        let tree = bvh_tree(self)?;
        let n = tree.slot_count();
        if out.len() < n {
            return Err(too_small(BlobSection::PackedTriangles, n, out.len()));
        }
        for (slot, (dst, id)) in out.iter_mut().zip(tree.order).enumerate() {
            if let Some(t) = self.mesh.corners(slot, u32::from_le_bytes(*id)) {
                *dst = PackedTriangle::new(&t);
            }
        }
        let out: &'p [PackedTriangle] = out;
        Ok(PackedTriangles::new(out.get(..n).unwrap_or_default()))
    }
}
