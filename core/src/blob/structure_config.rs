//! The build settings a blob records for its structure, and their wire form.

use serde::ser::{Serialize, Serializer};

use super::format::{ConfigCosts, GridWire, KdWire, OctreeWire, SpatialWire};
use crate::bvh::{BuildConfig, SplitStrategy};
use crate::grid::GridConfig;
use crate::kdtree::KdConfig;
use crate::octree::OctreeConfig;
use crate::structure_kind::StructureKind;

/// The config a blob's structure was built with, as its header records it. Informational for
/// the trees; a grid's `resolution` also fixes where its cells are.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StructureConfig {
    /// A BVH's config ([`SplitStrategy::Sah`] for version 1 blobs, which had no other).
    Bvh(BuildConfig),
    /// A k-d tree's config.
    KdTree(KdConfig),
    /// An octree's config.
    Octree(OctreeConfig),
    /// A grid's config and the resolution it was built at (cells along x, y, z).
    Grid {
        /// The config.
        config: GridConfig,
        /// Cells along x, y and z.
        resolution: [u32; 3],
    },
}

impl StructureConfig {
    /// The structure this config belongs to.
    #[must_use]
    pub const fn kind(&self) -> StructureKind {
        match self {
            Self::Bvh(_) => StructureKind::Bvh,
            Self::KdTree(_) => StructureKind::KdTree,
            Self::Octree(_) => StructureKind::Octree,
            Self::Grid { .. } => StructureKind::Grid,
        }
    }

    /// The BVH config, for a BVH blob.
    #[must_use]
    pub const fn bvh(&self) -> Option<&BuildConfig> {
        match self {
            Self::Bvh(c) => Some(c),
            _ => None,
        }
    }

    /// Whether every setting is in its documented range.
    pub(super) fn is_valid(&self) -> bool {
        match self {
            Self::Bvh(c) => c.check().is_ok(),
            Self::KdTree(c) => c.validate().is_ok(),
            Self::Octree(c) => c.validate().is_ok(),
            Self::Grid { config, .. } => config.validate().is_ok(),
        }
    }
}

/// The config part of a header on the wire, with the reference count of a cell structure:
/// fields back to back, no tag (the header's kind says which). A BVH with spatial splits
/// (`split_refs` is `Some`, version 4) adds its slot count and split references.
pub(super) struct WireConfig {
    pub(super) config: StructureConfig,
    pub(super) references: u32,
    pub(super) split_refs: Option<u32>,
}

impl Serialize for WireConfig {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let references = self.references;
        match self.config {
            StructureConfig::Bvh(c) => match self.split_refs {
                None => (c.split, ConfigCosts::of(&c)).serialize(s),
                Some(split_refs) => {
                    let spatial = SpatialWire {
                        references,
                        split_refs,
                    };
                    (c.split, ConfigCosts::of(&c), spatial).serialize(s)
                }
            },
            StructureConfig::KdTree(c) => KdWire {
                max_depth: c.max_depth,
                leaf_size: c.leaf_size,
                traversal_cost: c.traversal_cost,
                triangle_cost: c.triangle_cost,
                empty_bonus: c.empty_bonus,
                references,
            }
            .serialize(s),
            StructureConfig::Octree(c) => OctreeWire {
                max_depth: c.max_depth,
                max_items: c.max_items,
                references,
            }
            .serialize(s),
            StructureConfig::Grid { config, resolution } => GridWire {
                cells_per_triangle: config.cells_per_triangle,
                max_resolution: config.max_resolution,
                resolution,
                references,
            }
            .serialize(s),
        }
    }
}

impl From<KdWire> for WireConfig {
    fn from(w: KdWire) -> Self {
        Self {
            config: StructureConfig::KdTree(KdConfig {
                max_depth: w.max_depth,
                leaf_size: w.leaf_size,
                traversal_cost: w.traversal_cost,
                triangle_cost: w.triangle_cost,
                empty_bonus: w.empty_bonus,
            }),
            references: w.references,
            split_refs: None,
        }
    }
}

impl From<OctreeWire> for WireConfig {
    fn from(w: OctreeWire) -> Self {
        Self {
            config: StructureConfig::Octree(OctreeConfig {
                max_depth: w.max_depth,
                max_items: w.max_items,
            }),
            references: w.references,
            split_refs: None,
        }
    }
}

impl From<GridWire> for WireConfig {
    fn from(w: GridWire) -> Self {
        Self {
            config: StructureConfig::Grid {
                config: GridConfig {
                    cells_per_triangle: w.cells_per_triangle,
                    max_resolution: w.max_resolution,
                },
                resolution: w.resolution,
            },
            references: w.references,
            split_refs: None,
        }
    }
}

/// A BVH's wire config: the split tag and the costs.
pub(super) fn bvh_config(split: SplitStrategy, costs: ConfigCosts) -> StructureConfig {
    StructureConfig::Bvh(costs.with_split(split))
}
