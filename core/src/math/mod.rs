//! Plain value types shared by every module: boxes, rays, triangles, hits and the few scalar
//! helpers the kernels need.
//!
//! All arithmetic is `f32` with a fixed order of operations and no fused multiply-add, so the
//! same inputs give the same bits on every target.

mod aabb;
mod hit;
mod morton;
mod plane;
mod ray;
mod scalar;
mod triangle;

pub use aabb::Aabb;
pub use hit::{ClosestPoint, RayHit, TriangleFeature};
pub use morton::morton_code;
pub use plane::Plane;
pub use ray::Ray;
pub use scalar::{cross, dot, max_f32, min_f32};
pub use triangle::Triangle;

pub use glam::{Vec2, Vec3};
