//! The wire types: the header and the fixed-width records, as serde types postcard encodes.
//!
//! Postcard writes struct fields back to back, integers as varints unless marked fixed-width,
//! `f32` as 4 little-endian bytes, arrays element by element and sequences as a varint length
//! followed by the elements. Records mark every integer fixed-width, so every record of a kind
//! has the same size and the view can index it in place.

use serde::{Deserialize, Serialize};

use crate::bvh::{BuildConfig, BvhNode, SplitStrategy};
pub use crate::structure_kind::StructureKind;

/// The first four bytes of every blob.
pub const MAGIC: [u8; 4] = *b"MSHQ";

/// The newest format version this build writes and reads. Version 6 added a BVH's
/// winding-number expansions (one [`WindingNode`](crate::inside::WindingNode) per node, so that
/// winding numbers, containment and signed distance run from the blob in place). Version 5 added a BVH's collapse
/// plan (the role of every node in its eight-wide collapse, so that a loader need not plan it
/// again), and its BVH header always counts leaf slots and split references; version 4 BVHs
/// built with spatial splits (more leaf slots than triangles, and the table of split
/// references); version 3 the k-d tree, octree and grid kinds (a BVH blob is laid out as in
/// version 2); version 2 the split strategy to the config. Blobs are written at the oldest
/// version that can hold what they are given: version 5 for a BVH with its collapse roles,
/// version 4 for a BVH with spatial splits without them, version 3 otherwise, byte for byte as
/// before versions 4 and 5 existed; version 6 only for a BVH with its expansions. Version 1 and 2 blobs (always a BVH) are still read.
pub const FORMAT_VERSION: u16 = 6;

/// The first version whose BVH header counts slots and split references (version 4: spatial
/// splits), and whose payload has the split references after the order.
pub(crate) const SPATIAL_VERSION: u16 = 4;

/// The first version whose BVH payload holds the collapse roles, after the split references.
pub(crate) const PLANNED_VERSION: u16 = 5;

/// The first version whose BVH payload has the winding-number expansions, after the collapse
/// roles; in it both are sequences that may be empty.
pub(crate) const WINDING_VERSION: u16 = 6;

/// The version of blobs that need nothing newer: every blob but a BVH with spatial splits or
/// collapse roles.
pub(crate) const BASE_VERSION: u16 = 3;

/// The newest format version this build reads: [`FORMAT_VERSION`]. A build without the
/// `blob-spatial` feature refuses a BVH with spatial splits (versions 4 and 5) as a structure it
/// cannot query ([`BlobError::UnsupportedStructure`](crate::error::BlobError::UnsupportedStructure)).
pub const NEWEST_READABLE_VERSION: u16 = FORMAT_VERSION;

/// The oldest format version this build reads.
pub const OLDEST_READABLE_VERSION: u16 = 1;

/// Bytes of one node record.
pub(crate) const NODE_BYTES: usize = 32;
/// Bytes of one order entry.
pub(crate) const ORDER_BYTES: usize = 4;
/// Bytes of one position.
pub(crate) const POSITION_BYTES: usize = 12;
/// Bytes of one vertex-index triple.
pub(crate) const TRIANGLE_BYTES: usize = 12;
/// Bytes of one packed triangle.
pub(crate) const PACKED_BYTES: usize = 36;
/// Bytes of one word of a cell structure's arrays (node halves, cell offsets, references).
#[cfg(feature = "blob-cells")]
pub(crate) const WORD_BYTES: usize = 4;
/// Bytes of one winding-number expansion: its 28 `f32`s in field order.
pub(crate) const WINDING_BYTES: usize = 112;
/// Bytes of the trailing header checksum.
pub(crate) const CHECKSUM_BYTES: usize = 4;

/// How a blob stores the mesh its structure was built from.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum MeshLayout {
    /// Positions and vertex-index triples in the input's order: 12 bytes per vertex plus 12 per
    /// triangle, and the mesh can be recovered exactly. Wire tag 0. The default.
    #[default]
    Indexed,
    /// Each triangle's three corners, copied in leaf order: 36 bytes per triangle, fastest
    /// queries from a blob (a leaf reads one contiguous run). Wire tag 1.
    Packed,
    /// No mesh: the caller supplies it at load
    /// ([`BlobView::parse_with_mesh`](super::BlobView::parse_with_mesh)), checked against the
    /// header's mesh checksum. Wire tag 2.
    Omitted,
}

