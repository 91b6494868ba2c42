//! Bounding volume hierarchy over a mesh's triangles, built with binned SAH into caller
//! buffers.
//!
//! ```
//! use meshq::{bvh::{self, Bvh, BuildConfig, BvhNode, PrimRef}, math::{Ray, Vec3}, mesh::MeshRef};
//! let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
//! let mesh = MeshRef::new(&positions, &[[0, 1, 2]]).validate()?;
//! let mut nodes = [BvhNode::EMPTY; bvh::node_capacity(1)];
//! let mut order = [0u32; 1];
//! let mut scratch = [PrimRef::EMPTY; 1];
//! let bvh = Bvh::build(&mesh, &BuildConfig::default(), &mut nodes, &mut order, &mut scratch)?;
//! let hit = bvh.raycast(&mesh, &Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z));
//! assert_eq!(hit.map(|h| (h.tri, h.t)), Some((0, 1.0)));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Layout: a flat array of 32-byte [`BvhNode`]s, root at index 0, the two children of an inner
//! node adjacent and always after their parent; leaves name a range of the `order` array, which
//! maps back to the mesh's own triangle indices (the mesh itself is never reordered).

mod arrays;
mod batch_order;
mod binning;
mod build;
mod build_box;
mod centre;
pub(crate) mod check;
pub(crate) mod closest;
pub(crate) mod closest_batch;
mod config;
mod lanes;
mod leaf_batches;
mod median;
mod node;
pub(crate) mod overlap;
mod packed;
mod partition;
mod prim_ref;
pub(crate) mod raycast;
pub(crate) mod raycast_batch;
mod refit;
mod stats;
pub(crate) mod traverse;
mod tree;
mod wide;

pub use arrays::{LeafTriangleIds, TreeArrays};
pub use config::{BuildConfig, SplitStrategy};
pub use node::BvhNode;
pub use overlap::OverlapCount;
pub use packed::{LeafTriangles, PackedTriangle, PackedTriangles};
pub use prim_ref::PrimRef;
pub use raycast::{RayOptions, TriangleTest};
pub use stats::{LEAF_HISTOGRAM_LEN, TreeStats};
pub use traverse::BvhVisitor;
pub use tree::Bvh;
pub use wide::{WideBvh, WideNode};

/// The deepest tree any builder makes and any loader accepts (the root is level 1).
///
/// Every traversal keeps a fixed stack of this many entries, which therefore can never
/// overflow.
pub const MAX_DEPTH: u32 = 64;

/// Nodes needed for a tree over `tri_count` triangles: `2·n − 1` (0 for no triangles).
#[must_use]
pub const fn node_capacity(tri_count: usize) -> usize {
    if tri_count == 0 {
        0
    } else {
        tri_count.saturating_mul(2) - 1
    }
}
