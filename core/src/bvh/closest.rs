use core::ops::ControlFlow;

use glam::Vec3;

use super::{Bvh, BvhNode, BvhVisitor};
use crate::geom::closest_point_regions;
use crate::math::{ClosestPoint, dot};
use crate::mesh::ValidMesh;

/// Relative slack on box distances (as in ray traversal): a box is entered when it might hold
/// a point within a few thousand ulps of the current best, so rounding can never cull the
/// winner or a tie.
const MARGIN: f32 = 1.0 / 65_536.0;

struct Closest<'m> {
    mesh: &'m ValidMesh<'m>,
    point: Vec3,
    /// Current bound on the squared distance: the best so far, or the caller's maximum.
    limit: f32,
    best: Option<ClosestPoint>,
}

impl BvhVisitor for Closest<'_> {
    #[inline(always)]
    fn enter(&mut self, node: &BvhNode) -> Option<f32> {
        let d2 = node.aabb().distance_squared_to_point(self.point);
        let lo = d2 - d2 * MARGIN;
        (lo <= self.limit).then_some(lo)
    }

    #[inline(always)]
    fn revisit(&self, key: f32) -> bool {
        key <= self.limit
    }

    fn leaf(&mut self, tris: &[u32]) -> ControlFlow<()> {
        for &tri in tris {
            let Some(t) = self.mesh.triangle(tri) else {
                continue;
            };
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

impl Bvh<'_> {
    /// The point of `mesh` closest to `point`, if one lies within `max_distance` (inclusive;
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
    pub fn closest_point(
        &self,
        mesh: &ValidMesh<'_>,
        point: Vec3,
        max_distance: f32,
    ) -> Option<ClosestPoint> {
        if !point.is_finite() || !(max_distance >= 0.0) {
            return None;
        }
        let mut v = Closest {
            mesh,
            point,
            limit: max_distance * max_distance,
            best: None,
        };
        self.traverse(&mut v);
        v.best
    }
}
