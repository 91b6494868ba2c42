use super::build::build_into;
use super::check::{CheckLevel, check};
use super::{BuildConfig, BvhNode, PrimRef};
use crate::error::{BuildError, StructureError};
use crate::math::Aabb;
use crate::mesh::ValidMesh;

/// A built BVH: a read-only view over the caller's node and order buffers.
///
/// Created only by [`Bvh::build`], [`Bvh::from_parts`] (validating) or [`Bvh::refit`], so its
/// structure is always valid: every query terminates, stays in bounds and never panics. It
/// does not hold the mesh; pass the same [`ValidMesh`] it was built from to each query (a
/// different mesh gives meaningless answers, never a panic).
#[derive(Clone, Copy, Debug)]
pub struct Bvh<'a> {
    pub(super) nodes: &'a [BvhNode],
    pub(super) order: &'a [u32],
    pub(super) depth: u32,
}

impl<'a> Bvh<'a> {
    /// Builds a BVH of `mesh` into `nodes` (at least [`node_capacity`](super::node_capacity)
    /// of the triangle count), `order` (one slot per triangle) and `scratch` (one
    /// [`PrimRef`] per triangle, contents afterwards unspecified).
    ///
    /// Deterministic: the same mesh and config give the same nodes and order, bit for bit, on
    /// every target. Uses only the given buffers and a fixed amount of stack (a few KiB).
    ///
    /// # Errors
    /// [`BuildError::BufferTooSmall`], [`BuildError::TooDeep`] or
    /// [`BuildError::InvalidConfig`]; all are detected before anything is written.
    pub fn build(
        mesh: &ValidMesh<'_>,
        config: &BuildConfig,
        nodes: &'a mut [BvhNode],
        order: &'a mut [u32],
        scratch: &mut [PrimRef],
    ) -> Result<Self, BuildError> {
        let built = build_into(mesh, config, nodes, order, scratch)?;
        let nodes: &'a [BvhNode] = nodes;
        let order: &'a [u32] = order;
        Ok(Self {
            nodes: nodes.get(..built.node_count).unwrap_or_default(),
            order: order.get(..mesh.triangle_count()).unwrap_or_default(),
            depth: built.depth,
        })
    }

    /// A view over nodes and order kept from an earlier build (or decoded from storage),
    /// after checking them fully against `mesh` (see [`Bvh::check`]).
    ///
    /// # Errors
    /// The first [`StructureError`] found.
    pub fn from_parts(
        nodes: &'a [BvhNode],
        order: &'a [u32],
        mesh: &ValidMesh<'_>,
    ) -> Result<Self, StructureError> {
        let mut bvh = Self {
            nodes,
            order,
            depth: 0,
        };
        bvh.depth = check(&bvh, Some(mesh), CheckLevel::Full)?;
        Ok(bvh)
    }

    /// A view over arrays already known to be valid (decoded from a validated blob).
    #[cfg_attr(not(feature = "blob"), allow(dead_code))]
    pub(crate) const fn from_validated(nodes: &'a [BvhNode], order: &'a [u32], depth: u32) -> Self {
        Self {
            nodes,
            order,
            depth,
        }
    }

    /// Validates the structure against `mesh`: children after parents and in range, depth
    /// within [`MAX_DEPTH`](super::MAX_DEPTH), every node reachable, leaf ranges tiling the
    /// order array exactly once, finite boxes nested in their parents, and every triangle
    /// inside its leaf's box. (That `order` holds no triangle twice is not checked; it only
    /// affects answers, never safety.)
    ///
    /// # Errors
    /// The first [`StructureError`] found.
    pub fn check(&self, mesh: &ValidMesh<'_>) -> Result<(), StructureError> {
        check(self, Some(mesh), CheckLevel::Full).map(|_| ())
    }

    /// The nodes, root first.
    #[must_use]
    pub const fn nodes(&self) -> &'a [BvhNode] {
        self.nodes
    }

    /// Mesh triangle indices in leaf order.
    #[must_use]
    pub const fn order(&self) -> &'a [u32] {
        self.order
    }

    /// Levels in the tree (1 for a lone leaf, 0 when empty).
    #[must_use]
    pub const fn depth(&self) -> u32 {
        self.depth
    }

    /// True when the tree holds no triangles (every query returns nothing).
    #[must_use]
    pub const fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The root's (padded) box, or [`Aabb::EMPTY`].
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, BvhNode::aabb)
    }
}
