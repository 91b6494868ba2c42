//! Four- and eight-wide BVHs collapsed from a binary one, whose queries take fewer, fuller
//! steps: the structures built from another (a [`Bvh`](crate::bvh::Bvh)).
//!
//! ```
//! use meshq::prelude::*;
//! use meshq::bvh;
//! use meshq::wide::{self, CollapsePlan, PlanEntry, WideBvh, WideNode};
//! let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
//! let mesh = MeshRef::new(&positions, &[[0, 1, 2], [0, 1, 3], [0, 2, 3]]).validate()?;
//! let mut buffers = BvhBuffers::<3>::new();
//! let config = BuildConfig { max_leaf_size: 1, ..BuildConfig::default() };
//! let bvh = buffers.build(&mesh, &config)?;
//! // One plan entry per binary node: which binary nodes become each wide node's lanes.
//! let mut entries = [PlanEntry::EMPTY; bvh::node_capacity(3)];
//! let plan = CollapsePlan::<4>::new(&bvh, &mut entries)?;
//! let mut wide_nodes = [WideNode::EMPTY; wide::wide_node_capacity(3)];
//! let wide = WideBvh::build(&plan, &mut wide_nodes)?;
//! let ray = Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z);
//! assert_eq!(wide.with(&mesh).raycast(&ray), bvh.with(&mesh).raycast(&ray));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub(crate) mod collapse;
mod compact_node;
mod node;
mod node8;
#[cfg(feature = "parallel")]
pub(crate) mod parallel_collapse;
mod plan;
mod roles;
mod sizing;
mod traverse;
mod tree;
mod walk;

pub use compact_node::CompactNode;
pub use node::WideNode;
pub use node8::WideNode8;
pub use plan::{CollapsePlan, NODE_COST, PlanEntry, plan_capacity};
pub use roles::{CollapseRoles, MERGED_LEAF_MAX};
pub use sizing::wide_node_capacity;
pub use traverse::WARM_TREE_BYTES;
pub use tree::{WideBvh, WideNodeKind};
