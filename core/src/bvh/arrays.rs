//! Read access to a BVH's two arrays wherever they are stored: in slices (a
//! [`Bvh`](super::Bvh)) or in the bytes of a blob, read in place.

use super::BvhNode;
use crate::query::LeafTriangleIds;
use crate::query::SplitRefs;

/// The node and order arrays of a binary BVH, read by index.
///
/// Traversal ([`Traverse`](crate::query::Traverse), so every query) and the validator are
/// written once over this trait, so a tree in caller slices ([`Bvh`](super::Bvh)) and a tree
/// read straight out of a blob's bytes run the same code and return the same bits.
/// Implementations return `None` for anything out of range; they never panic.
pub trait TreeArrays {
    /// Number of nodes (0 for an empty tree).
    fn node_count(&self) -> usize;

    /// Number of order slots: one per triangle (more with spatial splits).
    fn slot_count(&self) -> usize;

    /// Node `index` (the root is 0), or `None` past the end.
    fn node(&self, index: usize) -> Option<BvhNode>;

    /// Nodes `first` and `first + 1` (the two children of an inner node), or `None` unless both
    /// exist.
    fn node_pair(&self, first: usize) -> Option<[BvhNode; 2]>;

    /// The mesh triangle indices in order slots `first..first + count`, or `None` unless all of
    /// them exist.
    fn leaf_triangles(&self, first: usize, count: usize) -> Option<LeafTriangleIds<'_>>;

    /// The references of triangles the tree holds more than once (a tree built with spatial
    /// splits), for walks that report each triangle once; empty (the default) otherwise.
    fn split_refs(&self) -> SplitRefs<'_> {
        SplitRefs::NONE
    }
}
