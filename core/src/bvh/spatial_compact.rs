//! The last step of a build with spatial splits: leaves moved down to dense slots, and the
//! table of split references written.

use super::spatial_bins::SPLIT_FLAG;
use super::{BvhNode, MAX_DEPTH};
use crate::query::SplitRef;

/// Walks `nodes` (a built tree whose leaves name their references where they lie in the
/// build's roomy layout of `order`) depth first, left child first, which visits leaves in
/// ascending position; moves each leaf's entries down to the next free slot and renames the
/// leaf's range; clears the split flag of each entry and writes a [`SplitRef`] for it to
/// `splits` (in slot order). Returns the slots used and the entries written.
pub(super) fn compact(
    nodes: &mut [BvhNode],
    order: &mut [u32],
    splits: &mut [SplitRef],
) -> (usize, usize) {
    let (mut written, mut split_count) = (0usize, 0usize);
    let mut stack = [0u32; MAX_DEPTH as usize];
    let mut sp = 0usize;
    let mut current = (!nodes.is_empty()).then_some(0u32);
    while let Some(index) = current.take() {
        let Some(node) = nodes.get_mut(index as usize) else {
            break;
        };
        if node.is_leaf() {
            let (first, count) = (node.first as usize, node.count as usize);
            // Leaves lie in ascending order, each at or after the slots written so far.
            if first + count <= order.len() && written <= first {
                order.copy_within(first..first + count, written);
            }
            // The reference room fits in u32 (checked before the build).
            node.first = written as u32;
            let leaf_box = node.aabb();
            for slot in written..written + count {
                let Some(entry) = order.get_mut(slot) else {
                    break;
                };
                if *entry & SPLIT_FLAG != 0 {
                    *entry &= !SPLIT_FLAG;
                    if let Some(r) = splits.get_mut(split_count) {
                        *r = SplitRef {
                            tri: *entry,
                            slot: slot as u32,
                            leaf_box,
                        };
                        split_count += 1;
                    }
                }
            }
            written += count;
            if sp > 0 {
                sp -= 1;
                current = stack.get(sp).copied();
            }
        } else {
            // A built tree is at most MAX_DEPTH deep: one pending right child per level.
            if let Some(slot) = stack.get_mut(sp) {
                *slot = node.first + 1;
                sp += 1;
            }
            current = Some(node.first);
        }
    }
    (written, split_count)
}
