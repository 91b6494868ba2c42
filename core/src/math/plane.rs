//! Planes in normal–offset form.

use glam::Vec3;

/// The plane of points `x` with `normal · x = offset`.
///
/// `normal` need not be unit length; functions that return distances say how they scale. A zero
/// normal describes no plane and every query on it returns `None` or the input unchanged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// Normal direction (any non-zero length).
    pub normal: Vec3,
    /// `normal · x` for every point `x` of the plane.
    pub offset: f32,
}

impl Plane {
    /// The plane with `normal` through `point`.
    #[inline]
    #[must_use]
    pub fn from_point_normal(point: Vec3, normal: Vec3) -> Self {
        Self {
            normal,
            offset: super::dot(normal, point),
        }
    }

    /// `normal · p − offset`: positive on the side `normal` points to, in units of `|normal|`
    /// times a length.
    #[inline]
    #[must_use]
    pub(crate) fn signed_distance_scaled(&self, p: Vec3) -> f32 {
        super::dot(self.normal, p) - self.offset
    }
}
