use glam::Vec3A;

use crate::math::{Aabb, Ray, max_f32, min_f32};

/// A ray prepared for the traversal's slab tests: its origin and a padded inverse direction.
///
/// A zero (or denormal) direction component would give an infinite inverse, and `0 · ∞` is NaN
/// when the origin lies on a slab plane. The inverse is therefore clamped to `±f32::MAX`, which
/// behaves like an exactly axis-parallel ray for any `t` a mesh can produce and keeps every slab
/// value a number. (It would miss a ray lying exactly in a `max` face plane; tree boxes are
/// padded beyond their triangles, so that plane never holds a triangle.)
///
/// The slab arithmetic runs on `Vec3A` (SIMD lanes where the target has them). That is safe for
/// bit-identical answers: box tests only decide which leaves a query visits, conservatively
/// (see the margins in the queries), and a query's answer is the minimum under a total order
/// (distance, then triangle index), whatever order leaves are visited in.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SlabRay {
    pub origin: Vec3A,
    pub inv_dir: Vec3A,
    pub t_min: f32,
    pub t_max: f32,
}

#[inline(always)]
fn padded_inverse(d: f32) -> f32 {
    let inv = 1.0 / d;
    if inv.is_finite() {
        inv
    } else {
        libm::copysignf(f32::MAX, d)
    }
}

impl SlabRay {
    #[inline(always)]
    pub fn new(ray: &Ray) -> Self {
        Self {
            origin: ray.origin.into(),
            inv_dir: Vec3A::new(
                padded_inverse(ray.dir.x),
                padded_inverse(ray.dir.y),
                padded_inverse(ray.dir.z),
            ),
            t_min: ray.t_min,
            t_max: ray.t_max,
        }
    }

    /// Entry and exit of the box clipped to `[t_min, t_max]`; entry > exit means a miss.
    #[inline(always)]
    pub fn clip(&self, min: [f32; 3], max: [f32; 3]) -> (f32, f32) {
        let t0 = (Vec3A::from_array(min) - self.origin) * self.inv_dir;
        let t1 = (Vec3A::from_array(max) - self.origin) * self.inv_dir;
        let entry = max_f32(t0.min(t1).max_element(), self.t_min);
        let exit = min_f32(t0.max(t1).min_element(), self.t_max);
        (entry, exit)
    }
}

