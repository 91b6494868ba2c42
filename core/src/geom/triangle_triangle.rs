use glam::{Vec2, Vec3};

use super::point_in_triangle_2d;
use super::triangles_meet::segments_meet_2d;
use crate::math::{Triangle, cross, dot};

/// How two triangles intersect.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TriangleTriangle {
    /// No common point.
    Disjoint,
    /// The triangles cross (or touch) along the segment `[a, b]` (`a == b` when they touch at a
    /// single point). `a` is the end with the smaller coordinate along the line
    /// `normal₁ × normal₂`.
    Segment {
        /// First end.
        a: Vec3,
        /// Second end.
        b: Vec3,
    },
    /// Both triangles lie in one plane (or in planes within about 0.06° of parallel, each
    /// touching the other's) and overlap in it (touching counts).
    Coplanar,
}

/// The signed distances (scaled by `|n|`) of `t`'s corners to the plane `n · x = n · origin`,
/// with values within `eps` snapped to exactly zero so that near-coplanar input is decided
/// consistently.
fn plane_distances(t: &Triangle, n: Vec3, origin: Vec3, eps: f32) -> [f32; 3] {
    [t.a, t.b, t.c].map(|v| {
        let d = dot(n, v - origin);
        if d.abs() <= eps { 0.0 } else { d }
    })
}

/// The points where the plane (given by `d`, the distances of `t`'s corners) cuts triangle `t`:
/// corners on the plane and edge crossings. At most two for a triangle that straddles or
/// touches the plane and is not in it.
fn plane_cut(t: &Triangle, d: [f32; 3]) -> ([Vec3; 2], usize) {
    let [d0, d1, d2] = d;
    let edges = [(t.a, t.b, d0, d1), (t.b, t.c, d1, d2), (t.c, t.a, d2, d0)];
    let mut out = [Vec3::ZERO; 2];
    let mut n = 0;
    let mut push = |p: Vec3| {
        if let Some(slot) = out.get_mut(n) {
            *slot = p;
            n += 1;
        }
    };
    for (vi, vj, di, dj) in edges {
        if di == 0.0 {
            push(vi);
        }
        if (di < 0.0 && dj > 0.0) || (di > 0.0 && dj < 0.0) {
            push(vi + (vj - vi) * (di / (di - dj)));
        }
    }
    (out, n)
}

/// The sine of the angle under which two planes count as parallel (about 0.06°).
const NEAR_PARALLEL: f32 = 1e-3;

fn same_strict_side(d: [f32; 3]) -> bool {
    (d[0] > 0.0 && d[1] > 0.0 && d[2] > 0.0) || (d[0] < 0.0 && d[1] < 0.0 && d[2] < 0.0)
}

