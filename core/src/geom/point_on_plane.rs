use glam::Vec3;

use crate::math::{Plane, dot};

/// True when `p` lies on `plane` within `relative` times the size of the question, plus the
/// rounding of `p`'s coordinates.
///
/// The size is the larger of `p`'s largest coordinate magnitude and the plane's distance from
/// the origin (`|offset| / |normal|`), so one `relative` serves a part in millimetres and a
/// terrain in metres alike. `relative = 0` accepts exactly the points whose distance to the
/// plane is within what rounding each coordinate to `f32` can cause (half a unit in the last
/// place each): a point computed on the plane in higher precision and stored as `f32` is
/// accepted. The residual `normal · p − offset` is evaluated in `f64`, where the products of
/// `f32` values are exact, so the answer does not depend on how large the coordinates are.
/// A zero or non-finite normal, a non-finite offset or point, and a negative or NaN
/// `relative` accept nothing.
///
/// ```
/// use meshq::{geom::point_on_plane, math::{Plane, Vec3}};
/// let tilted = Plane::from_point_normal(Vec3::new(1.0e6, 0.0, 0.0), Vec3::new(1.0, 1.0, 0.0));
/// assert!(point_on_plane(Vec3::new(1.0e6 - 0.5, 0.5, 5.0), &tilted, 0.0));
/// assert!(!point_on_plane(Vec3::new(1.0e6, 1.0, 5.0), &tilted, 0.0));
/// assert!(point_on_plane(Vec3::new(1.0e6, 1.0, 5.0), &tilted, 1e-6));
/// ```
#[must_use]
pub fn point_on_plane(p: Vec3, plane: &Plane, relative: f32) -> bool {
    let n = plane.normal;
    let nn = dot(n, n);
    if !(relative >= 0.0 && nn > 0.0 && nn.is_finite() && plane.offset.is_finite() && p.is_finite())
    {
        return false;
    }
    let wide = |x: f32| f64::from(x);
    let magnitude = |x: f64| if x < 0.0 { -x } else { x };
    let terms = [
        wide(n.x) * wide(p.x),
        wide(n.y) * wide(p.y),
        wide(n.z) * wide(p.z),
    ];
    let residual = magnitude(terms.iter().sum::<f64>() - wide(plane.offset));
    // Rounding a coordinate to f32 moves it by at most 2⁻²⁴ of itself, which moves the
    // residual by at most 2⁻²⁴ of the sum of the terms' magnitudes.
    let rounding = terms.iter().map(|&t| magnitude(t)).sum::<f64>() / 16_777_216.0;
    let normal_length = wide(libm::sqrtf(nn));
    let largest = wide(p.x.abs().max(p.y.abs()).max(p.z.abs()));
    let size = largest.max(magnitude(wide(plane.offset)) / normal_length);
    residual <= rounding + wide(relative) * size * normal_length
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_planes_points_and_tolerances() {
        let floor = Plane::from_point_normal(Vec3::ZERO, Vec3::Y);
        assert!(point_on_plane(Vec3::new(3.0, 0.0, -2.0), &floor, 0.0));
        assert!(!point_on_plane(Vec3::new(3.0, 1e-3, -2.0), &floor, 0.0));
        assert!(!point_on_plane(Vec3::ZERO, &floor, -1.0));
        assert!(!point_on_plane(Vec3::ZERO, &floor, f32::NAN));
        assert!(!point_on_plane(Vec3::new(f32::NAN, 0.0, 0.0), &floor, 1.0));
        let none = Plane {
            normal: Vec3::ZERO,
            offset: 0.0,
        };
        assert!(!point_on_plane(Vec3::ZERO, &none, 1.0));
    }

    #[test]
    fn huge_coordinates_do_not_overflow() {
        let far = Plane::from_point_normal(Vec3::splat(1e30), Vec3::X);
        assert!(point_on_plane(Vec3::new(1e30, -3e30, 0.0), &far, 0.0));
        assert!(!point_on_plane(Vec3::new(1.1e30, 0.0, 0.0), &far, 0.0));
    }
}
