use super::CollapsePlan;
use super::WideNode;
use super::collapse::{collapse_into, collapse_to};
use crate::error::{BuildError, StructureError};
use crate::math::Aabb;

/// A four-wide BVH: the same leaves as the [`Bvh`](crate::bvh::Bvh) it was collapsed from, under nodes of up to
/// four children whose boxes are tested together in SIMD lanes, so a query takes fewer,
/// fuller steps.
///
/// Made by [`WideBvh::build`] from a [`CollapsePlan`] into a caller buffer (sized by
/// [`wide_node_capacity`](super::wide_node_capacity) or [`CollapsePlan::node_count`]); it
/// borrows the binary tree's triangle order, so leaves read the same
/// [`PackedTriangles`](crate::query::PackedTriangles) slots. Queries go through
/// [`Traverse`](crate::query::Traverse) (`wide.with(&triangles)`), and every one returns
/// exactly what the binary tree's returns, bit for bit, on every target: box tests only decide
/// what to visit, conservatively, and each answer is the minimum under a total order.
#[derive(Clone, Copy, Debug)]
pub struct WideBvh<'a> {
    pub(super) nodes: &'a [WideNode],
    pub(super) order: &'a [u32],
    pub(super) splits: crate::query::SplitRefs<'a>,
}

impl<'a> WideBvh<'a> {
    /// Collapses the tree `plan` was made for into a four-wide tree in `out` (at least
    /// [`CollapsePlan::node_count`] nodes; [`wide_node_capacity`](super::wide_node_capacity)
    /// of the triangle count always suffices). Deterministic; the view covers only the nodes
    /// written.
    ///
    /// # Errors
    /// [`BuildError::BufferTooSmall`] when `out` is too small; nothing is written then.
    pub fn build(
        plan: &CollapsePlan<'a, '_, 4>,
        out: &'a mut [WideNode],
    ) -> Result<Self, BuildError> {
        let needed = collapse_into::<WideNode, 4>(plan, out)?;
        let nodes: &'a [WideNode] = out;
        let bvh = plan.tree();
        Ok(WideBvh {
            nodes: nodes.get(..needed).unwrap_or_default(),
            order: bvh.order(),
            splits: bvh.split_refs(),
        })
    }

    /// A view over wide nodes written earlier by [`WideBvh::build`] for this very `plan`'s
    /// tree (and moved since, into a struct that owns them, say), after checking that they are
    /// exactly the nodes the collapse gives, bit for bit. The check redoes the collapse, which
    /// is cheap next to a build, so nothing else can reach a query. `nodes` may be the
    /// untrimmed buffer `build` was given: nodes past those it wrote are ignored.
    ///
    /// # Errors
    /// [`StructureError::WideNodeMismatch`] naming the first node that differs.
    pub fn from_parts(
        plan: &CollapsePlan<'a, '_, 4>,
        nodes: &'a [WideNode],
    ) -> Result<Self, StructureError> {
        let mut first_difference: Option<usize> = None;
        let count = collapse_to::<WideNode, 4>(plan, |index, node| {
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
        Ok(WideBvh {
            nodes: nodes.get(..count).unwrap_or_default(),
            order: bvh.order(),
            splits: bvh.split_refs(),
        })
    }

    /// A view over nodes [`WideBvh::build`] wrote for the tree whose order is `order`, kept
    /// unchanged since (the owned type's buffers).
    #[cfg_attr(not(feature = "alloc"), allow(dead_code))]
    pub(crate) const fn from_validated(nodes: &'a [WideNode], order: &'a [u32]) -> Self {
        Self {
            nodes,
            order,
            splits: crate::query::SplitRefs::NONE,
        }
    }

    /// The nodes, root first.
    #[must_use]
    pub const fn nodes(&self) -> &'a [WideNode] {
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

    /// The union of the root's child boxes, or [`Aabb::EMPTY`]: it holds every triangle and
    /// lies within the binary root's box ([`Bvh::bounds`](crate::bvh::Bvh::bounds)), which is padded once more.
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        self.nodes
            .first()
            .map_or(Aabb::EMPTY, |root| root.bounds.union())
    }
}
