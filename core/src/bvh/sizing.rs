//! The limits and sizes every BVH buffer and traversal stack is planned with.

/// The deepest tree any builder makes and any loader accepts (the root is level 1).
///
/// Every traversal keeps a fixed stack of this many entries, which therefore can never
/// overflow.
pub const MAX_DEPTH: u32 = 64;

/// The buffer sizes of a BVH build, from [`Bvh::measure`](super::Bvh::measure): enough for every mesh of that many
/// triangles, so buffers can be sized before the mesh is at hand (or in a `const`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BvhSizes {
    /// Nodes: `2·r − 1` for `r` references (0 for none).
    pub nodes: usize,
    /// Order slots and scratch entries: one per reference, `r`.
    pub order: usize,
    /// Split references: 0 without spatial splits, two per extra reference with them.
    pub split_refs: usize,
}

/// Nodes needed for a tree over `count` references: `2·n − 1` (0 for none).
pub(crate) const fn node_capacity(count: usize) -> usize {
    if count == 0 {
        0
    } else {
        count.saturating_mul(2) - 1
    }
}
