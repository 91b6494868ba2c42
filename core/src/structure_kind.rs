//! [`StructureKind`]: which acceleration structure, by name and by blob tag.

use core::fmt;
use core::str::FromStr;

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

    /// The blob wire tag: 0 BVH, 1 k-d tree, 2 octree, 3 grid.
    #[must_use]
    pub const fn tag(self) -> u32 {
        match self {
            Self::Bvh => 0,
            Self::KdTree => 1,
            Self::Octree => 2,
            Self::Grid => 3,
        }
    }

    /// The kind with wire tag `tag`, if this build knows it.
    #[must_use]
    #[cfg(feature = "blob")]
    pub(crate) const fn from_tag(tag: u32) -> Option<Self> {
        match tag {
            0 => Some(Self::Bvh),
            1 => Some(Self::KdTree),
            2 => Some(Self::Octree),
            3 => Some(Self::Grid),
            _ => None,
        }
    }

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
