//! Bounding volume hierarchy over a mesh's triangles, built with binned SAH into caller
//! buffers.
//!
//! ```
//! use meshq::prelude::*;
//! use meshq::advanced::{BvhNode, PrimRef}; // the buffers' element types
//! let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
//! let mesh = MeshRef::new(&positions, &[[0, 1, 2]]).validate()?;
//! // Caller-owned buffers, sized by `measure`...
//! let sizes = Bvh::measure(mesh.triangle_count(), None);
//! let mut nodes = vec![BvhNode::EMPTY; sizes.nodes];
//! let mut order = vec![0u32; sizes.order];
//! let mut scratch = vec![PrimRef::EMPTY; sizes.order];
//! let bvh = Bvh::build(&mesh, &BuildConfig::default(), &mut nodes, &mut order, &mut scratch)?;
//! let hit = bvh.with(&mesh).raycast(&Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z));
//! assert_eq!(hit.map(|h| (h.tri, h.t)), Some((0, 1.0)));
//!
//! // ...or all of them in one value.
//! let mut buffers = BvhBuffers::<1>::new();
//! let again = buffers.build(&mesh, &BuildConfig::default())?;
//! assert_eq!(again.nodes(), bvh.nodes());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Layout: a flat array of 32-byte [`BvhNode`]s, root at index 0, the two children of an inner
//! node adjacent and always after their parent; leaves name a range of the `order` array, which
//! maps back to the mesh's own triangle indices (the mesh itself is never reordered).

pub(crate) mod arrays;
mod binning;
mod buffers;
mod build;
mod build_box;
mod centre;
mod centroid_sort;
pub(crate) mod check;
mod clip;
mod config;
mod lanes;
mod median;
pub(crate) mod node;
mod packed;
#[cfg(feature = "parallel")]
mod parallel_build;
#[cfg(feature = "parallel")]
mod parallel_spatial;
mod partition;
pub(crate) mod prim_ref;
mod refit;
mod sizing;
mod spatial;
mod spatial_bins;
mod spatial_build;
mod spatial_compact;
#[cfg(feature = "blob")]
pub(crate) mod split_coverage;
pub(crate) mod stats;
mod sweep_sah;
mod traverse;
mod tree;

pub(crate) use arrays::TreeArrays;
pub use buffers::BvhBuffers;
pub use config::{BuildConfig, SplitStrategy};
pub(crate) use node::BvhNode;
pub(crate) use prim_ref::PrimRef;
pub(crate) use sizing::node_capacity;
pub use sizing::{BvhSizes, MAX_DEPTH};
pub use spatial::SpatialSplits;
pub use tree::Bvh;
