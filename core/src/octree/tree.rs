//! A built octree over its arrays, and its build into caller buffers.

use super::split::{OctreeSplitter, octants, root_cube};
use super::{OctreeConfig, OctreeNode};
use crate::cells::{
    self, CellNode, CellStats, CellTree, ReferencePad, TreeSizes, Words, build_tree,
};
use crate::error::BuildError;
use crate::math::Aabb;
use crate::mesh::ValidMesh;
use crate::query::Cell;

/// Deferred cells of a depth-first walk: seven siblings per level.
pub(super) const STACK: usize = 7 * OctreeConfig::MAX_DEPTH as usize + 2;

/// An adaptive octree: a cube around the mesh, split into eight octants wherever a cell holds
/// more than `max_items` references, each leaf listing the triangles it touches.
///
/// `nodes` are [`OctreeNode`]s (two words each; node 0 is the root, children after their
/// parent), `items` the references leaves point into. The arrays are slices from
/// [`Octree::build`] or [`Octree::from_parts`], or a blob's bytes read in place
/// ([`LeWords`](crate::advanced::LeWords)).
///
/// It answers every query through [`Traverse`](crate::query::Traverse): at each cell the
/// visitor judges the eight octants (four at a time in SIMD lanes) and the walk takes them
/// nearest first — front to back along a ray — skipping deferred cells the answer has
/// already passed.
#[derive(Clone, Copy, Debug)]
pub struct Octree<N, W> {
    pub(super) root: Aabb,
    pub(super) nodes: N,
    pub(super) items: W,
}

impl<'a> Octree<&'a [OctreeNode], &'a [u32]> {
    /// The exact sizes [`Octree::build`] needs for `mesh` with `config`: a full build that
    /// writes no nodes, using `work` for the reference lists (see [`TreeSizes`]; give it a few
    /// times the triangle count, and retry longer while the result is not `complete`).
    ///
    /// # Errors
    /// [`BuildError::InvalidConfig`] for a config out of range;
    /// [`BuildError::BufferTooSmall`] when `work` is shorter than the triangle count.
    pub fn measure(
        mesh: &ValidMesh<'_>,
        config: &OctreeConfig,
        work: &mut [u32],
    ) -> Result<TreeSizes, BuildError> {
        config.validate()?;
        let splitter = splitter(mesh, config);
        let root = Cell::root(root_cube(&mesh.bounds()));
        let built = build_tree(&splitter, mesh.triangle_count(), root, work, None)?;
        Ok(built.sizes())
    }

    /// Builds the octree of `mesh` into `nodes` and `items`, which it borrows (their used
    /// prefixes).
    ///
    /// Stays inside the buffers: a cell whose octants would not fit (nodes, or references
    /// while building) stays a leaf, so short buffers give a coarser tree, never an error, as
    /// long as the root fits. The tree depends only on the mesh, the config and the two
    /// lengths; [`Octree::measure`] tells the lengths that build the full tree.
    ///
    /// # Errors
    /// [`BuildError::InvalidConfig`] for a config out of range;
    /// [`BuildError::BufferTooSmall`] when `items` is shorter than the triangle count or
    /// `nodes` is empty. Nothing usable is returned then.
    pub fn build(
        mesh: &ValidMesh<'_>,
        config: &OctreeConfig,
        nodes: &'a mut [OctreeNode],
        items: &'a mut [u32],
    ) -> Result<Self, BuildError> {
        Self::build_sized(mesh, config, nodes, items).map(|(tree, _)| tree)
    }

    /// [`Octree::build`], with the sizes [`Octree::measure`] would report for these buffer
    /// lengths: `complete` when no cell stayed a leaf for lack of room.
    pub(crate) fn build_sized(
        mesh: &ValidMesh<'_>,
        config: &OctreeConfig,
        nodes: &'a mut [OctreeNode],
        items: &'a mut [u32],
    ) -> Result<(Self, TreeSizes), BuildError> {
        config.validate()?;
        let splitter = splitter(mesh, config);
        let root = root_cube(&mesh.bounds());
        let built = build_tree(
            &splitter,
            mesh.triangle_count(),
            Cell::root(root),
            items,
            Some(nodes),
        )?;
        let nodes: &'a [OctreeNode] = nodes.get(..built.nodes).unwrap_or_default();
        let items: &'a [u32] = items.get(..built.references).unwrap_or_default();
        Ok((Self { root, nodes, items }, built.sizes()))
    }
}

fn splitter<'m>(mesh: &'m ValidMesh<'m>, config: &OctreeConfig) -> OctreeSplitter<'m> {
    OctreeSplitter {
        mesh,
        config: *config,
        pad: ReferencePad::of(&mesh.bounds()),
    }
}

impl<N: Words, W: Words> Octree<N, W> {
    /// Wraps arrays this crate built or checked itself, without checking again.
    #[cfg_attr(not(feature = "alloc"), allow(dead_code))]
    pub(crate) const fn from_validated(root: Aabb, nodes: N, items: W) -> Self {
        Self { root, nodes, items }
    }

    /// The root cell's box: the cube around the mesh bounds that the octants split.
    #[must_use]
    pub const fn bounds(&self) -> &Aabb {
        &self.root
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
    pub fn node(&self, i: usize) -> Option<OctreeNode> {
        let [a, b] = self.nodes.pair(i)?;
        Some(OctreeNode { a, b })
    }

    /// The cells the tree has cut its bounds into after `stop_depth` levels of splits, with
    /// their depth (the root is 0): every leaf at depth `stop_depth` or less, with its
    /// `(first, count)` range of references, and every inner node at depth `stop_depth`, with
    /// `None`. Together they tile the root; depth first, lower child first.
    pub fn for_each_cell(&self, stop_depth: u32, each: impl FnMut(Cell, u32, Option<(u32, u32)>)) {
        cells::for_each_cell::<_, STACK>(self, stop_depth, each);
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
        cells::first_uncovered_in_tree::<_, _, STACK>(self, pad, coverage, triangles)
    }

    /// Nodes, leaf cells, empty cells, references, depth.
    #[must_use]
    pub fn stats(&self, triangles: usize) -> CellStats {
        cells::stats::<_, STACK>(self, triangles)
    }
}

impl<N: Words, W: Words> CellTree for Octree<N, W> {
    fn root_cell(&self) -> Cell {
        Cell::root(self.root)
    }

    fn cell_node(&self, node: u32) -> Option<CellNode> {
        let n = self.node(node as usize)?;
        Some(match n.first_child() {
            None => CellNode::Leaf {
                first: n.a,
                count: n.b,
            },
            Some(_) => CellNode::Inner,
        })
    }

    fn children(&self, node: u32, cell: &Cell, depth: u32, mut child: impl FnMut(u32, Cell)) {
        let first = self.node(node as usize).and_then(|n| n.first_child());
        if let Some(first) = first
            && depth < OctreeConfig::MAX_DEPTH
        {
            for (k, c) in octants(cell).into_iter().enumerate().rev() {
                child(first + k as u32, c);
            }
        }
    }

    fn node_count(&self) -> usize {
        Octree::node_count(self)
    }

    fn reference_count(&self) -> usize {
        self.items.len()
    }
}
