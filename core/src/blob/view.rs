//! Loading a blob: every check once, then queries straight from the bytes.

use glam::Vec3;

use super::checksum::mesh_checksum;
use super::encode::blob_checksum;
use super::format::{
    MeshLayout, NODE_BYTES, ORDER_BYTES, PACKED_BYTES, PLANNED_VERSION, POSITION_BYTES,
    SPATIAL_VERSION, TRIANGLE_BYTES, WINDING_BYTES, WINDING_VERSION,
};
use super::mesh::{check_indexed, check_packed};
#[cfg(feature = "blob-cells")]
use super::order_check::MultisetFingerprint;
use super::reader::Reader;
use super::split_check::{check_repeated_corners, check_slots};
#[cfg(feature = "blob-cells")]
use super::structure_config::StructureConfig;
use super::{BlobHeader, BlobMesh, BlobStructure, BlobTree};
use crate::advanced::CollapseRoles;
use crate::bvh::TreeArrays;
use crate::bvh::check::{Extent, Shape, check_boxes_last};
use crate::bvh::split_coverage::check_split_coverage;
use crate::cells::LeWords;
#[cfg(feature = "blob-cells")]
use crate::cells::{Coverage, CoverageMesh, ReferencePad};
use crate::error::StructureError;
use crate::error::{BlobError, BlobSection};
#[cfg(feature = "blob-cells")]
use crate::grid::{Grid, GridLayout};
#[cfg(feature = "blob-cells")]
use crate::kdtree::KdTree;
use crate::math::{Aabb, PackedTriangle, Triangle};
use crate::mesh::ValidMesh;
#[cfg(feature = "blob-cells")]
use crate::octree::Octree;
use crate::query::split_refs::SPLIT_REF_BYTES;
use crate::query::{LeafTriangles, Traverse, Visitor};
use crate::structure_kind::StructureKind;

/// A validated blob of any structure kind, queried in place: nodes, references and (unless
/// omitted) the mesh are read from the byte slice on demand — a blob in flash is never copied
/// into RAM.
///
/// Made only by [`BlobView::parse`] or [`BlobView::parse_with_mesh`], which check everything
/// once (magic, version, structure kind, every count against the byte length, the checksum,
/// every child index and leaf range, the depth, finite nested boxes, the mesh), so no query on a
/// view can read out of bounds, loop forever or panic.
///
/// A view is a structure and its triangles at once, so it answers every query of
/// [`MeshQuery`](crate::query::MeshQuery) (`view.raycast(&ray)`, batches, overlaps) and runs
/// custom visitors ([`Traverse`]), exactly as the in-memory structure it was encoded from
/// does with its mesh, bit for bit.
#[derive(Clone, Copy, Debug)]
pub struct BlobView<'a> {
    pub(super) header: BlobHeader,
    pub(super) structure: BlobStructure<'a>,
    pub(super) mesh: BlobMesh<'a>,
}

/// A structure's arrays, cut out of the bytes and counted but not yet validated.
pub(super) enum RawStructure<'a> {
    Bvh(BlobTree<'a>),
    /// Node words (k-d tree, octree) or cell offsets (grid), then references.
    #[cfg_attr(not(feature = "blob-cells"), allow(dead_code))]
    Cells(LeWords<'a>, LeWords<'a>),
}

