//! When two triangles of one mesh that share corners count as intersecting: only when they
//! meet somewhere they should not.

use glam::{Vec2, Vec3};

use crate::geom::TriangleTriangle;
use crate::geom::onto_dominant_plane;
use crate::math::Triangle;

/// Whether triangles `t1` and `t2` of one mesh, with corner indices `i1` and `i2`, meet
/// somewhere besides what they share, given `how` they intersect
/// ([`intersect_triangle_triangle`](crate::geom::intersect_triangle_triangle)):
///
/// - sharing no corner: whenever they meet at all (touching counts);
/// - sharing one corner `v`: when they cross along more than the point `v` (an end farther
///   than about 2⁻²⁰ of the coordinates' magnitude from it), or lie in one plane and overlap
///   with positive area (a neighbour folded over);
/// - sharing an edge: only when they lie in one plane and overlap with positive area (folded
///   onto each other); crossing planes meet on the shared edge alone;
/// - sharing all three corners (a doubled face): whenever they meet.
///
/// A corner is shared when both triangles use its vertex index, or have a corner at its
/// position (within about 2⁻²⁰ of the coordinates' magnitude), so the seams of an unwelded
/// mesh, such as a UV sphere's, are neighbours too.
pub(crate) fn meets_beyond_shared(
    t1: &Triangle,
    t2: &Triangle,
    i1: [u32; 3],
    i2: [u32; 3],
    how: TriangleTriangle,
) -> bool {
    let corners2 = [t2.a, t2.b, t2.c];
    let tol = magnitude(t1, t2) * (1.0 / 1_048_576.0);
    let at_a_corner_of_t2 = |p: Vec3| corners2.iter().any(|q| (*q - p).abs().max_element() <= tol);
    let mut shared = 0usize;
    let mut shared_at = Vec3::ZERO;
    for (&i, p) in i1.iter().zip([t1.a, t1.b, t1.c]) {
        if i2.contains(&i) || at_a_corner_of_t2(p) {
            shared += 1;
            shared_at = p;
        }
    }
    match (shared, how) {
        (_, TriangleTriangle::Disjoint) => false,
        (0 | 3, _) => true,
        (1, TriangleTriangle::Segment { a, b }) => {
            (a - shared_at).abs().max_element() > tol || (b - shared_at).abs().max_element() > tol
        }
        (2, TriangleTriangle::Segment { .. }) => false,
        (_, TriangleTriangle::Coplanar) => overlap_with_area(t1, t2),
        _ => false,
    }
}

/// The largest coordinate magnitude of the two triangles' corners.
fn magnitude(t1: &Triangle, t2: &Triangle) -> f32 {
    [t1.a, t1.b, t1.c, t2.a, t2.b, t2.c]
        .iter()
        .fold(0.0f32, |m, p| m.max(p.abs().max_element()))
}

