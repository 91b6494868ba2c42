use crate::math::{Aabb, Aabb4};

/// One node of a [`WideBvh`](super::WideBvh): the boxes of up to four children side by side
/// (an [`Aabb4`], so a single SIMD operation tests a coordinate of all four), and what each
/// child is. 128 bytes, two cache lines.
///
/// | bytes | field | meaning |
/// |-------|-------|---------|
/// | 0–95 | `bounds` | lane `i`: child `i`'s box |
/// | 96–111 | `child` | lane `i`: inner child's node index, leaf child's first order slot, or 0 |
/// | 112–127 | `count` | lane `i`: leaf child's triangle count (≥ 1), or 0 |
///
/// A child *lane* is one of:
/// - an inner node: `count == 0`, `child` is its index in the node array (never 0, the root);
/// - a leaf: `count > 0` triangles in order slots `child..child + count`;
/// - unused: an empty box (`min = +∞`, `max = −∞`), `child == 0`, `count == 0`.
///
/// Inner lanes come first, then leaves, then unused lanes; inner lane `i`'s node index is
/// lane 0's plus `i` (a node's inner children are consecutive in the node array).
///
/// Boxes are the padded boxes of the binary tree the node was collapsed from.
#[repr(C, align(64))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WideNode {
    /// The four children's boxes.
    pub bounds: Aabb4,
    /// Inner child: node index; leaf child: first order slot; unused: 0.
    pub child: [u32; 4],
    /// Leaf child: triangle count (≥ 1); inner child or unused: 0.
    pub count: [u32; 4],
}

impl WideNode {
    /// A node with four unused lanes, for initializing buffers.
    pub const EMPTY: Self = Self {
        bounds: Aabb4::EMPTY,
        child: [0; 4],
        count: [0; 4],
    };

    /// Number of used lanes (1 to 4 in a built node).
    #[must_use]
    pub fn lanes(&self) -> usize {
        self.bounds.used_lanes()
    }

    /// True when every field of both nodes has the same bits (so `0.0` and `-0.0` differ).
    #[must_use]
    pub fn same_bits(&self, other: &Self) -> bool {
        self.bounds.same_bits(&other.bounds)
            && self.child == other.child
            && self.count == other.count
    }

    /// Writes `aabb`, `child` and `count` into lane `lane` (ignored for `lane ≥ 4`).
    pub(super) fn set_lane(&mut self, lane: usize, aabb: &Aabb, child: u32, count: u32) {
        self.bounds.set_lane(lane, aabb);
        if let (Some(c), Some(n)) = (self.child.get_mut(lane), self.count.get_mut(lane)) {
            *c = child;
            *n = count;
        }
    }
}

const _: () = assert!(core::mem::size_of::<WideNode>() == 128);
