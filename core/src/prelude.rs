//! The names most code needs, in one line: `use meshq::prelude::*;`.
//!
//! Brings what the README's examples use: the traits whose methods the queries are
//! ([`MeshQuery`], [`Traverse`]), the mesh types, the BVH with its buffers and config, the
//! owned `MeshBvh` (feature `alloc`) and `BlobView` (feature `blob`), rays and results.
//! Everything else is in its module: [`bvh`](crate::bvh), [`wide`](crate::wide),
//! [`kdtree`](crate::kdtree), [`query`](crate::query), …

#[cfg(feature = "blob")]
pub use crate::blob::BlobView;
pub use crate::bvh::{BuildConfig, Bvh, BvhBuffers};
pub use crate::math::{Aabb, ClosestPoint, Ray, RayHit, Vec3};
pub use crate::mesh::{MeshRef, ValidMesh};
#[cfg(feature = "alloc")]
pub use crate::owned::MeshBvh;
pub use crate::query::{MeshQuery, RayOptions, Traverse};
