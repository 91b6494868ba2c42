//! [`WindingTree`]: a BVH with its expansions, answering winding numbers and containment.

use glam::Vec3;

use super::WindingAccuracy;
use super::expansion::{
    Moments, WindingNode, leaf_moments, leaf_triangles, merged_moments, unit_scale,
};
use crate::bvh::{Bvh, MAX_DEPTH};
use crate::error::{BufferKind, BuildError};
use crate::math::dot;
use crate::mesh::ValidMesh;

/// A BVH, its mesh and one [`WindingNode`] per tree node: the fast winding number of Barill et
/// al. (2018) over memory the caller owns.
///
/// The generalized winding number of a point is the signed solid angle the mesh subtends there,
/// over `4π`: 1 inside a closed mesh whose triangles face outwards, 0 outside, −1 inside one
/// that faces inwards, and a smooth fraction near holes, so that it tells inside from outside
/// also on open, non-manifold and self-intersecting meshes. Far nodes are summed by their
/// expansions ([`WindingAccuracy`]), near triangles exactly; the order of the sum is fixed, so
/// every target gives the same bits.
#[derive(Clone, Copy, Debug)]
pub struct WindingTree<'a> {
    bvh: Bvh<'a>,
    mesh: ValidMesh<'a>,
    nodes: &'a [WindingNode],
    /// The power of two the expansions' coordinates are multiplied by (see [`WindingNode`]).
    scale: f32,
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
        let scale = unit_scale(bvh.bounds());
        // Post order on fixed stacks: a node's full moments exist only until its parent
        // merges them, so at most one per level waits (the tree is at most MAX_DEPTH deep).
        let tree = bvh.nodes();
        let mut work = [(0u32, false); 2 * MAX_DEPTH as usize + 2];
        let mut done = [Moments::default(); MAX_DEPTH as usize + 2];
        let (mut wp, mut dp) = (usize::from(count > 0), 0usize);
        while wp > 0 {
            wp -= 1;
            let (index, merge) = work.get(wp).copied().unwrap_or_default();
            let Some(node) = tree.get(index as usize) else {
                continue;
            };
            let moments = if node.is_leaf() {
                leaf_moments(leaf_triangles(&bvh, mesh, node, scale))
            } else if !merge {
                // Again after both children, which run left first.
                for next in [
                    (index, true),
                    (node.first.wrapping_add(1), false),
                    (node.first, false),
                ] {
                    if let Some(slot) = work.get_mut(wp) {
                        *slot = next;
                        wp += 1;
                    }
                }
                continue;
            } else {
                dp = dp.saturating_sub(2);
                let child = |k: usize| done.get(k).copied().unwrap_or_default();
                let mut merged = merged_moments(&child(dp), &child(dp + 1));
                // The children's balls bound the node loosely, more so each level up; the
                // corners themselves give the radius the far test wants small.
                merged.radius = merged.radius.min(subtree_radius(
                    &bvh,
                    mesh,
                    index as usize,
                    scale,
                    merged.centre,
                ));
                merged
            };
            if let Some(slot) = nodes.get_mut(index as usize) {
                *slot = WindingNode::of(&moments, moments.radius);
            }
            if let Some(slot) = done.get_mut(dp) {
                *slot = moments;
                dp += 1;
            }
        }
        Ok(Self {
            bvh,
            mesh,
            nodes,
            scale,
        })
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
        let scale = unit_scale(bvh.bounds());
        Ok(Self {
            bvh,
            mesh,
            nodes,
            scale,
        })
    }

    /// The expansions, one per tree node, root first.
    #[must_use]
    pub const fn nodes(&self) -> &'a [WindingNode] {
        self.nodes
    }

    /// The power of two the mesh's coordinates are multiplied by in the expansions: the one
    /// nearest above `1 / side` for the largest side of the tree's box (1 for an empty mesh or
    /// one that is a single point). Winding numbers do not change with scale; this one keeps
    /// the expansions' powers of length within `f32`.
    #[must_use]
    pub const fn scale(&self) -> f32 {
        self.scale
    }

    /// The tree.
    #[must_use]
    pub const fn bvh(&self) -> Bvh<'a> {
        self.bvh
    }

    /// The mesh.
    #[must_use]
    pub const fn mesh(&self) -> ValidMesh<'a> {
        self.mesh
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

/// The largest distance from `centre` to a corner of a triangle node `index` counts (scaled by
/// `scale`): the triangles of a subtree fill the order slots from its leftmost leaf's first to
/// its rightmost leaf's last.
fn subtree_radius(
    bvh: &Bvh<'_>,
    mesh: ValidMesh<'_>,
    index: usize,
    scale: f32,
    centre: Vec3,
) -> f32 {
    let nodes = bvh.nodes();
    let leaf_at = |mut i: usize, right: bool| {
        for _ in 0..=MAX_DEPTH {
            match nodes.get(i) {
                Some(n) if n.is_leaf() => return Some(*n),
                Some(n) => i = n.first as usize + usize::from(right),
                None => return None,
            }
        }
        None
    };
    let (Some(low), Some(high)) = (leaf_at(index, false), leaf_at(index, true)) else {
        return f32::INFINITY;
    };
    let span = crate::bvh::BvhNode {
        first: low.first,
        count: (high.first + high.count).saturating_sub(low.first),
        ..low
    };
    // The largest square, then one root: the root is monotonic and correctly rounded, so
    // this is the largest root, bit for bit.
    let mut farthest = 0.0f32;
    for t in leaf_triangles(bvh, mesh, &span, scale) {
        for corner in [t.a, t.b, t.c] {
            let d = corner - centre;
            farthest = farthest.max(dot(d, d));
        }
    }
    libm::sqrtf(farthest)
}
