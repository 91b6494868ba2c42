//! Working out every node's expansion bottom up, streamed to a sink: written into a buffer by
//! [`WindingTree::build`](super::WindingTree::build), compared with stored ones by a blob's
//! check.

use glam::Vec3;

use super::expansion::{Moments, WindingNode, leaf_moments, leaf_triangles, merged_moments};
use crate::bvh::{MAX_DEPTH, TreeArrays};
use crate::math::dot;
use crate::query::LeafTriangles;

/// Works out the expansion of every node of `tree` over `triangles` (corners times `scale`),
/// children before parents, and hands each to `sink` with its node index, on a few KiB of
/// stack: `O(triangles × depth)`. Stops early, returning `false`, when `sink` returns `false`;
/// `true` once every node was handed over.
pub(super) fn for_each_expansion<T, S>(
    tree: &T,
    triangles: &S,
    scale: f32,
    mut sink: impl FnMut(usize, WindingNode) -> bool,
) -> bool
where
    T: TreeArrays + ?Sized,
    S: LeafTriangles + ?Sized,
{
    // Post order on fixed stacks: a node's full moments exist only until its parent merges
    // them, so at most one per level waits (the tree is at most MAX_DEPTH deep).
    let mut work = [(0u32, false); 2 * MAX_DEPTH as usize + 2];
    let mut done = [Moments::default(); MAX_DEPTH as usize + 2];
    let (mut wp, mut dp) = (usize::from(tree.node_count() > 0), 0usize);
    while wp > 0 {
        wp -= 1;
        let (index, merge) = work.get(wp).copied().unwrap_or_default();
        let Some(node) = tree.node(index as usize) else {
            continue;
        };
        let moments = if node.is_leaf() {
            leaf_moments(leaf_triangles(tree, triangles, &node, scale))
        } else if !merge {
            // Again after both children, which run left first.
            for next in [
                (index, true),
                (node.first.wrapping_add(1), false),
                (node.first, false),
            ] {
                if let Some(slot) = work.get_mut(wp) {
                    *slot = next;
                    wp += 1;
                }
            }
            continue;
        } else {
            dp = dp.saturating_sub(2);
            let child = |k: usize| done.get(k).copied().unwrap_or_default();
            let mut merged = merged_moments(&child(dp), &child(dp + 1));
            // The children's balls bound the node loosely, more so each level up; the corners
            // themselves give the radius the far test wants small.
            merged.radius = merged.radius.min(subtree_radius(
                tree,
                triangles,
                index as usize,
                scale,
                merged.centre,
            ));
            merged
        };
        if !sink(index as usize, WindingNode::of(&moments, moments.radius)) {
            return false;
        }
        if let Some(slot) = done.get_mut(dp) {
            *slot = moments;
            dp += 1;
        }
    }
    true
}

/// The largest distance from `centre` to a corner of a triangle node `index` counts (scaled by
/// `scale`): the triangles of a subtree fill the order slots from its leftmost leaf's first to
/// its rightmost leaf's last.
fn subtree_radius<T, S>(tree: &T, triangles: &S, index: usize, scale: f32, centre: Vec3) -> f32
where
    T: TreeArrays + ?Sized,
    S: LeafTriangles + ?Sized,
{
    let leaf_at = |mut i: usize, right: bool| {
        for _ in 0..=MAX_DEPTH {
            match tree.node(i) {
                Some(n) if n.is_leaf() => return Some(n),
                Some(n) => i = n.first as usize + usize::from(right),
                None => return None,
            }
        }
        None
    };
    let (Some(low), Some(high)) = (leaf_at(index, false), leaf_at(index, true)) else {
        return f32::INFINITY;
    };
    let (first, count) = (
        low.first as usize,
        high.first
            .saturating_add(high.count)
            .saturating_sub(low.first) as usize,
    );
    // The largest square, then one root: the root is monotonic and correctly rounded, so this
    // is the largest root, bit for bit. Every reference counts (a triangle held twice has the
    // same corners twice, which leaves the largest alone), so no split references are looked up.
    let Some(ids) = tree.leaf_triangles(first, count) else {
        return f32::INFINITY;
    };
    let mut farthest = 0.0f32;
    for (slot, tri) in ids {
        if let Some(t) = triangles.corners(slot, tri) {
            for corner in [t.a, t.b, t.c] {
                let d = corner * scale - centre;
                farthest = farthest.max(dot(d, d));
            }
        }
    }
    libm::sqrtf(farthest)
}
