use glam::{Vec2, Vec3};

use super::closest_point_segment;
use crate::math::{ClosestPoint, Triangle, TriangleFeature, cross, dot, unit_scale_of_squares};

/// The point of triangle `tri` closest to `p`, with its barycentrics and feature.
///
/// Classifies `p` against the Voronoi regions of the corners, the edges and the face (the
/// region walk of Ericson, *Real-Time Collision Detection*, §5.1.5), with no square roots.
/// On a sliver (twice its area under an eighth of its longest edge squared) the face's
/// signed areas are triple products with a normal computed across the first edge, and a
/// point over the face goes to the foot of its perpendicular, so the point and the distance
/// are right to within a few units of rounding of the coordinates on every shape, needles
/// and caps included. The result's `tri` is 0; `distance_squared` is
/// `|p − point|²`. Barycentrics follow the crate convention: `point ≈ (1 − u − v)·a + u·b + v·c`.
///
/// A degenerate triangle (a segment or a point) is handled as the union of its edges; its
/// feature is then an edge or a corner, never the face.
///
/// ```
/// use meshq::{geom::closest_point_triangle, math::{Triangle, TriangleFeature, Vec3}};
/// let tri = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
/// let c = closest_point_triangle(Vec3::new(0.25, 0.25, 2.0), &tri);
/// assert_eq!((c.point, c.distance_squared, c.feature), (Vec3::new(0.25, 0.25, 0.0), 4.0, TriangleFeature::Face));
/// ```
#[must_use]
pub fn closest_point_triangle(p: Vec3, tri: &Triangle) -> ClosestPoint {
    if tri.is_degenerate() {
        return closest_point_on_edges(p, tri);
    }
    let (point, u, v, feature) = closest_point_regions(p, tri.a, tri.b, tri.c);
    let d = p - point;
    ClosestPoint {
        point,
        tri: 0,
        u,
        v,
        distance_squared: dot(d, d),
        feature,
    }
}

/// The point of the 2D triangle `a, b, c` (either winding) closest to `p`, with the same
/// barycentrics and feature as [`closest_point_triangle`] (the triangle is embedded at `z = 0`,
/// which leaves every product and sum unchanged).
///
/// Returns `(point, u, v, feature)`.
#[must_use]
pub fn closest_point_triangle_2d(
    p: Vec2,
    a: Vec2,
    b: Vec2,
    c: Vec2,
) -> (Vec2, f32, f32, TriangleFeature) {
    let tri = Triangle::new(a.extend(0.0), b.extend(0.0), c.extend(0.0));
    let r = closest_point_triangle(p.extend(0.0), &tri);
    (r.point.truncate(), r.u, r.v, r.feature)
}

/// `solve(p, tri)` at a scale where products of four lengths stay inside `f32`: as given when
/// the triangle's edges lie within 2^±20 and the point within 2⁴⁰ of its first corner,
/// otherwise on the point and triangle multiplied by the power of two that brings the edges
/// near 1 (or the point's offset under 2⁶⁰), with the point scaled back and its squared
/// distance measured again. Multiplying by a power of two rounds nothing.
pub(super) fn at_working_scale(
    p: Vec3,
    tri: &Triangle,
    solve: impl Fn(Vec3, &Triangle) -> ClosestPoint,
) -> ClosestPoint {
    let size = |v: Vec3| exponent(v.x.abs().max(v.y.abs()).max(v.z.abs()));
    let edges = size(tri.b - tri.a)
        .max(size(tri.c - tri.b))
        .max(size(tri.a - tri.c));
    let reach = size(p - tri.a);
    if (-20..=20).contains(&edges) && reach <= 40 {
        return solve(p, tri);
    }
    let s = f32::from_bits(((127 - edges.max(reach - 60)).clamp(1, 254) as u32) << 23);
    let scaled = Triangle::new(tri.a * s, tri.b * s, tri.c * s);
    let mut c = solve(p * s, &scaled);
    c.point *= 1.0 / s;
    let d = p - c.point;
    c.distance_squared = dot(d, d);
    c
}

