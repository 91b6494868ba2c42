//! [`WindingTree`]: a BVH with its expansions, answering winding numbers and containment.

use core::marker::PhantomData;

use glam::Vec3;

use super::expansion::{WindingNode, unit_scale};
use super::expansion_build::for_each_expansion;
use super::{WindingAccuracy, WindingNodes};
use crate::bvh::{Bvh, TreeArrays};
use crate::error::{BufferKind, BuildError};
use crate::mesh::ValidMesh;
use crate::query::LeafTriangles;

/// A BVH, its triangles and one [`WindingNode`] per tree node: the fast winding number of
/// Barill et al. (2018) over memory the caller owns.
///
/// The generalized winding number of a point is the signed solid angle the mesh subtends there,
/// over `4π`: 1 inside a closed mesh whose triangles face outwards, 0 outside, −1 inside one
/// that faces inwards, and a smooth fraction near holes, so that it tells inside from outside
/// also on open, non-manifold and self-intersecting meshes. Far nodes are summed by their
/// expansions ([`WindingAccuracy`]), near triangles exactly; the order of the sum is fixed, so
/// every target gives the same bits.
///
/// The tree, triangles and expansions may live anywhere: `T` is the tree ([`Bvh`] in slices by
/// default, or a blob's tree read in place), `S` its triangles (the mesh, or a blob's), `E` the
/// expansions (a slice, or a blob's records). Made by [`WindingTree::build`],
/// [`WindingTree::from_parts`] or `BlobView::winding_tree` (feature `blob-winding`);
/// every kind answers with the same bits.
#[derive(Clone, Copy, Debug)]
pub struct WindingTree<'a, T = Bvh<'a>, S = ValidMesh<'a>, E = &'a [WindingNode]> {
    tree: T,
    triangles: S,
    nodes: E,
    /// The power of two the expansions' coordinates are multiplied by (see [`WindingNode`]).
    scale: f32,
    life: PhantomData<&'a ()>,
}

impl<'a> WindingTree<'a> {
    /// Works out the expansion of every node of `bvh` (built over `mesh`, with or without
    /// spatial splits) into `nodes`, one per tree node, bottom up, on a few KiB of stack; each
    /// node's radius is measured over its triangles' corners: `O(triangles × depth)`.
    ///
    /// # Errors
    /// [`BuildError::BufferTooSmall`] (buffer [`BufferKind::WindingNodes`]) when `nodes` holds
    /// fewer than `bvh.nodes().len()` entries; nothing is written then.
    pub fn build(
        bvh: Bvh<'a>,
        mesh: ValidMesh<'a>,
        nodes: &'a mut [WindingNode],
    ) -> Result<Self, BuildError> {
        let count = bvh.nodes().len();
        let got = nodes.len();
        let nodes = nodes.get_mut(..count).ok_or(BuildError::BufferTooSmall {
            buffer: BufferKind::WindingNodes,
            needed: count,
            got,
        })?;
        let scale = unit_scale(&bvh);
        for_each_expansion(&bvh, &mesh, scale, |index, node| {
            if let Some(slot) = nodes.get_mut(index) {
                *slot = node;
            }
            true
        });
        let nodes: &'a [WindingNode] = nodes;
        Ok(Self::over(bvh, mesh, nodes))
    }

    /// A view over expansions [`WindingTree::build`] wrote earlier for the same `bvh` and
    /// `mesh` (kept, moved or stored since). Expansions that belong to another tree give wrong
    /// numbers, never a panic or an endless query.
    ///
    /// # Errors
    /// [`BuildError::BufferTooSmall`] when `nodes` holds fewer entries than the tree has nodes.
    pub fn from_parts(
        bvh: Bvh<'a>,
        mesh: ValidMesh<'a>,
        nodes: &'a [WindingNode],
    ) -> Result<Self, BuildError> {
        let count = bvh.nodes().len();
        let nodes = nodes.get(..count).ok_or(BuildError::BufferTooSmall {
            buffer: BufferKind::WindingNodes,
            needed: count,
            got: nodes.len(),
        })?;
        Ok(Self::over(bvh, mesh, nodes))
    }

