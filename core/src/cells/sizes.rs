//! What a cell tree build needs and made.

/// The buffer sizes of a k-d tree or octree build, from its `measure` pass.
///
/// The build keeps the references of cells still to split in the same buffer as the finished
/// leaves, so it needs more room while it runs (`work`) than the finished tree keeps
/// (`items`). A references buffer of `work` entries, with `nodes` nodes, builds exactly the
/// measured tree; the tree then uses the first `items` entries.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TreeSizes {
    /// Nodes of the tree.
    pub nodes: usize,
    /// References the finished tree holds.
    pub items: usize,
    /// References buffer length the build needs.
    pub work: usize,
    /// True when no cell stayed a leaf for lack of room: the tree is the one the config
    /// describes. False when the measuring buffer ran short: the sizes are those of the
    /// smaller tree that buffer allows, and a longer one may refine further.
    pub complete: bool,
}
