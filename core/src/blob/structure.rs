//! [`BlobStructure`]: the structure of a blob of any kind, read in place from its bytes.

use super::BlobTree;
use crate::cells::CellStats;
#[cfg(feature = "blob-cells")]
use crate::cells::LeWords;
#[cfg(feature = "blob-cells")]
use crate::grid::Grid;
#[cfg(feature = "blob-cells")]
use crate::kdtree::KdTree;
#[cfg(feature = "blob-cells")]
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
    /// A k-d tree (feature `blob-cells`).
    #[cfg(feature = "blob-cells")]
    KdTree(KdTree<LeWords<'a>, LeWords<'a>>),
    /// An octree (feature `blob-cells`).
    #[cfg(feature = "blob-cells")]
    Octree(Octree<LeWords<'a>, LeWords<'a>>),
    /// A uniform grid (feature `blob-cells`).
    #[cfg(feature = "blob-cells")]
    Grid(Grid<LeWords<'a>>),
}

impl BlobStructure<'_> {
    /// Which structure it is.
    #[must_use]
    pub const fn kind(&self) -> StructureKind {
        match self {
            Self::Bvh(_) => StructureKind::Bvh,
            #[cfg(feature = "blob-cells")]
            Self::KdTree(_) => StructureKind::KdTree,
            #[cfg(feature = "blob-cells")]
            Self::Octree(_) => StructureKind::Octree,
            #[cfg(feature = "blob-cells")]
            Self::Grid(_) => StructureKind::Grid,
        }
    }

    /// Cell figures of a k-d tree, octree or grid over `triangles` triangles; `None` for a BVH
    /// (see [`TreeStats`](crate::advanced::TreeStats)).
    #[must_use]
    #[cfg_attr(not(feature = "blob-cells"), allow(unused_variables))]
    pub fn cell_stats(&self, triangles: usize) -> Option<CellStats> {
        match self {
            Self::Bvh(_) => None,
            #[cfg(feature = "blob-cells")]
            Self::KdTree(t) => Some(t.stats(triangles)),
            #[cfg(feature = "blob-cells")]
            Self::Octree(t) => Some(t.stats(triangles)),
            #[cfg(feature = "blob-cells")]
            Self::Grid(g) => Some(g.stats(triangles)),
        }
    }
}

impl Traverse for BlobStructure<'_> {
    #[inline]
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        match self {
            Self::Bvh(t) => t.traverse(visitor),
            #[cfg(feature = "blob-cells")]
            Self::KdTree(t) => walk_apart(t, visitor),
            #[cfg(feature = "blob-cells")]
            Self::Octree(t) => walk_apart(t, visitor),
            #[cfg(feature = "blob-cells")]
            Self::Grid(g) => walk_apart(g, visitor),
        }
    }

    #[inline]
    fn split_refs(&self) -> crate::query::SplitRefs<'_> {
        match self {
            Self::Bvh(t) => crate::bvh::TreeArrays::split_refs(t),
            #[cfg(feature = "blob-cells")]
            _ => crate::query::SplitRefs::NONE,
        }
    }
}

#[cfg(feature = "blob-cells")]
/// A cell structure's walk in a frame of its own. Inlined, its traversal stack would join the
/// caller's frame, and a BVH walk would reserve the stack an octree's needs (kilobytes, on a
/// microcontroller) without using it.
#[inline(never)]
fn walk_apart<T: Traverse, V: Visitor + ?Sized>(structure: &T, visitor: &mut V) {
    structure.traverse(visitor);
}