    /// The expansions, one per tree node, root first.
    #[must_use]
    pub const fn nodes(&self) -> &'a [WindingNode] {
        self.nodes
    }

    /// The tree.
    #[must_use]
    pub const fn bvh(&self) -> Bvh<'a> {
        self.tree
    }

    /// The mesh.
    #[must_use]
    pub const fn mesh(&self) -> ValidMesh<'a> {
        self.triangles
    }
}

impl<'a, T: TreeArrays, S: LeafTriangles, E: WindingNodes> WindingTree<'a, T, S, E> {
    /// The tree, triangles and expansions as given, with the scale worked out from the tree's
    /// root box (the one [`WindingTree::build`] uses).
    pub(crate) fn over(tree: T, triangles: S, nodes: E) -> Self {
        let scale = unit_scale(&tree);
        Self {
            tree,
            triangles,
            nodes,
            scale,
            life: PhantomData,
        }
    }

    /// Whether `nodes` are exactly the expansions [`WindingTree::build`] works out for `tree`
    /// and `triangles`, bit for bit (how a blob's stored expansions are checked at load): one
    /// bottom-up pass, `O(triangles × depth)`, no allocation.
    #[cfg(feature = "blob")]
    pub(crate) fn expansions_match(tree: &T, triangles: &S, nodes: &E) -> bool {
        let bits = |n: &WindingNode| {
            let [c0, c1, c2] = n.centre;
            let [n0, n1, n2] = n.normal;
            let head = [c0, c1, c2, n.radius, n0, n1, n2, n.area];
            head.into_iter()
                .chain(n.first)
                .chain(n.second)
                .map(f32::to_bits)
        };
        nodes.count() == tree.node_count()
            && for_each_expansion(tree, triangles, unit_scale(tree), |index, built| {
                nodes
                    .expansion(index)
                    .is_some_and(|stored| bits(&stored).eq(bits(&built)))
            })
    }

    /// The expansions, wherever they are stored.
    #[must_use]
    pub const fn expansions(&self) -> &E {
        &self.nodes
    }

    /// The tree, wherever it is stored.
    #[must_use]
    pub const fn tree(&self) -> &T {
        &self.tree
    }

    /// The triangles, wherever they are stored.
    #[must_use]
    pub const fn triangles(&self) -> &S {
        &self.triangles
    }

    /// The power of two the mesh's coordinates are multiplied by in the expansions: the one
    /// nearest above `1 / side` for the largest side of the tree's box (1 for an empty mesh or
    /// one that is a single point). Winding numbers do not change with scale; this one keeps
    /// the expansions' powers of length within `f32`.
    #[must_use]
    pub const fn scale(&self) -> f32 {
        self.scale
    }

    /// The generalized winding number of the mesh at `point` (see the type): a node whose
    /// centre is farther from `point` than `accuracy`'s ratio times its radius counts by its
    /// expansion, every other triangle by its exact solid angle
    /// ([`solid_angle_triangle`](crate::geom::solid_angle_triangle)). On the surface itself the
    /// number lies between the two sides' values. 0 for an empty mesh; NaN for a point with a
    /// NaN or infinite coordinate.
    #[must_use]
    pub fn winding_number(&self, point: Vec3, accuracy: WindingAccuracy) -> f32 {
        let [[w, ..]] = self.winding_lanes(&[[point, Vec3::NAN, Vec3::NAN, Vec3::NAN]], accuracy);
        w
    }

    /// Whether `point` is inside: `|winding number| ≥ 1/2` (so a mesh facing inwards holds its
    /// inside too). False for a point with a NaN or infinite coordinate.
    #[must_use]
    pub fn contains(&self, point: Vec3, accuracy: WindingAccuracy) -> bool {
        self.winding_number(point, accuracy).abs() >= 0.5
    }
}
