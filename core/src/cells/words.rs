//! The arrays a cell structure is made of, read the same way from memory or from a blob.

use crate::query::LeafTriangleIds;

/// An array of `u32` words: a cell structure's nodes, cell offsets or references, as built in
/// memory (`&[u32]`, or a slice of two-word nodes) or stored little-endian in a blob
/// ([`LeWords`]). Reads never panic: out of range is `None`.
pub trait Words: Copy {
    /// Number of words.
    fn len(&self) -> usize;

    /// Whether there are no words.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Word `i`, if present.
    fn word(&self, i: usize) -> Option<u32>;

    /// Words `2i` and `2i + 1` (two-word node `i`), if both are present.
    #[inline(always)]
    fn pair(&self, i: usize) -> Option<[u32; 2]> {
        let at = i.checked_mul(2)?;
        Some([self.word(at)?, self.word(at.checked_add(1)?)?])
    }

    /// Words `first..first + count` as the triangle ids of a leaf whose first slot is `first`,
    /// if all are present.
    fn ids(&self, first: usize, count: usize) -> Option<LeafTriangleIds<'_>>;
}

impl Words for &[u32] {
    #[inline(always)]
    fn len(&self) -> usize {
        <[u32]>::len(self)
    }

    #[inline(always)]
    fn word(&self, i: usize) -> Option<u32> {
        self.get(i).copied()
    }

    #[inline(always)]
    fn ids(&self, first: usize, count: usize) -> Option<LeafTriangleIds<'_>> {
        LeafTriangleIds::in_order(self, first, count)
    }
}

/// Little-endian `u32` words read in place from bytes (a blob's arrays).
#[derive(Clone, Copy, Debug)]
pub struct LeWords<'a>(&'a [[u8; 4]]);

impl<'a> LeWords<'a> {
    /// The words stored in `bytes`, four bytes each, little-endian.
    #[must_use]
    pub const fn new(bytes: &'a [[u8; 4]]) -> Self {
        Self(bytes)
    }
}

impl Words for LeWords<'_> {
    #[inline(always)]
    fn len(&self) -> usize {
        self.0.len()
    }

    #[inline(always)]
    fn word(&self, i: usize) -> Option<u32> {
        self.0.get(i).map(|b| u32::from_le_bytes(*b))
    }

    #[inline(always)]
    fn pair(&self, i: usize) -> Option<[u32; 2]> {
        let at = i.checked_mul(2)?;
        match self.0.get(at..at.checked_add(2)?)? {
            [a, b] => Some([u32::from_le_bytes(*a), u32::from_le_bytes(*b)]),
            _ => None,
        }
    }

    #[inline(always)]
    fn ids(&self, first: usize, count: usize) -> Option<LeafTriangleIds<'_>> {
        let bytes = self.0.get(first..first.checked_add(count)?)?;
        Some(LeafTriangleIds::from_le_bytes(first, bytes))
    }
}

/// A node of two words (k-d tree and octree nodes), so a slice of them reads as [`Words`].
pub trait TwoWordNode: Copy {
    /// The node's two words.
    fn words(&self) -> [u32; 2];
}

impl<N: TwoWordNode> Words for &[N] {
    #[inline(always)]
    fn len(&self) -> usize {
        <[N]>::len(self) * 2
    }

    #[inline(always)]
    fn word(&self, i: usize) -> Option<u32> {
        let [a, b] = self.get(i / 2)?.words();
        Some(if i.is_multiple_of(2) { a } else { b })
    }

    #[inline(always)]
    fn pair(&self, i: usize) -> Option<[u32; 2]> {
        self.get(i).map(TwoWordNode::words)
    }

    #[inline(always)]
    fn ids(&self, _first: usize, _count: usize) -> Option<LeafTriangleIds<'_>> {
        None
    }
}
