//! Loading a BVH blob into owned buffers with its boxes checked on the decoded copy.
//!
//! [`BlobView::parse`] checks each leaf's triangles against its box by gathering them from the
//! blob's bytes through the indices, the dearest step of a load. A loader that decodes the
//! blob anyway can check the boxes afterwards, on the copy, whose triangles sit packed in leaf
//! order: the same checks in the same order over the same bits. [`BoxesUnchecked`] is the blob
//! with every other check done. A loader that finds any problem on this path starts again
//! with [`BlobView::parse`], so its errors are exactly the ones `parse` reports.

use glam::Vec3;

use super::split_check::{check_repeated_corners, check_slots};
use super::view::{RawStructure, check_mesh, same_bounds, sections};
use super::{BlobHeader, BlobMesh, BlobStructure, BlobView};
use crate::bvh::TreeArrays;
use crate::bvh::check::{CheckLevel, Extent, check};
use crate::error::BlobError;
use crate::math::{Aabb, Triangle};
use crate::query::LeafTriangles;
use crate::structure_kind::StructureKind;

/// A self-contained BVH blob whose every check has passed except the boxes (finite, nested,
/// holding their triangles), the collapse roles, which the collapse of the decoded tree checks
/// as it walks them, and (without split references) the fingerprint of the order, which the
/// decoded order's exact count replaces. Only for decoding into buffers that are then checked
/// in full.
pub(crate) struct BoxesUnchecked<'a>(BlobView<'a>);

impl<'a> BoxesUnchecked<'a> {
    /// [`BlobView::parse`] without the box checks, for BVH blobs that store their mesh.
    ///
    /// # Errors
    /// A problem found (not necessarily the one `parse` reports first), or
    /// [`BlobError::UnsupportedStructure`] for another kind, before the checksum is computed.
    pub(crate) fn parse(bytes: &'a [u8]) -> Result<Self, BlobError> {
        let kind = BlobHeader::read(bytes)?.kind;
        if kind != StructureKind::Bvh {
            return Err(BlobError::UnsupportedStructure { kind: kind.tag() });
        }
        let s = sections(bytes)?;
        let mesh = s.mesh.ok_or(BlobError::MeshNotIncluded)?;
        check_mesh(&mesh)?;
        let RawStructure::Bvh(mut tree) = s.structure else {
            return Err(BlobError::UnsupportedStructure { kind: kind.tag() });
        };
        let header = s.header;
        if header.config.bvh().is_none_or(|c| c.check().is_err()) {
            return Err(BlobError::HeaderMismatch { field: "config" });
        }
        let in_range = InRange::of(&mesh);
        tree.depth = check(&tree, Some(&in_range), CheckLevel::Topology, Extent::Exact)?.depth;
        // Without split references the loader's exact count of every triangle's slots
        // (`RepeatedTriangle`) comes next and covers this fingerprint of the order; with them
        // this also checks the table itself.
        if !tree.split_refs().is_empty() {
            check_slots(&tree, tree.order_entries(), header.triangle_count as usize)?;
        }
        check_repeated_corners(&tree, Some(&mesh))?;
        same_bounds(
            &tree.node(0).map_or(Aabb::EMPTY, |n| n.aabb()),
            &header.bounds,
        )?;
        if tree.depth != header.depth {
            return Err(BlobError::HeaderMismatch { field: "depth" });
        }
        Ok(Self(BlobView {
            header,
            structure: BlobStructure::Bvh(tree),
            mesh,
        }))
    }

    /// The view, to decode from. Its boxes are unchecked: check the decoded tree in full
    /// before it answers anything.
    pub(crate) const fn view(&self) -> &BlobView<'a> {
        &self.0
    }
}

/// A stand-in for a blob's mesh in the topology check: it has a triangle exactly where the
/// mesh has one (the mesh's own indices were checked already), with no corners worth reading.
struct InRange {
    triangles: usize,
    slots: usize,
}

impl InRange {
    fn of(mesh: &BlobMesh<'_>) -> Self {
        let slots = match mesh {
            // Packed corners are found by slot as well as named by triangle.
            BlobMesh::Packed { corners } => corners.len(),
            BlobMesh::Indexed { .. } | BlobMesh::External(_) => usize::MAX,
        };
        Self {
            triangles: mesh.triangle_count(),
            slots,
        }
    }
}

impl LeafTriangles for InRange {
    fn corners(&self, slot: usize, tri: u32) -> Option<Triangle> {
        ((tri as usize) < self.triangles && slot < self.slots).then_some(Triangle::new(
            Vec3::ZERO,
            Vec3::ZERO,
            Vec3::ZERO,
        ))
    }
}
