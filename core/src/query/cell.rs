//! The region of space a leaf of a spatial structure owns, for queries that must report each
//! triangle once although several cells hold it.

use glam::Vec3;

use crate::math::Aabb;

/// A leaf's cell in a structure that cuts space into cells (k-d tree, octree, grid), where a
/// triangle is referenced from every cell it touches.
///
/// The cells of one structure *tile* its bounds: each point of the bounds is
/// owned by exactly one leaf cell. A cell owns the points of its box that lie on
/// its `min` faces and inside it, but not those on its `max` faces, except the faces that lie on
/// the structure's own `max` faces (where no neighbour could own them). A query that must not
/// report a triangle twice picks one point of the triangle (the same in every cell, computed
/// from the triangle and the query alone) and reports the triangle only from the cell that owns
/// that point: the built-in overlap queries do so.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cell {
    aabb: Aabb,
    /// Bit `axis` set when the `max` face on that axis is closed (owned by this cell).
    closed_max: u8,
}

impl Cell {
    /// A cell with box `aabb`, whose `max` face on axis `a` is owned by it when
    /// `closed_max[a]` (the face lies on the structure's bounds).
    #[inline(always)]
    #[must_use]
    pub const fn new(aabb: Aabb, closed_max: [bool; 3]) -> Self {
        let [x, y, z] = closed_max;
        Self {
            aabb,
            closed_max: (x as u8) | ((y as u8) << 1) | ((z as u8) << 2),
        }
    }

    /// The whole box of a structure, which owns all of its faces.
    #[inline(always)]
    #[must_use]
    pub const fn root(aabb: Aabb) -> Self {
        Self::new(aabb, [true; 3])
    }

    /// The cell's box (closed: it includes every face, owned or not).
    #[inline(always)]
    #[must_use]
    pub const fn aabb(&self) -> &Aabb {
        &self.aabb
    }

    /// Whether the `max` face on `axis` (0, 1 or 2) is owned by this cell.
    #[inline(always)]
    #[must_use]
    pub(crate) const fn closed_max(&self, axis: usize) -> bool {
        axis < 3 && self.closed_max & (1 << axis) != 0
    }

    /// The two halves of this cell cut by the plane `axis = split` (`axis` 0, 1 or 2, `split`
    /// inside the box): the lower half `[min, split)` and the upper half `[split, max]`, which
    /// owns the plane.
    #[inline(always)]
    #[must_use]
    pub fn split(&self, axis: usize, split: f32) -> (Self, Self) {
        let (mut lo, mut hi) = (*self, *self);
        match axis {
            0 => (lo.aabb.max.x, hi.aabb.min.x) = (split, split),
            1 => (lo.aabb.max.y, hi.aabb.min.y) = (split, split),
            _ => (lo.aabb.max.z, hi.aabb.min.z) = (split, split),
        }
        lo.closed_max &= !(1 << axis.min(2));
        (lo, hi)
    }

    /// Whether this cell owns point `p` (see the type's docs). NaN coordinates are owned by no
    /// cell.
    #[inline]
    #[must_use]
    pub(crate) fn owns(&self, p: Vec3) -> bool {
        let (lo, hi) = (self.aabb.min.to_array(), self.aabb.max.to_array());
        let p = p.to_array();
        (0..3).all(|a| {
            let (Some(&x), Some(&l), Some(&h)) = (p.get(a), lo.get(a), hi.get(a)) else {
                return false;
            };
            x >= l && (x < h || (self.closed_max(a) && x <= h))
        })
    }
}
