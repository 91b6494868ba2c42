//! [`MeshBvh`]: a mesh, its BVH and the copies queries read, in buffers it owns.

use alloc::vec;
use alloc::vec::Vec;

use crate::advanced::{CollapsePlan, CollapseRoles};
use crate::bvh::{BuildConfig, Bvh, BvhNode, PrimRef, SpatialSplits, node_capacity};
use crate::error::BuildError;
use crate::inside::WindingNode;
use crate::math::{Aabb, PackedTriangle, Triangle};
use crate::mesh::ValidMesh;
use crate::query::{
    BatchHint, LeafTriangles, PackedTriangles, SplitRef, SplitRefs, Traverse, Visitor,
};
use crate::wide::collapse::{collapse_planned_vec, collapse_vec};
#[cfg(feature = "parallel")]
use crate::wide::parallel_collapse::collapse_vec_parallel;
use crate::wide::{CompactNode, WideBvh, WideNode, WideNode8};

/// A mesh with its BVH, owning every buffer: the positions and triangles, the binary tree
/// (nodes and order), the triangles packed in leaf order, and the tree collapsed for queries
/// (eight-wide where [`MeshBvh::EIGHT_WIDE_BY_DEFAULT`] says so, four-wide elsewhere) — each
/// sized by the crate's sizing functions and trimmed to what the build used.
///
/// It is a structure and its triangles at once, so it answers every query of
/// [`MeshQuery`](crate::query::MeshQuery) (`scene.raycast(&ray)`, batches, overlaps) and runs
/// custom visitors ([`Traverse`]). Queries walk the wide tree over the packed triangles; every
/// answer is exactly what the binary tree over the mesh gives, bit for bit, on every target,
/// whichever wide tree it is. [`MeshBvh::with_compact_nodes`] trades the wide nodes for
/// quantized four-wide ones ([`WideBvh`] of [`CompactNode`]), half the bytes of four-wide nodes;
/// [`MeshBvh::with_eight_wide_nodes`] and [`MeshBvh::with_four_wide_nodes`] pick the
/// eight-wide ([`WideBvh`] of [`WideNode8`]) or four-wide ([`WideBvh`]) tree whatever the target.
/// [`MeshBvh::bvh`], [`MeshBvh::wide`], [`MeshBvh::compact`], [`MeshBvh::eight_wide`],
/// [`MeshBvh::packed`] and [`MeshBvh::mesh`] lend the views for code that wants a particular
/// one.
#[derive(Clone, Debug)]
pub struct MeshBvh {
    pub(super) positions: Vec<[f32; 3]>,
    pub(super) triangles: Vec<[u32; 3]>,
    pub(super) nodes: Vec<BvhNode>,
    pub(super) order: Vec<u32>,
    pub(super) depth: u32,
    pub(super) packed: Vec<PackedTriangle>,
    pub(super) wide: WideNodes,
    pub(super) config: BuildConfig,
    /// The references of triangles held in several leaves (spatial splits), by triangle.
    pub(super) splits: Vec<SplitRef>,
    /// The winding-number expansions, one per binary node, once prepared.
    pub(super) winding: Option<Vec<WindingNode>>,
}

/// The nodes queries walk: the four-wide tree, the same quantized, or the eight-wide tree.
#[derive(Clone, Debug)]
pub(super) enum WideNodes {
    Full(Vec<WideNode>),
    Compact(Vec<CompactNode>),
    Eight(Vec<WideNode8>),
}

impl MeshBvh {
    /// Whether queries walk the eight-wide tree ([`WideBvh`] of [`WideNode8`]) unless told otherwise (by
    /// [`MeshBvh::with_four_wide_nodes`] or [`MeshBvh::with_compact_nodes`]): fixed when the
    /// crate is compiled, true for targets with 128-bit SIMD or wider — x86 with SSE2 (every
    /// x86-64), AArch64 and other targets with NEON, and wasm32 — where eight lanes are one
    /// instruction or two, false elsewhere (the four-wide tree, [`WideBvh`], where lanes are
    /// scalar). Answers are the same either way; only [`MeshBvh::wide`],
    /// [`MeshBvh::eight_wide`] and [`MeshBvh::query_node_bytes`] tell the difference.
    pub const EIGHT_WIDE_BY_DEFAULT: bool = cfg!(any(
        target_feature = "sse2",
        target_feature = "neon",
        target_arch = "wasm32"
    ));

