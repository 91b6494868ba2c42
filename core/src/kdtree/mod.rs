//! The k-d tree: the mesh bounds cut recursively by axis-aligned planes chosen by the surface-area
//! heuristic, each leaf cell listing the triangles it touches.
//!
//! - [`KdConfig`]: depth limit, leaf size and the heuristic's costs.
//! - [`KdTree::measure`]: the exact sizes; [`KdTree::build`]: the build into caller buffers,
//!   staying inside them.
//! - [`KdNode`]: two words per node.
//! - [`KdTree`]: the built tree, answering every query of the [query layer](crate::query): rays
//!   front to back with early exit once a hit lies inside the current cell, the rest nearest
//!   cell first.
//!
//! Unlike a BVH, a k-d tree's cells never overlap, so a ray visits them strictly in order and
//! stops at the first cell that holds its hit; the price is triangles referenced from several
//! cells.
//!
//! ```
//! use meshq::prelude::*;
//! use meshq::advanced::KdNode;
//! use meshq::kdtree::{KdConfig, KdTree};
//! # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
//! # let triangles = [[0u32, 1, 2]];
//! let mesh = MeshRef::new(&positions, &triangles).validate()?;
//! let mut work = vec![0; 4 * mesh.triangle_count()];
//! let sizes = KdTree::measure(&mesh, &KdConfig::default(), &mut work)?;
//! let mut nodes = vec![KdNode::default(); sizes.nodes];
//! let mut items = vec![0; sizes.work];
//! let tree = KdTree::build(&mesh, &KdConfig::default(), &mut nodes, &mut items)?;
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

pub use config::KdConfig;
pub(crate) use node::{KdKind, KdNode};
pub use tree::KdTree;