/// The unbiased binary exponent of `x ≥ 0` (−127 for zero, 128 for infinity and NaN).
fn exponent(x: f32) -> i32 {
    ((x.to_bits() >> 23) & 0xff) as i32 - 127
}

/// The Voronoi-region walk for a non-degenerate triangle. Returns `(point, u, v, feature)`.
///
/// Inlined into the hot scalar loops where code size is free; on bare metal one copy of the walk
/// is shared, for the firmware's flash budget. (Inlining never changes a result: no operation is
/// fused or reordered.)
///
/// Works at any size: where the walk's products of four lengths would overflow or underflow
/// `f32` (see [`in_range`]), it runs on the triangle and point scaled by a power of two and
/// scales the point back, which rounds nothing, so the answer is the one an `f32` with an
/// unbounded exponent would give.
#[inline(always)]
pub(crate) fn closest_point_regions(
    p: Vec3,
    a: Vec3,
    b: Vec3,
    c: Vec3,
) -> (Vec3, f32, f32, TriangleFeature) {
    regions(p, a, b, c, true)
}

/// Whether the walk's products stay within `f32` for a triangle whose longest edge squared is
/// `longest` and a point at squared distance `reach` from its first corner: every product of
/// two of its dot products is at most about `longest · (reach + longest)` and its sliver
/// normal's square `longest²`, so both are kept well inside `[2⁻¹⁰⁰, 2¹¹²]`. A zero `longest`
/// (every corner at one point) never reaches a product. NaN counts as in range: the walk then
/// gives what it gives, as before.
#[inline(always)]
pub(crate) fn in_range(longest: f32, reach: f32) -> bool {
    !(longest > MAX_SQUARED
        || (longest < MIN_SQUARED && longest > 0.0)
        || reach > MAX_REACH_SQUARED)
}

/// Largest longest-edge-squared the walk takes as it is (2⁵⁰).
pub(crate) const MAX_SQUARED: f32 = 1_125_899_906_842_624.0;
/// Smallest nonzero longest-edge-squared the walk takes as it is (2⁻⁵⁰).
pub(crate) const MIN_SQUARED: f32 = 1.0 / 1_125_899_906_842_624.0;
/// Largest squared distance from the first corner the walk takes as it is (2⁶⁰).
pub(crate) const MAX_REACH_SQUARED: f32 = 1_152_921_504_606_846_976.0;

/// The walk on `p, a, b, c` scaled by the power of two that brings its products near 1, with
/// the point scaled back.
#[inline(never)]
fn rescaled(
    p: Vec3,
    a: Vec3,
    b: Vec3,
    c: Vec3,
    longest: f32,
    reach: f32,
) -> (Vec3, f32, f32, TriangleFeature) {
    let s = unit_scale_of_squares(longest, reach.max(longest));
    let (q, u, v, feature) = regions(p * s, a * s, b * s, c * s, false);
    (q * (1.0 / s), u, v, feature)
}

