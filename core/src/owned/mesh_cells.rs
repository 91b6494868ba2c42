//! [`MeshCells`]: a mesh and a structure that cuts space into cells (k-d tree, octree or
//! uniform grid), in buffers it owns. One type for the three, generic over the kind
//! ([`CellKind`]): what they share (the mesh copy, the triangles packed per reference, the
//! queries) is written once, and each kind says only how it builds and reads its arrays.

use alloc::vec;
use alloc::vec::Vec;
use core::fmt::Debug;

use super::cell_scene::{CellScene, measure_fully, node_room, work_room};
use super::mesh_grid::fill_in_one_pass;
use crate::cells::CellStats;
use crate::error::BuildError;
use crate::grid::{Grid, GridConfig, GridLayout, layout_within, reference_budget};
use crate::kdtree::{KdConfig, KdNode, KdTree};
use crate::math::{Aabb, PackedTriangle, Triangle};
use crate::mesh::ValidMesh;
use crate::octree::{Octree, OctreeConfig, OctreeNode};
use crate::query::{LeafTriangles, MeshQuery, Traverse, Visitor};

mod sealed {
    /// Only this crate's kinds: the owned types' layout is this crate's to keep.
    pub trait Sealed {}
}

/// A kind of cell structure [`MeshCells`] holds: [`KdTreeCells`], [`OctreeCells`] or
/// [`GridCells`]. Sealed.
pub trait CellKind: sealed::Sealed + Sized {
    /// The build config.
    type Config: Copy + Debug + PartialEq;
    /// The structure's arrays, owned.
    #[doc(hidden)]
    type Arrays: Clone + Debug;
    /// The view over the arrays that queries walk.
    type View<'a>: Traverse
    where
        Self: 'a;
    /// Builds the arrays over `mesh` with `config`, at full size.
    #[doc(hidden)]
    fn build(mesh: &ValidMesh<'_>, config: &Self::Config) -> Result<Self::Arrays, BuildError>;
    /// The view over `arrays`.
    #[doc(hidden)]
    fn view(arrays: &Self::Arrays) -> Self::View<'_>;
    /// The references, in the order leaves read them.
    #[doc(hidden)]
    fn items(arrays: &Self::Arrays) -> &[u32];
    /// The root cell's box.
    #[doc(hidden)]
    fn bounds(arrays: &Self::Arrays) -> Aabb;
    /// Bytes of the arrays.
    #[doc(hidden)]
    fn structure_bytes(arrays: &Self::Arrays) -> usize;
    /// Nodes (or cells), references, empty cells, depth, for `triangles` triangles.
    #[doc(hidden)]
    fn stats(arrays: &Self::Arrays, triangles: usize) -> CellStats;
    /// What a blob of `view` with `config` is encoded from.
    #[cfg(feature = "blob")]
    #[doc(hidden)]
    fn source<'a, 'v: 'a>(
        view: &'a Self::View<'v>,
        config: Self::Config,
    ) -> crate::blob::BlobSource<'a>;
}

/// A mesh with a cell structure of kind `K`, owning every buffer: the mesh copy, the
/// structure's arrays (exactly what its builder writes into buffers of the measured lengths)
/// and the triangles packed per reference, which queries read. Answers every query of
/// [`MeshQuery`], exactly as the structure over the mesh does. Named for each kind:
/// [`MeshKdTree`], [`MeshOctree`], [`MeshGrid`].
#[derive(Clone, Debug)]
pub struct MeshCells<K: CellKind> {
    pub(super) scene: CellScene,
    pub(super) arrays: K::Arrays,
    pub(super) config: K::Config,
}

/// A mesh and its k-d tree ([`KdTree`]).
pub type MeshKdTree = MeshCells<KdTreeCells>;
/// A mesh and its octree ([`Octree`]).
pub type MeshOctree = MeshCells<OctreeCells>;
/// A mesh and its uniform grid ([`Grid`]).
pub type MeshGrid = MeshCells<GridCells>;

