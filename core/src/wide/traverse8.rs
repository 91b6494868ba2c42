//! Depth-first traversal of an eight-wide BVH, nearest child first.

use super::{WideBvh8, WideNode8};
use crate::bvh::MAX_DEPTH;
use crate::query::{LeafTriangleIds, Traverse, Visitor};

impl Traverse for WideBvh8<'_> {
    /// Depth first, each node's eight child boxes judged at once
    /// ([`Visitor::enter_lanes8`]) and visited in ascending key order (the lower lane first on
    /// equal keys), with a fixed stack and no allocation.
    #[inline(always)]
    fn traverse<V: Visitor + ?Sized>(&self, visitor: &mut V) {
        traverse_wide8(self.nodes, self.order, visitor);
    }

    /// Yes: boxes are judged eight at a time.
    #[inline(always)]
    fn traverse_packet<V: Visitor + ?Sized>(&self, visitor: &mut V) -> bool {
        self.traverse(visitor);
        true
    }
}

/// A child to visit: an inner node (`count == 0`, `child` its index) or a leaf.
#[derive(Clone, Copy)]
struct Child {
    child: u32,
    count: u32,
    key: f32,
    /// Where the child's box is: its parent node's index times eight plus its lane.
    parent_lane: u32,
}

/// Deferred children: each level defers at most seven, and the tree is no deeper than the
/// binary tree it came from ([`MAX_DEPTH`]), so the stack never fills.
const STACK: usize = 7 * MAX_DEPTH as usize;

/// The walk of [`Traverse`] over eight-lane nodes (root first) and their leaves' order:
/// depth first, nearest child first (lower lane on equal keys), a fixed stack.
#[inline(always)]
fn traverse_wide8<V: Visitor + ?Sized>(nodes: &[WideNode8], order: &[u32], visitor: &mut V) {
    // Uninitialised until pushed: zeroing kilobytes per query would cost more than a node.
    let mut stack = heapless::Vec::<Child, STACK>::new();
    let mut at = Child {
        child: 0,
        count: 0,
        key: 0.0,
        parent_lane: u32::MAX,
    };
    loop {
        if at.count > 0 {
            if let Some(tris) =
                LeafTriangleIds::in_order(order, at.child as usize, at.count as usize)
            {
                let boxed = visitor.wants_leaf_boxes();
                let (parent, lane) = (at.parent_lane >> 3, at.parent_lane & 7);
                let flow = match nodes.get(parent as usize) {
                    Some(parent) if boxed => {
                        visitor.leaf_in(&parent.bounds.lane(lane as usize), tris)
                    }
                    _ => visitor.leaf(tris),
                };
                if flow.is_break() {
                    return;
                }
            }
        } else if let Some(node) = nodes.get(at.child as usize) {
            let (mask, keys) = visitor.enter_lanes8(&node.bounds);
            let mask = mask & node.bounds.used_mask() & 0xFF;
            if mask != 0 {
                let parent = at.child.checked_mul(8).unwrap_or(u32::MAX - 7);
                let lane_of = |lane: u32| -> Child {
                    let at = lane as usize;
                    Child {
                        child: node.child.get(at).copied().unwrap_or(0),
                        count: node.count.get(at).copied().unwrap_or(0),
                        key: keys.get(at).copied().unwrap_or(f32::INFINITY),
                        parent_lane: parent | lane,
                    }
                };
                if mask & (mask - 1) == 0 {
                    at = lane_of(mask.trailing_zeros());
                    continue;
                }
                let (sorted, n) = by_key(mask, &keys);
                // Farthest deferred first, so the nearer ones come off the stack first.
                for &lane in sorted.iter().take(n).skip(1).rev() {
                    let _ = stack.push(lane_of(lane));
                }
                at = lane_of(sorted[0]);
                continue;
            }
        }
        loop {
            let Some(next) = stack.pop() else {
                return;
            };
            if visitor.revisit(next.key) {
                at = next;
                break;
            }
        }
    }
}

/// The lanes of `mask` sorted by key, ascending (the lower lane first on equal keys), and how
/// many there are.
///
/// Each key becomes an integer with the same order (the sign-flip of the float's bits) with
/// its lane below it, and an insertion sort places them: a ray enters one to three of a
/// node's lanes, so the few branches beat a branch-free network of 19 exchanges over all
/// eight.
#[inline(always)]
fn by_key(mut mask: u32, keys: &[f32; 8]) -> ([u32; 8], usize) {
    let mut sorted = [u64::MAX; 8];
    let mut n = 0usize;
    while mask != 0 {
        let lane = mask.trailing_zeros();
        mask &= mask - 1;
        // `+ 0.0` turns −0 into +0, which compare equal as floats and so must tie here too.
        let key = keys.get(lane as usize).copied().unwrap_or(f32::INFINITY) + 0.0;
        let bits = key.to_bits();
        let ordered = bits ^ ((((bits as i32) >> 31) as u32) | 0x8000_0000);
        let entry = (u64::from(ordered) << 3) | u64::from(lane);
        let mut at = n;
        while let Some(&before) = at.checked_sub(1).and_then(|i| sorted.get(i)) {
            if before <= entry {
                break;
            }
            if let Some(slot) = sorted.get_mut(at) {
                *slot = before;
            }
            at -= 1;
        }
        if let Some(slot) = sorted.get_mut(at) {
            *slot = entry;
        }
        n += 1;
    }
    (
        core::array::from_fn(|i| sorted.get(i).map_or(0, |&v| (v & 7) as u32)),
        n,
    )
}
