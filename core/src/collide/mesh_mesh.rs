//! Where two meshes meet: a walk down both BVHs at once, testing triangle pairs at the
//! leaves.

use core::ops::ControlFlow;

use super::budget::Tally;
use super::tree_pairs::for_each_leaf_pair;
use super::{Affine, CrossingSegment, Found, PairBudget, TrianglePair};
use crate::bvh::{BvhNode, TreeArrays};
use crate::error::PairBudgetSpent;
use crate::geom::{TriangleTriangle, intersect_triangle_triangle, triangles_meet};
use crate::math::Aabb;
use crate::query::{LeafTriangles, With};

/// Calls `on` with every pair of triangles, one of `a` and one of `b` (placed by `b_to_a`),
/// that meets, and how; in walk order. Stops when `on` breaks or `tally` runs out.
fn for_each_meeting_pair<A, SA, B, SB>(
    a: With<'_, A, SA>,
    b: With<'_, B, SB>,
    b_to_a: Option<&Affine>,
    tally: &mut Tally,
    tested: &mut usize,
    mut on: impl FnMut(TrianglePair, TriangleTriangle) -> ControlFlow<()>,
) -> ControlFlow<()>
where
    A: TreeArrays + ?Sized,
    SA: LeafTriangles + ?Sized,
    B: TreeArrays + ?Sized,
    SB: LeafTriangles + ?Sized,
{
    let (tree_a, tris_a) = (a.structure(), a.triangles());
    let (tree_b, tris_b) = (b.structure(), b.triangles());
    let (splits_a, splits_b) = (tree_a.split_refs(), tree_b.split_refs());
    let placed = |bx: &Aabb| b_to_a.map_or(*bx, |m| m.apply_box(bx));
    for_each_leaf_pair(
        tree_a,
        tree_b,
        b_to_a,
        |leaf_a: BvhNode, leaf_b: BvhNode| {
            let Some((ids_a, ids_b)) = tally.take_leaves(tree_a, tree_b, &leaf_a, &leaf_b)? else {
                return ControlFlow::Continue(());
            };
            // `b`'s triangles outside, each placed once.
            for (slot_b, id_b) in ids_b {
                let Some(tb) = tris_b.corners(slot_b, id_b) else {
                    continue;
                };
                let tb = b_to_a.map_or(tb, |m| m.apply_triangle(&tb));
                let bounds_b = tb.bounds();
                if !bounds_b.overlaps(&leaf_a.aabb()) {
                    continue;
                }
                for (slot_a, id_a) in ids_a.clone() {
                    let Some(ta) = tris_a.corners(slot_a, id_a) else {
                        continue;
                    };
                    *tested += 1;
                    // Of the leaf pairs holding references of both triangles (spatial
                    // splits), one reports: the first that this walk pairs and whose `a`
                    // leaf meets `b`'s triangle as placed.
                    let reports = || {
                        splits_a.reports_pair(
                            (slot_a, id_a, leaf_a.aabb()),
                            &splits_b,
                            (slot_b, id_b, leaf_b.aabb()),
                            |box_a, box_b| {
                                box_a.overlaps(&placed(box_b)) && bounds_b.overlaps(box_a)
                            },
                        )
                    };
                    // Decided exactly; where they meet is worked out for those that do.
                    if triangles_meet(&ta, &tb) && reports() {
                        let how = intersect_triangle_triangle(&ta, &tb);
                        on(TrianglePair { a: id_a, b: id_b }, how)?;
                    }
                }
            }
            ControlFlow::Continue(())
        },
    )
}

