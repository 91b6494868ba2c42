//! Query results.

use glam::Vec3;

/// The closest intersection of a ray with a mesh.
///
/// The hit point is `ray.at(t)`, or equivalently `(1 − u − v)·a + u·b + v·c` on triangle `tri`
/// (up to rounding).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayHit {
    /// Ray parameter of the hit, in units of the ray direction's length, within
    /// `[t_min, t_max]`.
    pub t: f32,
    /// Index of the triangle hit, in the mesh's own triangle order.
    pub tri: u32,
    /// Barycentric weight of the triangle's second corner.
    pub u: f32,
    /// Barycentric weight of the triangle's third corner.
    pub v: f32,
}

impl RayHit {
    /// True when `self` should replace `best` under the crate's tie rule: a strictly smaller
    /// `t` wins; on equal `t` the lower triangle index wins.
    #[inline]
    #[must_use]
    pub fn beats(&self, best: &Self) -> bool {
        self.t < best.t || (self.t == best.t && self.tri < best.tri)
    }
}

/// Which part of a triangle a closest point lies on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TriangleFeature {
    /// Strictly inside the face.
    Face,
    /// On the edge from corner `i` to corner `(i + 1) % 3` (0 = ab, 1 = bc, 2 = ca), between its
    /// ends.
    Edge(u8),
    /// At corner `i` (0 = a, 1 = b, 2 = c).
    Vertex(u8),
}

/// The closest point of a mesh (or a triangle) to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClosestPoint {
    /// The closest point on the surface.
    pub point: Vec3,
    /// Index of the triangle it lies on (0 for a lone triangle).
    pub tri: u32,
    /// Barycentric weight of the triangle's second corner.
    pub u: f32,
    /// Barycentric weight of the triangle's third corner.
    pub v: f32,
    /// Squared Euclidean distance from the query point to `point`; `+∞` when the distance
    /// exceeds about 1.8e19 and its square overflows `f32` (the point and triangle are still
    /// the nearest: see [`ClosestPoint::distance_from`]).
    pub distance_squared: f32,
    /// Which feature of the triangle `point` lies on.
    pub feature: TriangleFeature,
}

impl ClosestPoint {
    /// The Euclidean distance `√distance_squared` (`+∞` when the square overflowed).
    #[inline]
    #[must_use]
    pub fn distance(&self) -> f32 {
        libm::sqrtf(self.distance_squared)
    }

    /// The Euclidean distance from `query` (the point this answers) to [`point`](Self::point),
    /// finite whenever it fits in `f32`, also past the 1.8e19 where
    /// [`distance_squared`](Self::distance_squared) overflows: the same as
    /// [`distance`](Self::distance) up to rounding when that is finite.
    #[must_use]
    pub fn distance_from(&self, query: Vec3) -> f32 {
        if self.distance_squared.is_finite() {
            return self.distance();
        }
        // Scaled by 2⁻⁶⁴ and back, exactly: the square of the scaled difference fits.
        const DOWN: f32 = 1.0 / 18_446_744_073_709_551_616.0;
        let d = (query - self.point) * DOWN;
        libm::sqrtf(d.dot(d)) * 18_446_744_073_709_551_616.0
    }

    /// True when `self` should replace `best`: a strictly smaller squared distance wins; on
    /// equal distance the lower triangle index wins.
    #[inline]
    #[must_use]
    pub fn beats(&self, best: &Self) -> bool {
        self.distance_squared < best.distance_squared
            || (self.distance_squared == best.distance_squared && self.tri < best.tri)
    }
}
