use core::ops::ControlFlow;

use glam::Vec3;

use super::{Bvh, BvhNode, BvhVisitor};
use crate::geom::{closest_point_regions, overlap_triangle_aabb};
use crate::math::{Aabb, dot};
use crate::mesh::ValidMesh;

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
struct Overlap<'m, B, T, F> {
    mesh: &'m ValidMesh<'m>,
    enter_box: B,
    hits: T,
    report: F,
}

impl<B, T, F> BvhVisitor for Overlap<'_, B, T, F>
where
    B: Fn(&BvhNode) -> bool,
    T: Fn(&crate::math::Triangle) -> bool,
    F: FnMut(u32) -> ControlFlow<()>,
{
    fn enter(&mut self, node: &BvhNode) -> Option<f32> {
        (self.enter_box)(node).then_some(0.0)
    }

    fn leaf(&mut self, tris: &[u32]) -> ControlFlow<()> {
        for &tri in tris {
            let Some(t) = self.mesh.triangle(tri) else {
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
    pub fn overlap_aabb<F: FnMut(u32) -> ControlFlow<()>>(
        &self,
        mesh: &ValidMesh<'_>,
        aabb: &Aabb,
        report: F,
    ) {
        if aabb.is_empty() || !aabb.is_finite() {
            return;
        }
        let query = *aabb;
        let mut v = Overlap {
            mesh,
            enter_box: |n: &BvhNode| n.aabb().overlaps(&query),
            hits: |t: &crate::math::Triangle| overlap_triangle_aabb(t, &query),
            report,
        };
        self.traverse(&mut v);
    }

    /// Calls `report` with the index of every non-degenerate triangle within `radius`
    /// (inclusive) of `center`, in traversal order, until it returns `Break`. A non-finite
    /// center or a negative or NaN radius reports nothing.
    pub fn overlap_sphere<F: FnMut(u32) -> ControlFlow<()>>(
        &self,
        mesh: &ValidMesh<'_>,
        center: Vec3,
        radius: f32,
        report: F,
    ) {
        if !center.is_finite() || !(radius >= 0.0) {
            return;
        }
        let r2 = radius * radius;
        let mut v = Overlap {
            mesh,
            enter_box: |n: &BvhNode| n.aabb().distance_squared_to_point(center) <= r2,
            hits: |t: &crate::math::Triangle| {
                let (q, ..) = closest_point_regions(center, t.a, t.b, t.c);
                let d = center - q;
                dot(d, d) <= r2
            },
            report,
        };
        self.traverse(&mut v);
    }

    /// [`Bvh::overlap_aabb`] writing triangle indices into `out`; keeps counting past its end
    /// so the result says how large a buffer would have been needed.
    pub fn overlap_aabb_into(
        &self,
        mesh: &ValidMesh<'_>,
        aabb: &Aabb,
        out: &mut [u32],
    ) -> OverlapCount {
        let mut count = OverlapCount {
            written: 0,
            total: 0,
        };
        self.overlap_aabb(mesh, aabb, |tri| push(out, &mut count, tri));
        count
    }

    /// [`Bvh::overlap_sphere`] writing triangle indices into `out`; keeps counting past its
    /// end so the result says how large a buffer would have been needed.
    pub fn overlap_sphere_into(
        &self,
        mesh: &ValidMesh<'_>,
        center: Vec3,
        radius: f32,
        out: &mut [u32],
    ) -> OverlapCount {
        let mut count = OverlapCount {
            written: 0,
            total: 0,
        };
        self.overlap_sphere(mesh, center, radius, |tri| push(out, &mut count, tri));
        count
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
