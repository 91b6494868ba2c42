//! Exact orientation signs of `f32` points: the sign of the determinant as real numbers would
//! give it, by Shewchuk's adaptive predicates (the `robust` crate; its inputs are the points
//! widened to `f64`, exactly). Every target gives the same sign.

use glam::{Vec2, Vec3};

/// `-1`, `0` or `1`: the sign of `x`.
fn sign(x: f64) -> i8 {
    if x > 0.0 {
        1
    } else if x < 0.0 {
        -1
    } else {
        0
    }
}

fn coord3(v: Vec3) -> robust::Coord3D<f64> {
    robust::Coord3D {
        x: f64::from(v.x),
        y: f64::from(v.y),
        z: f64::from(v.z),
    }
}

/// The exact sign of the orientation of `d` against the plane through `a`, `b`, `c`: `0`
/// exactly when the four points are coplanar, and opposite signs for points on opposite
/// sides. Finite input only (the sign is meaningless otherwise).
pub(crate) fn orient3d(a: Vec3, b: Vec3, c: Vec3, d: Vec3) -> i8 {
    sign(robust::orient3d(coord3(a), coord3(b), coord3(c), coord3(d)))
}

/// The exact sign of the orientation of `c` against the line through `a` and `b`: `1` when
/// `a`, `b`, `c` turn counter-clockwise, `-1` clockwise, `0` exactly when they are collinear.
/// Finite input only.
pub(crate) fn orient2d(a: Vec2, b: Vec2, c: Vec2) -> i8 {
    let coord = |v: Vec2| robust::Coord {
        x: f64::from(v.x),
        y: f64::from(v.y),
    };
    sign(robust::orient2d(coord(a), coord(b), coord(c)))
}

/// `v` with coordinate `axis` dropped (0: `(y, z)`, 1: `(z, x)`, 2: `(x, y)`): exact.
pub(crate) fn dropped(v: Vec3, axis: usize) -> Vec2 {
    match axis {
        0 => Vec2::new(v.y, v.z),
        1 => Vec2::new(v.z, v.x),
        _ => Vec2::new(v.x, v.y),
    }
}

/// An axis whose dropping keeps triangle `t` non-degenerate (its projection has area), `z`
/// first, then `y`, then `x`; `None` exactly when the corners are collinear (or coincide).
pub(crate) fn projection_axis(t: [Vec3; 3]) -> Option<usize> {
    [2, 1, 0].into_iter().find(|&axis| {
        let [a, b, c] = t.map(|v| dropped(v, axis));
        orient2d(a, b, c) != 0
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn signs_are_exact_at_the_smallest_offsets() {
        // `d` is the exact midpoint of `b` and `c`, so the four points are coplanar; one step
        // of the smallest subnormal off the plane along z gives opposite signs on both sides.
        let e = f32::EPSILON;
        let a = Vec3::new(0.1, 0.2, 0.3);
        let b = Vec3::new(1.0 + e, 0.0, 0.0);
        let c = Vec3::new(0.0, 1.0 + e, 0.0);
        let d = Vec3::new(0.5 + e / 2.0, 0.5 + e / 2.0, 0.0);
        assert_eq!(orient3d(a, b, c, d), 0);
        let tiny = f32::from_bits(1);
        let above = orient3d(a, b, c, d + Vec3::Z * tiny);
        let below = orient3d(a, b, c, d - Vec3::Z * tiny);
        assert!(above != 0 && above == -below);
        assert_eq!(
            orient3d(a, b, c, a + Vec3::Z),
            -orient3d(b, a, c, a + Vec3::Z)
        );
        assert_eq!(orient2d(Vec2::ZERO, Vec2::X, Vec2::new(7.0, 0.0)), 0);
        assert_eq!(orient2d(Vec2::ZERO, Vec2::X, Vec2::new(7.0, 1e-30)), 1);
        assert_eq!(orient2d(Vec2::ZERO, Vec2::X, Vec2::new(7.0, -1e-30)), -1);
        assert_eq!(projection_axis([Vec3::ZERO, Vec3::X, Vec3::X * 2.0]), None);
        assert_eq!(projection_axis([Vec3::ZERO, Vec3::Y, Vec3::Z]), Some(0));
    }
}
