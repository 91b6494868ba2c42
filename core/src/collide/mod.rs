//! Where meshes meet: two meshes, each with its BVH, or one mesh with itself.
//!
//! - [`meshes_intersect`], [`intersecting_pairs`] and [`intersection_segments`] walk two
//!   BVHs together from their roots, the second mesh placed in the first one's frame by an
//!   optional [`Affine`] map, and test triangle pairs at the leaves with
//!   [`intersect_triangle_triangle`](crate::geom::intersect_triangle_triangle): a yes/no that
//!   stops at the first pair, every pair, or the crossing segments for drawing.
//! - [`mesh_distance`] finds the closest pair of points of two meshes (the second placed
//!   likewise), by a best-first walk that drops pairs of nodes farther apart than the best
//!   pair so far, with a maximum distance and an early stop.
//! - [`walk_pairs`] is the walk they share, opened to the caller (three-mesh-bvh's
//!   `bvhcast`): a [`PairVisitor`] scores pairs of nodes (which to skip, which first) and
//!   sees pairs of triangles.
//! - [`self_intersects`] and [`self_intersecting_pairs`] walk one BVH against itself and judge
//!   neighbouring triangles by what they share: touching along a shared edge or corner is not
//!   an intersection, crossing beyond it or folding over is.
//!
//! Results go into caller buffers with the true count ([`Found`]); nothing allocates, and
//! the walks use fixed stacks bounded by the trees' depth. Every walk takes a [`PairBudget`],
//! the most triangle pairs it may consider, so that meshes whose triangles no box separates
//! (copies of one triangle, triangles at one point) end in a typed error, not in work that
//! grows with the square of the count.

mod affine;
mod budget;
mod found;
mod mesh_distance;
mod mesh_mesh;
mod neighbours;
mod pair_walk;
mod self_intersect;
mod tree_pairs;

pub use affine::Affine;
pub use budget::PairBudget;
pub use found::{CrossingSegment, Found, TrianglePair};
pub use mesh_distance::{DistanceLimits, MeshDistance, mesh_distance};
pub use mesh_mesh::{intersecting_pairs, intersection_segments, meshes_intersect};
pub use pair_walk::{PairVisitor, WalkedTriangle, walk_pairs};
#[doc(hidden)]
pub use self_intersect::touching_pairs_unfiltered;
pub use self_intersect::{self_intersecting_pairs, self_intersects};
