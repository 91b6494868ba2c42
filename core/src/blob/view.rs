//! Loading a blob: every check once, then queries straight from the bytes.

use glam::Vec3;

use super::checksum::mesh_checksum;
use super::encode::blob_checksum;
use super::format::{
    MeshLayout, NODE_BYTES, ORDER_BYTES, PACKED_BYTES, POSITION_BYTES, TRIANGLE_BYTES,
};
use super::mesh::{check_indexed, check_packed};
use super::reader::Reader;
use super::{BlobHeader, BlobMesh, BlobTree};
use crate::bvh::TreeArrays;
use crate::bvh::check::{CheckLevel, Extent, check};
use crate::error::{BlobError, BlobSection};
use crate::math::{Aabb, PackedTriangle, Triangle};
use crate::mesh::ValidMesh;
use crate::query::{LeafTriangles, Traverse, Visitor};

/// A validated blob, queried in place: nodes, order and (unless omitted) the mesh are read from
/// the byte slice on demand — a blob in flash is never copied into RAM.
///
/// Made only by [`BlobView::parse`] or [`BlobView::parse_with_mesh`], which check everything
/// once (magic, version, structure kind, every count against the byte length, the checksum,
/// every child index and leaf range, the depth, finite nested boxes, the mesh), so no query on a
/// view can read out of bounds, loop forever or panic.
///
/// A view is a structure and its triangles at once, so it answers every query of
/// [`MeshQuery`](crate::query::MeshQuery) (`view.raycast(&ray)`, batches, overlaps) and runs
/// custom visitors ([`Traverse`]), exactly as the in-memory [`Bvh`](crate::bvh::Bvh) it was
/// encoded from does with its mesh, bit for bit.
#[derive(Clone, Copy, Debug)]
pub struct BlobView<'a> {
    pub(super) header: BlobHeader,
    pub(super) tree: BlobTree<'a>,
    pub(super) mesh: BlobMesh<'a>,
}

/// The arrays of a blob, split out and counted but not yet validated.
struct Sections<'a> {
    header: BlobHeader,
    tree: BlobTree<'a>,
    mesh: Option<BlobMesh<'a>>,
}

impl<'a> BlobView<'a> {
    /// Validates a self-contained blob ([`MeshLayout::Indexed`] or [`MeshLayout::Packed`]) and
    /// returns a view over it. Costs one pass over the bytes (checksum) and one over the tree.
    ///
    /// # Errors
    /// The first problem found, as a [`BlobError`] saying where; [`BlobError::MeshNotIncluded`]
    /// for a blob baked without its mesh.
    pub fn parse(bytes: &'a [u8]) -> Result<Self, BlobError> {
        let s = sections(bytes)?;
        let mesh = s.mesh.ok_or(BlobError::MeshNotIncluded)?;
        finish(s.header, s.tree, mesh)
    }

    /// Validates a blob against `mesh`, the mesh it was baked from, and returns a view whose
    /// queries read triangles from `mesh` (nodes and order still come from the bytes). Needed for
    /// a blob baked with [`MeshLayout::Omitted`]; allowed for any blob.
    ///
    /// # Errors
    /// As [`BlobView::parse`], and [`BlobError::MeshMismatch`] when `mesh` has other counts or
    /// another [`mesh_checksum`](super::mesh_checksum) than the blob records.
    pub fn parse_with_mesh(bytes: &'a [u8], mesh: ValidMesh<'a>) -> Result<Self, BlobError> {
        let s = sections(bytes)?;
        let same = mesh.triangle_count() == s.header.triangle_count as usize
            && mesh.vertex_count() == s.header.vertex_count as usize
            && mesh_checksum(&mesh) == s.header.mesh_checksum;
        if !same {
            return Err(BlobError::MeshMismatch);
        }
        finish(s.header, s.tree, BlobMesh::External(mesh))
    }

    /// The header.
    #[must_use]
    pub const fn header(&self) -> &BlobHeader {
        &self.header
    }

    /// The tree, read in place (a [`TreeArrays`] structure).
    #[must_use]
    pub const fn tree(&self) -> &BlobTree<'a> {
        &self.tree
    }

    /// The triangles queries read.
    #[must_use]
    pub const fn mesh(&self) -> &BlobMesh<'a> {
        &self.mesh
    }

    /// The root's padded box ([`Aabb::EMPTY`] for an empty mesh).
    #[must_use]
    pub const fn bounds(&self) -> Aabb {
        self.header.bounds
    }
}

impl Traverse for BlobView<'_> {
    /// Walks the tree in place, as [`Bvh`](crate::bvh::Bvh) walks its slices.
    #[inline(always)]
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        self.tree.traverse(visitor);
    }
}

impl LeafTriangles for BlobView<'_> {
    #[inline(always)]
    fn corners(&self, slot: usize, tri: u32) -> Option<Triangle> {
        self.mesh.corners(slot, tri)
    }

    #[inline(always)]
    fn run(&self, first: usize, count: usize) -> Option<&[PackedTriangle]> {
        self.mesh.run(first, count)
    }
}