/// The arrays of a blob, split out and counted but not yet validated.
pub(super) struct Sections<'a> {
    pub(super) header: BlobHeader,
    pub(super) structure: RawStructure<'a>,
    pub(super) mesh: Option<BlobMesh<'a>>,
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
        finish(s.header, s.structure, mesh)
    }

    /// Validates a blob against `mesh`, the mesh it was baked from, and returns a view whose
    /// queries read triangles from `mesh` (nodes and order still come from the bytes). Needed for
    /// a blob baked with [`MeshLayout::Omitted`]; allowed for any blob.
    ///
    /// # Errors
    /// As [`BlobView::parse`], and [`BlobError::MeshMismatch`] when `mesh` has other counts or
    /// another [`mesh_checksum`](crate::advanced::mesh_checksum) than the blob records.
    pub fn parse_with_mesh(bytes: &'a [u8], mesh: ValidMesh<'a>) -> Result<Self, BlobError> {
        let s = sections(bytes)?;
        let same = mesh.triangle_count() == s.header.triangle_count as usize
            && mesh.vertex_count() == s.header.vertex_count as usize
            && mesh_checksum(&mesh) == s.header.mesh_checksum;
        if !same {
            return Err(BlobError::MeshMismatch);
        }
        finish(s.header, s.structure, BlobMesh::External(mesh))
    }

    /// The header.
    #[must_use]
    pub const fn header(&self) -> &BlobHeader {
        &self.header
    }

    /// The structure, read in place.
    #[must_use]
    pub const fn structure(&self) -> &BlobStructure<'a> {
        &self.structure
    }

    /// The BVH of a BVH blob, read in place (a [`TreeArrays`] structure); `None` for another
    /// kind.
    #[must_use]
    pub const fn tree(&self) -> Option<&BlobTree<'a>> {
        match &self.structure {
            BlobStructure::Bvh(t) => Some(t),
            #[cfg(feature = "blob-cells")]
            _ => None,
        }
    }

    /// The triangles queries read.
    #[must_use]
    pub const fn mesh(&self) -> &BlobMesh<'a> {
        &self.mesh
    }

    /// The root's box ([`BlobHeader::bounds`]).
    #[must_use]
    pub const fn bounds(&self) -> Aabb {
        self.header.bounds
    }
}

impl Traverse for BlobView<'_> {
    /// Walks the structure in place, as the in-memory one walks its slices.
    #[inline(always)]
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        self.structure.traverse(visitor);
    }

    #[inline(always)]
    fn split_refs(&self) -> crate::query::SplitRefs<'_> {
        self.structure.split_refs()
    }

    /// The header's root box ([`BlobView::bounds`]) and triangle count; `None` when the box
    /// is empty.
    #[inline(always)]
    fn batch_hint(&self) -> Option<crate::query::BatchHint> {
        let bounds = self.bounds();
        (!bounds.is_empty()).then_some(crate::query::BatchHint {
            bounds,
            triangles: self.header.triangle_count as usize,
        })
    }
}

impl crate::query::MeshQuery for BlobView<'_> {}

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
pub(super) fn sections(bytes: &[u8]) -> Result<Sections<'_>, BlobError> {
    let header = BlobHeader::read(bytes)?;
    let short = bytes.len() < header.total_len;
    if bytes.len() > header.total_len {
        return Err(BlobError::TrailingBytes {
            offset: header.total_len,
        });
    }
    if !short {
        let computed = blob_checksum(bytes, header.header_len);
        if computed != header.checksum {
            return Err(BlobError::ChecksumMismatch {
                stored: header.checksum,
                computed,
            });
        }
    }
    // A short blob is cut as far as it goes, so the error names the section where the bytes
    // run out.
    let result = cut(bytes, header);
    if short {
        return Err(match result {
            Err(e @ BlobError::Truncated { .. }) => e,
            _ => BlobError::Truncated {
                offset: bytes.len(),
                section: BlobSection::Header,
            },
        });
    }
    result
}

/// The sections of `bytes` as `header` lays them out, each counted against it. Inlined into
/// its one caller, which keeps the firmware's validation code as small as before it existed.
#[inline(always)]
fn cut(bytes: &[u8], header: BlobHeader) -> Result<Sections<'_>, BlobError> {
    let mut r = Reader::new(bytes);
    r.bytes(header.header_len, BlobSection::Header)?;
    let structure = if header.kind == StructureKind::Bvh {
        let nodes = r.records::<NODE_BYTES>(header.node_count, BlobSection::Nodes)?;
        let order = r.records::<ORDER_BYTES>(header.reference_count, BlobSection::Order)?;
        // Read (and, without the feature, found empty by the header reader) either way.
        #[cfg_attr(not(feature = "blob-spatial"), allow(unused_variables))]
        let splits = split_records(&header, &mut r)?;
        RawStructure::Bvh(BlobTree {
            nodes,
            order,
            depth: 0,
            #[cfg(feature = "blob-spatial")]
            splits,
            roles: role_bytes(&header, &mut r)?,
            // Cut either way (the counts must hold); kept only where they are read.
            winding: if cfg!(feature = "blob-winding") {
                winding_records(&header, &mut r)?
            } else {
                winding_records(&header, &mut r).map(|_| &[][..])?
            },
        })
    } else {
        cell_arrays(&header, &mut r)?
    };
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
                .records::<PACKED_BYTES>(header.reference_count, BlobSection::PackedTriangles)?,
        }),
        MeshLayout::Omitted => None,
    };
    if !r.rest().is_empty() {
        return Err(BlobError::TrailingBytes { offset: r.offset() });
    }
    Ok(Sections {
        header,
        structure,
        mesh,
    })
}

