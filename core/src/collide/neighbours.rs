//! When two triangles of one mesh that share corners count as intersecting: only when they
//! meet somewhere besides what they share, decided exactly
//! ([`triangles_meet`](crate::geom::triangles_meet)'s predicates).

use glam::Vec3;

use crate::geom::exact_orientation::{dropped, orient2d, orient3d, projection_axis};
use crate::geom::triangles_meet::{proper_corners, proper_triangles_meet, segment_meets_triangle};
use crate::math::Triangle;

/// Whether triangles `t1` and `t2` of one mesh, with corner indices `i1` and `i2`, meet
/// somewhere besides what they share, decided exactly on their `f32` corners:
///
/// - sharing no corner: whenever they meet at all (touching counts);
/// - sharing one corner `v`: when they meet anywhere else, which is exactly when the edge of
///   either opposite `v` meets the other triangle (crossing beyond `v`, or in one plane with
///   overlapping wedges or edges running along each other);
/// - sharing an edge: only when they lie in one plane with the other corners on the same side
///   of the edge (folded onto each other); otherwise they meet on the edge alone;
/// - sharing all three corners (a doubled face): always.
///
/// A corner is shared when both triangles use its vertex index, or have a corner at exactly
/// its position, so the seams of an unwelded mesh are neighbours too. Triangles without area
/// (collinear corners) or with a non-finite corner meet nothing.
pub(crate) fn meets_beyond_shared(
    t1: &Triangle,
    t2: &Triangle,
    i1: [u32; 3],
    i2: [u32; 3],
) -> bool {
    let (Some(c1), Some(c2)) = (proper_corners(t1), proper_corners(t2)) else {
        return false;
    };
    if !t1.bounds().overlaps(&t2.bounds()) {
        return false;
    }
    // For each corner of t1, the corner of t2 it is (by index or position), if any.
    let partner = |k: usize| {
        let (i, p) = (i1.get(k).copied(), c1.get(k).copied());
        (0..3).find(|&m| {
            (i.is_some() && i2.get(m).copied() == i) || (p.is_some() && c2.get(m).copied() == p)
        })
    };
    let matched = [partner(0), partner(1), partner(2)];
    let shared = matched.iter().flatten().count();
    let corner = |c: [Vec3; 3], k: usize| c.get(k).copied().unwrap_or(Vec3::ZERO);
    match shared {
        0 => proper_triangles_meet(c1, c2),
        1 => {
            let (Some(k1), Some(Some(k2))) = (
                matched.iter().position(Option::is_some),
                matched.iter().find(|m| m.is_some()),
            ) else {
                return false;
            };
            let opposite =
                |c: [Vec3; 3], k: usize| (corner(c, (k + 1) % 3), corner(c, (k + 2) % 3));
            let (p1, q1) = opposite(c1, k1);
            let (p2, q2) = opposite(c2, *k2);
            segment_meets_triangle(p1, q1, c2) || segment_meets_triangle(p2, q2, c1)
        }
        2 => {
            let Some(free1) = matched.iter().position(Option::is_none) else {
                return false;
            };
            let Some(free2) = (0..3).find(|m| !matched.contains(&Some(*m))) else {
                return false;
            };
            let (p, q) = (corner(c1, (free1 + 1) % 3), corner(c1, (free1 + 2) % 3));
            let (r1, r2) = (corner(c1, free1), corner(c2, free2));
            if orient3d(p, q, r1, r2) != 0 {
                return false;
            }
            // In one plane: folded over when both free corners lie on one side of the edge,
            // seen in a projection that keeps t1's area (and so t2's).
            let Some(axis) = projection_axis(c1) else {
                return false;
            };
            let side = |r: Vec3| orient2d(dropped(p, axis), dropped(q, axis), dropped(r, axis));
            side(r1) == side(r2)
        }
        _ => true,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
        meets_beyond_shared(&t1, &t2, i1, i2)
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
