//! Four boxes side by side, one per SIMD lane.

use glam::{Vec3, Vec4};

use super::Aabb;

/// Four axis-aligned boxes stored coordinate by coordinate (one `[f32; 4]` per corner
/// coordinate), so one SIMD operation tests a coordinate of all four. 96 bytes.
///
/// *Lane* `i` is box `i`: `(min_x[i], min_y[i], min_z[i])` to `(max_x[i], max_y[i],
/// max_z[i])`. A lane whose box is empty (`min > max`, as [`Aabb4::EMPTY`] has in every lane)
/// is unused; structures put used lanes first.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb4 {
    /// Smallest x of each box.
    pub min_x: [f32; 4],
    /// Smallest y of each box.
    pub min_y: [f32; 4],
    /// Smallest z of each box.
    pub min_z: [f32; 4],
    /// Largest x of each box.
    pub max_x: [f32; 4],
    /// Largest y of each box.
    pub max_y: [f32; 4],
    /// Largest z of each box.
    pub max_z: [f32; 4],
}

impl Default for Aabb4 {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl Aabb4 {
    /// Four empty lanes (`min = +∞`, `max = −∞`).
    pub const EMPTY: Self = Self {
        min_x: [f32::INFINITY; 4],
        min_y: [f32::INFINITY; 4],
        min_z: [f32::INFINITY; 4],
        max_x: [f32::NEG_INFINITY; 4],
        max_y: [f32::NEG_INFINITY; 4],
        max_z: [f32::NEG_INFINITY; 4],
    };

    /// Lane `lane`'s box ([`Aabb::EMPTY`]'s corners for `lane ≥ 4`).
    #[must_use]
    pub fn lane(&self, lane: usize) -> Aabb {
        let get = |a: &[f32; 4], fallback: f32| a.get(lane).copied().unwrap_or(fallback);
        Aabb::new(
            Vec3::new(
                get(&self.min_x, f32::INFINITY),
                get(&self.min_y, f32::INFINITY),
                get(&self.min_z, f32::INFINITY),
            ),
            Vec3::new(
                get(&self.max_x, f32::NEG_INFINITY),
                get(&self.max_y, f32::NEG_INFINITY),
                get(&self.max_z, f32::NEG_INFINITY),
            ),
        )
    }

    /// Writes `aabb` into lane `lane` (ignored for `lane ≥ 4`).
    pub fn set_lane(&mut self, lane: usize, aabb: &Aabb) {
        let fields = [
            (&mut self.min_x, aabb.min.x),
            (&mut self.min_y, aabb.min.y),
            (&mut self.min_z, aabb.min.z),
            (&mut self.max_x, aabb.max.x),
            (&mut self.max_y, aabb.max.y),
            (&mut self.max_z, aabb.max.z),
        ];
        for (array, value) in fields {
            if let Some(slot) = array.get_mut(lane) {
                *slot = value;
            }
        }
    }

    /// Plane `index` of the four boxes: 0, 1, 2 their smallest x, y, z; 3, 4, 5 their largest
    /// x, y, z (a larger index: the largest z). With `index` the same for many calls, as a
    /// ray's near planes are over a walk, the pick compiles to a fixed offset from the boxes.
    #[must_use]
    #[inline(always)]
    pub fn plane(&self, index: usize) -> &[f32; 4] {
        match index {
            0 => &self.min_x,
            1 => &self.min_y,
            2 => &self.min_z,
            3 => &self.max_x,
            4 => &self.max_y,
            _ => &self.max_z,
        }
    }

    /// Bit `i` set for each lane whose box is not empty on x (`min_x ≤ max_x`; a NaN
    /// coordinate counts as empty). Built boxes are empty on every axis or on none.
    #[inline(always)]
    #[must_use]
    pub fn used_mask(&self) -> u32 {
        Vec4::from_array(self.min_x)
            .cmple(Vec4::from_array(self.max_x))
            .bitmask()
    }

    /// Number of used lanes, counted from lane 0 up to the first unused one.
    #[must_use]
    pub fn used_lanes(&self) -> usize {
        self.min_x
            .iter()
            .zip(&self.max_x)
            .take_while(|(lo, hi)| lo <= hi)
            .count()
    }

    /// The union of the used lanes' boxes ([`Aabb::EMPTY`] when none is used).
    #[must_use]
    pub fn union(&self) -> Aabb {
        (0..self.used_lanes()).fold(Aabb::EMPTY, |b, lane| b.union(self.lane(lane)))
    }

    /// True when every coordinate of both has the same bits (so `0.0` and `-0.0` differ).
    #[must_use]
    pub fn same_bits(&self, other: &Self) -> bool {
        let all = |b: &Self| [b.min_x, b.min_y, b.min_z, b.max_x, b.max_y, b.max_z];
        all(self)
            .iter()
            .flatten()
            .zip(all(other).iter().flatten())
            .all(|(a, b)| a.to_bits() == b.to_bits())
    }
}

const _: () = assert!(core::mem::size_of::<Aabb4>() == 96);
