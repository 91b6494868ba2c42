//! The walk over a collapse's wide nodes, in its numbering, shared by a solved plan and by
//! stored roles.

use crate::bvh::{BvhNode, MAX_DEPTH};

/// Inner binary nodes waiting to become wide nodes. A wide node is no deeper than the binary
/// node it starts from, and each one leaves at most seven siblings pending per level (eight
/// lanes at most), so a valid tree never fills this.
const PENDING: usize = 7 * MAX_DEPTH as usize + 1;

/// A wide node's lanes as `(binary index, node)` (a merged leaf as a leaf node over its
/// subtree's box and slots), left to right, and how many of the `W` places are used.
#[cfg(feature = "parallel")]
pub(super) type Lanes<const W: usize> = ([(u32, BvhNode); W], usize);

/// The places a wide node's lanes are written into, left to right (see [`Lanes`]).
pub(super) type LaneSlots<const W: usize> = [(u32, BvhNode); W];

/// Walks the wide nodes of the subtree under the inner binary node `root` in a collapse's
/// numbering, with each node's lanes written by `lanes_of` (which returns how many), handing `each`
/// every node's index, its lanes and the index its first inner lane gets; returns how many nodes
/// there are, or `None` when `lanes_of` fails or the walk grows deeper than a valid tree can.
/// `root`'s node is 0 and the others are numbered from 1, depth first: a node's inner lanes take
/// the next free indices in lane order, then the last one's subtree comes first.
pub(super) fn walk_wide_nodes<const W: usize>(
    root: u32,
    mut lanes_of: impl FnMut(u32, &mut LaneSlots<W>) -> Option<usize>,
    mut each: impl FnMut(u32, &[(u32, BvhNode)], u32),
) -> Option<usize> {
    let mut pending = [(root, 0u32); PENDING];
    let mut len = 1usize;
    let mut next = 1u32;
    // One buffer for every node's lanes: large values are not returned and copied per node.
    let mut slots = [(0u32, BvhNode::EMPTY); W];
    while let Some(at) = len.checked_sub(1) {
        len = at;
        let &(binary, wide) = pending.get(at)?;
        let count = lanes_of(binary, &mut slots)?;
        let lanes = slots.get(..count)?;
        each(wide, lanes, next);
        for &(index, lane) in lanes {
            if !lane.is_leaf() {
                *pending.get_mut(len)? = (index, next);
                len += 1;
                next = next.checked_add(1)?;
            }
        }
    }
    Some(next as usize)
}
