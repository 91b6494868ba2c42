use glam::Vec3;

use crate::math::{Ray, Triangle, cross, dot};

/// Which faces a ray–triangle test ignores.
///
/// The *front* face is the side the normal `(b − a) × (c − a)` points to (counter-clockwise
/// corners when seen from the front). A ray hits the front when `dir · normal < 0`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CullMode {
    /// Report hits on both faces (the default).
    #[default]
    None,
    /// Ignore hits on back faces (report front hits only).
    Back,
    /// Ignore hits on front faces (report back hits only).
    Front,
}

/// A ray–triangle hit: the ray parameter and the barycentric coordinates of the hit point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit {
    /// Ray parameter, in units of the direction's length, within `[t_min, t_max]`.
    pub t: f32,
    /// Weight of corner `b`; the point is `(1 − u − v)·a + u·b + v·c`.
    pub u: f32,
    /// Weight of corner `c`.
    pub v: f32,
}

/// Möller–Trumbore ray–triangle intersection (Möller & Trumbore 1997).
///
/// Reports a hit when `t ∈ [t_min, t_max]`, `u ≥ 0`, `v ≥ 0`, `u + v ≤ 1` (edges and corners
/// count) and the face is not culled by `cull`. Returns `None` for degenerate triangles
/// ([`Triangle::is_degenerate`]), rays parallel to the triangle's plane, and invalid rays
/// ([`Ray::is_valid`]).
///
/// This test is fast but not watertight: a ray through a shared edge can slip between two
/// triangles because each side rounds differently. Use
/// [`intersect_ray_triangle_watertight`](super::intersect_ray_triangle_watertight) when that
/// matters.
///
/// ```
/// use meshq::{geom::{intersect_ray_triangle, CullMode}, math::{Ray, Triangle, Vec3}};
/// let tri = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
/// let hit = intersect_ray_triangle(&Ray::new(Vec3::new(0.25, 0.25, 1.0), -Vec3::Z), &tri, CullMode::None);
/// assert_eq!(hit.map(|h| (h.t, h.u, h.v)), Some((1.0, 0.25, 0.25)));
/// ```
#[must_use]
pub fn intersect_ray_triangle(ray: &Ray, tri: &Triangle, cull: CullMode) -> Option<TriangleHit> {
    if !ray.is_valid() || tri.is_degenerate() {
        return None;
    }
    moller_trumbore(ray, tri.a, tri.b, tri.c, cull)
}

/// The Möller–Trumbore kernel without the ray and degeneracy checks. Acceleration structures
/// call it directly (the ray is checked once per query, degeneracy only for a winning hit).
#[inline(always)]
pub(crate) fn moller_trumbore(
    ray: &Ray,
    a: Vec3,
    b: Vec3,
    c: Vec3,
    cull: CullMode,
) -> Option<TriangleHit> {
    let e1 = b - a;
    let e2 = c - a;
    let p = cross(ray.dir, e2);
    // det = e1 · (d × e2) = −d · (e1 × e2): positive for a front-face hit.
    let det = dot(e1, p);
    let facing_ok = match cull {
        CullMode::None => det != 0.0,
        CullMode::Back => det > 0.0,
        CullMode::Front => det < 0.0,
    };
    if !facing_ok {
        return None;
    }
    let inv_det = 1.0 / det;
    let s = ray.origin - a;
    let u = dot(s, p) * inv_det;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = cross(s, e1);
    let v = dot(ray.dir, q) * inv_det;
    if !(v >= 0.0 && u + v <= 1.0) {
        return None;
    }
    let t = dot(e2, q) * inv_det;
    (t >= ray.t_min && t <= ray.t_max).then_some(TriangleHit { t, u, v })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri() -> Triangle {
        Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y)
    }

    #[test]
    fn hits_inside_with_barycentrics_and_t_in_direction_units() {
        let ray = Ray::new(Vec3::new(0.5, 0.25, 2.0), Vec3::new(0.0, 0.0, -4.0));
        let hit = intersect_ray_triangle(&ray, &tri(), CullMode::None);
        assert_eq!(
            hit,
            Some(TriangleHit {
                t: 0.5,
                u: 0.5,
                v: 0.25
            })
        );
    }

    #[test]
    fn edges_and_corners_count() {
        for p in [
            Vec3::ZERO,
            Vec3::X,
            Vec3::Y,
            Vec3::new(0.5, 0.0, 0.0),
            Vec3::new(0.0, 0.5, 0.0),
        ] {
            let ray = Ray::new(p + Vec3::Z, -Vec3::Z);
            assert!(
                intersect_ray_triangle(&ray, &tri(), CullMode::None).is_some(),
                "{p}"
            );
        }
        let outside = Ray::new(Vec3::new(0.6, 0.6, 1.0), -Vec3::Z);
        assert!(intersect_ray_triangle(&outside, &tri(), CullMode::None).is_none());
    }

    #[test]
    fn culling_follows_the_counter_clockwise_front() {
        let from_front = Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z);
        let from_back = Ray::new(Vec3::new(0.2, 0.2, -1.0), Vec3::Z);
        let t = tri();
        assert!(intersect_ray_triangle(&from_front, &t, CullMode::Back).is_some());
        assert!(intersect_ray_triangle(&from_front, &t, CullMode::Front).is_none());
        assert!(intersect_ray_triangle(&from_back, &t, CullMode::Back).is_none());
        assert!(intersect_ray_triangle(&from_back, &t, CullMode::Front).is_some());
    }

    #[test]
    fn degenerate_inputs_never_hit() {
        let down = Ray::new(Vec3::new(0.2, 0.0, 1.0), -Vec3::Z);
        let line = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::X * 2.0);
        assert!(intersect_ray_triangle(&down, &line, CullMode::None).is_none());
        let point = Triangle::new(Vec3::ONE, Vec3::ONE, Vec3::ONE);
        assert!(intersect_ray_triangle(&down, &point, CullMode::None).is_none());
        let parallel = Ray::new(Vec3::new(-1.0, 0.2, 0.0), Vec3::X);
        assert!(intersect_ray_triangle(&parallel, &tri(), CullMode::None).is_none());
        let zero = Ray::new(Vec3::new(0.2, 0.2, 0.0), Vec3::ZERO);
        assert!(intersect_ray_triangle(&zero, &tri(), CullMode::None).is_none());
        let nan = Ray::new(Vec3::new(0.2, f32::NAN, 1.0), -Vec3::Z);
        assert!(intersect_ray_triangle(&nan, &tri(), CullMode::None).is_none());
        let nan_tri = Triangle::new(Vec3::new(f32::NAN, 0.0, 0.0), Vec3::X, Vec3::Y);
        assert!(intersect_ray_triangle(&down, &nan_tri, CullMode::None).is_none());
    }

    #[test]
    fn range_is_inclusive_and_respected() {
        let ray = Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z);
        assert!(
            intersect_ray_triangle(&ray.with_range(1.0, 1.0), &tri(), CullMode::None).is_some()
        );
        assert!(
            intersect_ray_triangle(&ray.with_range(0.0, 0.99), &tri(), CullMode::None).is_none()
        );
        assert!(
            intersect_ray_triangle(&ray.with_range(1.01, 9.0), &tri(), CullMode::None).is_none()
        );
    }
}