/// A BVH's split references, after the order from version 4 on (empty for a tree without
/// spatial splits; without the `blob-spatial` feature the header reader makes sure of that).
#[inline(always)]
fn split_records<'a>(
    header: &BlobHeader,
    r: &mut Reader<'a>,
) -> Result<&'a [[u8; SPLIT_REF_BYTES]], BlobError> {
    if header.version >= SPATIAL_VERSION {
        r.records::<SPLIT_REF_BYTES>(header.split_ref_count, BlobSection::SplitRefs)
    } else {
        Ok(&[])
    }
}

/// A BVH's collapse roles, after the split references from version 5 on: one byte per four
/// nodes ([`CollapseRoles`](crate::advanced::CollapseRoles)); in version 6 possibly none.
/// Empty before version 5.
#[inline(always)]
fn role_bytes<'a>(header: &BlobHeader, r: &mut Reader<'a>) -> Result<&'a [u8], BlobError> {
    if header.version >= PLANNED_VERSION {
        let len = CollapseRoles::len_for(header.node_count as usize);
        let len = u32::try_from(len).map_err(|_| BlobError::TooLarge)?;
        let optional = header.version >= WINDING_VERSION;
        Ok(
            r.records_maybe::<1>(len, optional, BlobSection::CollapsePlan)?
                .as_flattened(),
        )
    } else {
        Ok(&[])
    }
}

/// A BVH's winding-number expansions, after the collapse roles in version 6: none, or one
/// 112-byte record per node. Empty before version 6.
#[inline(always)]
fn winding_records<'a>(
    header: &BlobHeader,
    r: &mut Reader<'a>,
) -> Result<&'a [[u8; WINDING_BYTES]], BlobError> {
    if header.version >= WINDING_VERSION {
        r.records_maybe::<WINDING_BYTES>(header.node_count, true, BlobSection::WindingNodes)
    } else {
        Ok(&[])
    }
}

/// A cell structure's node words (or cell offsets) and references, cut out of the bytes.
#[cfg(feature = "blob-cells")]
fn cell_arrays<'a>(header: &BlobHeader, r: &mut Reader<'a>) -> Result<RawStructure<'a>, BlobError> {
    let words = if header.kind == StructureKind::Grid {
        header.node_count.checked_add(1)
    } else {
        header.node_count.checked_mul(2)
    }
    .ok_or(BlobError::TooLarge)?;
    Ok(RawStructure::Cells(
        LeWords::new(r.records::<{ super::format::WORD_BYTES }>(words, BlobSection::Nodes)?),
        LeWords::new(r.records::<{ super::format::WORD_BYTES }>(
            header.reference_count,
            BlobSection::References,
        )?),
    ))
}

/// Without the feature the header reader refuses every kind but the BVH.
#[cfg(not(feature = "blob-cells"))]
fn cell_arrays<'a>(header: &BlobHeader, _: &mut Reader<'a>) -> Result<RawStructure<'a>, BlobError> {
    Err(BlobError::UnsupportedStructure {
        kind: header.kind.tag(),
    })
}

