//! Four- and eight-wide BVHs collapsed from a binary one, whose queries take fewer, fuller
//! steps: the structures built from another (a [`Bvh`](crate::bvh::Bvh)).
//!
//! ```
//! use meshq::prelude::*;
//! use meshq::advanced::{PlanEntry, WideNode};
//! use meshq::wide::WideBvh;
//! let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
//! let mesh = MeshRef::new(&positions, &[[0, 1, 2], [0, 1, 3], [0, 2, 3]]).validate()?;
//! let mut buffers = BvhBuffers::<3>::new();
//! let config = BuildConfig { max_leaf_size: 1, ..BuildConfig::default() };
//! let bvh = buffers.build(&mesh, &config)?;
//! // Scratch to plan which binary nodes become each wide node's lanes, and the nodes.
//! let sizes = WideBvh::<WideNode>::measure(&bvh);
//! let (mut plan, mut wide_nodes) = ([PlanEntry::EMPTY; 3], [WideNode::EMPTY; 3]);
//! assert!(sizes.plan <= plan.len() && sizes.nodes <= wide_nodes.len());
//! let wide = WideBvh::build(&bvh, &mut plan, &mut wide_nodes)?;
//! let ray = Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z);
//! assert_eq!(wide.with(&mesh).raycast(&ray), bvh.with(&mesh).raycast(&ray));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub(crate) mod collapse;
pub(crate) mod compact_node;
pub(crate) mod node;
pub(crate) mod node8;
mod node_build;
#[cfg(feature = "parallel")]
pub(crate) mod parallel_collapse;
pub(crate) mod plan;
pub(crate) mod roles;
mod sizing;
pub(crate) mod traverse;
mod tree;
mod walk;

pub(crate) use compact_node::CompactNode;
pub(crate) use node::WideNode;
pub(crate) use node8::WideNode8;
pub use sizing::WideSizes;
pub use tree::{WideBvh, WideNodeKind};
