//! The blob header as callers see it, and reading it on its own.

use glam::Vec3;

use super::format::{
    ConfigCosts, FixedU32, HeaderCounts, HeaderSeal, MAGIC, MeshLayout, NEWEST_READABLE_VERSION,
    OLDEST_READABLE_VERSION, SPATIAL_VERSION, StructureKind,
};
#[cfg(feature = "blob-cells")]
use super::format::{GridWire, KdWire, OctreeWire};
use super::reader::Reader;
use super::structure_config::{StructureConfig, WireConfig, bvh_config};
use crate::bvh::SplitStrategy;
use crate::error::{BlobError, BlobSection};
use crate::math::Aabb;

/// What a blob's header says. [`BlobHeader::read`] decodes it without checking anything below
/// it; [`BlobView::parse`](super::BlobView::parse) checks that everything agrees with it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlobHeader {
    /// The format version ([`FORMAT_VERSION`](crate::advanced::FORMAT_VERSION) for a BVH with its
    /// collapse roles, 4 for one with spatial splits without them, 3 for every other blob this
    /// build writes).
    pub version: u16,
    /// The structure.
    pub kind: StructureKind,
    /// How the mesh is stored.
    pub mesh: MeshLayout,
    /// Triangles in the mesh the structure was built from.
    pub triangle_count: u32,
    /// Vertices in that mesh.
    pub vertex_count: u32,
    /// Nodes in the tree; a grid's cell count.
    pub node_count: u32,
    /// Entries of the leaf-slot → triangle array: a BVH's leaf slots (its order: the triangle
    /// count, more with spatial splits), the reference count of a k-d tree, octree or grid (a
    /// triangle in several cells counts once per cell).
    pub reference_count: u32,
    /// Entries of a BVH's split references ([`SplitRefs`](crate::advanced::SplitRefs)): 0 unless
    /// it was built with spatial splits (version 4 or 5).
    pub split_ref_count: u32,
    /// A BVH's levels (0 when empty, 1 for a lone leaf); the depth of the deepest leaf of a
    /// k-d tree or octree (the root is depth 0); 0 for a grid.
    pub depth: u32,
    /// The root's box: a BVH's padded root box ([`Aabb::EMPTY`] when empty), a k-d tree's or
    /// grid's mesh bounds, an octree's root cube.
    pub bounds: Aabb,
    /// The config the structure was built with (informational, except a grid's resolution).
    pub config: StructureConfig,
    /// [`mesh_checksum`](crate::advanced::mesh_checksum) of the mesh the blob was baked from.
    pub mesh_checksum: u32,
    /// The blob checksum stored in the header.
    pub checksum: u32,
    /// Bytes of the header, checksum included: the payload starts here.
    pub header_len: usize,
    /// Bytes of the whole blob, header and payload.
    pub total_len: usize,
}

impl BlobHeader {
    /// Decodes the header at the start of `bytes`: magic, version, then the fields of that
    /// version. Reads nothing past the header; the payload may be missing.
    ///
    /// # Errors
    /// [`BlobError::BadMagic`], [`BlobError::UnsupportedVersion`] (the rest of the header is then
    /// not read: another version may lay it out differently),
    /// [`BlobError::UnsupportedStructure`], [`BlobError::Truncated`], [`BlobError::Malformed`],
    /// [`BlobError::TooLarge`].
    pub fn read(bytes: &[u8]) -> Result<Self, BlobError> {
        let mut r = Reader::new(bytes);
        let magic = r.bytes(MAGIC.len(), BlobSection::Header)?;
        if magic != MAGIC {
            return Err(BlobError::BadMagic);
        }
        let version: u16 = r.value(BlobSection::Header)?;
        if !(OLDEST_READABLE_VERSION..=NEWEST_READABLE_VERSION).contains(&version) {
            return Err(BlobError::UnsupportedVersion {
                found: version,
                oldest: OLDEST_READABLE_VERSION,
                newest: NEWEST_READABLE_VERSION,
            });
        }
        let f: HeaderCounts = r.value(BlobSection::Header)?;
        let kind = StructureKind::from_tag(f.kind)
            .filter(|&k| version >= 3 || k == StructureKind::Bvh)
            .ok_or(BlobError::UnsupportedStructure { kind: f.kind })?;
        let wire = read_config(&mut r, version, kind, f.triangle_count)?;
        let seal: HeaderSeal = r.value(BlobSection::Header)?;
        let FixedU32(checksum) = r.value(BlobSection::Header)?;
        let mesh = MeshLayout::from_tag(f.mesh).ok_or(BlobError::Malformed {
            offset: 0,
            section: BlobSection::MeshLayout,
        })?;
        let header_len = r.offset();
        let total_len = usize::try_from(seal.payload_len)
            .ok()
            .and_then(|p| p.checked_add(header_len))
            .ok_or(BlobError::TooLarge)?;
        Ok(Self {
            version,
            kind,
            mesh,
            triangle_count: f.triangle_count,
            vertex_count: f.vertex_count,
            node_count: f.node_count,
            reference_count: wire.references,
            split_ref_count: wire.split_refs.unwrap_or(0),
            depth: f.depth,
            bounds: Aabb::new(
                Vec3::from_array(f.bounds_min),
                Vec3::from_array(f.bounds_max),
            ),
            config: wire.config,
            mesh_checksum: seal.mesh_checksum,
            checksum,
            header_len,
            total_len,
        })
    }
}

/// The config part of the header for `kind` in `version`, with the reference count (a BVH's
/// is its triangle count).
fn read_config(
    r: &mut Reader<'_>,
    version: u16,
    kind: StructureKind,
    triangle_count: u32,
) -> Result<WireConfig, BlobError> {
    Ok(match kind {
        StructureKind::Bvh => {
            // Version 1 had no split tag: every tree was binned SAH.
            let split = if version == 1 {
                SplitStrategy::Sah
            } else {
                r.value(BlobSection::Header)?
            };
            let costs: ConfigCosts = r.value(BlobSection::Header)?;
            // Versions 4 and 5 count slots and split references (both plain for a tree
            // without spatial splits, which version 5 may hold too).
            // Two varints, read as the other counts are (one decoder in the firmware).
            let spatial = if version >= SPATIAL_VERSION {
                let references: u32 = r.value(BlobSection::Header)?;
                let split_refs: u32 = r.value(BlobSection::Header)?;
                Some(super::format::SpatialWire {
                    references,
                    split_refs,
                })
            } else {
                None
            };
            #[cfg(not(feature = "blob-spatial"))]
            if spatial.is_some_and(|s| s.split_refs != 0 || s.references != triangle_count) {
                // A tree with spatial splits: this build cannot check or query one.
                return Err(BlobError::UnsupportedStructure { kind: kind.tag() });
            }
            WireConfig {
                config: bvh_config(split, costs),
                references: spatial.map_or(triangle_count, |s| s.references),
                split_refs: spatial.map(|s| s.split_refs),
            }
        }
        #[cfg(feature = "blob-cells")]
        StructureKind::KdTree => r.value::<KdWire>(BlobSection::Header)?.into(),
        #[cfg(feature = "blob-cells")]
        StructureKind::Octree => r.value::<OctreeWire>(BlobSection::Header)?.into(),
        #[cfg(feature = "blob-cells")]
        StructureKind::Grid => r.value::<GridWire>(BlobSection::Header)?.into(),
        // Without the feature, only BVH headers are read (`blob::reseal` and tools included).
        #[cfg(not(feature = "blob-cells"))]
        other => {
            return Err(BlobError::UnsupportedStructure { kind: other.tag() });
        }
    })
}