impl<K: CellKind> MeshCells<K> {
    /// Copies `mesh` and builds its full structure with `config`.
    ///
    /// # Errors
    /// [`BuildError::InvalidConfig`] for a config out of range.
    pub fn build(mesh: &ValidMesh<'_>, config: &K::Config) -> Result<Self, BuildError> {
        let mut scene = CellScene::copy(mesh);
        let arrays = K::build(&scene.mesh(), config)?;
        scene.pack(K::items(&arrays))?;
        Ok(Self {
            scene,
            arrays,
            config: *config,
        })
    }

    /// The structure over [`MeshCells::mesh`].
    #[must_use]
    pub fn structure(&self) -> K::View<'_> {
        K::view(&self.arrays)
    }

    /// The mesh.
    #[must_use]
    pub fn mesh(&self) -> ValidMesh<'_> {
        self.scene.mesh()
    }

    /// The config it was built with.
    #[must_use]
    pub const fn config(&self) -> &K::Config {
        &self.config
    }

    /// The root cell's box: it holds every triangle (a k-d tree's and a grid's are the mesh
    /// bounds, an octree's the cube around them).
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        K::bounds(&self.arrays)
    }

    /// Nodes (or cells), references, empty cells, depth.
    #[must_use]
    pub fn stats(&self) -> CellStats {
        K::stats(&self.arrays, self.scene.triangles.len())
    }

    /// Bytes of the structure's own arrays (not the mesh or the packed triangles).
    #[must_use]
    pub fn structure_bytes(&self) -> usize {
        K::structure_bytes(&self.arrays)
    }

    /// Bytes of the packed triangles (36 per reference).
    #[must_use]
    pub fn packed_bytes(&self) -> usize {
        self.scene.packed_bytes()
    }
}

impl<K: CellKind> Traverse for MeshCells<K> {
    #[inline(always)]
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        self.structure().traverse(visitor);
    }
}

impl<K: CellKind> MeshQuery for MeshCells<K> {}

impl<K: CellKind> LeafTriangles for MeshCells<K> {
    #[inline(always)]
    fn corners(&self, slot: usize, tri: u32) -> Option<Triangle> {
        self.scene.corners(slot, tri)
    }

    #[inline(always)]
    fn run(&self, first: usize, count: usize) -> Option<&[PackedTriangle]> {
        self.scene.run(first, count)
    }
}

/// The owned arrays of a tree of cells (k-d tree or octree): its root cell's box, its nodes
/// and its references.
#[doc(hidden)]
#[derive(Clone, Debug)]
pub struct TreeArrays<N> {
    pub(super) bounds: Aabb,
    pub(super) nodes: Vec<N>,
    pub(super) items: Vec<u32>,
}

