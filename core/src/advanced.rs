//! How the structures are made inside: the node layouts, the collapse plan of the wide trees,
//! the blob records and header, the half-edge walk and edits of the remesher, the word codecs
//! of the cell structures, the planar and clipping kernels the builders use, SIMD lane boxes
//! and the tuning constants of the builders and the
//! walks. Nothing here is needed to build, store or query a structure; it is for tools and
//! tests that inspect or reproduce a build step by step, and it may change between versions
//! more freely than the rest of the crate.

#[cfg(feature = "blob")]
pub use crate::blob::checksum::mesh_checksum;
#[cfg(feature = "blob")]
pub use crate::blob::encode::reseal;
#[cfg(feature = "blob")]
pub use crate::blob::format::{
    FORMAT_VERSION, MAGIC, NEWEST_READABLE_VERSION, OLDEST_READABLE_VERSION,
};
#[cfg(feature = "blob")]
pub use crate::blob::header::BlobHeader;
pub use crate::bvh::arrays::TreeArrays;
pub use crate::bvh::node::BvhNode;
pub use crate::bvh::prim_ref::PrimRef;
pub use crate::bvh::stats::{LEAF_HISTOGRAM_LEN, TreeStats};
pub use crate::cells::pack::pack_references;
pub use crate::cells::words::{LeWords, TwoWordNode, Words};
pub use crate::geom::clip_triangle_aabb::{ClippedTriangle, clip_triangle_aabb};
pub use crate::geom::closest_point_triangle::closest_point_triangle_2d;
pub use crate::geom::line_line::{LineLine, intersect_line_line};
pub use crate::geom::point_in_triangle::{barycentric_triangle, point_in_triangle_2d};
pub use crate::grid::layout::GridLayout;
pub use crate::kdtree::node::{KdKind, KdNode};
pub use crate::math::aabb4::Aabb4;
pub use crate::math::aabb8::Aabb8;
pub use crate::math::packed_triangle::PackedTriangle;
pub use crate::octree::node::OctreeNode;
pub use crate::query::cell::Cell;
pub use crate::query::leaf::LeafTriangleIds;
pub use crate::query::split_refs::{SPLIT_REF_BYTES, SplitRef, SplitRefs};
pub use crate::query::traverse::BatchHint;
pub use crate::remesh::half_edge_edits::HalfEdgeEdits;
pub use crate::wide::compact_node::CompactNode;
pub use crate::wide::node::WideNode;
pub use crate::wide::node8::WideNode8;
pub use crate::wide::plan::PlanEntry;
pub use crate::wide::plan::{CollapsePlan, NODE_COST, plan_capacity};
pub use crate::wide::roles::{CollapseRoles, MERGED_LEAF_MAX};
pub use crate::wide::traverse::WARM_TREE_BYTES;
