use super::build::build_into;
use super::check::{CheckLevel, Extent, check};
use super::sizing::{BvhSizes, node_capacity};
use super::spatial_build::build_spatial_into;
use super::{BuildConfig, BvhNode, PrimRef, SpatialSplits, TreeArrays};
use crate::error::{BuildError, StructureError};
use crate::math::Aabb;
use crate::mesh::ValidMesh;
use crate::query::LeafTriangleIds;
use crate::query::{SplitRef, SplitRefs};

/// A built BVH: a read-only view over the caller's node and order buffers.
///
/// Created only by [`Bvh::build`], [`Bvh::from_parts`] (validating),
/// [`Bvh::from_built_parts`] (topology only) or [`Bvh::refit`], so its structure is always
/// valid: every query terminates, stays in bounds and never panics. It
/// does not hold the mesh; pass the same [`ValidMesh`] it was built from to each query (a
/// different mesh gives meaningless answers, never a panic).
#[derive(Clone, Copy, Debug)]
pub struct Bvh<'a> {
    pub(super) nodes: &'a [BvhNode],
    pub(super) order: &'a [u32],
    pub(super) depth: u32,
    pub(super) splits: SplitRefs<'a>,
}

impl<'a> Bvh<'a> {
    /// Builds a BVH of `mesh` into `nodes`, `order` and `scratch` ([`Bvh::measure`] sizes
    /// them: `2·n − 1` nodes, one order slot and one [`PrimRef`] of scratch per triangle;
    /// the contents of `scratch` afterwards are unspecified).
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
        Ok(Self::of_built(&built, mesh, nodes, order))
    }

    /// The view of what a builder wrote into `nodes` and `order`.
    fn of_built(
        built: &super::build::Built,
        mesh: &ValidMesh<'_>,
        nodes: &'a [BvhNode],
        order: &'a [u32],
    ) -> Self {
        Self {
            nodes: nodes.get(..built.node_count).unwrap_or_default(),
            order: order.get(..mesh.triangle_count()).unwrap_or_default(),
            depth: built.depth,
            splits: SplitRefs::NONE,
        }
    }

    /// Builds a BVH of `mesh` with spatial splits ([`SpatialSplits`]): the binned-SAH build of
    /// [`Bvh::build`], where a node whose best split by centroid leaves overlapping children
    /// may instead cut space at a plane and hold the triangles crossing it on both sides. A
    /// triangle may then appear in several leaves (and slots of `order`); `split_refs`
    /// receives one [`SplitRef`] per such reference, which queries that report triangles use
    /// to report each once ([`Bvh::split_refs`]). Answers are those of [`Bvh::build`]'s tree.
    ///
    /// Buffers: as [`Bvh::measure`] with `Some(spatial)` sizes them (contents of `scratch`
    /// afterwards unspecified). The view keeps the used prefixes. Deterministic, like [`Bvh::build`];
    /// meshes of 2³¹ triangles or more, and a room of 2³² references or more, are refused
    /// ([`BuildError::InvalidConfig`] naming `extra_references`).
    ///
    /// # Errors
    /// As [`Bvh::build`] (with [`BufferKind::SplitRefs`](crate::error::BufferKind::SplitRefs)
    /// for `split_refs`), and [`BuildError::InvalidConfig`] for a bad `spatial`.
    pub fn build_spatial(
        mesh: &ValidMesh<'_>,
        config: &BuildConfig,
        spatial: &SpatialSplits,
        nodes: &'a mut [BvhNode],
        order: &'a mut [u32],
        scratch: &mut [PrimRef],
        split_refs: &'a mut [SplitRef],
    ) -> Result<Self, BuildError> {
        let built = build_spatial_into(mesh, config, spatial, nodes, order, scratch, split_refs)?;
        Ok(Self::of_spatial(&built, nodes, order, split_refs))
    }

    /// [`Bvh::build`] on rayon's thread pool (feature `parallel`): the same nodes and order,
    /// bit for bit, whatever the number of threads. Large nodes bin their triangles in
    /// parallel and build their two children concurrently; subtrees under about 16,000
    /// triangles are built as [`Bvh::build`] builds them. Buffers and errors as
    /// [`Bvh::build`]; the build allocates room for the pieces it builds concurrently.
    ///
    /// # Errors
    /// As [`Bvh::build`].
    #[cfg(feature = "parallel")]
    pub fn build_parallel(
        mesh: &ValidMesh<'_>,
        config: &BuildConfig,
        nodes: &'a mut [BvhNode],
        order: &'a mut [u32],
        scratch: &mut [PrimRef],
    ) -> Result<Self, BuildError> {
        let built = super::parallel_build::build_parallel(mesh, config, nodes, order, scratch)?;
        Ok(Self::of_built(&built, mesh, nodes, order))
    }

    /// [`Bvh::build_spatial`] on rayon's thread pool (feature `parallel`): the same nodes,
    /// order and split references, bit for bit, whatever the number of threads. Once a node
    /// is split its two children are built concurrently (each owns its part of the buffers);
    /// subtrees under about 16,000 references are built as [`Bvh::build_spatial`] builds them.
    /// Buffers and errors as [`Bvh::build_spatial`]; the build allocates room for the pieces it
    /// builds concurrently.
    ///
    /// # Errors
    /// As [`Bvh::build_spatial`].
    #[cfg(feature = "parallel")]
    pub fn build_spatial_parallel(
        mesh: &ValidMesh<'_>,
        config: &BuildConfig,
        spatial: &SpatialSplits,
        nodes: &'a mut [BvhNode],
        order: &'a mut [u32],
        scratch: &mut [PrimRef],
        split_refs: &'a mut [SplitRef],
    ) -> Result<Self, BuildError> {
        let built = super::parallel_spatial::build_spatial_parallel(
            mesh, config, spatial, nodes, order, scratch, split_refs,
        )?;
        Ok(Self::of_spatial(&built, nodes, order, split_refs))
    }

    /// The view of what a spatial-split builder wrote.
    fn of_spatial(
        built: &super::spatial_build::SpatialBuilt,
        nodes: &'a [BvhNode],
        order: &'a [u32],
        split_refs: &'a [SplitRef],
    ) -> Self {
        Self {
            nodes: nodes.get(..built.node_count).unwrap_or_default(),
            order: order.get(..built.slots).unwrap_or_default(),
            depth: built.depth,
            splits: SplitRefs::new(split_refs.get(..built.split_refs).unwrap_or_default()),
        }
    }

    /// A view over nodes and order kept from an earlier build (or decoded from storage),
    /// after checking them fully against `mesh` (see [`Bvh::check`]).
    ///
    /// The buffers may be the untrimmed ones the build was given: the view keeps the nodes
    /// reachable from the root, which must be a prefix of `nodes`, and the slots its leaves
    /// tile, which must be a prefix of `order`; whatever follows is ignored. For a mesh with no
    /// triangles the view is empty, whatever the buffers hold.
    ///
    /// # Errors
    /// The first [`StructureError`] found.
    pub fn from_parts(
        nodes: &'a [BvhNode],
        order: &'a [u32],
        mesh: &ValidMesh<'_>,
    ) -> Result<Self, StructureError> {
        Self::checked(nodes, order, mesh, CheckLevel::Full)
    }

    /// A view over the used prefix of `nodes` and `order` once [`check`] at `level` passes.
    fn checked(
        nodes: &'a [BvhNode],
        order: &'a [u32],
        mesh: &ValidMesh<'_>,
        level: CheckLevel,
    ) -> Result<Self, StructureError> {
        if mesh.triangle_count() == 0 {
            return Ok(Self::from_validated(&[], &[], 0));
        }
        let unchecked = Self::from_validated(nodes, order, 0);
        let triangles = (level == CheckLevel::Full).then_some(mesh);
        let shape = check(&unchecked, triangles, level, Extent::Prefix)?;
        Ok(Self::from_validated(
            nodes.get(..shape.nodes).unwrap_or_default(),
            order.get(..shape.slots).unwrap_or_default(),
            shape.depth,
        ))
    }

    /// A view over nodes and order that [`Bvh::build`] wrote for `mesh` and nothing has changed
    /// since, for re-borrowing a tree after its buffers moved (into a struct that owns them,
    /// say). Checks what safety needs — topology, depth, leaf ranges tiling `order`, triangle
    /// indices below the mesh's count — but not box nesting or triangle containment, the
    /// costly part of [`Bvh::from_parts`] (a leaf's triangles are gathered from the mesh for
    /// that). Boxes that are wrong give wrong answers, never a panic or an endless query; when
    /// the arrays come from anywhere else, use [`Bvh::from_parts`]. Untrimmed buffers are
    /// accepted as by [`Bvh::from_parts`].
    ///
    /// # Errors
    /// The first [`StructureError`] found.
    pub fn from_built_parts(
        nodes: &'a [BvhNode],
        order: &'a [u32],
        mesh: &ValidMesh<'_>,
    ) -> Result<Self, StructureError> {
        let bvh = Self::checked(nodes, order, mesh, CheckLevel::Topology)?;
        let (nodes, order) = (bvh.nodes, bvh.order);
        let count = mesh.triangle_count();
        // One pass without early exit (it vectorises); the slow search only names the culprit.
        if !order
            .iter()
            .fold(true, |ok, &t| ok & ((t as usize) < count))
        {
            let (slot, &tri) = order
                .iter()
                .enumerate()
                .find(|&(_, &t)| t as usize >= count)
                .unwrap_or((0, &0));
            return Err(StructureError::TriangleOutOfRange {
                node: leaf_of_slot(nodes, slot),
                tri,
            });
        }
        Ok(bvh)
    }

    /// A view over arrays already known to be valid (decoded from a validated blob, or about
    /// to be checked).
    pub(crate) const fn from_validated(nodes: &'a [BvhNode], order: &'a [u32], depth: u32) -> Self {
        Self {
            nodes,
            order,
            depth,
            splits: SplitRefs::NONE,
        }
    }

    /// This view with `splits` as its split references (see [`Bvh::split_refs`]): for a tree
    /// built by [`Bvh::build_spatial`] and kept elsewhere since, with the table it wrote.
    /// A table that does not belong to the tree makes reporting queries report a triangle
    /// twice or not at all; never a panic.
    #[must_use]
    #[cfg(any(feature = "blob", feature = "alloc"))]
    pub(crate) const fn with_split_refs(mut self, splits: SplitRefs<'a>) -> Self {
        self.splits = splits;
        self
    }

    /// The references of triangles this tree holds more than once (built with spatial
    /// splits), sorted by triangle then slot; empty otherwise.
    #[must_use]
    pub const fn split_refs(&self) -> SplitRefs<'a> {
        self.splits
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
        check(self, Some(mesh), CheckLevel::Full, Extent::Exact).map(|_| ())
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

