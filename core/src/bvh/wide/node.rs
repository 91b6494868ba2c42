use crate::math::Aabb;

/// One node of a [`WideBvh`](super::WideBvh): the boxes of up to four children side by side
/// (one array per coordinate, so a single SIMD operation tests all four), and what each
/// child is. 128 bytes, two cache lines.
///
/// A child *lane* is one of:
/// - an inner node: `count == 0`, `child` is its index in the node array (never 0, the root);
/// - a leaf: `count > 0` triangles in order slots `child..child + count`;
/// - unused: an empty box (`min = +∞`, `max = −∞`), `child == 0`, `count == 0`. Used lanes
///   come first.
///
/// Boxes are the padded boxes of the binary tree the node was collapsed from.
#[repr(C, align(64))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WideNode {
    /// Smallest x of each child's box.
    pub min_x: [f32; 4],
    /// Smallest y of each child's box.
    pub min_y: [f32; 4],
    /// Smallest z of each child's box.
    pub min_z: [f32; 4],
    /// Largest x of each child's box.
    pub max_x: [f32; 4],
    /// Largest y of each child's box.
    pub max_y: [f32; 4],
    /// Largest z of each child's box.
    pub max_z: [f32; 4],
    /// Inner child: node index; leaf child: first order slot; unused: 0.
    pub child: [u32; 4],
    /// Leaf child: triangle count (≥ 1); inner child or unused: 0.
    pub count: [u32; 4],
}

impl WideNode {
    /// A node with four unused lanes, for initializing buffers.
    pub const EMPTY: Self = Self {
        min_x: [f32::INFINITY; 4],
        min_y: [f32::INFINITY; 4],
        min_z: [f32::INFINITY; 4],
        max_x: [f32::NEG_INFINITY; 4],
        max_y: [f32::NEG_INFINITY; 4],
        max_z: [f32::NEG_INFINITY; 4],
        child: [0; 4],
        count: [0; 4],
    };

    /// Lane `lane`'s box ([`Aabb::EMPTY`]-like for an unused lane or `lane ≥ 4`).
    #[must_use]
    pub fn lane_box(&self, lane: usize) -> Aabb {
        let get = |a: &[f32; 4], fallback: f32| a.get(lane).copied().unwrap_or(fallback);
        Aabb::new(
            glam::Vec3::new(
                get(&self.min_x, f32::INFINITY),
                get(&self.min_y, f32::INFINITY),
                get(&self.min_z, f32::INFINITY),
            ),
            glam::Vec3::new(
                get(&self.max_x, f32::NEG_INFINITY),
                get(&self.max_y, f32::NEG_INFINITY),
                get(&self.max_z, f32::NEG_INFINITY),
            ),
        )
    }

    /// Number of used lanes (1 to 4 in a built node).
    #[must_use]
    pub fn lanes(&self) -> usize {
        self.min_x
            .iter()
            .zip(&self.max_x)
            .take_while(|(lo, hi)| lo <= hi)
            .count()
    }

    /// True when every field of both nodes has the same bits (so `0.0` and `-0.0` differ).
    #[must_use]
    pub fn same_bits(&self, other: &Self) -> bool {
        let boxes = |n: &Self| [n.min_x, n.min_y, n.min_z, n.max_x, n.max_y, n.max_z];
        boxes(self)
            .iter()
            .flatten()
            .zip(boxes(other).iter().flatten())
            .all(|(a, b)| a.to_bits() == b.to_bits())
            && self.child == other.child
            && self.count == other.count
    }

    /// Writes `aabb`, `child` and `count` into lane `lane` (ignored for `lane ≥ 4`).
    pub(super) fn set_lane(&mut self, lane: usize, aabb: &Aabb, child: u32, count: u32) {
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
        if let (Some(c), Some(n)) = (self.child.get_mut(lane), self.count.get_mut(lane)) {
            *c = child;
            *n = count;
        }
    }
}

const _: () = assert!(core::mem::size_of::<WideNode>() == 128);
