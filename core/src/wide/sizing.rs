//! How many wide nodes a collapse may write.

/// Wide nodes [`WideBvh::build`](super::WideBvh::build) may write for a tree over `tri_count`
/// triangles: one per inner binary node at most (`n − 1`), 1 for a lone leaf, 0 for none. Size
/// a buffer with it to widen without counting first;
/// [`CollapsePlan::node_count`](super::CollapsePlan::node_count) gives the exact count for a
/// planned tree.
#[must_use]
pub const fn wide_node_capacity(tri_count: usize) -> usize {
    if tri_count <= 1 {
        tri_count
    } else {
        tri_count - 1
    }
}
