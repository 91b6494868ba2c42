//! [`MeshQuery`] for [`MeshIndex`]: every query picks the structure once per call and runs
//! that structure's own query, so node visits and leaf reads go straight to it. The answers
//! are the trait's, bit for bit (each structure answers exactly as brute force does).

use core::ops::ControlFlow;

use super::MeshIndex;
use crate::error::{BatchError, SweepError};
use crate::math::{Aabb, ClosestPoint, Obb, Ray, RayHit, Triangle, Vec3};
use crate::query::{MeshQuery, OverlapCount, RayHits, RayOptions, ShapeCast, SweepHit, SweepShape};

/// Runs `$query` with `$s` bound to the structure `$index` holds.
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

impl MeshQuery for MeshIndex {
    #[inline]
    fn raycast(&self, ray: &Ray) -> Option<RayHit> {
        on_structure!(self, s => s.raycast(ray))
    }

    #[inline]
    fn raycast_with(&self, ray: &Ray, options: &RayOptions) -> Option<RayHit> {
        on_structure!(self, s => s.raycast_with(ray, options))
    }

    #[inline]
    fn raycast_any(&self, ray: &Ray) -> bool {
        on_structure!(self, s => s.raycast_any(ray))
    }

    #[inline]
    fn raycast_any_with(&self, ray: &Ray, options: &RayOptions) -> bool {
        on_structure!(self, s => s.raycast_any_with(ray, options))
    }

    fn raycast_all(&self, ray: &Ray, options: &RayOptions, out: &mut [RayHit]) -> RayHits {
        on_structure!(self, s => s.raycast_all(ray, options, out))
    }

    #[inline]
    fn closest_point(&self, point: Vec3, max_distance: f32) -> Option<ClosestPoint> {
        on_structure!(self, s => s.closest_point(point, max_distance))
    }

    fn sweep(&self, shape: &SweepShape, motion: Vec3) -> Result<Option<SweepHit>, SweepError> {
        on_structure!(self, s => s.sweep(shape, motion))
    }

    fn closest_points(
        &self,
        points: &[Vec3],
        max_distance: f32,
        keys: &mut [u64],
        out: &mut [Option<ClosestPoint>],
    ) -> Result<(), BatchError> {
        on_structure!(self, s => s.closest_points(points, max_distance, keys, out))
    }

    fn raycast_batch(
        &self,
        rays: &[Ray],
        options: &RayOptions,
        keys: &mut [u64],
        out: &mut [Option<RayHit>],
    ) -> Result<(), BatchError> {
        on_structure!(self, s => s.raycast_batch(rays, options, keys, out))
    }

    fn raycast_any_batch(
        &self,
        rays: &[Ray],
        options: &RayOptions,
        keys: &mut [u64],
        out: &mut [bool],
    ) -> Result<(), BatchError> {
        on_structure!(self, s => s.raycast_any_batch(rays, options, keys, out))
    }

    fn overlap_aabb<F: FnMut(u32) -> ControlFlow<()>>(&self, aabb: &Aabb, report: F) {
        on_structure!(self, s => s.overlap_aabb(aabb, report));
    }

    fn overlap_sphere<F: FnMut(u32) -> ControlFlow<()>>(
        &self,
        center: Vec3,
        radius: f32,
        report: F,
    ) {
        on_structure!(self, s => s.overlap_sphere(center, radius, report));
    }

    fn overlap_aabb_into(&self, aabb: &Aabb, out: &mut [u32]) -> OverlapCount {
        on_structure!(self, s => s.overlap_aabb_into(aabb, out))
    }

    fn overlap_sphere_into(&self, center: Vec3, radius: f32, out: &mut [u32]) -> OverlapCount {
        on_structure!(self, s => s.overlap_sphere_into(center, radius, out))
    }

    fn overlap_triangle<F: FnMut(u32) -> ControlFlow<()>>(&self, query: &Triangle, report: F) {
        on_structure!(self, s => s.overlap_triangle(query, report));
    }

    fn overlap_obb<F: FnMut(u32) -> ControlFlow<()>>(&self, obb: &Obb, report: F) {
        on_structure!(self, s => s.overlap_obb(obb, report));
    }

    fn overlap_triangle_into(&self, query: &Triangle, out: &mut [u32]) -> OverlapCount {
        on_structure!(self, s => s.overlap_triangle_into(query, out))
    }

    fn overlap_obb_into(&self, obb: &Obb, out: &mut [u32]) -> OverlapCount {
        on_structure!(self, s => s.overlap_obb_into(obb, out))
    }

    fn shapecast<C: ShapeCast + ?Sized>(&self, cast: &mut C) {
        on_structure!(self, s => s.shapecast(cast));
    }

    fn shapecast_once<C: ShapeCast + ?Sized>(&self, cast: &mut C, seen: &mut [u64]) {
        on_structure!(self, s => s.shapecast_once(cast, seen));
    }
}
