//! Inside, outside and how far: generalized winding numbers, containment and signed distance,
//! on open, non-manifold and self-intersecting meshes as on closed ones.
//!
//! A [`WindingTree`] pairs a BVH with one [`WindingNode`] per tree node, built bottom up into
//! a buffer you own ([`WindingTree::build`]); it answers
//! - [`winding_number`](WindingTree::winding_number): the signed solid angle the mesh subtends
//!   at a point, over `4π` (1 inside a closed outward-facing mesh, 0 outside, a fraction near
//!   holes), by Barill et al.'s fast winding number with a chosen [`WindingAccuracy`];
//! - [`contains`](WindingTree::contains): `|winding number| ≥ 1/2`;
//! - [`signed_distance`](WindingTree::signed_distance): the closest point with that sign,
//!   negative inside;
//!
//! each also as a batch, and signed distances over a lattice of samples
//! ([`signed_distance_grid`](WindingTree::signed_distance_grid) over a [`SampleGrid`]), with an
//! optional narrow band.
//!
//! [`PseudoNormals`] sign distances the other way, by Bærentzen and Aanæs's angle-weighted
//! pseudo-normal at the closest point: one closest-point search and no winding number, for
//! closed, manifold, consistently oriented meshes only (building them checks that).
//!
//! ```
//! use meshq::prelude::*;
//! use meshq::inside::{WindingAccuracy, WindingNode, WindingTree};
//! // A closed tetrahedron, its triangles facing outwards.
//! let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
//! let triangles = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
//! let mesh = MeshRef::new(&positions, &triangles).validate()?;
//! let mut buffers = BvhBuffers::<4>::new();
//! let bvh = buffers.build(&mesh, &BuildConfig::default())?;
//! let mut nodes = [WindingNode::EMPTY; 7];
//! let tree = WindingTree::build(bvh, mesh, &mut nodes)?;
//! let accuracy = WindingAccuracy::DEFAULT;
//! assert!(tree.contains(Vec3::splat(0.1), accuracy));
//! assert!(!tree.contains(Vec3::splat(1.0), accuracy));
//! let inside = tree.signed_distance(Vec3::splat(0.1), f32::INFINITY, accuracy).unwrap();
//! assert!((inside.distance + 0.1).abs() < 1e-6);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod accuracy;
mod expansion;
mod expansion_build;
mod pseudo_normals;
mod sample_grid;
mod signed_distance;
mod winding_batch;
mod winding_nodes;
mod winding_tree;
mod winding_walk;

pub use accuracy::WindingAccuracy;
pub use expansion::WindingNode;
pub use pseudo_normals::{EdgeEntry, PseudoNormalError, PseudoNormals};
pub use sample_grid::SampleGrid;
pub use signed_distance::SignedDistance;
pub use winding_nodes::WindingNodes;
pub use winding_tree::WindingTree;
