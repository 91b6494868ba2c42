//! [`MeshIndex`]'s ray and point queries, each answered by the structure it holds.
//!
//! `MeshIndex` is a [`MeshQuery`] like every structure paired with its triangles, and a
//! generic caller gets that implementation: each node visit and each leaf read goes through
//! the enum. The methods here have the same names, signatures and answers; they pick the
//! structure once per call and run its own query, so a walk reads its leaves from the
//! structure directly. Method resolution prefers them wherever the type is `MeshIndex`.

use super::MeshIndex;
use crate::error::BatchError;
use crate::math::{ClosestPoint, Ray, RayHit, Vec3};
use crate::query::{MeshQuery, RayHits, RayOptions};

/// Runs `$query` on the structure `$index` holds, bound to `$s`.
macro_rules! on_structure {
    ($index:expr, $s:ident => $query:expr) => {
        match $index {
            MeshIndex::Bvh($s) => $query,
            MeshIndex::KdTree($s) => $query,
            MeshIndex::Octree($s) => $query,
            MeshIndex::Grid($s) => $query,
        }
    };
}

impl MeshIndex {
    /// [`MeshQuery::raycast`], run by the structure it holds (the same answer).
    #[must_use]
    #[inline]
    pub fn raycast(&self, ray: &Ray) -> Option<RayHit> {
        on_structure!(self, s => s.raycast(ray))
    }

    /// [`MeshQuery::raycast_with`], run by the structure it holds (the same answer).
    #[must_use]
    #[inline]
    pub fn raycast_with(&self, ray: &Ray, options: &RayOptions) -> Option<RayHit> {
        on_structure!(self, s => s.raycast_with(ray, options))
    }

    /// [`MeshQuery::raycast_any`], run by the structure it holds (the same answer).
    #[must_use]
    #[inline]
    pub fn raycast_any(&self, ray: &Ray) -> bool {
        on_structure!(self, s => s.raycast_any(ray))
    }

    /// [`MeshQuery::raycast_any_with`], run by the structure it holds (the same answer).
    #[must_use]
    #[inline]
    pub fn raycast_any_with(&self, ray: &Ray, options: &RayOptions) -> bool {
        on_structure!(self, s => s.raycast_any_with(ray, options))
    }

    /// [`MeshQuery::raycast_all`], run by the structure it holds (the same hits in `out`).
    pub fn raycast_all(&self, ray: &Ray, options: &RayOptions, out: &mut [RayHit]) -> RayHits {
        on_structure!(self, s => s.raycast_all(ray, options, out))
    }

    /// [`MeshQuery::closest_point`], run by the structure it holds (the same answer).
    #[must_use]
    pub fn closest_point(&self, point: Vec3, max_distance: f32) -> Option<ClosestPoint> {
        on_structure!(self, s => s.closest_point(point, max_distance))
    }

    /// [`MeshQuery::closest_points`], run by the structure it holds (the same answers).
    ///
    /// # Errors
    /// As [`MeshQuery::closest_points`].
    pub fn closest_points(
        &self,
        points: &[Vec3],
        max_distance: f32,
        keys: &mut [u64],
        out: &mut [Option<ClosestPoint>],
    ) -> Result<(), BatchError> {
        on_structure!(self, s => s.closest_points(points, max_distance, keys, out))
    }

    /// [`MeshQuery::raycast_batch`], run by the structure it holds (the same answers).
    ///
    /// # Errors
    /// As [`MeshQuery::raycast_batch`].
    pub fn raycast_batch(
        &self,
        rays: &[Ray],
        options: &RayOptions,
        keys: &mut [u64],
        out: &mut [Option<RayHit>],
    ) -> Result<(), BatchError> {
        on_structure!(self, s => s.raycast_batch(rays, options, keys, out))
    }

    /// [`MeshQuery::raycast_any_batch`], run by the structure it holds (the same answers).
    ///
    /// # Errors
    /// As [`MeshQuery::raycast_any_batch`].
    pub fn raycast_any_batch(
        &self,
        rays: &[Ray],
        options: &RayOptions,
        keys: &mut [u64],
        out: &mut [bool],
    ) -> Result<(), BatchError> {
        on_structure!(self, s => s.raycast_any_batch(rays, options, keys, out))
    }
}