/// Checks a mesh stored in a blob: coordinates finite and bounded, indices in range.
pub(super) fn check_mesh(mesh: &BlobMesh<'_>) -> Result<(), BlobError> {
    match *mesh {
        BlobMesh::Indexed {
            positions,
            triangles,
        } => check_indexed(positions, triangles),
        BlobMesh::Packed { corners } => check_packed(corners),
        BlobMesh::External(_) => Ok(()),
    }
}

/// Validates the mesh, then the structure against it and the header; returns the view.
fn finish<'a>(
    header: BlobHeader,
    raw: RawStructure<'a>,
    mesh: BlobMesh<'a>,
) -> Result<BlobView<'a>, BlobError> {
    check_mesh(&mesh)?;
    let structure = check_structure(&header, raw, Some(&mesh))?;
    Ok(BlobView {
        header,
        structure,
        mesh,
    })
}

/// Checks the structure (a BVH against `mesh` when given: triangle indices and containment;
/// a cell structure's references against the triangle count) and that the header's config,
/// depth and bounds agree with it.
fn check_structure<'a>(
    header: &BlobHeader,
    raw: RawStructure<'a>,
    mesh: Option<&BlobMesh<'_>>,
) -> Result<BlobStructure<'a>, BlobError> {
    let (structure, depth) = match raw {
        RawStructure::Bvh(mut tree) => {
            // One walk: the boxes' first problem is reported after the topology's.
            if let Some(problem) = check_before_boxes(
                header,
                &mut tree,
                mesh,
                |t| check_boxes_last(t, mesh, Extent::Exact),
                |t| check_slots(t, t.order_entries(), header.triangle_count as usize),
                false,
            )? {
                return Err(problem.into());
            }
            if let Some(mesh) = mesh {
                check_split_coverage(&tree, mesh)?;
            }
            let root = tree.node(0).map_or(Aabb::EMPTY, |n| n.aabb());
            same_bounds(&root, &header.bounds)?;
            #[cfg(feature = "blob-winding")]
            if let Some(mesh) = mesh {
                super::winding_check::check_winding(&tree, mesh)?;
            }
            (BlobStructure::Bvh(tree), tree.depth)
        }
        #[cfg(feature = "blob-cells")]
        RawStructure::Cells(words, items) => {
            // The header reader makes the config's kind the header's.
            if !header.config.is_valid() {
                return Err(BlobError::HeaderMismatch { field: "config" });
            }
            let (structure, depth) = check_cells(header, words, items)?;
            if let Some(mesh) = mesh {
                check_cell_coverage(&structure, header, mesh)?;
            }
            (structure, depth)
        }
        #[cfg(not(feature = "blob-cells"))]
        RawStructure::Cells(..) => {
            return Err(BlobError::UnsupportedStructure {
                kind: header.kind.tag(),
            });
        }
    };
    if depth != header.depth {
        return Err(BlobError::HeaderMismatch { field: "depth" });
    }
    Ok(structure)
}

#[cfg(feature = "blob-cells")]
/// [`check_structure`] for a k-d tree, octree or grid: the structure and its deepest leaf. In a
/// frame of its own, so that validating a BVH does not reserve the stack these checks use.
#[inline(never)]
fn check_cells<'a>(
    header: &BlobHeader,
    words: LeWords<'a>,
    items: LeWords<'a>,
) -> Result<(BlobStructure<'a>, u32), BlobError> {
    let n = header.triangle_count as usize;
    let b = header.bounds;
    let structure = match header.config {
        StructureConfig::KdTree(_) => {
            BlobStructure::KdTree(KdTree::from_parts(b, words, items, n)?)
        }
        StructureConfig::Octree(_) => {
            BlobStructure::Octree(Octree::from_parts(b, words, items, n)?)
        }
        StructureConfig::Grid { resolution, .. } => {
            let layout = GridLayout {
                bounds: b,
                resolution,
            };
            BlobStructure::Grid(Grid::from_parts(layout, words, items, n)?)
        }
        StructureConfig::Bvh(_) => {
            return Err(BlobError::InvalidNode(StructureError::BadNode { node: 0 }));
        }
    };
    let deepest = structure.cell_stats(n).map_or(0, |s| s.max_depth);
    Ok((structure, u32::try_from(deepest).unwrap_or(u32::MAX)))
}