/// The walk itself; `checked` sends a triangle out of [`in_range`] to [`rescaled`], which runs
/// the walk once more, unchecked (a flag, not a type parameter: bare metal keeps one copy).
#[cfg_attr(not(target_os = "none"), inline(always))]
#[cfg_attr(target_os = "none", inline(never))]
fn regions(p: Vec3, a: Vec3, b: Vec3, c: Vec3, checked: bool) -> (Vec3, f32, f32, TriangleFeature) {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = dot(ab, ap);
    let d2 = dot(ac, ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, 0.0, 0.0, TriangleFeature::Vertex(0));
    }
    let bp = p - b;
    let d3 = dot(ab, bp);
    let d4 = dot(ac, bp);
    if d3 >= 0.0 && d4 <= d3 {
        return (b, 1.0, 0.0, TriangleFeature::Vertex(1));
    }
    // `vc`, `vb` and `va` are twice the signed areas of `p` with each edge, times `|n|`.
    // Ericson writes them as differences of products of the dots above (Lagrange's
    // identity), exact to rounding of the coordinates on a fair triangle. On a sliver both
    // products are large and nearly equal, so in f32 the difference can take the wrong sign
    // and a point over the face is measured to an edge; there they are triple products with
    // a normal across the first edge instead (`n · (edge × offset)`: the cross product is
    // exact to rounding of its own size, and an error in `n`'s direction counts only to
    // second order).
    let cp = p - c;
    let d5 = dot(ab, cp);
    let d6 = dot(ac, cp);
    let e = d4 - d3;
    let f = d5 - d6;
    // `d1 − d3`, `d2 − d6` and `e + f` are the edges' squared lengths.
    let longest = (d1 - d3).max(d2 - d6).max(e + f);
    if checked {
        let reach = dot(ap, ap);
        if !in_range(longest, reach) {
            return rescaled(p, a, b, c, longest, reach);
        }
    }
    let n = sliver_normal(cross(ab, ac), longest, ab, ac);
    let vc = match n {
        Some(n) => dot(n, cross(ab, ap)),
        None => d1 * d4 - d3 * d2,
    };
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let s = d1 / (d1 - d3);
        return (a + ab * s, s, 0.0, TriangleFeature::Edge(0));
    }
    if d6 >= 0.0 && d5 <= d6 {
        return (c, 0.0, 1.0, TriangleFeature::Vertex(2));
    }
    let vb = match n {
        Some(n) => dot(n, cross(ap, ac)),
        None => d5 * d2 - d1 * d6,
    };
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let s = d2 / (d2 - d6);
        return (a + ac * s, 0.0, s, TriangleFeature::Edge(2));
    }
    let bc = c - b;
    let va = match n {
        Some(n) => dot(n, cross(bc, bp)),
        None => d3 * d6 - d5 * d4,
    };
    if va <= 0.0 && e >= 0.0 && f >= 0.0 {
        let s = e / (e + f);
        return (b + bc * s, 1.0 - s, s, TriangleFeature::Edge(1));
    }
    match n {
        // Over a sliver's face: the foot of the perpendicular. Rebuilt from the barycentrics
        // it would carry their rounding, a share of the sliver's long side.
        Some(n) => {
            let nn = dot(n, n);
            (
                p - n * (dot(n, ap) / nn),
                vb / nn,
                vc / nn,
                TriangleFeature::Face,
            )
        }
        None => {
            let inv = 1.0 / (va + vb + vc);
            let u = vb * inv;
            let v = vc * inv;
            (a + ab * u + ac * v, u, v, TriangleFeature::Face)
        }
    }
}

/// Twice the area over the longest edge squared under which a triangle counts as a sliver
/// (`1/8`: a smallest angle under about 7°). Above it the walk's differences of products
/// keep the point within two units of rounding of the coordinates (measured on random
/// triangles and points against `f64`).
pub(crate) const SLIVER: f32 = 1.0 / 8.0;

/// For a sliver (`|ab × ac|`, twice the area, under [`SLIVER`] times `longest`, the
/// longest edge squared), the normal [`normal_across`] computes; `None` for a fair triangle.
#[inline(always)]
fn sliver_normal(plain: Vec3, longest: f32, ab: Vec3, ac: Vec3) -> Option<Vec3> {
    let bound = longest * SLIVER;
    (dot(plain, plain) < bound * bound).then(|| normal_across(ab, ac))
}

/// The normal `ab × ac'` of the plane through edges `ab` and `ac`, where `ac'` is `ac` less its
/// part along `ab`. The same vector as `ab × ac` in exact arithmetic; in `f32` that cross
/// product rounds each coordinate by about `|ab|·|ac|`, which on a sliver (two edges nearly
/// parallel) is large beside the normal itself, and tilts it. Taking out the parallel part
/// first leaves an error along the normal or across `ab`, which tilts the plane only about
/// the line `ab`; every corner lies within the sliver's width of that line.
#[inline(always)]
fn normal_across(ab: Vec3, ac: Vec3) -> Vec3 {
    cross(ab, ac - ab * (dot(ab, ac) / dot(ab, ab)))
}

