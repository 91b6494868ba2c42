use super::collapse::CollapsedNode;
use crate::math::{Aabb, Aabb8};

/// One node of an eight-wide [`WideBvh`](super::WideBvh): the boxes of up to eight children side by side
/// (an [`Aabb8`], tested eight at a time), and what each child is. 256 bytes, four cache
/// lines. Lanes mean what a [`WideNode`](super::WideNode)'s do:
///
/// | bytes | field | meaning |
/// |-------|-------|---------|
/// | 0–191 | `bounds` | lane `i`: child `i`'s box |
/// | 192–223 | `child` | lane `i`: inner child's node index, leaf child's first order slot, or 0 |
/// | 224–255 | `count` | lane `i`: leaf child's triangle count (≥ 1), or 0 |
///
/// - an inner node: `count == 0`, `child` is its index in the node array (never 0, the root);
/// - a leaf: `count > 0` triangles in order slots `child..child + count`;
/// - unused: an empty box (`min = +∞`, `max = −∞`), `child == 0`, `count == 0`.
///
/// Inner lanes come first, then leaves, then unused lanes; inner lane `i`'s node index is
/// lane 0's plus `i` (a node's inner children are consecutive in the node array).
#[repr(C, align(64))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WideNode8 {
    /// The eight children's boxes.
    pub bounds: Aabb8,
    /// Inner child: node index; leaf child: first order slot; unused: 0.
    pub child: [u32; 8],
    /// Leaf child: triangle count (≥ 1); inner child or unused: 0.
    pub count: [u32; 8],
}

impl WideNode8 {
    /// A node with eight unused lanes, for initializing buffers.
    pub const EMPTY: Self = Self {
        bounds: Aabb8::EMPTY,
        child: [0; 8],
        count: [0; 8],
    };

    /// Number of used lanes (1 to 8 in a built node).
    #[must_use]
    pub fn lanes(&self) -> usize {
        self.bounds.used_mask().count_ones() as usize
    }

    /// True when every field of both nodes has the same bits (so `0.0` and `-0.0` differ).
    #[must_use]
    pub fn same_bits(&self, other: &Self) -> bool {
        self.bounds.same_bits(&other.bounds)
            && self.child == other.child
            && self.count == other.count
    }
}

impl CollapsedNode<8> for WideNode8 {
    const EMPTY: Self = WideNode8::EMPTY;
    fn same_bits(&self, other: &Self) -> bool {
        WideNode8::same_bits(self, other)
    }
    fn set_lane(&mut self, lane: usize, aabb: &Aabb, child: u32, count: u32) {
        self.bounds.set_lane(lane, aabb);
        if let (Some(c), Some(n)) = (self.child.get_mut(lane), self.count.get_mut(lane)) {
            *c = child;
            *n = count;
        }
    }
    #[cfg(feature = "parallel")]
    fn shift_inner(&mut self, by: u32) {
        super::collapse::shift_inner_lanes(&mut self.child, &self.count, by);
    }
}

const _: () = assert!(core::mem::size_of::<WideNode8>() == 256);