/// Intersects two triangles.
///
/// Both triangles are cut by the other's plane; the two cuts lie on the line where the planes
/// meet, and their overlap on that line is the intersection segment (the interval approach of
/// Möller 1997, "A Fast Triangle-Triangle Intersection Test", written as explicit cuts). Corner
/// distances within about 2⁻²¹ of the coordinate magnitude of a plane are treated as on it.
/// Coplanar triangles, and triangles whose planes are within about 0.06° of parallel and
/// each touch the other's plane (their common line is too ill-conditioned to use), are
/// projected on the first plane's dominant axes and tested for overlap with edge crossings
/// and containment.
///
/// Degenerate triangles (segments and points) and non-finite input are reported as
/// [`TriangleTriangle::Disjoint`].
///
/// ```
/// use meshq::{geom::{intersect_triangle_triangle, TriangleTriangle}, math::{Triangle, Vec3}};
/// let floor = Triangle::new(Vec3::new(-2.0, 0.0, -2.0), Vec3::new(2.0, 0.0, -2.0), Vec3::new(0.0, 0.0, 3.0));
/// let wall = Triangle::new(Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, -1.0, 0.0), Vec3::new(0.0, 1.0, 0.0));
/// assert!(matches!(intersect_triangle_triangle(&floor, &wall), TriangleTriangle::Segment { .. }));
/// ```
#[must_use]
pub fn intersect_triangle_triangle(t1: &Triangle, t2: &Triangle) -> TriangleTriangle {
    let finite = |t: &Triangle| t.a.is_finite() && t.b.is_finite() && t.c.is_finite();
    if !finite(t1) || !finite(t2) || t1.is_degenerate() || t2.is_degenerate() {
        return TriangleTriangle::Disjoint;
    }
    if !t1.bounds().overlaps(&t2.bounds()) {
        return TriangleTriangle::Disjoint;
    }
    let n1 = t1.normal();
    let n2 = t2.normal();
    let scale = [t1.a, t1.b, t1.c, t2.a, t2.b, t2.c]
        .iter()
        .fold(0.0f32, |m, v| m.max(v.abs().max_element()));
    let tol = scale * (1.0 / 2_097_152.0);
    let d1 = plane_distances(t1, n2, t2.a, tol * n2.length());
    if same_strict_side(d1) {
        return TriangleTriangle::Disjoint;
    }
    if d1 == [0.0; 3] {
        return if coplanar_overlap(t1, t2, n1) {
            TriangleTriangle::Coplanar
        } else {
            TriangleTriangle::Disjoint
        };
    }
    let d2 = plane_distances(t2, n1, t1.a, tol * n1.length());
    if same_strict_side(d2) {
        return TriangleTriangle::Disjoint;
    }
    let line = cross(n1, n2);
    // Planes within about 0.06° of parallel meet on a line too ill-conditioned to place the
    // cuts on (the snapping above moves a corner farther along it than the triangles are
    // wide): such a pair, each touching the other's plane, is judged in the plane.
    if dot(line, line) <= NEAR_PARALLEL * NEAR_PARALLEL * dot(n1, n1) * dot(n2, n2) {
        return if coplanar_overlap(t1, t2, n1) {
            TriangleTriangle::Coplanar
        } else {
            TriangleTriangle::Disjoint
        };
    }
    let (cut1, k1) = plane_cut(t1, d1);
    let (cut2, k2) = plane_cut(t2, d2);
    let (Some(cut1), Some(cut2)) = (cut1.get(..k1), cut2.get(..k2)) else {
        return TriangleTriangle::Disjoint;
    };
    let interval = |pts: &[Vec3]| {
        pts.iter()
            .fold(None, |acc: Option<((f32, Vec3), (f32, Vec3))>, &p| {
                let s = dot(line, p);
                Some(match acc {
                    None => ((s, p), (s, p)),
                    Some((lo, hi)) => (
                        if s < lo.0 { (s, p) } else { lo },
                        if s > hi.0 { (s, p) } else { hi },
                    ),
                })
            })
    };
    let (Some((lo1, hi1)), Some((lo2, hi2))) = (interval(cut1), interval(cut2)) else {
        return TriangleTriangle::Disjoint;
    };
    let lo = if lo1.0 >= lo2.0 { lo1 } else { lo2 };
    let hi = if hi1.0 <= hi2.0 { hi1 } else { hi2 };
    if lo.0 > hi.0 {
        return TriangleTriangle::Disjoint;
    }
    TriangleTriangle::Segment { a: lo.1, b: hi.1 }
}

/// `v` projected onto the coordinate plane most nearly parallel to the plane with normal `n`
/// (the normal's dominant axis dropped: the projection with the largest area), keeping the
/// orientation of the other two axes in cyclic order.
fn onto_dominant_plane(n: Vec3, v: Vec3) -> Vec2 {
    let a = n.abs();
    if a.x >= a.y && a.x >= a.z {
        Vec2::new(v.y, v.z)
    } else if a.y >= a.z {
        Vec2::new(v.z, v.x)
    } else {
        Vec2::new(v.x, v.y)
    }
}

