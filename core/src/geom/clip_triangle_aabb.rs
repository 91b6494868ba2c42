use glam::Vec3;

use crate::math::{Aabb, Triangle};

/// Most corners a triangle clipped by a box can have: each of the six planes adds at most one.
const MAX_CORNERS: usize = 9;

/// The part of a triangle inside a box: a convex polygon of up to nine corners, from
/// [`clip_triangle_aabb`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClippedTriangle {
    corners: [Vec3; MAX_CORNERS],
    len: usize,
}

impl ClippedTriangle {
    /// The polygon's corners, in the triangle's winding; empty when nothing is inside.
    #[must_use]
    pub fn corners(&self) -> &[Vec3] {
        self.corners.get(..self.len).unwrap_or(&[])
    }

    /// Whether nothing of the triangle is inside the box.
    #[must_use]
    pub const fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The bounds of the clipped part (empty when nothing is inside).
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        Aabb::from_points(self.corners())
    }
}

/// The part of triangle `tri` inside box `aabb` (faces included), by clipping against the six
/// face planes in turn (Sutherland–Hodgman).
///
/// New corners are interpolated in `f32`, so they lie within a few ulps of the true polygon;
/// they are clamped into the box, so the result's bounds never leave it. A triangle that only
/// touches the box (at a corner, an edge or a face) gives the touching points; a degenerate
/// triangle gives a degenerate polygon. Non-finite input gives an empty polygon.
///
/// ```
/// use meshq::{advanced::clip_triangle_aabb, math::{Aabb, Triangle, Vec3}};
/// let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
/// let tri = Triangle::new(Vec3::new(-1.0, 0.5, 0.5), Vec3::new(3.0, 0.5, 0.5), Vec3::new(1.0, 0.5, 2.5));
/// let part = clip_triangle_aabb(&tri, &unit);
/// assert_eq!(part.bounds().max.x, 1.0);
/// assert_eq!(part.bounds().max.z, 1.0);
/// ```
#[must_use]
pub fn clip_triangle_aabb(tri: &Triangle, aabb: &Aabb) -> ClippedTriangle {
    let mut poly = ClippedTriangle {
        corners: [Vec3::ZERO; MAX_CORNERS],
        len: 0,
    };
    if aabb.is_empty()
        || !aabb.is_finite()
        || !(tri.a.is_finite() && tri.b.is_finite() && tri.c.is_finite())
    {
        return poly;
    }
    poly.corners[..3].copy_from_slice(&[tri.a, tri.b, tri.c]);
    poly.len = 3;
    for axis in 0..3 {
        poly = clip_plane(&poly, axis, aabb.min[axis], false);
        poly = clip_plane(&poly, axis, aabb.max[axis], true);
    }
    for p in poly.corners.iter_mut() {
        *p = p.clamp(aabb.min, aabb.max);
    }
    poly
}

/// Keeps the part of `poly` with coordinate `axis` at least `plane` (at most, when `below`).
fn clip_plane(poly: &ClippedTriangle, axis: usize, plane: f32, below: bool) -> ClippedTriangle {
    let mut out = ClippedTriangle {
        corners: [Vec3::ZERO; MAX_CORNERS],
        len: 0,
    };
    let inside = |p: Vec3| {
        if below {
            p[axis] <= plane
        } else {
            p[axis] >= plane
        }
    };
    let corners = poly.corners();
    let Some(&last) = corners.last() else {
        return out;
    };
    let mut push = |p: Vec3| {
        if let Some(slot) = out.corners.get_mut(out.len) {
            *slot = p;
            out.len += 1;
        }
    };
    let mut prev = last;
    for &cur in corners {
        match (inside(prev), inside(cur)) {
            (true, true) => push(cur),
            (true, false) => push(crossing(prev, cur, axis, plane)),
            (false, true) => {
                push(crossing(prev, cur, axis, plane));
                push(cur);
            }
            (false, false) => {}
        }
        prev = cur;
    }
    out
}

/// Where segment `p`–`q` (on opposite sides) crosses the plane `axis = plane`, set exactly on
/// the plane along `axis`.
fn crossing(p: Vec3, q: Vec3, axis: usize, plane: f32) -> Vec3 {
    let s = (plane - p[axis]) / (q[axis] - p[axis]);
    let mut x = p + (q - p) * s;
    x[axis] = plane;
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inside_triangle_is_unchanged() {
        let t = Triangle::new(
            Vec3::splat(0.1),
            Vec3::new(0.9, 0.1, 0.1),
            Vec3::new(0.1, 0.9, 0.5),
        );
        let c = clip_triangle_aabb(&t, &Aabb::new(Vec3::ZERO, Vec3::ONE));
        assert_eq!(c.corners(), &[t.a, t.b, t.c]);
    }

    #[test]
    fn outside_triangle_is_empty() {
        let t = Triangle::new(
            Vec3::splat(2.0),
            Vec3::new(3.0, 2.0, 2.0),
            Vec3::new(2.0, 3.0, 2.0),
        );
        assert!(clip_triangle_aabb(&t, &Aabb::new(Vec3::ZERO, Vec3::ONE)).is_empty());
    }

    #[test]
    fn big_triangle_clips_to_the_box_face() {
        // A triangle covering the plane z = 0.5 far beyond the box: the part inside is the
        // square cross-section.
        let t = Triangle::new(
            Vec3::new(-10.0, -10.0, 0.5),
            Vec3::new(30.0, -10.0, 0.5),
            Vec3::new(-10.0, 30.0, 0.5),
        );
        let c = clip_triangle_aabb(&t, &Aabb::new(Vec3::ZERO, Vec3::ONE));
        assert_eq!(c.corners().len(), 4);
        assert_eq!(
            c.bounds(),
            Aabb::new(Vec3::new(0.0, 0.0, 0.5), Vec3::new(1.0, 1.0, 0.5))
        );
    }
}
