//! Distances between triangles and between meshes in `f64`, written independently of the
//! crate: the reference the mesh-distance tests compare against.
//!
//! Two triangles either meet (an edge of one crosses the other, or one holds a corner of the
//! other) or their closest pair is a corner of one against the other triangle, or an edge
//! against an edge. The oracle takes the minimum of those fifteen candidates and sets it to
//! zero when an edge crosses the other triangle.

use glam::DVec3;

/// A triangle in `f64`.
pub type Tri64 = [DVec3; 3];

/// A triangle's corners widened to `f64`.
pub fn widen(t: &meshq::math::Triangle) -> Tri64 {
    [t.a.as_dvec3(), t.b.as_dvec3(), t.c.as_dvec3()]
}

/// The squared distance from `p` to triangle `t` (a degenerate triangle as its edges).
pub fn point_triangle_squared(p: DVec3, t: &Tri64) -> f64 {
    let [a, b, c] = *t;
    let n = (b - a).cross(c - a);
    let nn = n.length_squared();
    let edges = segment_squared(p, a, b)
        .min(segment_squared(p, b, c))
        .min(segment_squared(p, c, a));
    if nn <= 0.0 {
        return edges;
    }
    // Inside the prism over the face: the plane distance; otherwise the nearest edge.
    let inside = [(a, b), (b, c), (c, a)]
        .iter()
        .all(|&(u, v)| (v - u).cross(p - u).dot(n) >= 0.0);
    if inside {
        let h = (p - a).dot(n);
        h * h / nn
    } else {
        edges
    }
}

/// The squared distance from `p` to segment `[a, b]`.
pub fn segment_squared(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let d = b - a;
    let len = d.length_squared();
    let t = if len > 0.0 {
        ((p - a).dot(d) / len).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + d * t - p).length_squared()
}

/// The squared distance between segments `[p1, q1]` and `[p2, q2]`, by minimising over one
/// parameter with the other solved in closed form, on a ladder of starting points (robust
/// for parallel and degenerate segments alike).
pub fn segment_segment_squared(p1: DVec3, q1: DVec3, p2: DVec3, q2: DVec3) -> f64 {
    let d1 = q1 - p1;
    let d2 = q2 - p2;
    let r = p1 - p2;
    let (a, e, b) = (d1.dot(d1), d2.dot(d2), d1.dot(d2));
    let (c, f) = (d1.dot(r), d2.dot(r));
    let mut best = segment_squared(p1, p2, q2)
        .min(segment_squared(q1, p2, q2))
        .min(segment_squared(p2, p1, q1))
        .min(segment_squared(q2, p1, q1));
    let denom = a * e - b * b;
    if denom > 1e-300 * a.max(1.0) * e.max(1.0) {
        let s = (b * f - c * e) / denom;
        let t = (a * f - b * c) / denom;
        if (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t) {
            best = best.min((p1 + d1 * s - (p2 + d2 * t)).length_squared());
        }
    }
    best
}

/// Whether segment `[p, q]` crosses or touches triangle `t`'s face (not merely its plane).
fn segment_crosses_triangle(p: DVec3, q: DVec3, t: &Tri64) -> bool {
    let [a, b, c] = *t;
    let n = (b - a).cross(c - a);
    if n.length_squared() <= 0.0 {
        return false;
    }
    let (dp, dq) = ((p - a).dot(n), (q - a).dot(n));
    if (dp > 0.0 && dq > 0.0) || (dp < 0.0 && dq < 0.0) || dp == dq {
        return false;
    }
    let x = p + (q - p) * (dp / (dp - dq));
    [(a, b), (b, c), (c, a)]
        .iter()
        .all(|&(u, v)| (v - u).cross(x - u).dot(n) >= 0.0)
}

/// The distance between triangles `s` and `t`.
pub fn triangle_triangle(s: &Tri64, t: &Tri64) -> f64 {
    let edges = |x: &Tri64| [(x[0], x[1]), (x[1], x[2]), (x[2], x[0])];
    let crosses = edges(s)
        .iter()
        .any(|&(p, q)| segment_crosses_triangle(p, q, t))
        || edges(t)
            .iter()
            .any(|&(p, q)| segment_crosses_triangle(p, q, s));
    if crosses {
        return 0.0;
    }
    let mut best = f64::INFINITY;
    for p in s {
        best = best.min(point_triangle_squared(*p, t));
    }
    for p in t {
        best = best.min(point_triangle_squared(*p, s));
    }
    for (p1, q1) in edges(s) {
        for (p2, q2) in edges(t) {
            best = best.min(segment_segment_squared(p1, q1, p2, q2));
        }
    }
    best.sqrt()
}