    /// Copies `mesh` and builds its BVH with `config` (see [`Bvh::build`]), then packs its
    /// triangles and widens it. Deterministic: the same mesh and config give the same buffers
    /// on every target.
    ///
    /// # Errors
    /// [`BuildError::TooDeep`] or [`BuildError::InvalidConfig`], as [`Bvh::build`].
    pub fn build(mesh: &ValidMesh<'_>, config: &BuildConfig) -> Result<Self, BuildError> {
        Self::build_with(mesh, config, false)
    }

    /// [`MeshBvh::build`] with the tree built on rayon's thread pool ([`Bvh::build_parallel`],
    /// feature `parallel`): the same buffers, bit for bit.
    ///
    /// # Errors
    /// As [`MeshBvh::build`].
    #[cfg(feature = "parallel")]
    pub fn build_parallel(mesh: &ValidMesh<'_>, config: &BuildConfig) -> Result<Self, BuildError> {
        Self::build_with(mesh, config, true)
    }

    /// [`MeshBvh::build`] with spatial splits ([`Bvh::build_spatial`]): a node whose best split
    /// by centroid leaves overlapping children may cut space instead and hold the triangles
    /// crossing the plane on both sides, each boxed by its part. For meshes of long thin
    /// triangles that cross (architecture, CAD, foliage) rays then visit fewer nodes; on
    /// meshes of even triangles the tree is much the one [`MeshBvh::build`] makes. Every query
    /// answers exactly as on [`MeshBvh::build`]'s tree: rays and closest points the same
    /// triangle and bits, overlaps and triangle pairs each triangle once
    /// ([`SplitRefs`]). [`MeshQuery::shapecast`](crate::query::MeshQuery::shapecast) may offer
    /// a split triangle once per leaf holding it; `shapecast_once` offers each once. Built on
    /// one thread ([`MeshBvh::build_spatial_parallel`] builds on the pool). Deterministic.
    ///
    /// # Errors
    /// As [`MeshBvh::build`], and [`BuildError::InvalidConfig`] for a bad `spatial`.
    pub fn build_spatial(
        mesh: &ValidMesh<'_>,
        config: &BuildConfig,
        spatial: &SpatialSplits,
    ) -> Result<Self, BuildError> {
        Self::build_spatial_with(mesh, config, spatial, false)
    }

    /// [`MeshBvh::build_spatial`] on rayon's thread pool ([`Bvh::build_spatial_parallel`],
    /// feature `parallel`): the same buffers, bit for bit.
    ///
    /// # Errors
    /// As [`MeshBvh::build_spatial`].
    #[cfg(feature = "parallel")]
    pub fn build_spatial_parallel(
        mesh: &ValidMesh<'_>,
        config: &BuildConfig,
        spatial: &SpatialSplits,
    ) -> Result<Self, BuildError> {
        Self::build_spatial_with(mesh, config, spatial, true)
    }

