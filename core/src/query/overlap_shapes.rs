//! Overlap with a triangle or an oriented box: every mesh triangle that touches it.

use core::ops::ControlFlow;

use super::overlap::{Overlap, box_witness, into_buffer};
use super::{LeafTriangles, OverlapCount, Traverse};
use crate::geom::{TriangleTriangle, intersect_triangle_triangle, overlap_triangle_obb};
use crate::math::{Aabb, Obb, Triangle};

/// Reports the triangles meeting `query` (see
/// [`MeshQuery::overlap_triangle`](super::MeshQuery::overlap_triangle)).
pub(crate) fn overlap_triangle<A, S, F>(tree: &A, source: &S, query: &Triangle, report: F)
where
    A: Traverse + ?Sized,
    S: LeafTriangles + ?Sized,
    F: FnMut(u32) -> ControlFlow<()>,
{
    let bounds = query.bounds();
    if query.is_degenerate() || bounds.is_empty() || !bounds.is_finite() {
        return;
    }
    // Cells are entered by the query's bounds, and each triangle is reported by the cell
    // owning a point of it inside those bounds: one cell the walk enters, and only one.
    let mut v = Overlap {
        source,
        splits: tree.split_refs(),
        enter_box: |b: &Aabb| b.overlaps(&bounds),
        hits: |t: &Triangle| intersect_triangle_triangle(t, query) != TriangleTriangle::Disjoint,
        witness: |t: &Triangle| box_witness(t, &bounds),
        report,
    };
    tree.traverse(&mut v);
}

/// Reports the triangles touching `obb` (see
/// [`MeshQuery::overlap_obb`](super::MeshQuery::overlap_obb)).
pub(crate) fn overlap_obb<A, S, F>(tree: &A, source: &S, obb: &Obb, report: F)
where
    A: Traverse + ?Sized,
    S: LeafTriangles + ?Sized,
    F: FnMut(u32) -> ControlFlow<()>,
{
    let bounds = obb.bounds();
    if bounds.is_empty() || !bounds.is_finite() {
        return;
    }
    let mut v = Overlap {
        source,
        splits: tree.split_refs(),
        enter_box: |b: &Aabb| b.overlaps(&bounds),
        hits: |t: &Triangle| overlap_triangle_obb(t, obb),
        witness: |t: &Triangle| box_witness(t, &bounds),
        report,
    };
    tree.traverse(&mut v);
}

/// [`overlap_triangle`] into a buffer.
pub(crate) fn overlap_triangle_into<A, S>(
    tree: &A,
    source: &S,
    query: &Triangle,
    out: &mut [u32],
) -> OverlapCount
where
    A: Traverse + ?Sized,
    S: LeafTriangles + ?Sized,
{
    into_buffer(out, |report| overlap_triangle(tree, source, query, report))
}

/// [`overlap_obb`] into a buffer.
pub(crate) fn overlap_obb_into<A, S>(
    tree: &A,
    source: &S,
    obb: &Obb,
    out: &mut [u32],
) -> OverlapCount
where
    A: Traverse + ?Sized,
    S: LeafTriangles + ?Sized,
{
    into_buffer(out, |report| overlap_obb(tree, source, obb, report))
}