/// The [`CellKind`] of a tree of cells: the k-d tree and the octree differ only by their
/// types (tree, node, config) and their blob source.
macro_rules! tree_cell_kind {
    ($kind:ident, $tree:ident, $node:ident, $config:ident, $what:literal, $alias:ident) => {
        #[doc = concat!("The ", $what, " kind of [`MeshCells`] ([`", stringify!($alias), "`]).")]
        #[derive(Clone, Copy, Debug)]
        pub struct $kind;

        impl sealed::Sealed for $kind {}

        impl CellKind for $kind {
            type Config = $config;
            type Arrays = TreeArrays<$node>;
            type View<'a> = $tree<&'a [$node], &'a [u32]>;

            fn build(mesh: &ValidMesh<'_>, config: &$config) -> Result<Self::Arrays, BuildError> {
                // One pass, into the room an ordinary mesh never outgrows; a mesh that does
                // is measured first and built into the lengths measured, as before.
                let triangles = mesh.triangle_count();
                let mut nodes = vec![$node::default(); node_room(triangles)];
                let mut items = vec![0u32; work_room(triangles)];
                let (tree, mut sizes) = $tree::build_sized(mesh, config, &mut nodes, &mut items)?;
                let mut bounds = *tree.bounds();
                if !sizes.complete {
                    sizes = measure_fully(triangles, |w| $tree::measure(mesh, config, w))?;
                    nodes = vec![$node::default(); sizes.nodes];
                    items = vec![0u32; sizes.work];
                    bounds = *$tree::build(mesh, config, &mut nodes, &mut items)?.bounds();
                }
                nodes.truncate(sizes.nodes);
                nodes.shrink_to_fit();
                items.truncate(sizes.items);
                items.shrink_to_fit();
                Ok(TreeArrays {
                    bounds,
                    nodes,
                    items,
                })
            }

            fn view(arrays: &Self::Arrays) -> Self::View<'_> {
                $tree::from_validated(arrays.bounds, &arrays.nodes, &arrays.items)
            }

            fn items(arrays: &Self::Arrays) -> &[u32] {
                &arrays.items
            }

            fn bounds(arrays: &Self::Arrays) -> Aabb {
                arrays.bounds
            }

            /// Two words per node, one per reference.
            fn structure_bytes(arrays: &Self::Arrays) -> usize {
                8 * arrays.nodes.len() + 4 * arrays.items.len()
            }

            fn stats(arrays: &Self::Arrays, triangles: usize) -> CellStats {
                Self::view(arrays).stats(triangles)
            }

            #[cfg(feature = "blob")]
            fn source<'a, 'v: 'a>(
                view: &'a Self::View<'v>,
                config: Self::Config,
            ) -> crate::blob::BlobSource<'a> {
                crate::blob::BlobSource::$tree(view, config)
            }
        }
    };
}

tree_cell_kind!(
    KdTreeCells,
    KdTree,
    KdNode,
    KdConfig,
    "k-d tree",
    MeshKdTree
);
tree_cell_kind!(
    OctreeCells,
    Octree,
    OctreeNode,
    OctreeConfig,
    "octree",
    MeshOctree
);

/// The uniform grid kind of [`MeshCells`] ([`MeshGrid`]).
#[derive(Clone, Copy, Debug)]
pub struct GridCells;

/// The owned arrays of a uniform grid.
#[doc(hidden)]
#[derive(Clone, Debug)]
pub struct GridArrays {
    pub(super) layout: GridLayout,
    pub(super) offsets: Vec<u32>,
    pub(super) items: Vec<u32>,
}

impl sealed::Sealed for GridCells {}

impl CellKind for GridCells {
    type Config = GridConfig;
    type Arrays = GridArrays;
    type View<'a> = Grid<&'a [u32]>;

    /// The layout [`Grid::measure`] picks: the finest within
    /// [`REFERENCES_PER_TRIANGLE`](crate::cells::REFERENCES_PER_TRIANGLE) references per
    /// triangle.
    fn build(mesh: &ValidMesh<'_>, config: &GridConfig) -> Result<GridArrays, BuildError> {
        config.validate()?;
        let (layout, _) = layout_within(mesh, config, reference_budget(mesh));
        let (offsets, items) = fill_in_one_pass(&layout, mesh)?;
        Ok(GridArrays {
            layout,
            offsets,
            items,
        })
    }

    fn view(arrays: &GridArrays) -> Self::View<'_> {
        Grid::from_validated(arrays.layout, &arrays.offsets, &arrays.items)
    }

    fn items(arrays: &GridArrays) -> &[u32] {
        &arrays.items
    }

    fn bounds(arrays: &GridArrays) -> Aabb {
        arrays.layout.bounds
    }

    fn structure_bytes(arrays: &GridArrays) -> usize {
        4 * (arrays.offsets.len() + arrays.items.len())
    }

    fn stats(arrays: &GridArrays, triangles: usize) -> CellStats {
        Self::view(arrays).stats(triangles)
    }

    #[cfg(feature = "blob")]
    fn source<'a, 'v: 'a>(
        view: &'a Self::View<'v>,
        config: Self::Config,
    ) -> crate::blob::BlobSource<'a> {
        crate::blob::BlobSource::Grid(view, config)
    }
}
