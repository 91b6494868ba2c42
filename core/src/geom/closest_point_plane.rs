use glam::Vec3;

use crate::math::{Plane, dot};

/// The orthogonal projection of `p` onto `plane`: `p − N·(N·p − offset)/(N·N)`.
///
/// The normal need not be unit length. A zero normal (no plane) returns `p` unchanged.
///
/// ```
/// use meshq::{geom::closest_point_plane, math::{Plane, Vec3}};
/// let floor = Plane::from_point_normal(Vec3::ZERO, Vec3::Y * 3.0);
/// assert_eq!(closest_point_plane(Vec3::new(1.0, 2.0, 3.0), &floor), Vec3::new(1.0, 0.0, 3.0));
/// ```
#[must_use]
pub fn closest_point_plane(p: Vec3, plane: &Plane) -> Vec3 {
    let nn = dot(plane.normal, plane.normal);
    if nn == 0.0 || !nn.is_finite() {
        return p;
    }
    p - plane.normal * (plane.signed_distance_scaled(p) / nn)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn projects_along_an_unnormalized_normal() {
        let plane = Plane::from_point_normal(Vec3::new(0.0, 0.0, 2.0), Vec3::new(0.0, 0.0, -5.0));
        let q = closest_point_plane(Vec3::new(1.0, -1.0, 7.0), &plane);
        assert_eq!(q, Vec3::new(1.0, -1.0, 2.0));
    }

    #[test]
    fn zero_normal_leaves_the_point() {
        let none = Plane {
            normal: Vec3::ZERO,
            offset: 1.0,
        };
        assert_eq!(closest_point_plane(Vec3::ONE, &none), Vec3::ONE);
    }
}
