//! How the structures are made inside: the collapse plan of the wide trees, the word codecs
//! of the cell structures, SIMD lane boxes and the tuning constants of the builders and the
//! walks. Nothing here is needed to build, store or query a structure; it is for tools and
//! tests that inspect or reproduce a build step by step, and it may change between versions
//! more freely than the rest of the crate.

pub use crate::cells::pack::pack_references;
pub use crate::cells::words::{LeWords, TwoWordNode, Words};
pub use crate::math::aabb4::Aabb4;
pub use crate::math::aabb8::Aabb8;
pub use crate::math::packed_triangle::PackedTriangle;
pub use crate::query::split_refs::{SPLIT_REF_BYTES, SplitRefs};
pub use crate::wide::plan::{CollapsePlan, NODE_COST, plan_capacity};
pub use crate::wide::roles::{CollapseRoles, MERGED_LEAF_MAX};
pub use crate::wide::traverse::WARM_TREE_BYTES;
