//! Axis-aligned bounding boxes.

use super::scalar::{max_f32, min_f32};
use glam::Vec3;

/// An axis-aligned box given by its inclusive corners `min` and `max`.
///
/// A box with `min > max` on any axis is *empty* ([`Aabb::EMPTY`] is the identity of
/// [`Aabb::union`]). Points on the boundary are inside.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Smallest corner (inclusive).
    pub min: Vec3,
    /// Largest corner (inclusive).
    pub max: Vec3,
}

impl Default for Aabb {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl Aabb {
    /// The empty box: `min = +∞`, `max = −∞`. Growing it by a point gives that point's box.
    pub const EMPTY: Self = Self {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    /// A box from its corners, taken as given (no reordering).
    #[inline]
    #[must_use]
    pub const fn new(min: Vec3, max: Vec3) -> Self {
        Self { min, max }
    }

    /// The smallest box holding all `points` ([`Aabb::EMPTY`] for none).
    #[must_use]
    pub fn from_points(points: &[Vec3]) -> Self {
        points.iter().fold(Self::EMPTY, |b, &p| b.grown(p))
    }

    /// This box grown to hold `p`.
    #[inline]
    #[must_use]
    pub fn grown(self, p: Vec3) -> Self {
        Self {
            min: Vec3::new(
                min_f32(p.x, self.min.x),
                min_f32(p.y, self.min.y),
                min_f32(p.z, self.min.z),
            ),
            max: Vec3::new(
                max_f32(p.x, self.max.x),
                max_f32(p.y, self.max.y),
                max_f32(p.z, self.max.z),
            ),
        }
    }

    /// The smallest box holding both boxes.
    #[inline]
    #[must_use]
    pub fn union(self, o: Self) -> Self {
        Self {
            min: Vec3::new(
                min_f32(o.min.x, self.min.x),
                min_f32(o.min.y, self.min.y),
                min_f32(o.min.z, self.min.z),
            ),
            max: Vec3::new(
                max_f32(o.max.x, self.max.x),
                max_f32(o.max.y, self.max.y),
                max_f32(o.max.z, self.max.z),
            ),
        }
    }

    /// True when `min > max` on some axis (or a corner is NaN).
    #[inline]
    #[must_use]
    pub fn is_empty(&self) -> bool {
        !(self.min.x <= self.max.x && self.min.y <= self.max.y && self.min.z <= self.max.z)
    }

    /// `max − min` (negative components for an empty box).
    #[inline]
    #[must_use]
    pub fn extent(&self) -> Vec3 {
        self.max - self.min
    }

    /// The centre `(min + max) / 2`.
    #[inline]
    #[must_use]
    pub fn center(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }

    /// Half the surface area, `xy + yz + zx` of the extent; 0 for an empty box.
    ///
    /// The surface area heuristic only compares ratios, so the factor 2 is left out.
    #[inline]
    #[must_use]
    pub fn half_area(&self) -> f32 {
        if self.is_empty() {
            return 0.0;
        }
        let e = self.extent();
        e.x * e.y + e.y * e.z + e.z * e.x
    }

    /// True when `p` is inside or on the boundary.
    #[inline]
    #[must_use]
    pub fn contains_point(&self, p: Vec3) -> bool {
        p.x >= self.min.x
            && p.y >= self.min.y
            && p.z >= self.min.z
            && p.x <= self.max.x
            && p.y <= self.max.y
            && p.z <= self.max.z
    }

    /// True when `o` lies inside this box (boundaries may touch). An empty `o` is contained.
    #[inline]
    #[must_use]
    pub fn contains_aabb(&self, o: &Self) -> bool {
        o.is_empty()
            || (o.min.x >= self.min.x
                && o.min.y >= self.min.y
                && o.min.z >= self.min.z
                && o.max.x <= self.max.x
                && o.max.y <= self.max.y
                && o.max.z <= self.max.z)
    }

    /// True when the boxes share at least one point (touching counts).
    #[inline]
    #[must_use]
    pub fn overlaps(&self, o: &Self) -> bool {
        self.min.x <= o.max.x
            && self.min.y <= o.max.y
            && self.min.z <= o.max.z
            && o.min.x <= self.max.x
            && o.min.y <= self.max.y
            && o.min.z <= self.max.z
    }

    /// Squared distance from `p` to the nearest point of the box (0 inside).
    #[inline]
    #[must_use]
    pub fn distance_squared_to_point(&self, p: Vec3) -> f32 {
        let dx = max_f32(max_f32(self.min.x - p.x, p.x - self.max.x), 0.0);
        let dy = max_f32(max_f32(self.min.y - p.y, p.y - self.max.y), 0.0);
        let dz = max_f32(max_f32(self.min.z - p.z, p.z - self.max.z), 0.0);
        dx * dx + dy * dy + dz * dz
    }

    /// Squared distance between the nearest points of this box and `o` (0 when they
    /// overlap or touch; +∞ when either is empty). A lower bound of the squared distance
    /// between anything the two boxes hold.
    #[inline]
    #[must_use]
    pub fn distance_squared_to_aabb(&self, o: &Self) -> f32 {
        let dx = max_f32(max_f32(o.min.x - self.max.x, self.min.x - o.max.x), 0.0);
        let dy = max_f32(max_f32(o.min.y - self.max.y, self.min.y - o.max.y), 0.0);
        let dz = max_f32(max_f32(o.min.z - self.max.z, self.min.z - o.max.z), 0.0);
        dx * dx + dy * dy + dz * dz
    }

    /// True when every corner coordinate is finite.
    #[inline]
    #[must_use]
    pub fn is_finite(&self) -> bool {
        self.min.is_finite() && self.max.is_finite()
    }

    /// This box grown outward on every side by `RELATIVE_PAD` times its largest absolute
    /// coordinate.
    ///
    /// Acceleration structures store padded boxes so that rounding in a slab test or a box
    /// distance can never cull a triangle whose own (independently rounded) hit distance would
    /// have won: the pad is far larger than the few ulps of error either computation makes, and
    /// far smaller than any geometric feature that matters.
    #[inline]
    #[must_use]
    pub fn padded(self) -> Self {
        if self.is_empty() {
            return self;
        }
        let m = self.min.abs().max(self.max.abs());
        let pad = max_f32(max_f32(m.x, m.y), m.z) * Self::RELATIVE_PAD;
        Self {
            min: self.min - Vec3::splat(pad),
            max: self.max + Vec3::splat(pad),
        }
    }

    /// Relative size of the pad added by [`Aabb::padded`]: 2⁻²⁰ ≈ 9.5·10⁻⁷.
    pub const RELATIVE_PAD: f32 = 1.0 / 1_048_576.0;
}
