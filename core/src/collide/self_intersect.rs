//! Where a mesh meets itself: its BVH walked against itself, neighbours judged by what they
//! share.

use core::ops::ControlFlow;

use super::budget::Tally;
use super::neighbours::meets_beyond_shared;
use super::tree_pairs::for_each_self_leaf_pair;
use super::{Found, PairBudget, TrianglePair};
use crate::bvh::{BvhNode, TreeArrays};
use crate::error::PairBudgetSpent;
use crate::geom::triangles_meet;
use crate::math::Aabb;
use crate::mesh::ValidMesh;

/// Calls `on` with every pair of `mesh`'s triangles (`a < b`) that meets beyond what the two
/// share; in walk order. Stops when `on` breaks or `tally` runs out.
fn for_each_self_pair<A: TreeArrays + ?Sized>(
    tree: &A,
    mesh: &ValidMesh<'_>,
    skip_shared: bool,
    tally: &mut Tally,
    tested: &mut usize,
    mut on: impl FnMut(TrianglePair) -> ControlFlow<()>,
) -> ControlFlow<()> {
    let triangles = mesh.triangles();
    let splits = tree.split_refs();
    for_each_self_leaf_pair(tree, |one: BvhNode, other: BvhNode| {
        let same_leaf = one.first == other.first;
        let (n_one, n_other) = (one.count as usize, other.count as usize);
        let pairs = if same_leaf {
            n_one.saturating_mul(n_one.saturating_sub(1)) / 2
        } else {
            n_one.saturating_mul(n_other)
        };
        if !tally.take(pairs) {
            return ControlFlow::Break(());
        }
        let (Some(ids_one), Some(ids_other)) = (
            tree.leaf_triangles(one.first as usize, one.count as usize),
            tree.leaf_triangles(other.first as usize, other.count as usize),
        ) else {
            return ControlFlow::Continue(());
        };
        for (k, (slot_i, i)) in ids_one.enumerate() {
            let (Some(ti), Some(&ci)) = (mesh.triangle(i), triangles.get(i as usize)) else {
                continue;
            };
            // Within one leaf, each unordered pair once: the entries after this one.
            let partners = ids_other.clone().skip(if same_leaf { k + 1 } else { 0 });
            for (slot_j, j) in partners {
                // Two references of one triangle (spatial splits) are not a pair.
                if i == j {
                    continue;
                }
                let (Some(tj), Some(&cj)) = (mesh.triangle(j), triangles.get(j as usize)) else {
                    continue;
                };
                // The lower index first, whatever the walk's order: borderline touches are
                // then decided the same way by any tree.
                let ((t1, c1), (t2, c2)) = if i < j {
                    ((ti, ci), (tj, cj))
                } else {
                    ((tj, cj), (ti, ci))
                };
                *tested += 1;
                let meets = if skip_shared {
                    meets_beyond_shared(&t1, &t2, c1, c2)
                } else {
                    triangles_meet(&t1, &t2)
                };
                // Of the leaf pairs holding references of both (spatial splits), the first
                // whose boxes meet reports, lower triangle's reference first.
                let (lower, higher) = {
                    let ri = (slot_i, i, one.aabb());
                    let rj = (slot_j, j, other.aabb());
                    if i < j { (ri, rj) } else { (rj, ri) }
                };
                if meets && splits.reports_pair(lower, &splits, higher, Aabb::overlaps) {
                    on(TrianglePair {
                        a: i.min(j),
                        b: i.max(j),
                    })?;
                }
            }
        }
        ControlFlow::Continue(())
    })
}

/// Whether `mesh` meets itself: whether two of its triangles meet somewhere besides the
/// corners or edge they share, decided exactly on their `f32` corners (the signs of exact
/// orientation determinants, as [`triangles_meet`](crate::geom::triangles_meet)). Neighbours
/// touch along what they share, which does not count: triangles sharing a corner count when
/// they meet anywhere else (crossing beyond it, or in one plane with overlapping wedges or
/// edges running along each other); triangles sharing an edge only when they lie in one plane
/// with their other corners on the same side of it (a face folded onto its neighbour).
/// Triangles sharing nothing count when they meet at all, touching included. A corner is
/// shared by index or by exactly equal position, so the seams of an unwelded mesh do not
/// count. Each pair is tested lower index first, so the answer does not depend on the tree.
/// Degenerate triangles (collinear corners) and triangles with NaN corners meet nothing.
///
/// `tree` is a BVH built over `mesh` (a [`Bvh`](crate::bvh::Bvh), or a blob's tree with the
/// blob's mesh). It is walked against itself, and the walk stops at the first pair. No
/// allocation: a fixed stack of about 2 KiB.
///
/// # Errors
/// [`PairBudgetSpent`] when the walk considered `budget`'s pairs without finding one (see
/// [`PairBudget`]; [`PairBudget::for_triangles`] with the triangle count twice is the usual
/// choice).
pub fn self_intersects<A: TreeArrays + ?Sized>(
    tree: &A,
    mesh: &ValidMesh<'_>,
    budget: PairBudget,
) -> Result<bool, PairBudgetSpent> {
    let mut tally = Tally::new(budget);
    let (mut tested, mut met) = (0, false);
    let _ = for_each_self_pair(tree, mesh, true, &mut tally, &mut tested, |_| {
        met = true;
        ControlFlow::Break(())
    });
    tally.yes_or_no(met, tested)
}

/// Every pair of `mesh`'s triangles that meets itself (as in [`self_intersects`]), `a < b`,
/// written to the front of `out` in walk order; counted as
/// [`intersecting_pairs`](super::intersecting_pairs) counts.
///
/// # Errors
/// [`PairBudgetSpent`] when the walk considered `budget`'s pairs before its end; the pairs
/// found until then are in `out` and in the error's count.
pub fn self_intersecting_pairs<A: TreeArrays + ?Sized>(
    tree: &A,
    mesh: &ValidMesh<'_>,
    budget: PairBudget,
    out: &mut [TrianglePair],
) -> Result<Found, PairBudgetSpent> {
    collect_self_pairs(tree, mesh, true, budget, out)
}

/// [`self_intersecting_pairs`] without the rule for neighbours: every pair that meets at
/// all, so every pair of triangles sharing a corner too. Wrong for a self-intersection check,
/// and kept only so that a test can show the rule matters.
#[doc(hidden)]
pub fn touching_pairs_unfiltered<A: TreeArrays + ?Sized>(
    tree: &A,
    mesh: &ValidMesh<'_>,
    out: &mut [TrianglePair],
) -> Found {
    let all = collect_self_pairs(tree, mesh, false, PairBudget::UNLIMITED, out);
    // An unlimited budget is never spent.
    all.unwrap_or_default()
}

/// Writes the pairs [`for_each_self_pair`] finds to the front of `out`, counting them all.
fn collect_self_pairs<A: TreeArrays + ?Sized>(
    tree: &A,
    mesh: &ValidMesh<'_>,
    skip_shared: bool,
    budget: PairBudget,
    out: &mut [TrianglePair],
) -> Result<Found, PairBudgetSpent> {
    let mut found = Found::default();
    let (mut tally, mut tested) = (Tally::new(budget), 0);
    let _ = for_each_self_pair(tree, mesh, skip_shared, &mut tally, &mut tested, |pair| {
        found.push(out, pair);
        ControlFlow::Continue(())
    });
    found.tested = tested;
    tally.finish(found)
}
