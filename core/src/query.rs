//! The queries every acceleration structure answers, as one trait, so code (and the test suite)
//! can run over any structure.

use glam::Vec3;

use crate::bvh::{Bvh, LeafTriangles, RayOptions, WideBvh};
use crate::math::{ClosestPoint, Ray, RayHit};

/// Ray and point queries over a mesh through an acceleration structure.
///
/// `source` is where leaf triangles are read: the [`ValidMesh`](crate::mesh::ValidMesh) the
/// structure was built from, or a packed copy. Every implementation returns exactly what a
/// linear scan over all triangles with the same primitive test would return, bits included,
/// under the crate's tie rule (lower triangle index wins on equal `t` or distance). Degenerate
/// triangles are never returned.
pub trait MeshQuery {
    /// The closest hit of `ray` (see [`Bvh::raycast`] for the conventions).
    fn raycast_with<S: LeafTriangles + ?Sized>(
        &self,
        source: &S,
        ray: &Ray,
        options: &RayOptions,
    ) -> Option<RayHit>;

    /// Whether `ray` hits anything; true exactly when [`MeshQuery::raycast_with`] is `Some`.
    fn raycast_any_with<S: LeafTriangles + ?Sized>(
        &self,
        source: &S,
        ray: &Ray,
        options: &RayOptions,
    ) -> bool;

    /// The closest point within `max_distance` (see [`Bvh::closest_point`]).
    fn closest_point<S: LeafTriangles + ?Sized>(
        &self,
        source: &S,
        point: Vec3,
        max_distance: f32,
    ) -> Option<ClosestPoint>;
}

impl MeshQuery for Bvh<'_> {
    fn raycast_with<S: LeafTriangles + ?Sized>(
        &self,
        source: &S,
        ray: &Ray,
        options: &RayOptions,
    ) -> Option<RayHit> {
        Bvh::raycast_with(self, source, ray, options)
    }

    fn raycast_any_with<S: LeafTriangles + ?Sized>(
        &self,
        source: &S,
        ray: &Ray,
        options: &RayOptions,
    ) -> bool {
        Bvh::raycast_any_with(self, source, ray, options)
    }

    fn closest_point<S: LeafTriangles + ?Sized>(
        &self,
        source: &S,
        point: Vec3,
        max_distance: f32,
    ) -> Option<ClosestPoint> {
        Bvh::closest_point(self, source, point, max_distance)
    }
}

impl MeshQuery for WideBvh<'_> {
    fn raycast_with<S: LeafTriangles + ?Sized>(
        &self,
        source: &S,
        ray: &Ray,
        options: &RayOptions,
    ) -> Option<RayHit> {
        WideBvh::raycast_with(self, source, ray, options)
    }

    fn raycast_any_with<S: LeafTriangles + ?Sized>(
        &self,
        source: &S,
        ray: &Ray,
        options: &RayOptions,
    ) -> bool {
        WideBvh::raycast_any_with(self, source, ray, options)
    }

    fn closest_point<S: LeafTriangles + ?Sized>(
        &self,
        source: &S,
        point: Vec3,
        max_distance: f32,
    ) -> Option<ClosestPoint> {
        WideBvh::closest_point(self, source, point, max_distance)
    }
}