    /// Copies the mesh, builds its tree with spatial splits (on the pool when `parallel`),
    /// packs and widens.
    fn build_spatial_with(
        mesh: &ValidMesh<'_>,
        config: &BuildConfig,
        spatial: &SpatialSplits,
        parallel: bool,
    ) -> Result<Self, BuildError> {
        spatial.check()?;
        let positions = mesh.positions().to_vec();
        let triangles = mesh.triangles().to_vec();
        let n = triangles.len();
        let room = spatial.reference_capacity(n);
        let mut nodes = filled(BvhNode::EMPTY, node_capacity(room), parallel);
        let mut order = filled(0u32, room, parallel);
        let mut scratch = filled(PrimRef::EMPTY, room, parallel);
        let mut splits = vec![SplitRef::EMPTY; spatial.split_ref_capacity(n)];
        let (used, slots, split_count, depth) = {
            let copy = ValidMesh::new_unchecked_by_validate(&positions, &triangles);
            let build = if parallel {
                #[cfg(feature = "parallel")]
                {
                    Bvh::build_spatial_parallel
                }
                #[cfg(not(feature = "parallel"))]
                {
                    Bvh::build_spatial
                }
            } else {
                Bvh::build_spatial
            };
            let bvh = build(
                &copy,
                config,
                spatial,
                &mut nodes,
                &mut order,
                &mut scratch,
                &mut splits,
            )?;
            (
                bvh.nodes().len(),
                bvh.order().len(),
                bvh.split_refs().len(),
                bvh.depth(),
            )
        };
        drop(scratch);
        nodes.truncate(used);
        order.truncate(slots);
        order.shrink_to_fit();
        splits.truncate(split_count);
        splits.shrink_to_fit();
        let mut built = Self::assemble(
            positions, triangles, nodes, order, depth, *config, parallel, None,
        )?;
        built.splits = splits;
        Ok(built)
    }

    /// Copies the mesh, builds its tree (on the thread pool when `parallel`), packs and
    /// widens.
    fn build_with(
        mesh: &ValidMesh<'_>,
        config: &BuildConfig,
        parallel: bool,
    ) -> Result<Self, BuildError> {
        let positions = mesh.positions().to_vec();
        let triangles = mesh.triangles().to_vec();
        let n = triangles.len();
        let mut nodes = filled(BvhNode::EMPTY, node_capacity(n), parallel);
        let mut order = vec![0u32; n];
        let mut scratch = filled(PrimRef::EMPTY, n, parallel);
        let depth = {
            let copy = ValidMesh::new_unchecked_by_validate(&positions, &triangles);
            #[cfg(feature = "parallel")]
            let bvh = if parallel {
                Bvh::build_parallel(&copy, config, &mut nodes, &mut order, &mut scratch)?
            } else {
                Bvh::build(&copy, config, &mut nodes, &mut order, &mut scratch)?
            };
            #[cfg(not(feature = "parallel"))]
            let bvh = {
                let _ = parallel;
                Bvh::build(&copy, config, &mut nodes, &mut order, &mut scratch)?
            };
            let used = bvh.nodes().len();
            let depth = bvh.depth();
            nodes.truncate(used);
            depth
        };
        drop(scratch);
        Self::assemble(
            positions, triangles, nodes, order, depth, *config, parallel, None,
        )
    }

