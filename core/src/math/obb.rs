//! Oriented boxes.

use glam::Vec3;

use super::{Aabb, dot};

/// An oriented box: the points `center + s₀·axes[0] + s₁·axes[1] + s₂·axes[2]` with each
/// `|sᵢ| ≤ half_extents[i]`.
///
/// The axes must be orthonormal (the columns of a rotation matrix): the tests project onto
/// them. A box with a negative or non-finite half extent, or non-finite centre or axes, is
/// empty: it overlaps nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Obb {
    /// The centre.
    pub center: Vec3,
    /// Three orthonormal directions.
    pub axes: [Vec3; 3],
    /// Half the box's size along each axis, in world units, each `≥ 0`.
    pub half_extents: Vec3,
}

impl Obb {
    /// The box with centre `center`, orthonormal `axes` and half extents `half_extents`.
    #[must_use]
    pub const fn new(center: Vec3, axes: [Vec3; 3], half_extents: Vec3) -> Self {
        Self {
            center,
            axes,
            half_extents,
        }
    }

    /// Whether the box holds any point: every field finite, every half extent `≥ 0`.
    #[must_use]
    pub fn is_valid(&self) -> bool {
        self.center.is_finite()
            && self.axes.iter().all(|a| a.is_finite())
            && self.half_extents.is_finite()
            && self.half_extents.min_element() >= 0.0
    }

    /// `p` in the box's frame: its coordinates along the three axes, from the centre.
    #[inline]
    #[must_use]
    pub(crate) fn to_local(self, p: Vec3) -> Vec3 {
        let d = p - self.center;
        let [a, b, c] = self.axes;
        Vec3::new(dot(d, a), dot(d, b), dot(d, c))
    }

    /// The axis-aligned box around it ([`Aabb::EMPTY`] for a box that is not
    /// [valid](Self::is_valid)), padded (see [`Aabb::padded`]) so that rounding cannot leave
    /// out a point of the box.
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        if !self.is_valid() {
            return Aabb::EMPTY;
        }
        let [a, b, c] = self.axes;
        let h = self.half_extents;
        let reach = a.abs() * h.x + b.abs() * h.y + c.abs() * h.z;
        Aabb::new(self.center - reach, self.center + reach).padded()
    }
}
