//! [`MeshIndex`]: any of the four structures over a mesh, picked at run time.

use super::{MeshBvh, MeshGrid, MeshKdTree, MeshOctree};
use crate::bvh::BuildConfig;
use crate::cells::CellStats;
use crate::error::BuildError;
use crate::grid::GridConfig;
use crate::kdtree::KdConfig;
use crate::math::{PackedTriangle, Triangle};
use crate::mesh::ValidMesh;
use crate::octree::OctreeConfig;
use crate::query::{LeafTriangles, Traverse, Visitor};
use crate::structure_kind::StructureKind;

/// A mesh with one structure of any kind, owning every buffer; it answers every query of
/// [`MeshQuery`](crate::query::MeshQuery) through whichever structure it holds.
#[derive(Clone, Debug)]
pub enum MeshIndex {
    /// A [`MeshBvh`].
    Bvh(MeshBvh),
    /// A [`MeshKdTree`].
    KdTree(MeshKdTree),
    /// A [`MeshOctree`].
    Octree(MeshOctree),
    /// A [`MeshGrid`].
    Grid(MeshGrid),
}

impl MeshIndex {
    /// Copies `mesh` and builds a structure of `kind` with its default config.
    ///
    /// # Errors
    /// The builder's [`BuildError`].
    pub fn build(mesh: &ValidMesh<'_>, kind: StructureKind) -> Result<Self, BuildError> {
        Ok(match kind {
            StructureKind::Bvh => Self::Bvh(MeshBvh::build(mesh, &BuildConfig::default())?),
            StructureKind::KdTree => Self::KdTree(MeshKdTree::build(mesh, &KdConfig::default())?),
            StructureKind::Octree => {
                Self::Octree(MeshOctree::build(mesh, &OctreeConfig::default())?)
            }
            StructureKind::Grid => Self::Grid(MeshGrid::build(mesh, &GridConfig::default())?),
        })
    }

    /// Which structure it holds.
    #[must_use]
    pub const fn kind(&self) -> StructureKind {
        match self {
            Self::Bvh(_) => StructureKind::Bvh,
            Self::KdTree(_) => StructureKind::KdTree,
            Self::Octree(_) => StructureKind::Octree,
            Self::Grid(_) => StructureKind::Grid,
        }
    }

    /// The mesh.
    #[must_use]
    pub fn mesh(&self) -> ValidMesh<'_> {
        match self {
            Self::Bvh(s) => s.mesh(),
            Self::KdTree(s) => s.mesh(),
            Self::Octree(s) => s.mesh(),
            Self::Grid(s) => s.mesh(),
        }
    }

    /// Cell figures of a k-d tree, octree or grid; `None` for a BVH (see
    /// [`TreeStats`](crate::advanced::TreeStats)).
    #[must_use]
    pub fn cell_stats(&self) -> Option<CellStats> {
        match self {
            Self::Bvh(_) => None,
            Self::KdTree(s) => Some(s.stats()),
            Self::Octree(s) => Some(s.stats()),
            Self::Grid(s) => Some(s.stats()),
        }
    }
}

impl Traverse for MeshIndex {
    #[inline]
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        match self {
            Self::Bvh(s) => s.traverse(visitor),
            Self::KdTree(s) => s.traverse(visitor),
            Self::Octree(s) => s.traverse(visitor),
            Self::Grid(s) => s.traverse(visitor),
        }
    }

    #[inline]
    fn split_refs(&self) -> crate::query::SplitRefs<'_> {
        match self {
            Self::Bvh(s) => s.split_refs(),
            Self::KdTree(_) | Self::Octree(_) | Self::Grid(_) => crate::query::SplitRefs::NONE,
        }
    }

    /// The BVH's ([`MeshBvh`]'s); `None` for the cell structures.
    #[inline]
    fn batch_hint(&self) -> Option<crate::query::BatchHint> {
        match self {
            Self::Bvh(s) => s.batch_hint(),
            Self::KdTree(_) | Self::Octree(_) | Self::Grid(_) => None,
        }
    }

    /// The BVH walks packets; the cell structures march one ray at a time.
    #[inline]
    fn walks_packets(&self) -> bool {
        match self {
            Self::Bvh(s) => s.walks_packets(),
            Self::KdTree(_) | Self::Octree(_) | Self::Grid(_) => false,
        }
    }
}

impl LeafTriangles for MeshIndex {
    #[inline]
    fn corners(&self, slot: usize, tri: u32) -> Option<Triangle> {
        match self {
            Self::Bvh(s) => s.corners(slot, tri),
            Self::KdTree(s) => s.corners(slot, tri),
            Self::Octree(s) => s.corners(slot, tri),
            Self::Grid(s) => s.corners(slot, tri),
        }
    }

    #[inline]
    fn run(&self, first: usize, count: usize) -> Option<&[PackedTriangle]> {
        match self {
            Self::Bvh(s) => s.run(first, count),
            Self::KdTree(s) => s.run(first, count),
            Self::Octree(s) => s.run(first, count),
            Self::Grid(s) => s.run(first, count),
        }
    }
}
