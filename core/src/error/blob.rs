//! Errors of the blob format (feature `blob`).

use core::fmt;

use super::mesh::MeshError;
use super::structure::StructureError;

/// A part of a blob, named in [`BlobError`]s.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BlobSection {
    /// The header (everything before the node array).
    Header,
    /// The node records.
    Nodes,
    /// The triangle order (leaf slot → input triangle index).
    Order,
    /// The vertex positions of a self-contained, indexed blob.
    Positions,
    /// The vertex-index triples of a self-contained, indexed blob.
    Triangles,
    /// The leaf-ordered triangle corners of a self-contained, packed blob.
    PackedTriangles,
    /// The tag saying how (or whether) the mesh is stored.
    MeshLayout,
    /// A k-d tree's, octree's or grid's references (leaf slot → input triangle index).
    References,
    /// The split references of a BVH built with spatial splits (version 4).
    SplitRefs,
    /// A BVH's collapse roles (version 5).
    CollapsePlan,
    /// A BVH's winding-number expansions (version 6).
    WindingNodes,
}

impl fmt::Display for BlobSection {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Header => "header",
            Self::Nodes => "nodes",
            Self::Order => "triangle order",
            Self::Positions => "positions",
            Self::Triangles => "triangles",
            Self::PackedTriangles => "packed triangles",
            Self::MeshLayout => "mesh layout",
            Self::References => "references",
            Self::SplitRefs => "split references",
            Self::CollapsePlan => "collapse plan",
            Self::WindingNodes => "winding-number expansions",
        })
    }
}

/// Why a blob could not be written, read or attached to a mesh.
///
/// Byte offsets count from the start of the blob.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BlobError {
    /// The bytes do not start with the blob magic `MSHQ`: not a meshq blob.
    BadMagic,
    /// The blob ends early. Fix: the file was cut short; copy it again.
    Truncated {
        /// Where the data ran out.
        offset: usize,
        /// The section being read.
        section: BlobSection,
    },
    /// A field does not decode (a bad varint or enum tag, a non-UTF-8-free postcard value).
    Malformed {
        /// Offset of the section that failed to decode.
        offset: usize,
        /// The section.
        section: BlobSection,
    },
    /// Written by another format version. Fix: re-bake the blob with this version of meshq.
    UnsupportedVersion {
        /// The version in the blob.
        found: u16,
        /// Oldest version this build reads.
        oldest: u16,
        /// Newest version this build reads.
        newest: u16,
    },
    /// The structure kind is not one this build can query (also a BVH with spatial splits, in
    /// a build without the `blob-spatial` feature).
    UnsupportedStructure {
        /// The kind tag in the blob.
        kind: u32,
    },
    /// The checksum does not match the bytes: the blob is corrupt.
    ChecksumMismatch {
        /// The checksum stored in the header.
        stored: u32,
        /// The checksum of the bytes as read.
        computed: u32,
    },
    /// A count in the header disagrees with the arrays or the byte length.
    CountMismatch {
        /// The section whose length is wrong.
        section: BlobSection,
        /// The count the header implies.
        expected: u64,
        /// The count found.
        found: u64,
    },
    /// Bytes are left over after the last section.
    TrailingBytes {
        /// Where the extra bytes start.
        offset: usize,
    },
    /// A header field contradicts the arrays (depth, root bounds, mesh layout) or is out of
    /// range (the build config).
    HeaderMismatch {
        /// The header field.
        field: &'static str,
    },
    /// A node or leaf fails validation; the payload names it.
    InvalidNode(StructureError),
    /// An order entry names a triangle beyond the triangle count.
    OrderOutOfRange {
        /// The order slot.
        slot: u32,
        /// The triangle index found there.
        tri: u32,
    },
    /// The order names a triangle a second time (found by the exact check of
    /// `MeshBvh::from_blob`, feature `alloc`; a view's check reports
    /// [`BlobError::OrderNotPermutation`]). No encoder writes that. Fix: bake again.
    RepeatedTriangle {
        /// The order slot naming the triangle again.
        slot: u32,
        /// The triangle index.
        tri: u32,
    },
    /// The BVH's triangle order is not a permutation of the triangles (some triangle is
    /// named twice and another never), found without memory by comparing a fingerprint of the
    /// order with that of `0..n`; the blob's checksum was recomputed over the damage. For a
    /// tree with spatial splits: the order does not name every triangle once plus each split
    /// triangle as often again as its split references say. For a packed k-d tree, octree or
    /// grid blob: its reference slots do not give every triangle one set of corners (one
    /// triangle has two, in cells apart, and another none).
    OrderNotPermutation,
    /// An entry of a BVH's split references (version 4) is out of order, out of range, names
    /// another triangle than its slot holds, or has another box than its leaf; or the table
    /// misses a slot of a triangle the order names twice. The payload is the entry's index
    /// (the entry count when an entry is missing).
    BadSplitRef {
        /// Index of the entry.
        entry: u32,
    },
    /// A BVH's collapse roles (version 5) do not describe an eight-wide collapse of its tree
    /// (see [`CollapseRoles::check`](crate::advanced::CollapseRoles::check)). No encoder writes
    /// that. Fix: bake again.
    BadCollapsePlan,
    /// A BVH's winding-number expansions (version 6) are not the ones
    /// [`WindingTree::build`](crate::inside::WindingTree::build) works out for its tree and
    /// mesh, bit for bit (the load works them out again to compare). No encoder writes that.
    /// Fix: bake again.
    BadWindingNodes,
    /// A k-d tree, octree or grid cell that triangle `tri` touches does not list it, so
    /// queries would miss it there, or (a packed blob, which stores corners per reference)
    /// lists it with other corners (a triangle outside the header's bounds is
    /// [`BlobError::HeaderMismatch`] with field `bounds`; a packed blob naming fewer triangles
    /// than its header counts, [`BlobError::CountMismatch`] of its references). No encoder
    /// writes that: builds list a triangle in every cell it touches, in ascending order. Fix:
    /// bake again.
    UnlistedTriangle {
        /// The triangle index.
        tri: u32,
    },
    /// The stored mesh fails validation; the payload names the vertex or triangle.
    InvalidMesh(MeshError),
    /// The blob was baked without its mesh. Fix: use
    /// [`BlobView::parse_with_mesh`](crate::blob::BlobView::parse_with_mesh) with the mesh it was
    /// baked from.
    MeshNotIncluded,
    /// The mesh given does not match the one the blob was baked from (counts or mesh checksum
    /// differ).
    MeshMismatch,
    /// A caller buffer is too small.
    BufferTooSmall {
        /// What the buffer holds.
        section: BlobSection,
        /// Elements (bytes for an encode buffer) needed.
        needed: usize,
        /// Elements given.
        got: usize,
    },
    /// The structure is too large for the format (a count beyond `u32`) or for this target's
    /// address space.
    TooLarge,
}

