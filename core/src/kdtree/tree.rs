//! A built k-d tree over its arrays, and its build into caller buffers.

use super::split::KdSplitter;
use super::{KdConfig, KdKind, KdNode};
use crate::cells::{
    self, CellNode, CellStats, CellTree, ReferencePad, TreeSizes, Words, build_tree,
};
use crate::error::BuildError;
use crate::math::Aabb;
use crate::mesh::ValidMesh;
use crate::query::Cell;

/// A k-d tree: the mesh bounds cut by axis-aligned planes into leaf cells, each listing the
/// triangles it touches.
///
/// `nodes` are [`KdNode`]s (two words each; node 0 is the root, children after their parent),
/// `items` the references that leaves point into. The arrays are slices from
/// [`KdTree::build`] or [`KdTree::from_parts`], or a blob's bytes read in place
/// ([`LeWords`](crate::advanced::LeWords)).
///
/// It answers every query through [`Traverse`](crate::query::Traverse): rays walk the leaves
/// they cross front to back, clipping their `(t_near, t_far)` span at each plane, and stop once
/// a hit lies inside the current cell; other queries descend nearest cell first.
#[derive(Clone, Copy, Debug)]
pub struct KdTree<N, W> {
    pub(super) bounds: Aabb,
    pub(super) nodes: N,
    pub(super) items: W,
}

impl<'a> KdTree<&'a [KdNode], &'a [u32]> {
    /// The exact sizes [`KdTree::build`] needs for `mesh` with `config`: a full build that
    /// writes no nodes, using `work` for the reference lists (see [`TreeSizes`]; give it a few
    /// times the triangle count, and retry longer while the result is not `complete`).
    ///
    /// # Errors
    /// [`BuildError::InvalidConfig`] for a config out of range;
    /// [`BuildError::BufferTooSmall`] when `work` is shorter than the triangle count.
    pub fn measure(
        mesh: &ValidMesh<'_>,
        config: &KdConfig,
        work: &mut [u32],
    ) -> Result<TreeSizes, BuildError> {
        config.validate()?;
        let splitter = splitter(mesh, config);
        let built = build_tree(
            &splitter,
            mesh.triangle_count(),
            Cell::root(mesh.bounds()),
            work,
            None,
        )?;
        Ok(built.sizes())
    }

    /// Builds the k-d tree of `mesh` into `nodes` and `items`, which it borrows (their used
    /// prefixes).
    ///
    /// Stays inside the buffers: a cell whose children would not fit (nodes, or references
    /// while building) stays a leaf, so a short buffer gives a coarser tree, never an error,
    /// as long as the root fits. The tree depends only on the mesh, the config and the two
    /// lengths; [`KdTree::measure`] tells the lengths that build the full tree.
    ///
    /// # Errors
    /// [`BuildError::InvalidConfig`] for a config out of range;
    /// [`BuildError::BufferTooSmall`] when `items` is shorter than the triangle count or
    /// `nodes` is empty. Nothing usable is returned then.
    pub fn build(
        mesh: &ValidMesh<'_>,
        config: &KdConfig,
        nodes: &'a mut [KdNode],
        items: &'a mut [u32],
    ) -> Result<Self, BuildError> {
        Self::build_sized(mesh, config, nodes, items).map(|(tree, _)| tree)
    }

    /// [`KdTree::build`], with the sizes [`KdTree::measure`] would report for these buffer
    /// lengths: `complete` when no cell stayed a leaf for lack of room.
    pub(crate) fn build_sized(
        mesh: &ValidMesh<'_>,
        config: &KdConfig,
        nodes: &'a mut [KdNode],
        items: &'a mut [u32],
    ) -> Result<(Self, TreeSizes), BuildError> {
        config.validate()?;
        let splitter = splitter(mesh, config);
        let built = build_tree(
            &splitter,
            mesh.triangle_count(),
            Cell::root(mesh.bounds()),
            items,
            Some(nodes),
        )?;
        let nodes: &'a [KdNode] = nodes.get(..built.nodes).unwrap_or_default();
        let items: &'a [u32] = items.get(..built.references).unwrap_or_default();
        let tree = Self {
            bounds: mesh.bounds(),
            nodes,
            items,
        };
        Ok((tree, built.sizes()))
    }
}

