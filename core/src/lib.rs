//! # meshq
//!
//! Geometric queries on triangle meshes — ray casts, closest points, overlaps — from structures
//! that live in memory the caller owns. `#![no_std]`, no allocation, no `unsafe`, no panics on
//! any input, and bit-identical answers on every target (x86_64, wasm32, Cortex-M).
//!
//! ```
//! use meshq::{bvh::{self, Bvh, BuildConfig, BvhNode, PrimRef}, math::{Ray, Vec3}, mesh::MeshRef};
//! # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
//! # let triangles = [[0u32, 1, 2]];
//! let mesh = MeshRef::new(&positions, &triangles).validate()?;
//! let (mut nodes, mut order, mut scratch) =
//!     ([BvhNode::EMPTY; bvh::node_capacity(1)], [0u32; 1], [PrimRef::EMPTY; 1]);
//! let bvh = Bvh::build(&mesh, &BuildConfig::default(), &mut nodes, &mut order, &mut scratch)?;
//! let hit = bvh.raycast(&mesh, &Ray::new(Vec3::new(0.25, 0.25, 1.0), -Vec3::Z));
//! assert_eq!(hit.map(|h| h.tri), Some(0));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Data flow
//!
//! ```text
//! positions + indices ──validate──▶ ValidMesh ──build──▶ Bvh (a view over your buffers)
//!                                                          │
//!                                                          ▼
//!                                   raycast · raycast_any · closest_point · overlap_aabb/sphere
//! ```
//!
//! ## Modules
//! - [`math`]: [`Aabb`](math::Aabb), [`Ray`](math::Ray), [`Triangle`](math::Triangle),
//!   [`RayHit`](math::RayHit), [`ClosestPoint`](math::ClosestPoint).
//! - [`geom`]: exact pairwise tests, `<op>_<a>_<b>` (ray–plane, ray–box, ray–triangle in
//!   Möller–Trumbore and watertight forms, closest points on plane/segment/triangle,
//!   point-in-triangle, segment–segment, line–line, triangle–triangle, triangle–box).
//! - [`mesh`]: [`MeshRef`](mesh::MeshRef) and its validation into [`ValidMesh`](mesh::ValidMesh).
//! - [`bvh`]: the binned-SAH BVH, its builder, traversal, queries, refit and validator, and
//!   [`WideBvh`](bvh::WideBvh), the same tree collapsed four-wide for faster queries.
//! - [`query`]: the [`MeshQuery`](query::MeshQuery) trait every structure implements.
//! - [`error`]: [`MeshError`](error::MeshError), [`BuildError`](error::BuildError),
//!   [`StructureError`](error::StructureError).
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
//!
//! Features add API only; none changes a layout, a wire format or a result.
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

#[cfg(feature = "blob")]
pub mod blob;
pub mod bvh;
pub mod error;
pub mod geom;
pub mod math;
pub mod mesh;
pub mod query;
