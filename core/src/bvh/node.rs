use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::math::Aabb;

/// One BVH node: 32 bytes, a plain `#[repr(C)]` record with a fixed serialized layout.
///
/// | bytes | field   | inner node (`count == 0`)        | leaf (`count > 0`)                  |
/// |-------|---------|----------------------------------|-------------------------------------|
/// | 0–11  | `min`   | box corner                       | box corner                          |
/// | 12–15 | `first` | index of the left child; the right child is `first + 1` | first slot in the triangle order array |
/// | 16–27 | `max`   | box corner                       | box corner                          |
/// | 28–31 | `count` | 0                                | number of triangles, ≥ 1            |
///
/// Boxes are *padded*: slightly larger than the exact bounds (see [`Aabb::padded`]) so that
/// rounding in a query can never cull a triangle inside.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct BvhNode {
    /// Smallest box corner.
    pub min: [f32; 3],
    /// Left child (inner node) or first order slot (leaf).
    pub first: u32,
    /// Largest box corner.
    pub max: [f32; 3],
    /// Triangle count of a leaf; 0 marks an inner node.
    pub count: u32,
}

impl BvhNode {
    /// A placeholder for initializing node buffers (an empty box, no children).
    pub const EMPTY: Self = Self {
        min: [f32::INFINITY; 3],
        first: 0,
        max: [f32::NEG_INFINITY; 3],
        count: 0,
    };

    /// True for a leaf (`count > 0`).
    #[inline(always)]
    #[must_use]
    pub const fn is_leaf(&self) -> bool {
        self.count > 0
    }

    /// The node's box.
    #[inline]
    #[must_use]
    pub fn aabb(&self) -> Aabb {
        Aabb::new(Vec3::from_array(self.min), Vec3::from_array(self.max))
    }

    pub(crate) fn new(aabb: Aabb, first: u32, count: u32) -> Self {
        Self {
            min: aabb.min.to_array(),
            first,
            max: aabb.max.to_array(),
            count,
        }
    }
}

const _: () = assert!(core::mem::size_of::<BvhNode>() == 32);
