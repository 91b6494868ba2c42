//! Eight axis-aligned boxes side by side, each coordinate in eight lanes: the child boxes of an
//! eight-wide BVH node.

use wide::f32x8;

use super::{Aabb, Aabb4};

/// Eight boxes stored coordinate-major (all eight `min.x`, then all eight `min.y`, …), so
/// one eight-lane operation handles one coordinate of every box. An unused lane holds the
/// empty box (`min = +∞`, `max = −∞`). 192 bytes.
#[repr(C, align(32))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb8 {
    /// Smallest x of each box.
    pub min_x: [f32; 8],
    /// Smallest y of each box.
    pub min_y: [f32; 8],
    /// Smallest z of each box.
    pub min_z: [f32; 8],
    /// Largest x of each box.
    pub max_x: [f32; 8],
    /// Largest y of each box.
    pub max_y: [f32; 8],
    /// Largest z of each box.
    pub max_z: [f32; 8],
}

impl Aabb8 {
    /// Eight empty (unused) lanes.
    pub const EMPTY: Self = Self {
        min_x: [f32::INFINITY; 8],
        min_y: [f32::INFINITY; 8],
        min_z: [f32::INFINITY; 8],
        max_x: [f32::NEG_INFINITY; 8],
        max_y: [f32::NEG_INFINITY; 8],
        max_z: [f32::NEG_INFINITY; 8],
    };

    /// Lane `lane`'s box ([`Aabb::EMPTY`] for `lane ≥ 8`).
    #[must_use]
    pub fn lane(&self, lane: usize) -> Aabb {
        if lane >= 8 {
            return Aabb::EMPTY;
        }
        self.half(lane >> 2).lane(lane & 3)
    }

    /// Lanes `0..4` (`half == 0`) or `4..8` (any other `half`) as four boxes.
    #[must_use]
    #[inline(always)]
    pub fn half(&self, half: usize) -> Aabb4 {
        let start = if half == 0 { 0 } else { 4 };
        let four = |a: &[f32; 8]| -> [f32; 4] {
            core::array::from_fn(|i| a.get(start + i).copied().unwrap_or(f32::NAN))
        };
        Aabb4 {
            min_x: four(&self.min_x),
            min_y: four(&self.min_y),
            min_z: four(&self.min_z),
            max_x: four(&self.max_x),
            max_y: four(&self.max_y),
            max_z: four(&self.max_z),
        }
    }

    /// Writes `aabb` into lane `lane` (ignored for `lane ≥ 8`).
    pub fn set_lane(&mut self, lane: usize, aabb: &Aabb) {
        let fields = [
            (&mut self.min_x, aabb.min.x),
            (&mut self.min_y, aabb.min.y),
            (&mut self.min_z, aabb.min.z),
            (&mut self.max_x, aabb.max.x),
            (&mut self.max_y, aabb.max.y),
            (&mut self.max_z, aabb.max.z),
        ];
        for (coords, value) in fields {
            if let Some(c) = coords.get_mut(lane) {
                *c = value;
            }
        }
    }

    /// Plane `index` of the eight boxes: 0, 1, 2 their smallest x, y, z; 3, 4, 5 their largest
    /// x, y, z (a larger index: the largest z). With `index` the same for many calls, as a
    /// ray's near planes are over a walk, the pick compiles to a fixed offset from the boxes.
    #[must_use]
    #[inline(always)]
    pub fn plane(&self, index: usize) -> &[f32; 8] {
        match index {
            0 => &self.min_x,
            1 => &self.min_y,
            2 => &self.min_z,
            3 => &self.max_x,
            4 => &self.max_y,
            _ => &self.max_z,
        }
    }

    /// Bit `i` set for each used lane (`min.x ≤ max.x`; the empty box fails it).
    #[must_use]
    #[inline(always)]
    pub fn used_mask(&self) -> u32 {
        f32x8::new(self.min_x)
            .simd_le(f32x8::new(self.max_x))
            .to_bitmask()
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

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::math::Aabb4;

    /// Each plane index names the coordinate its documentation says, for four lanes and for
    /// eight: plane `i` holds lane `k`'s `min[i]` for `i < 3`, its `max[i − 3]` above, and every
    /// index past 5 the largest z.
    #[test]
    fn plane_indices_name_their_coordinates() {
        let mut four = Aabb4::EMPTY;
        let mut eight = Aabb8::EMPTY;
        let boxes: [Aabb; 8] = core::array::from_fn(|k| {
            let k = k as f32;
            Aabb::new(
                Vec3::new(k, 10.0 + k, 20.0 + k),
                Vec3::new(30.0 + k, 40.0 + k, 50.0 + k),
            )
        });
        for (lane, b) in boxes.iter().enumerate() {
            four.set_lane(lane, b);
            eight.set_lane(lane, b);
        }
        for index in 0..8 {
            let coordinate = |b: &Aabb| match index {
                0..3 => b.min[index],
                _ => b.max[index.min(5) - 3],
            };
            for (lane, b) in boxes.iter().enumerate() {
                assert_eq!(eight.plane(index)[lane], coordinate(b), "plane {index}");
                if lane < 4 {
                    assert_eq!(four.plane(index)[lane], coordinate(b), "plane {index}");
                }
            }
        }
    }
}
