//! `--structure`: which acceleration structure a command builds.

use clap::ValueEnum;
use meshq::owned::StructureKind;

/// The structure to build over a mesh input. All four give the same answers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum StructureArg {
    /// Bounding volume hierarchy (binned SAH, walked four-wide).
    #[default]
    Bvh,
    /// k-d tree (SAH over clipped triangles).
    Kdtree,
    /// Adaptive octree.
    Octree,
    /// Uniform grid.
    Grid,
}

impl StructureArg {
    pub fn kind(self) -> StructureKind {
        match self {
            Self::Bvh => StructureKind::Bvh,
            Self::Kdtree => StructureKind::KdTree,
            Self::Octree => StructureKind::Octree,
            Self::Grid => StructureKind::Grid,
        }
    }
}
