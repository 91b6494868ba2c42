use glam::Vec3;

use super::WideNode;
use super::collapse::collapse;
use crate::bvh::closest::closest_point;
use crate::bvh::raycast::{raycast_any_with, raycast_with};
use crate::bvh::{Bvh, LeafTriangles, RayOptions};
use crate::error::{BufferKind, BuildError, StructureError};
use crate::math::{Aabb, ClosestPoint, Ray, RayHit};

/// A four-wide BVH: the same leaves as the [`Bvh`] it was collapsed from, under nodes of up to
/// four children whose boxes are tested together in SIMD lanes. Fewer, fuller nodes mean
/// fewer dependent steps per query: on the bunny, rays ran 2–27 % faster than on the binary
/// tree across our runs, closest points about as fast (both are bound by cache misses).
///
/// Made by [`Bvh::widen`] into a caller buffer (sized by [`Bvh::wide_node_count`]); it
/// borrows the binary tree's triangle order, so leaves read the same [`PackedTriangles`] slots.
/// Every query returns exactly what the binary tree's returns, bit for bit, on every target:
/// box tests only decide what to visit, conservatively, and each answer is the minimum under a
/// total order.
///
/// [`PackedTriangles`]: crate::bvh::PackedTriangles
#[derive(Clone, Copy, Debug)]
pub struct WideBvh<'a> {
    pub(super) nodes: &'a [WideNode],
    pub(super) order: &'a [u32],
}

impl<'a> Bvh<'a> {
    /// Number of wide nodes [`Bvh::widen`] writes for this tree (0 when empty; at most one
    /// per inner node, and 1 for a lone leaf).
    #[must_use]
    pub fn wide_node_count(&self) -> usize {
        collapse(self, |_, _| {}).unwrap_or(0)
    }

    /// At least as many wide nodes as [`Bvh::widen`] writes for a binary tree of
    /// `binary_nodes` nodes (one per inner node, or 1 for a lone leaf): size a buffer with it
    /// to widen without counting first.
    #[must_use]
    pub const fn wide_node_bound(binary_nodes: usize) -> usize {
        if binary_nodes == 0 {
            0
        } else {
            binary_nodes / 2 + 1
        }
    }

    /// Collapses this tree into a four-wide one in `out` (at least
    /// [`Bvh::wide_node_count`] nodes). Deterministic; takes a few percent of a build's time,
    /// less when `out` holds [`Bvh::wide_node_bound`] nodes (no counting pass).
    ///
    /// # Errors
    /// [`BuildError::BufferTooSmall`] when `out` is too small; nothing is written then.
    pub fn widen<'w>(&self, out: &'w mut [WideNode]) -> Result<WideBvh<'w>, BuildError>
    where
        'a: 'w,
    {
        if out.len() < Self::wide_node_bound(self.nodes.len()) {
            let needed = collapse(self, |_, _| {})?;
            if out.len() < needed {
                return Err(BuildError::BufferTooSmall {
                    buffer: BufferKind::WideNodes,
                    needed,
                    got: out.len(),
                });
            }
        }
        let needed = collapse(self, |index, node| {
            if let Some(slot) = out.get_mut(index) {
                *slot = node;
            }
        })?;
        if needed > out.len() {
            // Unreachable for a valid tree (the bound holds), but never hand out a short view.
            return Err(BuildError::BufferTooSmall {
                buffer: BufferKind::WideNodes,
                needed,
                got: out.len(),
            });
        }
        let nodes: &'w [WideNode] = out;
        Ok(WideBvh {
            nodes: nodes.get(..needed).unwrap_or_default(),
            order: self.order,
        })
    }
}

impl<'a> Bvh<'a> {
    /// A view over wide nodes written earlier by [`Bvh::widen`] for this very tree (and moved
    /// since, into a struct that owns them, say), after checking that they are exactly the
    /// nodes widening gives, bit for bit. The check redoes the collapse, which is cheap next to
    /// a build, so nothing else can reach a query.
    ///
    /// # Errors
    /// [`StructureError::WideNodeMismatch`] naming the first node that differs.
    pub fn wide_view<'w>(&self, nodes: &'w [WideNode]) -> Result<WideBvh<'w>, StructureError>
    where
        'a: 'w,
    {
        let mut first_difference: Option<usize> = None;
        let count = collapse(self, |index, node| {
            let same = nodes.get(index).is_some_and(|n| n.same_bits(&node));
            if !same && first_difference.is_none_or(|d| index < d) {
                first_difference = Some(index);
            }
        })
        .map_err(|_| StructureError::WideNodeMismatch { node: 0 })?;
        let mismatch = first_difference.or((count != nodes.len()).then_some(count));
        if let Some(node) = mismatch {
            return Err(StructureError::WideNodeMismatch {
                node: u32::try_from(node).unwrap_or(u32::MAX),
            });
        }
        Ok(WideBvh {
            nodes,
            order: self.order,
        })
    }
}

impl<'a> WideBvh<'a> {
    /// The nodes, root first.
    #[must_use]
    pub const fn nodes(&self) -> &'a [WideNode] {
        self.nodes
    }

    /// Mesh triangle indices in leaf order (the binary tree's).
    #[must_use]
    pub const fn order(&self) -> &'a [u32] {
        self.order
    }

    /// True when the tree holds no triangles (every query returns nothing).
    #[must_use]
    pub const fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The union of the root's child boxes, or [`Aabb::EMPTY`]: it holds every triangle and
    /// lies within the binary root's box ([`Bvh::bounds`]), which is padded once more.
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, |root| {
            (0..root.lanes()).fold(Aabb::EMPTY, |b, lane| b.union(root.lane_box(lane)))
        })
    }

    /// [`Bvh::raycast`] on the wide tree: the same hit, bit for bit.
    #[must_use]
    pub fn raycast<S: LeafTriangles + ?Sized>(&self, source: &S, ray: &Ray) -> Option<RayHit> {
        raycast_with(self, source, ray, &RayOptions::default())
    }

    /// [`Bvh::raycast_with`] on the wide tree: the same hit, bit for bit.
    #[must_use]
    pub fn raycast_with<S: LeafTriangles + ?Sized>(
        &self,
        source: &S,
        ray: &Ray,
        options: &RayOptions,
    ) -> Option<RayHit> {
        raycast_with(self, source, ray, options)
    }

    /// [`Bvh::raycast_any`] on the wide tree: the same answer.
    #[must_use]
    pub fn raycast_any<S: LeafTriangles + ?Sized>(&self, source: &S, ray: &Ray) -> bool {
        raycast_any_with(self, source, ray, &RayOptions::default())
    }

    /// [`Bvh::raycast_any_with`] on the wide tree: the same answer.
    #[must_use]
    pub fn raycast_any_with<S: LeafTriangles + ?Sized>(
        &self,
        source: &S,
        ray: &Ray,
        options: &RayOptions,
    ) -> bool {
        raycast_any_with(self, source, ray, options)
    }

    /// [`Bvh::closest_point`] on the wide tree: the same point, bit for bit.
    #[must_use]
    pub fn closest_point<S: LeafTriangles + ?Sized>(
        &self,
        source: &S,
        point: Vec3,
        max_distance: f32,
    ) -> Option<ClosestPoint> {
        closest_point(self, source, point, max_distance)
    }
}
