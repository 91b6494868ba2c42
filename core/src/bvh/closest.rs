use core::ops::ControlFlow;

use glam::{Vec3, Vec3A, Vec4};

use super::traverse::Walk;
use super::wide::traverse::LaneVisitor;
use super::wide::{WideNode, lanes};
use super::{Bvh, BvhNode, BvhVisitor, LeafTriangleIds, LeafTriangles};
use crate::geom::closest_point_regions;
use crate::math::{ClosestPoint, dot};

/// Relative slack on box distances (as in ray traversal): a box is entered when it might hold
/// a point within a few thousand ulps of the current best, so rounding can never cull the
/// winner or a tie.
const MARGIN: f32 = 1.0 / 65_536.0;

struct Closest<'m, S: ?Sized> {
    source: &'m S,
    point: Vec3,
    /// The same point in SIMD lanes, for box distances (see [`box_distance_squared`]).
    lanes: Vec3A,
    /// Current bound on the squared distance: the best so far, or the caller's maximum.
    limit: f32,
    best: Option<ClosestPoint>,
}

impl<S: LeafTriangles + ?Sized> BvhVisitor for Closest<'_, S> {
    #[inline(always)]
    fn enter(&mut self, node: &BvhNode) -> Option<f32> {
        let d2 = box_distance_squared(
            Vec3A::from_array(node.min),
            Vec3A::from_array(node.max),
            self.lanes,
        );
        // A product, not `d2 − d2·MARGIN`: an overflowed (infinite) distance stays comparable.
        let lo = d2 * (1.0 - MARGIN);
        (lo <= self.limit).then_some(lo)
    }

    #[inline(always)]
    fn revisit(&self, key: f32) -> bool {
        key <= self.limit
    }

    fn leaf(&mut self, tris: LeafTriangleIds<'_>) -> ControlFlow<()> {
        for (slot, tri) in tris {
            let Some(t) = self.source.corners(slot, tri) else {
                continue;
            };
            // The triangle's own box is a cheap lower bound on its distance: skip the full
            // region walk when even the box is beyond the best so far.
            let (a, b, c) = (Vec3A::from(t.a), Vec3A::from(t.b), Vec3A::from(t.c));
            let d2 = box_distance_squared(a.min(b).min(c), a.max(b).max(c), self.lanes);
            if d2 - d2 * MARGIN > self.limit {
                continue;
            }
            let (q, u, v, feature) = closest_point_regions(self.point, t.a, t.b, t.c);
            let d = self.point - q;
            let candidate = ClosestPoint {
                point: q,
                tri,
                u,
                v,
                distance_squared: dot(d, d),
                feature,
            };
            if candidate.distance_squared <= self.limit
                && self.best.is_none_or(|b| candidate.beats(&b))
                && !t.is_degenerate()
            {
                self.limit = candidate.distance_squared;
                self.best = Some(candidate);
            }
        }
        ControlFlow::Continue(())
    }
}

impl<S: LeafTriangles + ?Sized> LaneVisitor for Closest<'_, S> {
    #[inline(always)]
    fn enter_lanes(&mut self, node: &WideNode) -> (u32, Vec4) {
        lanes::enter_point(node, self.point, self.limit, MARGIN)
    }
}

/// Squared distance from `p` to the box `[min, max]`, in SIMD lanes where the target has them.
///
/// Used only to decide what to visit (with [`MARGIN`] of slack), never for a reported
/// distance, so lane-wise rounding cannot change an answer: the answer is the minimum under a
/// total order (distance, then triangle index), whatever order triangles are visited in.
#[inline(always)]
fn box_distance_squared(min: Vec3A, max: Vec3A, p: Vec3A) -> f32 {
    let d = (min - p).max(p - max).max(Vec3A::ZERO);
    d.dot(d)
}

impl Bvh<'_> {
    /// The point of `source` (the mesh, or its packed triangles) closest to `point`, if one lies within `max_distance` (inclusive;
    /// pass `f32::INFINITY` for no limit).
    ///
    /// Exact up to rounding: the answer equals the minimum of
    /// [`closest_point_triangle`](crate::geom::closest_point_triangle) over all non-degenerate
    /// triangles, with the same bits; on equal squared distance the lower triangle index wins.
    /// Distances are compared squared, so `max_distance` is squared once first. Returns `None`
    /// for a non-finite `point`, a negative or NaN `max_distance`, or an empty tree.
    ///
    /// The search is depth first, nearer box first, and skips boxes farther than the best
    /// distance so far.
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

/// [`Bvh::closest_point`] over any storage.
pub(crate) fn closest_point<A: Walk + ?Sized, S: LeafTriangles + ?Sized>(
    tree: &A,
    source: &S,
    point: Vec3,
    max_distance: f32,
) -> Option<ClosestPoint> {
    if !point.is_finite() || !(max_distance >= 0.0) {
        return None;
    }
    let mut v = Closest {
        source,
        point,
        lanes: point.into(),
        limit: max_distance * max_distance,
        best: None,
    };
    tree.walk(&mut v);
    v.best
}
