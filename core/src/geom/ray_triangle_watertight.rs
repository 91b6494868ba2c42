use glam::Vec3;

use super::{CullMode, TriangleHit};
use crate::math::{Ray, Triangle, max_f32, unit_scale};

/// A ray prepared for the watertight test: the permutation and shear that map its direction to
/// `+z` (Woop, Benthin & Wald 2013, "Watertight Ray/Triangle Intersection", JCGT 2(1)).
#[derive(Clone, Copy, Debug)]
pub(crate) struct WatertightRay {
    pub(super) origin: Vec3,
    /// Axis of the largest |direction| component, and the two others in an order that keeps
    /// the sheared frame right-handed.
    pub(super) kx: usize,
    pub(super) ky: usize,
    pub(super) kz: usize,
    /// The origin's coordinates at `kx`, `ky` and `kz`.
    pub(super) origin_k: [f32; 3],
    pub(super) sx: f32,
    pub(super) sy: f32,
    pub(super) sz: f32,
    pub(super) t_min: f32,
    pub(super) t_max: f32,
}

impl WatertightRay {
    #[inline]
    pub fn new(ray: &Ray) -> Self {
        // Every choice here is a select or an indexed load, not a branch: the frame of one
        // random ray says nothing about the next one's, so branches would mispredict.
        let d = ray.dir.to_array();
        let at = |v: &[f32; 3], k: usize| v.get(k).copied().unwrap_or(0.0);
        let [ax, ay, az] = ray.dir.abs().to_array();
        // Ties go to the lower axis so that every target picks the same frame.
        let x_largest = (ax >= ay) & (ax >= az);
        let kz = if x_largest {
            0
        } else {
            2 - usize::from(ay >= az)
        };
        let (next, after) = ((kz + 1) % 3, (kz + 2) % 3);
        let dz = at(&d, kz);
        // The two other axes in cyclic order, swapped for a negative `dz` so that the sheared
        // frame stays right-handed.
        let (kx, ky) = if dz < 0.0 {
            (after, next)
        } else {
            (next, after)
        };
        let (sx, sy, sz) = (at(&d, kx) / dz, at(&d, ky) / dz, 1.0 / dz);
        let o = ray.origin.to_array();
        Self {
            origin: ray.origin,
            kx,
            ky,
            kz,
            origin_k: [at(&o, kx), at(&o, ky), at(&o, kz)],
            sx,
            sy,
            sz,
            t_min: ray.t_min,
            t_max: ray.t_max,
        }
    }

    /// Lowers the accepted upper bound (a closer hit was found).
    #[inline(always)]
    pub(crate) fn set_t_max(&mut self, t_max: f32) {
        self.t_max = t_max;
    }

    /// The watertight test against corners `a`, `b`, `c` (no degeneracy check).
    #[inline(always)]
    pub fn intersect(&self, a: Vec3, b: Vec3, c: Vec3, cull: CullMode) -> Option<TriangleHit> {
        // Components are picked through arrays indexed by the ray's permutation (a store and
        // three indexed loads), cheaper than a three-way select per component.
        let pa = (a - self.origin).to_array();
        let pb = (b - self.origin).to_array();
        let pc = (c - self.origin).to_array();
        let pick = |v: &[f32; 3], k: usize| v.get(k).copied().unwrap_or(0.0);
        let (az, bz, cz) = (pick(&pa, self.kz), pick(&pb, self.kz), pick(&pc, self.kz));
        let ax = pick(&pa, self.kx) - self.sx * az;
        let ay = pick(&pa, self.ky) - self.sy * az;
        let bx = pick(&pb, self.kx) - self.sx * bz;
        let by = pick(&pb, self.ky) - self.sy * bz;
        let cx = pick(&pc, self.kx) - self.sx * cz;
        let cy = pick(&pc, self.ky) - self.sy * cz;
        let sheared = [ax, ay, az, bx, by, bz, cx, cy, cz];
        match solve_sheared(&sheared, self.sz, cull) {
            Sheared::Hit(hit) => (hit.t >= self.t_min && hit.t <= self.t_max).then_some(hit),
            Sheared::Miss => None,
            Sheared::OutOfRange => self.intersect_rescaled(sheared, cull),
        }
    }