impl MeshLayout {
    /// The layout's name in lower case: `indexed`, `packed` or `omitted` (what tools print
    /// and accept).
    #[must_use]
    pub const fn name(&self) -> &'static str {
        match self {
            Self::Indexed => "indexed",
            Self::Packed => "packed",
            Self::Omitted => "omitted",
        }
    }
}

impl MeshLayout {
    /// The wire tag.
    #[must_use]
    pub const fn tag(self) -> u32 {
        match self {
            Self::Indexed => 0,
            Self::Packed => 1,
            Self::Omitted => 2,
        }
    }

    /// The layout with wire tag `tag`, if this build knows it.
    #[must_use]
    pub(crate) const fn from_tag(tag: u32) -> Option<Self> {
        match tag {
            0 => Some(Self::Indexed),
            1 => Some(Self::Packed),
            2 => Some(Self::Omitted),
            _ => None,
        }
    }
}

/// The header fields between the version and the config (every version).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct HeaderCounts {
    /// [`StructureKind`] tag.
    pub kind: u32,
    /// [`MeshLayout`] tag.
    pub mesh: u32,
    pub triangle_count: u32,
    pub vertex_count: u32,
    pub node_count: u32,
    pub depth: u32,
    pub bounds_min: [f32; 3],
    pub bounds_max: [f32; 3],
}

/// The config fields after the split tag: all of version 1's config, which had no tag (it was
/// always SAH). The header is read piece by piece so that both versions share one decoder,
/// which keeps the firmware's code small.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct ConfigCosts {
    pub bins: u32,
    pub max_leaf_size: u32,
    pub max_depth: u32,
    pub traversal_cost: f32,
    pub triangle_cost: f32,
}

/// A BVH's leaf slots and split references, after its config (version 4 only: trees with
/// spatial splits).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct SpatialWire {
    pub references: u32,
    pub split_refs: u32,
}

/// A k-d tree's config and reference count, after the header counts (version 3).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct KdWire {
    pub max_depth: u32,
    pub leaf_size: u32,
    pub traversal_cost: f32,
    pub triangle_cost: f32,
    pub empty_bonus: f32,
    pub references: u32,
}

/// An octree's config and reference count, after the header counts (version 3).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct OctreeWire {
    pub max_depth: u32,
    pub max_items: u32,
    pub references: u32,
}

/// A grid's config, resolution and reference count, after the header counts (version 3).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct GridWire {
    pub cells_per_triangle: f32,
    pub max_resolution: u32,
    pub resolution: [u32; 3],
    pub references: u32,
}

/// The header fields after the config, before the header checksum.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct HeaderSeal {
    #[serde(with = "postcard::fixint::le")]
    pub mesh_checksum: u32,
    #[serde(with = "postcard::fixint::le")]
    pub payload_len: u64,
}

impl ConfigCosts {
    /// The costs of `config`.
    pub(crate) const fn of(config: &BuildConfig) -> Self {
        Self {
            bins: config.bins,
            max_leaf_size: config.max_leaf_size,
            max_depth: config.max_depth,
            traversal_cost: config.traversal_cost,
            triangle_cost: config.triangle_cost,
        }
    }

    /// The config these costs belong to, with the given split strategy.
    pub(crate) const fn with_split(self, split: SplitStrategy) -> BuildConfig {
        BuildConfig {
            split,
            bins: self.bins,
            max_leaf_size: self.max_leaf_size,
            max_depth: self.max_depth,
            traversal_cost: self.traversal_cost,
            triangle_cost: self.triangle_cost,
        }
    }
}

/// A node record: [`BvhNode`] with fixed-width little-endian integers (32 bytes).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct NodeRecord {
    pub min: [f32; 3],
    #[serde(with = "postcard::fixint::le")]
    pub first: u32,
    pub max: [f32; 3],
    #[serde(with = "postcard::fixint::le")]
    pub count: u32,
}

impl From<&BvhNode> for NodeRecord {
    fn from(n: &BvhNode) -> Self {
        Self {
            min: n.min,
            first: n.first,
            max: n.max,
            count: n.count,
        }
    }
}

