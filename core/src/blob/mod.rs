//! Prebuilt blobs (feature `blob`): a BVH, k-d tree, octree or grid (and, by default, its mesh)
//! encoded once, offline, and queried in place from the bytes — in RAM, from a `fetch`, or in
//! flash.
//!
//! ```
//! use meshq::blob::{self, EncodeOptions};
//! use meshq::prelude::*;
//! let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
//! let mesh = MeshRef::new(&positions, &[[0, 1, 2]]).validate()?;
//! let mut buffers = BvhBuffers::<1>::new();
//! let bvh = buffers.build(&mesh, &BuildConfig::default())?;
//!
//! let options = EncodeOptions::default();
//! let mut bytes = [0u8; 256];
//! let n = blob::encode_into(&bvh, &mesh, &options, &mut bytes)?;
//! assert_eq!(n, blob::encoded_len(&bvh, &mesh, &options)?);
//!
//! let view = BlobView::parse(&bytes[..n])?;
//! let hit = view.raycast(&Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z));
//! assert_eq!(hit, bvh.with(&mesh).raycast(&Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z)));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Format (version 6)
//!
//! One [postcard](https://docs.rs/postcard) message, fields back to back. *varint* is postcard's
//! LEB128-style unsigned varint; *fixed* integers are little-endian of the stated width; every
//! `f32` is 4 little-endian bytes. A sequence is a varint element count followed by the
//! elements.
//!
//! | field | encoding | meaning |
//! |---|---|---|
//! | magic | 4 bytes | `MSHQ` |
//! | version | varint `u16` | 6 ([`FORMAT_VERSION`](crate::advanced::FORMAT_VERSION)) for a BVH with its winding-number expansions, 5 for a BVH with its collapse roles only (what [`MeshBvh::to_blob`](crate::MeshBvh::to_blob) and the tools write by default), 4 for a BVH with spatial splits without them, 3 for every other blob; read before anything else |
//! | kind | varint `u32` | [`StructureKind`] tag: 0 BVH, 1 k-d tree, 2 octree, 3 grid |
//! | mesh | varint `u32` | [`MeshLayout`] tag: 0 indexed, 1 packed, 2 omitted |
//! | triangle_count, vertex_count, node_count, depth | varint `u32` each | counts of the mesh and structure (node_count: a grid's cells; depth: see [`BlobHeader::depth`]) |
//! | bounds | 6 × `f32` | root box min xyz, max xyz ([`BlobHeader::bounds`]) |
//! | config | by kind, see below | [`StructureConfig`] |
//! | mesh_checksum | fixed `u32` | [`mesh_checksum`](crate::advanced::mesh_checksum) of the mesh baked from |
//! | payload_len | fixed `u64` | bytes after the header |
//! | checksum | fixed `u32` | CRC-32/ISO-HDLC of every blob byte except these four |
//! | nodes | BVH: sequence of 32-byte records; others: sequence of fixed `u32` | BVH: [`BvhNode`](crate::bvh::BvhNode) (min `f32`×3, first fixed `u32`, max `f32`×3, count fixed `u32`); k-d tree and octree: two words per node ([`KdNode`](crate::kdtree::KdNode), [`OctreeNode`](crate::octree::OctreeNode) `a`, `b`); grid: the cell offsets (cells + 1) |
//! | order | sequence of fixed `u32` | leaf slot → input triangle index: a BVH's order (one per triangle; with spatial splits, the header's slot count), the references of the others (header `config`'s count) |
//! | split references | versions 4 and 5: sequence of 32-byte records | a BVH with spatial splits: [`SplitRef`](crate::query::SplitRef)s sorted by triangle then slot (triangle and slot fixed `u32`, the leaf's box `f32`×6); empty without spatial splits |
//! | collapse roles | versions 5 and 6: sequence of bytes, one per four nodes (version 6: or none) | a BVH's eight-wide collapse ([`CollapseRoles`](crate::advanced::CollapseRoles)): node `i`'s role in bits `2 (i mod 4)` and up of byte `i / 4`: 0 none, 1 starts a wide node, 2 a leaf merged from its subtree |
//! | winding expansions | version 6: sequence of 112-byte records, one per node, or none | a BVH's winding-number expansions ([`WindingNode`](crate::inside::WindingNode): its 28 `f32`s in field order: centre ×3, radius, normal ×3, area, first ×7, second ×13), read with the `blob-winding` feature; a load works them out again from the tree and mesh and refuses any that differ by a bit ([`BlobError::BadWindingNodes`](crate::error::BlobError::BadWindingNodes)) |
//! | mesh section | varint tag (= mesh), then by layout | indexed: positions (sequence of `f32`×3) and triangles (sequence of fixed `u32`×3); packed: sequence of 36-byte corner triples, one per order entry; omitted: nothing |
//!
//! The config by kind: BVH: split tag (0 SAH, 1 centre), then varint `u32` × 3 (bins,
//! max_leaf_size, max_depth) and `f32` × 2 (traversal_cost, triangle_cost); versions 4 and 5
//! then add varint `u32` × 2 (leaf slots, split references: the triangle count and 0 for a tree
//! without spatial splits). k-d tree:
//! varint max_depth, leaf_size, `f32` traversal_cost, triangle_cost, empty_bonus, varint
//! reference count. Octree: varint max_depth, max_items, reference count. Grid: `f32`
//! cells_per_triangle, varint max_resolution, resolution × 3, reference count.
//!
//! Fixed-width records let a view index node `i` at a known offset without decoding the ones
//! before it. Nothing is aligned; reads go through `from_le_bytes`, so the bytes can sit anywhere.
//!
//! # Versioning
//! The version is the second field and is read before anything else. A change to any field or
//! record increments [`FORMAT_VERSION`](crate::advanced::FORMAT_VERSION); a reader refuses versions outside
//! [`OLDEST_READABLE_VERSION`](crate::advanced::OLDEST_READABLE_VERSION)`..=`[`NEWEST_READABLE_VERSION`](crate::advanced::NEWEST_READABLE_VERSION) with
//! [`BlobError::UnsupportedVersion`](crate::error::BlobError::UnsupportedVersion), never guessing.
//! Blobs are written at the oldest version that holds them. Version 6 added a BVH's
//! winding-number expansions ([`EncodeOptions::winding`]; [`MeshBvh::to_blob`](crate::MeshBvh::to_blob)
//! stores them once [prepared](crate::MeshBvh::with_winding_numbers)), so that
//! `BlobView::winding_tree` answers containment and signed distance in place; in it the
//! collapse roles may be absent too. Without the `blob-winding` feature the expansions are
//! skipped (their count checked, their bytes not kept). Version 5 added a BVH's collapse
//! roles, so that loaders collapse its tree eight-wide with one checked walk instead of planning
//! it ([`EncodeOptions::collapse_roles`]; every BVH blob [`MeshBvh::to_blob`](crate::MeshBvh::to_blob)
//! writes). Version 4 added BVHs built with spatial splits (read with the `blob-spatial`
//! feature; without it a version 4 or 5 blob with spatial splits is refused as
//! [`BlobError::UnsupportedStructure`](crate::error::BlobError::UnsupportedStructure)); every
//! other blob is written as version 3, byte for byte as before version 4. Version 3 added the
//! k-d tree, octree and grid kinds; its BVH blobs are laid out as in version 2. Version 1 differs from 2 only in the config, which lacks the split tag (it was
//! always SAH); this build reads it as SAH. Versions 1 and 2 hold BVHs only.
//!
//! Within a version the bytes are stable: the same mesh and config give the same blob on every
//! target and every release that writes that version.