/// The nearest point of the three edges of `tri` (the first of equals in the order ab, bc,
/// ca): the answer for a zero-area triangle, and for a point whose projection falls outside
/// the face.
pub(super) fn closest_point_on_edges(p: Vec3, tri: &Triangle) -> ClosestPoint {
    let edges = [(tri.a, tri.b), (tri.b, tri.c), (tri.c, tri.a)];
    let mut best: Option<ClosestPoint> = None;
    for (i, (s, e)) in (0u8..).zip(edges) {
        let (q, t) = closest_point_segment(p, s, e);
        let d = p - q;
        let d2 = dot(d, d);
        if best.is_some_and(|b| !(d2 < b.distance_squared)) {
            continue;
        }
        let (u, v) = match i {
            0 => (t, 0.0),
            1 => (1.0 - t, t),
            _ => (0.0, 1.0 - t),
        };
        let feature = if t <= 0.0 {
            TriangleFeature::Vertex(i)
        } else if t >= 1.0 {
            TriangleFeature::Vertex((i + 1) % 3)
        } else {
            TriangleFeature::Edge(i)
        };
        best = Some(ClosestPoint {
            point: q,
            tri: 0,
            u,
            v,
            distance_squared: d2,
            feature,
        });
    }
    best.unwrap_or(ClosestPoint {
        point: tri.a,
        tri: 0,
        u: 0.0,
        v: 0.0,
        distance_squared: f32::NAN,
        feature: TriangleFeature::Vertex(0),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri() -> Triangle {
        Triangle::new(
            Vec3::ZERO,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
        )
    }

    #[test]
    fn every_voronoi_region() {
        let t = tri();
        let cases = [
            (
                Vec3::new(-1.0, -1.0, 1.0),
                Vec3::ZERO,
                TriangleFeature::Vertex(0),
            ),
            (
                Vec3::new(3.0, -1.0, 0.0),
                Vec3::new(2.0, 0.0, 0.0),
                TriangleFeature::Vertex(1),
            ),
            (
                Vec3::new(-1.0, 3.0, 0.0),
                Vec3::new(0.0, 2.0, 0.0),
                TriangleFeature::Vertex(2),
            ),
            (
                Vec3::new(1.0, -3.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                TriangleFeature::Edge(0),
            ),
            (
                Vec3::new(2.0, 2.0, 0.0),
                Vec3::new(1.0, 1.0, 0.0),
                TriangleFeature::Edge(1),
            ),
            (
                Vec3::new(-3.0, 1.0, 5.0),
                Vec3::new(0.0, 1.0, 0.0),
                TriangleFeature::Edge(2),
            ),
            (
                Vec3::new(0.5, 0.5, -3.0),
                Vec3::new(0.5, 0.5, 0.0),
                TriangleFeature::Face,
            ),
        ];
        for (p, q, f) in cases {
            let c = closest_point_triangle(p, &t);
            assert_eq!((c.point, c.feature), (q, f), "{p}");
            assert_eq!(c.distance_squared, (p - q).length_squared(), "{p}");
            let back = t.point_at(c.u, c.v);
            assert!((back - q).length() < 1e-6, "barycentrics of {p}");
        }
    }

    /// The walk at any size gives the unit-size answer scaled: a power of two rounds nothing,
    /// so triangles of 1e-12 to 1e15 (whose products of four lengths leave `f32`) and points
    /// up to 1e30 away answer exactly as at unit size. The unit-size answers are checked
    /// against an `f64` projection, so a walk that overflowed at every size would still fail.
    #[test]
    fn any_size_answers_as_unit_size() {
        let v = crate::test_floats::floats(0x5ca1e, 12 * 4_000);
        let mut rescaled = 0;
        for (i, x) in v.chunks_exact(12).enumerate() {
            let at = |k: usize| Vec3::new(x[k], x[k + 1], x[k + 2]);
            // Every third triangle a sliver; every fifth point far away.
            let c = if i % 3 == 0 {
                at(0) + (at(3) - at(0)) * 0.7 + at(6) * 1e-3
            } else {
                at(6)
            };
            let t = Triangle::new(at(0), at(3), c);
            let p = at(9) * if i % 5 == 0 { 1e6 } else { 2.0 };
            if t.is_degenerate() {
                continue;
            }
            let unit = closest_point_triangle(p, &t);
            let f64_distance = f64_point_triangle(p, &t);
            let got = f64::from(unit.distance_squared).sqrt();
            assert!(
                (got - f64_distance).abs() <= 1e-5 * (f64_distance + 1.0),
                "{t:?} {p}"
            );
            for k in [-40, -20, 20, 40, 48] {
                let s = 2f32.powi(k);
                let scaled = Triangle::new(t.a * s, t.b * s, t.c * s);
                let got = closest_point_triangle(p * s, &scaled);
                assert_eq!(got.point, unit.point * s, "{t:?} {p} at 2^{k}");
                assert_eq!((got.u, got.v, got.feature), (unit.u, unit.v, unit.feature));
                rescaled += 1;
            }
        }
        assert!(rescaled > 15_000);
        // A point 1e30 from a unit triangle: the nearest corner, at a squared distance past f32.
        let t = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
        let far = closest_point_triangle(Vec3::new(-1e30, -1e30, 0.0), &t);
        assert_eq!(
            (far.point, far.feature),
            (Vec3::ZERO, TriangleFeature::Vertex(0))
        );
    }

    /// The distance from `p` to `t` in `f64`, by projection onto the plane when the foot is
    /// inside and the nearest edge otherwise.
    fn f64_point_triangle(p: Vec3, t: &Triangle) -> f64 {
        type V = [f64; 3];
        let w = |v: Vec3| [f64::from(v.x), f64::from(v.y), f64::from(v.z)];
        let sub = |a: V, b: V| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let add = |a: V, b: V, s: f64| [a[0] + b[0] * s, a[1] + b[1] * s, a[2] + b[2] * s];
        let dot = |a: V, b: V| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let cross = |a: V, b: V| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let (p, a, b, c) = (w(p), w(t.a), w(t.b), w(t.c));
        let segment = |a: V, b: V| {
            let ab = sub(b, a);
            let s = (dot(sub(p, a), ab) / dot(ab, ab)).clamp(0.0, 1.0);
            let d = sub(p, add(a, ab, s));
            dot(d, d).sqrt()
        };
        let n = cross(sub(b, a), sub(c, a));
        let h = dot(sub(p, a), n) / dot(n, n);
        let foot = add(p, n, -h);
        let inside = [(a, b), (b, c), (c, a)]
            .iter()
            .all(|&(s, e)| dot(cross(sub(e, s), sub(foot, s)), n) >= 0.0);
        if inside {
            h.abs() * dot(n, n).sqrt()
        } else {
            segment(a, b).min(segment(b, c)).min(segment(c, a))
        }
    }

    #[test]
    fn degenerate_triangles_use_their_edges() {
        let line = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::X * 3.0);
        let c = closest_point_triangle(Vec3::new(2.0, 1.0, 0.0), &line);
        assert_eq!(
            (c.point, c.distance_squared),
            (Vec3::new(2.0, 0.0, 0.0), 1.0)
        );
        assert!(matches!(c.feature, TriangleFeature::Edge(_)));
        let point = Triangle::new(Vec3::ONE, Vec3::ONE, Vec3::ONE);
        let c = closest_point_triangle(Vec3::ZERO, &point);
        assert_eq!((c.point, c.distance_squared), (Vec3::ONE, 3.0));
        assert!(matches!(c.feature, TriangleFeature::Vertex(_)));
    }

    #[test]
    fn two_dimensional_variant_handles_either_winding() {
        let (a, b, c) = (Vec2::ZERO, Vec2::new(2.0, 0.0), Vec2::new(0.0, 2.0));
        for (a, b, c) in [(a, b, c), (a, c, b)] {
            let (q, _, _, f) = closest_point_triangle_2d(Vec2::new(2.0, 2.0), a, b, c);
            assert_eq!(q, Vec2::new(1.0, 1.0));
            assert!(matches!(f, TriangleFeature::Edge(_)));
            let (q, _, _, f) = closest_point_triangle_2d(Vec2::new(0.5, 0.5), a, b, c);
            assert_eq!((q, f), (Vec2::new(0.5, 0.5), TriangleFeature::Face));
        }
    }
}