/// Header, checksum, then each array counted against the header and cut out of the bytes.
fn sections(bytes: &[u8]) -> Result<Sections<'_>, BlobError> {
    let header = BlobHeader::read(bytes)?;
    if bytes.len() < header.total_len {
        return Err(BlobError::Truncated {
            offset: bytes.len(),
            section: BlobSection::Nodes,
        });
    }
    if bytes.len() > header.total_len {
        return Err(BlobError::TrailingBytes {
            offset: header.total_len,
        });
    }
    let computed = blob_checksum(bytes, header.header_len);
    if computed != header.checksum {
        return Err(BlobError::ChecksumMismatch {
            stored: header.checksum,
            computed,
        });
    }
    let mut r = Reader::new(bytes);
    r.bytes(header.header_len, BlobSection::Header)?;
    let nodes = r.records::<NODE_BYTES>(header.node_count, BlobSection::Nodes)?;
    let order = r.records::<ORDER_BYTES>(header.triangle_count, BlobSection::Order)?;
    let layout_at = r.offset();
    let tag: u32 = r.value(BlobSection::MeshLayout)?;
    if tag != header.mesh.tag() {
        return Err(BlobError::Malformed {
            offset: layout_at,
            section: BlobSection::MeshLayout,
        });
    }
    let mesh = match header.mesh {
        MeshLayout::Indexed => Some(BlobMesh::Indexed {
            positions: r.records::<POSITION_BYTES>(header.vertex_count, BlobSection::Positions)?,
            triangles: r
                .records::<TRIANGLE_BYTES>(header.triangle_count, BlobSection::Triangles)?,
        }),
        MeshLayout::Packed => Some(BlobMesh::Packed {
            corners: r
                .records::<PACKED_BYTES>(header.triangle_count, BlobSection::PackedTriangles)?,
        }),
        MeshLayout::Omitted => None,
    };
    if !r.rest().is_empty() {
        return Err(BlobError::TrailingBytes { offset: r.offset() });
    }
    Ok(Sections {
        header,
        tree: BlobTree {
            nodes,
            order,
            depth: 0,
        },
        mesh,
    })
}

/// Validates the mesh, then the tree against it and the header; returns the view.
fn finish<'a>(
    header: BlobHeader,
    mut tree: BlobTree<'a>,
    mesh: BlobMesh<'a>,
) -> Result<BlobView<'a>, BlobError> {
    match mesh {
        BlobMesh::Indexed {
            positions,
            triangles,
        } => check_indexed(positions, triangles)?,
        BlobMesh::Packed { corners } => check_packed(corners)?,
        BlobMesh::External(_) => {}
    }
    tree.depth = check_tree(&header, &tree, Some(&mesh))?;
    Ok(BlobView { header, tree, mesh })
}

/// Checks the tree (against `mesh` when given: triangle indices and containment) and that the
/// header's config, depth and bounds agree with it; returns the depth.
fn check_tree(
    header: &BlobHeader,
    tree: &BlobTree<'_>,
    mesh: Option<&BlobMesh<'_>>,
) -> Result<u32, BlobError> {
    header
        .config
        .check()
        .map_err(|_| BlobError::HeaderMismatch { field: "config" })?;
    let depth = check(tree, mesh, CheckLevel::Full, Extent::Exact)?.depth;
    if depth != header.depth {
        return Err(BlobError::HeaderMismatch { field: "depth" });
    }
    let root = tree.node(0).map_or(Aabb::EMPTY, |n| n.aabb());
    let bits = |v: Vec3| v.to_array().map(f32::to_bits);
    if bits(root.min) != bits(header.bounds.min) || bits(root.max) != bits(header.bounds.max) {
        return Err(BlobError::HeaderMismatch { field: "bounds" });
    }
    Ok(depth)
}

impl<'a> BlobTree<'a> {
    /// Validates the tree of any blob without its mesh — topology, leaf ranges, depth, finite
    /// nested boxes, every order entry below the triangle count, the checksum — and returns
    /// it with the header. For tools that inspect a blob, and for queries with a mesh held
    /// elsewhere (`tree.with(&mesh)`, which, as with a [`Bvh`](crate::bvh::Bvh), must be the
    /// mesh it was built from: another mesh gives meaningless answers, never a panic). Prefer
    /// [`BlobView::parse_with_mesh`], which checks the mesh too.
    ///
    /// # Errors
    /// As [`BlobView::parse`], except that a missing mesh is not an error.
    pub fn parse(bytes: &'a [u8]) -> Result<(BlobHeader, Self), BlobError> {
        let s = sections(bytes)?;
        let mut tree = s.tree;
        for (slot, id) in (0u32..).zip(tree.order) {
            let tri = u32::from_le_bytes(*id);
            if tri >= s.header.triangle_count {
                return Err(BlobError::OrderOutOfRange { slot, tri });
            }
        }
        tree.depth = check_tree(&s.header, &tree, None::<&BlobMesh<'_>>)?;
        Ok((s.header, tree))
    }
}