    /// Packs and widens a built (or decoded) tree and keeps it all, trimmed. A decoded tree's
    /// collapse `roles` (a blob's, checked against the tree) spare the sequential collapse
    /// planning it.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn assemble(
        positions: Vec<[f32; 3]>,
        triangles: Vec<[u32; 3]>,
        mut nodes: Vec<BvhNode>,
        order: Vec<u32>,
        depth: u32,
        config: BuildConfig,
        parallel: bool,
        roles: Option<CollapseRoles<'_>>,
    ) -> Result<Self, BuildError> {
        nodes.shrink_to_fit();
        let n = order.len();
        let mut packed = filled(PackedTriangle::EMPTY, n, parallel);
        // One wide node per inner binary node at most: sized by the tree, not by the triangle
        // count (a quarter to a third of `wide_node_capacity(n)` with small leaves), so
        // loading and building zero far less memory.
        let wide = {
            let mesh = ValidMesh::new_unchecked_by_validate(&positions, &triangles);
            let bvh = Bvh::from_validated(&nodes, &order, depth);
            #[cfg(feature = "parallel")]
            if parallel {
                bvh.pack_triangles_parallel(&mesh, &mut packed)?;
                if Self::EIGHT_WIDE_BY_DEFAULT {
                    WideNodes::Eight(collapse_vec_parallel::<WideNode8, 8>(&bvh)?)
                } else {
                    WideNodes::Full(collapse_vec_parallel::<WideNode, 4>(&bvh)?)
                }
            } else {
                sequential_wide(&bvh, &mesh, &mut packed, roles)?
            }
            #[cfg(not(feature = "parallel"))]
            {
                let _ = parallel;
                sequential_wide(&bvh, &mesh, &mut packed, roles)?
            }
        };
        Ok(Self {
            positions,
            triangles,
            nodes,
            order,
            depth,
            packed,
            wide,
            config,
            splits: Vec::new(),
            winding: None,
        })
    }

    /// This structure with its wide nodes quantized ([`WideBvh`] of [`CompactNode`]): the same answers,
    /// bit for bit, from nodes half the size. Deterministic. Already compact: unchanged.
    ///
    /// # Errors
    /// Never for a structure built or loaded by this crate (see [`WideBvh::quantize`]).
    pub fn with_compact_nodes(mut self) -> Result<Self, BuildError> {
        self.compact_nodes()?;
        Ok(self)
    }

    /// [`MeshBvh::with_compact_nodes`] in place. On error nothing changes.
    ///
    /// # Errors
    /// As [`MeshBvh::with_compact_nodes`].
    pub fn compact_nodes(&mut self) -> Result<(), BuildError> {
        let compact = match &self.wide {
            WideNodes::Compact(_) => return Ok(()),
            WideNodes::Full(nodes) => {
                let mut compact = vec![CompactNode::EMPTY; nodes.len()];
                WideBvh::quantize(&WideBvh::from_validated(nodes, &self.order), &mut compact)?;
                compact
            }
            WideNodes::Eight(_) => {
                let nodes = four_wide_of(&self.bvh())?;
                let mut compact = vec![CompactNode::EMPTY; nodes.len()];
                WideBvh::quantize(&WideBvh::from_validated(&nodes, &self.order), &mut compact)?;
                compact
            }
        };
        self.wide = WideNodes::Compact(compact);
        Ok(())
    }

    /// This structure with its tree collapsed eight-wide ([`WideBvh`] of [`WideNode8`]) for queries to walk
    /// instead of the four-wide (or compact) nodes: the same answers, bit for bit, with about
    /// a third fewer node visits per query, each testing eight boxes. The default where
    /// [`MeshBvh::EIGHT_WIDE_BY_DEFAULT`] is true. Deterministic. Already eight-wide:
    /// unchanged.
    ///
    /// # Errors
    /// Never for a structure built or loaded by this crate (see [`WideBvh::build`]).
    pub fn with_eight_wide_nodes(mut self) -> Result<Self, BuildError> {
        self.eight_wide_nodes()?;
        Ok(self)
    }

    /// [`MeshBvh::with_eight_wide_nodes`] in place. On error nothing changes.
    ///
    /// # Errors
    /// As [`MeshBvh::with_eight_wide_nodes`].
    pub fn eight_wide_nodes(&mut self) -> Result<(), BuildError> {
        if matches!(self.wide, WideNodes::Eight(_)) {
            return Ok(());
        }
        self.wide = WideNodes::Eight(eight_wide_of(&self.bvh())?);
        Ok(())
    }

    /// This structure with its tree collapsed four-wide ([`WideBvh`]) for queries to walk
    /// instead of its eight-wide or compact nodes: the same answers, bit for bit. The default
    /// where [`MeshBvh::EIGHT_WIDE_BY_DEFAULT`] is false; elsewhere, for comparing the two
    /// trees or for the smaller nodes. Deterministic. Already four-wide: unchanged.
    ///
    /// # Errors
    /// Never for a structure built or loaded by this crate (see [`WideBvh::build`]).
    pub fn with_four_wide_nodes(mut self) -> Result<Self, BuildError> {
        self.four_wide_nodes()?;
        Ok(self)
    }

    /// [`MeshBvh::with_four_wide_nodes`] in place. On error nothing changes.
    ///
    /// # Errors
    /// As [`MeshBvh::with_four_wide_nodes`].
    pub fn four_wide_nodes(&mut self) -> Result<(), BuildError> {
        if matches!(self.wide, WideNodes::Full(_)) {
            return Ok(());
        }
        self.wide = WideNodes::Full(four_wide_of(&self.bvh())?);
        Ok(())
    }

    /// The mesh.
    #[must_use]
    pub fn mesh(&self) -> ValidMesh<'_> {
        // Copied from a validated mesh (or decoded from a validated blob) and never changed.
        ValidMesh::new_unchecked_by_validate(&self.positions, &self.triangles)
    }

    /// The binary BVH over [`MeshBvh::mesh`].
    #[must_use]
    pub fn bvh(&self) -> Bvh<'_> {
        Bvh::from_validated(&self.nodes, &self.order, self.depth).with_split_refs(self.split_refs())
    }

    /// The references of triangles the tree holds in more than one leaf (built by
    /// [`MeshBvh::build_spatial`]), sorted by triangle then slot; empty otherwise.
    #[must_use]
    pub fn split_refs(&self) -> SplitRefs<'_> {
        SplitRefs::new(&self.splits)
    }

    /// Number of leaf references: [`MeshBvh::triangle_count`], and more when spatial splits
    /// hold some triangles in several leaves.
    #[must_use]
    pub fn reference_count(&self) -> usize {
        self.order.len()
    }

    /// The same tree four-wide, when queries walk it (by default where
    /// [`MeshBvh::EIGHT_WIDE_BY_DEFAULT`] is false, or after
    /// [`MeshBvh::with_four_wide_nodes`]); `None` while the nodes are compact or eight-wide.
    #[must_use]
    pub fn wide(&self) -> Option<WideBvh<'_>> {
        match &self.wide {
            WideNodes::Full(nodes) => {
                Some(WideBvh::from_validated(nodes, &self.order).with_split_refs(self.split_refs()))
            }
            WideNodes::Compact(_) | WideNodes::Eight(_) => None,
        }
    }

    /// The same tree eight-wide, when queries walk it (by default where
    /// [`MeshBvh::EIGHT_WIDE_BY_DEFAULT`] is true, or after [`MeshBvh::with_eight_wide_nodes`]);
    /// `None` while the nodes are four-wide or compact.
    #[must_use]
    pub fn eight_wide(&self) -> Option<WideBvh<'_, WideNode8>> {
        match &self.wide {
            WideNodes::Eight(nodes) => Some(
                WideBvh::<WideNode8>::from_validated(nodes, &self.order)
                    .with_split_refs(self.split_refs()),
            ),
            WideNodes::Full(_) | WideNodes::Compact(_) => None,
        }
    }

    /// The same tree four-wide with quantized nodes, which queries walk after
    /// [`MeshBvh::with_compact_nodes`]; `None` before.
    #[must_use]
    pub fn compact(&self) -> Option<WideBvh<'_, CompactNode>> {
        match &self.wide {
            WideNodes::Full(_) | WideNodes::Eight(_) => None,
            WideNodes::Compact(nodes) => Some(
                WideBvh::<CompactNode>::from_validated(nodes, &self.order)
                    .with_split_refs(self.split_refs()),
            ),
        }
    }

    /// Bytes of the nodes queries walk (four-wide, compact or eight-wide).
    #[must_use]
    pub fn query_node_bytes(&self) -> usize {
        match &self.wide {
            WideNodes::Full(nodes) => core::mem::size_of_val(nodes.as_slice()),
            WideNodes::Compact(nodes) => core::mem::size_of_val(nodes.as_slice()),
            WideNodes::Eight(nodes) => core::mem::size_of_val(nodes.as_slice()),
        }
    }

    /// The triangles in the tree's leaf order, which queries read.
    #[must_use]
    pub fn packed(&self) -> PackedTriangles<'_> {
        PackedTriangles::new(&self.packed)
    }

    /// The config the tree was built with (for a blob, the one it records).
    #[must_use]
    pub const fn config(&self) -> &BuildConfig {
        &self.config
    }

    /// Number of triangles.
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// The root's padded box ([`Aabb::EMPTY`] for no triangles).
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        self.bvh().bounds()
    }
}

