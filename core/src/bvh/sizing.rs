//! The limits and sizes every BVH buffer and traversal stack is planned with.

/// The deepest tree any builder makes and any loader accepts (the root is level 1).
///
/// Every traversal keeps a fixed stack of this many entries, which therefore can never
/// overflow.
pub const MAX_DEPTH: u32 = 64;

/// Nodes needed for a tree over `tri_count` triangles: `2·n − 1` (0 for no triangles). The
/// order array and the build scratch take one entry per triangle; packed triangles one per
/// triangle; a four-wide tree [`wide_node_capacity`](crate::wide::wide_node_capacity).
#[must_use]
pub const fn node_capacity(tri_count: usize) -> usize {
    if tri_count == 0 {
        0
    } else {
        tri_count.saturating_mul(2) - 1
    }
}
