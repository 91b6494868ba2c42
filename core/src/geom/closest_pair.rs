use glam::Vec3;

/// The closest points between two shapes: two triangles, a segment and a triangle, a box and a
/// triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClosestPair {
    /// The point of the first shape nearest the second.
    pub on_first: Vec3,
    /// The point of the second shape nearest the first (equal to `on_first`, or within
    /// rounding of it, when they meet).
    pub on_second: Vec3,
    /// `|on_first − on_second|²`: exactly 0 when the shapes meet.
    pub distance_squared: f32,
}