/// A fixed-width little-endian `u32` (an order entry).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub(crate) struct FixedU32(#[serde(with = "postcard::fixint::le")] pub u32);

/// A vertex-index triple with fixed-width little-endian indices (12 bytes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub(crate) struct TriangleRecord(
    #[serde(with = "postcard::fixint::le")] pub u32,
    #[serde(with = "postcard::fixint::le")] pub u32,
    #[serde(with = "postcard::fixint::le")] pub u32,
);

/// Decodes a node record from its 32 bytes.
#[inline(always)]
pub(crate) fn node_from_bytes(b: &[u8; NODE_BYTES]) -> BvhNode {
    let [
        a0,
        a1,
        a2,
        a3,
        b0,
        b1,
        b2,
        b3,
        c0,
        c1,
        c2,
        c3,
        f0,
        f1,
        f2,
        f3,
        d0,
        d1,
        d2,
        d3,
        e0,
        e1,
        e2,
        e3,
        g0,
        g1,
        g2,
        g3,
        n0,
        n1,
        n2,
        n3,
    ] = *b;
    BvhNode {
        min: [
            f32::from_le_bytes([a0, a1, a2, a3]),
            f32::from_le_bytes([b0, b1, b2, b3]),
            f32::from_le_bytes([c0, c1, c2, c3]),
        ],
        first: u32::from_le_bytes([f0, f1, f2, f3]),
        max: [
            f32::from_le_bytes([d0, d1, d2, d3]),
            f32::from_le_bytes([e0, e1, e2, e3]),
            f32::from_le_bytes([g0, g1, g2, g3]),
        ],
        count: u32::from_le_bytes([n0, n1, n2, n3]),
    }
}

/// Decodes three little-endian `f32`s.
#[inline(always)]
pub(crate) fn f32x3_from_bytes(b: &[u8; 12]) -> [f32; 3] {
    let [a0, a1, a2, a3, b0, b1, b2, b3, c0, c1, c2, c3] = *b;
    [
        f32::from_le_bytes([a0, a1, a2, a3]),
        f32::from_le_bytes([b0, b1, b2, b3]),
        f32::from_le_bytes([c0, c1, c2, c3]),
    ]
}

/// Decodes three little-endian `u32`s.
#[inline(always)]
pub(crate) fn u32x3_from_bytes(b: &[u8; 12]) -> [u32; 3] {
    let [a0, a1, a2, a3, b0, b1, b2, b3, c0, c1, c2, c3] = *b;
    [
        u32::from_le_bytes([a0, a1, a2, a3]),
        u32::from_le_bytes([b0, b1, b2, b3]),
        u32::from_le_bytes([c0, c1, c2, c3]),
    ]
}

/// Decodes a winding-number expansion from its 112 bytes: 28 little-endian `f32`s, in the
/// order of [`WindingNode`](crate::inside::WindingNode)'s fields.
#[cfg(feature = "blob-winding")]
#[inline]
pub(crate) fn winding_from_bytes(b: &[u8; WINDING_BYTES]) -> crate::inside::WindingNode {
    let (words, _) = b.as_chunks::<4>();
    let at = |i: usize| words.get(i).map_or(0.0, |w| f32::from_le_bytes(*w));
    crate::inside::WindingNode {
        centre: [at(0), at(1), at(2)],
        radius: at(3),
        normal: [at(4), at(5), at(6)],
        area: at(7),
        first: core::array::from_fn(|i| at(8 + i)),
        second: core::array::from_fn(|i| at(15 + i)),
    }
}

/// A winding-number expansion as written: its 28 `f32`s in the order [`winding_from_bytes`]
/// reads them (a tuple: no length).
pub(crate) struct WindingRecord<'n>(pub &'n crate::inside::WindingNode);

impl Serialize for WindingRecord<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeTuple;
        let n = self.0;
        let mut t = s.serialize_tuple(WINDING_BYTES / 4)?;
        for x in n
            .centre
            .iter()
            .chain([&n.radius])
            .chain(&n.normal)
            .chain([&n.area])
            .chain(&n.first)
            .chain(&n.second)
        {
            t.serialize_element(x)?;
        }
        t.end()
    }
}
