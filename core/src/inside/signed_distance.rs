//! Signed distance: the closest point, with the winding number's sign.

use glam::Vec3;

use super::{WindingAccuracy, WindingNodes, WindingTree};
use crate::bvh::TreeArrays;
use crate::math::ClosestPoint;
use crate::query::{LeafTriangles, MeshQuery, Traverse};

/// A signed distance to a mesh ([`WindingTree::signed_distance`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SignedDistance {
    /// The distance to the closest surface point, negative inside (where
    /// [`WindingTree::contains`] holds), `-0.0` or `+0.0` on the surface. Its magnitude is
    /// `closest.distance_from(point)`, bit for bit.
    pub distance: f32,
    /// The closest surface point, exactly as [`MeshQuery::closest_point`] finds it.
    pub closest: ClosestPoint,
    /// The winding number that gave the sign.
    pub winding_number: f32,
}

impl SignedDistance {
    /// The signed distance from `point` to `closest`, its sign from `winding_number`.
    pub(super) fn new(point: Vec3, closest: ClosestPoint, winding_number: f32) -> Self {
        let magnitude = closest.distance_from(point);
        let distance = if winding_number.abs() >= 0.5 {
            -magnitude
        } else {
            magnitude
        };
        Self {
            distance,
            closest,
            winding_number,
        }
    }
}

impl<T: TreeArrays, S: LeafTriangles, E: WindingNodes> WindingTree<'_, T, S, E> {
    /// The distance from `point` to the mesh, negative inside: the closest point within
    /// `max_distance` ([`MeshQuery::closest_point`] on this tree, same point and bits), signed
    /// by the generalized winding number (inside when `|w| ≥ 1/2`), so the sign holds on open,
    /// non-manifold and self-intersecting meshes. `None` when no surface point lies within
    /// `max_distance`, the mesh is empty or `point` is not finite.
    #[must_use]
    pub fn signed_distance(
        &self,
        point: Vec3,
        max_distance: f32,
        accuracy: WindingAccuracy,
    ) -> Option<SignedDistance> {
        let closest = self
            .tree()
            .with(self.triangles())
            .closest_point(point, max_distance)?;
        Some(SignedDistance::new(
            point,
            closest,
            self.winding_number(point, accuracy),
        ))
    }
}
