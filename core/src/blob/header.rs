//! The blob header as callers see it, and reading it on its own.

use glam::Vec3;

use super::format::{
    ConfigCosts, FORMAT_VERSION, FixedU32, HeaderCounts, HeaderSeal, MAGIC, MeshLayout,
    OLDEST_READABLE_VERSION, StructureKind,
};
use super::reader::Reader;
use crate::bvh::{BuildConfig, SplitStrategy};
use crate::error::{BlobError, BlobSection};
use crate::math::Aabb;

/// What a blob's header says. [`BlobHeader::read`] decodes it without checking anything below
/// it; [`BlobView::parse`](super::BlobView::parse) checks that everything agrees with it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlobHeader {
    /// The format version ([`FORMAT_VERSION`] for blobs this build writes).
    pub version: u16,
    /// The structure.
    pub kind: StructureKind,
    /// How the mesh is stored.
    pub mesh: MeshLayout,
    /// Triangles in the mesh the structure was built from.
    pub triangle_count: u32,
    /// Vertices in that mesh.
    pub vertex_count: u32,
    /// Nodes in the tree.
    pub node_count: u32,
    /// Levels in the tree (0 when empty, 1 for a lone leaf).
    pub depth: u32,
    /// The root's padded box ([`Aabb::EMPTY`] when empty).
    pub bounds: Aabb,
    /// The config the tree was built with (informational; [`SplitStrategy::Sah`] for version 1
    /// blobs, which had no other).
    ///
    /// [`SplitStrategy::Sah`]: crate::bvh::SplitStrategy::Sah
    pub config: BuildConfig,
    /// [`mesh_checksum`](super::mesh_checksum) of the mesh the blob was baked from.
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
        if !(OLDEST_READABLE_VERSION..=FORMAT_VERSION).contains(&version) {
            return Err(BlobError::UnsupportedVersion {
                found: version,
                oldest: OLDEST_READABLE_VERSION,
                newest: FORMAT_VERSION,
            });
        }
        let f: HeaderCounts = r.value(BlobSection::Header)?;
        // Version 1 had no split tag: every tree was binned SAH.
        let split = if version == 1 {
            SplitStrategy::Sah
        } else {
            r.value(BlobSection::Header)?
        };
        let costs: ConfigCosts = r.value(BlobSection::Header)?;
        let seal: HeaderSeal = r.value(BlobSection::Header)?;
        let FixedU32(checksum) = r.value(BlobSection::Header)?;
        let kind = StructureKind::from_tag(f.kind)
            .ok_or(BlobError::UnsupportedStructure { kind: f.kind })?;
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
            depth: f.depth,
            bounds: Aabb::new(
                Vec3::from_array(f.bounds_min),
                Vec3::from_array(f.bounds_max),
            ),
            config: costs.with_split(split),
            mesh_checksum: seal.mesh_checksum,
            checksum,
            header_len,
            total_len,
        })
    }
}
