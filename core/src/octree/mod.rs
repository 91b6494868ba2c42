//! The octree: a cube around the mesh split into octants wherever a cell holds too many
//! references, each leaf listing the triangles it touches.
//!
//! - [`OctreeConfig`]: maximum depth and items per leaf.
//! - [`Octree::measure`]: the exact sizes; [`Octree::build`]: the build into caller buffers,
//!   staying inside them.
//! - [`OctreeNode`]: two words per node.
//! - [`Octree`]: the built tree, answering every query of the [query layer](crate::query):
//!   octants nearest first (front to back along a ray), with early exit.
//!
//! An octree adapts to uneven geometry like a k-d tree but needs no split search: it builds
//! quickly and its cells are implicit (two words per node, no planes stored).
//!
//! ```
//! use meshq::prelude::*;
//! use meshq::advanced::OctreeNode;
//! use meshq::octree::{Octree, OctreeConfig};
//! # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
//! # let triangles = [[0u32, 1, 2]];
//! let mesh = MeshRef::new(&positions, &triangles).validate()?;
//! let mut work = vec![0; 4 * mesh.triangle_count()];
//! let sizes = Octree::measure(&mesh, &OctreeConfig::default(), &mut work)?;
//! let mut nodes = vec![OctreeNode::default(); sizes.nodes];
//! let mut items = vec![0; sizes.work];
//! let tree = Octree::build(&mesh, &OctreeConfig::default(), &mut nodes, &mut items)?;
//! let hit = tree.with(&mesh).raycast(&Ray::new(Vec3::new(0.25, 0.25, 1.0), -Vec3::Z));
//! assert_eq!(hit.map(|h| h.tri), Some(0));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod check;
mod config;
pub(crate) mod node;
mod split;
mod traverse;
mod tree;

pub use config::OctreeConfig;
pub(crate) use node::OctreeNode;
pub use tree::Octree;