/// Overlap of two triangles known to share the plane with normal `n`, decided in 2D (edge
/// crossings on exact orientation signs of the projected corners, which dropping a coordinate
/// leaves exact).
fn coplanar_overlap(t1: &Triangle, t2: &Triangle, n: Vec3) -> bool {
    let project = |v: Vec3| onto_dominant_plane(n, v);
    let [p0, p1, p2] = [t1.a, t1.b, t1.c].map(project);
    let [q0, q1, q2] = [t2.a, t2.b, t2.c].map(project);
    for (a, b) in [(p0, p1), (p1, p2), (p2, p0)] {
        for (c, d) in [(q0, q1), (q1, q2), (q2, q0)] {
            if segments_meet_2d(a, b, c, d) {
                return true;
            }
        }
    }
    point_in_triangle_2d(p0, q0, q1, q2) || point_in_triangle_2d(q0, p0, p1, p2)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn floor() -> Triangle {
        Triangle::new(
            Vec3::new(-2.0, 0.0, -2.0),
            Vec3::new(2.0, 0.0, -2.0),
            Vec3::new(0.0, 0.0, 3.0),
        )
    }

    #[test]
    fn crossing_gives_the_exact_segment() {
        let wall = Triangle::new(
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::new(1.0, -1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        );
        let (lo, hi) = (Vec3::new(-0.5, 0.0, 0.0), Vec3::new(0.5, 0.0, 0.0));
        let got = intersect_triangle_triangle(&floor(), &wall);
        assert!(
            got == TriangleTriangle::Segment { a: lo, b: hi }
                || got == TriangleTriangle::Segment { a: hi, b: lo },
            "{got:?}"
        );
        // Symmetric in its arguments as a set of points.
        assert!(matches!(
            intersect_triangle_triangle(&wall, &floor()),
            TriangleTriangle::Segment { .. }
        ));
    }

    #[test]
    fn touching_at_a_corner_is_a_point() {
        let above = Triangle::new(
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 2.0, 0.0),
            Vec3::new(-1.0, 2.0, 0.5),
        );
        assert_eq!(
            intersect_triangle_triangle(&floor(), &above),
            TriangleTriangle::Segment {
                a: Vec3::ZERO,
                b: Vec3::ZERO
            }
        );
    }

    #[test]
    fn separated_by_a_plane_or_on_the_line_but_apart() {
        let high = Triangle::new(
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(1.0, 2.0, 0.0),
            Vec3::new(-1.0, 2.0, 0.5),
        );
        assert_eq!(
            intersect_triangle_triangle(&floor(), &high),
            TriangleTriangle::Disjoint
        );
        // Crosses the floor's plane, but outside the floor triangle.
        let far = Triangle::new(
            Vec3::new(5.0, -1.0, 0.0),
            Vec3::new(7.0, -1.0, 0.0),
            Vec3::new(6.0, 1.0, 0.0),
        );
        assert_eq!(
            intersect_triangle_triangle(&floor(), &far),
            TriangleTriangle::Disjoint
        );
    }

    #[test]
    fn nearly_coplanar_triangles_apart_in_their_plane_do_not_meet() {
        // Two triangles of a flat strip (from fandisk), three hundred-thousandths out of one
        // plane, with a triangle's width between them: their planes' line is ill-conditioned,
        // and cutting along it once reported a touch.
        let t1 = Triangle::new(
            Vec3::new(1.68912, 15.3804, -1.37652),
            Vec3::new(1.68912, 15.3644, -1.47466),
            Vec3::new(1.58976, 15.3804, -1.37655),
        );
        let t2 = Triangle::new(
            Vec3::new(1.4904, 15.3644, -1.47466),
            Vec3::new(1.4904, 15.3804, -1.37657),
            Vec3::new(1.58976, 15.3644, -1.47466),
        );
        assert_eq!(
            intersect_triangle_triangle(&t1, &t2),
            TriangleTriangle::Disjoint
        );
        assert_eq!(
            intersect_triangle_triangle(&t2, &t1),
            TriangleTriangle::Disjoint
        );
        // Slid over each other in the plane, they overlap.
        let shift = Vec3::new(0.15, 0.0, 0.0);
        let t3 = Triangle::new(t2.a + shift, t2.b + shift, t2.c + shift);
        assert_eq!(
            intersect_triangle_triangle(&t1, &t3),
            TriangleTriangle::Coplanar
        );
    }

    #[test]
    fn coplanar_overlap_containment_and_separation() {
        let small = Triangle::new(
            Vec3::new(-0.1, 0.0, 0.0),
            Vec3::new(0.1, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 0.1),
        );
        assert_eq!(
            intersect_triangle_triangle(&floor(), &small),
            TriangleTriangle::Coplanar
        );
        assert_eq!(
            intersect_triangle_triangle(&small, &floor()),
            TriangleTriangle::Coplanar
        );
        let crossing = Triangle::new(
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(4.0, 0.0, 0.0),
            Vec3::new(3.0, 0.0, 1.0),
        );
        assert_eq!(
            intersect_triangle_triangle(&floor(), &crossing),
            TriangleTriangle::Coplanar
        );
        let apart = Triangle::new(
            Vec3::new(3.0, 0.0, 3.0),
            Vec3::new(4.0, 0.0, 3.0),
            Vec3::new(3.0, 0.0, 4.0),
        );
        assert_eq!(
            intersect_triangle_triangle(&floor(), &apart),
            TriangleTriangle::Disjoint
        );
    }

    #[test]
    fn degenerate_and_nan_are_disjoint() {
        let line = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::X * 2.0);
        assert_eq!(
            intersect_triangle_triangle(&floor(), &line),
            TriangleTriangle::Disjoint
        );
        let nan = Triangle::new(Vec3::NAN, Vec3::X, Vec3::Y);
        assert_eq!(
            intersect_triangle_triangle(&floor(), &nan),
            TriangleTriangle::Disjoint
        );
    }
}