/// Whether any triangle of `a` meets any triangle of `b`, with `b` placed in `a`'s frame by
/// `b_to_a` (`None`: as it is). Decided exactly on the corners (`b`'s as placed, in `f32`) by
/// [`triangles_meet`](crate::geom::triangles_meet): touching counts (a shared point, a corner
/// on a face, a coplanar overlap), a miss by any margin does not. Degenerate triangles and
/// triangles with NaN corners meet nothing.
///
/// `a` and `b` are BVHs with their triangles (`bvh.with(&mesh)`, a blob's tree and mesh, or a
/// tree with [`PackedTriangles`](crate::query::PackedTriangles)). Both trees are walked
/// together from the roots, and the walk stops at the first meeting pair. No allocation: a
/// fixed stack of about 5 KiB.
///
/// # Errors
/// [`PairBudgetSpent`] when the walk considered `budget`'s pairs without finding one that
/// meets (see [`PairBudget`]; [`PairBudget::for_triangles`] is the usual choice).
pub fn meshes_intersect<A, SA, B, SB>(
    a: With<'_, A, SA>,
    b: With<'_, B, SB>,
    b_to_a: Option<&Affine>,
    budget: PairBudget,
) -> Result<bool, PairBudgetSpent>
where
    A: TreeArrays + ?Sized,
    SA: LeafTriangles + ?Sized,
    B: TreeArrays + ?Sized,
    SB: LeafTriangles + ?Sized,
{
    let mut tally = Tally::new(budget);
    let (mut tested, mut met) = (0, false);
    let _ = for_each_meeting_pair(a, b, b_to_a, &mut tally, &mut tested, |_, _| {
        met = true;
        ControlFlow::Break(())
    });
    tally.yes_or_no(met, tested)
}

/// Every pair of triangles, one of `a` and one of `b`, that meets (as in
/// [`meshes_intersect`]), written to the front of `out` in walk order. Returns how many were
/// found and how many were written: when `out` is too short, the first ones are written and
/// the count goes on ([`Found::overflowed`]).
///
/// # Errors
/// [`PairBudgetSpent`] when the walk considered `budget`'s pairs before its end; the pairs
/// found until then are in `out` and in the error's count.
pub fn intersecting_pairs<A, SA, B, SB>(
    a: With<'_, A, SA>,
    b: With<'_, B, SB>,
    b_to_a: Option<&Affine>,
    budget: PairBudget,
    out: &mut [TrianglePair],
) -> Result<Found, PairBudgetSpent>
where
    A: TreeArrays + ?Sized,
    SA: LeafTriangles + ?Sized,
    B: TreeArrays + ?Sized,
    SB: LeafTriangles + ?Sized,
{
    collect(a, b, b_to_a, budget, out, |pair, _| Some(pair))
}

/// Where the meshes cross: for every pair of triangles that meets (as in
/// [`intersecting_pairs`]) and whose planes cross, the segment they share (a point for a
/// touch) as [`intersect_triangle_triangle`](crate::geom::intersect_triangle_triangle) places
/// it, in `a`'s frame, written to the front of `out` in walk order, counted as in
/// [`intersecting_pairs`]. Pairs that lie in one plane and overlap share an area, not a
/// segment: they are left out here ([`intersecting_pairs`] lists them), as are touches that
/// `intersect_triangle_triangle`'s tolerance judges in the plane or apart.
/// Drawn together, the segments trace the curves where the surfaces cross.
///
/// # Errors
/// As [`intersecting_pairs`].
pub fn intersection_segments<A, SA, B, SB>(
    a: With<'_, A, SA>,
    b: With<'_, B, SB>,
    b_to_a: Option<&Affine>,
    budget: PairBudget,
    out: &mut [CrossingSegment],
) -> Result<Found, PairBudgetSpent>
where
    A: TreeArrays + ?Sized,
    SA: LeafTriangles + ?Sized,
    B: TreeArrays + ?Sized,
    SB: LeafTriangles + ?Sized,
{
    collect(a, b, b_to_a, budget, out, |pair, how| match how {
        TriangleTriangle::Segment { a, b } => Some(CrossingSegment {
            pair,
            start: a,
            end: b,
        }),
        _ => None,
    })
}

/// Writes `keep(pair, how)` of every meeting pair that it keeps to the front of `out`,
/// counting them all.
fn collect<A, SA, B, SB, T>(
    a: With<'_, A, SA>,
    b: With<'_, B, SB>,
    b_to_a: Option<&Affine>,
    budget: PairBudget,
    out: &mut [T],
    keep: impl Fn(TrianglePair, TriangleTriangle) -> Option<T>,
) -> Result<Found, PairBudgetSpent>
where
    A: TreeArrays + ?Sized,
    SA: LeafTriangles + ?Sized,
    B: TreeArrays + ?Sized,
    SB: LeafTriangles + ?Sized,
{
    let mut found = Found::default();
    let (mut tally, mut tested) = (Tally::new(budget), 0);
    let _ = for_each_meeting_pair(a, b, b_to_a, &mut tally, &mut tested, |pair, how| {
        if let Some(item) = keep(pair, how) {
            found.push(out, item);
        }
        ControlFlow::Continue(())
    });
    found.tested = tested;
    tally.finish(found)
}
