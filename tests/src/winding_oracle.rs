//! The generalized winding number in `f64`, by brute force: every triangle's solid angle (Van
//! Oosterom and Strackee) summed in double precision. Shares no code with the core.

use glam::{DVec3, Vec3};

/// The winding number of the triangles `triangles` over `positions` at `p`, in `f64`.
#[must_use]
pub fn winding_number_f64(positions: &[[f32; 3]], triangles: &[[u32; 3]], p: Vec3) -> f64 {
    let q = p.as_dvec3();
    let corner = |i: u32| Vec3::from_array(positions[i as usize]).as_dvec3() - q;
    let mut sum = 0.0f64;
    for &[i, j, k] in triangles {
        let (a, b, c) = (corner(i), corner(j), corner(k));
        let triple = a.dot(b.cross(c));
        let (la, lb, lc) = (a.length(), b.length(), c.length());
        let below = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
        sum += 2.0 * triple.atan2(below);
    }
    sum / (4.0 * std::f64::consts::PI)
}

/// Whether a ray from `p` along `dir` crosses the triangles an odd number of times, in `f64`
/// (Möller–Trumbore without culling; hits at `t ≤ 0` do not count).
#[must_use]
pub fn odd_crossings_f64(
    positions: &[[f32; 3]],
    triangles: &[[u32; 3]],
    p: Vec3,
    dir: DVec3,
) -> bool {
    let o = p.as_dvec3();
    let v = |i: u32| Vec3::from_array(positions[i as usize]).as_dvec3();
    let mut odd = false;
    for &[i, j, k] in triangles {
        let (a, b, c) = (v(i), v(j), v(k));
        let (e1, e2) = (b - a, c - a);
        let h = dir.cross(e2);
        let det = e1.dot(h);
        if det == 0.0 {
            continue;
        }
        let s = o - a;
        let u = s.dot(h) / det;
        let q = s.cross(e1);
        let w = dir.dot(q) / det;
        let t = e2.dot(q) / det;
        if u >= 0.0 && w >= 0.0 && u + w <= 1.0 && t > 0.0 {
            odd = !odd;
        }
    }
    odd
}