impl Traverse for MeshBvh {
    /// Walks the wide tree (four-wide, compact or eight-wide).
    #[inline(always)]
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        match &self.wide {
            WideNodes::Full(nodes) => WideBvh::from_validated(nodes, &self.order).traverse(visitor),
            WideNodes::Compact(nodes) => {
                WideBvh::<CompactNode>::from_validated(nodes, &self.order).traverse(visitor);
            }
            WideNodes::Eight(nodes) => {
                WideBvh::<WideNode8>::from_validated(nodes, &self.order).traverse(visitor);
            }
        }
    }

    #[inline(always)]
    fn walks_packets(&self) -> bool {
        true
    }

    #[inline(always)]
    fn split_refs(&self) -> SplitRefs<'_> {
        SplitRefs::new(&self.splits)
    }

    /// The root's padded box ([`MeshBvh::bounds`]) and the triangle count; `None` for no
    /// triangles.
    #[inline(always)]
    fn batch_hint(&self) -> Option<BatchHint> {
        let bounds = self.bounds();
        (!bounds.is_empty()).then_some(BatchHint {
            bounds,
            triangles: self.triangle_count(),
        })
    }
}

impl crate::query::MeshQuery for MeshBvh {}

impl LeafTriangles for MeshBvh {
    #[inline(always)]
    fn corners(&self, slot: usize, tri: u32) -> Option<Triangle> {
        self.packed.as_slice().corners(slot, tri)
    }

