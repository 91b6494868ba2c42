use crate::math::{Plane, Ray, dot};

/// Where `ray` crosses `plane`: `t = (offset − N·o) / (N·d)`, if `t ∈ [t_min, t_max]`.
///
/// Returns `None` for a ray parallel to the plane (`N·d = 0`, including a ray lying in it), for a
/// zero normal, for an invalid ray ([`Ray::is_valid`]) and when `t` falls outside the ray's
/// interval. Both sides of the plane count.
///
/// ```
/// use meshq::{geom::intersect_ray_plane, math::{Plane, Ray, Vec3}};
/// let floor = Plane::from_point_normal(Vec3::ZERO, Vec3::Y);
/// let t = intersect_ray_plane(&Ray::new(Vec3::new(0.0, 2.0, 0.0), -Vec3::Y * 4.0), &floor);
/// assert_eq!(t, Some(0.5));
/// ```
#[must_use]
pub fn intersect_ray_plane(ray: &Ray, plane: &Plane) -> Option<f32> {
    if !ray.is_valid() {
        return None;
    }
    let denom = dot(plane.normal, ray.dir);
    if denom == 0.0 || !denom.is_finite() {
        return None;
    }
    let t = (plane.offset - dot(plane.normal, ray.origin)) / denom;
    (t >= ray.t_min && t <= ray.t_max).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Vec3;

    const FLOOR: Plane = Plane {
        normal: Vec3::Y,
        offset: 1.0,
    };

    #[test]
    fn hits_from_both_sides_and_scales_t_by_direction_length() {
        let down = Ray::new(Vec3::new(3.0, 5.0, -2.0), Vec3::new(0.0, -2.0, 0.0));
        assert_eq!(intersect_ray_plane(&down, &FLOOR), Some(2.0));
        let up = Ray::new(Vec3::new(0.0, -3.0, 0.0), Vec3::Y);
        assert_eq!(intersect_ray_plane(&up, &FLOOR), Some(4.0));
    }

    #[test]
    fn parallel_behind_and_out_of_range_miss() {
        let parallel = Ray::new(Vec3::new(0.0, 1.0, 0.0), Vec3::X);
        assert_eq!(intersect_ray_plane(&parallel, &FLOOR), None);
        let away = Ray::new(Vec3::new(0.0, 5.0, 0.0), Vec3::Y);
        assert_eq!(intersect_ray_plane(&away, &FLOOR), None);
        let short = Ray::new(Vec3::new(0.0, 5.0, 0.0), -Vec3::Y).with_range(0.0, 3.9);
        assert_eq!(intersect_ray_plane(&short, &FLOOR), None);
    }

    #[test]
    fn degenerate_inputs_miss() {
        let zero_dir = Ray::new(Vec3::new(0.0, 5.0, 0.0), Vec3::ZERO);
        assert_eq!(intersect_ray_plane(&zero_dir, &FLOOR), None);
        let nan = Ray::new(Vec3::new(f32::NAN, 5.0, 0.0), -Vec3::Y);
        assert_eq!(intersect_ray_plane(&nan, &FLOOR), None);
        let no_plane = Plane {
            normal: Vec3::ZERO,
            offset: 0.0,
        };
        assert_eq!(
            intersect_ray_plane(&Ray::new(Vec3::ZERO, Vec3::Y), &no_plane),
            None
        );
    }
}
