//! [`WideBvh`]: the one view over a wide tree, whatever its node.

use super::collapse::{CollapsedNode, collapse_into, collapse_to};
use super::node_build::CollapsesFrom;
use super::plan::{CollapsePlan, PlanEntry, plan_capacity};
use super::sizing::{WideSizes, wide_node_capacity};
use super::traverse::{LaneNode, STACK4, STACK8, traverse_wide};
use super::{CompactNode, WideNode, WideNode8};
use crate::bvh::Bvh;
use crate::error::{BufferKind, BuildError, StructureError};
use crate::math::Aabb;
use crate::query::{SplitRefs, Traverse, Visitor};

/// What a wide tree's node may be: [`WideNode`] (four lanes, the default), [`WideNode8`]
/// (eight lanes) or [`CompactNode`] (four lanes, boxes quantized to 8 bits). Sealed: the walk
/// of [`WideBvh`] is written for these three.
pub trait WideNodeKind: LaneNode + CollapsesFrom + Copy {}
impl WideNodeKind for WideNode {}
impl WideNodeKind for WideNode8 {}
impl WideNodeKind for CompactNode {}

/// A wide BVH: the same leaves as the [`Bvh`](crate::bvh::Bvh) it was collapsed from, under
/// nodes of four or eight children whose boxes are tested together in SIMD lanes, so a query
/// takes fewer, fuller steps. `N` is the node ([`WideNodeKind`]):
///
/// | `N` | lanes | bytes | made by |
/// | --- | --- | --- | --- |
/// | [`WideNode`] (default) | 4 | 128 | [`WideBvh::build`] |
/// | [`WideNode8`] | 8 | 256 | [`WideBvh::build`] |
/// | [`CompactNode`] | 4 | 64 | [`WideBvh::build`], or [`WideBvh::quantize`] of a four-wide tree |
///
/// Nodes live in a caller buffer (sized by [`WideBvh::measure`]); the view borrows the binary tree's triangle order, so
/// leaves read the same [`PackedTriangles`](crate::query::PackedTriangles) slots. Queries go
/// through [`Traverse`](crate::query::Traverse) (`wide.with(&triangles)`), and every one
/// returns exactly what the binary tree's returns, bit for bit, on every target and for every
/// node kind: box tests only decide what to visit, conservatively, and each answer is the
/// minimum under a total order.
#[derive(Clone, Copy, Debug)]
pub struct WideBvh<'a, N: WideNodeKind = WideNode> {
    pub(super) nodes: &'a [N],
    pub(super) order: &'a [u32],
    pub(super) splits: SplitRefs<'a>,
}

impl<'a, N: WideNodeKind> WideBvh<'a, N> {
    /// The buffer sizes [`WideBvh::build`] needs to collapse `tree`: `plan` entries of scratch
    /// (one per inner binary node) and at most `nodes` wide nodes (one per inner binary node,
    /// 1 for a lone leaf, 0 for an empty tree), whatever the node kind. Arithmetic only.
    #[must_use]
    pub const fn measure(tree: &Bvh<'_>) -> WideSizes {
        WideSizes {
            plan: plan_capacity(tree),
            nodes: wide_node_capacity(tree.order().len()),
        }
    }

    /// Collapses `tree` into `out` (at least [`WideSizes::nodes`] nodes), planning in `plan`
    /// (at least [`WideSizes::plan`] entries, contents afterwards unspecified): each wide node
    /// covers an inner binary node's subtree with the four or eight lanes that minimise the
    /// tree's surface-area cost, so every triangle keeps its slots and every query returns
    /// exactly what `tree`'s returns. [`CompactNode`]s are the four-wide nodes, quantized.
    /// Deterministic: the same tree gives the same nodes on every target; the view covers
    /// only the nodes written.
    ///
    /// # Errors
    /// [`BuildError::BufferTooSmall`] when `plan` or `out` is too small; nothing is written
    /// to `out` then.
    pub fn build(
        tree: &Bvh<'a>,
        plan: &mut [PlanEntry],
        out: &'a mut [N],
    ) -> Result<Self, BuildError> {
        let needed = N::collapse(tree, plan, out)?;
        let nodes: &'a [N] = out;
        Ok(Self {
            nodes: nodes.get(..needed).unwrap_or_default(),
            order: tree.order(),
            splits: tree.split_refs(),
        })
    }

    /// Collapses the tree `plan` was made for into `out` (at least
    /// [`CollapsePlan::node_count`] nodes), with nodes of the plan's width `W` (4 for
    /// [`WideNode`], 8 for [`WideNode8`]): [`WideBvh::build`] with a plan the caller made or
    /// read from stored roles. Deterministic; the view covers only the nodes written.
    ///
    /// # Errors
    /// [`BuildError::BufferTooSmall`] when `out` is too small; nothing is written then.
    pub fn from_plan<const W: usize>(
        plan: &CollapsePlan<'a, '_, W>,
        out: &'a mut [N],
    ) -> Result<Self, BuildError>
    where
        N: CollapsedNode<W>,
    {
        let needed = collapse_into::<N, W>(plan, out)?;
        let nodes: &'a [N] = out;
        let bvh = plan.tree();
        Ok(Self {
            nodes: nodes.get(..needed).unwrap_or_default(),
            order: bvh.order(),
            splits: bvh.split_refs(),
        })
    }

