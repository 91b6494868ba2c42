//! Triangles by value.

use glam::Vec3;

use super::{Aabb, cross, dot};

/// A triangle given by its three corners in counter-clockwise order as seen from its front.
///
/// The *front* is the side `(b − a) × (c − a)` points to. Barycentric coordinates `(u, v)` used
/// across the crate follow the Möller–Trumbore convention: the point is
/// `(1 − u − v)·a + u·b + v·c`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    /// First corner.
    pub a: Vec3,
    /// Second corner.
    pub b: Vec3,
    /// Third corner.
    pub c: Vec3,
}

impl Triangle {
    /// A triangle from its corners.
    #[inline]
    #[must_use]
    pub const fn new(a: Vec3, b: Vec3, c: Vec3) -> Self {
        Self { a, b, c }
    }

    /// The unnormalized normal `(b − a) × (c − a)`; its length is twice the area.
    #[inline]
    #[must_use]
    pub fn normal(&self) -> Vec3 {
        cross(self.b - self.a, self.c - self.a)
    }

    /// The unit normal, or `None` for a degenerate triangle.
    #[must_use]
    pub fn unit_normal(&self) -> Option<Vec3> {
        let n = self.normal();
        let len = libm::sqrtf(dot(n, n));
        (len > 0.0 && len.is_finite()).then(|| n / len)
    }

    /// The area, `|normal| / 2`.
    #[must_use]
    pub fn area(&self) -> f32 {
        let n = self.normal();
        0.5 * libm::sqrtf(dot(n, n))
    }

    /// True when the computed normal is exactly the zero vector: the corners are collinear or
    /// coincide as far as `f32` can tell.
    ///
    /// This is the crate-wide definition of a *degenerate* (zero-area) triangle. Such triangles
    /// stay in a mesh but are never returned by any query.
    #[inline]
    #[must_use]
    pub fn is_degenerate(&self) -> bool {
        self.normal() == Vec3::ZERO
    }

    /// The bounding box of the three corners.
    #[inline]
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        Aabb::new(self.a, self.a).grown(self.b).grown(self.c)
    }

    /// The point with barycentric coordinates `(u, v)`: `(1 − u − v)·a + u·b + v·c`.
    #[inline]
    #[must_use]
    pub fn point_at(&self, u: f32, v: f32) -> Vec3 {
        self.a * (1.0 - u - v) + self.b * u + self.c * v
    }
}
