//! Rays with an explicit parameter interval.

use glam::Vec3;

/// A ray `origin + t·dir` restricted to `t ∈ [t_min, t_max]` (both ends inclusive).
///
/// Conventions:
/// - `dir` is **not normalized** and never normalized for you: `t` is measured in units of
///   `dir`'s length, so a hit at `t` lies at `origin + t·dir`. Use [`Ray::normalized`] if you
///   want `t` to be a distance.
/// - A ray with a non-finite component, a zero direction, `t_min > t_max` or a NaN bound never
///   hits anything (see [`Ray::is_valid`]).
/// - `t_max` may be `+∞` (the default).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Start point.
    pub origin: Vec3,
    /// Direction, any non-zero length.
    pub dir: Vec3,
    /// Smallest accepted `t` (inclusive). Default 0.
    pub t_min: f32,
    /// Largest accepted `t` (inclusive). Default `+∞`.
    pub t_max: f32,
}

impl Ray {
    /// A ray over `t ∈ [0, +∞]`.
    #[inline]
    #[must_use]
    pub const fn new(origin: Vec3, dir: Vec3) -> Self {
        Self {
            origin,
            dir,
            t_min: 0.0,
            t_max: f32::INFINITY,
        }
    }

    /// The same ray restricted to `t ∈ [t_min, t_max]`.
    #[inline]
    #[must_use]
    pub const fn with_range(self, t_min: f32, t_max: f32) -> Self {
        Self {
            t_min,
            t_max,
            ..self
        }
    }

    /// The segment from `from` to `to`, as a ray: origin `from`, direction `to − from`, `t` in
    /// `[0, 1]` (both ends inclusive), so a hit's `t` is the fraction of the way to `to`. Any
    /// query takes it (closest hit, any hit, batches), on every structure. A segment of zero
    /// length, or with a non-finite end, hits nothing.
    ///
    /// ```
    /// use meshq::math::{Ray, Vec3};
    /// let s = Ray::segment(Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.0, 0.0, -3.0));
    /// assert_eq!((s.dir, s.t_min, s.t_max), (Vec3::new(0.0, 0.0, -4.0), 0.0, 1.0));
    /// assert_eq!(s.at(0.25), Vec3::ZERO);
    /// ```
    #[inline]
    #[must_use]
    pub fn segment(from: Vec3, to: Vec3) -> Self {
        Self::new(from, to - from).with_range(0.0, 1.0)
    }

    /// A ray over `[0, +∞]` whose direction is `dir` scaled to unit length (so `t` is a
    /// distance). A zero or non-finite `dir` is kept as is, which makes the ray invalid.
    #[must_use]
    pub fn normalized(origin: Vec3, dir: Vec3) -> Self {
        let len = libm::sqrtf(super::dot(dir, dir));
        let dir = if len > 0.0 && len.is_finite() {
            dir / len
        } else {
            dir
        };
        Self::new(origin, dir)
    }

    /// The point `origin + t·dir`.
    #[inline]
    #[must_use]
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + self.dir * t
    }

    /// True when the ray can hit something: finite origin and direction, a non-zero direction,
    /// `t_min` finite or `−∞`, `t_max` finite or `+∞`, and `t_min ≤ t_max`.
    #[inline]
    #[must_use]
    pub fn is_valid(&self) -> bool {
        self.origin.is_finite()
            && self.dir.is_finite()
            && self.dir != Vec3::ZERO
            && self.t_min <= self.t_max
            && self.t_min < f32::INFINITY
            && self.t_max > f32::NEG_INFINITY
    }
}