    /// A view over nodes written earlier by [`WideBvh::from_plan`] for this very `plan`'s tree
    /// (and moved since, into a struct that owns them, say), after checking that they are
    /// exactly the nodes the collapse gives, bit for bit. The check redoes the collapse, which
    /// is cheap next to a build, so nothing else can reach a query. `nodes` may be the
    /// untrimmed buffer `build` was given: nodes past those it wrote are ignored.
    ///
    /// # Errors
    /// [`StructureError::WideNodeMismatch`] naming the first node that differs.
    pub fn from_parts<const W: usize>(
        plan: &CollapsePlan<'a, '_, W>,
        nodes: &'a [N],
    ) -> Result<Self, StructureError>
    where
        N: CollapsedNode<W>,
    {
        let mut first_difference: Option<usize> = None;
        let count = collapse_to::<N, W>(plan, |index, node| {
            let same = nodes.get(index).is_some_and(|n| n.same_bits(&node));
            if !same && first_difference.is_none_or(|d| index < d) {
                first_difference = Some(index);
            }
        })
        .map_err(|_| StructureError::WideNodeMismatch { node: 0 })?;
        let mismatch = first_difference.or((count > nodes.len()).then_some(nodes.len()));
        if let Some(node) = mismatch {
            return Err(StructureError::WideNodeMismatch {
                node: u32::try_from(node).unwrap_or(u32::MAX),
            });
        }
        let bvh = plan.tree();
        Ok(Self {
            nodes: nodes.get(..count).unwrap_or_default(),
            order: bvh.order(),
            splits: bvh.split_refs(),
        })
    }

    /// A view over nodes written by this crate for the tree whose order is `order`, kept
    /// unchanged since (the owned type's buffers).
    #[cfg_attr(not(feature = "alloc"), allow(dead_code))]
    pub(crate) const fn from_validated(nodes: &'a [N], order: &'a [u32]) -> Self {
        Self {
            nodes,
            order,
            splits: SplitRefs::NONE,
        }
    }

    /// The nodes, root first.
    #[must_use]
    pub const fn nodes(&self) -> &'a [N] {
        self.nodes
    }

    /// Bytes of nodes: `size_of::<N>() ×` [`nodes`](Self::nodes)`().len()`.
    #[must_use]
    pub const fn node_bytes(&self) -> usize {
        core::mem::size_of_val(self.nodes)
    }

    /// This view with `splits` as its split references (those of the binary tree it was
    /// collapsed from), for reporting queries to report each triangle once.
    #[cfg(feature = "alloc")]
    #[must_use]
    pub(crate) const fn with_split_refs(mut self, splits: SplitRefs<'a>) -> Self {
        self.splits = splits;
        self
    }

    /// The split references queries read: those of the binary tree it was collapsed from.
    #[must_use]
    pub const fn split_refs(&self) -> SplitRefs<'a> {
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

    /// The union of the root's child boxes (decoded, for [`CompactNode`]), or
    /// [`Aabb::EMPTY`]: it holds every triangle and lies within the binary root's box
    /// ([`Bvh::bounds`](crate::bvh::Bvh::bounds)), which is padded once more; a quantized
    /// tree's holds its four-wide tree's.
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, LaneNode::union)
    }
}

impl<N: WideNodeKind> Traverse for WideBvh<'_, N> {
    /// Depth first, each node's four or eight child boxes judged at once
    /// ([`Visitor::enter_lanes`], [`Visitor::enter_lanes8`]) and visited in ascending key
    /// order (the lower lane first on equal keys), with a fixed stack and no allocation.
    #[inline(always)]
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        // The stack's length is a constant per node kind: the branch folds away.
        if N::LANES == 8 {
            traverse_wide::<_, _, STACK8>(self.nodes, self.order, visitor);
        } else {
            traverse_wide::<_, _, STACK4>(self.nodes, self.order, visitor);
        }
    }

    #[inline(always)]
    fn split_refs(&self) -> SplitRefs<'_> {
        self.splits
    }

    /// Yes: boxes are judged four or eight at a time.
    #[inline(always)]
    fn walks_packets(&self) -> bool {
        true
    }
}

impl<'a> WideBvh<'a, CompactNode> {
    /// Quantizes every node of `wide` into `out` (at least as many nodes): the same nodes,
    /// children and leaves, each child box rounded outward to an 8-bit grid of its parent's
    /// box, so queries return exactly what `wide`'s return and may only enter a few more
    /// leaves. Deterministic: the same tree gives the same nodes on every target.
    ///
    /// # Errors
    /// [`BuildError::BufferTooSmall`] when `out` is too small (nothing is written then);
    /// [`BuildError::InvalidConfig`] (`max_leaf_size`) when a leaf holds more than 255
    /// triangles or a box is not finite: never for a tree built or validated by this crate
    /// (leaves hold at most [`BuildConfig::MAX_LEAF_SIZE`](crate::bvh::BuildConfig::MAX_LEAF_SIZE)
    /// triangles, boxes are finite). Nothing useful is written then.
    pub fn quantize(wide: &WideBvh<'a>, out: &'a mut [CompactNode]) -> Result<Self, BuildError> {
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
}
