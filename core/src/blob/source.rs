//! [`BlobSource`]: a built structure of any kind, with its config, ready to encode.

use super::structure_config::StructureConfig;
use crate::advanced::CollapseRoles;
use crate::bvh::{BuildConfig, Bvh};
use crate::error::BlobError;
use crate::grid::{Grid, GridConfig};
use crate::inside::{WindingNode, WindingTree};
use crate::kdtree::{KdConfig, KdNode, KdTree};
use crate::math::Aabb;
use crate::mesh::ValidMesh;
use crate::octree::{Octree, OctreeConfig, OctreeNode};
use crate::structure_kind::StructureKind;

/// A structure built in memory, with the config it was built with, as
/// [`encode_structure_into`](super::encode_structure_into) writes it.
#[derive(Clone, Copy, Debug)]
pub enum BlobSource<'q> {
    /// A BVH, with the optional sections to store beside it.
    Bvh(&'q Bvh<'q>, BuildConfig, BvhSections<'q>),
    /// A k-d tree.
    KdTree(&'q KdTree<&'q [KdNode], &'q [u32]>, KdConfig),
    /// An octree.
    Octree(&'q Octree<&'q [OctreeNode], &'q [u32]>, OctreeConfig),
    /// A uniform grid (its resolution is recorded with the config).
    Grid(&'q Grid<&'q [u32]>, GridConfig),
}

/// What a BVH blob may hold besides the tree and mesh.
#[derive(Clone, Copy, Debug, Default)]
pub struct BvhSections<'q> {
    /// The roles of the tree's nodes in its eight-wide collapse (format version 5, see
    /// [`EncodeOptions::collapse_roles`](super::EncodeOptions::collapse_roles)), or `None`.
    pub collapse_roles: Option<CollapseRoles<'q>>,
    /// The winding-number expansions (format version 6, see
    /// [`EncodeOptions::winding`](super::EncodeOptions::winding)), or `None`.
    pub winding: Option<&'q [WindingNode]>,
}

impl BlobSource<'_> {
    /// Which structure it is.
    #[must_use]
    pub const fn kind(&self) -> StructureKind {
        match self {
            Self::Bvh(..) => StructureKind::Bvh,
            Self::KdTree(..) => StructureKind::KdTree,
            Self::Octree(..) => StructureKind::Octree,
            Self::Grid(..) => StructureKind::Grid,
        }
    }

    /// The config the header records.
    pub(super) fn config(&self) -> StructureConfig {
        match self {
            Self::Bvh(_, c, _) => StructureConfig::Bvh(*c),
            Self::KdTree(_, c) => StructureConfig::KdTree(*c),
            Self::Octree(_, c) => StructureConfig::Octree(*c),
            Self::Grid(g, c) => StructureConfig::Grid {
                config: *c,
                resolution: g.layout().resolution,
            },
        }
    }

    /// The box the header records (see [`BlobHeader::bounds`](super::BlobHeader::bounds)).
    pub(super) fn bounds(&self) -> Aabb {
        match self {
            Self::Bvh(b, ..) => b.bounds(),
            Self::KdTree(t, _) => *t.bounds(),
            Self::Octree(t, _) => *t.bounds(),
            Self::Grid(g, _) => g.layout().bounds,
        }
    }

    /// Nodes of a tree; cells of a grid.
    pub(super) fn node_count(&self) -> usize {
        match self {
            Self::Bvh(b, ..) => b.nodes().len(),
            Self::KdTree(t, _) => t.node_count(),
            Self::Octree(t, _) => t.node_count(),
            Self::Grid(g, _) => g.offsets().len().saturating_sub(1),
        }
    }

    /// The depth the header records (see [`BlobHeader::depth`](super::BlobHeader::depth)).
    pub(super) fn depth(&self, triangles: usize) -> u32 {
        let deepest = |d: usize| u32::try_from(d).unwrap_or(u32::MAX);
        match self {
            Self::Bvh(b, ..) => b.depth(),
            Self::KdTree(t, _) => deepest(t.stats(triangles).max_depth),
            Self::Octree(t, _) => deepest(t.stats(triangles).max_depth),
            Self::Grid(..) => 0,
        }
    }

    /// The leaf-slot → triangle array: a BVH's order, a cell structure's references.
    pub(super) fn order(&self) -> &[u32] {
        match self {
            Self::Bvh(b, ..) => b.order(),
            Self::KdTree(t, _) => t.items(),
            Self::Octree(t, _) => t.items(),
            Self::Grid(g, _) => g.items(),
        }
    }

    /// Validates the structure against `mesh`, as a reader will.
    pub(super) fn check(&self, mesh: &ValidMesh<'_>) -> Result<(), BlobError> {
        let n = mesh.triangle_count();
        match self {
            Self::Bvh(b, _, sections) => {
                b.check(mesh)?;
                if let Some(roles) = sections.collapse_roles {
                    roles.check(*b).map_err(|()| BlobError::BadCollapsePlan)?;
                }
                if let Some(nodes) = sections.winding
                    && !WindingTree::expansions_match(*b, mesh, &nodes)
                {
                    return Err(BlobError::BadWindingNodes);
                }
                super::split_check::check_slots(*b, b.order().iter().copied(), n)?;
                crate::bvh::split_coverage::check_split_coverage(*b, mesh)?;
            }
            Self::KdTree(t, _) => {
                KdTree::from_parts(*t.bounds(), t.nodes(), t.items(), n)?;
            }
            Self::Octree(t, _) => {
                Octree::from_parts(*t.bounds(), t.nodes(), t.items(), n)?;
            }
            Self::Grid(g, _) => {
                Grid::from_parts(*g.layout(), g.offsets(), g.items(), n)?;
            }
        }
        Ok(())
    }
}
