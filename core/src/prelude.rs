//! The names most code needs, in one line: `use meshq::prelude::*;`.
//!
//! Brings the traits whose methods the queries are ([`MeshQuery`], [`Traverse`]), the mesh
//! types, the BVH and its buffers, the wide tree, rays and results, and the sizing modules
//! (`bvh::node_capacity`, `wide::wide_node_capacity`).

#[cfg(feature = "blob")]
pub use crate::blob::BlobView;
pub use crate::bvh::{self, BuildConfig, Bvh, BvhBuffers, BvhNode, PrimRef};
pub use crate::math::{Aabb, ClosestPoint, PackedTriangle, Ray, RayHit, Vec3};
pub use crate::mesh::{MeshRef, ValidMesh};
#[cfg(feature = "alloc")]
pub use crate::owned::MeshBvh;
pub use crate::query::{MeshQuery, PackedTriangles, RayOptions, Traverse};
pub use crate::wide::{self, CollapsePlan, PlanEntry, WideBvh, WideNode};
