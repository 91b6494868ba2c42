//! The owned API (feature `alloc`): [`MeshBvh`] and [`MeshCells`] (a k-d tree, octree or grid:
//! [`MeshKdTree`], [`MeshOctree`], [`MeshGrid`]), each one value that sizes, owns and builds
//! every buffer of its structure, and
//! [`MeshIndex`], any of them picked at run time — for code with an allocator (tools, the
//! browser package, tests).
//!
//! ```
//! use meshq::prelude::*;
//! let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
//! let mesh = MeshRef::new(&positions, &[[0, 1, 2]]).validate()?;
//! let scene = MeshBvh::build(&mesh, &BuildConfig::default())?;
//! let hit = scene.raycast(&Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z));
//! assert_eq!(hit.map(|h| h.tri), Some(0));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#[cfg(feature = "blob")]
mod blob;
mod cell_scene;
#[cfg(feature = "blob-cells")]
mod index_blob;
mod mesh_bvh;
mod mesh_bvh_winding;
mod mesh_cells;
mod mesh_grid;
mod mesh_index;
mod mesh_index_queries;
mod mesh_pseudo_normals;
mod remeshed;
mod sampled_distance;

pub use crate::structure_kind::{StructureKind, UnknownStructure};
pub use mesh_bvh::MeshBvh;
pub use mesh_cells::{
    CellKind, GridCells, KdTreeCells, MeshCells, MeshGrid, MeshKdTree, MeshOctree, OctreeCells,
};
pub use mesh_index::MeshIndex;
pub use mesh_pseudo_normals::MeshPseudoNormals;
pub use remeshed::Remeshed;
pub use sampled_distance::SampledDistance;
