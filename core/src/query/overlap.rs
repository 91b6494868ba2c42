//! Overlap queries: every triangle that touches a box or a sphere.

use core::ops::ControlFlow;

use glam::Vec3;

use super::{LeafTriangleIds, LeafTriangles, SplitRefs, Traverse, Visitor};
use crate::geom::aabb_lanes::MARGIN;
use crate::geom::{clip_triangle_aabb, closest_point_regions, overlap_triangle_aabb};
use crate::math::{Aabb, Triangle, dot};

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

/// Visits leaves whose box passes `enter_box`, reporting triangles that pass `hits`. In a leaf
/// with a [`Cell`](super::Cell) a triangle is reported only when the cell owns its `witness`: a
/// point of the triangle and the query, the same in every cell, so exactly one cell reports it.
/// A triangle a tree holds in several leaves by spatial splits is reported by the reference
/// [`SplitRefs::reports`] picks.
pub(super) struct Overlap<'m, S: ?Sized, B, T, W, F> {
    pub(super) source: &'m S,
    pub(super) splits: SplitRefs<'m>,
    pub(super) enter_box: B,
    pub(super) hits: T,
    pub(super) witness: W,
    pub(super) report: F,
}

impl<S, B, T, W, F> Visitor for Overlap<'_, S, B, T, W, F>
where
    S: LeafTriangles + ?Sized,
    B: Fn(&Aabb) -> bool,
    T: Fn(&Triangle) -> bool,
    W: Fn(&Triangle) -> Vec3,
    F: FnMut(u32) -> ControlFlow<()>,
{
    fn enter(&mut self, aabb: &Aabb) -> Option<f32> {
        (self.enter_box)(aabb).then_some(0.0)
    }

    fn leaf(&mut self, tris: LeafTriangleIds<'_>) -> ControlFlow<()> {
        let cell = tris.cell().copied();
        for (slot, tri) in tris {
            let Some(t) = self.source.corners(slot, tri) else {
                continue;
            };
            if !t.is_degenerate()
                && (self.hits)(&t)
                && cell.is_none_or(|c| c.owns((self.witness)(&t)))
                && self.splits.reports(slot, tri, &self.enter_box)
            {
                (self.report)(tri)?;
            }
        }
        ControlFlow::Continue(())
    }
}

/// The point that decides which cell reports triangle `t` overlapping box `query`: the
/// lexicographically smallest corner of the part of `t` inside `query`, kept inside both the
/// query and the triangle's bounds, so it lies in a cell the query enters and that holds `t`.
pub(super) fn box_witness(t: &Triangle, query: &Aabb) -> Vec3 {
    let part = clip_triangle_aabb(t, query);
    let first = part.corners().iter().copied().reduce(|best, p| {
        let (a, b) = (p.to_array(), best.to_array());
        if a < b { p } else { best }
    });
    let tb = t.bounds();
    let (lo, hi) = (tb.min.max(query.min), tb.max.min(query.max));
    // No corner survives clipping only when rounding loses a touching point: the nearest
    // point of the shared bounds stands in.
    first.unwrap_or(t.a).clamp(lo, hi.max(lo))
}

fn push(out: &mut [u32], count: &mut OverlapCount, tri: u32) -> ControlFlow<()> {
    if let Some(slot) = out.get_mut(count.written) {
        *slot = tri;
        count.written += 1;
    }
    count.total += 1;
    ControlFlow::Continue(())
}

/// Reports the triangles touching `aabb` (see [`MeshQuery::overlap_aabb`](super::MeshQuery::overlap_aabb)).
pub(crate) fn overlap_aabb<A, S, F>(tree: &A, source: &S, aabb: &Aabb, report: F)
where
    A: Traverse + ?Sized,
    S: LeafTriangles + ?Sized,
    F: FnMut(u32) -> ControlFlow<()>,
{
    if aabb.is_empty() || !aabb.is_finite() {
        return;
    }
    let query = *aabb;
    let mut v = Overlap {
        source,
        splits: tree.split_refs(),
        enter_box: |b: &Aabb| b.overlaps(&query),
        hits: |t: &Triangle| overlap_triangle_aabb(t, &query),
        witness: |t: &Triangle| box_witness(t, &query),
        report,
    };
    tree.traverse(&mut v);
}

/// Reports the triangles within `radius` of `center` (see
/// [`MeshQuery::overlap_sphere`](super::MeshQuery::overlap_sphere)).
pub(crate) fn overlap_sphere<A, S, F>(tree: &A, source: &S, center: Vec3, radius: f32, report: F)
where
    A: Traverse + ?Sized,
    S: LeafTriangles + ?Sized,
    F: FnMut(u32) -> ControlFlow<()>,
{
    if !center.is_finite() || !(radius >= 0.0) {
        return;
    }
    let r2 = radius * radius;
    let mut v = Overlap {
        source,
        splits: tree.split_refs(),
        // With slack, so the cell owning a triangle's witness is entered despite rounding.
        enter_box: |b: &Aabb| b.distance_squared_to_point(center) * (1.0 - MARGIN) <= r2,
        hits: |t: &Triangle| {
            let (q, ..) = closest_point_regions(center, t.a, t.b, t.c);
            let d = center - q;
            dot(d, d) <= r2
        },
        witness: |t: &Triangle| {
            let (q, ..) = closest_point_regions(center, t.a, t.b, t.c);
            let b = t.bounds();
            q.clamp(b.min, b.max)
        },
        report,
    };
    tree.traverse(&mut v);
}

/// Runs an overlap query (`run` passes its report on to the query), writing the reported
/// triangle indices to the front of `out` and counting past its end.
pub(super) fn into_buffer(
    out: &mut [u32],
    run: impl FnOnce(&mut dyn FnMut(u32) -> ControlFlow<()>),
) -> OverlapCount {
    let mut count = OverlapCount {
        written: 0,
        total: 0,
    };
    run(&mut |tri| push(out, &mut count, tri));
    count
}

/// [`overlap_aabb`] into a buffer.
pub(crate) fn overlap_aabb_into<A, S>(
    tree: &A,
    source: &S,
    aabb: &Aabb,
    out: &mut [u32],
) -> OverlapCount
where
    A: Traverse + ?Sized,
    S: LeafTriangles + ?Sized,
{
    into_buffer(out, |report| overlap_aabb(tree, source, aabb, report))
}

/// [`overlap_sphere`] into a buffer.
pub(crate) fn overlap_sphere_into<A, S>(
    tree: &A,
    source: &S,
    center: Vec3,
    radius: f32,
    out: &mut [u32],
) -> OverlapCount
where
    A: Traverse + ?Sized,
    S: LeafTriangles + ?Sized,
{
    into_buffer(out, |report| {
        overlap_sphere(tree, source, center, radius, report);
    })
}