fn splitter<'m>(mesh: &'m ValidMesh<'m>, config: &KdConfig) -> KdSplitter<'m> {
    KdSplitter {
        mesh,
        config: *config,
        depth_limit: config.depth_limit(mesh.triangle_count()),
        pad: ReferencePad::of(&mesh.bounds()),
    }
}

impl<N: Words, W: Words> KdTree<N, W> {
    /// Wraps arrays this crate built or checked itself, without checking again.
    #[cfg_attr(not(feature = "alloc"), allow(dead_code))]
    pub(crate) const fn from_validated(bounds: Aabb, nodes: N, items: W) -> Self {
        Self {
            bounds,
            nodes,
            items,
        }
    }

    /// The root cell's box (the mesh bounds).
    #[must_use]
    pub const fn bounds(&self) -> &Aabb {
        &self.bounds
    }

    /// The node array.
    #[must_use]
    pub const fn nodes(&self) -> N {
        self.nodes
    }

    /// The references array.
    #[must_use]
    pub const fn items(&self) -> W {
        self.items
    }

    /// Node count.
    #[must_use]
    pub fn node_count(&self) -> usize {
        self.nodes.len() / 2
    }

    /// Node `i`, if present.
    #[inline(always)]
    #[must_use]
    pub fn node(&self, i: usize) -> Option<KdNode> {
        let [a, b] = self.nodes.pair(i)?;
        Some(KdNode { a, b })
    }

    /// The cells the tree has cut its bounds into after `stop_depth` levels of splits, with
    /// their depth (the root is 0): every leaf at depth `stop_depth` or less, with its
    /// `(first, count)` range of references, and every inner node at depth `stop_depth`, with
    /// `None`. Together they tile the root; depth first, lower child first.
    pub fn for_each_cell(&self, stop_depth: u32, each: impl FnMut(Cell, u32, Option<(u32, u32)>)) {
        cells::for_each_cell::<_, WALK_STACK>(self, stop_depth, each);
    }

    #[cfg(feature = "blob-cells")]
    /// The first subject of `coverage` (over `triangles` triangles, cells padded by `pad`, the
    /// build's pad: [`ReferencePad::of`] the mesh bounds) that reaches a leaf not holding it,
    /// handed down as the build hands references to the children it touches; `None` when
    /// every leaf holds every subject that reaches it.
    pub(crate) fn first_uncovered<C: Words>(
        &self,
        pad: ReferencePad,
        coverage: &mut cells::Coverage<'_, C>,
        triangles: usize,
    ) -> Option<u32> {
        cells::first_uncovered_in_tree::<_, _, WALK_STACK>(self, pad, coverage, triangles)
    }

    /// Nodes, leaf cells, empty cells, references, depth.
    #[must_use]
    pub fn stats(&self, triangles: usize) -> CellStats {
        cells::stats::<_, WALK_STACK>(self, triangles)
    }
}

/// Deferred cells of a walk over every cell: one per level below the depth limit, plus two.
const WALK_STACK: usize = KdConfig::MAX_DEPTH as usize + 2;

impl<N: Words, W: Words> CellTree for KdTree<N, W> {
    fn root_cell(&self) -> Cell {
        Cell::root(self.bounds)
    }

    fn cell_node(&self, node: u32) -> Option<CellNode> {
        Some(match self.node(node as usize)?.kind() {
            KdKind::Leaf { first, count } => CellNode::Leaf { first, count },
            KdKind::Inner { .. } => CellNode::Inner,
        })
    }

    fn children(&self, node: u32, cell: &Cell, _depth: u32, mut child: impl FnMut(u32, Cell)) {
        if let Some(KdKind::Inner {
            axis,
            split,
            first_child,
        }) = self.node(node as usize).map(|n| n.kind())
        {
            let (below, above) = cell.split(axis, split);
            child(first_child + 1, above);
            child(first_child, below);
        }
    }

    fn node_count(&self) -> usize {
        KdTree::node_count(self)
    }

    fn reference_count(&self) -> usize {
        self.items.len()
    }
}