    /// [`Self::intersect`] for a triangle whose products left the range of `f32` (coordinates
    /// past about 10¹² from the origin, or a determinant too small to invert): the sheared
    /// corners multiplied by the power of two that brings the largest near 1, solved as before,
    /// and `t` multiplied back. Multiplying by a power of two rounds nothing, so the answer is
    /// the one an `f32` with an unbounded exponent would give, and the edge signs neighbours
    /// share are unchanged: the test stays watertight at every scale.
    #[cold]
    #[inline(never)]
    fn intersect_rescaled(&self, sheared: [f32; 9], cull: CullMode) -> Option<TriangleHit> {
        let largest = sheared.iter().fold(0.0, |m, x| max_f32(m, x.abs()));
        let scale = unit_scale(largest);
        let Sheared::Hit(mut hit) = solve_sheared(&sheared.map(|x| x * scale), self.sz, cull)
        else {
            return None;
        };
        hit.t *= 1.0 / scale;
        (hit.t.is_finite() && hit.t >= self.t_min && hit.t <= self.t_max).then_some(hit)
    }
}

/// What the test decides about a sheared triangle, before the ray's interval is checked.
enum Sheared {
    /// The ray's line crosses it (at any `t`).
    Hit(TriangleHit),
    /// It does not, or it is culled, or the ray lies in its plane.
    Miss,
    /// A product overflowed or the determinant's inverse did: decide again at another scale.
    OutOfRange,
}

/// The watertight test on the sheared corners `[ax, ay, az, bx, by, bz, cx, cy, cz]` (relative to
/// the ray's origin, the ray along +z with `t = z · sz`). Inlined into every walk where code size
/// is free; on bare metal the walks and the rescaled test share one copy, for the firmware's
/// flash budget. (Inlining never changes a result: no operation is fused or reordered.)
#[cfg_attr(not(target_os = "none"), inline(always))]
#[cfg_attr(target_os = "none", inline(never))]
fn solve_sheared(corners: &[f32; 9], sz: f32, cull: CullMode) -> Sheared {
    let [ax, ay, az, bx, by, bz, cx, cy, cz] = *corners;
    // Scaled barycentrics: signed edge functions of the sheared triangle at the origin.
    let mut u = cx * by - cy * bx;
    let mut v = ax * cy - ay * cx;
    let mut w = bx * ay - by * ax;
    // An exact zero may be a rounding casualty; recompute all three in f64, where the products
    // of f32 values are exact, so neighbours sharing an edge agree on its side.
    if u == 0.0 || v == 0.0 || w == 0.0 {
        [u, v, w] = edge_functions_in_f64([ax, ay], [bx, by], [cx, cy]);
    }
    // A finite edge function has the sign of the exact one (rounding is monotone); an overflow
    // gives ±∞ with the right sign, or NaN. The tests ask "is one of them on the wrong side",
    // so a NaN passes them and is caught by the determinant below, never taken for a miss.
    let inside = match cull {
        CullMode::None => !((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)),
        CullMode::Back => !(u < 0.0 || v < 0.0 || w < 0.0),
        CullMode::Front => !(u > 0.0 || v > 0.0 || w > 0.0),
    };
    if !inside {
        return Sheared::Miss;
    }
    let det = u + v + w;
    // Zero: the ray lies in the plane, no hit. (In this frame det > 0 is a front-face hit, as in
    // Möller–Trumbore.)
    if det == 0.0 {
        return Sheared::Miss;
    }
    let t_scaled = u * (sz * az) + v * (sz * bz) + w * (sz * cz);
    let inv_det = 1.0 / det;
    let t = t_scaled * inv_det;
    // A finite determinant means finite edge functions; a finite `t` then means nothing
    // overflowed on the way.
    if !(det.is_finite() && t.is_finite()) {
        return Sheared::OutOfRange;
    }
    Sheared::Hit(TriangleHit {
        t,
        u: v * inv_det,
        v: w * inv_det,
    })
}

