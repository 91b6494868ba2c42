//! The builder's box: corners in 16-byte SIMD vectors, so a union is two vector operations.

use glam::{Vec3A, Vec3Swizzles};

use super::lanes::{max_lanes, min_lanes};
use crate::math::Aabb;

/// A box with inclusive corners; `min > max` on some axis means empty, as for [`Aabb`].
#[derive(Clone, Copy, Debug)]
pub(super) struct BuildBox {
    pub min: Vec3A,
    pub max: Vec3A,
}

impl BuildBox {
    /// The identity of [`BuildBox::union`].
    pub const EMPTY: Self = Self {
        min: Vec3A::INFINITY,
        max: Vec3A::NEG_INFINITY,
    };

    #[inline(always)]
    pub fn union(self, o: Self) -> Self {
        Self {
            min: min_lanes(o.min, self.min),
            max: max_lanes(o.max, self.max),
        }
    }

    #[inline(always)]
    pub fn grown(self, p: Vec3A) -> Self {
        Self {
            min: min_lanes(p, self.min),
            max: max_lanes(p, self.max),
        }
    }

    /// Half the surface area (`xy + yz + zx` of the extent, in that order); 0 when empty.
    #[inline(always)]
    pub fn half_area(&self) -> f32 {
        if !self.min.cmple(self.max).all() {
            return 0.0;
        }
        self.half_area_nonempty()
    }

    /// [`BuildBox::half_area`] without the emptiness test, for boxes known to hold something
    /// (an empty one gives a meaningless value).
    #[inline(always)]
    pub fn half_area_nonempty(&self) -> f32 {
        let e = self.max - self.min;
        let p = e * e.yzx();
        p.x + p.y + p.z
    }

    #[inline(always)]
    pub fn extent(&self) -> Vec3A {
        self.max - self.min
    }

    pub fn to_aabb(self) -> Aabb {
        Aabb::new(self.min.into(), self.max.into())
    }
}
