//! Every query, as one trait over anything that has both a traversal and its triangles.

use core::ops::ControlFlow;

use glam::Vec3;

use super::ray_all::RayHits;
use super::shapecast::ShapeCast;
use super::{
    LeafTriangles, OverlapCount, RayOptions, Traverse, closest, closest_batch, overlap,
    overlap_shapes, ray, ray_all, raycast_batch, shapecast,
};
use crate::error::BatchError;
use crate::math::{Aabb, ClosestPoint, Obb, Ray, RayHit, Triangle};

/// The queries of meshq, answered by a structure together with the triangles it indexes.
///
/// Implemented for a structure paired with its triangles by [`Traverse::with`]
/// (`bvh.with(&mesh)`), a blob's view (`BlobView`, feature `blob`) and the owned types (feature
/// `alloc`). A type of your own that is both a [`Traverse`] structure and a [`LeafTriangles`]
/// source gets every query with one line, `impl MeshQuery for MyStructure {}`: each method has
/// its implementation here. Override one only to answer the same thing another way (`MeshIndex`
/// picks its structure once per call, then runs that structure's query). Every
/// answer is exactly what a linear scan over all triangles with the same primitive test would
/// return, bits included, under the crate's tie rule: on equal `t` or distance the lower
/// triangle index wins, so every structure and target returns the same answer. Degenerate
/// (zero-area) triangles are never returned.
///
/// Run a query of your own with [`Traverse::traverse`] and a [`Visitor`](super::Visitor); it reads leaf
/// triangles through this value's [`LeafTriangles`].
pub trait MeshQuery: Traverse + LeafTriangles {
    /// The closest hit of `ray`, with the watertight test and both faces
    /// ([`RayOptions::default`]).
    ///
    /// Conventions: `t` in units of the ray direction's length, within `[t_min, t_max]`
    /// (inclusive); on equal `t` the lower triangle index wins; degenerate triangles are never
    /// hit; an invalid ray ([`Ray::is_valid`]) hits nothing.
    #[must_use]
    #[inline]
    fn raycast(&self, ray: &Ray) -> Option<RayHit> {
        ray::raycast_with(self, self, ray, &RayOptions::default())
    }

    /// [`MeshQuery::raycast`] with explicit options (triangle test, culled faces).
    #[must_use]
    #[inline]
    fn raycast_with(&self, ray: &Ray, options: &RayOptions) -> Option<RayHit> {
        ray::raycast_with(self, self, ray, options)
    }

    /// True when `ray` hits any triangle within `[t_min, t_max]` (occlusion, line of sight),
    /// stopping at the first hit found: true exactly when [`MeshQuery::raycast`] is `Some`.
    #[must_use]
    #[inline]
    fn raycast_any(&self, ray: &Ray) -> bool {
        ray::raycast_any_with(self, self, ray, &RayOptions::default())
    }

    /// [`MeshQuery::raycast_any`] with explicit options: true exactly when
    /// [`MeshQuery::raycast_with`] is `Some` with the same options.
    #[must_use]
    #[inline]
    fn raycast_any_with(&self, ray: &Ray, options: &RayOptions) -> bool {
        ray::raycast_any_with(self, self, ray, options)
    }

    /// Every hit of `ray` within `[t_min, t_max]`, nearest first, written to `out`: each
    /// non-degenerate triangle the ray meets is written once (also by structures that
    /// reference it from several cells), in ascending `t`, the lower triangle index first on
    /// equal `t`. When the ray hits more triangles than `out` holds, `out` gets the nearest
    /// `out.len()` of them and [`RayHits::more`] is set; grow the buffer, or cast again from
    /// beyond the last hit, for the rest.
    ///
    /// Exactly what a scan of all triangles with the same test returns, bits included: the
    /// first hit written is [`MeshQuery::raycast_with`]'s. An invalid ray hits nothing.
    /// Elements of `out` past [`RayHits::written`] are unspecified. For a segment (from one
    /// point to another), pass [`Ray::segment`].
    fn raycast_all(&self, ray: &Ray, options: &RayOptions, out: &mut [RayHit]) -> RayHits {
        ray_all::raycast_all(self, self, ray, options, out)
    }

    /// The point of the mesh closest to `point`, if one lies within `max_distance`
    /// (inclusive; pass `f32::INFINITY` for no limit).
    ///
    /// Exact up to rounding: the answer equals the minimum of
    /// [`closest_point_triangle`](crate::geom::closest_point_triangle()) over all
    /// non-degenerate triangles, with the same bits; on equal squared distance the lower
    /// triangle index wins. Distances are compared squared, so `max_distance` is squared once
    /// first. `None` for a non-finite `point`, a negative or NaN `max_distance` or no
    /// triangles. A point beyond 2⁶² (4.6e18) on some axis, whose squared distances could
    /// overflow `f32`, is searched in coordinates scaled by 2⁻⁶⁴ (a power of two: the same
    /// order and ties, short of mesh coordinates below about 1e-19 that become subnormal);
    /// past about 1.8e19 its [`distance_squared`](ClosestPoint::distance_squared) is `+∞`, and
    /// [`ClosestPoint::distance_from`] gives the distance.
    #[must_use]
    #[inline]
    fn closest_point(&self, point: Vec3, max_distance: f32) -> Option<ClosestPoint> {
        closest::closest_point(self, self, point, max_distance)
    }