/// The three edge functions of the sheared triangle `a`, `b`, `c` at the origin, as
/// [`WatertightRay::intersect`] computes them, recomputed in `f64`, where the products of `f32`
/// values are exact. Every ray walk reaches it; on bare metal, where `f64` is software and
/// flash is the budget, they share one copy.
#[cfg_attr(target_os = "none", inline(never))]
fn edge_functions_in_f64(a: [f32; 2], b: [f32; 2], c: [f32; 2]) -> [f32; 3] {
    let f = |p: f32, q: f32, r: f32, s: f32| {
        (f64::from(p) * f64::from(q) - f64::from(r) * f64::from(s)) as f32
    };
    let ([ax, ay], [bx, by], [cx, cy]) = (a, b, c);
    [f(cx, by, cy, bx), f(ax, cy, ay, cx), f(bx, ay, by, ax)]
}

/// Watertight ray–triangle intersection (Woop, Benthin & Wald 2013).
///
/// Same conventions and return value as
/// [`intersect_ray_triangle`](super::intersect_ray_triangle), but the edge tests are exact in
/// sign: a ray through an edge or a vertex shared by two triangles of a closed mesh hits at least
/// one of them, with no cracks. Edge functions that round to zero are recomputed in `f64`
/// (exact for products of `f32`), as the paper prescribes. Returns `None` for degenerate
/// triangles, rays parallel to the plane and invalid rays.
///
/// Any size works: where the test's products would leave the range of `f32` (coordinates past
/// about 10¹² from the ray's origin with a unit direction), it rescales the triangle by a power
/// of two, which rounds nothing, so the answer is the one an `f32` with an unbounded exponent
/// would give, and stays watertight.
///
/// ```
/// use meshq::{geom::{intersect_ray_triangle_watertight, CullMode}, math::{Ray, Triangle, Vec3}};
/// let tri = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
/// let ray = Ray::new(Vec3::new(0.5, 0.5, 1.0), -Vec3::Z); // exactly on edge bc
/// assert!(intersect_ray_triangle_watertight(&ray, &tri, CullMode::None).is_some());
/// ```
#[must_use]
pub fn intersect_ray_triangle_watertight(
    ray: &Ray,
    tri: &Triangle,
    cull: CullMode,
) -> Option<TriangleHit> {
    if !ray.is_valid() || tri.is_degenerate() {
        return None;
    }
    WatertightRay::new(ray).intersect(tri.a, tri.b, tri.c, cull)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::intersect_ray_triangle;

    fn tri() -> Triangle {
        Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y)
    }

    #[test]
    fn agrees_with_moller_trumbore_inside() {
        let ray = Ray::new(Vec3::new(0.5, 0.25, 2.0), Vec3::new(0.0, 0.0, -4.0));
        let w = intersect_ray_triangle_watertight(&ray, &tri(), CullMode::None);
        assert_eq!(
            w,
            Some(TriangleHit {
                t: 0.5,
                u: 0.5,
                v: 0.25
            })
        );
        // Every direction sign and dominant axis, against Möller–Trumbore.
        let t = Triangle::new(
            Vec3::new(1.0, 0.2, -0.3),
            Vec3::new(-0.4, 1.1, 0.2),
            Vec3::new(0.1, -0.8, 0.9),
        );
        let target = t.point_at(0.3, 0.3);
        for o in [
            Vec3::new(5.0, 0.1, 0.2),
            Vec3::new(-5.0, 0.3, 0.1),
            Vec3::new(0.2, 6.0, -0.1),
            Vec3::new(0.1, -6.0, 0.3),
            Vec3::new(0.0, 0.2, 7.0),
            Vec3::new(0.3, 0.0, -7.0),
        ] {
            let ray = Ray::new(o, target - o);
            for cull in [CullMode::None, CullMode::Back, CullMode::Front] {
                let a = intersect_ray_triangle(&ray, &t, cull);
                let b = intersect_ray_triangle_watertight(&ray, &t, cull);
                assert_eq!(a.is_some(), b.is_some(), "{o} {cull:?}");
                if let (Some(a), Some(b)) = (a, b) {
                    assert!((a.t - b.t).abs() < 1e-5 && (a.u - b.u).abs() < 1e-5, "{o}");
                    assert!((a.v - b.v).abs() < 1e-5, "{o}");
                }
            }
        }
    }

    #[test]
    fn culling_matches_the_counter_clockwise_front() {
        let from_front = Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z);
        let from_back = Ray::new(Vec3::new(0.2, 0.2, -1.0), Vec3::Z);
        let t = tri();
        assert!(intersect_ray_triangle_watertight(&from_front, &t, CullMode::Back).is_some());
        assert!(intersect_ray_triangle_watertight(&from_front, &t, CullMode::Front).is_none());
        assert!(intersect_ray_triangle_watertight(&from_back, &t, CullMode::Back).is_none());
        assert!(intersect_ray_triangle_watertight(&from_back, &t, CullMode::Front).is_some());
    }

    #[test]
    fn shared_edge_is_hit_by_one_side_or_both() {
        // Two triangles sharing the diagonal of a skewed quad; rays exactly through points of
        // the diagonal must hit at least one of them.
        let a = Vec3::new(0.1, 0.3, 0.7);
        let b = Vec3::new(1.3, 0.2, 0.9);
        let c = Vec3::new(1.1, 1.4, 0.1);
        let d = Vec3::new(-0.2, 1.2, 0.4);
        let t1 = Triangle::new(a, b, c);
        let t2 = Triangle::new(a, c, d);
        for i in 0..=64 {
            let p = a + (c - a) * (i as f32 / 64.0);
            let o = Vec3::new(0.37, 0.61, 5.0);
            let ray = Ray::new(o, p - o);
            let h1 = intersect_ray_triangle_watertight(&ray, &t1, CullMode::None);
            let h2 = intersect_ray_triangle_watertight(&ray, &t2, CullMode::None);
            assert!(h1.is_some() || h2.is_some(), "crack at step {i}");
        }
    }

    #[test]
    fn degenerate_inputs_never_hit() {
        let down = Ray::new(Vec3::new(0.2, 0.0, 1.0), -Vec3::Z);
        let line = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::X * 2.0);
        assert!(intersect_ray_triangle_watertight(&down, &line, CullMode::None).is_none());
        let parallel = Ray::new(Vec3::new(-1.0, 0.2, 0.0), Vec3::X);
        assert!(intersect_ray_triangle_watertight(&parallel, &tri(), CullMode::None).is_none());
        let zero = Ray::new(Vec3::new(0.2, 0.2, 1.0), Vec3::ZERO);
        assert!(intersect_ray_triangle_watertight(&zero, &tri(), CullMode::None).is_none());
        let nan = Ray::new(Vec3::new(0.2, f32::NAN, 1.0), -Vec3::Z);
        assert!(intersect_ray_triangle_watertight(&nan, &tri(), CullMode::None).is_none());
        let behind = Ray::new(Vec3::new(0.2, 0.2, 1.0), Vec3::Z);
        assert!(intersect_ray_triangle_watertight(&behind, &tri(), CullMode::None).is_none());
    }

    /// See [`check_power_of_two_scales`](crate::geom::test_support::check_power_of_two_scales):
    /// rays through shared edges too, where the exact edge signs decide.
    #[test]
    fn power_of_two_scales_give_the_unit_answer_scaled() {
        crate::geom::test_support::check_power_of_two_scales(|ray, tri, cull| {
            WatertightRay::new(ray).intersect(tri.a, tri.b, tri.c, cull)
        });
    }
}
