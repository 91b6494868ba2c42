//! [`MeshIndex`]: any of the four structures over a mesh, picked at run time.

use core::fmt;
use core::str::FromStr;

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

/// The four structures meshq builds. All answer every query identically; they differ in build
/// time, memory and speed by scene.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum StructureKind {
    /// Bounding volume hierarchy (binned SAH, walked four-wide): the default.
    #[default]
    Bvh,
    /// k-d tree (SAH over clipped triangles).
    KdTree,
    /// Adaptive octree.
    Octree,
    /// Uniform grid.
    Grid,
}

impl StructureKind {
    /// Every kind, in documentation order.
    pub const ALL: [Self; 4] = [Self::Bvh, Self::KdTree, Self::Octree, Self::Grid];

    /// The name the CLI and the wasm package use: `bvh`, `kdtree`, `octree`, `grid`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Bvh => "bvh",
            Self::KdTree => "kdtree",
            Self::Octree => "octree",
            Self::Grid => "grid",
        }
    }
}

impl fmt::Display for StructureKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is not one of [`StructureKind::name`]'s.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UnknownStructure;

impl fmt::Display for UnknownStructure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("unknown structure: expected bvh, kdtree, octree or grid")
    }
}

impl core::error::Error for UnknownStructure {}

impl FromStr for StructureKind {
    type Err = UnknownStructure;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or(UnknownStructure)
    }
}

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
    /// [`TreeStats`](crate::bvh::TreeStats)).
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