    /// The closest point to each of `points` within `max_distance`: `out[i]` is exactly what
    /// [`MeshQuery::closest_point`] returns for `points[i]`, bits included, whatever the other
    /// points are.
    ///
    /// The points are answered in Morton order, and each search starts from the triangle found
    /// for the previous one, a tight bound from the first box on. `keys` is scratch for that
    /// order, one per point (its contents afterwards are unspecified); elements of `keys` and
    /// `out` past `points.len()` are left alone.
    ///
    /// # Errors
    /// [`BatchError::BufferTooSmall`] when `keys` or `out` is shorter than `points`;
    /// [`BatchError::TooLarge`] beyond `u32::MAX` points. Nothing is written then.
    fn closest_points(
        &self,
        points: &[Vec3],
        max_distance: f32,
        keys: &mut [u64],
        out: &mut [Option<ClosestPoint>],
    ) -> Result<(), BatchError> {
        closest_batch::closest_points(self, self, points, max_distance, keys, out)
    }

    /// The closest hit of each of `rays`: `out[i]` is exactly what
    /// [`MeshQuery::raycast_with`] returns for `rays[i]`, whatever order they are cast in.
    ///
    /// The order: a batch of at least 65,536 rays whose origins are not all one point, on a
    /// structure whose [`Traverse::batch_hint`](crate::query::Traverse::batch_hint) names at
    /// least 131,072 triangles, is cast sorted by the line each ray draws through the hint's
    /// box (where it enters and leaves it, quantized), so that rays crossing the same region
    /// run together and find its nodes and triangles in cache. Any other batch is cast in the
    /// given order. On structures that walk packets
    /// ([`Traverse::walks_packets`](crate::query::Traverse::walks_packets): the wide
    /// BVHs), each run of eight consecutive rays with one origin (bit for bit) and the same
    /// direction signs walks the tree together, so give a camera's rays in small tiles or
    /// rows. Buffers, errors and scratch (`keys` holds the order) as
    /// [`MeshQuery::closest_points`].
    ///
    /// # Errors
    /// As [`MeshQuery::closest_points`].
    fn raycast_batch(
        &self,
        rays: &[Ray],
        options: &RayOptions,
        keys: &mut [u64],
        out: &mut [Option<RayHit>],
    ) -> Result<(), BatchError> {
        raycast_batch::raycast_batch(self, self, rays, options, keys, out)
    }

    /// Whether each of `rays` hits anything: `out[i]` is exactly
    /// [`MeshQuery::raycast_any_with`] for `rays[i]`, in the order of
    /// [`MeshQuery::raycast_batch`].
    ///
    /// # Errors
    /// As [`MeshQuery::closest_points`].
    fn raycast_any_batch(
        &self,
        rays: &[Ray],
        options: &RayOptions,
        keys: &mut [u64],
        out: &mut [bool],
    ) -> Result<(), BatchError> {
        raycast_batch::raycast_any_batch(self, self, rays, options, keys, out)
    }

    /// Where `shape` (a sphere, a capsule or an oriented box), moved by `motion` from where it
    /// is, first touches a non-degenerate triangle: the fraction `t ∈ [0, 1]` of the motion
    /// done, the contact point on the mesh, the unit normal from the mesh toward the shape and
    /// the triangle; `None` when it touches nothing along the way. A shape touching the mesh
    /// at the start gives `t = 0`; a zero motion asks whether it touches now.
    ///
    /// Exact up to [`SWEEP_TOLERANCE`](super::SWEEP_TOLERANCE) of the sweep's size (the
    /// shape's extent plus the motion's length): the shape is within that distance of the
    /// mesh at `t`, and does not touch it before. Of contacts at the same `t`, the lowest
    /// triangle index wins, so every structure gives the same answer.
    ///
    /// # Errors
    /// [`SweepError::InvalidShape`](crate::error::SweepError::InvalidShape) for a shape that is
    /// not [valid](super::SweepShape::is_valid) and
    /// [`SweepError::InvalidMotion`](crate::error::SweepError::InvalidMotion) for a motion that
    /// is not finite.
    fn sweep(
        &self,
        shape: &super::SweepShape,
        motion: Vec3,
    ) -> Result<Option<super::SweepHit>, crate::error::SweepError> {
        super::sweep::sweep(self, self, shape, motion)
    }

