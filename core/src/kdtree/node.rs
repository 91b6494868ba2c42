//! The k-d tree node: two words.

use crate::cells::TwoWordNode;

/// Tag in the low two bits of [`KdNode::b`] marking a leaf (an inner node has its axis there).
const LEAF: u32 = 3;

/// One k-d tree node in two `u32` words.
///
/// - Inner node: `a` is the split plane (`f32` bits), `b` is `first_child << 2 | axis` (axis 0,
///   1 or 2). Its children are nodes `first_child` (below the plane) and `first_child + 1`
///   (above), both after it.
/// - Leaf: `a` is its first reference, `b` is `count << 2 | 3`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct KdNode {
    /// Split plane bits, or first reference.
    pub a: u32,
    /// Child and axis, or count and the leaf tag.
    pub b: u32,
}

/// A decoded [`KdNode`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum KdKind {
    /// Splits its cell at `split` along `axis`; children `first_child` (below) and
    /// `first_child + 1` (above).
    Inner {
        /// 0, 1 or 2.
        axis: usize,
        /// The plane's coordinate.
        split: f32,
        /// The lower child.
        first_child: u32,
    },
    /// References `first..first + count`.
    Leaf {
        /// First reference.
        first: u32,
        /// Reference count.
        count: u32,
    },
}

impl KdNode {
    /// An inner node (`first_child` below 2³⁰, `axis` below 3).
    #[must_use]
    pub const fn inner(axis: usize, split: f32, first_child: u32) -> Self {
        Self {
            a: split.to_bits(),
            b: (first_child << 2) | (axis as u32 & 3),
        }
    }

    /// A leaf (`count` below 2³⁰).
    #[must_use]
    pub const fn leaf(first: u32, count: u32) -> Self {
        Self {
            a: first,
            b: (count << 2) | LEAF,
        }
    }

    /// What the node is.
    #[inline(always)]
    #[must_use]
    pub const fn kind(&self) -> KdKind {
        let tag = self.b & 3;
        if tag == LEAF {
            KdKind::Leaf {
                first: self.a,
                count: self.b >> 2,
            }
        } else {
            KdKind::Inner {
                axis: tag as usize,
                split: f32::from_bits(self.a),
                first_child: self.b >> 2,
            }
        }
    }
}

impl TwoWordNode for KdNode {
    #[inline(always)]
    fn words(&self) -> [u32; 2] {
        [self.a, self.b]
    }
}
