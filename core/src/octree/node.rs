//! The octree node: two words.

use crate::cells::TwoWordNode;

/// Marks an inner node in [`OctreeNode::b`].
const INNER: u32 = u32::MAX;

/// One octree node in two `u32` words.
///
/// - Inner node: `b` is `u32::MAX`, `a` its first child; its eight children are nodes `a..a + 8`,
///   after it, child `k` being the octant with `x` above the middle when bit 0 of `k` is set,
///   `y` for bit 1, `z` for bit 2.
/// - Leaf: `a` is its first reference, `b` the count.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct OctreeNode {
    /// First child, or first reference.
    pub a: u32,
    /// `u32::MAX` for an inner node, or the reference count.
    pub b: u32,
}

impl OctreeNode {
    /// An inner node whose children start at `first_child`.
    #[must_use]
    pub const fn inner(first_child: u32) -> Self {
        Self {
            a: first_child,
            b: INNER,
        }
    }

    /// A leaf holding references `first..first + count` (`count` below `u32::MAX`).
    #[must_use]
    pub const fn leaf(first: u32, count: u32) -> Self {
        Self { a: first, b: count }
    }

    /// The first child of an inner node; `None` for a leaf.
    #[inline(always)]
    #[must_use]
    pub const fn first_child(&self) -> Option<u32> {
        if self.b == INNER { Some(self.a) } else { None }
    }
}

impl TwoWordNode for OctreeNode {
    #[inline(always)]
    fn words(&self) -> [u32; 2] {
        [self.a, self.b]
    }
}
