//! Exact pairwise tests between primitives, as free functions named `<op>_<a>_<b>`.
//!
//! Every function takes plain values, allocates nothing, never panics, and documents what it
//! does with degenerate input (zero-length directions, zero-area triangles, parallel cases,
//! NaN). Each one lives in its own file.

pub(crate) mod aabb_lanes;
pub(crate) mod clip_triangle_aabb;
mod closest_pair;
mod closest_point_plane;
mod closest_point_segment;
pub(crate) mod closest_point_triangle;
mod closest_point_triangle_lanes;
mod closest_point_triangle_projection;
mod closest_point_triangle_rotation;
pub(crate) mod exact_orientation;
pub(crate) mod line_line;
pub(crate) mod obb_triangle_distance;
pub(crate) mod packet_aabb_lanes;
pub(crate) mod point_in_triangle;
mod point_on_plane;
mod point_on_segment;
mod ray_aabb;
mod ray_plane;
mod ray_triangle;
mod ray_triangle_two_step;
mod ray_triangle_watertight;
mod ray_triangle_watertight_lanes;
mod segment_segment;
mod segment_triangle_distance;
mod solid_angle_triangle;
#[cfg(test)]
mod test_support;
mod triangle_aabb;
mod triangle_lanes;
mod triangle_obb;
mod triangle_triangle;
mod triangle_triangle_distance;
pub(crate) mod triangles_meet;

pub(crate) use clip_triangle_aabb::clip_triangle_aabb;
pub use closest_pair::ClosestPair;
pub use closest_point_plane::closest_point_plane;
pub use closest_point_segment::closest_point_segment;
pub use closest_point_triangle::closest_point_triangle;
pub use closest_point_triangle_projection::closest_point_triangle_projection;
pub use closest_point_triangle_rotation::closest_point_triangle_rotation;
pub use obb_triangle_distance::closest_points_obb_triangle;
pub use point_in_triangle::point_in_triangle;
pub(crate) use point_in_triangle::point_in_triangle_2d;
pub use point_on_plane::point_on_plane;
pub use point_on_segment::point_on_segment;
pub use ray_aabb::intersect_ray_aabb;
pub use ray_plane::intersect_ray_plane;
pub use ray_triangle::{CullMode, TriangleHit, intersect_ray_triangle};
pub use ray_triangle_two_step::intersect_ray_triangle_two_step;
pub use ray_triangle_watertight::intersect_ray_triangle_watertight;
pub use segment_segment::{SegmentSegment, closest_points_segment_segment};
pub use segment_triangle_distance::closest_points_segment_triangle;
pub use solid_angle_triangle::solid_angle_triangle;
pub use triangle_aabb::overlap_triangle_aabb;
pub use triangle_obb::overlap_triangle_obb;
pub use triangle_triangle::{TriangleTriangle, intersect_triangle_triangle};
pub use triangle_triangle_distance::closest_points_triangle_triangle;
pub use triangles_meet::triangles_meet;

pub(crate) use closest_point_triangle::closest_point_regions;
pub(crate) use ray_aabb::SlabRay;
pub(crate) use ray_triangle::moller_trumbore;
pub(crate) use ray_triangle_two_step::two_step;
pub(crate) use ray_triangle_watertight::WatertightRay;
pub(crate) use ray_triangle_watertight_lanes::LaneHits;
pub(crate) use triangle_lanes::TriangleLanes;