/// Whether two triangles in one plane overlap with positive area: no edge direction of
/// either separates them, touching (within about 2⁻²⁰ of the coordinates' magnitude)
/// counting as separated. Projected onto the plane of `t1`'s two minor normal axes.
fn overlap_with_area(t1: &Triangle, t2: &Triangle) -> bool {
    let n = t1.normal();
    let flat = |p: Vec3| onto_dominant_plane(n, p);
    let p = [t1.a, t1.b, t1.c].map(flat);
    let q = [t2.a, t2.b, t2.c].map(flat);
    let tol = magnitude(t1, t2) * (1.0 / 1_048_576.0);
    let separates = |from: Vec2, to: Vec2| {
        let edge = to - from;
        let axis = Vec2::new(-edge.y, edge.x);
        let reach = tol * axis.abs().max_element() * 2.0;
        let span = |pts: &[Vec2; 3]| {
            pts.iter()
                .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), x| {
                    let s = axis.dot(*x);
                    (lo.min(s), hi.max(s))
                })
        };
        let ((lo1, hi1), (lo2, hi2)) = (span(&p), span(&q));
        hi1 <= lo2 + reach || hi2 <= lo1 + reach
    };
    let edges = |t: &[Vec2; 3]| {
        let [a, b, c] = *t;
        [(a, b), (b, c), (c, a)]
    };
    !edges(&p)
        .into_iter()
        .chain(edges(&q))
        .any(|(from, to)| separates(from, to))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::intersect_triangle_triangle;

    fn v(x: f32, y: f32, z: f32) -> Vec3 {
        Vec3::new(x, y, z)
    }

    /// Runs the rule on two triangles given by corner indices into `points`.
    fn meets(points: &[Vec3], i1: [u32; 3], i2: [u32; 3]) -> bool {
        let tri = |i: [u32; 3]| {
            let [a, b, c] = i.map(|k| points[k as usize]);
            Triangle::new(a, b, c)
        };
        let (t1, t2) = (tri(i1), tri(i2));
        meets_beyond_shared(&t1, &t2, i1, i2, intersect_triangle_triangle(&t1, &t2))
    }

    #[test]
    fn an_edge_shared_in_a_flat_sheet_or_at_a_fold_is_no_intersection() {
        // 0–1 is the shared edge; 2 lies on one side, 3 on the other, 4 above the edge.
        let p = [
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(0.5, 1.0, 0.0),
            v(0.5, -1.0, 0.0),
            v(0.5, 0.0, 1.0),
        ];
        assert!(!meets(&p, [0, 1, 2], [1, 0, 3]), "flat");
        assert!(!meets(&p, [0, 1, 2], [1, 0, 4]), "folded at a right angle");
    }

    #[test]
    fn a_neighbour_folded_onto_its_edge_partner_intersects() {
        // Both on the same side of the shared edge 0–1, in one plane: folded flat over.
        let p = [
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(0.5, 1.0, 0.0),
            v(0.4, 0.6, 0.0),
        ];
        assert!(meets(&p, [0, 1, 2], [1, 0, 3]));
    }

    #[test]
    fn a_shared_corner_alone_is_no_intersection_but_crossing_beyond_it_is() {
        let p = [
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(0.0, 1.0, 0.0),
            v(-1.0, 0.0, 0.5),
            v(-1.0, -1.0, 0.5),
            // Through the first triangle's face: from below its plane to above.
            v(0.6, 0.2, -0.5),
            v(0.2, 0.6, 0.5),
        ];
        assert!(!meets(&p, [0, 1, 2], [0, 3, 4]), "touching at the corner");
        assert!(
            meets(&p, [0, 1, 2], [0, 5, 6]),
            "crossing beyond the corner"
        );
    }

    #[test]
    fn coplanar_neighbours_at_a_corner_count_only_when_they_overlap_with_area() {
        let p = [
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(0.0, 1.0, 0.0),
            v(-1.0, 0.0, 0.0),
            v(0.0, -1.0, 0.0),
            v(1.0, 1.0, 0.0),
        ];
        assert!(!meets(&p, [0, 1, 2], [0, 3, 4]), "opposite quadrants");
        assert!(
            !meets(&p, [0, 1, 2], [0, 4, 1]),
            "touching along an edge line"
        );
        assert!(meets(&p, [0, 1, 2], [0, 1, 5]), "overlapping wedges");
    }

    #[test]
    fn triangles_sharing_nothing_count_when_they_touch() {
        let p = [
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(0.0, 1.0, 0.0),
            // A corner on the first triangle's face.
            v(0.2, 0.2, 0.0),
            v(0.2, 0.2, 1.0),
            v(1.0, 1.0, 1.0),
        ];
        assert!(meets(&p, [0, 1, 2], [3, 4, 5]));
    }

    #[test]
    fn corners_at_one_position_are_shared_whatever_their_indices() {
        // An unwelded seam: 3 and 4 repeat 0 and 1.
        let p = [
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(0.5, 1.0, 0.0),
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(0.5, -1.0, 0.2),
        ];
        assert!(!meets(&p, [0, 1, 2], [4, 3, 5]));
    }

    #[test]
    fn degenerate_and_nan_triangles_meet_nothing() {
        let p = [
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(0.0, 1.0, 0.0),
            v(2.0, 0.0, 0.0),
            v(f32::NAN, 0.0, 0.0),
        ];
        assert!(!meets(&p, [0, 1, 2], [0, 1, 3]), "a segment");
        assert!(!meets(&p, [0, 1, 2], [4, 1, 2]), "NaN");
    }
}