#[cfg(feature = "blob-cells")]
/// Proves a cell structure answers as a fresh build of `mesh` would: every triangle inside the
/// header's bounds (the root cell), and listed by every cell it touches as the builds decide
/// touching. A packed mesh stores corners per reference slot: each slot is walked with its
/// corners, every cell on the way must list its triangle with the same corners, and every
/// triangle must be named (exactly one slot is the first of its walk per triangle), so the
/// slots describe one mesh, which the structure covers.
#[inline(never)]
fn check_cell_coverage(
    structure: &BlobStructure<'_>,
    header: &BlobHeader,
    mesh: &BlobMesh<'_>,
) -> Result<(), BlobError> {
    let n = header.triangle_count as usize;
    let triangle = |tri: u32| mesh.triangle(tri);
    let items = match structure {
        BlobStructure::KdTree(t) => t.items(),
        BlobStructure::Octree(t) => t.items(),
        BlobStructure::Grid(t) => t.items(),
        BlobStructure::Bvh(_) => return Ok(()),
    };
    let (coverage_mesh, mesh_bounds) = match mesh {
        BlobMesh::Packed { corners } => {
            // The mesh a packed blob decodes to has the vertices its slots hold.
            let bounds = (0..corners.len())
                .filter_map(|slot| mesh.corners(slot, 0))
                .fold(Aabb::EMPTY, |b, t| b.union(t.bounds()));
            (CoverageMesh::Packed(corners), bounds)
        }
        _ => {
            // The builds pad cells by the mesh's bounds (every vertex, used or not), which for
            // an octree are not the header's (its root cube).
            let bounds = (0..header.vertex_count)
                .filter_map(|v| mesh.position(v))
                .fold(Aabb::EMPTY, |b, p| b.grown(Vec3::from_array(p)));
            (CoverageMesh::Triangles(&triangle), bounds)
        }
    };
    let mut fingerprint = MultisetFingerprint::default();
    let mut add = |tri: u32| fingerprint.add(tri, 1);
    let mut coverage = Coverage::new(items, coverage_mesh, &mut add);
    for i in 0..u32::try_from(coverage.subjects(n)).unwrap_or(u32::MAX) {
        let inside = coverage
            .subject(i)
            .is_some_and(|(_, t)| header.bounds.contains_aabb(&t.bounds()));
        if !inside {
            return Err(BlobError::HeaderMismatch { field: "bounds" });
        }
    }
    let pad = ReferencePad::of(&mesh_bounds);
    let uncovered = match structure {
        BlobStructure::KdTree(t) => t.first_uncovered(pad, &mut coverage, n),
        BlobStructure::Octree(t) => t.first_uncovered(pad, &mut coverage, n),
        BlobStructure::Grid(t) => t.first_uncovered(pad, &mut coverage, n),
        BlobStructure::Bvh(_) => None,
    };
    if let Some(i) = uncovered {
        let tri = coverage.subject(i).map_or(i, |(tri, _)| tri);
        return Err(BlobError::UnlistedTriangle { tri });
    }
    let named = coverage.named(n);
    if named != n {
        // Packed: some triangle has no slot, so no corners (the decoded mesh would make one up).
        return Err(BlobError::CountMismatch {
            section: BlobSection::References,
            expected: n as u64,
            found: named as u64,
        });
    }
    if matches!(mesh, BlobMesh::Packed { .. }) {
        // As many as the triangles, yet one named twice (two sets of corners) and another
        // not at all: the fingerprint of the named triangles against `0..n` tells.
        fingerprint.less_each_below(n);
        if !fingerprint.is_balanced() {
            return Err(BlobError::OrderNotPermutation);
        }
    }
    Ok(())
}

/// Refuses collapse roles (version 5) that do not describe an eight-wide collapse of the tree,
/// whose topology was checked.
pub(super) fn check_roles(tree: &BlobTree<'_>) -> Result<(), BlobError> {
    match tree.collapse_roles() {
        Some(roles) => roles
            .check(tree)
            .map(|_| ())
            .map_err(|()| BlobError::BadCollapsePlan),
        None => Ok(()),
    }
}