    #[inline(always)]
    fn run(&self, first: usize, count: usize) -> Option<&[PackedTriangle]> {
        self.packed.as_slice().run(first, count)
    }
}

/// `bvh` collapsed four-wide.
fn four_wide_of(bvh: &Bvh<'_>) -> Result<Vec<WideNode>, BuildError> {
    collapse_vec::<WideNode, 4>(bvh)
}

/// `len` copies of `value`, written by the pool's threads when `parallel` (feature `parallel`):
/// the first touch of a large new buffer's pages is otherwise a serial part of a parallel build.
fn filled<T: Clone + Send + Sync>(value: T, len: usize, parallel: bool) -> Vec<T> {
    #[cfg(feature = "parallel")]
    if parallel {
        use rayon::iter::ParallelIterator;
        return rayon::iter::repeat_n(value, len).collect();
    }
    let _ = parallel;
    vec![value; len]
}

/// Packs `mesh` for `bvh` into `packed` and collapses `bvh` into the default wide nodes, on
/// this thread: eight-wide as its collapse `roles` say when given, else planned here.
fn sequential_wide(
    bvh: &Bvh<'_>,
    mesh: &ValidMesh<'_>,
    packed: &mut [PackedTriangle],
    roles: Option<CollapseRoles<'_>>,
) -> Result<WideNodes, BuildError> {
    bvh.pack_triangles(mesh, packed)?;
    Ok(if MeshBvh::EIGHT_WIDE_BY_DEFAULT {
        WideNodes::Eight(match roles {
            // Checked as the collapse walks them.
            Some(roles) => {
                collapse_planned_vec(&CollapsePlan::<8>::from_roles_unchecked(bvh, roles))?
            }
            None => eight_wide_of(bvh)?,
        })
    } else {
        WideNodes::Full(four_wide_of(bvh)?)
    })
}

/// `bvh` collapsed eight-wide.
fn eight_wide_of(bvh: &Bvh<'_>) -> Result<Vec<WideNode8>, BuildError> {
    collapse_vec::<WideNode8, 8>(bvh)
}
