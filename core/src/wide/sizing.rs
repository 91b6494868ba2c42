//! How big the buffers of a collapse are.

/// The buffer sizes of a wide build, from [`WideBvh::measure`](super::WideBvh::measure).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct WideSizes {
    /// Plan entries of scratch: one per inner binary node (half the binary nodes, rounded
    /// down).
    pub plan: usize,
    /// Most wide nodes the collapse writes: one per inner binary node at most (`n − 1` for `n`
    /// triangles), 1 for a lone leaf, 0 for none. The collapse may write fewer.
    pub nodes: usize,
}

/// Most wide nodes a collapse of a tree over `tri_count` triangles writes ([`WideSizes::nodes`]).
pub(crate) const fn wide_node_capacity(tri_count: usize) -> usize {
    if tri_count <= 1 {
        tri_count
    } else {
        tri_count - 1
    }
}