/// A BVH blob's checks before its boxes, in the order both [`BlobView::parse`] and
/// `MeshBvh::from_blob` (which checks the boxes afterwards, on its decoded copy) make them, so
/// the two report the same first problem of a blob: the config, every order entry below the
/// triangle count, the topology and leaf ranges (`walk`, which returns the tree's shape and,
/// when it checks the boxes too, their first problem, held for the caller to report next),
/// the order against the split references (`slots`: their fingerprint, or an exact count that
/// falls back to it when it fails, so the error is the same), the corners of split triangles,
/// the collapse roles (unless `roles_later`: a loader whose collapse walks them next, failing as
/// [`check_roles`] does).
///
/// The walk is the caller's, not a flag: each caller's walk is then the only one in its code,
/// and the firmware's validation holds one walk's stack, not two.
pub(super) fn check_before_boxes(
    header: &BlobHeader,
    tree: &mut BlobTree<'_>,
    mesh: Option<&BlobMesh<'_>>,
    walk: impl FnOnce(&BlobTree<'_>) -> Result<(Shape, Option<StructureError>), StructureError>,
    slots: impl FnOnce(&BlobTree<'_>) -> Result<(), BlobError>,
    roles_later: bool,
) -> Result<Option<StructureError>, BlobError> {
    if header.config.bvh().is_none_or(|c| c.check().is_err()) {
        return Err(BlobError::HeaderMismatch { field: "config" });
    }
    for (slot, id) in (0u32..).zip(tree.order) {
        let tri = u32::from_le_bytes(*id);
        if tri >= header.triangle_count {
            return Err(BlobError::OrderOutOfRange { slot, tri });
        }
    }
    let (shape, held) = walk(tree)?;
    tree.depth = shape.depth;
    slots(tree)?;
    check_repeated_corners(&*tree, mesh)?;
    if !roles_later {
        check_roles(tree)?;
    }
    Ok(held)
}

/// Refuses a header box that differs from the structure's, bit for bit.
pub(crate) fn same_bounds(found: &Aabb, header: &Aabb) -> Result<(), BlobError> {
    let bits = |v: Vec3| v.to_array().map(f32::to_bits);
    if bits(found.min) != bits(header.min) || bits(found.max) != bits(header.max) {
        return Err(BlobError::HeaderMismatch { field: "bounds" });
    }
    Ok(())
}

impl<'a> BlobStructure<'a> {
    /// Validates the structure of any blob without its mesh — topology, leaf ranges, depth,
    /// bounds, every reference below the triangle count, the checksum — and returns it with
    /// the header. For tools that inspect a blob, and for queries with a mesh held elsewhere,
    /// which must be the mesh it was built from: another mesh gives meaningless answers, never
    /// a panic. Prefer [`BlobView::parse_with_mesh`], which checks the mesh too.
    ///
    /// # Errors
    /// As [`BlobView::parse`], except that a missing mesh is not an error.
    pub fn parse(bytes: &'a [u8]) -> Result<(BlobHeader, Self), BlobError> {
        let s = sections(bytes)?;
        let structure = check_structure(&s.header, s.structure, None)?;
        Ok((s.header, structure))
    }
}

impl<'a> BlobTree<'a> {
    /// [`BlobStructure::parse`] for a BVH blob: validates the tree of the blob without its
    /// mesh, for queries with a mesh held elsewhere (`tree.with(&mesh)`, which, as with a
    /// [`Bvh`](crate::bvh::Bvh), must be the mesh it was built from).
    ///
    /// # Errors
    /// As [`BlobStructure::parse`]; [`BlobError::UnsupportedStructure`] for another kind.
    pub fn parse(bytes: &'a [u8]) -> Result<(BlobHeader, Self), BlobError> {
        match BlobStructure::parse(bytes)? {
            (header, BlobStructure::Bvh(tree)) => Ok((header, tree)),
            #[cfg(feature = "blob-cells")]
            (header, _) => Err(BlobError::UnsupportedStructure {
                kind: header.kind.tag(),
            }),
        }
    }
}
