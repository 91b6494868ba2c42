//! Plain value types shared by every module: boxes, rays, triangles, hits and the few scalar
//! helpers the kernels need.
//!
//! All arithmetic is `f32` with a fixed order of operations and no fused multiply-add, so the
//! same inputs give the same bits on every target.

mod aabb;
pub(crate) mod aabb4;
pub(crate) mod aabb8;
mod hit;
mod morton;
mod obb;
pub(crate) mod packed_triangle;
mod plane;
mod ray;
mod scalar;
mod triangle;

pub use aabb::Aabb;
pub(crate) use aabb4::Aabb4;
pub(crate) use aabb8::Aabb8;
pub use hit::{ClosestPoint, RayHit, TriangleFeature};
pub(crate) use morton::morton_code;
pub use obb::Obb;
pub(crate) use packed_triangle::PackedTriangle;
pub use plane::Plane;
pub use ray::Ray;
pub use scalar::{cross, dot};
pub(crate) use scalar::{max_f32, min_f32, unit_scale, unit_scale_of_squares};
pub use triangle::Triangle;

pub use glam::{Vec2, Vec3};

/// The largest coordinate magnitude a valid mesh may have: 2⁵⁰ ≈ 1.1·10¹⁵ (also
/// `mesh::MAX_COORDINATE`).
///
/// Edge vectors and their cross products stay far from `f32` overflow below this bound.
pub const MAX_COORDINATE: f32 = 1_125_899_906_842_624.0;
