//! [`BlobStructure`]: the structure of a blob of any kind, read in place from its bytes.

use super::BlobTree;
use crate::cells::{CellStats, LeWords};
use crate::grid::Grid;
use crate::kdtree::KdTree;
use crate::octree::Octree;
use crate::query::{Traverse, Visitor};
use crate::structure_kind::StructureKind;

/// A validated blob's structure, its arrays read straight from the bytes (in RAM or in
/// flash). Obtained from [`BlobView::structure`](super::BlobView::structure) or
/// [`BlobStructure::parse`], so it is always valid; answers every query exactly as the
/// structure it was encoded from, bit for bit.
#[derive(Clone, Copy, Debug)]
pub enum BlobStructure<'a> {
    /// A BVH.
    Bvh(BlobTree<'a>),
    /// A k-d tree.
    KdTree(KdTree<LeWords<'a>, LeWords<'a>>),
    /// An octree.
    Octree(Octree<LeWords<'a>, LeWords<'a>>),
    /// A uniform grid.
    Grid(Grid<LeWords<'a>>),
}

impl BlobStructure<'_> {
    /// Which structure it is.
    #[must_use]
    pub const fn kind(&self) -> StructureKind {
        match self {
            Self::Bvh(_) => StructureKind::Bvh,
            Self::KdTree(_) => StructureKind::KdTree,
            Self::Octree(_) => StructureKind::Octree,
            Self::Grid(_) => StructureKind::Grid,
        }
    }

    /// Cell figures of a k-d tree, octree or grid over `triangles` triangles; `None` for a BVH
    /// (see [`TreeStats`](crate::bvh::TreeStats)).
    #[must_use]
    pub fn cell_stats(&self, triangles: usize) -> Option<CellStats> {
        match self {
            Self::Bvh(_) => None,
            Self::KdTree(t) => Some(t.stats(triangles)),
            Self::Octree(t) => Some(t.stats(triangles)),
            Self::Grid(g) => Some(g.stats(triangles)),
        }
    }
}

impl Traverse for BlobStructure<'_> {
    #[inline]
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        match self {
            Self::Bvh(t) => t.traverse(visitor),
            Self::KdTree(t) => t.traverse(visitor),
            Self::Octree(t) => t.traverse(visitor),
            Self::Grid(g) => g.traverse(visitor),
        }
    }
}
