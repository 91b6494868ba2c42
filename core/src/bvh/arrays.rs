//! Read access to a BVH's two arrays wherever they are stored: in slices (a [`Bvh`]) or in the
//! bytes of a blob, read in place.

use core::slice;

use super::{Bvh, BvhNode};

/// The node and order arrays of a BVH, read by index.
///
/// Traversal, the queries and the validator are written once over this trait, so a tree in
/// caller slices ([`Bvh`]) and a tree read straight out of a blob's bytes run the same code and
/// return the same bits. Implementations return `None` for anything out of range; they never
/// panic.
pub trait TreeArrays {
    /// Number of nodes (0 for an empty tree).
    fn node_count(&self) -> usize;

    /// Number of order slots: one per triangle.
    fn slot_count(&self) -> usize;

    /// Node `index` (the root is 0), or `None` past the end.
    fn node(&self, index: usize) -> Option<BvhNode>;

    /// Nodes `first` and `first + 1` (the two children of an inner node), or `None` unless both
    /// exist.
    fn node_pair(&self, first: usize) -> Option<[BvhNode; 2]>;

    /// The mesh triangle indices in order slots `first..first + count`, or `None` unless all of
    /// them exist.
    fn leaf_triangles(&self, first: usize, count: usize) -> Option<LeafTriangleIds<'_>>;
}

/// The triangles of one leaf: `(order slot, mesh triangle index)` pairs, slots ascending.
#[derive(Clone, Debug)]
pub struct LeafTriangleIds<'a> {
    next_slot: usize,
    ids: Ids<'a>,
}

#[derive(Clone, Debug)]
enum Ids<'a> {
    /// Native `u32`s in a slice.
    Words(slice::Iter<'a, u32>),
    /// Little-endian `u32`s in bytes (a blob).
    #[cfg_attr(not(feature = "blob"), allow(dead_code))]
    Bytes(slice::Iter<'a, [u8; 4]>),
}

impl<'a> LeafTriangleIds<'a> {
    pub(crate) fn from_words(first_slot: usize, ids: &'a [u32]) -> Self {
        Self {
            next_slot: first_slot,
            ids: Ids::Words(ids.iter()),
        }
    }

    /// Slots `first..first + count` of an order array, or `None` unless all exist.
    #[inline(always)]
    pub(crate) fn in_order(order: &'a [u32], first: usize, count: usize) -> Option<Self> {
        let ids = order.get(first..first.checked_add(count)?)?;
        Some(Self::from_words(first, ids))
    }

    #[cfg_attr(not(feature = "blob"), allow(dead_code))]
    pub(crate) fn from_le_bytes(first_slot: usize, ids: &'a [[u8; 4]]) -> Self {
        Self {
            next_slot: first_slot,
            ids: Ids::Bytes(ids.iter()),
        }
    }
}

impl LeafTriangleIds<'_> {
    /// The order slot of the next triangle (the first one, before iterating).
    #[inline(always)]
    pub(crate) const fn first_slot(&self) -> usize {
        self.next_slot
    }
}

impl Iterator for LeafTriangleIds<'_> {
    type Item = (usize, u32);

    #[inline(always)]
    fn next(&mut self) -> Option<(usize, u32)> {
        let tri = match &mut self.ids {
            Ids::Words(it) => *it.next()?,
            Ids::Bytes(it) => u32::from_le_bytes(*it.next()?),
        };
        let slot = self.next_slot;
        self.next_slot = slot.wrapping_add(1);
        Some((slot, tri))
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = match &self.ids {
            Ids::Words(it) => it.len(),
            Ids::Bytes(it) => it.len(),
        };
        (n, Some(n))
    }
}

impl ExactSizeIterator for LeafTriangleIds<'_> {}

impl TreeArrays for Bvh<'_> {
    #[inline(always)]
    fn node_count(&self) -> usize {
        self.nodes.len()
    }

    #[inline(always)]
    fn slot_count(&self) -> usize {
        self.order.len()
    }

    #[inline(always)]
    fn node(&self, index: usize) -> Option<BvhNode> {
        self.nodes.get(index).copied()
    }

    #[inline(always)]
    fn node_pair(&self, first: usize) -> Option<[BvhNode; 2]> {
        self.nodes
            .get(first..first.wrapping_add(2))
            .and_then(|pair| <&[BvhNode; 2]>::try_from(pair).ok())
            .copied()
    }

    #[inline(always)]
    fn leaf_triangles(&self, first: usize, count: usize) -> Option<LeafTriangleIds<'_>> {
        LeafTriangleIds::in_order(self.order, first, count)
    }
}
