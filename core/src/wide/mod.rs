//! A four-wide BVH collapsed from a binary one, whose queries take fewer, fuller steps: the one
//! structure built from another (a [`Bvh`](crate::bvh::Bvh)).
//!
//! ```
//! use meshq::prelude::*;
//! let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
//! let mesh = MeshRef::new(&positions, &[[0, 1, 2], [0, 1, 3], [0, 2, 3]]).validate()?;
//! let mut buffers = BvhBuffers::<3>::new();
//! let config = BuildConfig { max_leaf_size: 1, ..BuildConfig::default() };
//! let bvh = buffers.build(&mesh, &config)?;
//! let mut wide_nodes = [WideNode::EMPTY; wide::wide_node_capacity(3)];
//! let wide = bvh.widen(&mut wide_nodes)?;
//! let ray = Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z);
//! assert_eq!(wide.with(&mesh).raycast(&ray), bvh.with(&mesh).raycast(&ray));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod collapse;
mod node;
mod traverse;
mod tree;

pub use node::WideNode;
pub use tree::WideBvh;

/// Wide nodes [`Bvh::widen`](crate::bvh::Bvh::widen) may write for a tree over `tri_count`
/// triangles: one per inner binary node at most (`n − 1`), 1 for a lone leaf, 0 for none. Size
/// a buffer with it to widen without counting first; [`Bvh::wide_node_count`] gives the
/// exact count of a built tree.
///
/// [`Bvh::wide_node_count`]: crate::bvh::Bvh::wide_node_count
#[must_use]
pub const fn wide_node_capacity(tri_count: usize) -> usize {
    if tri_count <= 1 {
        tri_count
    } else {
        tri_count - 1
    }
}
