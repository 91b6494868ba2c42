//! [`CompactWideBvh`]: a four-wide BVH whose child boxes are quantized to 8 bits.

use super::traverse::{STACK4, traverse_wide};
use super::{CompactNode, WideBvh};
use crate::error::{BufferKind, BuildError};
use crate::math::Aabb;
use crate::query::{Traverse, Visitor};

/// A [`WideBvh`] with every node quantized ([`CompactNode`], 64 bytes instead of 128): the
/// same nodes, children and leaves, with each child box rounded outward to an 8-bit grid of
/// its parent's box. Its queries return exactly what the wide (and binary) tree's return, bit
/// for bit, on every target; the coarser boxes may only send a query into a few more leaves.
/// The choice for memory: about 10 bytes of nodes per triangle with the default leaves.
///
/// Made by [`CompactWideBvh::build`] into a caller buffer of
/// [`WideBvh::nodes`]`().len()` nodes; it borrows the tree's triangle order, so leaves read the
/// same [`PackedTriangles`](crate::query::PackedTriangles) slots.
#[derive(Clone, Copy, Debug)]
pub struct CompactWideBvh<'a> {
    nodes: &'a [CompactNode],
    order: &'a [u32],
    pub(super) splits: crate::query::SplitRefs<'a>,
}

impl<'a> CompactWideBvh<'a> {
    /// Quantizes every node of `wide` into `out` (at least as many nodes). Deterministic: the
    /// same tree gives the same nodes on every target.
    ///
    /// # Errors
    /// [`BuildError::BufferTooSmall`] when `out` is too small (nothing is written then);
    /// [`BuildError::InvalidConfig`] (`max_leaf_size`) when a leaf holds more than 255
    /// triangles or a box is not finite: never for a tree built or validated by this crate
    /// (leaves hold at most [`BuildConfig::MAX_LEAF_SIZE`](crate::bvh::BuildConfig::MAX_LEAF_SIZE)
    /// triangles, boxes are finite). Nothing useful is written then.
    pub fn build(wide: &WideBvh<'a>, out: &'a mut [CompactNode]) -> Result<Self, BuildError> {
        let needed = wide.nodes().len();
        if out.len() < needed {
            return Err(BuildError::BufferTooSmall {
                buffer: BufferKind::WideNodes,
                needed,
                got: out.len(),
            });
        }
        for (slot, node) in out.iter_mut().zip(wide.nodes()) {
            *slot = CompactNode::quantize(node).ok_or(BuildError::InvalidConfig {
                field: "max_leaf_size",
            })?;
        }
        let nodes: &'a [CompactNode] = out;
        Ok(Self {
            nodes: nodes.get(..needed).unwrap_or_default(),
            order: wide.order(),
            splits: wide.split_refs(),
        })
    }

    /// A view over nodes [`CompactWideBvh::build`] wrote for the tree whose order is `order`,
    /// kept unchanged since (the owned type's buffers).
    #[cfg_attr(not(feature = "alloc"), allow(dead_code))]
    pub(crate) const fn from_validated(nodes: &'a [CompactNode], order: &'a [u32]) -> Self {
        Self {
            nodes,
            order,
            splits: crate::query::SplitRefs::NONE,
        }
    }

    /// The nodes, root first.
    #[must_use]
    pub const fn nodes(&self) -> &'a [CompactNode] {
        self.nodes
    }

    /// This view with `splits` as its split references (those of the binary tree it was
    /// collapsed from, [`Bvh::split_refs`](crate::bvh::Bvh::split_refs)), for reporting
    /// queries to report each triangle once.
    #[must_use]
    pub const fn with_split_refs(mut self, splits: crate::query::SplitRefs<'a>) -> Self {
        self.splits = splits;
        self
    }

    /// The split references queries read (see [`Self::with_split_refs`]).
    #[must_use]
    pub const fn split_refs(&self) -> crate::query::SplitRefs<'a> {
        self.splits
    }

    /// Mesh triangle indices in leaf order (the binary tree's).
    #[must_use]
    pub const fn order(&self) -> &'a [u32] {
        self.order
    }

    /// True when the tree holds no triangles (every query returns nothing).
    #[must_use]
    pub const fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The union of the root's decoded child boxes, or [`Aabb::EMPTY`]: it holds the wide
    /// tree's [`WideBvh::bounds`].
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        self.nodes
            .first()
            .map_or(Aabb::EMPTY, |root| root.boxes().union())
    }

    /// Bytes of nodes, `64 ×` [`nodes`](Self::nodes)`().len()`.
    #[must_use]
    pub const fn node_bytes(&self) -> usize {
        core::mem::size_of_val(self.nodes)
    }
}

impl Traverse for CompactWideBvh<'_> {
    /// Depth first as [`WideBvh`]'s walk, each node's boxes decoded as it is entered.
    #[inline(always)]
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        traverse_wide::<_, _, STACK4>(self.nodes, self.order, visitor);
    }

    #[inline(always)]
    fn split_refs(&self) -> crate::query::SplitRefs<'_> {
        self.splits
    }

    /// Yes: boxes are judged four at a time.
    #[inline(always)]
    fn traverse_packet<V: Visitor + ?Sized>(&self, visitor: &mut V) -> bool {
        self.traverse(visitor);
        true
    }
}
