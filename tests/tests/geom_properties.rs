//! Property tests: every primitive against an independent `f64` reference written here with a
//! different method. Cases within rounding distance of a decision boundary are skipped (the
//! reference cannot call them either); everywhere else the answers must agree.

use glam::{DVec3, Vec2, Vec3};
use meshq::advanced::point_in_triangle_2d;
use meshq::geom::*;
use meshq::math::{Aabb, Plane, Ray, Triangle};
use proptest::prelude::*;

fn coord() -> impl Strategy<Value = f32> {
    -10.0f32..10.0
}

fn vec3() -> impl Strategy<Value = Vec3> {
    (coord(), coord(), coord()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn triangle() -> impl Strategy<Value = Triangle> {
    (vec3(), vec3(), vec3()).prop_map(|(a, b, c)| Triangle::new(a, b, c))
}

fn d(v: Vec3) -> DVec3 {
    v.as_dvec3()
}

fn dtri(t: &Triangle) -> [DVec3; 3] {
    [d(t.a), d(t.b), d(t.c)]
}

fn closest_on_segment_f64(p: DVec3, a: DVec3, b: DVec3) -> DVec3 {
    let ab = b - a;
    let len2 = ab.length_squared();
    if len2 == 0.0 {
        return a;
    }
    a + ab * ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
}

/// Closest point on a triangle by projection onto the plane, else the best of the three edges.
fn closest_on_triangle_f64(p: DVec3, [a, b, c]: [DVec3; 3]) -> DVec3 {
    let n = (b - a).cross(c - a);
    let edges = [(a, b), (b, c), (c, a)].map(|(s, e)| closest_on_segment_f64(p, s, e));
    let mut best = edges[0];
    for q in edges {
        if (q - p).length_squared() < (best - p).length_squared() {
            best = q;
        }
    }
    if n.length_squared() > 0.0 {
        let q = p - n * ((p - a).dot(n) / n.length_squared());
        let inside = [(a, b), (b, c), (c, a)]
            .iter()
            .all(|&(s, e)| (e - s).cross(q - s).dot(n) >= 0.0);
        if inside {
            return q;
        }
    }
    best
}

/// The distance between segments `[p1, q1]` and `[p2, q2]` in f64: the nearest of the four
/// endpoint-to-segment distances and, where the two lines' closest points (from the cross
/// products, a different formulation from the clamp-and-reproject code under test) lie on
/// both segments, their distance.
fn segment_distance_f64(p1: Vec3, q1: Vec3, p2: Vec3, q2: Vec3) -> f64 {
    let (a, b, c, e) = (d(q1 - p1), d(q2 - p2), d(p1), d(p2));
    let mut nearest = [
        (closest_on_segment_f64(c, e, e + b) - c).length(),
        (closest_on_segment_f64(c + a, e, e + b) - (c + a)).length(),
        (closest_on_segment_f64(e, c, c + a) - e).length(),
        (closest_on_segment_f64(e + b, c, c + a) - (e + b)).length(),
    ]
    .into_iter()
    .fold(f64::INFINITY, f64::min);
    let n = a.cross(b);
    if n.length_squared() > 0.0 {
        let w = c - e;
        let s = n.dot(b.cross(w)) / n.length_squared();
        let t = n.dot(a.cross(w)) / n.length_squared();
        if (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t) {
            nearest = nearest.min(((c + a * s) - (e + b * t)).length());
        }
    }
    nearest
}

/// Ray–triangle in f64 by Cramer's rule: `Some((t, u, v, margin))`, where `margin` is how far
/// the solution is from every decision boundary.
fn ray_triangle_f64(o: DVec3, dir: DVec3, [a, b, c]: [DVec3; 3]) -> Option<(f64, f64, f64, f64)> {
    let e1 = b - a;
    let e2 = c - a;
    let det = -dir.dot(e1.cross(e2));
    if det.abs() < 1e-9 {
        return None;
    }
    let s = o - a;
    // Solve s = u e1 + v e2 − t dir.
    let u = -dir.dot(s.cross(e2)) / det;
    let v = -dir.dot(e1.cross(s)) / det;
    let t = s.dot(e1.cross(e2)) / det;
    let margin = u.min(v).min(1.0 - u - v);
    Some((t, u, v, margin))
}

/// The closest-point-on-triangle methods, in the order the benchmark reports them.
const CLOSEST_POINT_METHODS: [fn(Vec3, &Triangle) -> meshq::math::ClosestPoint; 3] = [
    closest_point_triangle,
    closest_point_triangle_projection,
    closest_point_triangle_rotation,
];

proptest! {
    #![proptest_config(ProptestConfig { cases: 3_000, ..ProptestConfig::default() })]

    /// A point computed on a plane in `f64` and stored as `f32` is on it with no tolerance; a
    /// point moved off it by a thousandth of the size is on it only with a tolerance past
    /// that thousandth.
    #[test]
    fn point_on_plane_matches_f64(q in vec3(), n in vec3(), x in vec3(), magnitude in -3i32..6) {
        prop_assume!(n.length() > 1e-2);
        let size_of = 10f64.powi(magnitude);
        let (q, x) = (q * size_of as f32, x * size_of as f32);
        let plane = Plane::from_point_normal(q, n);
        let n64 = d(n);
        let onto = |x: DVec3| x - n64 * ((n64.dot(x) - f64::from(plane.offset)) / n64.length_squared());
        let on = onto(d(x));
        prop_assert!(point_on_plane(on.as_vec3(), &plane, 0.0), "{:?} on {:?}", on, plane);
        let size = on.abs().max_element().max(f64::from(plane.offset).abs() / n64.length());
        let off = (on + n64.normalize() * (1e-3 * size)).as_vec3();
        prop_assert!(!point_on_plane(off, &plane, 0.0));
        prop_assert!(!point_on_plane(off, &plane, 5e-4));
        prop_assert!(point_on_plane(off, &plane, 2e-3));
    }

    #[test]
    fn ray_plane_matches_f64(o in vec3(), dir in vec3(), p in vec3(), n in vec3()) {
        let plane = Plane::from_point_normal(p, n);
        let cos = n.normalize_or_zero().dot(dir.normalize_or_zero());
        prop_assume!(cos.abs() > 0.05);
        let t64 = (d(n).dot(d(p)) - d(n).dot(d(o))) / d(n).dot(d(dir));
        let got = intersect_ray_plane(&Ray::new(o, dir), &plane);
        prop_assume!((t64.abs()) > 1e-3);
        prop_assert_eq!(got.is_some(), t64 >= 0.0, "t64 {}", t64);
        if let Some(t) = got {
            prop_assert!((f64::from(t) - t64).abs() <= 1e-3 * t64.abs().max(1.0), "{} vs {}", t, t64);
        }
    }

    #[test]
    fn ray_aabb_matches_f64_slabs(o in vec3(), dir in vec3(), a in vec3(), b in vec3()) {
        prop_assume!(dir.length() > 0.1);
        let bx = Aabb::new(a.min(b), a.max(b));
        // f64 slabs, with the gap between entry and exit as the margin.
        let (mut lo, mut hi) = (0.0f64, f64::INFINITY);
        for k in 0..3 {
            let (o, dk, mn, mx) = (f64::from(o[k]), f64::from(dir[k]), f64::from(bx.min[k]), f64::from(bx.max[k]));
            if dk == 0.0 {
                if o < mn || o > mx { lo = 1.0; hi = 0.0; }
                continue;
            }
            let (t0, t1) = ((mn - o) / dk, (mx - o) / dk);
            lo = lo.max(t0.min(t1));
            hi = hi.min(t0.max(t1));
        }
        prop_assume!((hi - lo).abs() > 1e-4);
        let got = intersect_ray_aabb(&Ray::new(o, dir), &bx);
        prop_assert_eq!(got.is_some(), lo <= hi);
        if let Some((entry, exit)) = got {
            prop_assert!((f64::from(entry) - lo).abs() < 1e-3 && (f64::from(exit) - hi).abs() < 1e-3);
        }
    }

    #[test]
    fn ray_triangle_every_test_matches_f64(o in vec3(), tri in triangle(), u in 0.0f32..1.0, v in 0.0f32..1.0, aim in any::<bool>(), dir in vec3()) {
        prop_assume!(tri.area() > 0.5);
        // Half the rays aim at a point in the triangle's plane (inside or outside it).
        let dir = if aim { tri.point_at(u * 1.5 - 0.25, v * 1.5 - 0.25) - o } else { dir };
        prop_assume!(dir.length() > 0.1);
        // At grazing incidence the hit moves by about (rounding / cosine) across the plane, so
        // no f32 test can stay within a fixed distance of f64 there (a ray at cos 2.7e-4 moved
        // u by more than 1e-3); the watertightness suites cover grazing rays.
        let cos = tri.unit_normal().map_or(0.0, |n| n.dot(dir.normalize_or_zero()).abs());
        prop_assume!(cos > 1e-2);
        let reference = ray_triangle_f64(d(o), d(dir), dtri(&tri));
        let expected = reference.filter(|&(t, ..)| t >= 0.0);
        if let Some((t, _, _, margin)) = reference {
            prop_assume!(margin.abs() > 1e-4 && t.abs() > 1e-4);
        }
        let ray = Ray::new(o, dir);
        for got in [
            intersect_ray_triangle(&ray, &tri, CullMode::None),
            intersect_ray_triangle_watertight(&ray, &tri, CullMode::None),
            intersect_ray_triangle_two_step(&ray, &tri, CullMode::None),
        ] {
            let expected_hit = expected.filter(|e| e.3 >= 0.0);
            prop_assert_eq!(got.is_some(), expected_hit.is_some(), "{:?} vs {:?}", got, reference);
            if let (Some(h), Some((t, u, v, _))) = (got, expected_hit) {
                prop_assert!((f64::from(h.t) - t).abs() <= 1e-3 * t.max(1.0));
                prop_assert!((f64::from(h.u) - u).abs() <= 1e-3 && (f64::from(h.v) - v).abs() <= 1e-3);
            }
        }
    }

    #[test]
    fn closest_point_segment_matches_f64(p in vec3(), a in vec3(), b in vec3()) {
        let (q, t) = closest_point_segment(p, a, b);
        let r = closest_on_segment_f64(d(p), d(a), d(b));
        prop_assert!((0.0..=1.0).contains(&t));
        prop_assert!((d(q) - d(p)).length() - (r - d(p)).length() <= 1e-4);
        prop_assert!((d(q) - r).length() <= 1e-3);
    }

    /// The three methods (the region walk, projection with half-plane tests, rotation into
    /// 2D) on fair and random triangles.
    #[test]
    fn closest_point_triangle_matches_f64(p in vec3(), tri in triangle(), method in 0usize..3) {
        let c = CLOSEST_POINT_METHODS[method](p, &tri);
        let r = closest_on_triangle_f64(d(p), dtri(&tri));
        let (got, want) = ((f64::from(c.distance_squared)).sqrt(), (r - d(p)).length());
        prop_assert!((got - want).abs() <= 1e-4 * want.max(1.0), "{} vs {}", got, want);
        prop_assert!((f64::from(c.distance_squared) - (d(c.point) - d(p)).length_squared()).abs() <= 1e-3);
        // The reported barycentrics rebuild the reported point, inside the triangle.
        if !tri.is_degenerate() {
            prop_assert!(c.u >= -1e-5 && c.v >= -1e-5 && c.u + c.v <= 1.0 + 1e-5);
            prop_assert!((tri.point_at(c.u, c.v) - c.point).length() <= 1e-4);
        }
    }

    /// Slivers: needles (a cone's side facets meeting at its apex, a scan's jump edge) and
    /// caps (a corner almost on the opposite side), with the point near the face: the
    /// distance and the point must be right to within rounding of the coordinates (eight
    /// units in the last place of the largest), whatever the shape. Ericson's signed areas
    /// as differences of products of dots nearly cancel on a sliver, so a point over the
    /// face was measured to an edge; and the plane's normal as a plain cross product of two
    /// nearly parallel edges tilts by the rounding over the sliver's width.
    #[test]
    fn closest_point_triangle_on_slivers_matches_f64(
        a in vec3(), b in vec3(), side in vec3(), along in 0.0f32..1.0, needle in any::<bool>(),
        width in 1e-4f32..1e-2, u in 0.0f32..1.0, v in 0.0f32..1.0, lift in -1.0f32..1.0,
    ) {
        let ab = b - a;
        let across = side - ab * (side.dot(ab) / ab.length_squared());
        prop_assume!(ab.length() > 1e-2 && across.length() > 1e-3);
        // A needle's third corner lies beside `a`, a cap's anywhere along `ab`.
        let along = if needle { along * 1e-2 } else { along };
        let c = a + ab * along + across.normalize() * (width * ab.length());
        let tri = Triangle::new(a, b, c);
        prop_assume!(!tri.is_degenerate());
        let (u, v) = if u + v > 1.0 { (1.0 - u, 1.0 - v) } else { (u, v) };
        let normal = ab.cross(c - a).normalize();
        let p = tri.point_at(u, v) + normal * (lift * width * ab.length());
        let got = closest_point_triangle(p, &tri);
        let want = closest_on_triangle_f64(d(p), dtri(&tri));
        let scale = [a, b, c, p].iter().map(|x| f64::from(x.abs().max_element())).fold(0.0, f64::max);
        let bound = 8.0 * f64::from(f32::EPSILON) * scale;
        // The other two methods are not built for slivers: their bound grows with the
        // sliver's longest edge over its width (the foot of a plain cross product's normal).
        let slender = f64::from(ab.length()) / f64::from(width * ab.length());
        for other in [closest_point_triangle_projection, closest_point_triangle_rotation] {
            let c = other(p, &tri);
            let loose = bound * 4.0 * slender;
            prop_assert!((d(c.point) - want).length() <= loose, "{:?} vs {:?} (bound {})", c.point, want, loose);
        }
        let (distance, reference) = (f64::from(got.distance_squared).sqrt(), (want - d(p)).length());
        prop_assert!((distance - reference).abs() <= bound, "{} vs {} (bound {})", distance, reference, bound);
        prop_assert!((d(got.point) - want).length() <= bound, "{:?} vs {:?} (bound {})", got.point, want, bound);
    }

    #[test]
    fn closest_points_segment_segment_match_f64(p1 in vec3(), q1 in vec3(), p2 in vec3(), q2 in vec3()) {
        let r = closest_points_segment_segment(p1, q1, p2, q2);
        let want = segment_distance_f64(p1, q1, p2, q2);
        let got = f64::from(r.distance_squared).sqrt();
        prop_assert!((got - want).abs() <= 1e-3, "{} vs {}", got, want);
        prop_assert!((0.0..=1.0).contains(&r.s) && (0.0..=1.0).contains(&r.t));
    }

    /// Nearly parallel segments (turned by 10⁻⁵ to 10⁻² radians, overlapping or not): the
    /// distance within rounding of the coordinates (eight units in the last place of the
    /// largest). As `a·e − b²` the lines' determinant cancels to noise there, and the
    /// parameter it gives can sit anywhere along the segments, the distance off by up to the
    /// angle times their length.
    #[test]
    fn closest_points_of_nearly_parallel_segments_match_f64(
        p1 in vec3(), q1 in vec3(), axis in vec3(), angle in -5.0f32..-2.0, stretch in 0.3f32..2.0,
        shift in -1.0f32..1.0, lift in vec3(),
    ) {
        let d1 = q1 - p1;
        prop_assume!(d1.length() > 1e-1 && axis.length() > 1e-1);
        let turn = glam::Quat::from_axis_angle(axis.normalize(), 10f32.powf(angle));
        let p2 = p1 + d1 * shift + lift * 0.1;
        let q2 = p2 + turn * d1 * stretch;
        let r = closest_points_segment_segment(p1, q1, p2, q2);
        let want = segment_distance_f64(p1, q1, p2, q2);
        let got = f64::from(r.distance_squared).sqrt();
        let scale = [p1, q1, p2, q2].iter().map(|x| f64::from(x.abs().max_element())).fold(0.0, f64::max);
        let bound = 8.0 * f64::from(f32::EPSILON) * scale;
        prop_assert!((got - want).abs() <= bound, "{} vs {} (bound {})", got, want, bound);
        prop_assert!((d(r.on_first) - d(r.on_second)).length() - got <= bound);
    }

    #[test]
    fn point_in_triangle_2d_matches_f64(p in (coord(), coord()), a in (coord(), coord()), b in (coord(), coord()), c in (coord(), coord())) {
        let v = |(x, y): (f32, f32)| Vec2::new(x, y);
        let e = |s: (f32, f32), t: (f32, f32), q: (f32, f32)| {
            (f64::from(t.0) - f64::from(s.0)) * (f64::from(q.1) - f64::from(s.1))
                - (f64::from(t.1) - f64::from(s.1)) * (f64::from(q.0) - f64::from(s.0))
        };
        let area = e(a, b, c);
        prop_assume!(area.abs() > 1e-2);
        let w = [e(a, b, p), e(b, c, p), e(c, a, p)].map(|x| x * area.signum());
        prop_assume!(w.iter().all(|x| x.abs() > 1e-3));
        prop_assert_eq!(point_in_triangle_2d(v(p), v(a), v(b), v(c)), w.iter().all(|&x| x > 0.0));
    }

    #[test]
    fn triangle_aabb_matches_f64_clipping(tri in triangle(), a in vec3(), b in vec3()) {
        let bx = Aabb::new(a.min(b), a.max(b));
        let clip = |grow: f64| clip_nonempty(dtri(&tri), d(bx.min) - grow, d(bx.max) + grow);
        let (inner, outer) = (clip(-1e-3), clip(1e-3));
        prop_assume!(inner == outer);
        prop_assert_eq!(overlap_triangle_aabb(&tri, &bx), inner);
    }

    #[test]
    fn triangle_triangle_matches_f64_edge_crossings(t1 in triangle(), t2 in triangle()) {
        prop_assume!(t1.area() > 0.5 && t2.area() > 0.5);
        let reference = tri_tri_f64(dtri(&t1), dtri(&t2));
        prop_assume!(reference.is_some());
        let got = intersect_triangle_triangle(&t1, &t2);
        prop_assert_eq!(!matches!(got, TriangleTriangle::Disjoint), reference == Some(true), "{:?}", got);
        if let TriangleTriangle::Segment { a, b } = got {
            // Both ends lie on both triangles.
            for e in [a, b] {
                for t in [&t1, &t2] {
                    let q = closest_on_triangle_f64(d(e), dtri(t));
                    prop_assert!((q - d(e)).length() <= 1e-3, "{} off {:?}", e, t);
                }
            }
        }
    }
}

/// Sutherland–Hodgman: clip the triangle by the six planes of the box; true when anything is
/// left.
fn clip_nonempty(tri: [DVec3; 3], min: DVec3, max: DVec3) -> bool {
    let mut poly: Vec<DVec3> = tri.to_vec();
    for axis in 0..3 {
        for (bound, keep_below) in [(max[axis], true), (min[axis], false)] {
            let inside = |p: &DVec3| {
                if keep_below {
                    p[axis] <= bound
                } else {
                    p[axis] >= bound
                }
            };
            let mut out = Vec::new();
            for i in 0..poly.len() {
                let (cur, next) = (poly[i], poly[(i + 1) % poly.len()]);
                if inside(&cur) {
                    out.push(cur);
                }
                if inside(&cur) != inside(&next) {
                    let t = (bound - cur[axis]) / (next[axis] - cur[axis]);
                    out.push(cur + (next - cur) * t);
                }
            }
            poly = out;
            if poly.is_empty() {
                return false;
            }
        }
    }
    true
}

/// Whether segment `[p, q]` crosses triangle `t`, or `None` when too close to call.
fn segment_triangle_f64(p: DVec3, q: DVec3, t: [DVec3; 3]) -> Option<bool> {
    let (t_hit, _, _, margin) = ray_triangle_f64(p, q - p, t)?;
    let edge_margin = t_hit.min(1.0 - t_hit);
    if margin.abs() < 1e-6 || edge_margin.abs() < 1e-6 {
        return None;
    }
    Some(margin > 0.0 && edge_margin > 0.0)
}

/// Non-coplanar triangles intersect iff an edge of one crosses the other.
fn tri_tri_f64(a: [DVec3; 3], b: [DVec3; 3]) -> Option<bool> {
    let mut any = false;
    for (s, o) in [(a, b), (b, a)] {
        for i in 0..3 {
            match segment_triangle_f64(s[i], s[(i + 1) % 3], o) {
                None => {
                    // A parallel edge gives no Cramer solution; decide by distance instead.
                    let n = (o[1] - o[0]).cross(o[2] - o[0]).normalize();
                    let (dp, dq) = ((s[i] - o[0]).dot(n), (s[(i + 1) % 3] - o[0]).dot(n));
                    if dp.abs() < 1e-6 || dq.abs() < 1e-6 || (dp > 0.0) != (dq > 0.0) {
                        return None;
                    }
                }
                Some(hit) => any |= hit,
            }
        }
    }
    Some(any)
}
