//! Whether the leaves holding a split triangle cover it: the check a tree with spatial splits
//! needs where every other leaf must hold its triangles whole.
//!
//! A spatial split gives each leaf only a part of a triangle, so a leaf's box need only meet
//! the triangle. Queries find the triangle through whichever leaf holds the part they reach;
//! a point of the triangle outside every one of those boxes is never reached, and a query
//! near it gets another answer than a scan of the triangles. A tree whose boxes leave such a
//! point is refused.
//!
//! What is checked: every corner of a split triangle lies in the box of one of its
//! references, and every edge lies in the union of those boxes. Each box is widened by a
//! rounding allowance first (2⁻²⁰ of the magnitude of its coordinates, a few units in the
//! last place): the builder's boxes hold their parts exactly, and the allowance absorbs the
//! rounding of the edge's parameters computed here. A part of the interior that no box holds
//! while the whole boundary is held (a hole ringed by four boxes or more) is not detected.
//!
//! Cost: with no memory to sort into, an edge is chained across its boxes by rescanning them,
//! so a triangle held by `k` references costs about `k²` box tests (a few for the usual two to
//! four; a blob that holds one triangle by many thousands of references validates slowly).

use super::TreeArrays;
use crate::error::StructureError;
use crate::math::{Aabb, Triangle};
use crate::query::{LeafTriangles, SplitRef};

/// Relative rounding allowance around each reference box.
const ALLOWANCE: f32 = 1.0 / 1_048_576.0;

/// Checks every split triangle of `tree` against the boxes of its references (the split
/// references' `leaf_box`es), with its corners read from `mesh` through its first reference's
/// slot. Call it once the table itself is checked (`check_slots`: sorted, in range, each box
/// its leaf's), as the blob readers and the encoder do.
///
/// # Errors
/// [`StructureError::SplitTriangleUncovered`] naming the first triangle whose corners or
/// edges leave its references' boxes, or [`StructureError::TriangleOutOfRange`] (`node`
/// `u32::MAX`) when `mesh` has no corners for it.
pub(crate) fn check_split_coverage<A: TreeArrays + ?Sized, S: LeafTriangles + ?Sized>(
    tree: &A,
    mesh: &S,
) -> Result<(), StructureError> {
    let splits = tree.split_refs();
    let mut start = 0usize;
    while let Some(first) = splits.get(start) {
        // The references of one triangle are consecutive: the table is sorted by triangle.
        let mut end = start + 1;
        while splits.get(end).is_some_and(|r| r.tri == first.tri) {
            end += 1;
        }
        let corners = mesh.corners(first.slot as usize, first.tri).ok_or(
            StructureError::TriangleOutOfRange {
                node: u32::MAX,
                tri: first.tri,
            },
        )?;
        let boxes = (start..end).filter_map(|i| splits.get(i).map(|r: SplitRef| r.leaf_box));
        if !covered(&corners, boxes) {
            return Err(StructureError::SplitTriangleUncovered { tri: first.tri });
        }
        start = end;
    }
    Ok(())
}

/// Whether the corners and edges of `t` lie in the union of `boxes` (each widened by the
/// allowance).
fn covered(t: &Triangle, boxes: impl Iterator<Item = Aabb> + Clone) -> bool {
    let widened = boxes.map(|b| {
        let pad = (b.min.abs() + b.max.abs()) * ALLOWANCE;
        Aabb::new(b.min - pad, b.max + pad)
    });
    let corners = [t.a, t.b, t.c];
    let corners_held = corners
        .iter()
        .all(|&p| widened.clone().any(|b| b.contains_point(p)));
    corners_held
        && [(t.a, t.b), (t.b, t.c), (t.c, t.a)]
            .into_iter()
            .all(|(p, q)| edge_covered(p, q, widened.clone()))
}