/// The index of the leaf whose range holds order slot `slot` (0 when none does).
fn leaf_of_slot(nodes: &[BvhNode], slot: usize) -> u32 {
    nodes
        .iter()
        .position(|n| {
            let first = n.first as usize;
            n.is_leaf() && (first..first.saturating_add(n.count as usize)).contains(&slot)
        })
        .and_then(|i| u32::try_from(i).ok())
        .unwrap_or(0)
}

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

    #[inline(always)]
    fn split_refs(&self) -> SplitRefs<'_> {
        self.splits
    }
}

impl Bvh<'_> {
    /// The buffers a build of `tri_count` triangles needs: [`Bvh::build`]'s with `spatial`
    /// `None`, [`Bvh::build_spatial`]'s with the spatial-split settings (a tree may then hold
    /// up to `n + ⌊n·extra⌋` references; a `spatial` outside its documented ranges counts as
    /// no extra room, and its build fails with [`BuildError::InvalidConfig`](crate::error::BuildError::InvalidConfig)).
    /// Arithmetic only; saturates rather than overflows.
    #[must_use]
    pub fn measure(tri_count: usize, spatial: Option<&SpatialSplits>) -> BvhSizes {
        let (references, split_refs) = match spatial {
            None => (tri_count, 0),
            Some(s) => (
                s.reference_capacity(tri_count),
                s.split_ref_capacity(tri_count),
            ),
        };
        BvhSizes {
            nodes: node_capacity(references),
            order: references,
            split_refs,
        }
    }
}
