//! Exact yes/no decisions between triangles and segments: decided by the signs of exact
//! orientation determinants ([`exact_orientation`](super::exact_orientation)), so a touch at
//! one point, a shared edge and an exactly coplanar overlap are told apart from a miss by any
//! margin, on every target alike.

use glam::{Vec2, Vec3};

use super::exact_orientation::{dropped, orient2d, orient3d, projection_axis};
use crate::math::Triangle;

/// The corners of `t`, or `None` when one is not finite or they are collinear (exactly: a
/// triangle without area).
pub(crate) fn proper_corners(t: &Triangle) -> Option<[Vec3; 3]> {
    let c = [t.a, t.b, t.c];
    (c.iter().all(|v| v.is_finite()) && projection_axis(c).is_some()).then_some(c)
}

/// True when `x` lies within the box of `a` and `b` (closed; exact comparisons).
fn within_box_2d(a: Vec2, b: Vec2, x: Vec2) -> bool {
    x.x >= a.x.min(b.x) && x.x <= a.x.max(b.x) && x.y >= a.y.min(b.y) && x.y <= a.y.max(b.y)
}

/// Whether the closed segments `[a, b]` and `[c, d]` of the plane share a point.
pub(super) fn segments_meet_2d(a: Vec2, b: Vec2, c: Vec2, d: Vec2) -> bool {
    let o1 = orient2d(a, b, c);
    let o2 = orient2d(a, b, d);
    let o3 = orient2d(c, d, a);
    let o4 = orient2d(c, d, b);
    if o1 * o2 < 0 && o3 * o4 < 0 {
        return true;
    }
    (o1 == 0 && within_box_2d(a, b, c))
        || (o2 == 0 && within_box_2d(a, b, d))
        || (o3 == 0 && within_box_2d(c, d, a))
        || (o4 == 0 && within_box_2d(c, d, b))
}

/// Whether `x` lies in the closed triangle `t` of the plane (`t` with area).
fn in_triangle_2d(x: Vec2, t: [Vec2; 3]) -> bool {
    let [a, b, c] = t;
    let s = [orient2d(a, b, x), orient2d(b, c, x), orient2d(c, a, x)];
    s.iter().all(|&o| o >= 0) || s.iter().all(|&o| o <= 0)
}

/// Whether the closed segment `[p, q]` (a point when `p == q`) meets the closed triangle `t`,
/// whose corners must not be collinear ([`proper_corners`]).
pub(crate) fn segment_meets_triangle(p: Vec3, q: Vec3, t: [Vec3; 3]) -> bool {
    let [a, b, c] = t;
    let (sp, sq) = (orient3d(a, b, c, p), orient3d(a, b, c, q));
    if sp == sq && sp != 0 {
        return false;
    }
    if sp == 0 && sq == 0 {
        // In the triangle's plane: decided in a projection that keeps its area.
        let Some(axis) = projection_axis(t) else {
            return false;
        };
        let flat = t.map(|v| dropped(v, axis));
        let (p2, q2) = (dropped(p, axis), dropped(q, axis));
        let [fa, fb, fc] = flat;
        return in_triangle_2d(p2, flat)
            || in_triangle_2d(q2, flat)
            || segments_meet_2d(p2, q2, fa, fb)
            || segments_meet_2d(p2, q2, fb, fc)
            || segments_meet_2d(p2, q2, fc, fa);
    }
    // The segment meets the plane at one point, inside the triangle exactly when the line
    // through it passes every edge on the same side (or touches one).
    let s = [
        orient3d(p, q, a, b),
        orient3d(p, q, b, c),
        orient3d(p, q, c, a),
    ];
    s.iter().all(|&o| o >= 0) || s.iter().all(|&o| o <= 0)
}

/// Whether two closed triangles (both with area) share a point: exactly when an edge of one
/// meets the other (the ends of their common segment, or of their common region in one
/// plane, lie on edges).
pub(crate) fn proper_triangles_meet(t1: [Vec3; 3], t2: [Vec3; 3]) -> bool {
    let strictly_apart = |plane: [Vec3; 3], corners: [Vec3; 3]| {
        let [a, b, c] = plane;
        let s = corners.map(|v| orient3d(a, b, c, v));
        s.iter().all(|&o| o > 0) || s.iter().all(|&o| o < 0)
    };
    if strictly_apart(t2, t1) || strictly_apart(t1, t2) {
        return false;
    }
    let edges = |t: [Vec3; 3]| {
        let [a, b, c] = t;
        [(a, b), (b, c), (c, a)]
    };
    edges(t1)
        .into_iter()
        .any(|(p, q)| segment_meets_triangle(p, q, t2))
        || edges(t2)
            .into_iter()
            .any(|(p, q)| segment_meets_triangle(p, q, t1))
}

/// Whether two closed triangles share a point, decided exactly on their `f32` corners:
/// touching at one point or along an edge counts; a miss by the smallest representable
/// distance does not. Triangles with collinear corners (no area) or a non-finite corner
/// meet nothing.
///
/// [`intersect_triangle_triangle`](super::intersect_triangle_triangle) also says where, and
/// treats corners within about 2⁻²¹ of the coordinates' magnitude of the other's plane as on
/// it; the two can differ only on such near contacts.
///
/// ```
/// use meshq::{geom::triangles_meet, math::{Triangle, Vec3}};
/// let floor = Triangle::new(Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0));
/// let on_it = Triangle::new(Vec3::new(0.2, 0.2, 0.0), Vec3::new(0.3, 0.2, 1.0), Vec3::new(0.2, 0.3, 1.0));
/// let above = Triangle::new(Vec3::new(0.2, 0.2, 1e-30), Vec3::new(0.3, 0.2, 1.0), Vec3::new(0.2, 0.3, 1.0));
/// assert!(triangles_meet(&floor, &on_it));
/// assert!(!triangles_meet(&floor, &above));
/// ```
#[must_use]
pub fn triangles_meet(t1: &Triangle, t2: &Triangle) -> bool {
    let (Some(c1), Some(c2)) = (proper_corners(t1), proper_corners(t2)) else {
        return false;
    };
    t1.bounds().overlaps(&t2.bounds()) && proper_triangles_meet(c1, c2)
}