/// The distance between two triangle sets by every pair, skipping pairs whose boxes are
/// farther apart than the best so far (exact: a box gap bounds the distance from below).
pub fn mesh_mesh(a: &[Tri64], b: &[Tri64]) -> f64 {
    let bounds = |t: &Tri64| (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
    let boxes_b: Vec<(DVec3, DVec3)> = b.iter().map(bounds).collect();
    let mut best = f64::INFINITY;
    for s in a {
        let (lo, hi) = bounds(s);
        for (t, (tlo, thi)) in b.iter().zip(&boxes_b) {
            let gap = (*tlo - hi).max(lo - *thi).max(DVec3::ZERO);
            if gap.length() >= best {
                continue;
            }
            best = best.min(triangle_triangle(s, t));
        }
    }
    best
}

/// A shape swept by the oracle, in `f64`.
#[derive(Clone, Copy, Debug)]
pub enum Shape64 {
    /// Centre and radius.
    Sphere(DVec3, f64),
    /// Segment ends and radius.
    Capsule(DVec3, DVec3, f64),
    /// Centre, three orthonormal axes and half extents.
    Box(DVec3, [DVec3; 3], DVec3),
}

impl Shape64 {
    /// The shape moved by `d`.
    pub fn moved(&self, d: DVec3) -> Self {
        match *self {
            Self::Sphere(c, r) => Self::Sphere(c + d, r),
            Self::Capsule(a, b, r) => Self::Capsule(a + d, b + d, r),
            Self::Box(c, axes, h) => Self::Box(c + d, axes, h),
        }
    }

    /// Its distance to triangle `t` (0 when they meet).
    pub fn distance(&self, t: &Tri64) -> f64 {
        match *self {
            Self::Sphere(c, r) => (point_triangle_squared(c, t).sqrt() - r).max(0.0),
            Self::Capsule(a, b, r) => (triangle_triangle(&[a, b, b], t) - r).max(0.0),
            Self::Box(c, axes, h) => {
                let inside = |p: DVec3| {
                    let d = p - c;
                    (0..3).all(|i| d.dot(axes[i]).abs() <= h[i])
                };
                if t.iter().any(|&p| inside(p)) {
                    return 0.0;
                }
                let corner = |i: usize| {
                    let s = |bit: usize| if i & bit != 0 { 1.0 } else { -1.0 };
                    c + axes[0] * (s(1) * h.x) + axes[1] * (s(2) * h.y) + axes[2] * (s(4) * h.z)
                };
                let faces = [
                    [0, 1, 3, 2],
                    [4, 5, 7, 6],
                    [0, 1, 5, 4],
                    [2, 3, 7, 6],
                    [0, 2, 6, 4],
                    [1, 3, 7, 5],
                ];
                faces
                    .iter()
                    .flat_map(|f| [[f[0], f[1], f[2]], [f[0], f[2], f[3]]])
                    .map(|[i, j, k]| triangle_triangle(&[corner(i), corner(j), corner(k)], t))
                    .fold(f64::INFINITY, f64::min)
            }
        }
    }

    /// A box holding the shape.
    fn bounds(&self) -> (DVec3, DVec3) {
        match *self {
            Self::Sphere(c, r) => (c - r, c + r),
            Self::Capsule(a, b, r) => (a.min(b) - r, a.max(b) + r),
            Self::Box(c, axes, h) => {
                let reach = axes[0].abs() * h.x + axes[1].abs() * h.y + axes[2].abs() * h.z;
                (c - reach, c + reach)
            }
        }
    }
}

/// The distance from `shape` to the nearest of `mesh` (triangles whose boxes are farther than
/// the best so far are skipped: exact).
pub fn shape_mesh(shape: &Shape64, mesh: &[Tri64]) -> f64 {
    let (lo, hi) = shape.bounds();
    let mut best = f64::INFINITY;
    for t in mesh {
        let (tlo, thi) = (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
        let gap = (tlo - hi).max(lo - thi).max(DVec3::ZERO);
        if gap.length() >= best {
            continue;
        }
        best = best.min(shape.distance(t));
    }
    best
}

/// The first time `t ∈ [0, 1]` at which `shape` moved by `t · motion` comes within `eps` of
/// `mesh`, by steps no longer than the distance left (a shape moving at speed `|motion|`
/// cannot close a gap faster): never past the first contact, and within `eps` of it.
pub fn time_of_impact(shape: &Shape64, motion: DVec3, mesh: &[Tri64], eps: f64) -> Option<f64> {
    let speed = motion.length();
    let mut t = 0.0;
    for _ in 0..1_000_000 {
        let d = shape_mesh(&shape.moved(motion * t), mesh);
        if d <= eps {
            return Some(t);
        }
        if speed == 0.0 {
            return None;
        }
        t += d / speed;
        if t > 1.0 {
            return None;
        }
    }
    Some(t)
}