impl fmt::Display for BlobError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::BadMagic => f.write_str("not a meshq blob (bad magic)"),
            Self::Truncated { offset, section } => {
                write!(f, "blob truncated at offset {offset} (in the {section})")
            }
            Self::Malformed { offset, section } => {
                write!(f, "malformed {section} at offset {offset}")
            }
            Self::UnsupportedVersion {
                found,
                oldest,
                newest,
            } => write!(
                f,
                "blob format version {found} is not supported (this build reads versions {oldest} to {newest}); re-bake it"
            ),
            Self::UnsupportedStructure { kind } => {
                write!(f, "structure kind {kind} is not supported by this build")
            }
            Self::ChecksumMismatch { stored, computed } => write!(
                f,
                "blob checksum mismatch: stored {stored:#010x}, computed {computed:#010x} (corrupt blob)"
            ),
            Self::CountMismatch {
                section,
                expected,
                found,
            } => write!(
                f,
                "{section}: the header implies {expected} but the blob holds {found}"
            ),
            Self::TrailingBytes { offset } => {
                write!(f, "unexpected bytes after the blob at offset {offset}")
            }
            Self::HeaderMismatch { field } => {
                write!(
                    f,
                    "header field `{field}` does not match the blob's contents"
                )
            }
            Self::InvalidNode(e) => write!(f, "invalid tree: {e}"),
            Self::OrderOutOfRange { slot, tri } => {
                write!(f, "order slot {slot} names triangle {tri}, beyond the mesh")
            }
            Self::RepeatedTriangle { slot, tri } => {
                write!(f, "order slot {slot} names triangle {tri} again")
            }
            Self::OrderNotPermutation => f.write_str(
                "the triangle order names some triangle twice and another never (not a permutation)",
            ),
            Self::BadSplitRef { entry } => {
                write!(f, "split reference {entry} disagrees with the tree")
            }
            Self::BadCollapsePlan => {
                f.write_str("the collapse plan does not describe an eight-wide collapse of the tree")
            }
            Self::BadWindingNodes => f.write_str(
                "the winding-number expansions are not the ones the tree and mesh give",
            ),
            Self::UnlistedTriangle { tri } => {
                write!(f, "triangle {tri} touches a cell that does not list it")
            }
            Self::InvalidMesh(e) => write!(f, "invalid stored mesh: {e}"),
            Self::MeshNotIncluded => f.write_str(
                "the blob was baked without its mesh; supply the mesh it was baked from",
            ),
            Self::MeshMismatch => {
                f.write_str("the mesh given is not the one the blob was baked from")
            }
            Self::BufferTooSmall {
                section,
                needed,
                got,
            } => write!(f, "{section} buffer too small: needed {needed}, got {got}"),
            Self::TooLarge => f.write_str("structure too large for the blob format"),
        }
    }
}

impl core::error::Error for BlobError {}

impl From<StructureError> for BlobError {
    fn from(e: StructureError) -> Self {
        Self::InvalidNode(e)
    }
}

impl From<MeshError> for BlobError {
    fn from(e: MeshError) -> Self {
        Self::InvalidMesh(e)
    }
}
