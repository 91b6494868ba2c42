//! The solid angle a triangle subtends at a point.

use glam::Vec3;

use crate::math::{Triangle, cross, dot};

/// The signed solid angle, in steradians, that `tri` subtends at `p`: in `[−2π, 2π]`, positive
/// when `p` lies behind the triangle (on the side its normal `(b − a) × (c − a)` points away
/// from). Over a closed mesh whose triangles face outwards the angles sum to `4π` at a point
/// inside and to `0` at a point outside; divided by `4π`, the sum is the generalized winding
/// number.
///
/// Van Oosterom and Strackee's closed form: with the corners taken relative to `p`,
/// `Ω = 2·atan2(a · (b × c), |a||b||c| + (a · b)|c| + (a · c)|b| + (b · c)|a|)`. Exactly `0`
/// when `p` lies on the triangle's plane as far as `f32` can tell (the triple product is 0),
/// which includes every point of a degenerate triangle's line and a point on the triangle
/// itself, where the angle jumps from `+2π` to `−2π` and `0` is the mean of the two sides.
/// NaN when a coordinate is NaN or infinite.
#[inline]
#[must_use]
pub fn solid_angle_triangle(tri: &Triangle, p: Vec3) -> f32 {
    let (a, b, c) = (tri.a - p, tri.b - p, tri.c - p);
    let triple = dot(a, cross(b, c));
    if triple == 0.0 {
        return 0.0;
    }
    let (la, lb, lc) = (length(a), length(b), length(c));
    let below = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
    2.0 * libm::atan2f(triple, below)
}

/// `|v|` through `libm`, so every target rounds it alike.
#[inline]
fn length(v: Vec3) -> f32 {
    libm::sqrtf(dot(v, v))
}

#[cfg(test)]
mod tests {
    use super::*;

    const FOUR_PI: f32 = 4.0 * core::f32::consts::PI;

    /// The eight outward faces of the octahedron with corners at ±1 on the axes.
    fn octahedron() -> [Triangle; 8] {
        let mut out = [Triangle::new(Vec3::ZERO, Vec3::ZERO, Vec3::ZERO); 8];
        let mut k = 0;
        for sx in [-1.0f32, 1.0] {
            for sy in [-1.0f32, 1.0] {
                for sz in [-1.0f32, 1.0] {
                    let (x, y, z) = (Vec3::X * sx, Vec3::Y * sy, Vec3::Z * sz);
                    // Counter-clockwise seen from outside when the octant's sign product is +.
                    out[k] = if sx * sy * sz > 0.0 {
                        Triangle::new(x, y, z)
                    } else {
                        Triangle::new(x, z, y)
                    };
                    k += 1;
                }
            }
        }
        out
    }

    #[test]
    fn a_closed_surface_sums_to_four_pi_inside_and_zero_outside() {
        let faces = octahedron();
        let sum = |p: Vec3| {
            faces
                .iter()
                .map(|t| solid_angle_triangle(t, p))
                .sum::<f32>()
        };
        for p in [
            Vec3::ZERO,
            Vec3::new(0.2, -0.1, 0.3),
            Vec3::new(-0.3, 0.3, -0.3),
        ] {
            assert!((sum(p) - FOUR_PI).abs() < 1e-5, "{p}: {}", sum(p));
        }
        for p in [
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.5, 0.5, 0.5),
            Vec3::splat(-9.0),
        ] {
            assert!(sum(p).abs() < 1e-5, "{p}: {}", sum(p));
        }
    }

    #[test]
    fn an_octant_face_subtends_an_eighth_of_the_sphere() {
        let t = Triangle::new(Vec3::X, Vec3::Y, Vec3::Z);
        assert!((solid_angle_triangle(&t, Vec3::ZERO) - FOUR_PI / 8.0).abs() < 1e-6);
        let flipped = Triangle::new(Vec3::X, Vec3::Z, Vec3::Y);
        assert!((solid_angle_triangle(&flipped, Vec3::ZERO) + FOUR_PI / 8.0).abs() < 1e-6);
    }

    #[test]
    fn points_on_the_plane_and_degenerate_triangles_give_zero() {
        let t = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
        assert_eq!(solid_angle_triangle(&t, Vec3::new(0.2, 0.2, 0.0)), 0.0);
        assert_eq!(solid_angle_triangle(&t, Vec3::new(5.0, 5.0, 0.0)), 0.0);
        let line = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::X * 2.0);
        assert_eq!(solid_angle_triangle(&line, Vec3::new(0.3, 1.0, 0.5)), 0.0);
        assert!(solid_angle_triangle(&t, Vec3::new(f32::NAN, 0.0, 1.0)).is_nan());
    }
}