/// Whether the segment `p`–`q` lies in the union of `boxes`: the parameter intervals of the
/// segment inside each box, chained from 0 until one reaches 1.
fn edge_covered(p: glam::Vec3, q: glam::Vec3, boxes: impl Iterator<Item = Aabb> + Clone) -> bool {
    let d = q - p;
    let span = |b: &Aabb| -> Option<(f32, f32)> {
        let (mut lo, mut hi) = (0.0f32, 1.0f32);
        for axis in 0..3 {
            let (o, v, min, max) = (p[axis], d[axis], b.min[axis], b.max[axis]);
            if v == 0.0 {
                if o < min || o > max {
                    return None;
                }
                continue;
            }
            let (a, z) = ((min - o) / v, (max - o) / v);
            lo = lo.max(a.min(z));
            hi = hi.min(a.max(z));
        }
        (lo <= hi).then_some((lo, hi))
    };
    // Each round moves the reach to the far end of a box that holds the point reached, so it
    // ends within one round per box.
    let mut reach = 0.0f32;
    for _ in 0..=boxes.clone().count() {
        if reach >= 1.0 {
            return true;
        }
        let next = boxes
            .clone()
            .filter_map(|b| span(&b))
            .filter(|&(lo, _)| lo <= reach)
            .map(|(_, hi)| hi)
            .fold(reach, f32::max);
        if next <= reach {
            return false;
        }
        reach = next;
    }
    reach >= 1.0
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;

    fn tri() -> Triangle {
        Triangle::new(
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(4.0, 0.0, 0.0),
            Vec3::new(0.0, 4.0, 1.0),
        )
    }

    /// Points on the triangle, a fine grid of barycentric coordinates.
    fn samples(t: &Triangle) -> impl Iterator<Item = Vec3> + '_ {
        let n = 64;
        (0..=n).flat_map(move |i| {
            (0..=n - i).map(move |j| {
                let (u, v) = (i as f32 / n as f32, j as f32 / n as f32);
                t.a + (t.b - t.a) * u + (t.c - t.a) * v
            })
        })
    }

    /// The boxes of the triangle's parts on either side of `x = s`, as a spatial split makes
    /// them (each part's corners and crossings).
    fn halves(t: &Triangle, s: f32) -> [Aabb; 2] {
        let pts: Vec<Vec3> = samples(t).collect();
        let left = Aabb::from_points(&pts.iter().copied().filter(|p| p.x <= s).collect::<Vec<_>>());
        let right =
            Aabb::from_points(&pts.iter().copied().filter(|p| p.x >= s).collect::<Vec<_>>());
        // The sampled parts miss the crossing points only between samples: grow to the plane.
        let grow = |b: Aabb, x: f32| {
            b.grown(Vec3::new(x, b.min.y, b.min.z))
                .grown(Vec3::new(x, b.max.y, b.max.z))
        };
        [grow(left, s), grow(right, s)]
    }

    #[test]
    fn the_parts_of_a_split_cover_the_triangle() {
        let t = tri();
        for s in [0.5f32, 1.0, 2.0, 3.5] {
            let [l, r] = halves(&t, s);
            // The oracle: every sampled point is in one of the boxes.
            assert!(samples(&t).all(|p| l.contains_point(p) || r.contains_point(p)));
            assert!(covered(&t, [l, r].into_iter()), "split at {s}");
        }
    }

    #[test]
    fn a_box_shrunk_away_from_a_corner_or_an_edge_is_found() {
        let t = tri();
        let [l, r] = halves(&t, 2.0);
        // Moving the right box's far face in uncovers corner b.
        let shrunk = Aabb::new(r.min, Vec3::new(3.0, r.max.y, r.max.z));
        assert!(!samples(&t).all(|p| l.contains_point(p) || shrunk.contains_point(p)));
        assert!(!covered(&t, [l, shrunk].into_iter()));
        // A gap between the two boxes along x uncovers a band crossing two edges.
        let gapped = Aabb::new(Vec3::new(2.25, r.min.y, r.min.z), r.max);
        assert!(!covered(&t, [l, gapped].into_iter()));
        // A box lowered in y uncovers corner c and parts of two edges.
        let low = Aabb::new(l.min, Vec3::new(l.max.x, 3.0, l.max.z));
        assert!(!covered(&t, [low, r].into_iter()));
        // One box alone never covers a triangle both halves are needed for.
        assert!(!covered(&t, [l].into_iter()));
    }

    #[test]
    fn one_box_holding_the_triangle_covers_it() {
        let t = tri();
        let whole = t.bounds();
        assert!(covered(&t, [whole].into_iter()));
        // A degenerate triangle (a segment) on an axis-aligned line, held by boxes of zero
        // width in two axes.
        let seg = Triangle::new(
            Vec3::ZERO,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
        );
        let a = Aabb::new(Vec3::ZERO, Vec3::new(1.0, 0.0, 0.0));
        let b = Aabb::new(Vec3::new(1.0, 0.0, 0.0), Vec3::new(2.0, 0.0, 0.0));
        assert!(covered(&seg, [a, b].into_iter()));
        assert!(!covered(&seg, [a].into_iter()));
    }
}