/// The part of `ray` inside `aabb`, as `(t_entry, t_exit)` clipped to `[t_min, t_max]`.
///
/// A ray starting inside the box gets `t_entry = t_min`. Boundaries count as inside, so a ray
/// grazing a face or an edge hits. Returns `None` for a miss, an empty or non-finite box and an
/// invalid ray ([`Ray::is_valid`]); no NaN ever reaches a comparison.
///
/// ```
/// use meshq::{geom::intersect_ray_aabb, math::{Aabb, Ray, Vec3}};
/// let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
/// let ray = Ray::new(Vec3::new(-1.0, 0.5, 0.5), Vec3::X);
/// assert_eq!(intersect_ray_aabb(&ray, &unit), Some((1.0, 2.0)));
/// ```
#[must_use]
pub fn intersect_ray_aabb(ray: &Ray, aabb: &Aabb) -> Option<(f32, f32)> {
    if !ray.is_valid() || aabb.is_empty() || !aabb.is_finite() {
        return None;
    }
    // Exact per-axis handling (a division, not the traversal's padded inverse), so a ray lying
    // in a face plane is inside for every face, `max` faces included.
    let mut entry = ray.t_min;
    let mut exit = ray.t_max;
    for axis in 0..3 {
        let (o, d, lo, hi) = (
            ray.origin[axis],
            ray.dir[axis],
            aabb.min[axis],
            aabb.max[axis],
        );
        if d == 0.0 {
            if o < lo || o > hi {
                return None;
            }
            continue;
        }
        let t0 = (lo - o) / d;
        let t1 = (hi - o) / d;
        let (near, far) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
        entry = max_f32(near, entry);
        exit = min_f32(far, exit);
    }
    (entry <= exit).then_some((entry, exit))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    const UNIT: Aabb = Aabb::new(Vec3::ZERO, Vec3::ONE);

    #[test]
    fn entry_and_exit_along_each_axis_and_diagonal() {
        for axis in [Vec3::X, Vec3::Y, Vec3::Z] {
            let o = Vec3::splat(0.5) - axis * 2.0;
            assert_eq!(
                intersect_ray_aabb(&Ray::new(o, axis), &UNIT),
                Some((1.5, 2.5))
            );
            assert_eq!(
                intersect_ray_aabb(&Ray::new(o, axis * 0.5), &UNIT),
                Some((3.0, 5.0))
            );
        }
        let diag = Ray::new(Vec3::splat(-1.0), Vec3::ONE);
        assert_eq!(intersect_ray_aabb(&diag, &UNIT), Some((1.0, 2.0)));
    }

    #[test]
    fn inside_start_and_range_clipping() {
        let inside = Ray::new(Vec3::splat(0.5), Vec3::X);
        assert_eq!(intersect_ray_aabb(&inside, &UNIT), Some((0.0, 0.5)));
        let clipped = Ray::new(Vec3::new(-1.0, 0.5, 0.5), Vec3::X).with_range(1.25, 1.5);
        assert_eq!(intersect_ray_aabb(&clipped, &UNIT), Some((1.25, 1.5)));
        let too_short = Ray::new(Vec3::new(-1.0, 0.5, 0.5), Vec3::X).with_range(0.0, 0.5);
        assert_eq!(intersect_ray_aabb(&too_short, &UNIT), None);
    }

    #[test]
    fn ray_lying_in_a_face_plane_is_inside_not_nan() {
        // The origin is exactly on the x = 0 slab plane and dir.x = 0: 0 · ∞ would be NaN.
        let on_face = Ray::new(Vec3::new(0.0, -1.0, 0.5), Vec3::Y);
        assert_eq!(intersect_ray_aabb(&on_face, &UNIT), Some((1.0, 2.0)));
        let on_edge = Ray::new(Vec3::new(1.0, -1.0, 1.0), Vec3::Y);
        assert_eq!(intersect_ray_aabb(&on_edge, &UNIT), Some((1.0, 2.0)));
        let beside = Ray::new(Vec3::new(1.0001, -1.0, 0.5), Vec3::Y);
        assert_eq!(intersect_ray_aabb(&beside, &UNIT), None);
    }

    #[test]
    fn parallel_outside_behind_and_degenerate_miss() {
        assert_eq!(
            intersect_ray_aabb(&Ray::new(Vec3::new(-1.0, 2.0, 0.5), Vec3::X), &UNIT),
            None
        );
        assert_eq!(
            intersect_ray_aabb(&Ray::new(Vec3::new(2.0, 0.5, 0.5), Vec3::X), &UNIT),
            None
        );
        assert_eq!(
            intersect_ray_aabb(&Ray::new(Vec3::splat(0.5), Vec3::ZERO), &UNIT),
            None
        );
        let nan = Ray::new(Vec3::new(f32::NAN, 0.5, 0.5), Vec3::X);
        assert_eq!(intersect_ray_aabb(&nan, &UNIT), None);
        let nan_dir = Ray::new(Vec3::ZERO, Vec3::new(1.0, f32::NAN, 0.0));
        assert_eq!(intersect_ray_aabb(&nan_dir, &UNIT), None);
        assert_eq!(
            intersect_ray_aabb(&Ray::new(Vec3::splat(-1.0), Vec3::ONE), &Aabb::EMPTY),
            None
        );
    }

    #[test]
    fn denormal_direction_components_stay_finite() {
        let ray = Ray::new(Vec3::new(0.0, -1.0, 0.5), Vec3::new(1e-45, 1.0, 0.0));
        assert_eq!(intersect_ray_aabb(&ray, &UNIT), Some((1.0, 2.0)));
    }
}
