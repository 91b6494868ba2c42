use glam::Vec3;

use super::{CullMode, TriangleHit};
use crate::math::{Ray, Triangle, cross, dot, unit_scale};

/// The two-step ray–triangle test: where the ray crosses the triangle's plane (step one, as
/// [`intersect_ray_plane`](super::intersect_ray_plane) finds it), then whether that point's
/// barycentric coordinates lie in the triangle (step two, signed areas against the
/// unnormalized normal).
///
/// Reports a hit when `t ∈ [t_min, t_max]`, `u ≥ 0`, `v ≥ 0`, `u + v ≤ 1` (edges and corners
/// count) and the face is not culled by `cull`, as
/// [`intersect_ray_triangle`](super::intersect_ray_triangle) does; returns `None` for
/// degenerate triangles, rays parallel to the plane and invalid rays. Not watertight: near a
/// shared edge the rounding of the crossing point decides the side, so a ray can slip between
/// two triangles (or hit both). Its `t` is the plane's, so on a sliver it is the most accurate
/// of the three tests; the barycentrics carry the crossing point's rounding. The normal is
/// scaled to unit size by a power of two before use, so its products stay within `f32` for
/// coordinates up to about 10¹⁸ (where the other two tests overflow past about 10¹²).
///
/// ```
/// use meshq::{geom::{intersect_ray_triangle_two_step, CullMode}, math::{Ray, Triangle, Vec3}};
/// let tri = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
/// let hit = intersect_ray_triangle_two_step(&Ray::new(Vec3::new(0.25, 0.25, 1.0), -Vec3::Z), &tri, CullMode::None);
/// assert_eq!(hit.map(|h| (h.t, h.u, h.v)), Some((1.0, 0.25, 0.25)));
/// ```
#[must_use]
pub fn intersect_ray_triangle_two_step(
    ray: &Ray,
    tri: &Triangle,
    cull: CullMode,
) -> Option<TriangleHit> {
    if !ray.is_valid() || tri.is_degenerate() {
        return None;
    }
    two_step(ray, tri.a, tri.b, tri.c, cull)
}

/// The two-step kernel without the ray and degeneracy checks, for acceleration structures.
#[inline(always)]
pub(crate) fn two_step(
    ray: &Ray,
    a: Vec3,
    b: Vec3,
    c: Vec3,
    cull: CullMode,
) -> Option<TriangleHit> {
    let e1 = b - a;
    let e2 = c - a;
    // The normal scaled by a power of two (exactly) to its largest coordinate in [1, 2): `t`
    // and the barycentrics are ratios in which its length cancels, and unscaled its square
    // would overflow for triangles a few billion units across.
    let normal = cross(e1, e2);
    let n = normal * unit_scale(normal.abs().max_element());
    // Front hits have `dir · n < 0`.
    let facing = dot(n, ray.dir);
    let facing_ok = match cull {
        CullMode::None => facing != 0.0,
        CullMode::Back => facing < 0.0,
        CullMode::Front => facing > 0.0,
    };
    if !facing_ok {
        return None;
    }
    let t = dot(n, a - ray.origin) / facing;
    if !(t >= ray.t_min && t <= ray.t_max) {
        return None;
    }
    let along = ray.origin + ray.dir * t - a;
    let area = dot(n, normal);
    let u = dot(n, cross(along, e2)) / area;
    let v = dot(n, cross(e1, along)) / area;
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0).then_some(TriangleHit { t, u, v })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::intersect_ray_triangle;

    fn tri() -> Triangle {
        Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y)
    }

    #[test]
    fn hits_edges_and_corners_and_misses_outside() {
        for p in [
            Vec3::ZERO,
            Vec3::X,
            Vec3::Y,
            Vec3::new(0.5, 0.5, 0.0),
            Vec3::new(0.2, 0.1, 0.0),
        ] {
            let ray = Ray::new(p + Vec3::Z * 2.0, -Vec3::Z * 4.0);
            let hit = intersect_ray_triangle_two_step(&ray, &tri(), CullMode::None);
            assert_eq!(
                hit,
                intersect_ray_triangle(&ray, &tri(), CullMode::None),
                "{p}"
            );
            assert_eq!(hit.map(|h| h.t), Some(0.5), "{p}");
        }
        let outside = Ray::new(Vec3::new(0.6, 0.6, 1.0), -Vec3::Z);
        assert_eq!(
            intersect_ray_triangle_two_step(&outside, &tri(), CullMode::None),
            None
        );
    }

    #[test]
    fn huge_triangles_are_hit() {
        for s in [1e6f32, 1e10, 1e12, 1e15] {
            let big = Triangle::new(Vec3::ZERO, Vec3::X * s, Vec3::Y * s);
            let ray = Ray::new(Vec3::new(0.25 * s, 0.25 * s, s), -Vec3::Z);
            let hit = intersect_ray_triangle_two_step(&ray, &big, CullMode::None);
            assert_eq!(hit.map(|h| (h.t, h.u, h.v)), Some((s, 0.25, 0.25)), "{s}");
        }
    }

    #[test]
    fn culls_like_moller_trumbore_and_rejects_bad_input() {
        let from_front = Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z);
        let from_back = Ray::new(Vec3::new(0.2, 0.2, -1.0), Vec3::Z);
        for cull in [CullMode::None, CullMode::Back, CullMode::Front] {
            for ray in [from_front, from_back] {
                assert_eq!(
                    intersect_ray_triangle_two_step(&ray, &tri(), cull).is_some(),
                    intersect_ray_triangle(&ray, &tri(), cull).is_some()
                );
            }
        }
        let parallel = Ray::new(Vec3::new(0.2, 0.2, 0.0), Vec3::X);
        assert_eq!(
            intersect_ray_triangle_two_step(&parallel, &tri(), CullMode::None),
            None
        );
        let flat = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::X * 2.0);
        assert_eq!(
            intersect_ray_triangle_two_step(&from_front, &flat, CullMode::None),
            None
        );
        let behind = Ray::new(Vec3::new(0.2, 0.2, -1.0), -Vec3::Z);
        assert_eq!(
            intersect_ray_triangle_two_step(&behind, &tri(), CullMode::None),
            None
        );
    }
}
