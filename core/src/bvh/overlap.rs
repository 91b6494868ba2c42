use core::ops::ControlFlow;

use glam::Vec3;

use super::traverse::traverse;
use super::{Bvh, BvhNode, BvhVisitor, LeafTriangleIds, LeafTriangles, TreeArrays};
use crate::geom::{closest_point_regions, overlap_triangle_aabb};
use crate::math::{Aabb, dot};

/// How many triangles an `*_into` overlap query found and how many fit in the buffer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct OverlapCount {
    /// Triangle indices written to the front of the buffer.
    pub written: usize,
    /// Triangles that overlap in all; more than `written` when the buffer was too small.
    pub total: usize,
}

impl OverlapCount {
    /// True when every overlapping triangle was written.
    #[must_use]
    pub const fn is_complete(&self) -> bool {
        self.written == self.total
    }
}

/// Visits leaves whose box passes `enter_box`, reporting triangles that pass `hits`.
struct Overlap<'m, S: ?Sized, B, T, F> {
    source: &'m S,
    enter_box: B,
    hits: T,
    report: F,
}

impl<S, B, T, F> BvhVisitor for Overlap<'_, S, B, T, F>
where
    S: LeafTriangles + ?Sized,
    B: Fn(&BvhNode) -> bool,
    T: Fn(&crate::math::Triangle) -> bool,
    F: FnMut(u32) -> ControlFlow<()>,
{
    fn enter(&mut self, node: &BvhNode) -> Option<f32> {
        (self.enter_box)(node).then_some(0.0)
    }

    fn leaf(&mut self, tris: LeafTriangleIds<'_>) -> ControlFlow<()> {
        for (slot, tri) in tris {
            let Some(t) = self.source.corners(slot, tri) else {
                continue;
            };
            if !t.is_degenerate() && (self.hits)(&t) {
                (self.report)(tri)?;
            }
        }
        ControlFlow::Continue(())
    }
}

impl Bvh<'_> {
    /// Calls `report` with the index of every non-degenerate triangle that shares a point with
    /// `aabb` (exact triangle–box test; touching counts), in traversal order, until it returns
    /// `Break`.
    pub fn overlap_aabb<S: LeafTriangles + ?Sized, F: FnMut(u32) -> ControlFlow<()>>(
        &self,
        source: &S,
        aabb: &Aabb,
        report: F,
    ) {
        overlap_aabb(self, source, aabb, report);
    }

    /// Calls `report` with the index of every non-degenerate triangle within `radius`
    /// (inclusive) of `center`, in traversal order, until it returns `Break`. A non-finite
    /// center or a negative or NaN radius reports nothing.
    pub fn overlap_sphere<S: LeafTriangles + ?Sized, F: FnMut(u32) -> ControlFlow<()>>(
        &self,
        source: &S,
        center: Vec3,
        radius: f32,
        report: F,
    ) {
        overlap_sphere(self, source, center, radius, report);
    }

    /// [`Bvh::overlap_aabb`] writing triangle indices into `out`; keeps counting past its end
    /// so the result says how large a buffer would have been needed.
    pub fn overlap_aabb_into<S: LeafTriangles + ?Sized>(
        &self,
        source: &S,
        aabb: &Aabb,
        out: &mut [u32],
    ) -> OverlapCount {
        overlap_aabb_into(self, source, aabb, out)
    }

    /// [`Bvh::overlap_sphere`] writing triangle indices into `out`; keeps counting past its
    /// end so the result says how large a buffer would have been needed.
    pub fn overlap_sphere_into<S: LeafTriangles + ?Sized>(
        &self,
        source: &S,
        center: Vec3,
        radius: f32,
        out: &mut [u32],
    ) -> OverlapCount {
        overlap_sphere_into(self, source, center, radius, out)
    }
}

fn push(out: &mut [u32], count: &mut OverlapCount, tri: u32) -> ControlFlow<()> {
    if let Some(slot) = out.get_mut(count.written) {
        *slot = tri;
        count.written += 1;
    }
    count.total += 1;
    ControlFlow::Continue(())
}

/// [`Bvh::overlap_aabb`] over any storage.
pub(crate) fn overlap_aabb<A, S, F>(tree: &A, source: &S, aabb: &Aabb, report: F)
where
    A: TreeArrays + ?Sized,
    S: LeafTriangles + ?Sized,
    F: FnMut(u32) -> ControlFlow<()>,
{
    if aabb.is_empty() || !aabb.is_finite() {
        return;
    }
    let query = *aabb;
    let mut v = Overlap {
        source,
        enter_box: |n: &BvhNode| n.aabb().overlaps(&query),
        hits: |t: &crate::math::Triangle| overlap_triangle_aabb(t, &query),
        report,
    };
    traverse(tree, &mut v);
}

/// [`Bvh::overlap_sphere`] over any storage.
pub(crate) fn overlap_sphere<A, S, F>(tree: &A, source: &S, center: Vec3, radius: f32, report: F)
where
    A: TreeArrays + ?Sized,
    S: LeafTriangles + ?Sized,
    F: FnMut(u32) -> ControlFlow<()>,
{
    if !center.is_finite() || !(radius >= 0.0) {
        return;
    }
    let r2 = radius * radius;
    let mut v = Overlap {
        source,
        enter_box: |n: &BvhNode| n.aabb().distance_squared_to_point(center) <= r2,
        hits: |t: &crate::math::Triangle| {
            let (q, ..) = closest_point_regions(center, t.a, t.b, t.c);
            let d = center - q;
            dot(d, d) <= r2
        },
        report,
    };
    traverse(tree, &mut v);
}

/// [`Bvh::overlap_aabb_into`] over any storage.
pub(crate) fn overlap_aabb_into<A, S>(
    tree: &A,
    source: &S,
    aabb: &Aabb,
    out: &mut [u32],
) -> OverlapCount
where
    A: TreeArrays + ?Sized,
    S: LeafTriangles + ?Sized,
{
    let mut count = OverlapCount {
        written: 0,
        total: 0,
    };
    overlap_aabb(tree, source, aabb, |tri| push(out, &mut count, tri));
    count
}

/// [`Bvh::overlap_sphere_into`] over any storage.
pub(crate) fn overlap_sphere_into<A, S>(
    tree: &A,
    source: &S,
    center: Vec3,
    radius: f32,
    out: &mut [u32],
) -> OverlapCount
where
    A: TreeArrays + ?Sized,
    S: LeafTriangles + ?Sized,
{
    let mut count = OverlapCount {
        written: 0,
        total: 0,
    };
    overlap_sphere(tree, source, center, radius, |tri| {
        push(out, &mut count, tri)
    });
    count
}