#[cfg(feature = "alloc")]
mod boxes_deferred;
pub(crate) mod checksum;
// The checksum by byte shuffles where the build computes it so (see `build.rs`), tested on
// every target.
#[cfg(any(test, crc_lanes))]
mod crc_lanes;
mod decode;
pub(crate) mod encode;
pub(crate) mod format;
pub(crate) mod header;
mod mesh;
mod order_check;
mod reader;
mod source;
mod split_check;
mod structure;
mod structure_config;
mod tree;
mod view;
#[cfg(feature = "blob-winding")]
mod winding;
#[cfg(feature = "blob-winding")]
mod winding_check;
#[cfg(feature = "blob-winding")]
mod winding_nodes;

#[cfg(feature = "alloc")]
pub(crate) use boxes_deferred::BoxesUnchecked;
pub use encode::{
    EncodeOptions, encode_into, encode_structure_into, encoded_len, structure_encoded_len,
};
pub use format::{MeshLayout, StructureKind};
pub(crate) use header::BlobHeader;
pub use mesh::BlobMesh;
pub use source::{BlobSource, BvhSections};
pub use structure::BlobStructure;
pub use structure_config::StructureConfig;
pub use tree::BlobTree;
pub use view::BlobView;
#[cfg(feature = "alloc")]
pub(crate) use view::same_bounds;
#[cfg(feature = "blob-winding")]
pub use winding::BlobWindingTree;
#[cfg(feature = "blob-winding")]
pub use winding_nodes::BlobWindingNodes;
