//! A four-wide BVH collapsed from a binary one, for faster queries.
//!
//! ```
//! use meshq::{bvh::{self, Bvh, BuildConfig, BvhNode, PrimRef, WideNode}, math::{Ray, Vec3}, mesh::MeshRef};
//! let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
//! let mesh = MeshRef::new(&positions, &[[0, 1, 2], [0, 1, 3], [0, 2, 3]]).validate()?;
//! let mut nodes = [BvhNode::EMPTY; bvh::node_capacity(3)];
//! let (mut order, mut scratch) = ([0u32; 3], [PrimRef::EMPTY; 3]);
//! let config = BuildConfig { max_leaf_size: 1, ..BuildConfig::default() };
//! let bvh = Bvh::build(&mesh, &config, &mut nodes, &mut order, &mut scratch)?;
//! let mut wide_nodes = [WideNode::EMPTY; 2];
//! let wide = bvh.widen(&mut wide_nodes[..bvh.wide_node_count()])?;
//! let ray = Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z);
//! assert_eq!(wide.raycast(&mesh, &ray), bvh.raycast(&mesh, &ray));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod collapse;
pub(crate) mod lanes;
mod node;
pub(crate) mod traverse;
mod tree;

pub use node::WideNode;
pub use tree::WideBvh;