    /// Calls `report` with the index of every non-degenerate triangle that shares a point with
    /// `aabb` (exact triangle–box test; touching counts), in traversal order, until it returns
    /// `Break`. An empty or non-finite box reports nothing.
    fn overlap_aabb<F: FnMut(u32) -> ControlFlow<()>>(&self, aabb: &Aabb, report: F) {
        overlap::overlap_aabb(self, self, aabb, report);
    }

    /// Calls `report` with the index of every non-degenerate triangle within `radius`
    /// (inclusive) of `center`, in traversal order, until it returns `Break`. A non-finite
    /// center or a negative or NaN radius reports nothing.
    fn overlap_sphere<F: FnMut(u32) -> ControlFlow<()>>(
        &self,
        center: Vec3,
        radius: f32,
        report: F,
    ) {
        overlap::overlap_sphere(self, self, center, radius, report);
    }

    /// [`MeshQuery::overlap_aabb`] writing triangle indices into `out`; keeps counting past
    /// its end, so the result says how large a buffer would have been needed.
    fn overlap_aabb_into(&self, aabb: &Aabb, out: &mut [u32]) -> OverlapCount {
        overlap::overlap_aabb_into(self, self, aabb, out)
    }

    /// [`MeshQuery::overlap_sphere`] writing triangle indices into `out`; keeps counting past
    /// its end, so the result says how large a buffer would have been needed.
    fn overlap_sphere_into(&self, center: Vec3, radius: f32, out: &mut [u32]) -> OverlapCount {
        overlap::overlap_sphere_into(self, self, center, radius, out)
    }

    /// Calls `report` with the index of every non-degenerate triangle that meets triangle
    /// `query` (as [`intersect_triangle_triangle`](crate::geom::intersect_triangle_triangle)
    /// decides: touching and coplanar overlap count), in traversal order, until it returns
    /// `Break`. A degenerate or non-finite `query` reports nothing. (Each mesh triangle is
    /// reported once, also by structures that reference it from several cells.)
    fn overlap_triangle<F: FnMut(u32) -> ControlFlow<()>>(&self, query: &Triangle, report: F) {
        overlap_shapes::overlap_triangle(self, self, query, report);
    }

    /// Calls `report` with the index of every non-degenerate triangle that shares a point
    /// with the oriented box `obb` ([`overlap_triangle_obb`](crate::geom::overlap_triangle_obb);
    /// touching counts), in traversal order, until it returns `Break`. A box that is not
    /// [valid](Obb::is_valid) reports nothing.
    fn overlap_obb<F: FnMut(u32) -> ControlFlow<()>>(&self, obb: &Obb, report: F) {
        overlap_shapes::overlap_obb(self, self, obb, report);
    }

    /// [`MeshQuery::overlap_triangle`] writing triangle indices into `out`; keeps counting
    /// past its end, so the result says how large a buffer would have been needed.
    fn overlap_triangle_into(&self, query: &Triangle, out: &mut [u32]) -> OverlapCount {
        overlap_shapes::overlap_triangle_into(self, self, query, out)
    }

    /// [`MeshQuery::overlap_obb`] writing triangle indices into `out`; keeps counting past its
    /// end, so the result says how large a buffer would have been needed.
    fn overlap_obb_into(&self, obb: &Obb, out: &mut [u32]) -> OverlapCount {
        overlap_shapes::overlap_obb_into(self, self, obb, out)
    }

    /// Casts a shape of the caller's own (see [`ShapeCast`]), in the style of three-mesh-bvh's
    /// `shapecast`: boxes the shape judges `Outside` are skipped, the others entered in
    /// ascending [`score`](ShapeCast::score), and every non-degenerate triangle inside them is
    /// offered until the cast breaks.
    ///
    /// A BVH (and a blob of one) offers each triangle at most once, unless it was built with
    /// spatial splits: then a triangle cut by them may be offered once per leaf holding a part
    /// of it. A structure that references a triangle from several cells (k-d tree, octree,
    /// grid) drops most repeats but may offer a triangle again. [`MeshQuery::shapecast_once`]
    /// offers each once on every structure.
    fn shapecast<C: ShapeCast + ?Sized>(&self, cast: &mut C) {
        shapecast::shapecast(self, self, cast, None);
    }

    /// [`MeshQuery::shapecast`] offering each triangle at most once on every structure, with
    /// `seen` as the record of triangles offered: one bit per triangle index, so
    /// ⌈triangle count / 64⌉ words (cleared by the call; its contents afterwards are
    /// unspecified). A triangle whose index lies beyond `seen` may be offered more than once.
    fn shapecast_once<C: ShapeCast + ?Sized>(&self, cast: &mut C, seen: &mut [u64]) {
        shapecast::shapecast(self, self, cast, Some(seen));
    }
}

impl<T: Traverse + ?Sized, S: LeafTriangles + ?Sized> MeshQuery for super::With<'_, T, S> {}
