use super::CollapsePlan;
use super::WideNode8;
use super::collapse::collapse_into;
use crate::error::BuildError;
use crate::math::Aabb;

/// An eight-wide BVH: the same leaves as the [`Bvh`](crate::bvh::Bvh) it was collapsed from, under nodes of up
/// to eight children whose boxes are tested together ([`WideNode8`]). Next to the four-wide
/// [`WideBvh`](super::WideBvh) a query takes about a third fewer steps, each testing twice the
/// boxes: on x86-64 built for AVX2 (`-C target-cpu=x86-64-v3` or `native`) each coordinate of
/// the eight boxes is one instruction, elsewhere two four-lane ones.
///
/// Made by [`WideBvh8::build`] into a caller buffer (sized by
/// [`wide_node_capacity`](super::wide_node_capacity) or [`CollapsePlan::node_count`]) from a
/// [`CollapsePlan`]; it
/// borrows the binary tree's triangle order, so leaves read the same
/// [`PackedTriangles`](crate::query::PackedTriangles) slots. Queries go through
/// [`Traverse`](crate::query::Traverse) and return exactly what the binary and four-wide trees
/// return, bit for bit, on every target.
#[derive(Clone, Copy, Debug)]
pub struct WideBvh8<'a> {
    pub(super) nodes: &'a [WideNode8],
    pub(super) order: &'a [u32],
    pub(super) splits: crate::query::SplitRefs<'a>,
}

impl<'a> WideBvh8<'a> {
    /// Collapses the tree `plan` was made for into an eight-wide tree in `out` (at least
    /// [`CollapsePlan::node_count`] nodes; [`wide_node_capacity`](super::wide_node_capacity)
    /// of the triangle count always suffices). Each node covers an inner binary node's subtree
    /// with the lanes the plan chose. Deterministic; the view covers only the nodes written.
    ///
    /// # Errors
    /// [`BuildError::BufferTooSmall`] when `out` is too small; nothing is written then.
    pub fn build(
        plan: &CollapsePlan<'a, '_, 8>,
        out: &'a mut [WideNode8],
    ) -> Result<Self, BuildError> {
        let needed = collapse_into::<WideNode8, 8>(plan, out)?;
        let nodes: &'a [WideNode8] = out;
        let bvh = plan.tree();
        Ok(Self {
            nodes: nodes.get(..needed).unwrap_or_default(),
            order: bvh.order(),
            splits: bvh.split_refs(),
        })
    }

    /// A view over nodes [`WideBvh8::build`] wrote for the tree whose order is `order`, kept
    /// unchanged since (the owned type's buffers).
    #[cfg_attr(not(feature = "alloc"), allow(dead_code))]
    pub(crate) const fn from_validated(nodes: &'a [WideNode8], order: &'a [u32]) -> Self {
        Self {
            nodes,
            order,
            splits: crate::query::SplitRefs::NONE,
        }
    }

    /// The nodes, root first.
    #[must_use]
    pub const fn nodes(&self) -> &'a [WideNode8] {
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

    /// The union of the root's child boxes, or [`Aabb::EMPTY`].
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, |root| {
            (0..root.lanes()).fold(Aabb::EMPTY, |b, lane| b.union(root.bounds.lane(lane)))
        })
    }
}
