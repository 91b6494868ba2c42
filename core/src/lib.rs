//! # meshq
//!
//! Geometric queries on triangle meshes — ray casts, closest points, overlaps — from structures
//! that live in memory the caller owns. `#![no_std]`, no allocation, no `unsafe`, no panics on
//! any input, and bit-identical answers on every target (x86_64, wasm32, Cortex-M).
//!
//! ```
//! use meshq::prelude::*;
//! # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
//! # let triangles = [[0u32, 1, 2]];
//! let mesh = MeshRef::new(&positions, &triangles).validate()?;
//! let mut buffers = BvhBuffers::<1>::new();
//! let bvh = buffers.build(&mesh, &BuildConfig::default())?;
//! let hit = bvh.with(&mesh).raycast(&Ray::new(Vec3::new(0.25, 0.25, 1.0), -Vec3::Z));
//! assert_eq!(hit.map(|h| h.tri), Some(0));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Data flow
//!
//! ```text
//! positions + indices ──validate──▶ ValidMesh ──build──▶ Bvh ──widen──▶ WideBvh  (views over your buffers)
//!                                                        │
//!                                                   encode_into ──▶ blob bytes ──parse──▶ BlobView
//!
//! structure.with(&triangles) · BlobView · MeshBvh ──▶ MeshQuery: raycast · raycast_any ·
//!     closest_point · raycast_batch · raycast_any_batch · closest_points · overlap_aabb/sphere
//! ```
//!
//! ## Modules
//! - [`math`]: [`Aabb`], [`Aabb4`](math::Aabb4), [`Obb`](math::Obb), [`Ray`],
//!   [`Triangle`](math::Triangle), [`PackedTriangle`](math::PackedTriangle),
//!   [`RayHit`], [`ClosestPoint`].
//! - [`geom`]: exact pairwise tests, `<op>_<a>_<b>` (ray–plane, ray–box, ray–triangle in
//!   Möller–Trumbore and watertight forms, closest points on plane/segment/triangle,
//!   point-in-triangle, segment–segment, line–line, triangle–triangle, triangle–box,
//!   triangle–oriented box).
//! - [`mesh`]: [`MeshRef`] and its validation into [`ValidMesh`].
//! - [`query`]: the query layer every structure shares: [`Traverse`] (what a
//!   structure implements), [`Visitor`](query::Visitor) (what a query is),
//!   [`MeshQuery`] (every query), leaf access and batches.
//! - [`bvh`]: the binned-SAH BVH, its builder, traversal, refit and validator.
//! - [`wide`]: [`WideBvh`], the same tree collapsed four-wide.
//! - [`kdtree`], [`octree`], [`grid`]: the structures that cut space into cells, on what they
//!   share in [`cells`] (reference padding, the depth-first build inside one references
//!   buffer, packed references, figures).
//! - [`inside`]: inside, outside and how far — generalized winding numbers (fast, on open
//!   and non-manifold meshes too), containment and signed distance.
//! - [`collide`]: where meshes meet — two meshes (each with its BVH, the second placed by an
//!   [`Affine`](collide::Affine) map) or one mesh with itself: yes/no, the triangle pairs,
//!   the crossing segments.
//! - [`remesh`]: isotropic remeshing in caller buffers.
//! - [`error`]: [`MeshError`](error::MeshError), [`BuildError`](error::BuildError),
//!   [`StructureError`](error::StructureError), [`BatchError`](error::BatchError).
//! - [`prelude`]: the names most code needs, in one `use`.
//! - `parallel` (feature `parallel`): the batches spread over a thread pool, with the same
//!   answers.
//!
//! ## Conventions
//! - `f32` everywhere, no fused multiply-add, transcendental functions only through `libm`.
//! - Ray directions are not normalized; `t` is in units of the direction's length and hits lie
//!   in `[t_min, t_max]` (inclusive).
//! - Ties go to the lower triangle index, so every structure and target agrees.
//! - Degenerate (zero-area) triangles stay in the mesh and are never returned by a query.
//! - Counter-clockwise triangles face the side their normal `(b − a) × (c − a)` points to.
//!
//! ## Features
//! - `blob`: prebuilt blobs (module `blob`): encode a BVH and its mesh with postcard and query them
//!   in place from bytes. Adds `postcard` and `crc` (both `no_std`, no allocation).
//! - `alloc`: `MeshBvh`, `MeshKdTree`, `MeshOctree`, `MeshGrid` and `MeshIndex` (module
//!   `owned`), each one value that sizes, owns and builds every buffer
//!   of its structure and answers every query; with `blob`, `MeshBvh`
//!   round-trips blobs too. Links the `alloc` crate; without this feature the crate links no
//!   allocator.
//! - `std`: links the standard library for what only it can do, find CPU features at run
//!   time. With `blob`, on x86, x86-64 and AArch64, blob checksums are then computed with the
//!   CPU's carry-less multiply or CRC32 instructions where present (through `crc32fast`);
//!   the same checksums. Not for firmware.
//! - `parallel`: batches and builds on rayon's thread pool (module `parallel`); implies `std`.
//!
//! Features add API (`std` only speed); none changes a layout, a wire format or a result.
#![cfg_attr(not(test), no_std)]
#![forbid(unsafe_code)]
#![deny(missing_docs)]
#![deny(clippy::std_instead_of_core, clippy::alloc_instead_of_core)]
#![cfg_attr(
    not(test),
    deny(
        clippy::unwrap_used,
        clippy::expect_used,
        clippy::panic,
        clippy::indexing_slicing
    )
)]

#[cfg(feature = "alloc")]
extern crate alloc;

pub mod advanced;
#[cfg(feature = "blob")]
pub mod blob;
pub mod bvh;
pub mod cells;
pub mod collide;
pub mod error;
pub mod geom;
pub mod grid;
pub mod inside;
pub mod kdtree;
pub mod math;
pub mod mesh;
pub mod octree;
#[cfg(feature = "alloc")]
pub mod owned;
#[cfg(feature = "parallel")]
pub mod parallel;
pub mod prelude;
pub mod query;
pub mod remesh;
mod structure_kind;
#[cfg(test)]
mod test_floats;
pub mod wide;

#[cfg(feature = "blob")]
pub use blob::BlobView;
pub use bvh::{BuildConfig, Bvh, BvhBuffers};
pub use math::{Aabb, ClosestPoint, Ray, RayHit, Vec3};
pub use mesh::{MeshRef, ValidMesh};
#[cfg(feature = "alloc")]
pub use owned::MeshBvh;
pub use query::{MeshQuery, RayOptions, Traverse};
pub use structure_kind::{StructureKind, UnknownStructure};
pub use wide::WideBvh;
